//! The command line: bad input is refused before any work with a message naming the flag,
//! a run that fails mid-way leaves only a file marked incomplete, and a good run writes the
//! documented CSV and JSON.

use crate::common;

use common::{jkrbem, stderr};

#[test]
fn bad_input_is_refused_with_the_flag_named_and_nothing_written() {
    let cases: &[(&[&str], &str)] = &[
        (&["--ratio", "0.5"], "--ratio"),
        (&["--ratio", "NaN"], "--ratio"),
        (&["--ratio", "inf"], "--ratio"),
        (&["--r1", "0.5", "--r2", "1"], "--r1"),
        (&["--r2", "0"], "--r2"),
        (&["--e-star=-1"], "--e-star"),
        (&["--e-star", "0"], "--e-star"),
        (&["--work-of-adhesion", "0"], "--work-of-adhesion"),
        (&["--grid", "100"], "--grid"),
        (&["--grid", "8"], "--grid"),
        (
            &["--ratio", "1", "--grid", "64", "--grid-y", "16"],
            "--grid-y",
        ),
        (&["--start-radius", "0"], "--start-radius"),
        (&["--start-radius", "NaN"], "--start-radius"),
        (&["--steps", "0"], "--steps"),
        (&["--cg-accept", "0"], "--cg-accept"),
        (&["--cg-accept", "1"], "--cg-accept"),
        (&["--final-d", "5"], "--final-d"),
        (&["--backend", "quantum"], "--backend"),
        (&["--grid", "abc"], "--grid"),
    ];
    for (args, flag) in cases {
        let dir = tempfile::tempdir().unwrap();
        let mut full = vec!["simulate", "--out", "out/states.csv"];
        full.extend_from_slice(args);
        let o = jkrbem(&full, dir.path());
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?} was accepted");
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(flag),
            "{args:?}: message does not name {flag}: {err}"
        );
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(!dir.path().join("out").exists(), "{args:?} wrote output");
    }
}

#[test]
fn a_run_that_fails_midway_leaves_only_an_incomplete_file() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--cg-max-iterations",
            "2",
            "--out",
            "s.csv",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("did not converge"), "{err}");
    assert!(
        !dir.path().join("s.csv").exists(),
        "a failed run must not look complete"
    );
    // The partial states carry a name unique to the run: s.incomplete-<pid>.csv.
    let partial: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("s.incomplete-") && n.ends_with(".csv"))
        .collect();
    assert_eq!(partial.len(), 1, "{partial:?}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(summary["complete"], false);
}

#[test]
fn a_contact_reaching_the_domain_edge_stops_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate", "--ratio", "1", "--grid", "32", "--margin", "0", "--out", "s.csv",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("edge of the domain"), "{err}");
    assert!(!dir.path().join("s.csv").exists());
}

#[test]
fn a_good_run_writes_the_documented_csv_and_summary() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "2",
            "--grid",
            "32",
            "--steps",
            "40",
            "--out",
            "s.csv",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("s.csv")).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "step,phase,d,force,area,mean_radius,a_axis,b_axis,n_contact,cg_iterations,\
         detach_sweeps,d_bar,f_bar,c_bar,a_bar,b_bar,cg_residual,dx,onsets"
    );
    assert!(text.lines().count() > 40);
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    for key in [
        "estimate",
        "f_ad_bar",
        "f_ad_bar_uncertainty",
        "c_bar_at_min",
        "d_bar_at_min",
        "jg_f_ad_bar",
        "jg_deviation",
        "cg_iterations",
        "wall_s",
        "complete",
    ] {
        assert!(!s[key].is_null(), "summary lacks {key}: {s}");
    }
    let run = &s["runs"][0];
    for key in ["f_ad_bar", "n_d", "nx", "ny", "dx", "backend", "precision"] {
        assert!(!run[key].is_null(), "the run lacks {key}: {s}");
    }
    assert_eq!(s["complete"], true);
    assert_eq!(run["backend"], "cpu");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("adhesive force"), "{stdout}");
}

#[test]
fn theory_writes_curves_and_refuses_jkr_for_an_ellipsoid() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &["theory", "--model", "jg", "--ratio", "1", "--out", "jg.csv"],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("F̄ = -0.500000"), "{stdout}");
    let text = std::fs::read_to_string(dir.path().join("jg.csv")).unwrap();
    assert_eq!(
        text.lines().next().unwrap(),
        "c_bar,f_bar,d_bar,a_bar,b_bar"
    );
    let o = jkrbem(
        &["theory", "--model", "jkr", "--ratio", "2", "--out", "j.csv"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(!dir.path().join("j.csv").exists());
}

#[test]
fn mesh_angle_is_checked_and_reported() {
    for (args, flag) in [
        (&["--mesh-angle", "NaN"][..], "--mesh-angle"),
        (&["--mesh-angle", "inf"][..], "--mesh-angle"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let mut full = vec!["simulate", "--out", "out/s.csv"];
        full.extend_from_slice(args);
        let o = jkrbem(&full, dir.path());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(flag),
            "{args:?}: message does not name {flag}: {err}"
        );
        assert!(!dir.path().join("out").exists(), "{args:?} wrote output");
    }
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "5",
            "--grid",
            "32",
            "--steps",
            "20",
            "--backend",
            "cpu",
            "--mesh-angle",
            "-45",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir
        .path()
        .join("jkrbem-out/simulate-r5-n32-a-45.csv")
        .exists());
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(s["runs"][0]["mesh_angle_deg"], -45.0);
    assert_eq!(s["runs"][0]["ny"], 32);
    assert_eq!(s["runs"][0]["backend"], "cpu");
    // An isolated contact is not periodic: the periodic convolution is refused for it.
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "5",
            "--grid",
            "32",
            "--convolution",
            "periodic",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--convolution periodic is for"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_bare_simulate_states_the_adhesive_force_to_two_percent() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--backend",
            "cpu",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("--accuracy 2.000 %"),
        "it says what it chose: {err}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(s["target"], 0.02, "{s}");
    assert_eq!(s["target_met"], true, "{s}");
    assert_eq!(s["estimate"], "single-grid", "{s}");
    let (f, u) = (
        s["f_ad_bar"].as_f64().unwrap(),
        s["f_ad_bar_uncertainty"].as_f64().unwrap(),
    );
    assert!((f - 0.5).abs() <= u && u / f <= 0.02, "{f} ± {u}");
    // The one grid's states are under the default name, and its own value is biased high.
    let run = &s["runs"][0];
    let states = run["states_csv"].as_str().unwrap();
    assert!(states.starts_with("jkrbem-out/simulate-r1-n"), "{states}");
    assert!(dir.path().join(states).exists(), "{states}");
    assert!(run["f_ad_bar"].as_f64().unwrap() > f + 0.5 * s["f_ad_bar_bias"].as_f64().unwrap());
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("deviation from JG") && !stdout.contains("error +"),
        "{stdout}"
    );
}

#[test]
fn a_time_limit_gives_the_best_answer_so_far_and_says_the_target_was_missed() {
    let dir = tempfile::tempdir().unwrap();
    // 0.2 % for the sphere needs a fine grid (minutes on a CPU); 5 s leaves time only for the
    // coarsest grid that resolves the contact (32², well under a second), run first.
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--accuracy",
            "0.2%",
            "--time-limit",
            "5s",
            "--backend",
            "cpu",
            "--out",
            "t.csv",
            "--summary",
            "t.json",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    // The warning goes to standard error, beside the progress; the answer to stdout.
    assert!(err.contains("WARNING: --time-limit 5s reached"), "{err}");
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("adhesive force") && !stdout.contains("WARNING"),
        "{stdout}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("t.json")).unwrap()).unwrap();
    assert_eq!(s["target_met"], false, "{s}");
    assert_eq!(s["runs"][0]["nx"], 32, "{s}");
    assert!(s["runs"]
        .as_array()
        .unwrap()
        .iter()
        .all(|r| r["min_reached"] == true));
    let (f, u) = (
        s["f_ad_bar"].as_f64().unwrap(),
        s["f_ad_bar_uncertainty"].as_f64().unwrap(),
    );
    assert!((f - 0.5).abs() <= u && u / f > 0.002, "{f} ± {u}");
    assert!(s["warnings"].to_string().contains("--time-limit"), "{s}");
    assert!(dir.path().join("t-n32.csv").exists());

    // With time to spare the plan's own grid answers (64² for 2 %), and the fallback 32² run
    // first is not pooled with it: the estimator is the one the plan chose.
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--accuracy",
            "2%",
            "--time-limit",
            "10min",
            "--backend",
            "cpu",
            "--out",
            "p.csv",
            "--summary",
            "p.json",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("p.json")).unwrap()).unwrap();
    let runs = s["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1, "{s}");
    assert_eq!(runs[0]["nx"], 64, "{s}");
    assert_eq!(s["estimate"], "single-grid", "{s}");
    assert_eq!(s["target_met"], true, "{s}");
    assert!(dir.path().join("p-n32.csv").exists() && dir.path().join("p-n64.csv").exists());
    let out = String::from_utf8_lossy(&o.stdout).to_string() + &stderr(&o);
    assert!(out.contains("is not used"), "{out}");

    // The unit is required, and the limit belongs to an accuracy run.
    for (args, says) in [
        (&["--time-limit", "30"][..], "write the unit"),
        (&["--time-limit", "0s"][..], "[1 s, 30 days]"),
        (&["--grid", "64", "--time-limit", "30s"][..], "--accuracy"),
    ] {
        let mut full = vec!["simulate", "--out", "x/y.csv"];
        full.extend_from_slice(args);
        let o = jkrbem(&full, dir.path());
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("--time-limit") && err.contains(says),
            "{args:?}: {err}"
        );
        assert!(!dir.path().join("x").exists());
    }
}

#[test]
fn an_accuracy_plan_keeps_its_target_with_one_run_not_several_that_may_disagree() {
    // 1 % for the sphere: one 128² run. Two 64² runs at other margins would be predicted
    // within 1 % only if they agreed; allowing for the Birge ratio they show one time in ten,
    // they are not (two such runs for R1/R2 = 5 and 25 stated ± 1.6 %).
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--accuracy",
            "1%",
            "--backend",
            "cpu",
            "--out",
            "t.csv",
            "--summary",
            "t.json",
        ],
        dir.path(),
    );
    let out = String::from_utf8_lossy(&o.stdout).to_string() + &stderr(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("grid 128"), "it says what it chose: {out}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("t.json")).unwrap()).unwrap();
    let runs = s["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 1, "{s}");
    assert_eq!(runs[0]["nx"], 128, "{s}");
    assert_eq!(s["estimate"], "single-grid", "{s}");
    assert_eq!(s["target_met"], true, "{s}");
    let (f, u) = (
        s["f_ad_bar"].as_f64().unwrap(),
        s["f_ad_bar_uncertainty"].as_f64().unwrap(),
    );
    assert!((f - 0.5).abs() <= u && u / f <= 0.01, "{f} ± {u}");
}

/// `simulate --indenter` runs the flat punch and the power law on one grid, sets them beside
/// their closed forms, and refuses what needs a convergence law they do not have.
#[test]
fn other_indenters_run_one_grid_beside_their_closed_form() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("punch.csv");
    let summary = dir.path().join("punch.json");
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
        .args([
            "simulate",
            "--indenter",
            "flat-punch",
            "--radius",
            "2",
            "--grid",
            "32",
        ])
        .args(["--measure", "adhesive-force", "--backend", "cpu", "--out"])
        .arg(&out)
        .arg("--summary")
        .arg(&summary)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(text.contains("Kendall's exact limit 1.0000"), "{text}");
    assert!(!text.contains("Johnson–Greenwood"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    assert_eq!(json["indenter"], "flat-punch");
    assert_eq!(json["exact_limit"]["name"], "Kendall");
    assert!(
        json["f_ad_bar"].is_null(),
        "no estimate without a convergence law"
    );
    let own = json["runs"][0]["f_ad_bar"].as_f64().unwrap();
    let err = json["exact_limit"]["grid_error"].as_f64().unwrap();
    assert!(
        (own - 1.0 - err).abs() < 1e-12 && err.abs() < 0.05,
        "{own} {err}"
    );

    for (args, flag) in [
        // Extrapolated without a convergence law: bad grids and targets are still refused.
        (
            &["--indenter", "flat-punch", "--accuracy", "150%"][..],
            "--accuracy",
        ),
        (
            &[
                "--indenter",
                "power-law",
                "--extrapolate",
                "--extrapolate-grids",
                "64",
            ][..],
            "--extrapolate-grids",
        ),
        (
            &["--indenter", "power-law", "--exponent", "0.5"][..],
            "--exponent",
        ),
        (&["--indenter", "power-law", "--scale", "-1"][..], "--scale"),
        (
            &["--indenter", "flat-punch", "--radius", "nan"][..],
            "--radius",
        ),
        (&["--indenter", "flat-punch", "--r1", "3"][..], "--r1"),
        (
            &["--indenter", "cone", "--half-angle", "90"][..],
            "--half-angle",
        ),
        (
            &["--indenter", "power-law", "--half-angle", "60"][..],
            "--half-angle",
        ),
        (&["--indenter", "cone", "--exponent", "3"][..], "--exponent"),
    ] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
            .arg("simulate")
            .args(args)
            .args(["--backend", "cpu", "--out"])
            .arg(dir.path().join("refused.csv"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(flag), "{args:?}: {err}");
        assert!(!dir.path().join("refused.csv").exists());
    }
}

/// `--indenter height-map` reads a text grid, runs it, and refuses bad maps before any work.
#[test]
fn a_height_map_file_runs_and_bad_maps_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let grid = |f: &dyn Fn(f64, f64) -> f64| {
        let (n, s) = (161, 0.05);
        let mut text = String::from("# a sphere of radius 1, spacing 0.05\n");
        for j in 0..n {
            let row: Vec<String> = (0..n)
                .map(|i| {
                    let (x, y) = ((i as f64 - 80.0) * s, (j as f64 - 80.0) * s);
                    format!("{}", f(x, y))
                })
                .collect();
            text += &row.join(" ");
            text += "\n";
        }
        text
    };
    let write = |name: &str, text: String| {
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    };
    let sphere = write("sphere.txt", grid(&|x, y| 0.5 * (x * x + y * y) + 2.0));
    let run = |map: &std::path::Path, extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
            .args(["simulate", "--indenter", "height-map", "--height-map"])
            .arg(map)
            .args(extra)
            .args([
                "--grid",
                "32",
                "--measure",
                "adhesive-force",
                "--backend",
                "cpu",
            ])
            .arg("--out")
            .arg(dir.path().join("map.csv"))
            .output()
            .unwrap()
    };
    let o = run(&sphere, &["--spacing", "0.05"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(text.contains("height-map"), "{text}");
    // The sampled sphere on 32² is the sphere on 32² up to the map's bilinear interpolation
    // (element centres fall between its nodes): s²/8·h'' ≈ 3e-4 in height against an approach
    // scale of 3.7, about 1e-4 relative.
    let sphere_run = std::process::Command::new(env!("CARGO_BIN_EXE_jkrbem"))
        .args([
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--measure",
            "adhesive-force",
        ])
        .args(["--backend", "cpu", "--out"])
        .arg(dir.path().join("sphere.csv"))
        .output()
        .unwrap();
    let own = |t: &str| {
        t.lines()
            .filter(|l| l.starts_with("grid "))
            .find_map(|l| l.split("|min F̄| = ").nth(1))
            .and_then(|v| v.split(',').next())
            .and_then(|v| v.parse::<f64>().ok())
    };
    let sphere_text = String::from_utf8_lossy(&sphere_run.stdout);
    let (m, s) = (own(&text).unwrap(), own(&sphere_text).unwrap());
    assert!((m / s - 1.0).abs() < 1e-3, "{text}\n{sphere_text}");

    let nan = write(
        "nan.txt",
        grid(&|x, y| {
            if (x - 0.05).abs() < 1e-9 && (y + 4.0).abs() < 1e-9 {
                f64::NAN
            } else {
                x * x + y * y
            }
        }),
    );
    let saddle = write("saddle.txt", grid(&|x, y| x * x - y * y));
    for (map, extra, says) in [
        (&sphere, &[][..], "--spacing"),
        (&sphere, &["--spacing", "-1"][..], "spacing"),
        (&nan, &["--spacing", "0.05"][..], "row 1"),
        (
            &dir.path().join("absent.txt"),
            &["--spacing", "0.05"][..],
            "--height-map",
        ),
        (
            &dir.path().to_path_buf(),
            &["--spacing", "0.05"][..],
            "not a regular file",
        ),
    ] {
        let o = run(map, extra);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{map:?} {extra:?}: {err}");
        assert!(err.contains(says), "{map:?} {extra:?}: {err}");
    }
    // A saddle has no apex: it is placed on the whole map, pressed on and pulled off, its
    // results in the user's units.
    let o = run(&saddle, &["--spacing", "0.05"]);
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert_eq!(o.status.code(), Some(0), "{out}{err}");
    assert!(err.contains("not normalised"), "{out}{err}");
}

#[test]
fn fields_are_written_as_npz_numpy_reads_and_a_pressure_picture() {
    use ndarray::{Array1, Array3};
    use ndarray_npy::NpzReader;
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "2",
            "--grid",
            "64",
            "--backend",
            "cpu",
            "--fields",
            "every:100",
            "--out",
            "r.csv",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("fields written to r.fields.npz"),
        "{stdout}"
    );
    let svg = std::fs::read_to_string(dir.path().join("r.pressure.svg")).unwrap();
    assert!(svg.contains("p (force/length²)") && svg.contains("force minimum"));
    let mut npz =
        NpzReader::new(std::fs::File::open(dir.path().join("r.fields.npz")).unwrap()).unwrap();
    let p: Array3<f64> = npz.by_name("pressure").unwrap();
    let c: Array3<bool> = npz.by_name("contact").unwrap();
    let force: Array1<f64> = npz.by_name("force").unwrap();
    let dx: Array1<f64> = npz.by_name("dx").unwrap();
    let index: Array1<u64> = npz.by_name("state_index").unwrap();
    let meta: Array1<u8> = npz.by_name("metadata").unwrap();
    let meta: serde_json::Value = serde_json::from_slice(meta.as_slice().unwrap()).unwrap();
    assert_eq!(p.shape(), c.shape());
    assert_eq!(p.shape()[2], 64, "(states, ny, nx)");
    assert_eq!(index.as_slice().unwrap()[..2], [0, 100]);
    assert!(meta["labels"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .as_str()
        .unwrap()
        .contains("force minimum"));
    assert!(meta["units"]["pressure"]
        .as_str()
        .unwrap()
        .starts_with("force/length²"));
    // Each state's Σ p Δx² is its force; the states CSV has the same force on that row.
    let states = jkrbem::output::data::read_states(&dir.path().join("r.csv"))
        .unwrap()
        .states;
    for k in 0..p.shape()[0] {
        let sum = p.index_axis(ndarray::Axis(0), k).sum() * dx[k] * dx[k];
        assert!(
            (sum - force[k]).abs() <= 1e-6 * force[k].abs().max(1e-3),
            "{sum} vs {}",
            force[k]
        );
        assert_eq!(states[index[k] as usize].force, force[k]);
    }
    // A bad choice is refused naming the flag, before any work.
    let o = jkrbem(
        &[
            "simulate", "--grid", "64", "--fields", "every:0", "--out", "b.csv",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--fields"), "{}", stderr(&o));
    assert!(!dir.path().join("b.csv").exists());
}
