//! The study's fits of recorded pull-offs (physics §8.4–§8.5): per ratio, the adhesive
//! branch's laws (d̄(c̄) and F̄(c̄)), from one grid or extrapolated to Δx → 0 from several
//! ([`super::branch_limit`]); across ratios, each coefficient's power law in R1/R2, with the
//! uncertainty its coefficients' uncertainties leave.

use super::branch::columns;
use super::branch_limit::{branch_laws, BranchLaws, GridBranch};
use super::fit::quality;
use super::{adhesive_branch, fit_d_of_c, fit_f_of_c, fit_power_law};
use super::{FitQuality, LinearFit2, PowerFit, PowerLawFit};
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
#[derive(Clone)]
pub struct BranchFits {
    /// R1/R2.
    pub ratio: f64,
    /// d̄ = A c̄² + B c̄^½.
    pub d_of_c: Option<LinearFit2>,
    /// F̄ = c1 c̄³ + c2 c̄^α.
    pub f_of_c: Option<PowerFit>,
    /// The half-widths of A, B, c1, c2 and α where the fits are extrapolated to Δx → 0
    /// (`None` for one grid's fits, whose discretisation error is not known).
    pub uncertainty: Option<[f64; 5]>,
    /// The grids (Nx) the fits come from.
    pub grids: Vec<usize>,
}

/// Least-squares fits of one run's adhesive branch.
pub fn branch_fits(run: &RatioRun) -> BranchFits {
    let (c, d, f) = columns(&adhesive_branch(&run.states));
    BranchFits {
        ratio: run.ratio,
        d_of_c: fit_d_of_c(&c, &d).ok(),
        f_of_c: fit_f_of_c(&c, &f).ok(),
        uncertainty: None,
        grids: vec![run.grid.0],
    }
}

/// The branch laws of one ratio at Δx → 0 from its runs on several grids, as fits with
/// uncertainties (`None` if they cannot be formed; see [`branch_laws`]).
pub fn limit_fits(ratio: f64, runs: &[RatioRun]) -> Option<(BranchFits, BranchLaws)> {
    let branches: Vec<GridBranch> = runs
        .iter()
        .map(|r| GridBranch {
            nx: r.grid.0,
            points: adhesive_branch(&r.states),
        })
        .collect();
    let laws = branch_laws(ratio, &branches)?;
    let l = &laws.limit;
    let d = LinearFit2 {
        a: laws.a.value,
        b: laws.b.value,
        quality: FitQuality::NONE,
    };
    let f = PowerFit {
        c1: laws.c1.value,
        c2: laws.c2.value,
        alpha: laws.alpha.value,
        alpha_at_bound: laws.alpha_at_bound,
        quality: FitQuality::NONE,
    };
    let fits = BranchFits {
        ratio,
        d_of_c: Some(LinearFit2 {
            quality: quality(&l.c_bar, &l.d_bar, |c| d.eval(c)),
            ..d
        }),
        f_of_c: Some(PowerFit {
            quality: quality(&l.c_bar, &l.f_bar, |c| f.eval(c)),
            ..f
        }),
        uncertainty: Some([
            laws.a.uncertainty,
            laws.b.uncertainty,
            laws.c1.uncertainty,
            laws.c2.uncertainty,
            laws.alpha.uncertainty,
        ]),
        grids: laws.grids.clone(),
    };
    Some((fits, laws))
}

/// A coefficient's name and its value in a ratio's fits.
type Coefficient = (&'static str, fn(&BranchFits) -> Option<f64>);

/// The coefficients of the branch laws, in the order of [`BranchFits::uncertainty`].
pub const COEFFICIENTS: [Coefficient; 5] = [
    ("A", |f| f.d_of_c.as_ref().map(|d| d.a)),
    ("B", |f| f.d_of_c.as_ref().map(|d| d.b)),
    ("c1", |f| f.f_of_c.as_ref().map(|p| p.c1)),
    ("c2", |f| f.f_of_c.as_ref().map(|p| p.c2)),
    ("α", |f| f.f_of_c.as_ref().map(|p| p.alpha)),
];

/// One coefficient across ratios and its law k1·(R1/R2)^k2 + k3.
pub struct CoefficientLaw {
    /// The coefficient's name.
    pub name: &'static str,
    /// (R1/R2, value, half-width if known) per ratio.
    pub points: Vec<(f64, f64, Option<f64>)>,
    /// The law, fitted to the points of ratios not in `coarse` (None with three such ratios
    /// or fewer, or a failed fit).
    pub law: Option<PowerLawFit>,
    /// The ratios whose branch fits rest on grids too coarse for their estimate: drawn apart,
    /// left out of the law.
    pub coarse: Vec<f64>,
    /// Half-widths of (k1, k2, k3) where every point has one: each point moved by its
    /// standard deviation (half its half-width) in turn and the law refitted, the shifts
    /// added in quadrature (first-order propagation), times two.
    pub uncertainty: Option<[f64; 3]>,
}

/// Fewer points than this leave a coefficient without a law: k1·(R1/R2)^k2 + k3 has three
/// coefficients, and through three points it says nothing about the data.
pub const MIN_LAW_POINTS: usize = 4;

/// Each coefficient's values against R1/R2 and its law, with uncertainties where the fits
/// have them. The ratios in `coarse` (branch fits from grids too coarse for their estimate)
/// keep their points but are left out of the law.
pub fn coefficient_laws(fits: &[BranchFits], coarse: &[f64]) -> Vec<CoefficientLaw> {
    COEFFICIENTS
        .iter()
        .enumerate()
        .map(|(i, (name, get))| {
            let points: Vec<(f64, f64, Option<f64>)> = fits
                .iter()
                .filter_map(|f| Some((f.ratio, get(f)?, f.uncertainty.map(|u| u[i]))))
                .collect();
            let fitted: Vec<&(f64, f64, Option<f64>)> =
                points.iter().filter(|p| !coarse.contains(&p.0)).collect();
            let x: Vec<f64> = fitted.iter().map(|p| p.0).collect();
            let y: Vec<f64> = fitted.iter().map(|p| p.1).collect();
            let law = (x.len() >= MIN_LAW_POINTS)
                .then(|| fit_power_law(&x, &y).ok())
                .flatten();
            let uncertainty = law.as_ref().and_then(|_| {
                let sds: Vec<f64> = fitted
                    .iter()
                    .map(|p| p.2.map(|u| 0.5 * u))
                    .collect::<Option<_>>()?;
                let mut var = [0.0f64; 3];
                for (j, sd) in sds.iter().enumerate() {
                    let moved = |s: f64| {
                        let mut y = y.clone();
                        y[j] += s;
                        fit_power_law(&x, &y).ok()
                    };
                    let (up, down) = (moved(*sd)?, moved(-sd)?);
                    for (v, (a, b)) in
                        var.iter_mut()
                            .zip([(up.k1, down.k1), (up.k2, down.k2), (up.k3, down.k3)])
                    {
                        *v += (0.5 * (a - b)).powi(2);
                    }
                }
                Some(var.map(|v| 2.0 * v.sqrt()))
            });
            CoefficientLaw {
                name,
                coarse: points
                    .iter()
                    .map(|p| p.0)
                    .filter(|r| coarse.contains(r))
                    .collect(),
                points,
                law,
                uncertainty,
            }
        })
        .collect()
}
