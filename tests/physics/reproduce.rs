//! `jkrbem reproduce --quick`: the whole study on coarse grids writes every chart of physics §8
//! (with data in each; as SVG and the PNG asked for, each with its `.plot.csv`) and an
//! index.html that shows them with captions, and the adhesive
//! force falls with R1/R2 less steeply than Johnson–Greenwood's.

use crate::common;

use common::{jkrbem, stderr};

#[test]
fn quick_reproduction_writes_every_chart_with_data_and_an_index() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "reproduce",
            "--quick",
            "--backend",
            "cpu",
            "--jobs",
            "2",
            "--figure-format",
            "png",
            "--out",
            "rep",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let rep = dir.path().join("rep");
    let index = std::fs::read_to_string(rep.join("index.html")).unwrap();
    let charts = [
        "pulloff_curves.svg",
        "axis_ratio.svg",
        "d_of_c.svg",
        "f_of_c.svg",
        "f_of_d.svg",
        "coefficients.svg",
        "force_vs_ratio.svg",
        "crossed.svg",
        "contours_r1.svg",
        "contours_r5.svg",
        "contours_r25.svg",
    ];
    for c in charts {
        assert!(
            index.contains(&format!("src=\"{c}\"")),
            "{c} missing from index.html"
        );
        let svg = std::fs::read_to_string(rep.join(c)).unwrap();
        assert!(
            svg.matches("<circle").count() >= 5,
            "{c} shows no simulated points"
        );
        assert!(
            svg.contains("<polyline") || svg.contains("<path"),
            "{c} has no lines"
        );
        // The PNG asked for beside the SVG the index shows (crossed.png copied from
        // crossed/), and the points drawn.
        let png = std::fs::read(rep.join(c).with_extension("png")).unwrap();
        assert!(png.starts_with(b"\x89PNG"), "{c}");
        let data = std::fs::read_to_string(rep.join(c).with_extension("plot.csv")).unwrap();
        assert!(data.lines().count() >= 6, "{c}: {data}");
    }
    // The study's Fig. 2b: the curve with four marked states beside their whole outlines
    // (closed loops), and the sphere's accuracy against cost with its stated uncertainty.
    let shapes = std::fs::read_to_string(rep.join("pulloff_shapes_r5.plot.csv")).unwrap();
    for k in 1..=4 {
        assert!(
            shapes.contains(&format!("Contact outlines 1–4: {k},")),
            "{shapes}"
        );
    }
    let outline: Vec<&str> = shapes
        .lines()
        .filter(|l| l.starts_with("Contact outlines 1–4: 1,"))
        .collect();
    assert!(
        outline.len() > 20
            && outline.first().map(|l| l.split(',').nth(2))
                == outline.last().map(|l| l.split(',').nth(2))
    );
    assert!(index.contains("src=\"pulloff_shapes_r5.svg\"") && index.contains("Fig. 2b"));
    for chart in ["accuracy_cost", "accuracy_cost_iterations"] {
        let data = std::fs::read_to_string(rep.join(format!("{chart}.plot.csv"))).unwrap();
        let bar: f64 = data
            .lines()
            .nth(1)
            .and_then(|l| l.rsplit(',').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!(bar > 0.0, "{chart}: {data}");
        assert!(index.contains(&format!("src=\"{chart}.svg\"")));
    }
    assert_eq!(index.matches("<figcaption>").count(), charts.len() + 3);
    // The ratios too coarse for their estimate (10, 25, 50 on the quick grids) are drawn
    // hollow, marked "coarse", and left out of the coefficients' laws, which then have too
    // few ratios to be fitted.
    for chart in ["d_of_c.svg", "axis_ratio.svg"] {
        let svg = std::fs::read_to_string(rep.join(chart)).unwrap();
        assert!(svg.contains(", coarse)"), "{chart}");
    }
    let coefficients = std::fs::read_to_string(rep.join("coefficients.svg")).unwrap();
    assert!(coefficients.contains("coarse grid, not fitted"));
    let laws = std::fs::read_to_string(rep.join("coefficient_laws.csv")).unwrap();
    assert!(
        laws.lines().skip(1).all(|l| l.contains(",,,,,,3,")),
        "{laws}"
    );
    // The fits with their quality, per ratio and across ratios.
    let fits = std::fs::read_to_string(rep.join("fits.csv")).unwrap();
    assert!(fits.starts_with(
        "ratio,a,b,d_r_squared,d_rms,c1,c2,alpha,alpha_at_bound,f_r_squared,f_rms,points"
    ));
    assert_eq!(fits.lines().count(), 7);
    let coarse: Vec<&str> = fits
        .lines()
        .filter(|l| l.ends_with(",true"))
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(coarse, ["10.0", "25.0", "50.0"], "{fits}");
    let laws = std::fs::read_to_string(rep.join("coefficient_laws.csv")).unwrap();
    assert_eq!(laws.lines().count(), 6, "{laws}");
    assert!(index.contains("backend cpu-f64"));
    // |min F̄| at Δx → 0 (with its stated uncertainty) falls with the ratio, and less steeply
    // than JG.
    let mut csv = csv::Reader::from_path(rep.join("sweep/sweep.csv")).unwrap();
    let header = csv.headers().unwrap().clone();
    let rows: Vec<csv::StringRecord> = csv.records().map(|r| r.unwrap()).collect();
    let f = |r: &csv::StringRecord, name: &str| -> f64 {
        r[header.iter().position(|h| h == name).unwrap()]
            .parse()
            .unwrap()
    };
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    assert_eq!(f(first, "ratio"), 1.0);
    assert!((f(first, "f_ad_bar") - 0.5).abs() <= f(first, "f_ad_bar_uncertainty"));
    assert!(
        f(last, "f_ad_bar") < f(first, "f_ad_bar"),
        "the adhesive force falls with R1/R2"
    );
    assert!(
        f(first, "f_ad_bar") - f(last, "f_ad_bar")
            < f(first, "jg_f_ad_bar") - f(last, "jg_f_ad_bar"),
        "it falls less steeply than JG"
    );
    // Every value is shown with its uncertainty, and the coarse grids' warnings are listed.
    assert!(
        index.contains(" ± ") && index.contains("<h2>Warnings</h2>"),
        "{index}"
    );
    // Without the pinned transient, F̄ = c1 c̄³ + c2 c̄^α fits every ratio's branch smoothly
    // (it was RMS 0.16 with α at its bound for 50:1).
    let mut fits = csv::Reader::from_path(rep.join("fits.csv")).unwrap();
    let fh = fits.headers().unwrap().clone();
    for r in fits.records().map(|r| r.unwrap()) {
        let get = |name: &str| r[fh.iter().position(|h| h == name).unwrap()].to_string();
        let rms: f64 = get("f_rms").parse().unwrap();
        assert!(rms < 0.03, "R1/R2 = {}: F̄ fit RMS {rms}", get("ratio"));
        assert_eq!(get("alpha_at_bound"), "false", "R1/R2 = {}", get("ratio"));
    }
}
