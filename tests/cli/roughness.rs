//! `jkrbem roughness`: it writes the surface (.npy) and its sidecar (.json) with the asked rms
//! met exactly, the same seed gives the same bytes, and bad input is refused (exit 2) naming
//! its flag with nothing written.

use crate::common::{jkrbem, stderr, stdout};
use jkrbem::scene::height_map::HeightMap;
use jkrbem::scene::roughness::{self, RoughnessParams, GENERATOR_VERSION};

/// A 64 × 48 surface at spacing 0.5 with H = 0.8 and rms height 0.2.
const SURFACE: &[&str] = &[
    "roughness",
    "--grid",
    "64",
    "--grid-y",
    "48",
    "--spacing",
    "0.5",
    "--hurst",
    "0.8",
    "--rms-height",
    "0.2",
];

/// Run `jkrbem roughness` with SURFACE, `--out out`, and `more`.
fn run(dir: &std::path::Path, out: &str, more: &[&str]) -> std::process::Output {
    let mut args = SURFACE.to_vec();
    args.extend(["--out", out]);
    args.extend_from_slice(more);
    jkrbem(&args, dir)
}

#[test]
fn it_writes_the_surface_and_its_sidecar_with_the_asked_rms() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(dir.path(), "s/surface.npy", &["--seed", "17"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(text.contains("rms height    0.2 (length)"), "{text}");
    assert!(
        text.contains("cut-off 2 "),
        "the default cut-off is 4 spacings: {text}"
    );
    let map = HeightMap::read(&dir.path().join("s/surface.npy"), 0.5).unwrap();
    assert_eq!((map.nx(), map.ny()), (64, 48));
    let rms = roughness::rms_height(&map);
    assert!(((rms - 0.2) / 0.2).abs() < 1e-9, "{rms}");
    // The same surface as the library makes from the same parameters, to the bit.
    let params = RoughnessParams {
        grid_y: Some(48),
        seed: 17,
        ..RoughnessParams::with_rms_height(64, 0.5, 0.8, 0.2)
    };
    assert_eq!(roughness::generate(&params).unwrap(), map);
    let meta: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s/surface.json")).unwrap())
            .unwrap();
    assert_eq!(meta["generator"], GENERATOR_VERSION);
    assert_eq!(meta["params"]["seed"], 17);
    assert_eq!(meta["params"]["cutoff"], 2.0);
    assert_eq!(meta["params"]["largest_wavelength"], 32.0);
    assert_eq!(meta["params"]["rms_slope"], serde_json::Value::Null);
    let achieved = meta["statistics"]["rms_height"].as_f64().unwrap();
    assert!(((achieved - 0.2) / 0.2).abs() < 1e-9);
    // The slope asked for instead.
    let o = jkrbem(
        &[
            "roughness",
            "--out",
            "slope.npy",
            "--grid",
            "32",
            "--spacing",
            "1",
            "--hurst",
            "0.5",
            "--rms-slope",
            "0.1",
            "--rolloff",
            "16",
            "--cutoff",
            "4",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let map = HeightMap::read(&dir.path().join("slope.npy"), 1.0).unwrap();
    let slope = roughness::rms_slope(&map);
    assert!(((slope - 0.1) / 0.1).abs() < 1e-9, "{slope}");
}

#[test]
fn the_same_seed_gives_the_same_bytes_and_another_seed_others() {
    let dir = tempfile::tempdir().unwrap();
    for (out, seed) in [("a.npy", "5"), ("b.npy", "5"), ("c.npy", "6")] {
        let o = run(dir.path(), out, &["--seed", seed]);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("a.npy"), read("b.npy"));
    assert_ne!(read("a.npy"), read("c.npy"));
}

#[test]
fn bad_input_is_refused_naming_its_flag_and_nothing_is_written() {
    let cases: &[(&[&str], &str)] = &[
        (&["--hurst", "1.5"], "--hurst"),
        (&["--hurst", "0"], "--hurst"),
        (&["--hurst", "NaN"], "--hurst"),
        (&["--hurst", "-0.5"], "--hurst"),
        (&["--rms-slope", "0.1"], "--rms-slope"),
        (&["--cutoff", "0.9"], "--cutoff"),
        (&["--cutoff", "40"], "--cutoff"),
        (&["--rolloff", "40"], "--rolloff"),
        (&["--largest-wavelength", "33"], "--largest-wavelength"),
        (&["--grid-y", "2"], "--grid-y"),
        (&["--grid-y", "abc"], "--grid-y"),
        (&["--seed", "-1"], "--seed"),
        (&["--spacing", "0"], "--spacing"),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (more, flag) in cases {
        let o = run(dir.path(), "bad.npy", more);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{more:?}: {err}");
        assert!(err.contains(flag), "{more:?} should name {flag}: {err}");
        assert!(err.len() < 600, "{err}");
    }
    // Neither rms height nor slope.
    let o = jkrbem(
        &[
            "roughness",
            "--out",
            "bad.npy",
            "--grid",
            "32",
            "--spacing",
            "1",
            "--hurst",
            "0.5",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("--rms-height or --rms-slope is required"),
        "{}",
        stderr(&o)
    );
    // The sidecar cannot be the surface itself, nor the surface standard output.
    for out in ["bad.json", "-"] {
        let o = run(dir.path(), out, &[]);
        assert_eq!(o.status.code(), Some(2), "{out}: {}", stderr(&o));
        assert!(stderr(&o).contains("--out"), "{}", stderr(&o));
    }
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn help_states_the_units_and_defaults() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(&["roughness", "--help"], dir.path());
    let text = stdout(&o);
    for word in [
        "--hurst",
        "--rms-height",
        "--rms-slope",
        "--rolloff",
        "--cutoff",
        "--largest-wavelength",
        "--seed",
        "length",
        "4 × --spacing",
        "(0, 1]",
    ] {
        assert!(text.contains(word), "{word} missing from:\n{text}");
    }
}

/// `roughness` checks, before any work, that the surface fits in the memory the machine can
/// give it, honouring `JKRBEM_MEMORY_LIMIT` as `simulate` does (issue 55, item 21): a
/// 4096² surface (about 0.55 GB at 32 bytes per node) is refused under a 100 MB limit, naming
/// the flags that set its size and the largest that fits, with nothing written; a 64² one
/// passes under the same limit. Before, it generated the big one (exit 0) and never read
/// the variable.
#[test]
fn a_surface_past_the_memory_is_refused_before_any_work() {
    use crate::common::run_in;
    let dir = tempfile::tempdir().unwrap();
    let limit = [("JKRBEM_MEMORY_LIMIT", "1e8")];
    let big = |more: &[&str]| {
        let mut args = vec![
            "roughness",
            "--out",
            "big.npy",
            "--spacing",
            "1",
            "--hurst",
            "0.8",
            "--rms-height",
            "1",
        ];
        args.extend_from_slice(more);
        let start = std::time::Instant::now();
        let o = run_in(dir.path(), &args, &limit);
        (o, start.elapsed())
    };
    let (o, wall) = big(&["--grid", "4096"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains(
            "--grid = 4096 is invalid: a surface of --grid × --grid-y = 4096 × 4096 nodes"
        ) && err.contains("more than the 100 MB this machine has available")
            && err.contains("the largest that fits is --grid 1612"),
        "{err}"
    );
    // Refused at once: generating it takes seconds.
    assert!(wall.as_secs_f64() < 2.0, "{wall:?}");
    // With --grid-y, both flags in the advice.
    let (o, _) = big(&["--grid", "4096", "--grid-y", "1024"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("the largest of this shape that fits is --grid 3225 --grid-y 806"),
        "{err}"
    );
    // A limit that is no number of bytes is refused, naming the variable.
    let o = run_in(
        dir.path(),
        &[
            "roughness",
            "--out",
            "big.npy",
            "--grid",
            "64",
            "--spacing",
            "1",
            "--hurst",
            "0.8",
            "--rms-height",
            "1",
        ],
        &[("JKRBEM_MEMORY_LIMIT", "lots")],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("JKRBEM_MEMORY_LIMIT"), "{}", stderr(&o));
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "{left:?}");
    // A small surface fits under the same limit.
    let (o, _) = big(&["--grid", "64"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(dir.path().join("big.npy").exists());
}

/// `roughness --help` states the total node cap and the memory check with --grid.
#[test]
fn help_states_the_total_node_cap_and_the_memory_check() {
    let dir = tempfile::tempdir().unwrap();
    let text = stdout(&jkrbem(&["roughness", "--help"], dir.path()));
    for word in [
        "67108864 nodes in all",
        "32 bytes per node",
        "JKRBEM_MEMORY_LIMIT",
    ] {
        assert!(text.contains(word), "{word} missing from:\n{text}");
    }
}
