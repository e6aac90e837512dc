//! Closed-form and semi-analytic contact theories (physics §3) in the physics §2 normalisation:
//! Hertz, JKR (sphere) and Johnson–Greenwood (ellipse), the oracles the solver is checked against.

pub mod elliptic;
pub mod hertz;
pub mod jg;
pub mod jkr;
pub mod johnson_wave;
pub mod power_law;
mod solve;

pub use elliptic::{d_and_c, ellip_e, ellip_k};
pub use hertz::{hertz_ellipticity_exact, hertz_for_depth, hertz_for_mean_radius, HertzContact};
pub use jg::{hertz_ellipticity, jg_point};
pub use jkr::{jkr_end_of_contact, jkr_force_min, jkr_point};

use std::fmt;

/// Largest normalised mean contact radius c̄ of a theory curve (dimensionless).
const C_BAR_MAX: f64 = 3.0;
/// Smallest c̄ of the adhesive curves (dimensionless), below the JKR end point (1/18)^(1/3).
const C_BAR_MIN: f64 = 0.05;

/// Bad input to a theory function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TheoryError {
    /// Argument `name` has value `value` outside the range described by `valid`.
    OutOfRange {
        /// The argument's name.
        name: &'static str,
        /// The value given (counts converted to f64).
        value: f64,
        /// The valid range, in words.
        valid: &'static str,
    },
    /// A pull-off was asked of the non-adhesive Hertz model.
    NoAdhesion,
}

impl fmt::Display for TheoryError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutOfRange { name, value, valid } => {
                write!(
                    f,
                    "{name} = {} is out of range: it must be {valid}",
                    crate::text::compact(*value)
                )
            }
            Self::NoAdhesion => {
                write!(
                    f,
                    "the Hertz model has no adhesion and so no pull-off; use Jkr or Jg"
                )
            }
        }
    }
}

impl std::error::Error for TheoryError {}

/// One state of a theory branch in the physics §2 normalisation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TheoryPoint {
    /// Mean contact radius c̄ = √(A/π)/c_r (dimensionless).
    pub c_bar: f64,
    /// Force F̄ = F/(3π Re Δγ), compressive positive (dimensionless).
    pub f_bar: f64,
    /// Approach d̄ = d·Re/c_r², pressing in positive (dimensionless).
    pub d_bar: f64,
    /// Half-axis ā = a/c_r along x, the major axis (dimensionless).
    pub a_bar: f64,
    /// Half-axis b̄ = b/c_r along y, the minor axis (dimensionless).
    pub b_bar: f64,
}

/// Which theory to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TheoryModel {
    /// Non-adhesive elliptic Hertz.
    Hertz,
    /// JKR for a sphere (ratio must be 1).
    Jkr,
    /// Johnson–Greenwood (2005) for an ellipse.
    Jg,
}

impl TheoryModel {
    /// The closed form an adhesive run of R1/R2 = `ratio` is compared with: JKR for the
    /// sphere, Johnson–Greenwood otherwise.
    pub fn adhesive_reference(ratio: f64) -> TheoryModel {
        if ratio == 1.0 {
            TheoryModel::Jkr
        } else {
            TheoryModel::Jg
        }
    }

    /// Short lower-case name ("hertz", "jkr", "jg").
    pub fn name(self) -> &'static str {
        match self {
            TheoryModel::Hertz => "hertz",
            TheoryModel::Jkr => "jkr",
            TheoryModel::Jg => "jg",
        }
    }
}

/// The two critical points of an adhesive branch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOff {
    /// Minimum F̄: the force-controlled pull-off.
    pub force_min: TheoryPoint,
    /// Minimum d̄: where the contact jumps off under displacement control.
    pub end_of_contact: TheoryPoint,
}

/// `Ok(())` when `ok`, else the error naming argument `name`, its `value` and the `valid` range.
fn require(
    ok: bool,
    name: &'static str,
    value: f64,
    valid: &'static str,
) -> Result<(), TheoryError> {
    if ok {
        Ok(())
    } else {
        Err(TheoryError::OutOfRange { name, value, valid })
    }
}

/// Checks `ratio` = R1/R2 (dimensionless): finite and ≥ 1, and exactly 1 if `sphere`.
fn check_ratio(ratio: f64, sphere: bool) -> Result<(), TheoryError> {
    require(
        ratio.is_finite() && (1.0..=crate::params::limits::MAX_RATIO).contains(&ratio),
        "ratio",
        ratio,
        "in [1, 1000] (R1/R2, R1 ≥ R2), as every command takes it",
    )?;
    require(
        !sphere || ratio == 1.0,
        "ratio",
        ratio,
        "exactly 1 for the JKR (sphere) model",
    )
}

pub use crate::params::limits::MAX_CURVE_POINTS;

/// `n` points (2 to [`MAX_CURVE_POINTS`]) of the closed-form curve for `ratio` = R1/R2
/// (dimensionless, in [1, 1000]), evenly spaced in c̄ and ordered by decreasing c̄: from 3 to 0 (Hertz) or to 0.05 (Jkr, Jg).
pub fn curve(model: TheoryModel, ratio: f64, n: usize) -> Result<Vec<TheoryPoint>, TheoryError> {
    check_ratio(ratio, model == TheoryModel::Jkr)?;
    require(
        (2..=MAX_CURVE_POINTS).contains(&n),
        "points",
        n as f64,
        "from 2 to 1000000",
    )?;
    let c_min = if model == TheoryModel::Hertz {
        0.0
    } else {
        C_BAR_MIN
    };
    let targets = (0..n).map(|i| C_BAR_MAX + (c_min - C_BAR_MAX) * i as f64 / (n - 1) as f64);
    match model {
        TheoryModel::Hertz => {
            let g = hertz_ellipticity_exact(ratio)?;
            Ok(targets.map(|c| hertz::hertz_point(ratio, g, c)).collect())
        }
        TheoryModel::Jkr => Ok(targets.map(jkr_point).collect()),
        TheoryModel::Jg if ratio == 1.0 => curve(TheoryModel::Jkr, ratio, n),
        TheoryModel::Jg => {
            let t_h = jg::hertz_gap(ratio);
            Ok(targets.map(|c| jg::jg_point_at_c(ratio, t_h, c)).collect())
        }
    }
}

/// The adhesive force |min F̄| of the closed form an adhesive run of R1/R2 = `ratio` is
/// compared with (JKR's 1/2 for the sphere, Johnson–Greenwood's otherwise).
pub fn reference_adhesive_force(ratio: f64) -> Result<f64, TheoryError> {
    Ok(pull_off(TheoryModel::adhesive_reference(ratio), ratio)?
        .force_min
        .f_bar
        .abs())
}

/// Force-controlled pull-off and displacement-controlled end of contact of an adhesive branch
/// for `ratio` = R1/R2 (dimensionless, finite, ≥ 1; exactly 1 for Jkr). Hertz has none.
pub fn pull_off(model: TheoryModel, ratio: f64) -> Result<PullOff, TheoryError> {
    check_ratio(ratio, model == TheoryModel::Jkr)?;
    match model {
        TheoryModel::Hertz => Err(TheoryError::NoAdhesion),
        TheoryModel::Jkr => Ok(PullOff {
            force_min: jkr_force_min(),
            end_of_contact: jkr_end_of_contact(),
        }),
        TheoryModel::Jg if ratio == 1.0 => pull_off(TheoryModel::Jkr, ratio),
        TheoryModel::Jg => {
            let (force_min, end_of_contact) = jg::jg_critical_points(ratio);
            Ok(PullOff {
                force_min,
                end_of_contact,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_run_from_three_down_evenly_in_c_bar() {
        for (model, ratio, c_end) in [
            (TheoryModel::Hertz, 4.0, 0.0),
            (TheoryModel::Jkr, 1.0, C_BAR_MIN),
            (TheoryModel::Jg, 10.0, C_BAR_MIN),
        ] {
            let pts = curve(model, ratio, 60).unwrap();
            assert_eq!(pts.len(), 60);
            let step = (C_BAR_MAX - c_end) / 59.0;
            for (i, p) in pts.iter().enumerate() {
                let target = C_BAR_MAX - step * i as f64;
                assert!(
                    (p.c_bar - target).abs() < 1e-9 && p.f_bar.is_finite() && p.d_bar.is_finite(),
                    "{model:?} {p:?}"
                );
            }
        }
    }

    #[test]
    fn jg_curve_and_pull_off_at_ratio_one_are_jkr() {
        assert_eq!(
            curve(TheoryModel::Jg, 1.0, 20),
            curve(TheoryModel::Jkr, 1.0, 20)
        );
        let p = pull_off(TheoryModel::Jg, 1.0).unwrap();
        assert!((p.force_min.f_bar + 0.5).abs() < 1e-15);
        assert!((p.end_of_contact.f_bar + 5.0 / 18.0).abs() < 1e-15);
    }

    #[test]
    fn jg_pull_off_lies_on_its_curve_below_every_sampled_point() {
        let p = pull_off(TheoryModel::Jg, 5.0).unwrap();
        for q in curve(TheoryModel::Jg, 5.0, 400).unwrap() {
            assert!(
                q.f_bar >= p.force_min.f_bar - 1e-12 && q.d_bar >= p.end_of_contact.d_bar - 1e-12
            );
        }
    }

    #[test]
    fn bad_input_is_rejected_with_value_and_range() {
        let e = curve(TheoryModel::Jkr, 2.0, 10).unwrap_err();
        assert!(
            e.to_string().contains("ratio = 2") && e.to_string().contains("exactly 1"),
            "{e}"
        );
        assert!(curve(TheoryModel::Jg, 0.5, 10)
            .unwrap_err()
            .to_string()
            .contains("in [1, 1000]"));
        // The commands' range: a ratio above 1000 and a count of points beyond a million are
        // refused (they answered, or tried to allocate a billion points).
        assert!(curve(TheoryModel::Jg, 1e300, 10).is_err());
        let e = curve(TheoryModel::Jg, 2.0, 1_000_000_000).unwrap_err();
        assert!(e.to_string().contains("points"), "{e}");
        assert!(
            curve(TheoryModel::Jg, f64::NAN, 10).is_err()
                && curve(TheoryModel::Jg, 2.0, 1).is_err()
        );
        assert_eq!(
            pull_off(TheoryModel::Hertz, 1.0),
            Err(TheoryError::NoAdhesion)
        );
    }
}
