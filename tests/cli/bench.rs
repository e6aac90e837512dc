//! `jkrbem bench`: a quick CPU run writes one CSV row per grid with the documented columns and
//! a chart; bad grids and unknown backends are refused before any work, naming the flag.

use crate::common;

use common::{jkrbem, stderr};

const HEADER: &str = "backend,precision,adapter,grid,nx,ny,convolution_ms,cg_iteration_ms,\
dispatches_per_iteration,readbacks_per_iteration,pulloff_s,pulloff_cg_iterations,f_ad_bar,\
pulloff_states,pulloff_steps,pulloff_onsets,pulloff_rounds,pulloff_solves,\
pulloff_convolutions,pulloff_readbacks,pulloff_cg_c_below_070,pulloff_cg_c_070_090,\
pulloff_cg_c_090_110,pulloff_cg_c_above_110,pulloff_cg_whole_steps_to_minimum,\
pulloff_cg_whole_steps_past_minimum,pulloff_cg_search_to_minimum,pulloff_cg_search_past_minimum,\
pulloff_dispatches,pulloff_submits,pulloff_wait_s,pulloff_submit_s";

#[test]
fn a_quick_cpu_bench_writes_one_row_per_grid_and_a_chart() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "bench",
            "--backends",
            "cpu",
            "--grids",
            "16,32",
            "--repeats",
            "1",
            "--pulloff-max-grid",
            "16",
            // The default margin (0.08) is less than one element on 16²: see the test below.
            "--margin",
            "0.2",
            "--out",
            "b",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mut csv = csv::Reader::from_path(dir.path().join("b/bench.csv")).unwrap();
    let header: Vec<String> = csv.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header.join(","), HEADER);
    let rows: Vec<csv::StringRecord> = csv.records().map(|r| r.unwrap()).collect();
    assert_eq!(rows.len(), 2, "one row per grid");
    let col = |r: &csv::StringRecord, name: &str| {
        r[header.iter().position(|h| h == name).unwrap()].to_string()
    };
    for (r, n) in rows.iter().zip(["16", "32"]) {
        assert_eq!(col(r, "backend"), "cpu");
        assert_eq!(col(r, "precision"), "f64");
        assert_eq!(col(r, "grid"), n);
        assert_eq!(col(r, "nx"), n);
        assert_eq!(col(r, "ny"), n, "a sphere's grid is square");
        for t in ["convolution_ms", "cg_iteration_ms"] {
            let v: f64 = col(r, t).parse().unwrap();
            assert!(v.is_finite() && v > 0.0, "{t} = {v}");
        }
    }
    // The pull-off ran on 16² only. It is the same deterministic f64 run as `simulate` builds
    // for that grid and margin, so its |min F̄| matches an in-process run to the CSV's 4
    // decimals.
    let f: f64 = col(&rows[0], "f_ad_bar").parse().unwrap();
    let reference = common::run_ratio(
        1.0,
        jkrbem::model::ModelOptions {
            nx: 16,
            margin: 0.2,
            ..Default::default()
        },
    );
    let expected = reference.outcome.force_minimum().unwrap().f_bar.abs();
    assert!(
        (f - expected).abs() <= 0.5e-4 + 1e-12,
        "|min F̄| = {f}, in-process run {expected}"
    );
    let its: usize = col(&rows[0], "pulloff_cg_iterations").parse().unwrap();
    assert!(its > 0);
    // The CPU dispatches nothing, reads nothing back and waits on nothing.
    for name in ["pulloff_dispatches", "pulloff_submits"] {
        assert_eq!(col(&rows[0], name), "0", "{name}");
    }
    for name in ["pulloff_wait_s", "pulloff_submit_s"] {
        assert_eq!(col(&rows[0], name).parse::<f64>().unwrap(), 0.0, "{name}");
    }
    // The cost account: the in-process run's, count for count (the same f64 run).
    let cost = &reference.outcome.cost;
    for (name, want) in [
        ("pulloff_states", cost.states),
        ("pulloff_steps", cost.steps),
        ("pulloff_onsets", cost.onsets),
        ("pulloff_rounds", cost.work.rounds),
        ("pulloff_solves", cost.work.solves),
    ] {
        assert_eq!(col(&rows[0], name), want.to_string(), "{name}");
    }
    assert!(cost.work.solves >= cost.steps && cost.steps > 0 && cost.states > cost.steps);
    // Its CG iterations per c̄ band, and by activity on either side of the minimum, add up.
    let sum = |names: &[&str]| -> usize {
        names
            .iter()
            .map(|n| col(&rows[0], n).parse::<usize>().unwrap())
            .sum()
    };
    let bands = [
        "pulloff_cg_c_below_070",
        "pulloff_cg_c_070_090",
        "pulloff_cg_c_090_110",
        "pulloff_cg_c_above_110",
    ];
    let activities = [
        "pulloff_cg_whole_steps_to_minimum",
        "pulloff_cg_whole_steps_past_minimum",
        "pulloff_cg_search_to_minimum",
        "pulloff_cg_search_past_minimum",
    ];
    assert_eq!(sum(&bands), its);
    assert_eq!(sum(&activities), its);
    assert_eq!(
        col(&rows[0], "pulloff_cg_search_past_minimum"),
        cost.past_minimum.search.cg_iterations.to_string()
    );
    for empty in [
        "pulloff_s",
        "pulloff_cg_iterations",
        "f_ad_bar",
        "pulloff_solves",
    ] {
        assert_eq!(col(&rows[1], empty), "", "{empty} at 32² was not measured");
    }
    let svg = std::fs::read_to_string(dir.path().join("b/bench.svg")).unwrap();
    assert!(svg.len() > 2000, "the chart is near empty: {svg}");
    assert!(svg.contains("<svg") && svg.contains("</svg>"));
    assert!(svg.contains("CG iteration") && svg.contains("(ms)"));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("16×16") && stdout.contains("32×32"),
        "{stdout}"
    );
    assert!(stdout.contains("pull-off cost account"), "{stdout}");
}

#[test]
fn a_pulloff_that_fails_leaves_its_cells_empty_and_exits_1() {
    // On 16² with no margin the contact reaches the domain's edge. The timings are still
    // written; the pull-off's cells stay empty.
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "bench",
            "--backends",
            "cpu",
            "--grids",
            "16",
            "--repeats",
            "1",
            "--pulloff-max-grid",
            "16",
            "--margin",
            "0",
            "--out",
            "b",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("edge of the domain") && err.contains("--margin"),
        "{err}"
    );
    let text = std::fs::read_to_string(dir.path().join("b/bench.csv")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert!(lines[1].ends_with(",,,"), "{}", lines[1]);
    assert!(dir.path().join("b/bench.svg").exists());
}

#[test]
fn bad_grids_and_unknown_backends_are_refused_naming_the_flag() {
    let cases: &[(&[&str], &str)] = &[
        (&["--grids", "30"], "--grids"),
        (&["--grids", "64,8"], "--grids"),
        (&["--grids", "abc"], "--grids"),
        (&["--backends", "tpu"], "--backends"),
        (&["--repeats", "0"], "--repeats"),
        (&["--ratio", "0.5"], "--ratio"),
    ];
    for (args, flag) in cases {
        let dir = tempfile::tempdir().unwrap();
        let mut full = vec!["bench", "--backends", "cpu", "--out", "b"];
        full.extend_from_slice(args);
        let o = jkrbem(&full, dir.path());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(flag),
            "{args:?}: message does not name {flag}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!dir.path().join("b").exists(), "{args:?} wrote output");
    }
}

#[test]
fn each_backend_is_timed_in_each_precision_asked_for() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "bench",
            "--backends",
            "cpu",
            "--precisions",
            "f64,f32",
            "--grids",
            "16",
            "--repeats",
            "1",
            "--pulloff-max-grid",
            "0",
            "--margin",
            "0.2",
            "--out",
            "b",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let mut csv = csv::Reader::from_path(dir.path().join("b/bench.csv")).unwrap();
    let precisions: Vec<String> = csv.records().map(|r| r.unwrap()[1].to_string()).collect();
    assert_eq!(precisions, ["f64", "f32"]);
    // The GPU has no f64: asked for alone, refused before any work, naming the precision.
    let o = jkrbem(
        &[
            "bench",
            "--backends",
            "gpu",
            "--precisions",
            "f64",
            "--grids",
            "16",
            "--out",
            "g",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("f64"), "{}", stderr(&o));
    assert!(!dir.path().join("g/bench.csv").exists());
}
