//! The first, non-adhesive press against elliptic Hertz theory.

use crate::common;

use jkrbem::model::ModelOptions;
use jkrbem::solver::Phase;
use std::f64::consts::PI;

/// Run only the non-adhesive approach (the final d̄ is just below the first one).
fn approach(ratio: f64, nx: usize) -> (f64, f64, f64, f64) {
    let mut model = common::model_for(
        ratio,
        ModelOptions {
            nx,
            ..Default::default()
        },
    );
    model.load.d_final = model.load.d0;
    let run = common::run_model(model);
    assert_eq!(run.outcome.states.len(), 1);
    let s = &run.outcome.states[0];
    assert_eq!(s.phase, Phase::Approach);
    let h = run.model.initial;
    (s.force, h.force, s.area, PI * h.a * h.b)
}

#[test]
fn sphere_hertz_force_within_half_percent_and_area_within_two_percent_at_128() {
    let (f, f_h, a, a_h) = approach(1.0, 128);
    println!(
        "sphere 128²: F/F_Hertz − 1 = {:+.3e}, A/A_Hertz − 1 = {:+.3e}",
        f / f_h - 1.0,
        a / a_h - 1.0
    );
    assert!((f / f_h - 1.0).abs() < 0.005);
    assert!((a / a_h - 1.0).abs() < 0.02);
}

#[test]
fn ellipsoid_hertz_force_and_area_at_128() {
    // Elliptic Hertz (R1/R2 = 5): same bounds, on a grid of 128 along the major axis.
    let (f, f_h, a, a_h) = approach(5.0, 128);
    println!(
        "5:1 ellipsoid 128: F/F_Hertz − 1 = {:+.3e}, A/A_Hertz − 1 = {:+.3e}",
        f / f_h - 1.0,
        a / a_h - 1.0
    );
    assert!((f / f_h - 1.0).abs() < 0.005);
    assert!((a / a_h - 1.0).abs() < 0.02);
}
