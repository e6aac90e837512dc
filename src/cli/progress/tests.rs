//! Tests of the progress line: its text, its bar per grid and the pace of plain lines.

use super::*;
use jkrbem::model::ModelOptions;
use jkrbem::scene::Scene;
use jkrbem::solver::Phase;

#[test]
fn the_progress_line_shows_the_step_of_all_and_an_eta() {
    // Before: "state 57" (the load step, repeated by its onsets), no fraction, no ETA.
    let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
    let model = Model::build(
        &scene,
        &ModelOptions {
            nx: 32,
            steps: 200,
            ..ModelOptions::default()
        },
    )
    .unwrap();
    assert_eq!(model.expected_steps(), 200);
    let mut state = State {
        step: 57,
        phase: Phase::Onset,
        d: 0.1,
        force: -0.3,
        area: 1.0,
        mean_radius: 1.0,
        a_axis: 1.0,
        b_axis: 1.0,
        n_contact: 100,
        cg_iterations: 5,
        detach_sweeps: 1,
        d_bar: -0.00001,
        f_bar: -0.4321,
        c_bar: 0.9,
        a_bar: 0.9,
        b_bar: 0.9,
        cg_residual: 1e-9,
        dx: 0.1,
    };
    let mut count = StepCount::new(model.expected_steps());
    count.advance(state.step);
    let text = progress_message(&model, &state, false, &count);
    assert!(text.contains("step 57/200 (onset)"), "{text}");
    let held = progress_message(&model, &state, true, &count);
    assert!(
        held.contains("step 57/200 (onset, searching near the minimum)"),
        "{held}"
    );
    assert!(
        text.contains("d̄ = 0.0000") && text.contains("F̄ = -0.4321"),
        "{text}"
    );
    assert!(!text.contains("state"), "{text}");
    for part in ["{bar", "{percent", "{eta}"] {
        assert!(PROGRESS_TEMPLATE.contains(part), "{part}");
    }
    assert!(ProgressStyle::with_template(PROGRESS_TEMPLATE).is_ok());
    // Past the estimate the line no longer claims a total it has passed.
    state.step = 203;
    count.advance(state.step);
    let past = progress_message(&model, &state, false, &count);
    assert!(past.contains("step 203, past the 200 expected"), "{past}");
    assert!(!past.contains("203/200"), "{past}");
    // A final approach stops the bar's length early.
    let short = Model::build(
        &scene,
        &ModelOptions {
            nx: 32,
            steps: 200,
            final_d_bar: Some(0.0),
            ..ModelOptions::default()
        },
    )
    .unwrap();
    assert!(short.expected_steps() < 200);
}

#[test]
fn each_grid_starts_a_fresh_count() {
    // A new grid starts at step 0 with its own length, whatever the last grid reached.
    let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
    let options = |nx| ModelOptions {
        nx,
        steps: 100,
        ..ModelOptions::default()
    };
    let coarse = Model::build(&scene, &options(32)).unwrap();
    let fine = Model::build(&scene, &options(64)).unwrap();
    let watch = Progress::new();
    let at = |step| State {
        step,
        phase: Phase::Pulloff,
        ..State::default()
    };
    watch.pulloff_started(&coarse);
    for step in [10, 90, 120] {
        watch.state(&coarse, &at(step));
    }
    let counted = |w: &Progress| w.grid.lock().unwrap().as_ref().map(|g| g.count);
    let c = counted(&watch).unwrap();
    assert_eq!((c.position(), c.length()), (120, 120));
    watch.pulloff_started(&fine);
    let c = counted(&watch).unwrap();
    assert_eq!(
        (c.position(), c.length()),
        (0, fine.expected_steps() as u64)
    );
    watch.state(&fine, &at(3));
    assert_eq!(counted(&watch).unwrap().position(), 3);
    watch.pulloff_ended();
    assert!(counted(&watch).is_none());
}
