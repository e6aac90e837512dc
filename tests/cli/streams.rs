//! What goes where: results on standard output, warnings and progress on standard error, `-`
//! as standard output where a flag names a file of results, and no display-server noise from
//! the GPU probe on a machine without a display.

use crate::common::{jkrbem, stderr, stdout, SHORT};
use std::process::{Command, Output};

fn run(extra: &[&str], dir: &std::path::Path) -> Output {
    let mut args = SHORT.to_vec();
    args.extend_from_slice(extra);
    jkrbem(&args, dir)
}

#[test]
fn a_simulate_warning_goes_to_stderr_and_the_answer_to_stdout() {
    // Before: "WARNING: too coarse a grid …" was printed on stdout, inside the answer.
    let dir = tempfile::tempdir().unwrap();
    let o = run(&["--out", "s.csv"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let (out, err) = (stdout(&o), stderr(&o));
    assert!(out.contains("adhesive force |min F̄|"), "{out}");
    assert!(out.contains("states written to s.csv"), "{out}");
    assert!(!out.contains("WARNING"), "{out}");
    assert!(err.contains("WARNING: too coarse a grid"), "{err}");
}

#[test]
fn a_sweep_warning_goes_to_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "sweep",
            "--ratios",
            "1",
            "--grid",
            "32",
            "--steps",
            "20",
            "--backend",
            "cpu",
            "--out",
            "sw",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let (out, err) = (stdout(&o), stderr(&o));
    assert!(out.contains("summary written to"), "{out}");
    assert!(!out.contains("WARNING"), "{out}");
    assert!(err.contains("WARNING: R1/R2 = 1"), "{err}");
}

#[test]
fn out_dash_sends_the_states_csv_to_stdout_and_the_rest_to_stderr() {
    // Before: `--out -` wrote a file named "-".
    let dir = tempfile::tempdir().unwrap();
    let file = run(&["--out", "s.csv"], dir.path());
    assert!(file.status.success(), "{}", stderr(&file));
    let o = run(&["--out", "-"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read(dir.path().join("s.csv")).unwrap();
    assert_eq!(o.stdout, csv, "the bytes the file holds");
    assert!(!dir.path().join("-").exists());
    let err = stderr(&o);
    assert!(err.contains("adhesive force |min F̄|"), "{err}");
    // Several grids cannot share the one stream; nor can fields be written beside it.
    for extra in [&["--extrapolate"][..], &["--fields", "minimum"]] {
        let mut args = vec!["simulate", "--ratio", "1", "--backend", "cpu", "--out", "-"];
        args.extend_from_slice(extra);
        let o = jkrbem(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(stderr(&o).contains("--out -"), "{}", stderr(&o));
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn summary_dash_sends_the_summary_json_to_stdout_and_its_text_to_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let o = run(&["--out", "s.csv", "--summary", "-"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value = serde_json::from_slice(&o.stdout).expect("stdout is the JSON");
    assert!(json["f_ad_bar"].as_f64().is_some(), "{json}");
    let err = stderr(&o);
    assert!(err.contains("adhesive force |min F̄|"), "{err}");
    assert!(err.contains("states written to s.csv"), "{err}");
    assert!(!dir.path().join("-").exists());
    // One stream, one file.
    let o = run(&["--out", "-", "--summary", "-"], dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("--out") && err.contains("--summary"), "{err}");
    assert!(o.stdout.is_empty());
}

#[test]
fn theory_out_dash_writes_the_curve_to_stdout_and_folders_refuse_it() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(&["theory", "--model", "jg", "--out", "-"], dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.starts_with("c_bar,f_bar,d_bar,a_bar,b_bar\n"), "{out}");
    assert_eq!(out.lines().count(), 401, "the header and 400 points");
    assert!(stderr(&o).contains("F̄ = -0.500000"), "{}", stderr(&o));
    for command in [
        "sweep",
        "crossed",
        "reproduce",
        "accuracy",
        "bench",
        "coverage",
    ] {
        let o = jkrbem(&[command, "--out", "-"], dir.path());
        assert_eq!(o.status.code(), Some(2), "{command}: {}", stderr(&o));
        assert!(stderr(&o).contains("--out -"), "{command}: {}", stderr(&o));
    }
    assert!(!dir.path().join("-").exists());
}

#[test]
fn a_headless_auto_run_prints_no_display_server_errors() {
    // Before: two "error: XDG_RUNTIME_DIR is invalid or not set in the environment." lines
    // from Mesa's device-select layer probing for a Wayland display.
    let dir = tempfile::tempdir().unwrap();
    let mut c = Command::new(env!("CARGO_BIN_EXE_jkrbem"));
    for var in [
        "XDG_RUNTIME_DIR",
        "WAYLAND_DISPLAY",
        "WAYLAND_SOCKET",
        "DISPLAY",
        "NODEVICE_SELECT",
        "MESA_VK_DEVICE_SELECT",
        "DRI_PRIME",
        "JKRBEM_MEMORY_LIMIT",
    ] {
        c.env_remove(var);
    }
    let o = c
        .args(["simulate", "--ratio", "1", "--grid", "32", "--steps", "20"])
        .args(["--backend", "auto", "--out", "s.csv"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(!err.contains("XDG_RUNTIME_DIR"), "{err}");
}
