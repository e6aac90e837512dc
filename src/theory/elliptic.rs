//! Complete elliptic integrals K(m), E(m) in the parameter convention (m = e², dimensionless)
//! and the combinations D = (K − E)/m, B = K − D, C = (D − B)/m of elliptic contact theory.

use std::f64::consts::FRAC_PI_2;

/// Below this parameter D and C come from their power series, above it from the AGM;
/// the two forms agree there to about 1e-15 (see the tests).
const SERIES_MAX_M: f64 = 0.5;

/// K, D, B and C at one parameter (all dimensionless).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Kdbc {
    pub k: f64,
    pub d: f64,
    pub b: f64,
    pub c: f64,
}

/// AGM for parameter m with complementary parameter mc = 1 − m (passed separately so that
/// callers holding g² = mc keep its accuracy). Returns (K, S) with S = Σ_{n≥1} 2^(n−1) c_n²,
/// so that E = K (1 − m/2 − S). c_{n+1} = c_n²/(4 a_{n+1}) avoids the difference a_n − b_n.
fn agm(m: f64, mc: f64) -> (f64, f64) {
    if !(0.0..1.0).contains(&m) || mc.is_nan() || mc <= 0.0 {
        return (f64::NAN, f64::NAN);
    }
    let mut a = 0.5 * (1.0 + mc.sqrt()); // a_1
    let mut b = mc.sqrt().sqrt(); // b_1 = √(a_0 b_0)
    let mut c = m / (4.0 * a); // c_1 = c_0²/(4 a_1), c_0² = m
    let (mut weight, mut sum) = (1.0, 0.0); // weight = 2^(n−1)
    for _ in 0..64 {
        sum += weight * c * c;
        if c <= f64::EPSILON * a {
            break;
        }
        let a_next = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = a_next;
        c = c * c / (4.0 * a);
        weight *= 2.0;
    }
    (FRAC_PI_2 / a, sum)
}

/// Complete elliptic integral of the first kind K(m); m ∈ [0, 1) (dimensionless), NaN outside.
pub fn ellip_k(m: f64) -> f64 {
    agm(m, 1.0 - m).0
}

/// Complete elliptic integral of the second kind E(m); m ∈ [0, 1) (dimensionless), NaN outside.
pub fn ellip_e(m: f64) -> f64 {
    let (k, s) = agm(m, 1.0 - m);
    k * (1.0 - 0.5 * m - s)
}

/// D and C from the AGM sums: K − E = K (m/2 + S) ⇒ D = K (1/2 + S/m);
/// 2D − K = 2KS/m ⇒ C = (2D − K)/m = 2KS/m².
fn agm_d_c(m: f64, mc: f64) -> (f64, f64) {
    let (k, s) = agm(m, mc);
    (k * (0.5 + s / m), 2.0 * k * s / (m * m))
}

/// D and C from their power series (a_n = (2n−1)!!/(2n)!!):
/// D = (π/2) Σ_{n≥1} a_n² (2n/(2n−1)) m^(n−1),  C = (π/2) Σ_{n≥1} a_n² (n/(n+1)) m^(n−1)
/// (the second from 2 a_{n+1}² (2n+2)/(2n+1) − a_n² = a_n² n/(n+1)).
fn series_d_c(m: f64) -> (f64, f64) {
    let (mut a_sq, mut power, mut d, mut c) = (1.0, 1.0, 0.0, 0.0);
    for n in 1..400 {
        let nf = n as f64;
        let ratio = (2.0 * nf - 1.0) / (2.0 * nf); // a_n / a_{n−1}
        a_sq *= ratio * ratio;
        let term_d = a_sq * (2.0 * nf / (2.0 * nf - 1.0)) * power;
        d += term_d;
        c += a_sq * (nf / (nf + 1.0)) * power;
        if term_d <= 1e-3 * f64::EPSILON * d {
            break;
        }
        power *= m;
    }
    (FRAC_PI_2 * d, FRAC_PI_2 * c)
}

/// D = (K − E)/m and C = (D − B)/m = (2D − K)/m, both dimensionless, free of the m → 0
/// cancellation; m ∈ [0, 1), NaN outside. D(0) = π/4, C(0) = π/16.
pub fn d_and_c(m: f64) -> (f64, f64) {
    let e = kdbc(m, 1.0 - m);
    (e.d, e.c)
}

/// K, D, B, C for parameter m and complementary parameter mc = 1 − m.
pub(crate) fn kdbc(m: f64, mc: f64) -> Kdbc {
    let k = agm(m, mc).0;
    let (d, c) = if (0.0..SERIES_MAX_M).contains(&m) {
        series_d_c(m)
    } else {
        agm_d_c(m, mc)
    };
    Kdbc { k, d, b: k - d, c }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn k_and_e_at_zero_are_half_pi() {
        assert!((ellip_k(0.0) - FRAC_PI_2).abs() < 1e-15);
        assert!((ellip_e(0.0) - FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn k_and_e_match_reference_values_at_half() {
        assert!((ellip_k(0.5) - 1.8540746773013719).abs() < 1e-15);
        assert!((ellip_e(0.5) - 1.3506438810476755).abs() < 1e-15);
    }

    #[test]
    fn d_and_c_limits_at_zero_are_quarter_pi_and_sixteenth_pi() {
        let (d, c) = d_and_c(0.0);
        assert!((d - PI / 4.0).abs() < 1e-15 && (c - PI / 16.0).abs() < 1e-15);
    }

    #[test]
    fn series_and_agm_forms_of_d_and_c_agree_across_crossover() {
        for i in 0..=40 {
            let m = 0.3 + 0.01 * i as f64;
            let (ds, cs) = series_d_c(m);
            let (da, ca) = agm_d_c(m, 1.0 - m);
            assert!(
                (ds - da).abs() < 1e-13 && (cs - ca).abs() < 1e-13,
                "m = {m}"
            );
        }
    }

    #[test]
    fn d_and_c_match_their_definitions_away_from_zero() {
        let m = 0.8;
        let (k, e) = (ellip_k(m), ellip_e(m));
        let (d, c) = d_and_c(m);
        assert!((d - (k - e) / m).abs() < 1e-14);
        assert!((c - (d - (k - d)) / m).abs() < 1e-13);
    }

    #[test]
    fn out_of_domain_parameter_gives_nan() {
        assert!(ellip_k(1.0).is_nan() && ellip_e(-0.1).is_nan() && d_and_c(f64::NAN).0.is_nan());
    }
}
