//! The adhesive pull-off of a sphere against JKR (physics §3, §7).

use crate::common;

use jkrbem::model::ModelOptions;
use jkrbem::solver::{Outcome, Phase};
use jkrbem::theory::jkr::jkr_point;

/// RMS and max of F̄ − F̄_JKR(c̄) and d̄ − d̄_JKR(c̄) over the shrinking branch
/// 0.8 ≤ c̄ ≤ 0.9·c̄0.
fn branch_deviation(outcome: &Outcome, c0: f64) -> ((f64, f64), (f64, f64)) {
    let (mut n, mut sf, mut sd, mut mf, mut md) = (0.0, 0.0, 0.0, 0.0f64, 0.0f64);
    for s in outcome.states.iter().filter(|s| s.phase != Phase::Approach) {
        if (0.8..=0.9 * c0).contains(&s.c_bar) {
            let t = jkr_point(s.c_bar);
            let (ef, ed) = (s.f_bar - t.f_bar, s.d_bar - t.d_bar);
            n += 1.0;
            sf += ef * ef;
            sd += ed * ed;
            mf = mf.max(ef.abs());
            md = md.max(ed.abs());
        }
    }
    assert!(n > 20.0, "too few states on the branch: {n}");
    (((sf / n).sqrt(), mf), ((sd / n).sqrt(), md))
}

/// Adhesive force within `bound` of 1/2, and the branch within `bound` (relative to the
/// JKR scales |F̄_min| = 1/2 and |d̄_end| = 0.437) in the RMS over the branch.
fn check_sphere(nx: usize, bound: f64) {
    let run = common::run_ratio(
        1.0,
        ModelOptions {
            nx,
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let min = run.outcome.force_minimum().unwrap();
    let err = -min.f_bar / 0.5 - 1.0;
    let n_d = 2.0 * min.b_axis / run.model.dx;
    let ((rf, mf), (rd, md)) = branch_deviation(&run.outcome, 1.5);
    let end = jkrbem::theory::jkr::jkr_end_of_contact();
    println!(
        "sphere {nx}²: |min F̄| = {:.4} ({:+.2} % vs 1/2, n_d = {n_d:.0}); branch F̄: RMS {rf:.4}, \
         max {mf:.4}; d̄: RMS {rd:.4}, max {md:.4}",
        -min.f_bar,
        100.0 * err
    );
    assert!(err.abs() < bound, "adhesive force error {err:+.4}");
    assert!(rf < bound * 0.5, "F̄(c̄) RMS deviation {rf:.4}");
    assert!(rd < bound * end.d_bar.abs(), "d̄(c̄) RMS deviation {rd:.4}");
    // The contact must vanish at the end (displacement-controlled jump-off).
    assert_eq!(run.outcome.states.last().unwrap().n_contact, 0);
}

#[test]
fn sphere_128_follows_jkr_within_6_percent() {
    check_sphere(128, 0.06);
}

#[test]
#[ignore = "slow tier (about 2 minutes): cargo test --release -- --ignored"]
fn sphere_256_follows_jkr_within_4_percent() {
    check_sphere(256, 0.04);
}

#[test]
fn force_minimum_does_not_depend_on_step_size() {
    // Detachment onsets are located exactly, so 40 and 160 steps find the same minimum.
    let f = |steps| {
        let run = common::run_ratio(
            1.0,
            ModelOptions {
                nx: 64,
                steps,
                ..Default::default()
            },
        );
        -run.outcome.force_minimum().unwrap().f_bar
    };
    let (coarse, fine) = (f(40), f(160));
    println!("64²: |min F̄| = {coarse:.9} (40 steps), {fine:.9} (160 steps)");
    // The claim of docs/commands.md ("The protocol"): the same minimum to 1e-6.
    assert!((coarse / fine - 1.0).abs() < 1e-6, "{coarse} vs {fine}");
    // A regression pin of this deterministic f64 figure (0.546318 in docs/failures.md and
    // docs/gpu.md), not an accuracy claim: its distance to JKR's 1/2 is the first-order grid
    // error.
    assert!(
        (fine - 0.546318).abs() < 1e-4,
        "|min F̄| at 64² moved: {fine}"
    );
}
