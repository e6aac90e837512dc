//! A mesh turned against the ellipsoid (`mesh_angle_deg`): a quarter turn is the aligned
//! run transposed, and at 45° the contact stays mirror-symmetric in the grid's diagonal with
//! its half-axes measured along the turned axes.

use crate::common;

use jkrbem::model::{MeshAngle, ModelOptions};

#[test]
fn quarter_turned_mesh_gives_the_aligned_pulloff() {
    // The aligned 64 × 32 grid of R1/R2 = 5, transposed and turned by 90°: the same
    // elements see the same heights, so every state must repeat, up to FFT round-off.
    let aligned = common::model_for(
        5.0,
        ModelOptions {
            nx: 64,
            ..Default::default()
        },
    );
    let mut turned = aligned.clone();
    (turned.nx, turned.ny) = (aligned.ny, aligned.nx);
    turned.mesh = MeshAngle::from_degrees(90.0);
    let (r0, r90) = (common::run_model(aligned), common::run_model(turned));
    assert!(r0.outcome.complete() && r90.outcome.complete());
    let (s0, s90) = (&r0.outcome.states, &r90.outcome.states);
    assert_eq!(s0.len(), s90.len(), "state counts differ");
    let mut worst = 0f64;
    for (a, b) in s0.iter().zip(s90) {
        assert_eq!(a.n_contact, b.n_contact, "step {}", a.step);
        assert_eq!(
            (a.a_axis, a.b_axis),
            (b.a_axis, b.b_axis),
            "step {}",
            a.step
        );
        worst = worst.max((a.force - b.force).abs() / a.force.abs().max(1e-3));
    }
    println!(
        "{} states; largest relative force difference {worst:.2e}",
        s0.len()
    );
    assert!(worst < 1e-9);
}

#[test]
fn mesh_at_45_degrees_keeps_the_contact_mirror_symmetric_along_its_axes() {
    // R1/R2 = 5 on a 64² grid turned by 45°, stopped near the force minimum.
    let run = common::run_ratio(
        5.0,
        ModelOptions {
            nx: 64,
            mesh_angle_deg: 45.0,
            final_d_bar: Some(-0.2),
            ..Default::default()
        },
    );
    assert!(run.outcome.complete(), "{:?}", run.outcome.error);
    let (n, m) = (run.model.nx, &run.final_mask);
    assert_eq!(run.model.ny, n);
    let asym = (0..n * n)
        .filter(|&k| m[k] != m[(k % n) * n + k / n])
        .count();
    assert_eq!(asym, 0, "elements not mirrored in the diagonal");
    for s in run.outcome.states.iter().filter(|s| s.n_contact > 20) {
        // The measured half-axes span the contact's area: π a b ≈ A within the
        // quantisation of a chord (one element diagonal on each end).
        let ellipse = std::f64::consts::PI * s.a_axis * s.b_axis;
        let dx = run.model.dx;
        let slack = std::f64::consts::PI * (s.a_axis + s.b_axis) * dx * 2f64.sqrt();
        assert!(
            (ellipse - s.area).abs() < slack,
            "step {}: π a b = {ellipse:.3}, A = {:.3}",
            s.step,
            s.area
        );
        assert!(
            s.a_axis > s.b_axis,
            "step {}: a = {}, b = {}",
            s.step,
            s.a_axis,
            s.b_axis
        );
    }
}
