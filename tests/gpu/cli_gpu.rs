//! The command line's backend choice: `devices` lists adapters, `--backend gpu` runs on the
//! best adapter (saying when it is a software one), `--backend auto` says what it took, and
//! bad backend settings are refused before any work.

use crate::common;

use common::jkrbem;

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Whether wgpu sees an adapter; prints the skip reason when it does not (and fails when
/// `JKRBEM_REQUIRE_GPU=1`).
fn have_gpu() -> bool {
    jkrbem::backend::gpu::test_context().is_some()
}

fn devices_lists_adapters_with_their_limits() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(&["devices"], dir.path());
    assert!(o.status.success(), "{}", text(&o.stderr));
    let out = text(&o.stdout);
    println!("{out}");
    if have_gpu() {
        assert!(out.contains("GPU adapters, best first"), "{out}");
        assert!(
            out.contains("storage binding") && out.contains("grids up to"),
            "{out}"
        );
    } else {
        assert!(out.contains("no GPU adapter"), "{out}");
    }
}

fn gpu_backend_runs_a_pulloff_from_the_command_line() {
    if !have_gpu() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--steps",
            "30",
            "--backend",
            "gpu",
            "--out",
            "g.csv",
            "--summary",
            "g.json",
        ],
        dir.path(),
    );
    let (out, err) = (text(&o.stdout), text(&o.stderr));
    assert!(o.status.success(), "{err}");
    assert!(err.contains("gpu (f32, wgpu) on"), "{err}");
    assert!(out.contains("gpu backend (f32)"), "{out}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("g.json")).unwrap()).unwrap();
    assert_eq!(summary["runs"][0]["backend"], "gpu");
    assert_eq!(summary["runs"][0]["precision"], "f32");
    assert_eq!(summary["complete"], true);
    assert!(dir.path().join("g.csv").exists());
}

fn auto_says_which_backend_it_took() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate", "--ratio", "1", "--grid", "32", "--steps", "20", "--out", "a.csv",
        ],
        dir.path(),
    );
    let err = text(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.contains("(auto:"), "auto must say why it chose: {err}");
}

fn a_zero_readback_interval_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &["simulate", "--cg-check-every", "0", "--out", "out/x.csv"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("--cg-check-every"));
    assert!(!dir.path().join("out").exists());
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "cli_gpu",
        &[
            (
                "devices_lists_adapters_with_their_limits",
                devices_lists_adapters_with_their_limits,
            ),
            (
                "gpu_backend_runs_a_pulloff_from_the_command_line",
                gpu_backend_runs_a_pulloff_from_the_command_line,
            ),
            (
                "auto_says_which_backend_it_took",
                auto_says_which_backend_it_took,
            ),
            (
                "a_zero_readback_interval_is_refused",
                a_zero_readback_interval_is_refused,
            ),
        ],
        &[],
        &[],
        missing,
    )
}
