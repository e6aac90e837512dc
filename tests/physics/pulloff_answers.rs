//! A pull-off that costs less gives the same answers (issue 22) on larger grids, a turned
//! mesh and with the loose cascade rounds alone, against today's exact protocol (every onset
//! located, every cascade round solved to the CG tolerance): the grid's |min F̄| within 1e-6
//! relative, and every step-end state within 1e-6. The fast checks are in `pulloff_cost.rs`.

use crate::common;

use common::run_model;
use common::same_answers::{assert_same_answers, compare, exact, model};
use jkrbem::model::{Measure, ModelOptions};

#[test]
fn sphere_curves_keep_every_state_and_the_minimum() {
    for nx in [64, 128] {
        compare(
            &format!("sphere {nx}²"),
            1.0,
            nx,
            None,
            ModelOptions::default(),
        );
    }
}

#[test]
#[ignore = "slow tier (about 3 minutes): cargo test --release -- --ignored"]
fn slow_an_ellipsoid_and_a_turned_mesh_keep_every_state_and_the_minimum() {
    compare("5:1 256×128", 5.0, 256, Some(128), ModelOptions::default());
    compare(
        "5:1 128×128 at 30°",
        5.0,
        128,
        Some(128),
        ModelOptions {
            mesh_angle_deg: 30.0,
            ..ModelOptions::default()
        },
    );
}

#[test]
fn slow_the_adhesive_force_alone_is_the_curves_minimum() {
    // 20 whole steps (the default of an adhesive-force run) against every onset of 200.
    let fast = run_model(model(
        5.0,
        256,
        Some(128),
        ModelOptions {
            measure: Measure::AdhesiveForce,
            steps: 20,
            ..ModelOptions::default()
        },
    ));
    let reference = run_model(model(5.0, 256, Some(128), exact(&ModelOptions::default())));
    assert!(fast.outcome.stopped_after_minimum && fast.outcome.min_reached());
    assert_same_answers("5:1 256×128, adhesive force", &fast, &reference);
    assert!(fast.outcome.cost.work.cg_iterations * 4 < reference.outcome.cost.work.cg_iterations);
}

#[test]
#[ignore = "slow tier (about 4 minutes): cargo test --release -- --ignored"]
fn larger_grids_keep_the_minimum() {
    // The reference locates every onset of 200 steps; its cascade rounds are solved loosely,
    // as the run checked, to keep the slow tier short: `slow_loose_rounds_give_the_exact_rounds_states`
    // checks that rule on its own.
    for (ratio, nx, ny) in [(5.0, 512, 256), (25.0, 512, 128)] {
        let options = ModelOptions {
            measure: Measure::AdhesiveForce,
            ..ModelOptions::default()
        };
        let fast = run_model(model(
            ratio,
            nx,
            Some(ny),
            ModelOptions {
                steps: 20,
                ..options.clone()
            },
        ));
        let reference = run_model(model(
            ratio,
            nx,
            Some(ny),
            ModelOptions {
                loose_rounds: true,
                ..exact(&options)
            },
        ));
        let what = format!("{ratio}:1 {nx}×{ny}, adhesive force");
        println!(
            "{what}: {} CG iterations against {}",
            fast.outcome.cost.work.cg_iterations, reference.outcome.cost.work.cg_iterations
        );
        assert_same_answers(&what, &fast, &reference);
    }
}

#[test]
#[ignore = "slow tier (about 2 minutes): cargo test --release -- --ignored"]
fn slow_loose_rounds_give_the_exact_rounds_states() {
    // The same onsets policy, every cascade round exact or only the last: the same states.
    for (ratio, nx, ny) in [(1.0, 128, None), (5.0, 256, Some(128))] {
        let options = ModelOptions::default();
        let loose = run_model(model(ratio, nx, ny, options.clone()));
        let tight = run_model(model(
            ratio,
            nx,
            ny,
            ModelOptions {
                loose_rounds: false,
                ..options
            },
        ));
        let what = format!("{ratio}:1 {nx}, loose rounds");
        assert_same_answers(&what, &loose, &tight);
        let (a, b) = (&loose.outcome.states, &tight.outcome.states);
        assert_eq!(a.len(), b.len(), "{what}: the same onsets are located");
        for (x, y) in a.iter().zip(b) {
            assert_eq!((x.phase, x.n_contact), (y.phase, y.n_contact), "{what}");
        }
        let (cl, ct) = (&loose.outcome.cost.work, &tight.outcome.cost.work);
        println!(
            "{what}: {} CG iterations, {} solves (every round exact: {}, {})",
            cl.cg_iterations, cl.solves, ct.cg_iterations, ct.solves
        );
        assert!(cl.cg_iterations < ct.cg_iterations, "{what}");
    }
}

/// The CPU's f32 mode (issue 46: its convolution's FFT passes in f32, CG's vectors and sums
/// in f64) on the 64² sphere's pull-off, through the request as `simulate` takes it: |min F̄|
/// within 2e-5 (relative) of f64's, the same number of states ±2, and the run and its
/// provenance say f32.
#[test]
fn the_f32_fft_passes_give_the_f64_pull_off() {
    use jkrbem::session::request::Request;
    use jkrbem::session::simulate::{simulate, Sink};
    let run = |precision: &str| {
        let request = Request::from_texts([
            ("ratio", "1"),
            ("grid", "64"),
            ("backend", "cpu"),
            ("precision", precision),
        ])
        .unwrap();
        let request = request.simulate_request(Sink::Memory, None).unwrap();
        simulate(&request, &jkrbem::session::Quiet).unwrap().summary
    };
    let (f64_run, f32_run) = (run("f64"), run("f32"));
    let (a, b) = (&f64_run.runs[0], &f32_run.runs[0]);
    assert_eq!((a.precision.as_str(), b.precision.as_str()), ("f64", "f32"));
    assert!(a.min_reached && b.min_reached && a.complete && b.complete);
    let backend = &f32_run.provenance.as_ref().unwrap().backend;
    assert_eq!(backend["precision"], "f32");
    assert_eq!(backend["runs"][0]["precision"], "f32");
    let (fa, fb) = (a.f_ad_bar.unwrap(), b.f_ad_bar.unwrap());
    println!(
        "64² sphere: |min F̄| f64 {fa:.9}, f32 {fb:.9} ({:.1e} relative); states {} and {}; \
         CG iterations {} and {}",
        (fb / fa - 1.0).abs(),
        a.states,
        b.states,
        a.cg_iterations,
        b.cg_iterations
    );
    assert!((fb / fa - 1.0).abs() < 2e-5, "{fa} vs {fb}");
    assert!(
        a.states.abs_diff(b.states) <= 2,
        "{} vs {}",
        a.states,
        b.states
    );
}
