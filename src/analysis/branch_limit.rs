//! The adhesive branch at Δx → 0 and the study's branch laws fitted to it, each coefficient
//! with the half-width of an interval stated to hold it (physics §8.4).
//!
//! Each grid's branch ([`super::adhesive_branch`]) is interpolated at common c̄ points; at each
//! point d̄ and F̄ are extrapolated to Δx → 0 along a line in 1/n (n: elements across the
//! minor axis at that state, so the error is first order as for |min F̄|), weighted by the
//! grid-phase scatter. The laws d̄ = A c̄² + B c̄^½ and F̄ = c1 c̄³ + c2 c̄^α are fitted to the
//! extrapolated branch by weighted least squares. A coefficient's stated half-width combines
//! in quadrature twice its standard deviation from the fit (widened by the residuals' Birge
//! ratio) and its largest move under each of two independent choices: the extrapolation's
//! model (one grid left out, or a parabola in 1/n instead of the line; three grids or more),
//! and the c̄ range (a tenth left out at either end: near its top the front has only just
//! left its pinned start, near its bottom the contact spans the fewest elements).

use super::branch::BranchPoint;
use super::convergence::CORNER_SCATTER;
use super::estimate::Estimate;
use super::fit::ALPHA_RANGE;
use super::line_fit::{fit_free_line, Point};
use super::lstsq::{least_squares, minimise};

/// Points at which the extrapolated branch is formed, evenly spaced in c̄.
pub const LIMIT_POINTS: usize = 60;

/// The fraction of the c̄ range left out at either end to measure how much the laws depend
/// on the range (dimensionless).
pub const RANGE_TRIM: f64 = 0.1;

/// Scan step of the α search (dimensionless).
const ALPHA_STEP: f64 = 0.005;

/// One grid's adhesive branch.
#[derive(Debug, Clone, PartialEq)]
pub struct GridBranch {
    /// Elements along x of the grid.
    pub nx: usize,
    /// Its branch points (any order).
    pub points: Vec<BranchPoint>,
}

/// The branch at Δx → 0: at each c̄, d̄ and F̄ with their standard deviations.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitBranch {
    /// Mean contact radius c̄ (dimensionless), increasing.
    pub c_bar: Vec<f64>,
    /// d̄ at Δx → 0.
    pub d_bar: Vec<f64>,
    /// Its standard deviation (Birge-widened).
    pub d_sd: Vec<f64>,
    /// F̄ at Δx → 0.
    pub f_bar: Vec<f64>,
    /// Its standard deviation (Birge-widened).
    pub f_sd: Vec<f64>,
}

/// The branch laws of one ratio at Δx → 0, each coefficient with its stated half-width.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchLaws {
    /// R1/R2.
    pub ratio: f64,
    /// The grids (Nx) extrapolated from, coarse to fine.
    pub grids: Vec<usize>,
    /// The c̄ range fitted.
    pub c_range: (f64, f64),
    /// A in d̄ = A c̄² + B c̄^½.
    pub a: Estimate,
    /// B.
    pub b: Estimate,
    /// c1 in F̄ = c1 c̄³ + c2 c̄^α.
    pub c1: Estimate,
    /// c2.
    pub c2: Estimate,
    /// α.
    pub alpha: Estimate,
    /// Whether α's best value lies at an end of [`ALPHA_RANGE`].
    pub alpha_at_bound: bool,
    /// RMS residual of the d̄ law on the extrapolated branch (dimensionless).
    pub d_rms: f64,
    /// RMS residual of the F̄ law on the extrapolated branch (dimensionless).
    pub f_rms: f64,
    /// Points of the extrapolated branch.
    pub points: usize,
    /// The extrapolated branch over the whole range.
    pub limit: LimitBranch,
}

/// The c̄ range every branch covers, if they overlap.
pub fn common_range(branches: &[GridBranch]) -> Option<(f64, f64)> {
    let mut range = (f64::NEG_INFINITY, f64::INFINITY);
    for b in branches {
        let lo = b
            .points
            .iter()
            .map(|p| p.c_bar)
            .fold(f64::INFINITY, f64::min);
        let hi = b
            .points
            .iter()
            .map(|p| p.c_bar)
            .fold(f64::NEG_INFINITY, f64::max);
        range = (range.0.max(lo), range.1.min(hi));
    }
    (!branches.is_empty() && range.0 < range.1 && range.0 > 0.0).then_some(range)
}

/// A field of branch points sorted by c̄, for interpolation.
struct Sorted {
    c: Vec<f64>,
    value: Vec<f64>,
}

impl Sorted {
    fn new(points: &[BranchPoint], get: fn(&BranchPoint) -> f64) -> Self {
        let mut p: Vec<(f64, f64)> = points.iter().map(|q| (q.c_bar, get(q))).collect();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (c, value) = p.into_iter().unzip();
        Sorted { c, value }
    }

    /// Linear interpolation at `c` (clamped to the ends).
    fn at(&self, c: f64) -> f64 {
        let i = self.c.partition_point(|&x| x < c);
        if i == 0 {
            return self.value[0];
        }
        if i == self.c.len() {
            return self.value[i - 1];
        }
        let (c0, c1) = (self.c[i - 1], self.c[i]);
        let t = if c1 > c0 { (c - c0) / (c1 - c0) } else { 0.0 };
        self.value[i - 1] + t * (self.value[i] - self.value[i - 1])
    }
}

/// How the branch is extrapolated at each c̄.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Order {
    /// A line in 1/n, weighted by the grid-phase scatter (the estimate).
    First,
    /// A parabola in 1/n (three grids or more), with the line's standard deviations: the
    /// alternative model whose difference is part of the stated uncertainty.
    Second,
}

/// The branch at Δx → 0 over `range` at `n` points (≥ 2 grids, ≥ 2 points; ≥ 3 grids for
/// [`Order::Second`]). `None` if a branch is empty or a point cannot be extrapolated.
pub fn extrapolate(
    branches: &[GridBranch],
    range: (f64, f64),
    n: usize,
    order: Order,
) -> Option<LimitBranch> {
    if order == Order::Second && branches.len() < 3 {
        return None;
    }
    if branches.len() < 2 || n < 2 || branches.iter().any(|b| b.points.is_empty()) {
        return None;
    }
    let c_bar: Vec<f64> = (0..n)
        .map(|j| range.0 + (range.1 - range.0) * j as f64 / (n - 1) as f64)
        .collect();
    let inv_n: Vec<Sorted> = branches
        .iter()
        .map(|b| Sorted::new(&b.points, |p| p.inv_n))
        .collect();
    let column = |get: fn(&BranchPoint) -> f64| -> Option<(Vec<f64>, Vec<f64>)> {
        let fields: Vec<Sorted> = branches
            .iter()
            .map(|b| Sorted::new(&b.points, get))
            .collect();
        // The field's scale over the range: the grid-phase scatter is relative to it.
        let inside: Vec<f64> = branches
            .iter()
            .flat_map(|b| b.points.iter())
            .filter(|p| (range.0..=range.1).contains(&p.c_bar))
            .map(get)
            .collect();
        let scale = (inside.iter().map(|v| v * v).sum::<f64>() / inside.len().max(1) as f64)
            .sqrt()
            .max(1e-12);
        let mut values = Vec::with_capacity(n);
        let mut sds = Vec::with_capacity(n);
        for &c in &c_bar {
            let pts: Vec<Point> = fields
                .iter()
                .zip(&inv_n)
                .map(|(f, x)| {
                    let x = x.at(c);
                    Point {
                        x,
                        y: f.at(c),
                        sd: (CORNER_SCATTER * x * scale).max(1e-15),
                    }
                })
                .collect();
            let fit = fit_free_line(&pts)?;
            values.push(match order {
                Order::First => fit.intercept,
                Order::Second => {
                    let cols: Vec<Vec<f64>> = (0..3)
                        .map(|k| pts.iter().map(|p| p.x.powi(k) / p.sd).collect())
                        .collect();
                    let y: Vec<f64> = pts.iter().map(|p| p.y / p.sd).collect();
                    least_squares(&cols, &y)?[0]
                }
            });
            sds.push(fit.intercept_sd_from_residuals());
        }
        Some((values, sds))
    };
    let (d_bar, d_sd) = column(|p| p.d_bar)?;
    let (f_bar, f_sd) = column(|p| p.f_bar)?;
    Some(LimitBranch {
        c_bar,
        d_bar,
        d_sd,
        f_bar,
        f_sd,
    })
}

/// A weighted least-squares fit: coefficients, their standard deviations (Birge-widened) and
/// the plain RMS residual.
struct Weighted {
    values: Vec<f64>,
    sd: Vec<f64>,
    rms: f64,
}

/// The diagonal of the inverse of the symmetric positive-definite `m` (Gauss–Jordan), or
/// `None` if it is singular.
fn inverse_diagonal(mut m: Vec<Vec<f64>>) -> Option<Vec<f64>> {
    let p = m.len();
    let mut inv: Vec<Vec<f64>> = (0..p)
        .map(|i| (0..p).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    for k in 0..p {
        let pivot = (k..p).max_by(|&a, &b| m[a][k].abs().total_cmp(&m[b][k].abs()))?;
        m.swap(k, pivot);
        inv.swap(k, pivot);
        let d = m[k][k];
        if !(d.abs() > 1e-300 && d.is_finite()) {
            return None;
        }
        for j in 0..p {
            m[k][j] /= d;
            inv[k][j] /= d;
        }
        for i in 0..p {
            if i != k {
                let f = m[i][k];
                for j in 0..p {
                    m[i][j] -= f * m[k][j];
                    inv[i][j] -= f * inv[k][j];
                }
            }
        }
    }
    Some((0..p).map(|i| inv[i][i]).collect())
}

/// The standard deviations of the coefficients of a weighted fit whose (weighted) Jacobian
/// columns are `jac` and whose weighted residuals sum to `chi2` over `dof` degrees of freedom.
fn coefficient_sd(jac: &[Vec<f64>], chi2: f64, dof: usize) -> Option<Vec<f64>> {
    let jtj: Vec<Vec<f64>> = jac
        .iter()
        .map(|a| {
            jac.iter()
                .map(|b| a.iter().zip(b).map(|(x, y)| x * y).sum())
                .collect()
        })
        .collect();
    let birge2 = if dof > 0 {
        (chi2 / dof as f64).max(1.0)
    } else {
        1.0
    };
    Some(
        inverse_diagonal(jtj)?
            .into_iter()
            .map(|v| (v.max(0.0) * birge2).sqrt())
            .collect(),
    )
}

/// d̄ = A c̄² + B c̄^½ fitted to (c, y ± sd).
fn fit_d(c: &[f64], y: &[f64], sd: &[f64]) -> Option<Weighted> {
    let cols: Vec<Vec<f64>> = vec![
        c.iter().zip(sd).map(|(c, s)| c * c / s).collect(),
        c.iter().zip(sd).map(|(c, s)| c.sqrt() / s).collect(),
    ];
    let yw: Vec<f64> = y.iter().zip(sd).map(|(y, s)| y / s).collect();
    let beta = least_squares(&cols, &yw)?;
    let (a, b) = (beta[0], beta[1]);
    finish(c, y, sd, |c| a * c * c + b * c.sqrt(), beta, &cols)
}

/// F̄ = c1 c̄³ + c2 c̄^α fitted to (c, y ± sd); also whether α is at an end of its range.
fn fit_f(c: &[f64], y: &[f64], sd: &[f64]) -> Option<(Weighted, bool)> {
    let yw: Vec<f64> = y.iter().zip(sd).map(|(y, s)| y / s).collect();
    let cols = |alpha: f64| -> Vec<Vec<f64>> {
        vec![
            c.iter().zip(sd).map(|(c, s)| c.powi(3) / s).collect(),
            c.iter().zip(sd).map(|(c, s)| c.powf(alpha) / s).collect(),
        ]
    };
    let ssr = |alpha: f64| {
        let cols = cols(alpha);
        match least_squares(&cols, &yw) {
            Some(b) => (0..yw.len())
                .map(|i| (yw[i] - b[0] * cols[0][i] - b[1] * cols[1][i]).powi(2))
                .sum(),
            None => f64::INFINITY,
        }
    };
    let (lo, hi) = ALPHA_RANGE;
    let best = minimise(ssr, lo, hi, ((hi - lo) / ALPHA_STEP) as usize, 1e-10);
    let alpha = best.x;
    let lin = least_squares(&cols(alpha), &yw)?;
    let (c1, c2) = (lin[0], lin[1]);
    let jac: Vec<Vec<f64>> = vec![
        c.iter().zip(sd).map(|(c, s)| c.powi(3) / s).collect(),
        c.iter().zip(sd).map(|(c, s)| c.powf(alpha) / s).collect(),
        c.iter()
            .zip(sd)
            .map(|(c, s)| c2 * c.powf(alpha) * c.ln() / s)
            .collect(),
    ];
    let law = |c: f64| c1 * c.powi(3) + c2 * c.powf(alpha);
    Some((
        finish(c, y, sd, law, vec![c1, c2, alpha], &jac)?,
        best.at_bound,
    ))
}

/// The fit's standard deviations and RMS residual from its law and weighted Jacobian.
fn finish(
    c: &[f64],
    y: &[f64],
    sd: &[f64],
    law: impl Fn(f64) -> f64,
    values: Vec<f64>,
    jac: &[Vec<f64>],
) -> Option<Weighted> {
    let chi2: f64 = (0..c.len())
        .map(|i| ((y[i] - law(c[i])) / sd[i]).powi(2))
        .sum();
    let rms = ((0..c.len())
        .map(|i| (y[i] - law(c[i])).powi(2))
        .sum::<f64>()
        / c.len() as f64)
        .sqrt();
    let sd = coefficient_sd(jac, chi2, c.len().saturating_sub(values.len()))?;
    values
        .iter()
        .chain(&sd)
        .all(|v| v.is_finite())
        .then_some(Weighted { values, sd, rms })
}

/// The five coefficients (A, B, c1, c2, α) and their standard deviations from the branches
/// extrapolated over `range`, with α's bound flag, the RMS residuals and the limit branch.
struct Coefficients {
    values: [f64; 5],
    sd: [f64; 5],
    alpha_at_bound: bool,
    rms: (f64, f64),
    limit: LimitBranch,
}

fn coefficients(branches: &[GridBranch], range: (f64, f64), order: Order) -> Option<Coefficients> {
    let l = extrapolate(branches, range, LIMIT_POINTS, order)?;
    let d = fit_d(&l.c_bar, &l.d_bar, &l.d_sd)?;
    let (f, at_bound) = fit_f(&l.c_bar, &l.f_bar, &l.f_sd)?;
    let v = [d.values.as_slice(), f.values.as_slice()].concat();
    let s = [d.sd.as_slice(), f.sd.as_slice()].concat();
    Some(Coefficients {
        values: v.try_into().ok()?,
        sd: s.try_into().ok()?,
        alpha_at_bound: at_bound,
        rms: (d.rms, f.rms),
        limit: l,
    })
}

/// The branch laws of R1/R2 = `ratio` at Δx → 0 from its branches on two grids or more (see
/// the module's description for the half-widths). `None` with fewer than two grids, branches
/// that do not overlap in c̄, or data the laws cannot be fitted to.
pub fn branch_laws(ratio: f64, branches: &[GridBranch]) -> Option<BranchLaws> {
    let mut branches = branches.to_vec();
    branches.sort_by_key(|b| b.nx);
    let range = common_range(&branches)?;
    let all = coefficients(&branches, range, Order::First)?;
    // The largest move of each coefficient over the alternatives of one choice.
    let largest_move = |alternatives: Vec<Option<Coefficients>>| {
        let mut shift = [0.0f64; 5];
        for o in alternatives.into_iter().flatten() {
            for (s, (a, b)) in shift.iter_mut().zip(o.values.iter().zip(&all.values)) {
                *s = s.max((a - b).abs());
            }
        }
        shift
    };
    // The extrapolation's model: one grid left out, or a parabola (three grids or more).
    let mut models = Vec::new();
    if branches.len() >= 3 {
        for i in 0..branches.len() {
            let rest: Vec<GridBranch> = branches
                .iter()
                .enumerate()
                .filter(|(j, _)| *j != i)
                .map(|(_, b)| b.clone())
                .collect();
            models.push(coefficients(&rest, range, Order::First));
        }
        models.push(coefficients(&branches, range, Order::Second));
    }
    let model = largest_move(models);
    // The c̄ range: a tenth left out at either end.
    let w = RANGE_TRIM * (range.1 - range.0);
    let trimmed = largest_move(vec![
        coefficients(&branches, (range.0 + w, range.1), Order::First),
        coefficients(&branches, (range.0, range.1 - w), Order::First),
    ]);
    // Independent choices add in quadrature, with twice the fit's standard deviation.
    let est = |i: usize| Estimate {
        value: all.values[i],
        uncertainty: (2.0 * all.sd[i]).hypot(model[i]).hypot(trimmed[i]),
    };
    Some(BranchLaws {
        ratio,
        grids: branches.iter().map(|b| b.nx).collect(),
        c_range: range,
        a: est(0),
        b: est(1),
        c1: est(2),
        c2: est(3),
        alpha: est(4),
        alpha_at_bound: all.alpha_at_bound,
        d_rms: all.rms.0,
        f_rms: all.rms.1,
        points: all.limit.c_bar.len(),
        limit: all.limit,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// JKR's branch: d̄ = c̄² − (2/3)√2 c̄^½, F̄ = c̄³ − √2 c̄^{3/2}.
    fn jkr(c: f64) -> (f64, f64) {
        let r2 = std::f64::consts::SQRT_2;
        (
            c * c - 2.0 / 3.0 * r2 * c.sqrt(),
            c.powi(3) - r2 * c.powf(1.5),
        )
    }

    /// A grid's branch: JKR's, off by k/n at first order (n = c̄/h elements across), with a
    /// grid-phase wobble of relative amplitude `wobble`/n and a period of one element.
    fn grid(nx: usize, h: f64, k: (f64, f64), wobble: f64) -> GridBranch {
        let points = (0..1000)
            .map(|i| {
                let c = 0.45 + 1.0 * i as f64 / 999.0;
                let inv_n = h / c;
                let (d, f) = jkr(c);
                let phase = wobble * inv_n * (std::f64::consts::TAU * c / h + nx as f64).sin();
                BranchPoint {
                    c_bar: c,
                    d_bar: d + k.0 * inv_n + phase * d.abs().max(0.3),
                    f_bar: f + k.1 * inv_n + phase * f.abs().max(0.3),
                    inv_n,
                }
            })
            .collect();
        GridBranch { nx, points }
    }

    #[test]
    fn exact_first_order_branches_give_jkr_exactly() {
        let b: Vec<GridBranch> = [(32, 0.04), (64, 0.02), (128, 0.01)]
            .iter()
            .map(|&(nx, h)| grid(nx, h, (0.8, 1.5), 0.0))
            .collect();
        let l = branch_laws(1.0, &b).unwrap();
        let r2 = std::f64::consts::SQRT_2;
        for (e, exact) in [
            (l.a, 1.0),
            (l.b, -2.0 / 3.0 * r2),
            (l.c1, 1.0),
            (l.c2, -r2),
            (l.alpha, 1.5),
        ] {
            // Exact but for the linear interpolation between branch points 0.001 apart.
            assert!((e.value - exact).abs() < 1e-5, "{e:?} vs {exact}");
        }
        assert_eq!(l.grids, [32, 64, 128]);
        assert!((l.c_range.0 - 0.45).abs() < 1e-12 && (l.c_range.1 - 1.45).abs() < 1e-12);
    }

    #[test]
    fn a_grid_phase_wobble_is_held_by_the_stated_intervals() {
        let r2 = std::f64::consts::SQRT_2;
        for wobble in [0.05, 0.15] {
            let b: Vec<GridBranch> = [(32, 0.04), (64, 0.02), (128, 0.01)]
                .iter()
                .map(|&(nx, h)| grid(nx, h, (0.8, 1.5), wobble))
                .collect();
            let l = branch_laws(1.0, &b).unwrap();
            for (name, e, exact) in [
                ("A", l.a, 1.0),
                ("B", l.b, -2.0 / 3.0 * r2),
                ("c1", l.c1, 1.0),
                ("c2", l.c2, -r2),
                ("α", l.alpha, 1.5),
            ] {
                assert!(
                    e.contains(exact),
                    "wobble {wobble}: {name} {e:?} vs {exact}"
                );
                assert!(e.uncertainty > 0.0);
            }
        }
    }

    #[test]
    fn one_grid_or_disjoint_branches_give_no_laws() {
        let one = [grid(64, 0.02, (0.8, 1.5), 0.0)];
        assert!(branch_laws(1.0, &one).is_none());
        let mut far = grid(128, 0.01, (0.8, 1.5), 0.0);
        for p in &mut far.points {
            p.c_bar += 5.0;
        }
        assert!(branch_laws(1.0, &[one[0].clone(), far]).is_none());
    }

    #[test]
    fn the_inverse_diagonal_of_a_known_matrix() {
        let m = vec![vec![4.0, 2.0], vec![2.0, 3.0]];
        let d = inverse_diagonal(m).unwrap();
        // inverse = [[3, −2], [−2, 4]] / 8
        assert!((d[0] - 3.0 / 8.0).abs() < 1e-15 && (d[1] - 0.5).abs() < 1e-15);
        assert!(inverse_diagonal(vec![vec![1.0, 1.0], vec![1.0, 1.0]]).is_none());
    }
}
