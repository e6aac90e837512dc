//! What the user described: the indenter ([`Indenter`]), the material and the adhesion, and
//! the normalisation (physics §2) that every output uses. Knows nothing of grids or FFTs.

pub mod height_map;
pub mod indenter;
mod measured;
mod rough;
pub mod roughness;

pub use indenter::{
    FirstContact, Indenter, IndenterShape, PullOffHint, DEFAULT_POWER_LAW_SCALE, MAX_EXPONENT,
    MIN_EXPONENT,
};
pub use measured::{MeasuredSurface, Placement};
pub use rough::RoughShape;

use crate::params::{Spec, E_STAR, R1, R2, RATIO, WORK_OF_ADHESION};
use crate::text::compact;
use thiserror::Error;

pub use crate::params::limits::MAX_RATIO;

pub use crate::params::limits::MIN_INPUT;

pub use crate::params::limits::MAX_INPUT;

/// An invalid scene parameter, named by its [`Spec`] (which each front end words: the
/// command line as its flag, Python as its keyword).
#[derive(Debug, Error, PartialEq)]
pub enum SceneError {
    /// A parameter is outside its valid range.
    #[error("{param} = {} is invalid: {expected}", compact(*value))]
    Invalid {
        /// The parameter.
        param: &'static Spec,
        /// The value given.
        value: f64,
        /// The valid range, in words.
        expected: String,
    },
    /// An input that is not a number (a file) cannot be used, for the reason given.
    #[error("{param} {why}")]
    Refused {
        /// The parameter that gives the input.
        param: &'static Spec,
        /// What is wrong, starting with the input's name.
        why: String,
    },
}

impl SceneError {
    /// The parameter the error names.
    pub fn param(&self) -> &'static Spec {
        match self {
            SceneError::Invalid { param, .. } | SceneError::Refused { param, .. } => param,
        }
    }

    /// The same error naming its parameter as the front end does (`rename` maps the
    /// library's parameter, e.g. [`ANGLE`](crate::params::ANGLE), to the one that sets
    /// it there, e.g. [`ANGLES`](crate::params::ANGLES)).
    pub fn renamed(self, rename: &dyn Fn(&'static Spec) -> &'static Spec) -> SceneError {
        match self {
            SceneError::Invalid {
                param,
                value,
                expected,
            } => SceneError::Invalid {
                param: rename(param),
                value,
                expected,
            },
            SceneError::Refused { param, why } => SceneError::Refused {
                param: rename(param),
                why,
            },
        }
    }
}

/// A rigid indenter ([`Indenter`]: an ellipsoid h = x²/(2 R1) + y²/(2 R2), a power law or a
/// flat punch) on an elastic half-space, with JKR adhesion.
///
/// Lengths are in the user's length unit L, E* and Δγ in consistent units (E* in F/L²,
/// Δγ in F/L), so that forces come out in F.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// The indenter's shape.
    pub indenter: Indenter,
    /// Effective modulus E* = E/(1 − ν²) (force / length²).
    pub e_star: f64,
    /// Work of adhesion Δγ (energy / area = force / length).
    pub work_of_adhesion: f64,
}

pub(crate) fn check(
    param: &'static Spec,
    value: f64,
    ok: bool,
    expected: &str,
) -> Result<(), SceneError> {
    if ok && value.is_finite() {
        Ok(())
    } else {
        Err(SceneError::Invalid {
            param,
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
pub(crate) fn input_range(what: &str) -> String {
    format!(
        "{what} in [{}, {}] (any consistent units; the normalised results do not depend on them)",
        compact(MIN_INPUT),
        compact(MAX_INPUT)
    )
}

impl Scene {
    /// A scene from the two radii (length), E* (force/length²) and Δγ (force/length).
    pub fn new(r1: f64, r2: f64, e_star: f64, work_of_adhesion: f64) -> Result<Self, SceneError> {
        check(R2, r2, input_in_range(r2), &input_range("a radius"))?;
        check(R1, r1, input_in_range(r1), &input_range("a radius"))?;
        check(R1, r1, r1 >= r2, "R1 must be ≥ R2 (x is the major axis)")?;
        check(
            R1,
            r1,
            r1 / r2 <= MAX_RATIO,
            &format!("R1/R2 = {} must be ≤ {MAX_RATIO}", compact(r1 / r2)),
        )?;
        Scene::with_indenter(Indenter::ellipsoid(r1, r2), e_star, work_of_adhesion)
    }

    /// A scene of any indenter, E* (force/length²) and Δγ (force/length); the shape's
    /// parameters are checked (errors name their parameters).
    pub fn with_indenter(
        indenter: Indenter,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<Self, SceneError> {
        check(
            E_STAR,
            e_star,
            input_in_range(e_star),
            &input_range("a modulus"),
        )?;
        check(
            WORK_OF_ADHESION,
            work_of_adhesion,
            input_in_range(work_of_adhesion),
            &input_range("an energy per area"),
        )?;
        Ok(Scene {
            indenter: indenter.checked()?,
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
            RATIO,
            ratio,
            (1.0..=MAX_RATIO).contains(&ratio),
            &format!("R1/R2 must be in [1, {MAX_RATIO}]"),
        )?;
        Scene::new(ratio * r2, r2, e_star, work_of_adhesion)
    }

    /// R1/R2 of an ellipsoid; 1 for the axisymmetric indenters (dimensionless).
    pub fn ratio(&self) -> f64 {
        self.indenter.ratio()
    }

    /// A short tag for file names: "r5" for an ellipsoid of R1/R2 = 5, "flat-punch",
    /// "power-law-n3", "cone-a70", "rough-r1" for a rough sphere.
    pub fn tag(&self) -> String {
        self.indenter.shape().tag()
    }

    /// The scene in a few words for progress lines: "R1/R2 = 5" for an ellipsoid, else the
    /// indenter's description.
    pub fn headline(&self) -> String {
        match self.indenter {
            Indenter::Ellipsoid(_) => format!("R1/R2 = {}", self.ratio()),
            _ => self.indenter.describe(),
        }
    }

    /// Whether the indenter is an ellipsoid (the shape the study, its convergence law, the
    /// reference table and Johnson–Greenwood's theory are for).
    pub fn is_ellipsoid(&self) -> bool {
        matches!(self.indenter, Indenter::Ellipsoid(_))
    }

    /// Whether the indenter is pressed on by default (a loading phase to the first contact's
    /// approach) rather than its first contact built in one piece: a height map or a rough
    /// shape, whose first contact has no closed form.
    pub fn presses_on(&self) -> bool {
        matches!(self.indenter, Indenter::HeightMap(_) | Indenter::Rough(_))
    }

    /// The half-widths (length) of the window a height map is placed on, which is the
    /// domain; `None` for every other placement and shape.
    pub fn window_half(&self) -> Option<(f64, f64)> {
        match self.indenter {
            Indenter::HeightMap(ref m) => m.window_half(),
            _ => None,
        }
    }

    /// What normalises the results, in words.
    pub fn normalised_by(&self) -> String {
        self.indenter.shape().normalised_by()
    }

    /// Whether the results are normalised (by the shape's own scales, a base shape's or a
    /// height map's apex radii); `false` for a height map without an apex, whose results are
    /// in the user's units.
    pub fn is_normalised(&self) -> bool {
        !matches!(self.indenter, Indenter::HeightMap(ref m) if m.radii.is_none())
    }

    /// Indenter height h(x, y) (length) at (x, y) (length) from the apex, in its own axes.
    pub fn profile(&self, x: f64, y: f64) -> f64 {
        self.indenter
            .height(x, y, self.e_star, self.work_of_adhesion)
    }

    /// The normalisation scales of physics §2 (see [`Indenter::scales`]).
    pub fn scales(&self) -> Scales {
        self.indenter.scales(self.e_star, self.work_of_adhesion)
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

impl Scales {
    /// The scales of a surface without a normalisation: each 1 in the user's units, so that
    /// the "normalised" values are the dimensional ones.
    pub const UNITS: Scales = Scales {
        length: 1.0,
        force: 1.0,
        approach: 1.0,
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn approach_scale_matches_spec_formula() {
        // d̄ = d · (4E*/(9π Δγ √Re))^(2/3) must equal d · Re / c_r².
        let s = Scene::new(7.0, 2.0, 3.0, 0.5).unwrap();
        let re: f64 = (7.0f64 * 2.0).sqrt();
        let direct = (4.0 * s.e_star / (9.0 * PI * s.work_of_adhesion * re.sqrt())).powf(2.0 / 3.0);
        assert!((1.0 / s.scales().approach / direct - 1.0).abs() < 1e-12);
    }

    #[test]
    fn bad_values_name_their_parameter() {
        for (e, param) in [
            (Scene::from_ratio(0.5, 1.0, 1.0, 1.0), RATIO),
            (Scene::from_ratio(f64::NAN, 1.0, 1.0, 1.0), RATIO),
            (Scene::from_ratio(2.0, 1.0, -1.0, 1.0), E_STAR),
            (Scene::from_ratio(2.0, 1.0, 1.0, 0.0), WORK_OF_ADHESION),
            (Scene::from_ratio(2.0, 0.0, 1.0, 1.0), R2),
        ] {
            let e = e.unwrap_err();
            assert_eq!(e.param(), param);
            assert!(e.to_string().starts_with(&param.to_string()), "{e}");
        }
    }

    #[test]
    fn inputs_are_bounded_and_echoed_short() {
        for (e, param) in [
            (Scene::from_ratio(1e8, 1.0, 1.0, 1.0), RATIO),
            (Scene::from_ratio(2.0, 1.0, 1e300, 1.0), E_STAR),
            (Scene::from_ratio(2.0, 1.0, 1e-300, 1.0), E_STAR),
            (Scene::from_ratio(2.0, 1.0, 1.0, 1e-300), WORK_OF_ADHESION),
            (Scene::new(2e3, 1.0, 1.0, 1.0), R1),
        ] {
            let e = e.unwrap_err();
            assert_eq!(e.param(), param);
            assert!(e.to_string().len() < 200, "{e}");
        }
        let e = Scene::from_ratio(2.0, 1.0, 1e300, 1.0)
            .unwrap_err()
            .to_string();
        let shown = crate::params::words::flags(&e);
        assert!(shown.starts_with("--e-star = 1e300 is invalid"), "{shown}");
        assert!(Scene::from_ratio(MAX_RATIO, 1.0, MAX_INPUT, MIN_INPUT).is_ok());
    }
}
