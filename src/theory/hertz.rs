//! Non-adhesive elliptic Hertz contact (Johnson 1985, §3.4), dimensional and normalised.
//!
//! For p = p0 √(1 − x²/a² − y²/b²), a ≥ b, g = b/a, m = 1 − g², the surface displacement in
//! the contact is u = (L − Mx² − Ny²)/(πE*) with L = πp0bK, M = πp0b(K − E)/(m a²),
//! N = πp0b((a²/b²)E − K)/(m a²). Matching u = d − x²/(2R1) − y²/(2R2) gives
//! R1/R2 = N/M = (E/g² − K)/(K − E), p0 = a²E*/(2R1 b D), d = a²K/(2R1 D),
//! F = (2/3)πab p0 = πE* a³/(3R1 D).

use super::elliptic::{d_and_c, ellip_e, ellip_k};
use super::solve::bisect;
use super::{require, TheoryError, TheoryPoint};
use std::f64::consts::PI;

/// A dimensional Hertz contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzContact {
    /// Major half-axis, along x (length, the user's unit).
    pub a: f64,
    /// Minor half-axis, along y (length).
    pub b: f64,
    /// Approach, pressing in positive (length).
    pub d: f64,
    /// Normal force, compressive positive (force, the user's unit).
    pub force: f64,
    /// Peak pressure at the centre (force per length²).
    pub p0: f64,
}

/// Hertz axis ratio g = b/a (dimensionless) for `ratio` = R1/R2 (dimensionless, finite, ≥ 1),
/// the root in (0, 1] of (E − g²K) − ratio·g²(K − E) = 0 (Johnson's relation times g²).
pub fn hertz_ellipticity_exact(ratio: f64) -> Result<f64, TheoryError> {
    super::check_ratio(ratio, false)?;
    if ratio == 1.0 {
        return Ok(1.0);
    }
    let residual = |g: f64| {
        let m = 1.0 - g * g;
        let (k, e) = (ellip_k(m), ellip_e(m));
        (e - g * g * k) - ratio * g * g * (k - e)
    };
    Ok(bisect(0.0, 1.0, |g| residual(g) > 0.0).1)
}

/// Validates r1 ≥ r2 > 0 and e_star > 0 and returns (g, K, D) for R1/R2.
fn shape(r1: f64, r2: f64, e_star: f64) -> Result<(f64, f64, f64), TheoryError> {
    require(r2.is_finite() && r2 > 0.0, "r2", r2, "finite and > 0")?;
    require(
        r1.is_finite() && r1 >= r2,
        "r1",
        r1,
        "finite and ≥ r2 (the major-axis radius)",
    )?;
    require(
        e_star.is_finite() && e_star > 0.0,
        "e_star",
        e_star,
        "finite and > 0",
    )?;
    let g = hertz_ellipticity_exact(r1 / r2)?;
    let m = (1.0 - g) * (1.0 + g);
    Ok((g, ellip_k(m), d_and_c(m).0))
}

/// Hertz contact with mean radius `c` = √(ab) (length, ≥ 0) for indenter radii `r1` ≥ `r2`
/// (length) and effective modulus `e_star` (force per length²).
pub fn hertz_for_mean_radius(
    r1: f64,
    r2: f64,
    e_star: f64,
    c: f64,
) -> Result<HertzContact, TheoryError> {
    let (g, k, d_int) = shape(r1, r2, e_star)?;
    require(c.is_finite() && c >= 0.0, "c", c, "finite and ≥ 0")?;
    let (a, b) = (c / g.sqrt(), c * g.sqrt());
    Ok(HertzContact {
        a,
        b,
        d: a * a * k / (2.0 * r1 * d_int),
        force: PI * e_star * a.powi(3) / (3.0 * r1 * d_int),
        p0: a * e_star / (2.0 * r1 * g * d_int), // = 3F/(2πab), finite at c = 0
    })
}

/// Hertz contact at approach `d` (length, ≥ 0) for radii `r1` ≥ `r2` (length) and effective
/// modulus `e_star` (force per length²): a² = 2R1 D d/K.
pub fn hertz_for_depth(r1: f64, r2: f64, e_star: f64, d: f64) -> Result<HertzContact, TheoryError> {
    let (g, k, d_int) = shape(r1, r2, e_star)?;
    require(d.is_finite() && d >= 0.0, "d", d, "finite and ≥ 0")?;
    let a = (2.0 * r1 * d_int * d / k).sqrt();
    hertz_for_mean_radius(r1, r2, e_star, a * g.sqrt())
}

/// Normalised Hertz state at `c_bar` (dimensionless) for `ratio` = R1/R2 with Hertz axis
/// ratio `g`: with c = c̄c_r, Re/R1 = λ, the physics §2 scales give d̄ = c̄² λK/(2gD) and
/// F̄ = (π/4) c̄³ λ/(g^(3/2) D) (sphere: d̄ = c̄², F̄ = c̄³).
pub(super) fn hertz_point(ratio: f64, g: f64, c_bar: f64) -> TheoryPoint {
    let lambda = (1.0 / ratio).sqrt();
    let m = (1.0 - g) * (1.0 + g);
    let (k, d_int) = (ellip_k(m), d_and_c(m).0);
    TheoryPoint {
        c_bar,
        f_bar: PI / 4.0 * c_bar.powi(3) * lambda / (g.powf(1.5) * d_int),
        d_bar: c_bar * c_bar * lambda * k / (2.0 * g * d_int),
        a_bar: c_bar / g.sqrt(),
        b_bar: c_bar * g.sqrt(),
    }
}

#[cfg(test)]
mod tests {
    use super::super::jg::{hertz_ellipticity, hertz_gap, jg_point, jg_point_at_c};
    use super::*;

    #[test]
    fn hertz_ellipticity_equals_jg_hertz_root() {
        for ratio in [2.0, 5.0, 10.0, 50.0] {
            let (exact, jg) = (
                hertz_ellipticity_exact(ratio).unwrap(),
                hertz_ellipticity(ratio),
            );
            assert!((exact - jg).abs() < 1e-13, "ratio {ratio}: {exact} vs {jg}");
        }
    }

    #[test]
    fn jg_c_bar_diverges_at_hertz_ellipticity() {
        for ratio in [2.0, 10.0, 50.0] {
            let g_h = hertz_ellipticity_exact(ratio).unwrap();
            let c: Vec<f64> = [1e-3, 1e-6, 1e-9]
                .iter()
                .map(|&e| jg_point(ratio, g_h + e).c_bar)
                .collect();
            assert!(
                c[0] < c[1] && c[1] < c[2] && c[2] > 1e4,
                "ratio {ratio}: {c:?}"
            );
        }
    }

    #[test]
    fn hertz_sphere_limit_gives_d_equal_a_squared_over_r() {
        let (r, e_star, c) = (2.0, 3.0, 0.1);
        let h = hertz_for_mean_radius(r, r, e_star, c).unwrap();
        assert!(
            (h.d - c * c / r).abs() < 1e-15
                && (h.force - 4.0 / 3.0 * e_star * c.powi(3) / r).abs() < 1e-15
        );
    }

    #[test]
    fn hertz_depth_and_mean_radius_forms_agree_and_p0_balances_force() {
        let h = hertz_for_mean_radius(7.0, 1.5, 2.0, 0.2).unwrap();
        let back = hertz_for_depth(7.0, 1.5, 2.0, h.d).unwrap();
        assert!((back.a - h.a).abs() < 1e-14 && (back.force - h.force).abs() < 1e-14);
        assert!((h.p0 - 3.0 * h.force / (2.0 * PI * h.a * h.b)).abs() < 1e-13 * h.p0);
    }

    #[test]
    fn hertz_normalised_point_matches_dimensional_contact() {
        let (r1, r2, e_star, gamma, c) = (6.0f64, 1.5, 2.0, 0.01, 0.3);
        let re = (r1 * r2).sqrt();
        let c_r = (9.0 * PI * re * re * gamma / (4.0 * e_star)).cbrt();
        let h = hertz_for_mean_radius(r1, r2, e_star, c).unwrap();
        let p = hertz_point(r1 / r2, hertz_ellipticity_exact(r1 / r2).unwrap(), c / c_r);
        assert!((p.f_bar - h.force / (3.0 * PI * re * gamma)).abs() < 1e-12 * p.f_bar);
        assert!((p.d_bar - h.d * re / (c_r * c_r)).abs() < 1e-12 * p.d_bar);
        assert!((p.a_bar - h.a / c_r).abs() < 1e-12 && (p.b_bar - h.b / c_r).abs() < 1e-12);
    }

    #[test]
    fn jg_tends_to_hertz_for_large_contacts() {
        for ratio in [2.0, 25.0] {
            let (t_h, g_h) = (hertz_gap(ratio), hertz_ellipticity(ratio));
            let (jg, hz) = (jg_point_at_c(ratio, t_h, 1e3), hertz_point(ratio, g_h, 1e3));
            assert!(
                (jg.f_bar / hz.f_bar - 1.0).abs() < 1e-3
                    && (jg.d_bar / hz.d_bar - 1.0).abs() < 1e-3
            );
        }
    }

    #[test]
    fn hertz_rejects_bad_input_naming_the_value() {
        let err = hertz_for_mean_radius(1.0, 2.0, 1.0, 0.1)
            .unwrap_err()
            .to_string();
        assert!(err.contains("r1") && err.contains("≥ r2"), "{err}");
        assert!(hertz_for_depth(2.0, 1.0, 1.0, -1.0)
            .unwrap_err()
            .to_string()
            .contains("d = -1"));
        assert!(hertz_ellipticity_exact(f64::NAN).is_err());
    }
}
