//! The study's fits of recorded pull-offs (physics §8.4–§8.5): per ratio, least squares of the
//! adhesive branch (d̄(c̄) and F̄(c̄)); across ratios, each coefficient's power law in R1/R2.

use super::branch::columns;
use super::{adhesive_branch, fit_d_of_c, fit_f_of_c, fit_power_law};
use super::{LinearFit2, PowerFit, PowerLawFit};
use crate::solver::State;

/// One ratio's pull-off.
pub struct RatioRun {
    /// R1/R2.
    pub ratio: f64,
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// The recorded states.
    pub states: Vec<State>,
}

/// The branch fits of one ratio (None where there were too few branch points).
pub struct BranchFits {
    /// R1/R2.
    pub ratio: f64,
    /// d̄ = A c̄² + B c̄^½.
    pub d_of_c: Option<LinearFit2>,
    /// F̄ = c1 c̄³ + c2 c̄^α.
    pub f_of_c: Option<PowerFit>,
}

/// Least-squares fits of a run's adhesive branch.
pub fn branch_fits(run: &RatioRun) -> BranchFits {
    let (c, d, f) = columns(&adhesive_branch(&run.states));
    BranchFits {
        ratio: run.ratio,
        d_of_c: fit_d_of_c(&c, &d).ok(),
        f_of_c: fit_f_of_c(&c, &f).ok(),
    }
}

/// A coefficient's name and its value in a ratio's fits.
type Coefficient = (&'static str, fn(&BranchFits) -> Option<f64>);

/// The coefficients of the branch laws.
pub const COEFFICIENTS: [Coefficient; 5] = [
    ("A", |f| f.d_of_c.as_ref().map(|d| d.a)),
    ("B", |f| f.d_of_c.as_ref().map(|d| d.b)),
    ("c1", |f| f.f_of_c.as_ref().map(|p| p.c1)),
    ("c2", |f| f.f_of_c.as_ref().map(|p| p.c2)),
    ("α", |f| f.f_of_c.as_ref().map(|p| p.alpha)),
];

/// A coefficient's name, its (R1/R2, value) points and its fitted law.
pub type CoefficientLaw = (&'static str, Vec<(f64, f64)>, Option<PowerLawFit>);

/// Each coefficient's values against R1/R2 and its law k1·(R1/R2)^k2 + k3 (None with fewer
/// than three ratios or a failed fit).
pub fn coefficient_laws(fits: &[BranchFits]) -> Vec<CoefficientLaw> {
    COEFFICIENTS
        .iter()
        .map(|(name, get)| {
            let pts: Vec<(f64, f64)> = fits
                .iter()
                .filter_map(|f| Some((f.ratio, get(f)?)))
                .collect();
            let (x, y): (Vec<f64>, Vec<f64>) = pts.iter().copied().unzip();
            let law = fit_power_law(&x, &y).ok();
            (*name, pts, law)
        })
        .collect()
}
