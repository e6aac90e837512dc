//! The adhesion of a wavy surface (K. L. Johnson, "The adhesion of two elastic bodies with
//! slightly wavy surfaces", Int. J. Solids Struct. 32 (1995) 423–430), in plane strain: a
//! rigid wave h(x) = Δ(1 − cos 2πx/λ) against a flat elastic half-space of effective modulus
//! E* with JKR adhesion (work of adhesion Δγ), in contact on the strips |x − nλ| < a.
//!
//! Write ψ = πa/λ and s = sin ψ. The pressure is the sum of two periodic solutions on the
//! strips, both even in x and with u = d − h on the strips:
//!
//! - Westergaard's, with no stress at the strips' edges: p₁(x) = 2p* cos(πx/λ)·√(s² −
//!   sin²(πx/λ)), of mean p* s², where p* = πE*Δ/λ is the mean pressure of full contact;
//! - the periodic flat punches', of mean p̄₂: p₂(x) = p̄₂ cos(πx/λ)/√(s² − sin²(πx/λ))
//!   (its mean is p̄₂: with v = sin(πx/λ), ∫ dv/√(s² − v²) = π).
//!
//! Near an edge, s² − sin²(πx/λ) ≈ (π/λ) sin 2ψ (a − x), so p₂ ≈ −K/√(2π(a − x)) with the
//! stress-intensity factor K = −p̄₂ √(λ / tan ψ). Griffith's balance for the JKR crack,
//! G = K²/(2E*) = Δγ, gives p̄₂ = −√(2E*Δγ tan ψ / λ), so that the mean pressure of the
//! adhesive contact is Johnson's
//!
//! p̄/p* = sin² ψ − α √(tan ψ),   α = √(2λΔγ / (π² E* Δ²)),
//!
//! which at Δγ = 0 is Westergaard's p̄ = p* sin² ψ. [`Wave::stress_intensity`] is K for any
//! (a, p̄); the tests take it from the profile's edge instead and check G = Δγ, and check K
//! against the energy released by the punches' compliance (Irwin).
//!
//! The approach. The periodic operator sets the displacement's mean to zero (the
//! convention of [`crate::backend::kernel`]): d is measured from the mean plane of the
//! elastic surface, and the mean gap is Δ − d. In that convention the flat punches' approach
//! under the mean pressure p̄₂ is C p̄₂ with the compliance C(a) = (2λ/(πE*)) ln(1/sin ψ) (zero
//! at full contact, the isolated strip's logarithm as a → 0; its derivative gives the K
//! above through Irwin's G = ½ p̄₂² λ |dC/d(2a)|), and Betti's reciprocity between the
//! Westergaard state and the punches' gives d₁ = C p̄₁ + (1/λ)∫ p₂/p̄₂ · h = C p̄₁ + Δ sin² ψ.
//! So for any p̄ on the strips of half-width a
//!
//! d = Δ sin² ψ + (2λ p̄/(πE*)) ln(1/sin ψ).
//!
//! Stability and pull-off. Under load control a state is stable where p̄(a) rises with a.
//! f(ψ) = sin² ψ − α√(tan ψ) falls from 0, has a minimum at ψ₁ (the pull-off: the most
//! tensile mean pressure, [`Wave::pull_off_mean_pressure`]) and a maximum at ψ₂, then falls to −∞
//! at full contact, provided α < α_c = 3^{3/4} 5^{5/4}/16 ≈ 1.065 (f′ = 0 ⇔ α = 4 sin^{3/2} ψ
//! cos^{5/2} ψ, largest at tan² ψ = 3/5). Beyond α_c no partial contact is stable. At zero load
//! the surfaces jump spontaneously into full contact once f(ψ₂) < 0, i.e. for α > α₀ = 3^{3/4}/4
//! ≈ 0.570 (f = f′ = 0 at ψ = π/3), Johnson's 0.57. For α → 0 the pull-off tends to that of
//! an isolated JKR cylinder of the crest's radius R = λ²/(4π²Δ): p̄λ → −3(πE*RΔγ²/16)^{1/3}.
//! Under displacement control the contact jumps off at the smallest d(ψ) on the adhesive
//! branch ([`Wave::jump_off_approach`]).

use std::f64::consts::PI;

/// A wavy surface against a flat half-space (every quantity in consistent units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wave {
    /// Wavelength λ (length).
    pub lambda: f64,
    /// Amplitude Δ (length): h(x) = Δ(1 − cos 2πx/λ), peak to valley 2Δ.
    pub delta: f64,
    /// Effective modulus E* (stress).
    pub e_star: f64,
    /// Work of adhesion Δγ (energy per area; 0 for a non-adhesive contact).
    pub work_of_adhesion: f64,
}

/// α₀ = 3^{3/4}/4 (dimensionless): above it the surfaces jump into full contact at zero load.
pub fn alpha_spontaneous() -> f64 {
    3f64.powf(0.75) / 4.0
}

/// α_c = 3^{3/4} 5^{5/4}/16 (dimensionless): above it no partial contact is stable under
/// load control.
pub fn alpha_critical() -> f64 {
    3f64.powf(0.75) * 5f64.powf(1.25) / 16.0
}

impl Wave {
    /// The profile h(x) = Δ(1 − cos 2πx/λ) (length) at `x` (length).
    pub fn height(&self, x: f64) -> f64 {
        self.delta * (1.0 - (2.0 * PI * x / self.lambda).cos())
    }

    /// p* = πE*Δ/λ (stress): the mean pressure that brings the wave into full contact.
    pub fn p_star(&self) -> f64 {
        PI * self.e_star * self.delta / self.lambda
    }

    /// Johnson's α = √(2λΔγ/(π²E*Δ²)) (dimensionless).
    pub fn alpha(&self) -> f64 {
        (2.0 * self.lambda * self.work_of_adhesion / (PI * PI * self.e_star * self.delta.powi(2)))
            .sqrt()
    }

    /// ψ = πa/λ for the contact half-width `a` (length).
    fn psi(&self, a: f64) -> f64 {
        PI * a / self.lambda
    }

    /// Westergaard's mean pressure p* sin²(πa/λ) (stress) with no adhesion, for the contact
    /// half-width `a` (length, 0 < a < λ/2).
    pub fn westergaard_mean_pressure(&self, a: f64) -> f64 {
        self.p_star() * self.psi(a).sin().powi(2)
    }

    /// Johnson's adhesive mean pressure p*(sin² ψ − α √(tan ψ)) (stress) for the contact
    /// half-width `a` (length, 0 < a < λ/2).
    pub fn adhesive_mean_pressure(&self, a: f64) -> f64 {
        let psi = self.psi(a);
        self.p_star() * (psi.sin().powi(2) - self.alpha() * psi.tan().sqrt())
    }

    /// The stress-intensity factor K = (p* sin² ψ − p̄)·√(λ/tan ψ) (stress·√length) at the
    /// edges of strips of half-width `a` (length) carrying the mean pressure `p_mean`
    /// (stress); positive where the edge is in tension.
    pub fn stress_intensity(&self, a: f64, p_mean: f64) -> f64 {
        let psi = self.psi(a);
        (self.p_star() * psi.sin().powi(2) - p_mean) * (self.lambda / psi.tan()).sqrt()
    }

    /// The pressure (stress, compressive positive) at `x` (length, |x| < a) on strips of
    /// half-width `a` (length) carrying the mean pressure `p_mean` (stress): Westergaard's
    /// plus the flat punches' (see the module); 0 off the strips.
    pub fn pressure(&self, x: f64, a: f64, p_mean: f64) -> f64 {
        let s = self.psi(a).sin();
        let t = PI * x / self.lambda;
        let root2 = s * s - t.sin().powi(2);
        if x.abs() >= a || root2 <= 0.0 {
            return 0.0;
        }
        let root = root2.sqrt();
        let p1 = 2.0 * self.p_star() * t.cos() * root;
        let p2 = (p_mean - self.p_star() * s * s) * t.cos() / root;
        p1 + p2
    }

    /// The compliance C(a) = (2λ/(πE*)) ln(1/sin ψ) (length per stress) of the periodic flat
    /// punches: their approach, from the mean plane, per unit mean pressure.
    pub fn punch_compliance(&self, a: f64) -> f64 {
        -2.0 * self.lambda / (PI * self.e_star) * self.psi(a).sin().ln()
    }

    /// The approach d = Δ sin² ψ + C(a) p̄ (length, from the mean plane of the elastic
    /// surface) of strips of half-width `a` (length) carrying the mean pressure `p_mean`
    /// (stress).
    pub fn approach(&self, a: f64, p_mean: f64) -> f64 {
        self.delta * self.psi(a).sin().powi(2) + self.punch_compliance(a) * p_mean
    }

    /// The half-width a (length) of the load-controlled pull-off: the minimum of Johnson's
    /// p̄(a), at ψ₁ where α = 4 sin^{3/2} ψ cos^{5/2} ψ on the rising side; `None` where
    /// α ≥ α_c (no stable partial contact) or Δγ = 0 (no tension).
    pub fn pull_off_half_width(&self) -> Option<f64> {
        let alpha = self.alpha();
        if !(alpha > 0.0 && alpha < alpha_critical()) {
            return None;
        }
        let g = |psi: f64| 4.0 * psi.sin().powf(1.5) * psi.cos().powf(2.5) - alpha;
        // g rises on (0, ψ*), ψ* = atan √(3/5), from −α to α_c − α.
        let (mut lo, mut hi) = (0.0, (0.6f64).sqrt().atan());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi) * self.lambda / PI)
    }

    /// The most tensile mean pressure (stress, negative) the strips hold under load control:
    /// Johnson's p̄ at [`Self::pull_off_half_width`].
    pub fn pull_off_mean_pressure(&self) -> Option<f64> {
        self.pull_off_half_width()
            .map(|a| self.adhesive_mean_pressure(a))
    }

    /// The approach (length, from the mean plane) along Johnson's adhesive branch at the
    /// half-width `a` (length).
    pub fn adhesive_approach(&self, a: f64) -> f64 {
        self.approach(a, self.adhesive_mean_pressure(a))
    }

    /// The jump-off under displacement control: the half-width (length) and approach
    /// (length, from the mean plane) where d(a) along the adhesive branch is smallest on
    /// (0, a₂), a₂ the maximum of p̄(a) (where it exists, else λ/2); `None` for Δγ = 0.
    /// Found by a scan and a golden-section refinement.
    pub fn jump_off_approach(&self) -> Option<(f64, f64)> {
        if self.work_of_adhesion <= 0.0 {
            return None;
        }
        let top = 0.5 * self.lambda * (1.0 - 1e-9);
        let n = 4000;
        let (mut best, mut best_d) = (0usize, f64::INFINITY);
        for i in 1..n {
            let a = top * i as f64 / n as f64;
            let d = self.adhesive_approach(a);
            if d < best_d {
                (best, best_d) = (i, d);
            }
        }
        let (mut lo, mut hi) = (
            top * (best - 1) as f64 / n as f64,
            top * (best + 1).min(n) as f64 / n as f64,
        );
        let r = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..200 {
            let (x1, x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
            if self.adhesive_approach(x1) < self.adhesive_approach(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        let a = 0.5 * (lo + hi);
        Some((a, self.adhesive_approach(a)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave(dg: f64) -> Wave {
        Wave {
            lambda: 2.0,
            delta: 0.05,
            e_star: 3.0,
            work_of_adhesion: dg,
        }
    }

    /// Simpson's rule on [lo, hi] with `n` (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, lo: f64, hi: f64, n: usize) -> f64 {
        let h = (hi - lo) / n as f64;
        let mut s = f(lo) + f(hi);
        for i in 1..n {
            s += f(lo + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    #[test]
    fn full_contact_pressure_is_the_continuum_one() {
        // p* = πE*Δ/λ: the single mode Δ cos(2πx/λ) needs E*|q|Δ/2 = p*.
        let w = wave(0.0);
        let q = 2.0 * PI / w.lambda;
        assert!((w.p_star() - w.e_star * q * w.delta / 2.0).abs() < 1e-15);
        // Westergaard at a → λ/2 is full contact's mean p*.
        assert!((w.westergaard_mean_pressure(0.5 * w.lambda) / w.p_star() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn adhesive_relation_without_adhesion_is_westergaards() {
        let (w, tiny) = (wave(0.0), wave(1e-20));
        for a in [0.05, 0.3, 0.6, 0.9] {
            assert_eq!(w.adhesive_mean_pressure(a), w.westergaard_mean_pressure(a));
            let d = tiny.adhesive_mean_pressure(a) - tiny.westergaard_mean_pressure(a);
            assert!(d < 0.0 && d.abs() < 1e-6 * w.p_star());
        }
    }

    #[test]
    fn profiles_have_the_means_they_are_given() {
        let w = wave(0.01);
        for (a, p_mean) in [
            (0.3, 0.02),
            (0.6, -0.01),
            (0.8, w.adhesive_mean_pressure(0.8)),
        ] {
            // ∫ over the strip with x = (λ/π) asin(s sin φ): the edge singularity is smoothed.
            let s = (PI * a / w.lambda).sin();
            let x = |phi: f64| w.lambda / PI * (s * phi.sin()).asin();
            let dx =
                |phi: f64| w.lambda / PI * s * phi.cos() / (1.0 - (s * phi.sin()).powi(2)).sqrt();
            let mean = simpson(
                |phi| w.pressure(x(phi), a, p_mean) * dx(phi),
                -0.5 * PI + 1e-6,
                0.5 * PI - 1e-6,
                4000,
            ) / w.lambda;
            // The ends left out (2e-6 of φ) hold about 1e-8 of p*.
            assert!(
                (mean - p_mean).abs() < 1e-6 * w.p_star(),
                "a = {a}: {mean} vs {p_mean}"
            );
        }
    }

    #[test]
    fn edge_stress_intensity_of_the_adhesive_branch_releases_the_work_of_adhesion() {
        // K from the profile's edge, K = lim √(2πr)·(−p(a − r)), against G = K²/(2E*) = Δγ.
        let w = wave(0.004);
        for a in [0.1, 0.4, 0.7, 0.95] {
            let p_mean = w.adhesive_mean_pressure(a);
            let k_at = |r: f64| -(2.0 * PI * r).sqrt() * w.pressure(a - r, a, p_mean);
            // The next term is O(r): extrapolate r → 0 from r and r/2.
            let r = 1e-7 * w.lambda;
            let k = 2.0 * k_at(r / 2.0) - k_at(r);
            let g = k * k / (2.0 * w.e_star);
            assert!(
                (g / w.work_of_adhesion - 1.0).abs() < 1e-5,
                "a = {a}: G = {g}"
            );
            assert!((k / w.stress_intensity(a, p_mean) - 1.0).abs() < 1e-5);
        }
    }

    #[test]
    fn stress_intensity_matches_the_energy_released_by_the_compliance() {
        // Irwin: for the punches alone, G = ½ p̄² λ |dC/d(2a)| (two edges per period) must be
        // K²/(2E*): the compliance and the profile's edge are the same solution.
        let w = wave(0.0);
        for a in [0.1, 0.5, 0.9] {
            let p_mean = -0.01;
            let h = 1e-5;
            let dc = (w.punch_compliance(a + h) - w.punch_compliance(a - h)) / (2.0 * h);
            let g_energy = 0.5 * p_mean * p_mean * w.lambda * dc.abs() / 2.0;
            // K of the punches alone: the Westergaard part has no edge stress.
            let k = -p_mean * (w.lambda / (PI * a / w.lambda).tan()).sqrt();
            let g_k = k * k / (2.0 * w.e_star);
            assert!(
                (g_energy / g_k - 1.0).abs() < 1e-8,
                "a = {a}: {g_energy} vs {g_k}"
            );
        }
    }

    #[test]
    fn pull_off_is_the_minimum_of_the_adhesive_relation() {
        let w = wave(0.004);
        assert!(w.alpha() < alpha_critical());
        let a1 = w.pull_off_half_width().unwrap();
        let p1 = w.pull_off_mean_pressure().unwrap();
        assert!(p1 < 0.0);
        for i in 1..2000 {
            let a = a1 * 2.0 * i as f64 / 2000.0;
            assert!(
                w.adhesive_mean_pressure(a) >= p1 - 1e-12 * w.p_star(),
                "a = {a}"
            );
        }
    }

    #[test]
    fn small_alpha_pull_off_is_the_jkr_cylinders() {
        // p̄λ → −3(πE*RΔγ²/16)^{1/3} with R = λ²/(4π²Δ), the crest's radius.
        let mut last = f64::INFINITY;
        for dg in [1e-5, 1e-7, 1e-9] {
            let w = wave(dg);
            let r = w.lambda.powi(2) / (4.0 * PI * PI * w.delta);
            let jkr = -3.0 * (PI * w.e_star * r * dg * dg / 16.0).cbrt();
            let dev = (w.pull_off_mean_pressure().unwrap() * w.lambda / jkr - 1.0).abs();
            assert!(dev < last, "α = {}: {dev}", w.alpha());
            last = dev;
        }
        assert!(last < 1e-3, "{last}");
    }

    #[test]
    fn johnsons_thresholds() {
        // α₀ ≈ 0.57: f(ψ₂) = 0 at the maximum; α_c: the maximum and minimum merge.
        assert!((alpha_spontaneous() - 0.5699).abs() < 1e-4);
        let f = |psi: f64, alpha: f64| psi.sin().powi(2) - alpha * psi.tan().sqrt();
        let psi = PI / 3.0;
        let a0 = alpha_spontaneous();
        assert!(f(psi, a0).abs() < 1e-14);
        let h = 1e-6;
        assert!(((f(psi + h, a0) - f(psi - h, a0)) / (2.0 * h)).abs() < 1e-8);
        // Just below α_c a pull-off exists, at and above it none.
        let for_alpha = |alpha: f64| Wave {
            work_of_adhesion: alpha * alpha * PI * PI * 3.0 * 0.05f64.powi(2) / (2.0 * 2.0),
            ..wave(0.0)
        };
        assert!((for_alpha(0.7).alpha() - 0.7).abs() < 1e-12);
        assert!(for_alpha(alpha_critical() * 0.999)
            .pull_off_half_width()
            .is_some());
        assert!(for_alpha(alpha_critical() * 1.001)
            .pull_off_half_width()
            .is_none());
        // Above α₀ Johnson's p̄ stays negative for every a: no equilibrium at zero load.
        let w = for_alpha(0.6);
        assert!((1..1000).all(|i| w.adhesive_mean_pressure(i as f64 / 1000.0) < 0.0));
        let w = for_alpha(0.5);
        assert!((1..1000).any(|i| w.adhesive_mean_pressure(i as f64 / 1000.0) > 0.0));
    }

    #[test]
    fn approach_limits() {
        let w = wave(0.004);
        // Full contact at d = Δ (mean gap zero), first touch at d = 0 with no load.
        assert!((w.approach(0.5 * w.lambda, 0.3) - w.delta).abs() < 1e-12);
        assert!(w.approach(1e-12, 0.0).abs() < 1e-20);
        // The jump-off under displacement control: adhesive (d < 0), and no later than
        // the load-controlled pull-off along the branch (d at the load minimum is larger).
        let (a, d) = w.jump_off_approach().unwrap();
        assert!(d < 0.0, "{d}");
        let a1 = w.pull_off_half_width().unwrap();
        assert!(a < a1, "{a} vs {a1}");
        assert!(d <= w.adhesive_approach(a1));
        assert!(wave(0.0).jump_off_approach().is_none());
    }
}
