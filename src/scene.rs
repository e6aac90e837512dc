//! What the user described: the indenter's radii, the material and the adhesion, and the
//! normalisation (physics §2) that every output uses. Knows nothing of grids or FFTs.

use crate::text::compact;
use std::f64::consts::PI;
use thiserror::Error;

/// Largest axis ratio R1/R2 accepted (dimensionless). The study goes to 50; beyond about
/// 1000 the contact is a thin strip that no grid of [`crate::model::MAX_GRID`] columns
/// resolves across its minor axis from the default c̄0.
pub const MAX_RATIO: f64 = 1000.0;

/// Smallest dimensional input accepted (R1, R2, E*, Δγ, in the user's units). With every
/// input in [`MIN_INPUT`, `MAX_INPUT`] every scale of the problem (c_r, the approach scale,
/// σ_c, forces) and its square stay far inside the range of f64.
pub const MIN_INPUT: f64 = 1e-30;

/// Largest dimensional input accepted (see [`MIN_INPUT`]).
pub const MAX_INPUT: f64 = 1e30;

/// An invalid scene parameter, named as the command-line flag that sets it.
#[derive(Debug, Error, PartialEq)]
pub enum SceneError {
    /// A parameter is outside its valid range.
    #[error("{flag} = {} is invalid: {expected}", compact(*value))]
    Invalid {
        /// The flag that sets the parameter.
        flag: &'static str,
        /// The value given.
        value: f64,
        /// The valid range, in words.
        expected: String,
    },
}

impl SceneError {
    /// The same error naming its parameter by the front end's flag (`rename` maps the
    /// library's name, e.g. "--angle", to the flag that sets it there, e.g. "--angles").
    pub fn renamed(self, rename: &dyn Fn(&'static str) -> &'static str) -> SceneError {
        match self {
            SceneError::Invalid {
                flag,
                value,
                expected,
            } => SceneError::Invalid {
                flag: rename(flag),
                value,
                expected,
            },
        }
    }
}

/// A rigid ellipsoid h = x²/(2 R1) + y²/(2 R2) on an elastic half-space, with JKR adhesion.
///
/// Lengths are in the user's length unit L, E* and Δγ in consistent units (E* in F/L²,
/// Δγ in F/L), so that forces come out in F.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scene {
    /// Radius of curvature along x, the contact's major axis (length). R1 ≥ R2.
    pub r1: f64,
    /// Radius of curvature along y, the minor axis (length).
    pub r2: f64,
    /// Effective modulus E* = E/(1 − ν²) (force / length²).
    pub e_star: f64,
    /// Work of adhesion Δγ (energy / area = force / length).
    pub work_of_adhesion: f64,
}

fn check(flag: &'static str, value: f64, ok: bool, expected: &str) -> Result<(), SceneError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SceneError::Invalid {
            flag,
            value,
            expected: expected.to_string(),
        })
    }
}

/// Whether a dimensional input lies in [`MIN_INPUT`, `MAX_INPUT`].
pub fn input_in_range(v: f64) -> bool {
    (MIN_INPUT..=MAX_INPUT).contains(&v)
}

/// The valid range of a dimensional input, in words.
fn input_range(what: &str) -> String {
    format!(
        "{what} in [{}, {}] (any consistent units; the normalised results do not depend on them)",
        compact(MIN_INPUT),
        compact(MAX_INPUT)
    )
}

impl Scene {
    /// A scene from the two radii (length), E* (force/length²) and Δγ (force/length).
    pub fn new(r1: f64, r2: f64, e_star: f64, work_of_adhesion: f64) -> Result<Self, SceneError> {
        check("--r2", r2, input_in_range(r2), &input_range("a radius"))?;
        check("--r1", r1, input_in_range(r1), &input_range("a radius"))?;
        check(
            "--r1",
            r1,
            r1 >= r2,
            "R1 must be ≥ R2 (x is the major axis)",
        )?;
        check(
            "--r1",
            r1,
            r1 / r2 <= MAX_RATIO,
            &format!("R1/R2 = {} must be ≤ {MAX_RATIO}", compact(r1 / r2)),
        )?;
        check(
            "--e-star",
            e_star,
            input_in_range(e_star),
            &input_range("a modulus"),
        )?;
        check(
            "--work-of-adhesion",
            work_of_adhesion,
            input_in_range(work_of_adhesion),
            &input_range("an energy per area"),
        )?;
        Ok(Scene {
            r1,
            r2,
            e_star,
            work_of_adhesion,
        })
    }

    /// A scene from the ratio R1/R2 (≥ 1, dimensionless) and R2 (length).
    pub fn from_ratio(
        ratio: f64,
        r2: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<Self, SceneError> {
        check(
            "--ratio",
            ratio,
            (1.0..=MAX_RATIO).contains(&ratio),
            &format!("R1/R2 must be in [1, {MAX_RATIO}]"),
        )?;
        Scene::new(ratio * r2, r2, e_star, work_of_adhesion)
    }

    /// R1/R2 (dimensionless).
    pub fn ratio(&self) -> f64 {
        self.r1 / self.r2
    }

    /// Equivalent radius Re = √(R1 R2) (length).
    pub fn re(&self) -> f64 {
        (self.r1 * self.r2).sqrt()
    }

    /// Indenter height h(x, y) = x²/(2R1) + y²/(2R2) (length) at (x, y) (length).
    pub fn profile(&self, x: f64, y: f64) -> f64 {
        x * x / (2.0 * self.r1) + y * y / (2.0 * self.r2)
    }

    /// The normalisation scales of physics §2.
    pub fn scales(&self) -> Scales {
        let re = self.re();
        let c_r = (9.0 * PI * re * re * self.work_of_adhesion / (4.0 * self.e_star)).cbrt();
        Scales {
            length: c_r,
            force: 3.0 * PI * re * self.work_of_adhesion,
            approach: c_r * c_r / re,
        }
    }
}

/// Scales that make quantities dimensionless: x̄ = x / scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    /// c_r = (9π Re² Δγ / (4E*))^(1/3) (length): contact radii and half-axes.
    pub length: f64,
    /// 3π Re Δγ (force).
    pub force: f64,
    /// c_r² / Re (length): the approach d.
    pub approach: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn approach_scale_matches_spec_formula() {
        // d̄ = d · (4E*/(9π Δγ √Re))^(2/3) must equal d · Re / c_r².
        let s = Scene::new(7.0, 2.0, 3.0, 0.5).unwrap();
        let direct =
            (4.0 * s.e_star / (9.0 * PI * s.work_of_adhesion * s.re().sqrt())).powf(2.0 / 3.0);
        assert!((1.0 / s.scales().approach / direct - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_values_name_their_flag() {
        let e = Scene::from_ratio(0.5, 1.0, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("--ratio"));
        let e = Scene::from_ratio(f64::NAN, 1.0, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("--ratio"));
        let e = Scene::from_ratio(2.0, 1.0, -1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("--e-star"));
        let e = Scene::from_ratio(2.0, 1.0, 1.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("--work-of-adhesion"));
        let e = Scene::from_ratio(2.0, 0.0, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("--r2"));
    }

    #[test]
    fn inputs_are_bounded_and_echoed_short() {
        for (e, flag) in [
            (Scene::from_ratio(1e8, 1.0, 1.0, 1.0), "--ratio"),
            (Scene::from_ratio(2.0, 1.0, 1e300, 1.0), "--e-star"),
            (Scene::from_ratio(2.0, 1.0, 1e-300, 1.0), "--e-star"),
            (
                Scene::from_ratio(2.0, 1.0, 1.0, 1e-300),
                "--work-of-adhesion",
            ),
            (Scene::new(2e3, 1.0, 1.0, 1.0), "--r1"),
        ] {
            let e = e.unwrap_err().to_string();
            assert!(e.contains(flag), "{e}");
            assert!(e.len() < 200, "{e}");
        }
        let e = Scene::from_ratio(2.0, 1.0, 1e300, 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--e-star = 1e300 is invalid"), "{e}");
        assert!(Scene::from_ratio(MAX_RATIO, 1.0, MAX_INPUT, MIN_INPUT).is_ok());
    }
}
