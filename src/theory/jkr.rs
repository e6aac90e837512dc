//! JKR theory for a sphere (R1 = R2) in the physics §2 normalisation.

use super::TheoryPoint;
use std::f64::consts::SQRT_2;

/// JKR state at normalised contact radius `c_bar` (dimensionless, ≥ 0; NaN below 0):
/// F̄ = c̄³ − √2 c̄^(3/2), d̄ = c̄² − (2/3)√2 c̄^(1/2), ā = b̄ = c̄.
pub fn jkr_point(c_bar: f64) -> TheoryPoint {
    let root = c_bar.sqrt();
    TheoryPoint {
        c_bar,
        f_bar: c_bar.powi(3) - SQRT_2 * c_bar * root,
        d_bar: c_bar * c_bar - 2.0 / 3.0 * SQRT_2 * root,
        a_bar: c_bar,
        b_bar: c_bar,
    }
}

/// Force-controlled pull-off (minimum F̄): dF̄/dc̄ = 3c̄² − (3/√2) c̄^(1/2) = 0 ⇒ c̄³ = 1/2,
/// so c̄ = 2^(−1/3) and F̄ = 1/2 − √2·(1/√2) = −1/2.
pub fn jkr_force_min() -> TheoryPoint {
    jkr_point(0.5f64.cbrt())
}

/// Displacement-controlled end of contact (minimum d̄): dd̄/dc̄ = 2c̄ − (√2/3) c̄^(−1/2) = 0
/// ⇒ c̄^(3/2) = √2/6 ⇒ c̄³ = 1/18, where F̄ = 1/18 − 1/3 = −5/18.
pub fn jkr_end_of_contact() -> TheoryPoint {
    jkr_point((1.0f64 / 18.0).cbrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jkr_force_min_is_minus_half_at_cube_root_of_half() {
        let p = jkr_force_min();
        assert!((p.c_bar - 2f64.powf(-1.0 / 3.0)).abs() < 1e-15);
        assert!((p.f_bar + 0.5).abs() < 1e-15);
        assert!((p.d_bar + 0.20999).abs() < 1e-5);
    }

    #[test]
    fn jkr_end_of_contact_is_minus_five_eighteenths() {
        let p = jkr_end_of_contact();
        assert!((p.f_bar + 5.0 / 18.0).abs() < 1e-15);
        assert!((p.d_bar + 0.43679).abs() < 1e-5);
    }

    #[test]
    fn jkr_critical_points_are_minima_of_force_and_approach() {
        let h = 1e-4;
        let (f, d) = (jkr_force_min(), jkr_end_of_contact());
        for s in [-h, h] {
            assert!(jkr_point(f.c_bar + s).f_bar > f.f_bar);
            assert!(jkr_point(d.c_bar + s).d_bar > d.d_bar);
        }
    }
}
