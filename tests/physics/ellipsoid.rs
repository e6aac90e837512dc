//! A 5:1 ellipsoid: a contact elongated along x and mirror-symmetric in both axes.

use crate::common;

use jkrbem::model::ModelOptions;
use jkrbem::solver::Phase;

#[test]
fn ellipsoid_5_to_1_contact_is_mirror_symmetric_and_elongated_along_x() {
    // Stop near the force minimum so the final contact is the adhesive one.
    let mut run = common::run_ratio(
        5.0,
        ModelOptions {
            nx: 128,
            final_d_bar: Some(-0.2),
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let (nx, ny) = (run.model.nx, run.model.ny);
    let m = std::mem::take(&mut run.final_mask);
    let n = m.iter().filter(|&&v| v).count();
    assert!(n > 100, "contact too small to test: {n}");
    let mut mirror_x = 0;
    let mut mirror_y = 0;
    for j in 0..ny {
        for i in 0..nx {
            mirror_x += (m[j * nx + i] != m[j * nx + (nx - 1 - i)]) as usize;
            mirror_y += (m[j * nx + i] != m[(ny - 1 - j) * nx + i]) as usize;
        }
    }
    println!("{n} elements in contact; asymmetric in x: {mirror_x}, in y: {mirror_y}");
    assert_eq!(mirror_x, 0);
    assert_eq!(mirror_y, 0);
    for s in run.outcome.states.iter().filter(|s| s.n_contact > 0) {
        assert!(
            s.a_axis > s.b_axis,
            "state {} ({:?}): a = {}, b = {}",
            s.step,
            s.phase,
            s.a_axis,
            s.b_axis
        );
    }
    let last = run
        .outcome
        .states
        .iter()
        .rev()
        .find(|s| s.phase == Phase::Pulloff)
        .unwrap();
    println!(
        "at d̄ = {:.3}: ā = {:.3}, b̄ = {:.3}, b/a = {:.3}",
        last.d_bar,
        last.a_bar,
        last.b_bar,
        last.b_axis / last.a_axis
    );
}
