//! The closed form a state's pressure field is set beside: JKR's for a sphere (an ellipsoid of
//! R1 = R2, or the power law of n = 2), at the state's own contact radius and approach.

use crate::scene::Scene;
use crate::theory::jkr::jkr_pressure;

/// A sphere's JKR closed form: what [`jkr_pressure`] needs beyond the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JkrSphere {
    /// The sphere's radius R (length).
    pub radius: f64,
    /// The effective modulus E* (force/length²).
    pub e_star: f64,
}

impl JkrSphere {
    /// The closed form of `scene`'s indenter where it has one: the sphere, as an ellipsoid of
    /// R1 = R2 or a power law of n = 2 (h = s r², R = 1/(2s)). `None` for every other shape,
    /// rough spheres and height maps among them.
    pub fn of(scene: &Scene) -> Option<JkrSphere> {
        let radius = scene.indenter.shape().sphere_radius()?;
        Some(JkrSphere {
            radius,
            e_star: scene.e_star,
        })
    }

    /// JKR's pressure (force/length²) at distance `r` (length) from the apex for the state of
    /// mean contact radius `a` and approach `d` (length).
    pub fn pressure(&self, r: f64, a: f64, d: f64) -> f64 {
        jkr_pressure(r, a, d, self.radius, self.e_star)
    }
}
