//! Adhesive (JKR) contact of a rigid axisymmetric power-law indenter on an
//! elastic half-space, solved by the method of dimensionality reduction (MDR).
//!
//! The indenter profile is `h(r) = s·rⁿ` with exponent `n` (dimensionless) and
//! scale `s` (length^(1−n), so that `h` is a length). The half-space has the
//! effective modulus `E*` (force/length²) and the interface the work of
//! adhesion `Δγ` (force/length). For axisymmetric JKR contacts the MDR is
//! exact: the three-dimensional profile is replaced by the one-dimensional
//! profile `g(x) = κ_n·s·|x|ⁿ` pressed into a Winkler foundation of stiffness
//! `E*` per unit length, where
//!
//! `κ_n = √π · Γ(n/2 + 1) / Γ(n/2 + 1/2)` (so `κ_1 = π/2`, `κ_2 = 2`).
//!
//! Sign conventions: the approach (indentation depth) `d > 0` presses the
//! indenter into the half-space and the normal force `F > 0` is compressive;
//! adhesive (tensile) forces are negative.
//!
//! Formulas, all parametrised by the contact radius `a` (length):
//!
//! * non-adhesive (Hertz-like) contact: `d_H(a) = κ_n s aⁿ`,
//!   `F_H(a) = 2E* · n/(n+1) · κ_n s a^(n+1)`, centre pressure
//!   `p0(a) = E* n κ_n s a^(n−1) / (π (n − 1))` (finite only for `n > 1`);
//! * JKR branch: `d(a) = κ_n s aⁿ − √(2π a Δγ / E*)`,
//!   `F(a) = 2E* (d(a)·a − κ_n s a^(n+1)/(n+1))`;
//! * displacement-controlled pull-off: the contact shrinks along the branch
//!   while `dd/da > 0` and jumps off at `dd/da = 0`, i.e. at
//!   `a_end = (√(2πΔγ/E*) / (2 n κ_n s))^(1/(n − 1/2))`;
//! * the adhesive force is the minimum of `F(a)` on the stable branch
//!   `a ≥ a_end`, reached where `dF/da = 0`, i.e. at
//!   `a_F = (3√(2πΔγ/E*) / (2 n κ_n s))^(1/(n − 1/2)) = 3^(1/(n − 1/2)) · a_end`;
//! * flat punch of radius `a` (Kendall 1971), the limit `n → ∞`: pull-off
//!   force `−F_K` with `F_K = √(8π E* Δγ a³)` at approach `−d_K`,
//!   `d_K = F_K / (2E* a)`.
//!
//! For `n = 2` and `s = 1/(2R)` these reduce to the classical JKR sphere.

use std::f64::consts::PI;

/// Lanczos parameter `g` (dimensionless) of the gamma-function approximation.
const LANCZOS_G: f64 = 7.0;

/// Lanczos coefficients (dimensionless) for `g = 7` with nine terms.
const LANCZOS_COEFFS: [f64; 9] = [
    0.999_999_999_999_809_9,
    676.520_368_121_885_1,
    -1_259.139_216_722_402_8,
    771.323_428_777_653_1,
    -176.615_029_162_140_6,
    12.507_343_278_686_905,
    -0.138_571_095_265_720_12,
    9.984_369_578_019_572e-6,
    1.505_632_735_149_311_6e-7,
];

/// Largest accepted exponent `n` (dimensionless).
const MAX_EXPONENT: f64 = 1000.0;

/// Lanczos series `A(z)` (dimensionless) such that
/// `Γ(z) = √(2π) · t^(z − 1/2) · e^(−t) · A(z)` with `t = z − 1/2 + g`.
/// Valid for `z ≥ 1/2`.
fn lanczos_sum(z: f64) -> f64 {
    let x = z - 1.0;
    let mut sum = LANCZOS_COEFFS[0];
    for (i, &c) in LANCZOS_COEFFS.iter().enumerate().skip(1) {
        sum += c / (x + i as f64);
    }
    sum
}

/// Natural logarithm of the gamma function, `ln Γ(x)` (dimensionless), for
/// real `x > 0` (dimensionless).
///
/// Uses the Lanczos approximation with `g = 7` and nine coefficients; for
/// `0 < x < 1/2` the recurrence `ln Γ(x) = ln Γ(x + 1) − ln x` is applied
/// first (no reflection formula is needed). The absolute error of the
/// result, i.e. the relative error of `Γ(x)`, is about `1e-15` on `[0.5, 200]`.
/// Returns NaN for `x ≤ 0` or NaN, and `+∞` for `x = +∞`.
pub fn ln_gamma(x: f64) -> f64 {
    if x.is_nan() || x <= 0.0 {
        return f64::NAN;
    }
    if x.is_infinite() {
        return f64::INFINITY;
    }
    if x < 0.5 {
        return ln_gamma(x + 1.0) - x.ln();
    }
    let t = x - 0.5 + LANCZOS_G;
    0.5 * (2.0 * PI).ln() + (x - 0.5) * t.ln() - t + lanczos_sum(x).ln()
}

/// Ratio `Γ(z + 1/2) / Γ(z)` (dimensionless) for `z ≥ 1/2` (dimensionless).
///
/// This is the difference `ln Γ(z + 1/2) − ln Γ(z)` of two Lanczos
/// approximations, rearranged so that the large terms cancel analytically:
/// it neither overflows nor loses digits for large `z`.
fn gamma_ratio_half(z: f64) -> f64 {
    let t_lo = z - 0.5 + LANCZOS_G;
    let t_hi = t_lo + 0.5;
    let exponent = (z - 0.5) * (0.5 / t_lo).ln_1p() + 0.5 * t_hi.ln() - 0.5;
    exponent.exp() * lanczos_sum(z + 0.5) / lanczos_sum(z)
}

/// MDR stretch factor `κ_n = √π · Γ(n/2 + 1) / Γ(n/2 + 1/2)` (dimensionless)
/// of the power law `rⁿ` with exponent `n > −1` (dimensionless).
///
/// `κ_1 = π/2`, `κ_2 = 2`, `κ_4 = 8/3`, and `κ_n ≈ √(π n / 2)` for large `n`.
/// The gamma functions are combined as a difference of logarithms, so large
/// `n` does not overflow. Returns NaN for `n ≤ −1` or NaN.
pub fn kappa(n: f64) -> f64 {
    if n.is_nan() || n <= -1.0 {
        return f64::NAN;
    }
    if n.is_infinite() {
        return f64::INFINITY;
    }
    if n < 0.0 {
        // κ_{n+2} / κ_n = (n + 2) / (n + 1).
        return kappa(n + 2.0) * (n + 1.0) / (n + 2.0);
    }
    PI.sqrt() * gamma_ratio_half(0.5 * n + 0.5)
}

/// Flat-punch pull-off force `F_K = √(8π E* Δγ a³)` (force, positive) of
/// Kendall (1971) for a punch of `radius` `a` (length), effective modulus
/// `e_star` (force/length²) and work of adhesion `work_of_adhesion`
/// (force/length). The force at pull-off is `−F_K` (tensile).
pub fn kendall_force(radius: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
    (8.0 * PI * e_star * work_of_adhesion * radius.powi(3)).sqrt()
}

/// Flat-punch approach at pull-off magnitude `d_K = F_K / (2 E* a)` (length,
/// positive) for a punch of `radius` `a` (length), effective modulus `e_star`
/// (force/length²) and work of adhesion `work_of_adhesion` (force/length);
/// `2E*a` (force/length) is the punch's contact stiffness. The approach at
/// pull-off is `−d_K`, and `d_K = √(2π Δγ a / E*)`.
pub fn kendall_approach(radius: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
    kendall_force(radius, e_star, work_of_adhesion) / (2.0 * e_star * radius)
}

/// Adhesive contact of the rigid power-law indenter `h(r) = scale · rⁿ` with
/// an elastic half-space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLawContact {
    /// Exponent `n` of the profile (dimensionless), in `(1, 1000]`.
    pub n: f64,
    /// Scale `s` of the profile (length^(1−n)): `h(r) = s·rⁿ` is a length
    /// when `r` is a length.
    pub scale: f64,
    /// Effective modulus `E* = E / (1 − ν²)` of the half-space
    /// (force/length²).
    pub e_star: f64,
    /// Work of adhesion `Δγ` of the interface (force/length = energy/length²).
    pub work_of_adhesion: f64,
}

/// One state of the contact, parametrised by its contact radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchPoint {
    /// Contact radius `a` (length).
    pub a: f64,
    /// Approach `d` (length), positive when pressing in.
    pub d: f64,
    /// Normal force `F` (force), positive when compressive.
    pub force: f64,
}

/// True when `x` is finite and strictly positive.
fn positive_finite(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

impl PowerLawContact {
    /// Creates a contact from the exponent `n` (dimensionless, in
    /// `(1, 1000]`), the profile scale `scale` (length^(1−n)), the effective
    /// modulus `e_star` (force/length²) and the work of adhesion
    /// `work_of_adhesion` (force/length). All must be finite and positive.
    ///
    /// # Errors
    ///
    /// Returns a message naming the offending parameter (`"n"`, `"scale"`,
    /// `"e_star"` or `"work_of_adhesion"`) when a value is out of range.
    pub fn new(n: f64, scale: f64, e_star: f64, work_of_adhesion: f64) -> Result<Self, String> {
        if n.is_nan() || n <= 1.0 || n > MAX_EXPONENT {
            return Err(format!("n must lie in (1, {MAX_EXPONENT}], got {n}"));
        }
        if !positive_finite(scale) {
            return Err(format!("scale must be positive and finite, got {scale}"));
        }
        if !positive_finite(e_star) {
            return Err(format!("e_star must be positive and finite, got {e_star}"));
        }
        if !positive_finite(work_of_adhesion) {
            return Err(format!(
                "work_of_adhesion must be positive and finite, got {work_of_adhesion}"
            ));
        }
        Ok(Self {
            n,
            scale,
            e_star,
            work_of_adhesion,
        })
    }

    /// `κ_n · s` (length^(1−n)): the scale of the MDR-equivalent 1D profile.
    fn kappa_scale(&self) -> f64 {
        kappa(self.n) * self.scale
    }

    /// `√(2π Δγ / E*)` (length^(1/2)): the adhesive (Griffith) length factor;
    /// the adhesive part of the approach is this times `√a`.
    fn adhesion_root(&self) -> f64 {
        (2.0 * PI * self.work_of_adhesion / self.e_star).sqrt()
    }

    /// Non-adhesive approach `d_H(a) = κ_n s aⁿ` (length) at contact radius
    /// `a ≥ 0` (length).
    pub fn hertz_approach(&self, a: f64) -> f64 {
        self.kappa_scale() * a.powf(self.n)
    }

    /// Non-adhesive normal force `F_H(a) = 2E* · n/(n+1) · κ_n s a^(n+1)`
    /// (force) at contact radius `a ≥ 0` (length).
    pub fn hertz_force(&self, a: f64) -> f64 {
        2.0 * self.e_star * self.n / (self.n + 1.0) * self.kappa_scale() * a.powf(self.n + 1.0)
    }

    /// Non-adhesive peak (centre) pressure
    /// `p0(a) = E* n κ_n s a^(n−1) / (π (n − 1))` (force/length²) at contact
    /// radius `a ≥ 0` (length).
    ///
    /// The centre pressure is finite only for `n > 1`; for `n ≤ 1` (a cone or
    /// sharper tip) it is infinite (logarithmically for `n = 1`) and
    /// `f64::INFINITY` is returned.
    pub fn hertz_peak_pressure(&self, a: f64) -> f64 {
        if self.n <= 1.0 {
            return f64::INFINITY;
        }
        self.e_star * self.n * self.kappa_scale() * a.powf(self.n - 1.0) / (PI * (self.n - 1.0))
    }

    /// Non-adhesive contact radius `a = (d / (κ_n s))^(1/n)` (length) at the
    /// approach `d` (length): the inverse of [`Self::hertz_approach`].
    /// Returns 0 for `d ≤ 0` (no contact).
    pub fn hertz_radius(&self, d: f64) -> f64 {
        if d <= 0.0 {
            return 0.0;
        }
        (d / self.kappa_scale()).powf(1.0 / self.n)
    }

    /// Contact radius `a` (length) whose mean contact radius equals
    /// `mean_radius` (length). For axisymmetric contacts the contact area is
    /// the disc of radius `a`, so its mean radius is `a` itself; returns 0 for
    /// `mean_radius ≤ 0`.
    pub fn radius_from_mean_radius(&self, mean_radius: f64) -> f64 {
        if mean_radius <= 0.0 {
            return 0.0;
        }
        mean_radius
    }

    /// Point of the adhesive (JKR) branch at contact radius `a ≥ 0` (length):
    /// approach `d(a) = κ_n s aⁿ − √(2π a Δγ / E*)` (length) and force
    /// `F(a) = 2E* (d(a)·a − κ_n s a^(n+1)/(n+1))` (force).
    pub fn jkr(&self, a: f64) -> BranchPoint {
        let ks = self.kappa_scale();
        let d = ks * a.powf(self.n) - self.adhesion_root() * a.sqrt();
        let force = 2.0 * self.e_star * (d * a - ks * a.powf(self.n + 1.0) / (self.n + 1.0));
        BranchPoint { a, d, force }
    }

    /// Contact radius (length) where `dd/da = 0` on the JKR branch:
    /// `(√(2πΔγ/E*) / (2 n κ_n s))^(1/(n − 1/2))`.
    fn end_radius(&self) -> f64 {
        (self.adhesion_root() / (2.0 * self.n * self.kappa_scale())).powf(1.0 / (self.n - 0.5))
    }

    /// End of contact under displacement control: the point of the JKR branch
    /// where `dd/da = 0`, at
    /// `a_end = (√(2πΔγ/E*) / (2 n κ_n s))^(1/(n − 1/2))` (length). Its `d` is
    /// the smallest (most negative) approach at which contact persists; the
    /// indenter jumps off when pulled further.
    pub fn end_of_contact(&self) -> BranchPoint {
        self.jkr(self.end_radius())
    }

    /// Adhesive force under displacement control: the minimum of `F(a)` on
    /// the stable branch `a ≥ a_end`, reached where `dF/da = 0`, i.e. at
    /// `a_F = (3√(2πΔγ/E*) / (2 n κ_n s))^(1/(n − 1/2)) = 3^(1/(n−1/2)) a_end`
    /// (length). Its `force` (force) is negative (tensile); there
    /// `F = −√(8πE*Δγ a_F³) · (1 − 3/(2(n+1)))`.
    pub fn force_minimum(&self) -> BranchPoint {
        let a_end = self.end_radius();
        let a_f = (3.0 * self.adhesion_root() / (2.0 * self.n * self.kappa_scale()))
            .powf(1.0 / (self.n - 0.5));
        self.jkr(a_f.max(a_end))
    }

    /// Normalisation scales `(length, force, approach)` of the power-law
    /// contact, reducing to the usual JKR-sphere scales at `n = 2`.
    ///
    /// With `c_n = (9π Δγ / (16 E* s²))^(1/(2n−1))` (length) and the
    /// equivalent radius `R_n = c_n^(2−n) / (2s)` (length), the scales are
    /// the length `c_n`, the force `3π R_n Δγ` (force) and the approach
    /// `c_n² / R_n` (length). For `n = 2`, `s = 1/(2R)` they are
    /// `c = (9π R² Δγ / (4E*))^(1/3)`, `3πRΔγ` and `c²/R`, and in these units
    /// the normalised force minimum depends on `n` only.
    pub fn scales(&self) -> (f64, f64, f64) {
        let s = self.scale;
        let c = (9.0 * PI * self.work_of_adhesion / (16.0 * self.e_star * s * s))
            .powf(1.0 / (2.0 * self.n - 1.0));
        let r_n = c.powf(2.0 - self.n) / (2.0 * s);
        (c, 3.0 * PI * r_n * self.work_of_adhesion, c * c / r_n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, SQRT_2};

    /// Relative difference `|a − b| / max(|a|, |b|)` (dimensionless).
    fn rel(a: f64, b: f64) -> f64 {
        let m = a.abs().max(b.abs());
        if m == 0.0 {
            0.0
        } else {
            (a - b).abs() / m
        }
    }

    fn contact(n: f64, s: f64, e: f64, w: f64) -> PowerLawContact {
        match PowerLawContact::new(n, s, e, w) {
            Ok(c) => c,
            Err(msg) => panic!("valid parameters rejected: {msg}"),
        }
    }

    #[test]
    fn ln_gamma_known_values() {
        assert!((ln_gamma(0.5) - 0.5 * PI.ln()).abs() < 1e-14);
        assert!((ln_gamma(5.0) - 24.0_f64.ln()).abs() < 1e-14);
        assert!(rel(ln_gamma(5.0).exp(), 24.0) < 1e-13);
        assert!(rel(ln_gamma(10.5).exp(), 1_133_278.388_948_785_6) < 1e-13);
        assert!(ln_gamma(1.0).abs() < 1e-14);
        assert!(ln_gamma(2.0).abs() < 1e-14);
        // Reference values of ln Γ (high-precision arithmetic).
        let reference: [(f64, f64); 9] = [
            (0.5, 0.572_364_942_924_700_1),
            (0.75, 0.203_280_951_431_295_37),
            (1.5, -0.120_782_237_635_245_22),
            (3.3, 0.987_098_577_894_734_6),
            (10.5, 13.940_625_219_403_764),
            (25.25, 55.585_686_044_869_43),
            (77.7, 259.260_436_897_598),
            (150.0, 600.009_470_555_327_4),
            (200.0, 857.933_669_825_857_4),
        ];
        for (x, want) in reference {
            let got = ln_gamma(x);
            // Absolute error of ln Γ = relative error of Γ; for large ln Γ
            // allow for the rounding of the logarithm itself.
            let tol = 1e-13 * want.abs().max(1.0);
            assert!(
                (got - want).abs() < tol,
                "ln_gamma({x}) = {got}, want {want}"
            );
        }
        // Recurrence Γ(x + 1) = x Γ(x) over [0.5, 200].
        let mut x = 0.5;
        while x < 200.0 {
            let lhs = ln_gamma(x + 1.0) - ln_gamma(x);
            assert!((lhs - x.ln()).abs() < 1e-13 * ln_gamma(x + 1.0).abs().max(1.0));
            x += 0.37;
        }
        // Below 1/2 via the recurrence: Γ(0.25) = 3.625609908221908.
        assert!(rel(ln_gamma(0.25).exp(), 3.625_609_908_221_908) < 1e-13);
        assert!(ln_gamma(0.0).is_nan());
        assert!(ln_gamma(-1.0).is_nan());
        assert!(ln_gamma(f64::NAN).is_nan());
    }

    #[test]
    fn kappa_known_values() {
        assert!(rel(kappa(1.0), FRAC_PI_2) < 1e-13);
        assert!(rel(kappa(2.0), 2.0) < 1e-13);
        assert!(rel(kappa(3.0), 0.75 * PI) < 1e-13);
        assert!(rel(kappa(4.0), 8.0 / 3.0) < 1e-13);
        // κ_0 = 1 (flat punch normalisation of the MDR).
        assert!(rel(kappa(0.0), 1.0) < 1e-13);
        // High-precision reference values.
        let reference: [(f64, f64); 4] = [
            (7.5, 3.548_338_387_486_177),
            (20.0, 5.675_463_855_030_418),
            (400.0, 25.081_954_053_475_63),
            (1000.0, 39.643_182_531_295_33),
        ];
        for (n, want) in reference {
            assert!(rel(kappa(n), want) < 1e-13, "kappa({n}) = {}", kappa(n));
        }
        // Recurrence κ_{n+2} / κ_n = (n + 2) / (n + 1), including n < 0.
        let mut n = -0.9;
        while n < 998.0 {
            let ratio = kappa(n + 2.0) / kappa(n);
            assert!(rel(ratio, (n + 2.0) / (n + 1.0)) < 1e-13, "n = {n}");
            n += 1.13;
        }
        assert!(kappa(-1.0).is_nan());
        assert!(kappa(1e6).is_finite());
    }

    #[test]
    fn new_validates_and_names_parameter() {
        assert!(PowerLawContact::new(2.0, 1.0, 1.0, 1.0).is_ok());
        assert!(PowerLawContact::new(1000.0, 1.0, 1.0, 1.0).is_ok());
        for bad_n in [1.0, 0.5, -2.0, 1000.5, f64::NAN, f64::INFINITY] {
            match PowerLawContact::new(bad_n, 1.0, 1.0, 1.0) {
                Err(msg) => assert!(msg.starts_with("n "), "{msg}"),
                Ok(_) => panic!("n = {bad_n} accepted"),
            }
        }
        let bad_values = [0.0, -1.0, f64::NAN, f64::INFINITY];
        for bad in bad_values {
            let cases = [
                ("scale", PowerLawContact::new(2.0, bad, 1.0, 1.0)),
                ("e_star", PowerLawContact::new(2.0, 1.0, bad, 1.0)),
                ("work_of_adhesion", PowerLawContact::new(2.0, 1.0, 1.0, bad)),
            ];
            for (name, result) in cases {
                match result {
                    Err(msg) => assert!(msg.starts_with(name), "{msg}"),
                    Ok(_) => panic!("{name} = {bad} accepted"),
                }
            }
        }
    }

    #[test]
    fn hertz_radius_inverts_hertz_approach() {
        for n in [1.2, 2.0, 3.0, 7.5, 50.0] {
            let c = contact(n, 0.7, 3.0, 0.1);
            for a in [1e-3, 0.1, 0.5, 1.0, 1.3] {
                let d = c.hertz_approach(a);
                assert!(rel(c.hertz_radius(d), a) < 1e-13, "n = {n}, a = {a}");
            }
            assert_eq!(c.hertz_radius(0.0), 0.0);
            assert_eq!(c.hertz_radius(-1.0), 0.0);
            assert_eq!(c.radius_from_mean_radius(0.25), 0.25);
            assert_eq!(c.radius_from_mean_radius(-0.25), 0.0);
        }
    }

    #[test]
    fn hertz_sphere_and_stiffness() {
        let (r, e) = (2.5, 7.0);
        let c = contact(2.0, 1.0 / (2.0 * r), e, 0.3);
        for a in [0.01, 0.2, 1.0] {
            assert!(rel(c.hertz_approach(a), a * a / r) < 1e-13);
            assert!(rel(c.hertz_force(a), 4.0 * e * a.powi(3) / (3.0 * r)) < 1e-13);
            assert!(rel(c.hertz_peak_pressure(a), 2.0 * e * a / (PI * r)) < 1e-13);
            // Hertz: p0 = 3F / (2π a²).
            let p0 = 3.0 * c.hertz_force(a) / (2.0 * PI * a * a);
            assert!(rel(c.hertz_peak_pressure(a), p0) < 1e-13);
        }
        // dF_H/dd_H = 2E* a for any profile.
        let c = contact(3.7, 0.9, e, 0.3);
        let (a, h) = (0.6, 1e-5);
        let slope = (c.hertz_force(a + h) - c.hertz_force(a - h))
            / (c.hertz_approach(a + h) - c.hertz_approach(a - h));
        assert!(rel(slope, 2.0 * e * a) < 1e-8);
        // Peak pressure is infinite for n <= 1 (fields are public).
        let cone = PowerLawContact { n: 1.0, ..c };
        assert_eq!(cone.hertz_peak_pressure(0.5), f64::INFINITY);
    }

    #[test]
    fn jkr_sphere_matches_classical_formulas() {
        let (r, e, w) = (1.5, 2.0, 0.05);
        let c = contact(2.0, 1.0 / (2.0 * r), e, w);
        for a in [0.05, 0.3, 1.0, 2.0] {
            let p = c.jkr(a);
            let f = 4.0 * e * a.powi(3) / (3.0 * r) - (8.0 * PI * e * w * a.powi(3)).sqrt();
            let d = a * a / r - (2.0 * PI * a * w / e).sqrt();
            assert_eq!(p.a, a);
            assert!(rel(p.force, f) < 1e-12, "a = {a}");
            assert!(rel(p.d, d) < 1e-12, "a = {a}");
        }
    }

    #[test]
    fn jkr_tends_to_hertz_without_adhesion() {
        let c = contact(3.3, 0.8, 5.0, 1e-30);
        for a in [0.1, 0.5, 1.0] {
            let p = c.jkr(a);
            assert!(rel(p.d, c.hertz_approach(a)) < 1e-12);
            assert!(rel(p.force, c.hertz_force(a)) < 1e-12);
        }
    }

    #[test]
    fn sphere_normalisation() {
        for (r, e, w) in [(1.0, 1.0, 1.0), (2e-3, 1e6, 0.05), (30.0, 0.2, 7.0)] {
            let c = contact(2.0, 1.0 / (2.0 * r), e, w);
            let (len, force, approach) = c.scales();
            let c_sphere = (9.0 * PI * r * r * w / (4.0 * e)).cbrt();
            assert!(rel(len, c_sphere) < 1e-13);
            let r_n = len * len / approach;
            assert!(rel(r_n, r) < 1e-13);
            assert!(rel(force, 3.0 * PI * r * w) < 1e-13);

            let min = c.force_minimum();
            assert!((min.force / force + 0.5).abs() < 1e-12);
            assert!(rel(min.a / len, 0.5_f64.cbrt()) < 1e-12);

            let end = c.end_of_contact();
            let a_bar = (1.0_f64 / 18.0).cbrt();
            assert!(rel(end.a / len, a_bar) < 1e-12);
            assert!((end.force / force + 5.0 / 18.0).abs() < 1e-12);
            let d_bar = a_bar * a_bar - 2.0 * SQRT_2 / 3.0 * a_bar.sqrt();
            assert!((end.d / approach - d_bar).abs() < 1e-12);
            assert!((end.d / approach + 0.43679).abs() < 5e-6);
        }
    }

    #[test]
    fn end_of_contact_and_force_minimum_are_stationary() {
        for (n, s, e, w) in [
            (1.5, 0.4, 3.0, 0.02),
            (3.0, 2.0, 1.0, 0.1),
            (12.0, 1.0, 1.0, 0.01),
        ] {
            let c = contact(n, s, e, w);
            let end = c.end_of_contact();
            let min = c.force_minimum();
            let h = 1e-5 * end.a;
            let dd = (c.jkr(end.a + h).d - c.jkr(end.a - h).d) / (2.0 * h);
            let d_scale = end.d.abs() / end.a;
            assert!(dd.abs() < 1e-7 * d_scale, "n = {n}: dd/da = {dd}");
            assert!(c.jkr(end.a * 1.01).d > end.d && c.jkr(end.a * 0.99).d > end.d);

            let h = 1e-5 * min.a;
            let df = (c.jkr(min.a + h).force - c.jkr(min.a - h).force) / (2.0 * h);
            assert!(
                df.abs() < 1e-7 * min.force.abs() / min.a,
                "n = {n}: dF/da = {df}"
            );
            // No lower force on the stable branch a >= a_end.
            for k in 0..=2000 {
                let a = end.a * (1.0 + 4.0 * f64::from(k) / 2000.0);
                assert!(c.jkr(a).force >= min.force);
            }
            // Closed form of the minimum.
            let kendall_at_a = kendall_force(min.a, e, w);
            assert!(rel(min.force, -kendall_at_a * (1.0 - 1.5 / (n + 1.0))) < 1e-12);
            let d_k = kendall_approach(min.a, e, w);
            // (d = 0 exactly for n = 3/2, so compare on the scale of d_K.)
            assert!((min.d + d_k * (1.0 - 1.5 / n)).abs() < 1e-12 * d_k);
        }
    }

    #[test]
    fn force_minimum_lies_beyond_end_of_contact() {
        // a_F / a_end = 3^(1/(n − 1/2)) > 1 for every n > 1/2; the struct is
        // built directly to reach exponents below the constructor's range.
        for n in [0.51, 0.75, 1.0, 1.01, 1.5, 2.0, 3.0, 10.0, 100.0, 1000.0] {
            let c = PowerLawContact {
                n,
                scale: 0.8,
                e_star: 2.0,
                work_of_adhesion: 0.03,
            };
            let end = c.end_of_contact();
            let min = c.force_minimum();
            assert!(min.a > end.a, "n = {n}");
            assert!(rel(min.a / end.a, 3.0_f64.powf(1.0 / (n - 0.5))) < 1e-12);
            assert!(min.force < end.force, "n = {n}");
        }
    }

    #[test]
    fn normalised_minimum_is_invariant_for_n3() {
        let sets = [(1.0, 1.0, 1.0), (0.03, 2e6, 0.07), (250.0, 0.5, 40.0)];
        let kappa3 = 0.75 * PI;
        let a_bar = (2.0 * SQRT_2 / (3.0 * kappa3)).powf(1.0 / 2.5);
        let expected = -SQRT_2 * a_bar.powf(1.5) * (1.0 - 3.0 / 8.0);
        for (s, e, w) in sets {
            let c = contact(3.0, s, e, w);
            let (len, force, _) = c.scales();
            let min = c.force_minimum();
            assert!((min.force / force - expected).abs() < 1e-12, "s = {s}");
            assert!(rel(min.a / len, a_bar) < 1e-12, "s = {s}");
        }
    }

    #[test]
    fn kendall_flat_punch_limit() {
        // Units with the punch radius = 1 length; h(r) = (r / radius)ⁿ.
        // The minimum force is exactly −F_K(a_F)·(1 − 3/(2(n+1))), so against
        // the Kendall force of the actual pull-off radius it converges like
        // 3/(2n). The pull-off radius itself approaches the punch radius only
        // like 1 − ln(2nκ_n / (3√(2πΔγ/(E* radius)))) / n, so against
        // F_K(radius) the error is ~ (3/2)·ln(n)/n and depends on
        // Δγ/(E* radius): about 5 % at n = 400 for the value used here.
        let (radius, e, w) = (1.0_f64, 1.0, 1e-4);
        let f_k = kendall_force(radius, e, w);
        let d_k = kendall_approach(radius, e, w);
        assert!(rel(d_k, (2.0 * PI * w * radius / e).sqrt()) < 1e-14);
        eprintln!("Kendall limit, Δγ/(E* radius) = {:e}", w / (e * radius));
        eprintln!("    n    a_F/radius  F/F_K(radius)  F/F_K(a_F)  d/d_K(radius)");
        let mut last_error = f64::INFINITY;
        let mut last_a = 0.0;
        for n in [20.0, 50.0, 100.0, 200.0, 400.0, 1000.0] {
            let c = contact(n, radius.powf(-n), e, w);
            let min = c.force_minimum();
            let ratio_radius = -min.force / f_k;
            let ratio_local = -min.force / kendall_force(min.a, e, w);
            let ratio_d = -min.d / d_k;
            eprintln!(
                "{n:5}    {:.6}    {ratio_radius:.6}     {ratio_local:.6}    {ratio_d:.6}",
                min.a / radius
            );
            // Against the punch of the actual pull-off radius: exactly
            // 1 − 3/(2(n+1)).
            assert!(rel(ratio_local, 1.0 - 1.5 / (n + 1.0)) < 1e-12);
            // Monotone convergence to the punch of the indenter's radius.
            assert!(min.a > last_a && min.a < radius);
            assert!(1.0 - ratio_radius < last_error);
            last_error = 1.0 - ratio_radius;
            last_a = min.a;
            if n == 400.0 {
                assert!((ratio_local - 1.0).abs() < 0.02);
            }
        }
    }
}
