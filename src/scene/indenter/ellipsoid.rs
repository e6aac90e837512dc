//! The ellipsoid h = x²/(2 R1) + y²/(2 R2): the study's shape, normalised by physics §2, its
//! first contact Hertz's ellipse and its pull-off JKR's or Johnson–Greenwood's.

use super::{FirstContact, IndenterShape, PullOffHint};
use crate::scene::Scales;
use crate::text::compact;
use crate::theory::{self, TheoryModel};
use std::f64::consts::PI;

/// An ellipsoid of radii of curvature R1 ≥ R2 (length): x is the contact's major axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// Radius of curvature along x (length).
    pub r1: f64,
    /// Radius of curvature along y (length).
    pub r2: f64,
}

impl IndenterShape for Ellipsoid {
    fn name(&self) -> &'static str {
        "ellipsoid"
    }

    fn describe(&self) -> String {
        format!(
            "ellipsoid R1 = {}, R2 = {} (R1/R2 = {})",
            compact(self.r1),
            compact(self.r2),
            compact(self.r1 / self.r2)
        )
    }

    fn tag(&self) -> String {
        format!("r{}", self.r1 / self.r2)
    }

    fn normalised_by(&self) -> String {
        "the ellipsoid's c_r, 3πRΔγ, c_r²/R".to_string()
    }

    fn parameters(&self) -> Vec<(&'static str, f64)> {
        vec![
            ("r1", self.r1),
            ("r2", self.r2),
            ("ratio", self.r1 / self.r2),
        ]
    }

    fn height(&self, x: f64, y: f64, _e_star: f64, _work_of_adhesion: f64) -> f64 {
        x * x / (2.0 * self.r1) + y * y / (2.0 * self.r2)
    }

    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        ellipsoid_scales(self.r1, self.r2, e_star, work_of_adhesion)
    }

    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        _work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        theory::hertz::hertz_for_mean_radius(self.r1, self.r2, e_star, c)
            .map(FirstContact::from)
            .map_err(|e| e.to_string())
    }

    fn pull_off_hint(&self, _e_star: f64, _work_of_adhesion: f64) -> Option<PullOffHint> {
        ellipsoid_hint(self.r1 / self.r2)
    }

    fn exact_adhesive_force(
        &self,
        _e_star: f64,
        _work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        (self.r1 == self.r2).then_some(("JKR", 0.5))
    }

    fn ellipsoid_like(&self) -> Option<(f64, f64)> {
        Some((self.r1, self.r2))
    }

    fn sphere_radius(&self) -> Option<f64> {
        (self.r1 == self.r2).then_some(self.r1)
    }
}

/// Physics §2's scales of an ellipsoid of radii R1, R2 (length), for E* (force/length²) and
/// Δγ (force/length).
pub(crate) fn ellipsoid_scales(r1: f64, r2: f64, e_star: f64, work_of_adhesion: f64) -> Scales {
    let re = (r1 * r2).sqrt();
    let c_r = (9.0 * PI * re * re * work_of_adhesion / (4.0 * e_star)).cbrt();
    Scales {
        length: c_r,
        force: 3.0 * PI * re * work_of_adhesion,
        approach: c_r * c_r / re,
    }
}

/// The pull-off of the adhesive reference theory (JKR for the sphere, JG otherwise) for an
/// ellipsoid of axis ratio `ratio` (dimensionless), normalised.
pub(crate) fn ellipsoid_hint(ratio: f64) -> Option<PullOffHint> {
    let p = theory::pull_off(TheoryModel::adhesive_reference(ratio), ratio).ok()?;
    Some(PullOffHint {
        end_d_bar: p.end_of_contact.d_bar,
        b_bar_at_min: p.force_min.b_bar,
    })
}
