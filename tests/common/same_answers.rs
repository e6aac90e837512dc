//! The checks that a cheaper pull-off gives the exact protocol's answers (issue 22), shared by
//! `physics/pulloff_cost.rs` (fast) and `physics/pulloff_answers.rs`.

use super::{run_model, Run};
use jkrbem::model::{Measure, Model, ModelOptions, Onsets};
use jkrbem::scene::Scene;
use jkrbem::solver::{Phase, State};

/// The model of R1/R2 = `ratio` on `nx` × `ny` (None: fitted) with `options` on top.
pub fn model(ratio: f64, nx: usize, ny: Option<usize>, options: ModelOptions) -> Model {
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).unwrap();
    Model::build(&scene, &ModelOptions { nx, ny, ..options }).unwrap()
}

/// Today's exact protocol for `options`: every onset, every round exact.
pub fn exact(options: &ModelOptions) -> ModelOptions {
    ModelOptions {
        onsets: Onsets::All,
        loose_rounds: false,
        ..options.clone()
    }
}

pub fn f_min(run: &Run) -> f64 {
    run.outcome.force_minimum().expect("a force minimum").f_bar
}

pub fn step_ends(run: &Run) -> Vec<&State> {
    run.outcome
        .states
        .iter()
        .filter(|s| s.phase == Phase::Pulloff)
        .collect()
}

/// `fast` has the exact protocol's |min F̄| within 1e-6 and, for curves, its step-end states:
/// the same contact sets and forces within 1e-6 of the curve's scale.
pub fn assert_same_answers(what: &str, fast: &Run, reference: &Run) {
    assert!(fast.outcome.complete(), "{what}: {:?}", fast.outcome.error);
    assert!(
        reference.outcome.complete(),
        "{what}: {:?}",
        reference.outcome.error
    );
    let (a, b) = (f_min(fast), f_min(reference));
    assert!(
        (a / b - 1.0).abs() <= 1e-6,
        "{what}: |min F̄| {a} against the exact protocol's {b}"
    );
    if fast.model.measure == Measure::Curve {
        let (sa, sb) = (step_ends(fast), step_ends(reference));
        assert_eq!(sa.len(), sb.len(), "{what}: step count");
        for (x, y) in sa.iter().zip(&sb) {
            assert_eq!(x.d, y.d, "{what}: step {}", x.step);
            assert_eq!(
                x.n_contact, y.n_contact,
                "{what}: contact set at step {}",
                x.step
            );
            let scale = y.f_bar.abs().max(b.abs());
            assert!(
                (x.f_bar - y.f_bar).abs() <= 1e-6 * scale,
                "{what}: F̄ at step {}: {} against {}",
                x.step,
                x.f_bar,
                y.f_bar
            );
        }
    }
}

/// The cost account adds up: the bands sum to the totals, the states are those recorded, an
/// onset state costs no solve of its own, and no more solves are made than probes (one per
/// step and per onset located), cascade rounds and the first press's.
pub fn assert_account_adds_up(what: &str, run: &Run) {
    let c = &run.outcome.cost;
    assert_eq!(c.states, run.outcome.states.len(), "{what}");
    let sum =
        |f: fn(&jkrbem::solver::cost::BandCost) -> usize| c.bands.iter().map(f).sum::<usize>();
    assert_eq!(
        sum(|b| b.work.cg_iterations),
        c.work.cg_iterations,
        "{what}"
    );
    assert_eq!(sum(|b| b.work.solves), c.work.solves, "{what}");
    assert_eq!(sum(|b| b.work.rounds), c.work.rounds, "{what}");
    assert_eq!(sum(|b| b.steps), c.steps, "{what}");
    assert_eq!(sum(|b| b.onsets), c.onsets, "{what}");
    // Every iteration is charged to a state: the states' column adds up to the run's.
    let recorded: usize = run.outcome.states.iter().map(|s| s.cg_iterations).sum();
    assert_eq!(recorded, c.work.cg_iterations, "{what}");
    for s in &run.outcome.states {
        if s.phase == Phase::Onset {
            assert_eq!(s.cg_iterations, 0, "{what}: an onset is an interpolation");
        }
    }
    assert!(c.work.solves > 0 && c.steps > 0, "{what}");
    // The split by activity on either side of the force minimum adds up to the whole too.
    let (to, past) = (&c.to_minimum, &c.past_minimum);
    let split = |f: fn(&jkrbem::solver::cost::Work) -> usize| {
        f(&to.whole_steps) + f(&to.search) + f(&past.whole_steps) + f(&past.search)
    };
    assert_eq!(split(|w| w.cg_iterations), c.work.cg_iterations, "{what}");
    assert_eq!(split(|w| w.solves), c.work.solves, "{what}");
    assert_eq!(split(|w| w.rounds), c.work.rounds, "{what}");
}

pub fn compare(what: &str, ratio: f64, nx: usize, ny: Option<usize>, options: ModelOptions) {
    let fast = run_model(model(ratio, nx, ny, options.clone()));
    let reference = run_model(model(ratio, nx, ny, exact(&options)));
    let (cf, cr) = (&fast.outcome.cost, &reference.outcome.cost);
    println!(
        "{what}: |min F̄| {:.10} ({} CG iterations, {} solves, {} states) against the exact \
         protocol's {:.10} ({} CG iterations, {} solves, {} states)",
        -f_min(&fast),
        cf.work.cg_iterations,
        cf.work.solves,
        cf.states,
        -f_min(&reference),
        cr.work.cg_iterations,
        cr.work.solves,
        cr.states
    );
    assert_same_answers(what, &fast, &reference);
    assert_account_adds_up(what, &fast);
    assert_account_adds_up(what, &reference);
    assert!(
        cf.work.cg_iterations < cr.work.cg_iterations,
        "{what}: no cheaper than the exact protocol"
    );
    // The window's check: every step left whole has its bound at or above the minimum, and
    // no located onset fell below the bound of its part.
    let w = fast.outcome.refinement.as_ref().expect("a window report");
    assert!(w.margin_f_bar.is_some_and(|m| m >= 0.0), "{what}: {w:?}");
    assert_eq!(w.bound_violation_f_bar, 0.0, "{what}: {w:?}");
    assert!(!w.widened && !w.steps.is_empty(), "{what}: {w:?}");
    // A step gone back to is probed again only where its start was not kept: a kept start
    // keeps its step's probe.
    assert_eq!(w.probed_again, w.recomputed, "{what}: {w:?}");
    // The minimum is an onset of a searched step.
    let min = fast.outcome.force_minimum().unwrap();
    assert_eq!(min.phase, Phase::Onset, "{what}");
    assert!(w.steps.contains(&min.step), "{what}: {w:?}");
}
