//! The flat cylindrical punch: normalised by its radius and Kendall's pull-off, its first
//! contact the whole face.

use super::{FirstContact, IndenterShape, PullOffHint};
use crate::params::RADIUS;
use crate::scene::{check, input_in_range, input_range, Scales, SceneError};
use crate::text::compact;
use crate::theory::power_law::{kendall_approach, kendall_force};
use std::f64::consts::PI;

/// Height of the flat punch's walls above its face, in the larger of its radius and Kendall's
/// approach at pull-off (dimensionless): far beyond any gap the half-space can close (the
/// surface outside the face never rises above the approach, and no run presses beyond a few
/// Kendall approaches), so that nothing outside the face ever touches. In radii alone it was
/// not: a punch of radius 1e-7 with E* = Δγ = 1 is pressed 4000 radii deep.
const PUNCH_WALL: f64 = 1e3;

/// A flat cylindrical punch: h = 0 on the face r < radius, walls outside (length).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPunch {
    /// The face's radius a (length).
    pub radius: f64,
}

impl IndenterShape for FlatPunch {
    fn name(&self) -> &'static str {
        "flat-punch"
    }

    fn describe(&self) -> String {
        format!("flat punch of radius {}", compact(self.radius))
    }

    fn tag(&self) -> String {
        "flat-punch".to_string()
    }

    fn normalised_by(&self) -> String {
        "the punch's radius, Kendall's force and approach".into()
    }

    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![("radius", self.radius)]
    }

    fn check(&self) -> Result<(), SceneError> {
        check(
            RADIUS,
            self.radius,
            input_in_range(self.radius),
            &input_range("a punch radius"),
        )
    }

    fn height(&self, x: f64, y: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
        let radius = self.radius;
        if x * x + y * y < radius * radius {
            0.0
        } else {
            PUNCH_WALL * radius.max(kendall_approach(radius, e_star, work_of_adhesion))
        }
    }

    /// Its radius a, Kendall's pull-off force √(8π E* Δγ a³) and the approach at pull-off
    /// F/(2E* a).
    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        Scales {
            length: self.radius,
            force: kendall_force(self.radius, e_star, work_of_adhesion),
            approach: kendall_approach(self.radius, e_star, work_of_adhesion),
        }
    }

    /// The whole face pressed to half Kendall's pull-off approach (it does not depend on `c`).
    fn first_contact(
        &self,
        _c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        let radius = self.radius;
        let d = 0.5 * kendall_approach(radius, e_star, work_of_adhesion);
        Ok(FirstContact {
            a: radius,
            b: radius,
            d,
            force: 2.0 * e_star * radius * d,
            // The pressure at the face's centre (it is singular at the edge).
            p0: e_star * d / (PI * radius),
        })
    }

    fn pull_off_hint(&self, _e_star: f64, _work_of_adhesion: f64) -> Option<PullOffHint> {
        Some(PullOffHint {
            end_d_bar: -1.0,
            b_bar_at_min: 1.0,
        })
    }

    fn exact_adhesive_force(
        &self,
        _e_star: f64,
        _work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        Some(("Kendall", 1.0))
    }
}
