//! `--convolution periodic` on a height map, as the command line words it: the map is one
//! period (its domain the period n·s, not the nodes' hull), a map that is not periodic is
//! refused naming `--height-map`, and a window, a grid or a turned mesh that does not repeat
//! with the map is refused naming its flag, before any work.

use crate::common::{jkrbem, stderr};
use std::f64::consts::PI;
use std::path::Path;

/// Nodes along x (one wavelength) and y, and their spacing (length).
const NX: usize = 64;
const NY: usize = 16;
const SPACING: &str = "0.015625";

/// A text grid of NX × NY nodes of `f(i, j)`, written to `dir/name`.
fn write_map(dir: &Path, name: &str, f: impl Fn(usize, usize) -> f64) {
    let text: String = (0..NY)
        .map(|j| {
            let row: Vec<String> = (0..NX).map(|i| format!("{:.12e}", f(i, j))).collect();
            row.join(" ") + "\n"
        })
        .collect();
    std::fs::write(dir.join(name), text).unwrap();
}

/// A wave of one wavelength along x (λ = 1, amplitude 0.02), uniform along y: periodic.
fn wave(i: usize, _j: usize) -> f64 {
    0.02 * (1.0 - (2.0 * PI * (i as f64 + 0.5) / NX as f64).cos())
}

/// `simulate` of the map `name` with the periodic convolution, pressed on to 40 % of the
/// period, and `extra` flags.
fn run(dir: &Path, name: &str, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["--preload-area", "0.4"];
    args.extend_from_slice(extra);
    periodic(dir, name, SPACING, &args)
}

/// `simulate` on the CPU of the map `name` of node spacing `spacing` (E* = 1, Δγ = 1.7765e-4)
/// with the periodic convolution and `extra` flags.
fn periodic(dir: &Path, name: &str, spacing: &str, extra: &[&str]) -> std::process::Output {
    let mut args = vec![
        "simulate",
        "--indenter",
        "height-map",
        "--height-map",
        name,
        "--spacing",
        spacing,
        "--e-star",
        "1",
        "--work-of-adhesion",
        "1.7765e-4",
        "--convolution",
        "periodic",
        "--backend",
        "cpu",
    ];
    args.extend_from_slice(extra);
    jkrbem(&args, dir)
}

/// The run was refused before any work (exit 2) naming `flag` and saying each of `words`.
fn refused(o: &std::process::Output, flag: &str, words: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(flag), "{flag} not named: {err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not said: {err}");
    }
}

#[test]
fn a_periodic_map_runs_on_its_period() {
    let dir = tempfile::tempdir().unwrap();
    write_map(dir.path(), "wave.txt", wave);
    let o = run(
        dir.path(),
        "wave.txt",
        &["--grid", "64", "--summary", "s.json"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    // The domain is the period: 64 × 16 elements of the map's spacing, not the hull's
    // 63/64 of it.
    assert_eq!(s["runs"][0]["nx"], 64, "{s}");
    assert_eq!(s["runs"][0]["ny"], 16, "{s}");
    // The same window given explicitly, or moved by half a period, runs too.
    for window in ["-0.5,0.5", "0,1"] {
        let o = run(
            dir.path(),
            "wave.txt",
            &["--grid", "64", "--window-x", window, "--steps", "20"],
        );
        assert!(o.status.success(), "{window}: {}", stderr(&o));
    }
}

#[test]
fn what_does_not_repeat_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_map(d, "wave.txt", wave);
    // A tilted map: its seam jumps by its whole rise.
    write_map(d, "tilt.txt", |i, j| {
        0.001 * i as f64 + 1e-4 * ((i + j) % 3) as f64
    });
    refused(
        &run(d, "tilt.txt", &["--grid", "64"]),
        "--height-map",
        &[
            "is not periodic along x",
            "one period",
            "--convolution padded",
        ],
    );
    // The nodes' hull is not the period.
    refused(
        &run(
            d,
            "wave.txt",
            &["--grid", "64", "--window-x", "-0.4921875,0.4921875"],
        ),
        "--window-x",
        &["is not a period of", "give a window 1 long, e.g. -0.5,0.5"],
    );
    // Rows that are not the period along y, a grid that leaves 4 rows, a turned mesh.
    refused(
        &run(d, "wave.txt", &["--grid", "64", "--grid-y", "32"]),
        "--grid-y",
        &["--grid-y = 32 is invalid: 16 under --convolution periodic"],
    );
    refused(
        &run(d, "wave.txt", &["--grid", "16"]),
        "--grid",
        &["leaves 4 elements along y"],
    );
    refused(
        &run(d, "wave.txt", &["--grid", "64", "--mesh-angle", "45"]),
        "--mesh-angle",
        &["does not repeat"],
    );
    assert!(!d.join("jkrbem-out").exists(), "nothing written");
}

/// A text grid of `nx` × `ny` nodes of `f(x, y)` at the nodes' positions in periods (0–1),
/// written to `dir/name`.
fn write_period(dir: &Path, name: &str, (nx, ny): (usize, usize), f: impl Fn(f64, f64) -> f64) {
    let text: String = (0..ny)
        .map(|j| {
            let row: Vec<String> = (0..nx)
                .map(|i| {
                    let (x, y) = ((i as f64 + 0.5) / nx as f64, (j as f64 + 0.5) / ny as f64);
                    format!("{:.12e}", f(x, y))
                })
                .collect();
            row.join(" ") + "\n"
        })
        .collect();
    std::fs::write(dir.join(name), text).unwrap();
}

#[test]
fn a_wave_whose_fronts_run_along_the_grid_is_withheld_and_an_egg_crate_is_not() {
    // Johnson's wave extruded along y (128 nodes a wavelength, 32 rows): its contact is a
    // strip whose two fronts run straight along y, which the criterion pins (1.82 Δγ).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_period(d, "ridge.txt", (128, 32), |x, _| {
        0.02 * (1.0 - (2.0 * PI * x).cos())
    });
    let mut args = ["--grid", "128", "--summary", "r.json", "--out", "r.csv"];
    let o = periodic(
        d,
        "ridge.txt",
        "0.0078125",
        &[&["--preload-area", "0.4"][..], &args].concat(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("r.json")).unwrap()).unwrap();
    let run = &s["runs"][0];
    assert_eq!(run["straight_front_share"], 1.0, "{run}");
    assert!(s["f_ad_bar"].is_null() && run["f_ad_bar"].is_null());
    let why = run["withheld"].as_str().unwrap();
    assert!(
        why.contains("runs straight along the grid") && why.contains("1.82 Δγ"),
        "{why}"
    );
    let text = crate::common::stdout(&o);
    assert!(text.contains("NO ADHESIVE FORCE"), "{text}");
    // A valley has no apex: its results are in the user's units, not normalised by a fitted
    // "apex" of radii 16220.6 and 1.27 (a round-off radius along the ridge).
    let scene = &s["provenance"]["scene"];
    assert!(scene["fitted_radii"].is_null(), "{scene}");
    assert!(
        scene["normalisation"]["by"]
            .as_str()
            .unwrap()
            .starts_with("none"),
        "{scene}"
    );

    // An egg crate (a wave along both axes): each period's contact is a rounded patch.
    write_period(d, "egg.txt", (128, 128), |x, y| {
        0.01 * (2.0 - (2.0 * PI * x).cos() - (2.0 * PI * y).cos())
    });
    args[3] = "e.json";
    args[5] = "e.csv";
    let o = periodic(d, "egg.txt", "0.0078125", &args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("e.json")).unwrap()).unwrap();
    let run = &s["runs"][0];
    assert!(run["straight_front_share"].as_f64().unwrap() < 0.5, "{run}");
    assert!(run.get("withheld").is_none(), "{run}");
    assert!(run["f_ad_bar"].as_f64().unwrap() > 0.0, "{run}");
}

#[test]
fn a_period_pressed_towards_full_contact_fails_naming_the_cause() {
    // An egg crate 0.04 deep pressed 0.05 in (or to 97 % of its period): the contact nears the
    // whole period, where a periodic press has no finite answer. CG failed there with "CG
    // diverged" and advice about the preconditioner and the steps.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    write_period(d, "egg.txt", (64, 64), |x, y| {
        0.01 * (2.0 - (2.0 * PI * x).cos() - (2.0 * PI * y).cos())
    });
    for preload in [["--preload-depth", "0.05"], ["--preload-area", "0.97"]] {
        let mut args = vec!["--grid", "64", "--out", "x.csv"];
        args.extend(preload);
        let o = periodic(d, "egg.txt", "0.015625", &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{preload:?}: {err}");
        assert!(
            err.contains("neared the whole period") && err.contains("--preload-depth"),
            "{preload:?}: {err}"
        );
    }
}
