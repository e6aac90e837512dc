//! Two identical elastic cylinders crossed at an angle, as the equivalent ellipsoid scene
//! (physics §1, §8.7).

use crate::params::{Spec, ANGLE, E_STAR, POISSON, RADIUS, RATIO, WORK_OF_ADHESION, YOUNG};
use crate::scene::{self, Scene, SceneError, MAX_RATIO};
use crate::text::compact;

pub use crate::params::limits::MIN_POISSON;

/// Two identical elastic cylinders of radius R whose axes cross at angle θ, with JKR
/// adhesion between them. Units as for [`Scene`]: with R in m, E in Pa and Δγ in J/m²,
/// forces come out in N.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossedCylinders {
    /// Radius R of each cylinder (length).
    pub radius: f64,
    /// Crossing angle θ between the axes (degrees, in (0, 90]; 90° is sphere-like).
    pub angle_deg: f64,
    /// Young's modulus E of each cylinder (force/length²).
    pub young: f64,
    /// Poisson's ratio ν of each cylinder (dimensionless, in (−1, 0.5]).
    pub poisson: f64,
    /// Work of adhesion Δγ between them (energy/area = force/length).
    pub work_of_adhesion: f64,
}

fn invalid(param: &'static Spec, value: f64, expected: impl ToString) -> SceneError {
    SceneError::Invalid {
        param,
        value,
        expected: expected.to_string(),
    }
}

/// Smallest crossing angle accepted (degrees): the one at which R1/R2 = cot²(θ/2) reaches
/// [`MAX_RATIO`], θ = 2 arctan(1/√MAX_RATIO) ≈ 3.62°.
pub fn min_angle_deg() -> f64 {
    2.0 * MAX_RATIO.recip().sqrt().atan().to_degrees()
}

/// The range of crossing angles, in words.
fn angle_range() -> String {
    format!(
        "a crossing angle in degrees in [{}, 90] (90 is sphere-like; smaller angles than that \
         give R1/R2 > {MAX_RATIO})",
        compact_angle(min_angle_deg())
    )
}

/// An angle rounded up to 0.01° for messages.
fn compact_angle(a: f64) -> String {
    compact((a * 100.0).ceil() / 100.0)
}

impl CrossedCylinders {
    /// Checks every parameter, naming the offending one: [`RADIUS`], [`ANGLE`], [`YOUNG`],
    /// [`POISSON`] or [`WORK_OF_ADHESION`].
    pub fn validate(&self) -> Result<(), SceneError> {
        let bounded = |param, v: f64, what: &str| {
            if scene::input_in_range(v) {
                Ok(())
            } else {
                Err(invalid(
                    param,
                    v,
                    format!(
                        "{what} in [{}, {}] (any consistent units)",
                        compact(scene::MIN_INPUT),
                        compact(scene::MAX_INPUT)
                    ),
                ))
            }
        };
        bounded(RADIUS, self.radius, "a radius")?;
        let t = self.angle_deg;
        if !(t >= min_angle_deg() && t <= 90.0) {
            return Err(invalid(ANGLE, t, angle_range()));
        }
        bounded(YOUNG, self.young, "a Young's modulus")?;
        let nu = self.poisson;
        if !((MIN_POISSON..=0.5).contains(&nu)) {
            return Err(invalid(
                POISSON,
                nu,
                format!("a Poisson's ratio in [{MIN_POISSON}, 0.5] (0.5 is incompressible)"),
            ));
        }
        bounded(
            WORK_OF_ADHESION,
            self.work_of_adhesion,
            "an energy per area",
        )
    }

    /// (R1, R2) = (R/(1 − cos θ), R/(1 + cos θ)) (lengths), R1 ≥ R2. cos θ is evaluated as
    /// sin(90° − θ), which is exactly 0 at θ = 90°, so that case is an exact sphere (R1 = R2 = R).
    pub fn radii(&self) -> Result<(f64, f64), SceneError> {
        self.validate()?;
        let cos = (90.0 - self.angle_deg).to_radians().sin();
        Ok((self.radius / (1.0 - cos), self.radius / (1.0 + cos)))
    }

    /// Effective modulus of the pair, 1/E* = 2(1 − ν²)/E (force/length²).
    pub fn e_star(&self) -> Result<f64, SceneError> {
        self.validate()?;
        Ok(self.young / (2.0 * (1.0 - self.poisson * self.poisson)))
    }

    /// The equivalent rigid ellipsoid on an elastic half-space. An error names this pair's
    /// parameters ([`RADIUS`], [`YOUNG`], …), never the ellipsoid's ([`R1`](crate::params::R1),
    /// [`E_STAR`]).
    pub fn scene(&self) -> Result<Scene, SceneError> {
        let (r1, r2) = self.radii()?;
        Scene::new(r1, r2, self.e_star()?, self.work_of_adhesion).map_err(|e| {
            let SceneError::Invalid {
                param,
                value,
                expected,
            } = e
            else {
                // An ellipsoid's scene refuses only numbers.
                return e;
            };
            let (param, value) = if param == E_STAR {
                (YOUNG, self.young)
            } else if param == WORK_OF_ADHESION {
                (param, value)
            } else {
                (RADIUS, self.radius)
            };
            invalid(
                param,
                value,
                format!(
                    "{expected} (for the equivalent ellipsoid at {}°)",
                    self.angle_deg
                ),
            )
        })
    }

    /// The force scale 3π Re Δγ (force; N for SI inputs) with Re = R/sin θ: F = F̄ · scale.
    pub fn force_scale(&self) -> Result<f64, SceneError> {
        Ok(self.scene()?.scales().force)
    }
}

/// R1/R2 = cot²(θ/2) (dimensionless) of cylinders crossed at `angle_deg` (degrees, in (0, 90]).
pub fn ratio_for_angle(angle_deg: f64) -> Result<f64, SceneError> {
    if !(angle_deg > 0.0 && angle_deg <= 90.0) {
        return Err(invalid(ANGLE, angle_deg, "an angle in degrees in (0, 90]"));
    }
    Ok((0.5 * angle_deg).to_radians().tan().recip().powi(2))
}

/// The crossing angle θ = 2 arctan(√(R2/R1)) (degrees) that gives `ratio` = R1/R2
/// (dimensionless, finite, ≥ 1).
pub fn angle_for_ratio(ratio: f64) -> Result<f64, SceneError> {
    if !(ratio.is_finite() && ratio >= 1.0) {
        return Err(invalid(RATIO, ratio, "R1/R2 must be a finite number ≥ 1"));
    }
    Ok(2.0 * ratio.recip().sqrt().atan().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::R1;
    use std::f64::consts::PI;

    fn pair(angle_deg: f64) -> CrossedCylinders {
        CrossedCylinders {
            radius: 0.01,
            angle_deg,
            young: 1e6,
            poisson: 0.5,
            work_of_adhesion: 0.05,
        }
    }

    #[test]
    fn crossing_at_right_angles_is_a_sphere_of_the_cylinder_radius() {
        let s = pair(90.0).scene().unwrap();
        assert_eq!(s.indenter.radii(), Some((0.01, 0.01)));
        assert_eq!(s.ratio(), 1.0);
        // E* = E/(2(1 − ν²)) = 1e6/1.5 for ν = 1/2.
        assert!((s.e_star - 1e6 / 1.5).abs() < 1e-9);
    }

    #[test]
    fn axis_ratio_is_cot_squared_of_half_the_angle() {
        for angle in [5.0, 16.1, 30.0, 45.0, 60.0, 89.0] {
            let (r1, r2) = pair(angle).radii().unwrap();
            let cot_sq = ratio_for_angle(angle).unwrap();
            assert!((r1 / r2 / cot_sq - 1.0).abs() < 1e-12, "θ = {angle}°");
            // Re = √(R1 R2) = R/sin θ.
            let re = (r1 * r2).sqrt();
            assert!((re * angle.to_radians().sin() / 0.01 - 1.0).abs() < 1e-12);
            assert!((angle_for_ratio(r1 / r2).unwrap() - angle).abs() < 1e-10);
        }
    }

    #[test]
    fn sixteen_point_one_degrees_is_a_fifty_to_one_ellipsoid() {
        let ratio = pair(16.1).scene().unwrap().ratio();
        assert!((ratio / 50.0 - 1.0).abs() < 1e-3, "R1/R2 = {ratio}");
        let angle = angle_for_ratio(50.0).unwrap();
        assert!(
            (angle - 16.1).abs() < 0.005,
            "θ = {angle}° (16.1° to one decimal)"
        );
    }

    #[test]
    fn force_scale_is_three_pi_re_work_of_adhesion() {
        let c = pair(30.0);
        let re = c.radius / 30f64.to_radians().sin();
        let want = 3.0 * PI * re * c.work_of_adhesion;
        assert!((c.force_scale().unwrap() / want - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_parameters_name_their_parameter() {
        let param = |c: CrossedCylinders| c.scene().unwrap_err().param();
        let base = pair(45.0);
        for (c, want) in [
            (
                CrossedCylinders {
                    radius: -1.0,
                    ..base
                },
                RADIUS,
            ),
            (
                CrossedCylinders {
                    angle_deg: 0.0,
                    ..base
                },
                ANGLE,
            ),
            (
                CrossedCylinders {
                    angle_deg: 120.0,
                    ..base
                },
                ANGLE,
            ),
            (
                CrossedCylinders {
                    angle_deg: f64::NAN,
                    ..base
                },
                ANGLE,
            ),
            (CrossedCylinders { young: 0.0, ..base }, YOUNG),
            (
                CrossedCylinders {
                    poisson: -1.0,
                    ..base
                },
                POISSON,
            ),
            (
                CrossedCylinders {
                    poisson: 0.6,
                    ..base
                },
                POISSON,
            ),
            (
                CrossedCylinders {
                    work_of_adhesion: f64::INFINITY,
                    ..base
                },
                WORK_OF_ADHESION,
            ),
        ] {
            assert_eq!(param(c), want, "{c:?}");
        }
        assert!(CrossedCylinders {
            poisson: 0.5,
            ..base
        }
        .scene()
        .is_ok());
        assert!(ratio_for_angle(0.0).is_err() && angle_for_ratio(0.5).is_err());
    }

    #[test]
    fn a_tiny_angle_is_blamed_on_the_angle_not_on_a_radius() {
        // Before: θ = 1e-10° gave R1 = inf and the message named --r1, a flag `crossed` lacks.
        for angle in [1e-10, 1.0, 3.6] {
            let e = pair(angle).scene().unwrap_err().to_string();
            assert!(e.starts_with(&format!("{ANGLE} = ")), "{e}");
            assert!(!e.contains(&R1.to_string()) && !e.contains("inf"), "{e}");
        }
        assert!(pair(3.63).scene().is_ok());
        // A modulus out of range after the pair's E* = E/(2(1 − ν²)) names --young.
        let e = CrossedCylinders {
            young: 1e30,
            poisson: -0.99,
            ..pair(45.0)
        }
        .scene()
        .unwrap_err()
        .to_string();
        assert!(e.starts_with(&YOUNG.to_string()), "{e}");
    }
}
