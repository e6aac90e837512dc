//! Johnson–Greenwood (2005) approximate JKR theory for an elliptical contact (physics §3), as a
//! one-parameter branch in the axis ratio g = b/a ∈ (g_H, 1].

use super::elliptic::kdbc;
use super::solve::{bisect, minimise_on_unit};
use super::TheoryPoint;
use std::f64::consts::{PI, SQRT_2};

/// The end of the branch g = 1, where the contact has shrunk to a point.
const ORIGIN: TheoryPoint = TheoryPoint {
    c_bar: 0.0,
    f_bar: 0.0,
    d_bar: 0.0,
    a_bar: 0.0,
    b_bar: 0.0,
};

/// Normalised state on the JG branch for `ratio` = R1/R2 ≥ 1 (dimensionless) at axis ratio
/// `g` = b/a (dimensionless, in (g_H, 1]; g = 1 gives the origin, g ≤ g_H gives NaN).
pub fn jg_point(ratio: f64, g: f64) -> TheoryPoint {
    point(ratio, 1.0 - g)
}

/// The branch point at `t` = 1 − g (dimensionless), which keeps full precision as g → 1.
///
/// The formulas of docs/physics.md §3 are evaluated in a rearranged, cancellation-free form (same values):
/// δ = βg² − α = (g²D − λ²B)/(λQ) with g²D − λ²B = m(C − D) + (1 − λ²)B and
/// Q = (C + D)(B + g²C) − g²C² = B(C + D) + g²CD; then X = √g(1 − √g)/δ,
/// T = βg² − √g/X, F̄ = (8/(3π)) X [X(βg² + δ)/3 − √g] and
/// 2KT − αB − g²βD = K(βg² − 2√g/X) + δB.
fn point(ratio: f64, t: f64) -> TheoryPoint {
    if t == 0.0 {
        return ORIGIN;
    }
    let lambda_sq = 1.0 / ratio; // λ² = R2/R1 (dimensionless)
    let lambda = lambda_sq.sqrt();
    let mu = (ratio - 1.0) / ratio; // 1 − λ², exact for ratio near 1
    let g = 1.0 - t;
    let m = t * (1.0 + g); // m = e² = 1 − g²
    let (g_sq, root_g) = (g * g, g.sqrt());
    let e = kdbc(m, g_sq);
    let q = e.b * (e.c + e.d) + g_sq * e.c * e.d;
    let beta = ((lambda_sq + 1.0) * e.c + e.d) / (lambda * q);
    let delta = (m * (e.c - e.d) + mu * e.b) / (lambda * q);
    let x = root_g * (t / (1.0 + root_g)) / delta; // 1 − √g = (1 − g)/(1 + √g)
    let a_bar = (4.0 * SQRT_2 / (3.0 * PI) * x).powf(2.0 / 3.0);
    let f_bar = 8.0 / (3.0 * PI) * x * (x * (beta * g_sq + delta) / 3.0 - root_g);
    let d_scale = (2f64.powf(3.5) / (9.0 * PI * PI)).powf(2.0 / 3.0); // (2^(7/2)/(9π²))^(2/3)
    let bracket = e.k * (beta * g_sq - 2.0 * root_g / x) + delta * e.b;
    let d_bar = d_scale * x.powf(4.0 / 3.0) * bracket;
    TheoryPoint {
        c_bar: root_g * a_bar,
        f_bar,
        d_bar,
        a_bar,
        b_bar: a_bar - t * a_bar,
    }
}

/// Hertz ellipticity g_H (dimensionless): the root of βg² = α, i.e. g²D = λ²B, in (0, 1] for
/// `ratio` = R1/R2 (dimensionless). 1 at ratio 1; NaN for ratio < 1 or not finite.
pub fn hertz_ellipticity(ratio: f64) -> f64 {
    1.0 - hertz_gap(ratio)
}

/// t_H = 1 − g_H (dimensionless), by bisection in t on g²D − λ²B = m(C − D) + (1 − λ²)B,
/// which is positive for t < t_H (g near 1) and negative beyond.
pub(super) fn hertz_gap(ratio: f64) -> f64 {
    if !ratio.is_finite() || ratio < 1.0 {
        return f64::NAN;
    }
    let mu = (ratio - 1.0) / ratio; // 1 − λ²
    let root_above = |t: f64| {
        let g = 1.0 - t;
        let m = t * (1.0 + g);
        let e = kdbc(m, g * g);
        m * (e.c - e.d) + mu * e.b > 0.0
    };
    if ratio == 1.0 {
        0.0
    } else {
        bisect(0.0, 1.0, root_above).0
    }
}

/// The branch point with mean radius `c_bar` (dimensionless, > 0) for t_H = `t_h`, found by
/// bisection in t = 1 − g over (0, t_H): c̄ rises monotonically from 0 at t = 0 to ∞ at t_H.
pub(super) fn jg_point_at_c(ratio: f64, t_h: f64, c_bar: f64) -> TheoryPoint {
    let (t, _) = bisect(0.0, t_h, |t| point(ratio, t).c_bar < c_bar);
    point(ratio, t)
}

/// (minimum-F̄ point, minimum-d̄ point) of the JG branch for `ratio` > 1, each found by a grid
/// scan and golden-section search in s = t/t_H = (1 − g)/(1 − g_H) to 1e-10.
pub(super) fn jg_critical_points(ratio: f64) -> (TheoryPoint, TheoryPoint) {
    let t_h = hertz_gap(ratio);
    let at = |s: f64| point(ratio, s * t_h);
    let s_force = minimise_on_unit(|s| at(s).f_bar, 512, 1e-10);
    let s_depth = minimise_on_unit(|s| at(s).d_bar, 512, 1e-10);
    (at(s_force), at(s_depth))
}

#[cfg(test)]
mod tests {
    use super::super::elliptic::{ellip_e, ellip_k};
    use super::super::jkr::{jkr_end_of_contact, jkr_point};
    use super::*;

    /// The physics §3 formulas typed literally (fine away from g = 1 and λ = 1).
    fn spec_point(ratio: f64, g: f64) -> (f64, f64, f64) {
        let (lambda, m) = ((1.0 / ratio).sqrt(), 1.0 - g * g);
        let (k, e) = (ellip_k(m), ellip_e(m));
        let d = (k - e) / m;
        let b = k - d;
        let c = (d - b) / m;
        let beta = ((lambda * lambda + 1.0) * c + d)
            / ((c + d) * (b + g * g * c) - g * g * c * c)
            / lambda;
        let alpha = (lambda + 1.0 / lambda - beta * b) / d;
        let x = g.sqrt() * (1.0 - g.sqrt()) / (beta * g * g - alpha);
        let t = (alpha - beta * g.powf(2.5)) / (1.0 - g.sqrt());
        let c_bar = g.sqrt() * (4.0 * SQRT_2 / (3.0 * PI) * x).powf(2.0 / 3.0);
        let f = 8.0 / (3.0 * PI) * g * (1.0 - g.sqrt()).powi(2) / (beta * g * g - alpha).powi(2)
            * (t - (beta * g * g + alpha) / 3.0);
        let dd = (2f64.powf(3.5) / (9.0 * PI * PI)).powf(2.0 / 3.0)
            * x.powf(4.0 / 3.0)
            * (2.0 * k * t - alpha * b - g * g * beta * d);
        (c_bar, f, dd)
    }

    #[test]
    fn jg_rearranged_form_equals_spec_formulas() {
        let g_h = hertz_ellipticity(5.0);
        for s in [0.05, 0.3, 0.6, 0.9] {
            let g = g_h + s * (1.0 - g_h);
            let (p, (c, f, d)) = (jg_point(5.0, g), spec_point(5.0, g));
            let close = |u: f64, v: f64| (u - v).abs() < 1e-10 * (1.0 + v.abs());
            assert!(
                close(p.c_bar, c) && close(p.f_bar, f) && close(p.d_bar, d),
                "g = {g}"
            );
        }
    }

    #[test]
    fn jg_hertz_ellipticity_solves_beta_g_squared_equals_alpha() {
        assert_eq!(hertz_ellipticity(1.0), 1.0);
        assert!(hertz_ellipticity(0.5).is_nan() && hertz_ellipticity(f64::INFINITY).is_nan());
        for ratio in [2.0, 50.0] {
            let g = hertz_ellipticity(ratio);
            let e = kdbc(1.0 - g * g, g * g);
            assert!((g * g * e.d - e.b / ratio).abs() < 1e-14, "ratio {ratio}");
        }
    }

    #[test]
    fn jg_reproduces_jkr_as_ratio_tends_to_one() {
        for ratio in [1.0 + 1e-13, 1.0 + 1e-9, 1.0 + 1e-6] {
            let t_h = hertz_gap(ratio);
            for i in 0..=200 {
                let c_bar = 0.3 + 2.2 * i as f64 / 200.0;
                let p = jg_point_at_c(ratio, t_h, c_bar);
                assert!((p.c_bar - c_bar).abs() < 1e-9 && (p.b_bar / p.a_bar - 1.0).abs() < 1e-5);
                let j = jkr_point(p.c_bar);
                assert!(
                    (p.f_bar - j.f_bar).abs() < 1e-10 && (p.d_bar - j.d_bar).abs() < 1e-10,
                    "{p:?}"
                );
            }
        }
    }

    #[test]
    fn jg_pull_off_tends_to_jkr_as_ratio_tends_to_one() {
        let (force, depth) = jg_critical_points(1.0 + 1e-9);
        let end = jkr_end_of_contact();
        assert!((force.f_bar + 0.5).abs() < 1e-6, "{force:?}");
        assert!((depth.d_bar - end.d_bar).abs() < 1e-6 && (depth.f_bar - end.f_bar).abs() < 1e-6);
    }

    /// g on a logistic grid: g − g_H from 1e-6 up and 1 − g down to 1e-9, log-spaced at both ends.
    fn dense_g(g_h: f64, n: usize) -> Vec<f64> {
        let w = 1.0 - g_h;
        let (u0, u1) = ((1e-6 / w).ln(), (w / 1e-9).ln());
        let u = (0..=n).map(|i| u0 + (u1 - u0) * i as f64 / n as f64);
        u.map(|u| {
            if u < 0.0 {
                g_h + w / (1.0 + (-u).exp())
            } else {
                1.0 - w / (1.0 + u.exp())
            }
        })
        .collect()
    }

    /// No second difference exceeds 1e-2 × the largest |value| within ±10 grid points.
    fn is_smooth(v: &[f64]) -> bool {
        (1..v.len() - 1).all(|i| {
            let near = &v[i.saturating_sub(10)..(i + 11).min(v.len())];
            let scale = near.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            (v[i - 1] - 2.0 * v[i] + v[i + 1]).abs() < 1e-2 * scale
        })
    }

    #[test]
    fn jg_branch_is_smooth_and_c_bar_falls_monotonically_to_zero() {
        for ratio in [2.0, 5.0, 10.0, 25.0, 50.0] {
            let pts: Vec<TheoryPoint> = dense_g(hertz_ellipticity(ratio), 4000)
                .into_iter()
                .map(|g| jg_point(ratio, g))
                .collect();
            let (first, last) = (pts[0].c_bar, pts[pts.len() - 1].c_bar);
            assert!(first > 1e3 && last < 1e-4, "ratio {ratio}");
            assert!(
                pts.windows(2).all(|t| t[1].c_bar < t[0].c_bar),
                "ratio {ratio}"
            );
            assert!(
                is_smooth(&pts.iter().map(|p| p.f_bar).collect::<Vec<_>>()),
                "F̄ {ratio}"
            );
            assert!(
                is_smooth(&pts.iter().map(|p| p.d_bar).collect::<Vec<_>>()),
                "d̄ {ratio}"
            );
        }
    }

    #[test]
    fn jg_adhesive_force_decreases_with_ratio() {
        let mut last = 0.5; // JKR |min F̄| at ratio 1
        println!("ratio 1: |min F̄| = 0.5, g_H = 1");
        for ratio in [2.0, 5.0, 10.0, 25.0, 50.0] {
            let (force, depth) = jg_critical_points(ratio);
            let g_h = hertz_ellipticity(ratio);
            println!("ratio {ratio}: g_H = {g_h:.10}, force min {force:?}, end {depth:?}");
            assert!(-force.f_bar < last, "ratio {ratio}: {force:?}");
            last = -force.f_bar;
        }
    }
}
