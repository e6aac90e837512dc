//! The cone h = r·cot α: the power law of n = 1, its first contact and its pull-off the method
//! of dimensionality reduction's closed forms: F(a) = (π/2)E* cot α a² − √(8πE*Δγ) a^{3/2},
//! d(a) = (π/2) cot α a − √(2πΔγa/E*). Under displacement control the force is least at
//! a_F = 18 Δγ tan²α / (π E*) and d_F = 3 Δγ tan α / E*, where |F| = 54 Δγ² tan³α / (π E*),
//! and the contact ends at a_F/9 and d = −Δγ tan α / E*. The cone's results are normalised by
//! its own pull-off, as Kendall's normalise the flat punch's: forces by |F|, lengths by 2 a_F,
//! approaches by the way from the force minimum to the end, 4 Δγ tan α / E*. Its exact
//! adhesive force is then F̄ = 1, at c̄ = 1/2 and d̄ = 3/4, and it jumps off at d̄ = −1/4, for
//! every angle, E* and Δγ.
//!
//! The scales put the cone where the model's defaults, set in normalised units on the sphere,
//! expect a pull-off: the sphere's force minimum lies at c̄ = 0.79 and the first contact at
//! c̄0 = 1.5, where its JKR branch is compressive; the cone's at c̄ = 1/2 with c̄0 = 1.5 three
//! times as wide (F̄ = +6.2 there). In the power law's scales c_1, R_1 the cone's minimum would
//! lie at c̄ = 3.24, beyond the first contact; with a_F as the length, c̄0 = 1.5 holds a
//! tensile contact (F̄ = −0.6 on its branch), and a coarse grid's first detachment, from the
//! pinned first contact, overshoots to near the minimum and is confirmed as it (measured:
//! |min F̄| = 0.986 on 32², against 1.30 from the true minimum).

use super::power_law::{mdr_adhesive_force, mdr_hint, PowerLaw};
use super::{FirstContact, IndenterShape, PullOffHint};
use crate::params::limits::{MAX_HALF_ANGLE, MIN_HALF_ANGLE};
use crate::params::HALF_ANGLE;
use crate::scene::{check, Scales, SceneError};
use crate::text::compact;
use crate::theory::power_law::PowerLawContact;
use std::f64::consts::PI;

/// The cone's half-angle where none is given (degrees): a common AFM tip's.
pub const DEFAULT_HALF_ANGLE: f64 = 70.0;

/// A cone of half-angle α between its axis and its flank: h = r·cot α, r = √(x² + y²)
/// (length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cone {
    /// The half-angle α (degrees), in [[`MIN_HALF_ANGLE`], [`MAX_HALF_ANGLE`]].
    half_angle: f64,
    /// cot α (dimensionless), computed once: the height of every node needs it.
    slope: f64,
}

impl Cone {
    /// The cone of half-angle `half_angle` (degrees, between its axis and its flank; checked
    /// by [`IndenterShape::check`]).
    pub fn new(half_angle: f64) -> Cone {
        Cone {
            half_angle,
            slope: 1.0 / half_angle.to_radians().tan(),
        }
    }

    /// The half-angle α (degrees).
    pub fn half_angle(&self) -> f64 {
        self.half_angle
    }

    /// cot α (dimensionless): the flank's slope.
    pub fn slope(&self) -> f64 {
        self.slope
    }

    /// The power law the cone is: n = 1, factor cot α.
    fn law(&self) -> PowerLaw {
        PowerLaw {
            n: 1.0,
            scale: self.slope,
        }
    }

    /// The closed forms for E* (force/length²) and Δγ (force/length).
    fn contact(&self, e_star: f64, work_of_adhesion: f64) -> PowerLawContact {
        self.law().contact(e_star, work_of_adhesion)
    }
}

impl IndenterShape for Cone {
    fn name(&self) -> &'static str {
        "cone"
    }

    fn describe(&self) -> String {
        format!("cone h = r·cot α, α = {}°", compact(self.half_angle))
    }

    fn tag(&self) -> String {
        format!("cone-a{}", self.half_angle)
    }

    fn normalised_by(&self) -> String {
        "the cone's pull-off: twice its contact radius, its force, the approach to the end"
            .to_string()
    }

    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("half_angle", self.half_angle)]
    }

    fn check(&self) -> Result<(), SceneError> {
        check(
            HALF_ANGLE,
            self.half_angle,
            (MIN_HALF_ANGLE..=MAX_HALF_ANGLE).contains(&self.half_angle),
            &format!(
                "a half-angle α in [{MIN_HALF_ANGLE}, {MAX_HALF_ANGLE}] degrees (between the \
                 axis and the flank)"
            ),
        )
    }

    fn height(&self, x: f64, y: f64, _e_star: f64, _work_of_adhesion: f64) -> f64 {
        self.slope * (x * x + y * y).sqrt()
    }

    /// 2 a_F = 36 Δγ tan²α / (π E*), 54 Δγ² tan³α / (π E*) and 4 Δγ tan α / E*.
    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        let tan = 1.0 / self.slope;
        let end = work_of_adhesion * tan / e_star;
        Scales {
            length: 36.0 / PI * end * tan,
            force: 54.0 / PI * work_of_adhesion * end * tan * tan,
            approach: 4.0 * end,
        }
    }

    /// The non-adhesive contact of radius `c`; its pressure is the mean F/(πc²), the
    /// centre's being infinite (logarithmically) under a cone's tip.
    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        let first = self.law().first_contact(c, e_star, work_of_adhesion)?;
        Ok(FirstContact {
            p0: first.force / (PI * c * c),
            ..first
        })
    }

    fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint> {
        let p = self.contact(e_star, work_of_adhesion);
        Some(mdr_hint(&p, self.scales(e_star, work_of_adhesion)))
    }

    fn exact_adhesive_force(
        &self,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        let p = self.contact(e_star, work_of_adhesion);
        let f = mdr_adhesive_force(&p, self.scales(e_star, work_of_adhesion));
        Some(("JKR (cone)", f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The MDR closed forms of the issue, written out for the cone, against the power law's
    /// general ones at n = 1: the branch, the force minimum and its place.
    #[test]
    fn the_cone_is_the_power_law_of_exponent_one_in_closed_form() {
        let (e, w) = (2.0, 0.3);
        for alpha in [MIN_HALF_ANGLE, 45.0, 70.0, 85.0] {
            let cone = Cone::new(alpha);
            let cot = cone.slope();
            assert!((cot - 1.0 / alpha.to_radians().tan()).abs() < 1e-15);
            let p = cone.contact(e, w);
            for a in [0.01, 0.3, 2.0] {
                let b = p.jkr(a);
                let f = PI / 2.0 * e * cot * a * a - (8.0 * PI * e * w).sqrt() * a.powf(1.5);
                let d = PI / 2.0 * cot * a - (2.0 * PI * w * a / e).sqrt();
                assert!(
                    (b.force - f).abs() <= 1e-12 * f.abs().max(1.0),
                    "{b:?} vs {f}"
                );
                assert!((b.d - d).abs() <= 1e-12 * d.abs().max(1.0), "{b:?} vs {d}");
            }
            let tan = alpha.to_radians().tan();
            let min = p.force_minimum();
            let exact = 54.0 * w * w * tan.powi(3) / (PI * e);
            assert!(
                (min.force + exact).abs() <= 1e-12 * exact,
                "{min:?} vs {exact}"
            );
            assert!((min.a / p.end_of_contact().a - 9.0).abs() < 1e-9);
            // Normalised by its own pull-off: F̄ = 1 at c̄ = 1/2 and d̄ = 3/4, the end at d̄ = −1/4.
            let (name, f_bar) = cone.exact_adhesive_force(e, w).unwrap();
            assert_eq!(name, "JKR (cone)");
            assert!((f_bar - 1.0).abs() < 1e-12, "{f_bar}");
            let hint = cone.pull_off_hint(e, w).unwrap();
            assert!((hint.b_bar_at_min - 0.5).abs() < 1e-12, "{hint:?}");
            assert!((hint.end_d_bar + 0.25).abs() < 1e-12, "{hint:?}");
            let s = cone.scales(e, w);
            assert!((min.d / s.approach - 0.75).abs() < 1e-12, "{min:?}");
            assert!((s.length - 36.0 * w * tan * tan / (PI * e)).abs() <= 1e-12 * s.length);
        }
    }

    #[test]
    fn a_cone_is_its_flank_and_checks_its_angle() {
        let cone = Cone::new(60.0);
        let h = cone.height(0.3, 0.4, 1.0, 1.0);
        assert!((h - 0.5 / 3f64.sqrt()).abs() < 1e-15, "{h}");
        let fc = cone.first_contact(0.5, 1.0, 1.0).unwrap();
        assert!(fc.p0.is_finite() && (fc.p0 - fc.force / (PI * 0.25)).abs() < 1e-15);
        for bad in [0.0, MIN_HALF_ANGLE - 1.0, 90.0, f64::NAN] {
            let e = Cone::new(bad).check().unwrap_err();
            assert_eq!(e.param(), HALF_ANGLE);
        }
    }
}
