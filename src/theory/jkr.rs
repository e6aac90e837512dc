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

/// JKR's contact pressure (force/length², p < 0 tensile) at distance `r` (length) from the
/// axis of a sphere of radius `radius` (length) pressed by `d` (length, > 0 presses in) into a
/// half-space of modulus `e_star` (force/length²) over a contact of radius `a` (length): Hertz's
/// pressure of radius a and a flat punch's for the rest of the approach, d − a²/R,
///
/// p(r) = (2E*/(πR)) √(a² − r²) + E* (d − a²/R) / (π √(a² − r²)),
///
/// i.e. p0 (1 − r²/a²)^½ − p0′ (1 − r²/a²)^−½ with p0 = 2E*a/(πR) and
/// p0′ = E*(a²/R − d)/(πa). It diverges at the edge r → a (JKR's tension singularity); 0
/// outside the contact (r > a), and NaN for a non-finite or negative input.
pub fn jkr_pressure(r: f64, a: f64, d: f64, radius: f64, e_star: f64) -> f64 {
    let r = r.abs();
    if !(a >= 0.0 && radius > 0.0 && e_star.is_finite() && d.is_finite() && r.is_finite()) {
        return f64::NAN;
    }
    if r > a {
        return 0.0;
    }
    let s = ((a - r) * (a + r)).sqrt();
    let pi = std::f64::consts::PI;
    2.0 * e_star / (pi * radius) * s + e_star * (d - a * a / radius) / (pi * s)
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

    #[test]
    fn jkr_pressure_is_hertz_plus_a_punch_and_carries_jkr_s_force() {
        let (radius, e_star, a) = (2.0, 3.0, 0.5);
        let pi = std::f64::consts::PI;
        // At Hertz's approach d = a²/R the punch part vanishes: Hertz's p0 at the centre.
        let hertz = jkr_pressure(0.0, a, a * a / radius, radius, e_star);
        assert!((hertz - 2.0 * e_star * a / (pi * radius)).abs() < 1e-15);
        // F = ∫ p 2πr dr = 4E*a³/(3R) + 2E*a (d − a²/R): JKR's force at (a, d).
        let d = a * a / radius - 0.3;
        let n = 200_000;
        // r = a sin θ takes the edge's r^−½ singularity out of the quadrature.
        let h = 0.5 * pi / n as f64;
        let force: f64 = (0..n)
            .map(|k| {
                let t = (k as f64 + 0.5) * h;
                let r = a * t.sin();
                jkr_pressure(r, a, d, radius, e_star) * 2.0 * pi * r * a * t.cos() * h
            })
            .sum();
        let expected =
            4.0 * e_star * a.powi(3) / (3.0 * radius) + 2.0 * e_star * a * (d - a * a / radius);
        assert!(
            (force - expected).abs() < 1e-6 * expected.abs(),
            "{force} vs {expected}"
        );
        assert_eq!(jkr_pressure(0.6, a, d, radius, e_star), 0.0);
        assert!(jkr_pressure(0.0, a, d, -1.0, e_star).is_nan());
    }
}
