//! The GPU's own CG limits (issues 5 and 22): asked for a tolerance below f32's floor, CG
//! stops at the floor (precision-aware stopping: no iterations, and no retries, spent on a
//! residual f32 cannot reach), the states carry their residual and the run says so; at the
//! default tolerance nothing is flagged; the command line says where it stopped.
//!
//! Reported as ignored, with the reason, where no GPU adapter exists; a failure instead with
//! `JKRBEM_REQUIRE_GPU=1`.

use crate::common;

use common::cg_failures::{cpu_run, gpu_run, short_run};
use common::model_for;
// The test that runs the binary needs the `cli` feature, which builds it.
#[cfg(feature = "cli")]
use common::{cg_failures::number_after, jkrbem, stderr};
use jkrbem::backend::gpu::F32_RESIDUAL_FLOOR;
use jkrbem::model::ModelOptions;
use jkrbem::solver::cg::TRUE_RESIDUAL_SLACK;

fn f32_asked_for_1e_11_stops_at_its_floor_and_says_so() {
    let tolerance = 1e-11;
    let mut model = short_run(64, tolerance);
    // As `jkrbem simulate --backend gpu` does: read the residual every 2 iterations.
    model.cg.check_every = 2;
    let Some(g) = gpu_run(&model, "GPU f32, tolerance 1e-11, 64²") else {
        return;
    };
    assert!(g.complete(), "{:?}", g.error);
    assert!(
        g.cg_retries.is_empty(),
        "the floor is known: nothing to retry"
    );
    for s in &g.states {
        assert!(
            s.cg_residual > tolerance && s.cg_residual < TRUE_RESIDUAL_SLACK * F32_RESIDUAL_FLOOR,
            "state not marked with its residual: {s:?}"
        );
    }
    let text = g.warnings.join("\n");
    assert!(
        text.contains("precision floor")
            && text.contains("cg_residual")
            && text.contains("1.0e-11"),
        "{text}"
    );
    // The marked states are still right to the f32 floor: f64 reaches 1e-11 without help.
    let c = cpu_run(&model, "CPU f64, tolerance 1e-11, 64²");
    assert!(c.complete() && c.cg_retries.is_empty() && c.warnings.is_empty());
    assert_eq!(g.states.len(), c.states.len());
    let dev = g
        .states
        .iter()
        .zip(&c.states)
        .map(|(a, b)| (a.f_bar - b.f_bar).abs())
        .fold(0.0, f64::max);
    println!("max |ΔF̄| GPU − CPU over the states: {dev:.2e}");
    assert!(dev < 1e-5, "{dev:e}");
}

fn f32_at_the_default_tolerance_is_not_flagged() {
    let mut model = model_for(
        1.0,
        ModelOptions {
            nx: 32,
            ..ModelOptions::default()
        },
    );
    model.cg.check_every = 2;
    let Some(g) = gpu_run(&model, "GPU f32, default tolerance, 32²") else {
        return;
    };
    assert!(g.complete(), "{:?}", g.error);
    assert!(g.cg_retries.is_empty() && g.warnings.is_empty());
    let worst = g.worst_cg_residual().unwrap();
    assert!(
        worst < TRUE_RESIDUAL_SLACK * model.cg.tolerance,
        "{worst:e}"
    );
}

#[cfg(feature = "cli")]
fn cli_gpu_asked_for_1e_11_says_it_stopped_at_the_f32_floor() {
    if jkrbem::backend::gpu::test_context().is_none() {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "64",
            "--backend",
            "gpu",
            "--cg-tolerance",
            "1e-11",
            "--steps",
            "10",
            "--final-d",
            "1.5",
            "--out",
            "g.csv",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    println!("{err}");
    assert!(o.status.success(), "{err}");
    assert!(err.contains("precision floor"), "{err}");
    let reached = number_after(&err, "at relative residual");
    assert!(reached > 1e-8 && reached < 1e-6, "{reached:e}");
    assert!(err.contains("--backend cpu"), "{err}");
}

/// This file's tests, for `tests/gpu/main.rs`; `missing`: why there is no GPU adapter.
pub fn trials(missing: Option<&str>) -> Vec<libtest_mimic::Trial> {
    #[cfg_attr(not(feature = "cli"), allow(unused_mut))]
    let mut tests: Vec<(&'static str, fn())> = vec![
        (
            "f32_asked_for_1e_11_stops_at_its_floor_and_says_so",
            f32_asked_for_1e_11_stops_at_its_floor_and_says_so,
        ),
        (
            "f32_at_the_default_tolerance_is_not_flagged",
            f32_at_the_default_tolerance_is_not_flagged,
        ),
    ];
    #[cfg(feature = "cli")]
    tests.push((
        "cli_gpu_asked_for_1e_11_says_it_stopped_at_the_f32_floor",
        cli_gpu_asked_for_1e_11_says_it_stopped_at_the_f32_floor,
    ));
    common::gpu_trials("failure_cg_gpu", &tests, &[], &[], missing)
}
