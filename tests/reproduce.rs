//! `jkrbem reproduce --quick`: the whole study on coarse grids writes every chart of SPEC §8
//! (with data in each) and an index.html that shows them with captions, and the adhesive
//! force falls with R1/R2 less steeply than Johnson–Greenwood's.

mod common;

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
    }
    assert_eq!(index.matches("<figcaption>").count(), charts.len());
    // The fits with their quality, per ratio and across ratios.
    let fits = std::fs::read_to_string(rep.join("fits.csv")).unwrap();
    assert!(fits.starts_with(
        "ratio,a,b,d_r_squared,d_rms,c1,c2,alpha,alpha_at_bound,f_r_squared,f_rms,points"
    ));
    assert_eq!(fits.lines().count(), 7);
    let laws = std::fs::read_to_string(rep.join("coefficient_laws.csv")).unwrap();
    assert_eq!(laws.lines().count(), 6, "{laws}");
    assert!(index.contains("backend cpu-f64"));
    // |min F̄| falls with the ratio, and less steeply than JG.
    let rows: Vec<Vec<String>> = std::fs::read_to_string(rep.join("sweep/sweep.csv"))
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    let f = |r: &Vec<String>, i: usize| r[i].parse::<f64>().unwrap();
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    assert_eq!(f(first, 0), 1.0);
    assert!(
        f(last, 1) < f(first, 1),
        "the adhesive force falls with R1/R2"
    );
    assert!(
        f(first, 1) - f(last, 1) < f(first, 4) - f(last, 4),
        "it falls less steeply than JG"
    );
}
