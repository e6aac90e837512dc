//! Conjugate gradients that stagnate or diverge (issue 5, "Stability where methods fail").
//! Each failure is provoked on purpose. jkrbem must detect it from CG's residual history,
//! say so with the residual it reached, and retry in the safer mode (true residual
//! recomputed at least every 50 iterations). What it still returns must be marked: each
//! state's `cg_residual` and the outcome's warnings. If even the retry falls short, it stops
//! with an error that names the residual and what to change. Healthy runs are not flagged.
//!
//! The GPU's own failures (f32's floor) are in `failure_cg_gpu.rs`.

use crate::common;

use common::cg_failures::{assert_floor_detected_and_marked, cpu_run, short_run};
use common::{cpu_backend, model_for, pseudo_random};
// The tests that run the binary need the `cli` feature, which builds it.
#[cfg(feature = "cli")]
use common::{cg_failures::number_after, jkrbem, stderr};
use jkrbem::backend::prelude::*;
use jkrbem::backend::Preconditioner;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::solver::cg::CgEnd;
use jkrbem::solver::equilibrium::{solve_fixed, Fields};
use jkrbem::solver::retry::RetryVerdict;
use jkrbem::solver::SolverError;

#[test]
fn f64_asked_for_1e_19_detects_its_floor_the_same_way() {
    let tolerance = 1e-19;
    let model = short_run(64, tolerance);
    let o = cpu_run(&model, "CPU f64, tolerance 1e-19, 64²");
    assert_floor_detected_and_marked(&o, tolerance, (1e-17, 1e-14));
}

#[test]
fn a_healthy_sphere_run_is_not_flagged() {
    let model = model_for(
        1.0,
        ModelOptions {
            nx: 64,
            ..ModelOptions::default()
        },
    );
    let o = cpu_run(&model, "CPU f64, default tolerance, 64²");
    assert!(o.complete(), "{:?}", o.error);
    assert!(o.cg_retries.is_empty() && o.warnings.is_empty());
    let worst = o.worst_cg_residual().unwrap();
    assert!(worst <= model.cg.tolerance, "{worst:e}");
}

/// A 256² sphere model without preconditioner whose contact set is a random half of the
/// initial disk (a ragged set), with `max_iterations` per CG solve; returns the model, its
/// backend with that set, and the solver's fields at p = 0.
fn ragged_unpreconditioned(
    max_iterations: usize,
) -> (
    Model,
    jkrbem::backend::cpu::CpuBackend,
    Fields<Vec<f64>, Vec<bool>>,
) {
    let mut model = model_for(
        1.0,
        ModelOptions {
            nx: 256,
            preconditioner: Preconditioner::None,
            ..ModelOptions::default()
        },
    );
    model.cg.max_iterations = max_iterations;
    let mut backend = cpu_backend(&model);
    let n = model.nx * model.ny;
    let mask: Vec<bool> = model
        .initial_contact()
        .iter()
        .zip(pseudo_random(n, 3))
        .map(|(&m, r)| m && r > 0.0)
        .collect();
    let fields = Fields::new(&mut backend, mask).unwrap();
    (model, backend, fields)
}

#[test]
fn an_iteration_starved_solve_on_a_ragged_set_fails_naming_its_residual() {
    // Unpreconditioned CG needs 46 iterations on this set; it is given 10 (and 10 more for
    // the retry).
    let (model, mut backend, mut fields) = ragged_unpreconditioned(10);
    let err = solve_fixed(&mut backend, &model, &mut fields, model.load.d0).unwrap_err();
    // The message as the command line words it.
    let message = jkrbem::params::words::flags(&err.to_string());
    println!("{message}");
    let SolverError::CgNotConverged {
        first,
        end,
        residual,
        iterations,
        ..
    } = err
    else {
        panic!("expected CgNotConverged, got {err:?}");
    };
    assert_eq!((first, end), (CgEnd::IterationLimit, CgEnd::IterationLimit));
    assert_eq!(iterations, 20);
    assert!(residual > model.cg.accept && residual < 1.0, "{residual:e}");
    for needle in [
        format!("{residual:.2e}"),
        "20 iterations".into(),
        "--cg-max-iterations".into(),
        "--cg-tolerance 1.0e-8".into(),
        "--cg-accept 1.0e-5".into(),
    ] {
        assert!(message.contains(&needle), "lacks {needle}: {message}");
    }
}

#[test]
fn a_retry_that_converges_lets_the_run_go_on_and_is_counted() {
    // Given 30 of the 46 iterations it needs, the normal mode stops at its limit; the safer
    // retry goes on from there and reaches the tolerance.
    let (model, mut backend, mut fields) = ragged_unpreconditioned(30);
    let solve = solve_fixed(&mut backend, &model, &mut fields, model.load.d0).unwrap();
    println!("{solve:?}");
    let retry = solve.retry.expect("a retry");
    assert_eq!(retry.first.end, CgEnd::IterationLimit);
    assert_eq!(retry.first.iterations, 30);
    assert_eq!(retry.verdict, RetryVerdict::Converged);
    assert_eq!(solve.iterations, 30 + retry.retry.iterations);
    assert!(solve.residual <= model.cg.tolerance);
}

#[test]
fn a_non_finite_warm_start_is_caught_and_the_retry_starts_from_zero() {
    let (model, mut backend, mut fields) = ragged_unpreconditioned(5000);
    let n = model.nx * model.ny;
    let mut p = vec![0.0; n];
    p[n / 2 + model.nx / 2] = f64::NAN;
    backend.upload(&mut fields.p, &p).unwrap();
    let solve = solve_fixed(&mut backend, &model, &mut fields, model.load.d0).unwrap();
    println!("{solve:?}");
    let retry = solve.retry.expect("a retry");
    assert_eq!(retry.first.end, CgEnd::NonFinite);
    assert_eq!(retry.first.iterations, 0);
    assert_eq!(retry.verdict, RetryVerdict::Converged);
    backend.download(&fields.p, &mut p).unwrap();
    assert!(p.iter().all(|v| v.is_finite()));
}

#[cfg(feature = "cli")]
#[test]
fn cli_stops_with_the_residual_reached_when_even_the_retry_falls_short() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "64",
            "--backend",
            "cpu",
            "--preconditioner",
            "none",
            "--cg-max-iterations",
            "3",
            "--out",
            "s.csv",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    println!("{err}");
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("did not converge"), "{err}");
    let reached = number_after(&err, "best relative residual reached was");
    assert!(reached > 1e-5 && reached < 1.0, "{reached:e}");
    assert!(err.contains("--cg-max-iterations"), "{err}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(s["complete"], false);
    assert!(s["runs"][0]["error"]
        .as_str()
        .unwrap()
        .contains("did not converge"));
}

#[cfg(feature = "cli")]
#[test]
fn cli_warns_and_marks_a_run_accepted_above_its_tolerance() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--backend",
            "cpu",
            "--cg-tolerance",
            "1e-19",
            "--steps",
            "10",
            "--final-d",
            "1.5",
            "--out",
            "s.csv",
            "--summary",
            "s.json",
        ],
        dir.path(),
    );
    let err = stderr(&o);
    println!("{err}");
    assert!(o.status.success(), "{err}");
    assert!(err.contains("jkrbem: warning:"), "{err}");
    assert!(
        err.contains("precision floor") && err.contains("cg_residual"),
        "{err}"
    );
    let reached = number_after(&err, "at relative residual");
    assert!(reached > 1e-19 && reached < 1e-14, "{reached:e}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(s["complete"], true);
    assert!(s["runs"][0]["cg_retries"].as_u64().unwrap() > 0, "{s}");
    assert!(!s["warnings"].as_array().unwrap().is_empty(), "{s}");
    let worst = s["runs"][0]["cg_residual_max"].as_f64().unwrap();
    assert!(worst > 1e-19 && worst < 1e-14, "{worst:e}");
    let states = jkrbem::output::data::read_states(&dir.path().join("s.csv"))
        .unwrap()
        .states;
    assert!(states.iter().all(|s| s.cg_residual > 1e-19));
}
