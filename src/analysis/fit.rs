//! Least-squares fits of the study (physics §8.4–8.6), each reported with its quality:
//! d̄ = A c̄² + B c̄^(1/2), F̄ = c1 c̄³ + c2 c̄^α and y = k1·x^k2 + k3.
//!
//! Forms that are nonlinear in one exponent are linear in the other coefficients once the
//! exponent is fixed; the exponent is found by a coarse scan of its range followed by
//! golden-section search on the residual of the linear fit (variable projection), which is
//! deterministic and finds the global minimum unless two minima lie within one scan step.

use super::lstsq::{least_squares, minimise};
use thiserror::Error;

/// Range searched for α in F̄ = c1 c̄³ + c2 c̄^α (dimensionless). It stops short of 3, where the
/// two terms coincide and (c1, c2) are undetermined; JKR has α = 3/2.
pub const ALPHA_RANGE: (f64, f64) = (0.5, 2.9);

/// Range searched for k2 in y = k1·x^k2 + k3 (dimensionless).
pub const K2_RANGE: (f64, f64) = (-3.0, 3.0);

/// Scan step of the exponent searches (dimensionless): minima closer than this may be confused.
const SCAN_STEP: f64 = 0.01;

/// Golden-section tolerance on the exponents (dimensionless).
const EXPONENT_TOLERANCE: f64 = 1e-12;

/// |k2| at or below which a power law is refused as a logarithm (dimensionless): there k1 and
/// k3 would exceed the data by a factor 1/|k2| and cancel.
const LOG_LIMIT: f64 = 1e-6;

/// Data that cannot be fitted.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum FitError {
    /// The x and y slices differ in length.
    #[error("{x_name} has {x_len} values but {y_name} has {y_len}: give one y per x")]
    LengthMismatch {
        /// Name of the abscissa.
        x_name: &'static str,
        /// Its number of values.
        x_len: usize,
        /// Name of the ordinate.
        y_name: &'static str,
        /// Its number of values.
        y_len: usize,
    },
    /// Fewer points than the form has coefficients.
    #[error(
        "{got} points cannot determine the {needed} coefficients of {form}: give at least {needed}"
    )]
    TooFewPoints {
        /// The fitted form, in words.
        form: &'static str,
        /// Coefficients to determine.
        needed: usize,
        /// Points given.
        got: usize,
    },
    /// A NaN or infinite value.
    #[error("{name}[{index}] = {value} is not finite: drop that point")]
    NonFinite {
        /// Which input.
        name: &'static str,
        /// Its position.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A value of the abscissa that a power of it cannot take.
    #[error("{name}[{index}] = {value} must be > 0 (it is raised to non-integer powers)")]
    NotPositive {
        /// Which input.
        name: &'static str,
        /// Its position.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The data do not determine the coefficients.
    #[error("the data cannot be fitted by {form}: {reason}")]
    Degenerate {
        /// The fitted form, in words.
        form: &'static str,
        /// Why, in words.
        reason: String,
    },
}

/// How well a fit matches its data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitQuality {
    /// Coefficient of determination R² = 1 − SS_res/SS_tot, SS_tot taken about the mean of
    /// y (dimensionless; 1 is a perfect fit, as it is whenever the form can interpolate
    /// the points, e.g. two points for d̄(c̄)).
    pub r_squared: f64,
    /// Root-mean-square residual √(SS_res/n) (in the units of y).
    pub rms_residual: f64,
    /// Largest |residual| (in the units of y).
    pub max_residual: f64,
    /// Number of points n.
    pub points: usize,
}

/// d̄ = A c̄² + B c̄^(1/2) (all dimensionless; JKR: A = 1, B = −(2/3)√2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearFit2 {
    /// A (dimensionless).
    pub a: f64,
    /// B (dimensionless).
    pub b: f64,
    /// Quality of the fit in d̄.
    pub quality: FitQuality,
}

impl LinearFit2 {
    /// d̄ at `c_bar` (both dimensionless).
    pub fn eval(&self, c_bar: f64) -> f64 {
        self.a * c_bar * c_bar + self.b * c_bar.sqrt()
    }
}

/// F̄ = c1 c̄³ + c2 c̄^α (all dimensionless; JKR: c1 = 1, c2 = −√2, α = 3/2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerFit {
    /// c1 (dimensionless).
    pub c1: f64,
    /// c2 (dimensionless).
    pub c2: f64,
    /// α (dimensionless), within [`ALPHA_RANGE`].
    pub alpha: f64,
    /// Whether α ended at an end of [`ALPHA_RANGE`]: the true minimum may lie beyond it.
    pub alpha_at_bound: bool,
    /// Quality of the fit in F̄.
    pub quality: FitQuality,
}

impl PowerFit {
    /// F̄ at `c_bar` (both dimensionless).
    pub fn eval(&self, c_bar: f64) -> f64 {
        self.c1 * c_bar.powi(3) + self.c2 * c_bar.powf(self.alpha)
    }
}

/// y = k1·x^k2 + k3, with x > 0 (k2 dimensionless; k1 and k3 in the units of y).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLawFit {
    /// k1 (units of y).
    pub k1: f64,
    /// k2 (dimensionless), within [`K2_RANGE`].
    pub k2: f64,
    /// k3 (units of y).
    pub k3: f64,
    /// Whether k2 ended at an end of [`K2_RANGE`]: the true minimum may lie beyond it.
    pub k2_at_bound: bool,
    /// Quality of the fit in y.
    pub quality: FitQuality,
}

impl PowerLawFit {
    /// y at `x` (> 0).
    pub fn eval(&self, x: f64) -> f64 {
        self.k1 * x.powf(self.k2) + self.k3
    }
}

const D_FORM: &str = "d̄ = A c̄² + B c̄^(1/2)";
const F_FORM: &str = "F̄ = c1 c̄³ + c2 c̄^α";
const LAW_FORM: &str = "y = k1·x^k2 + k3";

/// Least-squares fit of d̄ = A c̄² + B c̄^(1/2) to points (`c_bar[i]`, `d_bar[i]`) (all
/// dimensionless; c̄ > 0; at least 2 points with 2 distinct c̄, not all d̄ equal).
pub fn fit_d_of_c(c_bar: &[f64], d_bar: &[f64]) -> Result<LinearFit2, FitError> {
    check(D_FORM, 2, ("c_bar", c_bar), ("d_bar", d_bar))?;
    let cols = vec![
        c_bar.iter().map(|c| c * c).collect(),
        c_bar.iter().map(|c| c.sqrt()).collect(),
    ];
    let beta = least_squares(&cols, d_bar).ok_or_else(|| dependent(D_FORM))?;
    let fit = LinearFit2 {
        a: beta[0],
        b: beta[1],
        quality: FitQuality::NONE,
    };
    Ok(LinearFit2 {
        quality: quality(c_bar, d_bar, |c| fit.eval(c)),
        ..fit
    })
}

/// Least-squares fit of F̄ = c1 c̄³ + c2 c̄^α to points (`c_bar[i]`, `f_bar[i]`) (all
/// dimensionless; c̄ > 0; at least 3 points with 3 distinct c̄, not all F̄ equal), with α
/// searched over [`ALPHA_RANGE`].
pub fn fit_f_of_c(c_bar: &[f64], f_bar: &[f64]) -> Result<PowerFit, FitError> {
    check(F_FORM, 3, ("c_bar", c_bar), ("f_bar", f_bar))?;
    let cube: Vec<f64> = c_bar.iter().map(|c| c.powi(3)).collect();
    let linear = |alpha: f64| {
        let cols = vec![cube.clone(), c_bar.iter().map(|c| c.powf(alpha)).collect()];
        least_squares(&cols, f_bar)
    };
    let residual = |alpha: f64| match linear(alpha) {
        Some(b) => sum_sq(c_bar, f_bar, |c| b[0] * c.powi(3) + b[1] * c.powf(alpha)),
        None => f64::INFINITY,
    };
    let (lo, hi) = ALPHA_RANGE;
    let best = minimise(residual, lo, hi, scan_points(lo, hi), EXPONENT_TOLERANCE);
    let beta = linear(best.x)
        .filter(|_| best.value.is_finite())
        .ok_or_else(|| dependent(F_FORM))?;
    let fit = PowerFit {
        c1: beta[0],
        c2: beta[1],
        alpha: best.x,
        alpha_at_bound: best.at_bound,
        quality: FitQuality::NONE,
    };
    Ok(PowerFit {
        quality: quality(c_bar, f_bar, |c| fit.eval(c)),
        ..fit
    })
}

/// Least-squares fit of y = k1·x^k2 + k3 to points (`x[i]` > 0, `y[i]`) (at least 3 points
/// with 3 distinct x, not all y equal), with k2 searched over [`K2_RANGE`].
///
/// For fixed k2 the fit is linear in the Box–Cox basis {(x^k2 − 1)/k2, 1}, which spans the
/// same functions as {x^k2, 1} but tends to {ln x, 1} as k2 → 0 instead of collapsing onto
/// one column, so the residual is smooth through k2 = 0 and the search may cross it. If the
/// best |k2| ≤ 1e-6 the data follow a logarithm (k1 and k3 would be huge and of opposite
/// sign) and the fit is refused as degenerate.
pub fn fit_power_law(x: &[f64], y: &[f64]) -> Result<PowerLawFit, FitError> {
    check(LAW_FORM, 3, ("x", x), ("y", y))?;
    let ln_x: Vec<f64> = x.iter().map(|v| v.ln()).collect();
    let linear = |k2: f64| {
        let cols = [
            ln_x.iter().map(|&l| box_cox(l, k2)).collect(),
            vec![1.0; x.len()],
        ];
        least_squares(&cols, y)
    };
    let residual = |k2: f64| match linear(k2) {
        Some(b) => sum_sq(&ln_x, y, |l| b[0] * box_cox(l, k2) + b[1]),
        None => f64::INFINITY,
    };
    let (lo, hi) = K2_RANGE;
    let best = minimise(residual, lo, hi, scan_points(lo, hi), EXPONENT_TOLERANCE);
    let beta = linear(best.x)
        .filter(|_| best.value.is_finite())
        .ok_or_else(|| dependent(LAW_FORM))?;
    if best.x.abs() <= LOG_LIMIT {
        return Err(FitError::Degenerate {
            form: LAW_FORM,
            reason: format!(
                "the best exponent k2 = {:.1e} is 0 to within {LOG_LIMIT:.0e}: the data follow \
                 a logarithm y = k ln x + c, not a power law",
                best.x
            ),
        });
    }
    // b0 (x^k2 − 1)/k2 + b1 = (b0/k2) x^k2 + (b1 − b0/k2).
    let k1 = beta[0] / best.x;
    let fit = PowerLawFit {
        k1,
        k2: best.x,
        k3: beta[1] - k1,
        k2_at_bound: best.at_bound,
        quality: FitQuality::NONE,
    };
    Ok(PowerLawFit {
        quality: quality(x, y, |v| fit.eval(v)),
        ..fit
    })
}

/// The Box–Cox term (x^k2 − 1)/k2 (→ ln x as k2 → 0) from `ln_x` = ln x, without
/// cancellation for small k2·ln x.
fn box_cox(ln_x: f64, k2: f64) -> f64 {
    if k2 == 0.0 {
        ln_x
    } else {
        (k2 * ln_x).exp_m1() / k2
    }
}

impl FitQuality {
    /// Placeholder until the coefficients are known.
    pub(super) const NONE: FitQuality = FitQuality {
        r_squared: f64::NAN,
        rms_residual: f64::NAN,
        max_residual: f64::NAN,
        points: 0,
    };
}

/// Number of scan intervals covering [lo, hi] in steps of at most [`SCAN_STEP`].
fn scan_points(lo: f64, hi: f64) -> usize {
    ((hi - lo) / SCAN_STEP).round() as usize
}

/// Σ (y_i − f(x_i))².
fn sum_sq(x: &[f64], y: &[f64], f: impl Fn(f64) -> f64) -> f64 {
    x.iter().zip(y).map(|(&x, &y)| (y - f(x)).powi(2)).sum()
}

/// The quality of model `f` on the points (x_i, y_i).
pub(super) fn quality(x: &[f64], y: &[f64], f: impl Fn(f64) -> f64) -> FitQuality {
    let n = y.len() as f64;
    let mean = y.iter().sum::<f64>() / n;
    let ss_tot: f64 = y.iter().map(|v| (v - mean).powi(2)).sum();
    let ss_res = sum_sq(x, y, &f);
    let max_residual = x
        .iter()
        .zip(y)
        .map(|(&x, &y)| (y - f(x)).abs())
        .fold(0.0, f64::max);
    FitQuality {
        r_squared: 1.0 - ss_res / ss_tot,
        rms_residual: (ss_res / n).sqrt(),
        max_residual,
        points: y.len(),
    }
}

fn dependent(form: &'static str) -> FitError {
    FitError::Degenerate {
        form,
        reason: "its terms are numerically indistinguishable on these abscissae".into(),
    }
}

/// Checks the points for a form with `needed` coefficients: equal lengths, at least `needed`
/// points, all finite, x > 0 (raised to non-integer powers), at least `needed` distinct x and not all y equal.
fn check(
    form: &'static str,
    needed: usize,
    (x_name, x): (&'static str, &[f64]),
    (y_name, y): (&'static str, &[f64]),
) -> Result<(), FitError> {
    if x.len() != y.len() {
        return Err(FitError::LengthMismatch {
            x_name,
            x_len: x.len(),
            y_name,
            y_len: y.len(),
        });
    }
    if x.len() < needed {
        return Err(FitError::TooFewPoints {
            form,
            needed,
            got: x.len(),
        });
    }
    for (name, values) in [(x_name, x), (y_name, y)] {
        if let Some((index, &value)) = values.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(FitError::NonFinite { name, index, value });
        }
    }
    if let Some((index, &value)) = x.iter().enumerate().find(|(_, v)| **v <= 0.0) {
        return Err(FitError::NotPositive {
            name: x_name,
            index,
            value,
        });
    }
    let mut sorted = x.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.dedup();
    if sorted.len() < needed {
        return Err(FitError::Degenerate {
            form,
            reason: format!(
                "{x_name} takes only {} distinct values, fewer than the {needed} coefficients",
                sorted.len()
            ),
        });
    }
    if y.iter().all(|v| *v == y[0]) {
        return Err(FitError::Degenerate {
            form,
            reason: format!("every {y_name} equals {}, so R² is undefined", y[0]),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests;
