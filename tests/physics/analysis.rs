//! The study's analysis on real pull-offs: fits of the simulated adhesive branch against JKR
//! (physics §8.4), and the quarter contour of an ellipsoid's adhesive contact beside the ellipse
//! with the same half-axes (physics §8.3).

use crate::common;

use jkrbem::analysis::study_fits::{limit_fits, RatioRun};
use jkrbem::analysis::{self, branch::columns, contour};
use jkrbem::model::ModelOptions;
use jkrbem::solver::Phase;
use std::f64::consts::SQRT_2;

#[test]
fn sphere_branch_fits_give_the_jkr_coefficients_within_the_mesh_error() {
    let run = common::run_ratio(
        1.0,
        ModelOptions {
            nx: 128,
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let branch = analysis::adhesive_branch(&run.outcome.states);
    let (c, d, f) = columns(&branch);
    let c_min = c.iter().cloned().fold(f64::INFINITY, f64::min);
    println!(
        "{} branch points, c̄ from {c_min:.3} to {:.3}",
        branch.len(),
        c[0]
    );
    // The branch runs from the initial contact to below the JKR force minimum (c̄ = 0.79).
    assert!(branch.len() > 100 && c_min < 0.5 && c[0] > 1.4);
    let fd = analysis::fit_d_of_c(&c, &d).unwrap();
    let ff = analysis::fit_f_of_c(&c, &f).unwrap();
    println!("128² sphere:\n{fd:?}\n{ff:?}");
    // At 128² (about 40 elements across the contact at the force minimum) the branch is off
    // JKR by a few per cent (physics §7); the coefficients must be too, no more.
    let rel = |got: f64, want: f64| (got / want - 1.0).abs();
    assert!(rel(fd.a, 1.0) < 0.02, "A = {}", fd.a);
    assert!(rel(fd.b, -2.0 / 3.0 * SQRT_2) < 0.05, "B = {}", fd.b);
    assert!(rel(ff.c1, 1.0) < 0.03, "c1 = {}", ff.c1);
    assert!(rel(ff.c2, -SQRT_2) < 0.03, "c2 = {}", ff.c2);
    assert!(rel(ff.alpha, 1.5) < 0.03, "α = {}", ff.alpha);
    assert!(fd.quality.r_squared > 0.999 && ff.quality.r_squared > 0.999);
}

#[test]
fn sphere_branch_laws_at_the_limit_hold_the_jkr_coefficients() {
    // The branch of 32², 64² and 128² extrapolated to Δx → 0: every JKR coefficient lies in
    // its stated interval, and the intervals are narrower than one grid's error.
    let runs: Vec<RatioRun> = [32, 64, 128]
        .into_iter()
        .map(|nx| {
            let run = common::run_ratio(
                1.0,
                ModelOptions {
                    nx,
                    ..Default::default()
                },
            );
            assert!(run.outcome.complete(), "{:?}", run.outcome.error);
            RatioRun {
                ratio: 1.0,
                grid: (nx, nx),
                states: run.outcome.states,
            }
        })
        .collect();
    let (fits, laws) = limit_fits(1.0, &runs).expect("the branches overlap");
    println!("{laws:#?}");
    for (name, e, jkr) in [
        ("A", laws.a, 1.0),
        ("B", laws.b, -2.0 / 3.0 * SQRT_2),
        ("c1", laws.c1, 1.0),
        ("c2", laws.c2, -SQRT_2),
        ("α", laws.alpha, 1.5),
    ] {
        assert!(e.contains(jkr), "{name} = {e:?}, JKR {jkr}");
    }
    assert!(
        laws.a.uncertainty < 0.02 && laws.b.uncertainty < 0.03,
        "{laws:?}"
    );
    assert!(laws.alpha.uncertainty < 0.1, "{laws:?}");
    assert_eq!(fits.grids, [32, 64, 128]);
    assert!(fits.uncertainty.is_some());
}

#[test]
fn ellipsoid_adhesive_contact_is_close_to_an_ellipse() {
    // 5:1, stopped near the force minimum so the final contact is the adhesive one.
    let run = common::run_ratio(
        5.0,
        ModelOptions {
            nx: 128,
            final_d_bar: Some(-0.2),
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let last = run
        .outcome
        .states
        .iter()
        .rev()
        .find(|s| s.phase == Phase::Pulloff)
        .unwrap();
    let pts = contour::quarter_contour_for(&run.model, &run.final_mask).unwrap();
    let dep = analysis::ellipse_departure(&pts, last.a_axis, last.b_axis).unwrap();
    let b_elements = last.b_axis / run.model.dx;
    println!(
        "5:1 at d̄ = {:.3}: a = {:.1}, b = {b_elements:.1} elements, {} points, {dep:?}",
        last.d_bar,
        last.a_axis / run.model.dx,
        pts.len()
    );
    // The boundary passes through the ends of the axes by construction; in between it stays
    // within a few elements of the ellipse (JG's assumption holds to a few per cent).
    assert!(pts.len() as f64 > b_elements);
    assert!(dep.rms < 0.05 && dep.max < 0.1, "{dep:?}");
}

#[test]
fn the_pinned_transient_after_the_press_is_dropped_from_the_slender_branch() {
    // 25:1, where the transient is largest: after the press the ends of the major axis detach
    // while the minor axis holds, and F̄ there lies far above the propagating branch.
    let run = common::run_ratio(
        25.0,
        ModelOptions {
            nx: 256,
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let states = &run.outcome.states;
    let skip = analysis::branch::pinned_transient(states);
    let onsets: Vec<_> = states
        .iter()
        .filter(|s| s.phase == Phase::Onset && s.n_contact > 0)
        .collect();
    let dropped = onsets.len() - analysis::adhesive_branch(states).len();
    let first = &states[skip];
    println!(
        "25:1 at 256×{}: {dropped} of {} onsets dropped; the branch starts at c̄ = {:.3}, F̄ = {:.3}",
        run.model.ny,
        onsets.len(),
        first.c_bar,
        first.f_bar
    );
    // The minor axis held through the dropped onsets, and the major axis moved.
    assert!(dropped > 20, "{dropped}");
    let b0 = states[0].b_axis;
    for s in &states[..skip] {
        assert!(s.b_axis >= b0 * (1.0 - 1e-9) || s.a_axis >= states[0].a_axis);
    }
    // Fitted with the transient, F̄ = c1 c̄³ + c2 c̄^α is far off (RMS 0.12, c1 = 7.0, α = 2.67);
    // without it the branch is smooth (RMS 0.011).
    let (c, _, f) = columns(&analysis::adhesive_branch(states));
    let kept = analysis::fit_f_of_c(&c, &f).unwrap();
    let all_c: Vec<f64> = onsets.iter().map(|s| s.c_bar).collect();
    let all_f: Vec<f64> = onsets.iter().map(|s| s.f_bar).collect();
    let all = analysis::fit_f_of_c(&all_c, &all_f).unwrap();
    println!("kept: {kept:?}\nall: {all:?}");
    assert!(
        kept.quality.rms_residual < 0.02 && !kept.alpha_at_bound,
        "{kept:?}"
    );
    assert!(
        all.quality.rms_residual > 5.0 * kept.quality.rms_residual,
        "{all:?}"
    );
}

#[test]
fn the_sphere_s_branch_starts_once_the_front_has_moved_and_follows_jkr() {
    // For the sphere the front moves all round within a few onsets of the press, and every
    // kept onset lies on JKR's branch to within the mesh error (a few per cent at 128²).
    let run = common::run_ratio(
        1.0,
        ModelOptions {
            nx: 128,
            ..Default::default()
        },
    );
    let states = &run.outcome.states;
    let skip = analysis::branch::pinned_transient(states);
    let branch = analysis::adhesive_branch(states);
    let onsets = states
        .iter()
        .filter(|s| s.phase == Phase::Onset && s.n_contact > 0)
        .count();
    assert!(onsets - branch.len() < 20, "{} of {onsets}", branch.len());
    assert!(states[skip].c_bar > 1.45, "c̄ = {}", states[skip].c_bar);
    for p in &branch {
        let jkr = p.c_bar.powi(3) - SQRT_2 * p.c_bar.powf(1.5);
        assert!(
            (p.f_bar - jkr).abs() < 0.06,
            "c̄ = {}: {} vs JKR {jkr}",
            p.c_bar,
            p.f_bar
        );
    }
}
