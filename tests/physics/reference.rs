//! `jkrbem reference`: the table of converged adhesive forces. A short ladder for the sphere
//! holds JKR's exact 1/2 within its stated uncertainty and records the command; bad input is
//! refused before any work; the committed table's sphere row is recomputed (slow tier).

use crate::common;

use common::{jkrbem, stderr};

/// The rows of a reference table CSV as (header, records).
fn table(path: &std::path::Path) -> (csv::StringRecord, Vec<csv::StringRecord>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let h = r.headers().unwrap().clone();
    (h, r.records().map(|x| x.unwrap()).collect())
}

fn get(h: &csv::StringRecord, r: &csv::StringRecord, name: &str) -> String {
    r[h.iter().position(|x| x == name).unwrap()].to_string()
}

/// The committed table's header and its row for R1/R2 = `ratio`.
fn committed_row(ratio: f64) -> (csv::StringRecord, csv::StringRecord) {
    let committed =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/reference/adhesive-force.csv");
    let (h, rows) = table(&committed);
    let row = rows
        .into_iter()
        .find(|r| get(&h, r, "ratio").parse::<f64>().unwrap() == ratio)
        .unwrap_or_else(|| panic!("the committed table has no row for R1/R2 = {ratio}"));
    (h, row)
}

#[test]
fn a_short_sphere_ladder_holds_one_half_and_records_its_command() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "reference",
        "--ratios",
        "1",
        "--max-grid",
        "128",
        "--target",
        "1%",
        "--backend",
        "cpu",
        "--out",
        "ref/t.csv",
    ];
    // A row of another ratio already in the table is kept (tables grow over several jobs).
    std::fs::create_dir_all(dir.path().join("ref")).unwrap();
    let other = "ratio,f_ad_bar,f_ad_bar_uncertainty,c_bar_at_min,c_bar_at_min_uncertainty,\
d_bar_at_min,d_bar_at_min_uncertainty,k,target_met,grids,n_d,cg_iterations,wall_s,command\n\
7.0,0.48,0.001,0.77,0.01,-0.2,0.01,2.1,true,128;256;512,100.0,1000,10.0,jkrbem reference\n";
    std::fs::write(dir.path().join("ref/t.csv"), other).unwrap();
    let o = jkrbem(&args, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let (h, rows) = table(&dir.path().join("ref/t.csv"));
    assert_eq!(rows.len(), 2, "sorted by ratio, the other row kept");
    assert_eq!(get(&h, &rows[1], "ratio"), "7.0");
    let r = &rows[0];
    let f: f64 = get(&h, r, "f_ad_bar").parse().unwrap();
    let u: f64 = get(&h, r, "f_ad_bar_uncertainty").parse().unwrap();
    assert!((f - 0.5).abs() <= u && u / f <= 0.01, "{f} ± {u}");
    assert_eq!(get(&h, r, "grids"), "32;64;128");
    assert_eq!(get(&h, r, "target_met"), "true");
    let k: f64 = get(&h, r, "k").parse().unwrap();
    assert!((2.5..4.0).contains(&k), "k = {k}");
    assert!(get(&h, r, "command").starts_with("jkrbem reference --ratios 1"));
    let ku: f64 = get(&h, r, "k_uncertainty").parse().unwrap();
    assert!(ku > 0.0 && ku < k, "k = {k} ± {ku}");
    // Every run is kept beside the table, and a second job reuses them: same row, no new run.
    for nx in [32, 64, 128] {
        let json = dir.path().join(format!("ref/t-runs/r1-n{nx}.json"));
        assert!(json.exists());
    }
    let o = jkrbem(&args, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stderr(&o).matches("reusing").count(), 3, "{}", stderr(&o));
    let (_, again) = table(&dir.path().join("ref/t.csv"));
    assert_eq!(get(&h, &again[0], "f_ad_bar"), get(&h, r, "f_ad_bar"));
}

#[test]
fn a_ladder_with_several_phases_per_grid_fits_them_all_and_holds_one_half() {
    // Two runs per grid (margins 0.08 and 0.13): both are kept, the row says so, and the
    // limit from all six holds JKR's 1/2 within its stated uncertainty.
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "reference",
            "--ratios",
            "1",
            "--max-grid",
            "128",
            "--phases",
            "2",
            "--target",
            "1%",
            "--backend",
            "cpu",
            "--out",
            "t.csv",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (h, rows) = table(&dir.path().join("t.csv"));
    let r = &rows[0];
    assert_eq!(get(&h, r, "grids"), "32;64;128");
    assert_eq!(get(&h, r, "runs_per_grid"), "2");
    let f: f64 = get(&h, r, "f_ad_bar").parse().unwrap();
    let u: f64 = get(&h, r, "f_ad_bar_uncertainty").parse().unwrap();
    assert!((f - 0.5).abs() <= u && u / f <= 0.01, "{f} ± {u}");
    for nx in [32, 64, 128] {
        assert!(dir.path().join(format!("t-runs/r1-n{nx}.json")).exists());
        assert!(dir
            .path()
            .join(format!("t-runs/r1-n{nx}-m0.13.json"))
            .exists());
    }
}

#[test]
fn bad_reference_requests_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    for bad in [
        vec!["reference", "--ratios", "0.5", "--out", "t.csv"],
        vec!["reference", "--target", "0.3", "--out", "t.csv"],
        vec!["reference", "--first-grid", "48", "--out", "t.csv"],
        vec!["reference", "--first-grid", "16", "--out", "t.csv"],
        vec!["reference", "--phases", "0", "--out", "t.csv"],
        vec!["reference", "--phases", "9", "--out", "t.csv"],
        vec![
            "reference",
            "--first-grid",
            "1024",
            "--max-grid",
            "512",
            "--out",
            "t.csv",
        ],
    ] {
        let o = jkrbem(&bad, dir.path());
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    // A file that is not a reference table is never replaced.
    std::fs::write(dir.path().join("notes.csv"), "my,own\n1,2\n").unwrap();
    let o = jkrbem(
        &["reference", "--ratios", "1", "--out", "notes.csv"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("not a reference table"));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("notes.csv")).unwrap(),
        "my,own\n1,2\n"
    );
}

#[test]
#[ignore = "slow tier (about 2 minutes): cargo test --release -- --ignored"]
fn the_committed_table_s_sphere_row_is_reproduced_within_its_uncertainty() {
    let (h, row) = committed_row(1.0);
    let (f, u): (f64, f64) = (
        get(&h, &row, "f_ad_bar").parse().unwrap(),
        get(&h, &row, "f_ad_bar_uncertainty").parse().unwrap(),
    );
    // The table's own interval holds the exact value.
    assert!((f - 0.5).abs() <= u, "{f} ± {u}");
    let max_grid = get(&h, &row, "grids")
        .rsplit(';')
        .next()
        .unwrap()
        .to_string();
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "reference",
            "--ratios",
            "1",
            "--max-grid",
            &max_grid,
            "--target",
            "0.3%",
            "--backend",
            "cpu",
            "--out",
            "t.csv",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (h2, again) = table(&dir.path().join("t.csv"));
    let f2: f64 = get(&h2, &again[0], "f_ad_bar").parse().unwrap();
    // The CPU is deterministic: the same ladder gives the same value.
    assert!(
        (f2 - f).abs() <= 1e-9 + 1e-6 * f,
        "{f2} vs the table's {f} ± {u}"
    );
}

#[test]
#[ignore = "slow tier (about 1 minute): cargo test --release -- --ignored"]
fn a_two_grid_fit_agrees_with_the_committed_table_s_slender_row() {
    // 5:1, a slender tabled ratio cheap enough for this tier: the two coarser grids of its ladder, fitted with the
    // law's prior (as `simulate --extrapolate` does), must agree with the table's value within
    // the two stated uncertainties.
    let (h, row) = committed_row(5.0);
    let (f, u): (f64, f64) = (
        get(&h, &row, "f_ad_bar").parse().unwrap(),
        get(&h, &row, "f_ad_bar_uncertainty").parse().unwrap(),
    );
    let grids: Vec<&str> = get(&h, &row, "grids").leak().split(';').collect();
    let coarse = grids[..2].join(",");
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "5",
            "--extrapolate",
            "--extrapolate-grids",
            &coarse,
            "--measure",
            "adhesive-force",
            "--regrid",
            "--steps",
            "100",
            "--backend",
            "cpu",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    let (f2, u2) = (
        s["f_ad_bar"].as_f64().unwrap(),
        s["f_ad_bar_uncertainty"].as_f64().unwrap(),
    );
    println!("table {f} ± {u}; grids {coarse}: {f2} ± {u2}");
    assert!(
        (f2 - f).abs() <= u.hypot(u2),
        "{f2} ± {u2} against the table's {f} ± {u}"
    );
}
