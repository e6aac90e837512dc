//! `jkrbem sweep` and `jkrbem collect`: per-ratio states and summaries, the summary CSV with
//! the documented columns, shards that a cluster runs separately and their merge, and bad
//! input refused before any work.

use crate::common;

use common::{jkrbem, stderr};
use std::path::Path;
use std::process::Output;

const QUICK: &[&str] = &[
    "--grid",
    "32",
    "--margin",
    "0.2",
    "--steps",
    "40",
    "--backend",
    "cpu",
    "--out",
    "sw",
];

fn sweep(dir: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["sweep", "--ratios", "1,2,5"];
    args.extend_from_slice(QUICK);
    args.extend_from_slice(extra);
    jkrbem(&args, dir)
}

#[test]
fn shards_run_separately_and_collect_merges_them_into_the_whole_sweep() {
    let whole = tempfile::tempdir().unwrap();
    let o = sweep(whole.path(), &["--jobs", "2"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let expected = std::fs::read_to_string(whole.path().join("sw/sweep.csv")).unwrap();
    let header = expected.lines().next().unwrap();
    assert!(header.starts_with(
        "ratio,f_ad_bar,f_ad_bar_uncertainty,estimate,c_bar_at_min,d_bar_at_min,jg_f_ad_bar,n_d,\
         grid,dx,wall_s"
    ));
    assert_eq!(expected.lines().count(), 4);
    for r in ["1", "2", "5"] {
        assert!(whole.path().join(format!("sw/r{r}-n32.csv")).exists());
        assert!(whole.path().join(format!("sw/r{r}-n32.json")).exists());
    }

    let split = tempfile::tempdir().unwrap();
    assert!(sweep(split.path(), &["--shard", "1/2"]).status.success());
    let early = jkrbem(&["collect", "sw"], split.path());
    assert_eq!(early.status.code(), Some(1), "a missing shard is reported");
    assert!(stderr(&early).contains("shards [2] of 2"));
    assert!(sweep(split.path(), &["--shard", "2/2"]).status.success());
    assert!(jkrbem(&["collect", "sw"], split.path()).status.success());
    let merged = std::fs::read_to_string(split.path().join("sw/sweep.csv")).unwrap();
    // Everything but the wall times is the same as the unsplit sweep.
    let strip = |s: &str| -> Vec<String> {
        s.lines()
            .map(|l| {
                let mut f: Vec<&str> = l.split(',').collect();
                f[10] = "";
                f.join(",")
            })
            .collect()
    };
    assert_eq!(strip(&merged), strip(&expected));
}

#[test]
fn bad_sweep_input_is_refused_before_any_work() {
    for (extra, flag) in [
        (&["--shard", "3/2"][..], "--shard"),
        (&["--shard", "x"][..], "--shard"),
        (&["--jobs", "0"][..], "--jobs"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let o = sweep(dir.path(), extra);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains(flag), "{extra:?}: {err}");
        assert!(!dir.path().join("sw").exists());
    }
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(&["sweep", "--ratios", "1,0.5", "--out", "sw"], dir.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--ratios"));
    assert!(!dir.path().join("sw").exists());
    let o = jkrbem(&["collect", "nowhere"], dir.path());
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn crossed_cylinders_give_forces_in_newtons_beside_jg() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "crossed",
            "--angles",
            "90,50",
            "--radius",
            "0.01",
            "--e",
            "1e6",
            "--nu",
            "0.5",
            "--work-of-adhesion",
            "0.05",
            "--grid",
            "32",
            "--margin",
            "0.2",
            "--steps",
            "40",
            "--backend",
            "cpu",
            "--out",
            "cr",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("cr/crossed.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 2);
    // θ = 90°: a sphere of radius R; JKR's pull-off force is (3/2)·π·R·Δγ.
    let sphere = &rows[0];
    assert_eq!(sphere[col("angle_deg")], 90.0);
    assert!((sphere[col("ratio")] - 1.0).abs() < 1e-12);
    let jkr = 1.5 * std::f64::consts::PI * 0.01 * 0.05;
    assert!((sphere[col("jg_f_ad")] / jkr - 1.0).abs() < 1e-9);
    // The simulated force is the normalised one times 3π Re Δγ, and over-adheres on a coarse grid.
    let f = sphere[col("f_ad")];
    assert!(
        (f / (sphere[col("f_ad_bar")] * 3.0 * std::f64::consts::PI * 0.01 * 0.05) - 1.0).abs()
            < 1e-9
    );
    assert!(f > jkr && f < 1.3 * jkr, "{f} vs {jkr}");
    // θ = 50°: R1/R2 = cot²(25°).
    let cot = 1.0 / 25f64.to_radians().tan();
    assert!((rows[1][col("ratio")] / (cot * cot) - 1.0).abs() < 1e-9);
    // The chart's title gives the inputs with their units (issue 12: it had none).
    let svg = std::fs::read_to_string(dir.path().join("cr/crossed.svg")).unwrap();
    assert!(
        svg.contains("R = 0.01 m, E = 1e6 Pa, ν = 0.5, Δγ = 0.05 J/m²"),
        "title without units"
    );

    let bad = jkrbem(&["crossed", "--nu", "0.7", "--out", "x"], dir.path());
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("--nu"));
    assert!(!dir.path().join("x").exists());
}

#[test]
fn extrapolation_to_zero_element_size_moves_the_sphere_towards_jkr() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--extrapolate",
            "--extrapolate-grids",
            "32,64,128",
            "--margin",
            "0.1",
            "--backend",
            "cpu",
            "--out",
            "ex/s.csv",
            "--summary",
            "ex/s.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("ex/s.json")).unwrap())
            .unwrap();
    assert_eq!(report["estimate"], "extrapolated");
    let (value, bar, finest) = (
        report["f_ad_bar"].as_f64().unwrap(),
        report["f_ad_bar_uncertainty"].as_f64().unwrap(),
        report["runs"][2]["f_ad_bar"].as_f64().unwrap(),
    );
    println!("extrapolated |min F̄| = {value:.4} ± {bar:.4}, finest {finest:.4}");
    // Closer to JKR's 1/2 than the finest grid, and within its own error bar of it.
    assert!((value - 0.5).abs() < (finest - 0.5).abs());
    assert!((value - 0.5).abs() <= bar, "{value} ± {bar}");
    for n in [32, 64, 128] {
        assert!(dir.path().join(format!("ex/s-n{n}.csv")).exists());
    }
    let bad = jkrbem(
        &[
            "simulate",
            "--extrapolate",
            "--extrapolate-grids",
            "128,64",
            "--out",
            "y/s.csv",
        ],
        dir.path(),
    );
    assert_eq!(bad.status.code(), Some(2));
    assert!(stderr(&bad).contains("--extrapolate-grids"));
    assert!(!dir.path().join("y").exists());
}

#[test]
fn accuracy_charts_error_against_cost_with_the_extrapolated_point() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "accuracy",
            "--ratio",
            "1",
            "--grids",
            "32,64",
            "--backends",
            "cpu",
            "--out",
            "acc",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("acc/accuracy.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "variant,backend,precision,grid,n_d,f_ad_bar,error,wall_s,cg_iterations,reference,\
         reference_uncertainty,stated,stated_uncertainty,stated_error"
    );
    // Every answer the program states (one grid corrected, two extrapolated) holds JKR's 1/2
    // inside its stated interval.
    for l in text.lines().skip(1) {
        let c: Vec<&str> = l.split(',').collect();
        let (stated, u): (f64, f64) = (c[11].parse().unwrap(), c[12].parse().unwrap());
        assert!(
            (stated - 0.5).abs() <= u && u < 0.05,
            "{l}: {stated} ± {u} misses 1/2"
        );
    }
    // Per variant (plain, measure, regrid): two grids and the extrapolated point.
    let rows: Vec<(String, f64, usize)> = lines
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            (
                c[0].to_string(),
                c[6].parse().unwrap(),
                c[8].parse().unwrap(),
            )
        })
        .collect();
    let of = |v: &str| -> Vec<(f64, usize)> {
        rows.iter()
            .filter(|r| r.0 == v)
            .map(|r| (r.1, r.2))
            .collect()
    };
    let (plain, measure, regrid) = (of("plain"), of("measure"), of("regrid"));
    for e in [&plain, &measure, &regrid] {
        // The error falls with the grid, and extrapolation beats the finest grid.
        assert_eq!(e.len(), 3);
        assert!(e[0].0 > e[1].0 && e[1].0 > 0.0);
        assert!(e[2].0.abs() < e[1].0);
    }
    // Measuring only the adhesive force gives the same answers for fewer CG iterations;
    // re-gridding gives smaller errors on the same grids.
    for k in 0..2 {
        assert!((measure[k].0 - plain[k].0).abs() < 1e-9);
        assert!(measure[k].1 <= plain[k].1);
        assert!(regrid[k].0 < plain[k].0);
    }
    let svg = std::fs::read_to_string(dir.path().join("acc/accuracy.svg")).unwrap();
    assert!(svg.contains("exact JKR value"));
    // The same against CG iterations, with the stated uncertainties as bars in its data.
    let iterations =
        std::fs::read_to_string(dir.path().join("acc/accuracy_iterations.plot.csv")).unwrap();
    assert!(
        iterations.lines().skip(1).any(|l| !l.ends_with(',')),
        "{iterations}"
    );
    let bad = jkrbem(&["accuracy", "--backends", "tpu", "--out", "z"], dir.path());
    assert_eq!(bad.status.code(), Some(2));
    assert!(!dir.path().join("z").exists());
}

#[test]
fn without_a_grid_each_ratio_gets_the_grid_its_accuracy_needs() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "sweep",
            "--ratios",
            "1,2",
            "--accuracy",
            "5%",
            "--backend",
            "cpu",
            "--out",
            "sw",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let mut csv = csv::Reader::from_path(dir.path().join("sw/sweep.csv")).unwrap();
    let header = csv.headers().unwrap().clone();
    let col = |r: &csv::StringRecord, name: &str| -> String {
        r[header.iter().position(|h| h == name).unwrap()].to_string()
    };
    let rows: Vec<csv::StringRecord> = csv.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 2);
    let grids: Vec<String> = rows.iter().map(|r| col(r, "grid")).collect();
    assert_ne!(grids[0], grids[1], "the planner chose per ratio: {grids:?}");
    for r in &rows {
        let (f, u): (f64, f64) = (
            col(r, "f_ad_bar").parse().unwrap(),
            col(r, "f_ad_bar_uncertainty").parse().unwrap(),
        );
        assert!(u > 0.0 && u / f <= 0.05, "{f} ± {u}");
        assert_eq!(col(r, "estimate"), "single-grid");
        let json = dir.path().join(format!(
            "sw/r{}-n{}.json",
            col(r, "ratio").parse::<f64>().unwrap(),
            col(r, "grid")
        ));
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap();
        assert_eq!(s["target"], 0.05, "{s}");
        assert_eq!(s["target_met"], true, "{s}");
    }
    // The sphere's interval holds JKR's 1/2.
    let f: f64 = col(&rows[0], "f_ad_bar").parse().unwrap();
    let u: f64 = col(&rows[0], "f_ad_bar_uncertainty").parse().unwrap();
    assert!((f - 0.5).abs() <= u, "{f} ± {u}");
    let svg = std::fs::read_to_string(dir.path().join("sw/force_vs_ratio.svg")).unwrap();
    assert!(
        svg.contains("stated uncertainty"),
        "error bars in the legend"
    );
    // --grid and --accuracy together are refused.
    let o = jkrbem(
        &[
            "sweep",
            "--ratios",
            "1",
            "--grid",
            "32",
            "--accuracy",
            "5%",
            "--out",
            "x",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}
