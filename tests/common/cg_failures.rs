//! Helpers of the CG-failure tests (`backend/failure_cg.rs`, `gpu/failure_cg_gpu.rs`).

use super::model_for;
use jkrbem::model::{Model, ModelOptions};
#[cfg(feature = "gpu")]
use jkrbem::solver;
use jkrbem::solver::cg::CgEnd;
use jkrbem::solver::retry::RetryVerdict;
use jkrbem::solver::Outcome;
use std::time::Instant;

/// A short sphere pull-off on an `nx` grid at CG tolerance `tolerance`: the press to
/// d̄0 = 2.25 and two load steps, down to d̄ = 1.5.
pub fn short_run(nx: usize, tolerance: f64) -> Model {
    model_for(
        1.0,
        ModelOptions {
            nx,
            steps: 10,
            final_d_bar: Some(1.5),
            cg_tolerance: tolerance,
            ..ModelOptions::default()
        },
    )
}

/// Print what a run's CG retries were, one line per kind of first ending.
pub fn describe(label: &str, o: &Outcome, wall: f64) {
    let worst = o.worst_cg_residual().unwrap_or(f64::NAN);
    println!(
        "{label}: {} states, {} CG iterations, {} retries, worst cg_residual {worst:.2e}, \
         {wall:.2} s",
        o.states.len(),
        o.cg_iterations(),
        o.cg_retries.len()
    );
    for r in o.cg_retries.iter().take(3) {
        println!(
            "  d̄ = {:.5}: normal mode {:?} after {} iterations at {:.2e}; safer retry {:?} \
             after {} iterations at {:.2e} ({:?})",
            r.d_bar,
            r.first.end,
            r.first.iterations,
            r.first.residual,
            r.retry.end,
            r.retry.iterations,
            r.retry.residual,
            r.verdict
        );
    }
    for w in &o.warnings {
        println!("  warning: {w}");
    }
}

/// Run `model` on the GPU (None, test skipped, without an adapter) and describe it.
#[cfg(feature = "gpu")]
pub fn gpu_run(model: &Model, label: &str) -> Option<Outcome> {
    let mut gpu = super::gpu_backend(&model.grid_setup())?;
    let t0 = Instant::now();
    let o = solver::run(&mut gpu, model, &mut |_| {});
    describe(label, &o, t0.elapsed().as_secs_f64());
    Some(o)
}

/// Run `model` on the CPU and describe it.
pub fn cpu_run(model: &Model, label: &str) -> Outcome {
    let t0 = Instant::now();
    let o = super::run_model(model.clone()).outcome;
    describe(label, &o, t0.elapsed().as_secs_f64());
    o
}

/// Check a run asked for a tolerance below its arithmetic's floor: every solve's recurrence
/// reached the tolerance but its true residual did not (a residual gap, at about `floor`);
/// the safer retry stagnated there within a few windows and was accepted; every state is
/// marked with a residual above the tolerance and near the floor; the warnings say so.
pub fn assert_floor_detected_and_marked(o: &Outcome, tolerance: f64, floor: (f64, f64)) {
    assert!(o.complete(), "{:?}", o.error);
    assert!(!o.cg_retries.is_empty(), "no retry: the floor went unseen");
    for r in &o.cg_retries {
        assert_eq!(r.first.end, CgEnd::ResidualGap, "{r:?}");
        assert!(
            r.first.residual > floor.0 && r.first.residual < floor.1,
            "{r:?}"
        );
        assert_eq!(r.retry.end, CgEnd::Stagnated, "{r:?}");
        assert_eq!(r.verdict, RetryVerdict::Accepted, "{r:?}");
        assert!(r.retry.residual < floor.1, "{r:?}");
        // Stagnation is seen after about one 50-iteration window, not at the 5000 limit.
        assert!(r.retry.iterations <= 120, "{r:?}");
    }
    for s in &o.states {
        assert!(
            s.cg_residual > tolerance && s.cg_residual < floor.1,
            "state not marked: {s:?}"
        );
    }
    let text = o.warnings.join("\n");
    assert!(
        text.contains("precision floor") && text.contains("cg_residual"),
        "{text}"
    );
    assert!(text.contains(&format!("{tolerance:.1e}")), "{text}");
}

/// The number printed after `after` in `text`.
pub fn number_after(text: &str, after: &str) -> f64 {
    let rest = &text[text
        .find(after)
        .unwrap_or_else(|| panic!("no {after}: {text}"))
        + after.len()..];
    rest.split_whitespace()
        .next()
        .unwrap()
        .trim_end_matches([',', ';', '.'])
        .parse()
        .unwrap()
}
