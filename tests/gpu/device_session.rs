//! The device session cannot rot: the slow tier packages this build as a device session would
//! (`benches/device-package.sh`, with the binaries already built: no cargo inside cargo test)
//! and dry-runs `benches/device-session.sh` on whatever adapter is here (lavapipe in CI) with
//! tiny settings. Every step must write its table, the GPU tests must run and pass, a run cut at
//! its limit must show its states, and the figures must come from each run's own files.

use crate::common;

use std::path::Path;
use std::process::Command;

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn slow_device_session_dry_run() {
    if jkrbem::backend::gpu::test_context().is_none() {
        return;
    }
    let tmp = tempfile::tempdir().unwrap();
    let pack = tmp.path().join("pack");
    let out = tmp.path().join("out");
    let me = std::env::current_exe().expect("the gpu test binary's path");

    let o = Command::new(repo().join("benches/device-package.sh"))
        .env("PACK", &pack)
        .env("FETCH_LOADERS", "0")
        .env("JKRBEM_EXE", env!("CARGO_BIN_EXE_jkrbem"))
        .env("GPU_TEST_EXE", &me)
        .output()
        .expect("device-package.sh runs");
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{text}{}", common::stderr(&o));
    for f in ["jkrbem", "tests/gpu", "built-at", "commit"] {
        assert!(pack.join(f).exists(), "the package lacks {f}: {text}");
    }
    assert!(text.contains("benches/device-session.sh"), "{text}");

    // Tiny settings: the measure and parity runs finish; the curve is cut at its limit (a
    // 128 grid takes minutes on a software adapter; on a GPU, 2048 does).
    let software = jkrbem::backend::gpu::list_adapters()
        .first()
        .is_none_or(|a| a.device_type == "Cpu");
    let curve_grid = if software { "128" } else { "2048" };
    let o = Command::new(repo().join("benches/device-session.sh"))
        .args([
            "devices", "measure", "bench", "floors", "parity", "tests", "accuracy", "curve",
        ])
        .env("JKRBEM_BIN_DIR", &pack)
        .env("OUT", &out)
        .env("SESSION_LIMIT_S", "900")
        .env("MEASURE_GRID", "32")
        .env("MEASURE_LIMIT_S", "200")
        .env("GRIDS", "16,32")
        .env("BENCH_REPEATS", "1")
        .env("PARITY_GRID", "32")
        .env("TESTS_FILTER", "gpu_fft::")
        .env("ACCURACY_RATIOS", "1")
        .env("ACCURACY_TARGET", "20%")
        .env("ACCURACY_LIMIT_S", "200")
        .env("CURVE_GRID", curve_grid)
        .env("CURVE_LIMIT_S", "25")
        .output()
        .expect("device-session.sh runs");
    assert!(o.status.success(), "{}", common::stderr(&o));
    let report = std::fs::read_to_string(out.join("report.md")).expect("report.md is written");
    println!("{report}");
    assert!(out.join("log.txt").exists() && out.join("results.tar.gz").exists());

    // The headline comes first, with the measure run's figures from its summary JSON.
    let headline = report.find("## Headline").expect("a headline");
    assert!(headline < report.find("## Adapters").unwrap(), "{report}");
    assert!(report.contains("**gpu-32-measure**"), "{report}");
    assert!(report.contains("Vulkan preflight: "), "{report}");
    assert!(!report.contains("commit: unknown"), "{report}");

    // Every step wrote its section and its table or lines.
    for section in [
        "## Adapters",
        "## 32 grid, R1/R2 = 5, adhesive force",
        "## Kernels and CG iterations",
        "## Floors",
        "## Parity",
        "## GPU tests",
        "## `--accuracy 20%`",
    ] {
        assert!(report.contains(section), "no {section}: {report}");
    }
    let curve_section = format!("## {curve_grid} grid, R1/R2 = 5, whole curve");
    assert!(report.contains(&curve_section), "{report}");
    assert!(!report.contains("skipped"), "{report}");
    let row = |label: &str| {
        report
            .lines()
            .find(|l| l.starts_with(&format!("| {label} |")))
            .unwrap_or_else(|| panic!("no row {label}: {report}"))
            .to_string()
    };
    let measure = row("gpu-32-measure");
    assert!(
        measure.contains("| complete |") && measure.contains("summary JSON"),
        "{measure}"
    );
    assert!(row("cpu-parity-32-measure").contains("summary JSON"));
    assert!(
        report.contains("- grid's own |min F̄| (`runs[0].f_ad_bar`): GPU (f32)"),
        "{report}"
    );
    assert!(
        report.contains("cpu f64") && report.contains("gpu f32"),
        "{report}"
    );

    // The GPU tests ran and passed.
    let tests = row("gpu");
    assert!(
        tests.contains("test result: ok") && !tests.contains(" 0 passed"),
        "{tests}"
    );

    // The accuracy run states an estimate beside the reference table's.
    assert!(
        report.contains("- R1/R2 = 1: complete") && report.contains("reference 0.49"),
        "{report}"
    );

    // The cut curve shows the states it had computed.
    let curve = row(&format!("gpu-{curve_grid}-curve"));
    assert!(
        curve.contains("cut at its limit") && curve.contains("partial states"),
        "{curve}"
    );
    let states: usize = curve.split('|').nth(6).unwrap().trim().parse().unwrap();
    assert!(states > 0, "{curve}");
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    common::gpu_trials(
        "device_session",
        &[("slow_device_session_dry_run", slow_device_session_dry_run)],
        &["slow_device_session_dry_run"],
        &[],
        missing,
    )
}
