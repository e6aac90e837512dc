//! The axisymmetric power law h = s·rⁿ: normalised by its own c_n and R_n (the sphere's at
//! n = 2), its first contact and pull-off the method of dimensionality reduction's.

use super::{FirstContact, IndenterShape, PullOffHint};
use crate::params::limits::{MAX_EXPONENT, MIN_EXPONENT};
use crate::params::{EXPONENT, SCALE};
use crate::scene::{check, input_in_range, input_range, Scales, SceneError};
use crate::text::compact;
use crate::theory::power_law::PowerLawContact;

/// The power law's factor s of h = s·rⁿ where none is given (length^(1−n)): with n = 2,
/// s = 1/(2R) = 0.5 is the sphere of radius 1.
pub const DEFAULT_POWER_LAW_SCALE: f64 = 0.5;

/// Axisymmetric h = scale·rⁿ, r = √(x² + y²) (length); n = 2 is the sphere of radius
/// 1/(2·scale).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    /// The exponent n (dimensionless), in [[`MIN_EXPONENT`], [`MAX_EXPONENT`]].
    pub n: f64,
    /// The factor s (length^(1−n)).
    pub scale: f64,
}

impl PowerLaw {
    /// The closed forms for E* (force/length²) and Δγ (force/length).
    pub(super) fn contact(&self, e_star: f64, work_of_adhesion: f64) -> PowerLawContact {
        PowerLawContact {
            n: self.n,
            scale: self.scale,
            e_star,
            work_of_adhesion,
        }
    }
}

impl IndenterShape for PowerLaw {
    fn name(&self) -> &'static str {
        "power-law"
    }

    fn describe(&self) -> String {
        format!(
            "power law h = s·rⁿ, n = {}, s = {}",
            compact(self.n),
            compact(self.scale)
        )
    }

    fn tag(&self) -> String {
        format!("power-law-n{}", self.n)
    }

    fn normalised_by(&self) -> String {
        "the power law's c_n, 3πR_nΔγ, c_n²/R_n".to_string()
    }

    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("exponent", self.n), ("scale", self.scale)]
    }

    fn check(&self) -> Result<(), SceneError> {
        let (n, scale) = (self.n, self.scale);
        check(
            EXPONENT,
            n,
            (MIN_EXPONENT..=MAX_EXPONENT).contains(&n),
            &format!("an exponent n in [{MIN_EXPONENT}, {MAX_EXPONENT}] (2 is the sphere)"),
        )?;
        check(
            SCALE,
            scale,
            input_in_range(scale),
            &input_range("the factor s of h = s·rⁿ (length^(1−n))"),
        )?;
        // Every scale of the problem must stay finite: the length scale c_n.
        let probe = PowerLawContact::new(n, scale, 1.0, 1.0).map_err(|e| SceneError::Invalid {
            param: SCALE,
            value: scale,
            expected: e,
        })?;
        let (length, _, _) = probe.scales();
        check(
            SCALE,
            scale,
            length.is_finite() && length > 0.0,
            "a factor whose contact length scale is finite; rescale the units",
        )
    }

    fn height(&self, x: f64, y: f64, _e_star: f64, _work_of_adhesion: f64) -> f64 {
        self.scale * (x * x + y * y).sqrt().powf(self.n)
    }

    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        mdr_scales(&self.contact(e_star, work_of_adhesion))
    }

    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        let p = self.contact(e_star, work_of_adhesion);
        Ok(FirstContact {
            a: c,
            b: c,
            d: p.hertz_approach(c),
            force: p.hertz_force(c),
            p0: p.hertz_peak_pressure(c),
        })
    }

    fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint> {
        let p = self.contact(e_star, work_of_adhesion);
        Some(mdr_hint(&p, mdr_scales(&p)))
    }

    fn exact_adhesive_force(
        &self,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        let p = self.contact(e_star, work_of_adhesion);
        Some(("JKR (power law)", mdr_adhesive_force(&p, mdr_scales(&p))))
    }

    fn sphere_radius(&self) -> Option<f64> {
        (self.n == 2.0).then_some(0.5 / self.scale)
    }
}

/// The scales of an axisymmetric power-law contact `p` (its c_n, 3πR_nΔγ, c_n²/R_n).
fn mdr_scales(p: &PowerLawContact) -> Scales {
    let (length, force, approach) = p.scales();
    Scales {
        length,
        force,
        approach,
    }
}

/// Where the method of dimensionality reduction puts `p`'s pull-off, normalised by the
/// scales `s` (the power law's [`mdr_scales`], or a shape's own).
pub(super) fn mdr_hint(p: &PowerLawContact, s: Scales) -> PullOffHint {
    PullOffHint {
        end_d_bar: p.end_of_contact().d / s.approach,
        b_bar_at_min: p.force_minimum().a / s.length,
    }
}

/// `p`'s exact adhesive force under displacement control, normalised by the scales `s`.
pub(super) fn mdr_adhesive_force(p: &PowerLawContact, s: Scales) -> f64 {
    -p.force_minimum().force / s.force
}
