//! The Δx → 0 limit of a grid-dependent value, with its uncertainty, for a shape that has no
//! convergence law of its own (the power law, the flat punch, a height map): from the value on
//! several grids of one domain (Δx refined), each run at several grid phases (the apex's
//! position within an element, [`crate::model::ModelOptions::apex_offset`]).
//!
//! # Method
//!
//! Each grid i (element side h_i) gives P_i ≥ [`MIN_PHASES`] values, one per grid phase: their
//! mean m_i and the standard error of that mean σ_i = s_i/√P_i (s_i: the phases' sample standard
//! deviation). The phase scatter is where the contact's edge falls between element centres; it
//! need not shrink with h like a power law (the flat punch's edge), so it is measured on every
//! grid, not modelled.
//!
//! The means are Richardson-extrapolated: m_i = v∞ + k·h_i^p, fitted by weighted least squares
//! (weights 1/σ_i²) at each order p in [[`MIN_ORDER`], [`MAX_ORDER`]] (steps of 0.005). The
//! order is estimated from the grids where there are three or more: each p is weighted by the
//! fit's likelihood exp(−χ²(p)/2) times a prior, the mesh-dependent criterion's first order
//! (physics §7), p ~ N([`PRIOR_ORDER`], [`PRIOR_ORDER_SD`]²). Where the grids fix p (three or
//! more grids whose differences stand out of their phase scatter) the prior hardly matters and
//! the order is *estimated*; where they cannot (two grids, or differences lost in the
//! scatter), the order is *assumed* first order, within the prior's spread, and the data are
//! only checked against it ([`GenericLimit::order_estimated`] says which). The limit is the
//! average of v∞(p) over that weighting. Its stated half-width combines:
//!
//! - (a) the grid phases: the weighted mean of the fit's intercept variance (the spread of
//!   the phases at each grid, propagated through the extrapolation);
//! - (b) the extrapolation's own error: how far the limit moves when the coarsest grid is
//!   left out (four grids or more), and at least [`SAFETY_MARGIN`] of the correction
//!   v∞ − m_finest (the three-grid safety factor 1.25 of Roache's grid convergence index);
//! - (c) the order's uncertainty: the spread of v∞(p) over the weighting of p.
//!
//! (a) and (c) are standard deviations, widened by the Birge ratio of the fit where four grids
//! or more scatter more than their phases say, and multiplied by Student's t (97.5 %) for the
//! degrees of freedom of the phase scatter Σ(P_i − 1) (few phases know their scatter
//! poorly); (b) is a bound. The half-width is the three in quadrature.
//!
//! The estimate is refused, saying why, where the values do not converge: a finest difference
//! that stands out of the scatter and does not shrink (or alternates in sign with a coarser one
//! that also stands out), or an order the data put outside [[`MIN_ORDER`], [`MAX_ORDER`]]
//! (the best order on [0.05, 8] fits better than every plausible one by Δχ² > 4).

use super::line_fit::{fit_free_line, Point};
use serde::Serialize;

/// Smallest plausible order of convergence (dimensionless).
pub const MIN_ORDER: f64 = 0.3;
/// Largest plausible order of convergence (dimensionless).
pub const MAX_ORDER: f64 = 3.0;
/// The order the prior centres on: the mesh-dependent criterion converges at first order in
/// Δx (physics §7).
pub const PRIOR_ORDER: f64 = 1.0;
/// The prior's standard deviation of the order (dimensionless).
pub const PRIOR_ORDER_SD: f64 = 0.25;
/// Fewest grid phases per grid: one value per grid says nothing of the phase scatter.
pub const MIN_PHASES: usize = 2;
/// The least part of the Richardson correction stated as the extrapolation's own error (b):
/// Roache's three-grid safety factor 1.25, less one.
pub const SAFETY_MARGIN: f64 = 0.25;
/// The factor the order's standard deviation is multiplied by: its posterior's two-sided
/// 95 % (the prior, not the phases' few samples, sets most of it).
const ORDER_FACTOR: f64 = 2.0;
/// Steps of the order's grid (dimensionless).
const ORDER_STEP: f64 = 0.005;
/// The wider range of orders the data are searched over, to tell an order outside the
/// plausible range (dimensionless).
const SEARCH_RANGE: (f64, f64) = (0.05, 8.0);
/// How many standard deviations a difference must exceed to stand out of the phase scatter.
const SIGNIFICANT: f64 = 2.0;
/// Δχ² by which an order outside the plausible range must fit better to refuse (2σ).
const OUTSIDE_CHI2: f64 = 4.0;
/// The smallest standard error of a grid's mean, relative to its value: a floor for phases
/// that agree to round-off.
const MIN_RELATIVE_SE: f64 = 1e-9;

/// One grid's values: its element side and the value at each grid phase.
#[derive(Debug, Clone, PartialEq)]
pub struct GridPhases {
    /// The grid, for messages ("128×128").
    pub label: String,
    /// Element side Δx (length; any unit common to the grids).
    pub dx: f64,
    /// The value at each grid phase (any unit common to the grids).
    pub values: Vec<f64>,
}

/// The Δx → 0 limit and how it was made.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GenericLimit {
    /// The best estimate of the limit (the values' unit).
    pub value: f64,
    /// Half-width of the interval stated to hold the limit (the values' unit): (a), (b) and
    /// (c) in quadrature.
    pub uncertainty: f64,
    /// (a): the grid phases' part of the half-width.
    pub phase_part: f64,
    /// (b): the extrapolation's own error (a bound).
    pub extrapolation_part: f64,
    /// (c): the order's part of the half-width.
    pub order_part: f64,
    /// The order p (the weighted mean over its posterior; dimensionless).
    pub order: f64,
    /// Its standard deviation (dimensionless).
    pub order_sd: f64,
    /// Whether the grids estimated the order (three or more whose differences stand out);
    /// false: it is assumed first order within the prior's spread, the data only checked
    /// against it.
    pub order_estimated: bool,
    /// The order the grids alone fit best in the plausible range (three grids or more).
    pub data_order: Option<f64>,
    /// The factor the standard deviations are multiplied by (Student's t at 97.5 %, times
    /// the Birge ratio where above 1).
    pub coverage_factor: f64,
    /// The finest grid's mean over its phases.
    pub finest_mean: f64,
    /// The finest grid's phase spread (sample standard deviation).
    pub finest_spread: f64,
    /// The grids' labels, coarse to fine.
    pub grids: Vec<String>,
    /// Phases per grid, coarse to fine.
    pub phases: Vec<usize>,
}

impl GenericLimit {
    /// The half-width relative to the value (dimensionless).
    pub fn relative(&self) -> f64 {
        self.uncertainty / self.value.abs()
    }

    /// How the estimate was made, in words.
    pub fn method(&self) -> String {
        let order = if self.order_estimated {
            format!(
                "order p = {:.2} ± {:.2} estimated from the grids (prior: first order, ± {})",
                self.order, self.order_sd, PRIOR_ORDER_SD
            )
        } else {
            let data = self.data_order.map_or(String::new(), |p| {
                format!("; the grids alone fit p = {p:.2}")
            });
            format!(
                "order assumed first order (p = {:.2} ± {:.2}: the grids cannot fix it{data})",
                self.order, self.order_sd
            )
        };
        format!(
            "grids {} with {:?} grid phases (apex offsets): their phase means Richardson-\
             extrapolated, v = v∞ + k·Δx^p by weighted least squares, {order}; ± the grid \
             phases {:.2e}, the extrapolation's own error {:.2e} (the shift without the \
             coarsest grid, at least {} of the correction) and the order's uncertainty {:.2e}, \
             in quadrature (factor {:.2})",
            self.grids.join(", "),
            self.phases,
            self.phase_part,
            self.extrapolation_part,
            SAFETY_MARGIN,
            self.order_part,
            self.coverage_factor
        )
    }
}

/// One grid's summary: h (relative to the finest), mean, its standard error, phase sd.
#[derive(Debug, Clone, Copy)]
struct GridMean {
    h: f64,
    mean: f64,
    se: f64,
    sd: f64,
}

/// The weighted least-squares line m = v + k·x, x = h^p, through the grids at one order
/// ([`fit_free_line`], weights 1/se²): (v, var v, χ²).
fn fit_at(grids: &[GridMean], p: f64) -> Option<(f64, f64, f64)> {
    let points: Vec<Point> = grids
        .iter()
        .map(|g| Point {
            x: g.h.powf(p),
            y: g.mean,
            sd: g.se,
        })
        .collect();
    let f = fit_free_line(&points)?;
    Some((f.intercept, f.intercept_sd * f.intercept_sd, f.chi2))
}

/// The orders from `lo` to `hi` in [`ORDER_STEP`]s.
fn orders(lo: f64, hi: f64) -> impl Iterator<Item = f64> {
    let n = ((hi - lo) / ORDER_STEP).round() as usize;
    (0..=n).map(move |i| lo + (hi - lo) * i as f64 / n as f64)
}

/// Student's t at 97.5 % (two-sided 95 %) for `dof` degrees of freedom (dimensionless).
pub fn student_t_975(dof: usize) -> f64 {
    const T: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match dof {
        0 => f64::INFINITY,
        d if d <= 30 => T[d - 1],
        d if d <= 60 => 2.0,
        _ => 1.96,
    }
}

/// The weighted limit over the orders: (v∞, its phase variance, its order variance, the
/// order's mean and sd, χ² at the posterior's mode).
struct Weighted {
    value: f64,
    var_phase: f64,
    var_order: f64,
    order: f64,
    order_sd: f64,
    chi2_at_mode: f64,
}

/// Average v∞(p) over p in the plausible range, weighted by the fit's likelihood and the
/// first-order prior.
fn weighted(grids: &[GridMean]) -> Option<Weighted> {
    let fits: Vec<(f64, (f64, f64, f64))> = orders(MIN_ORDER, MAX_ORDER)
        .filter_map(|p| fit_at(grids, p).map(|f| (p, f)))
        .collect();
    let log_post =
        |p: f64, chi2: f64| -0.5 * chi2 - 0.5 * ((p - PRIOR_ORDER) / PRIOR_ORDER_SD).powi(2);
    let (mode, best) = fits
        .iter()
        .map(|&(p, (_, _, chi2))| (p, log_post(p, chi2)))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let mut sum = 0.0;
    let (mut v, mut var, mut pm) = (0.0, 0.0, 0.0);
    for &(p, (vp, varp, chi2)) in &fits {
        let w = (log_post(p, chi2) - best).exp();
        sum += w;
        v += w * vp;
        var += w * varp;
        pm += w * p;
    }
    if sum.is_nan() || sum <= 0.0 {
        return None;
    }
    let (v, var, pm) = (v / sum, var / sum, pm / sum);
    let (mut var_order, mut var_p) = (0.0, 0.0);
    for &(p, (vp, _, chi2)) in &fits {
        let w = (log_post(p, chi2) - best).exp() / sum;
        var_order += w * (vp - v).powi(2);
        var_p += w * (p - pm).powi(2);
    }
    let chi2_at_mode = fit_at(grids, mode)?.2;
    Some(Weighted {
        value: v,
        var_phase: var,
        var_order,
        order: pm,
        order_sd: var_p.sqrt(),
        chi2_at_mode,
    })
}

/// The order the grids alone fit best on `range`, with its χ² (three grids or more).
fn best_order(grids: &[GridMean], range: (f64, f64)) -> Option<(f64, f64)> {
    orders(range.0, range.1)
        .filter_map(|p| fit_at(grids, p).map(|f| (p, f.2)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// The Δx → 0 limit of `grids` (any order; at least two, each with at least [`MIN_PHASES`]
/// values) and its uncertainty (see the module's method). Fails, saying why, on too few
/// grids or phases, a value that is not finite, two grids of one Δx, or values that do not
/// converge.
pub fn limit(grids: &[GridPhases]) -> Result<GenericLimit, String> {
    let mut grids: Vec<&GridPhases> = grids.iter().collect();
    if grids.len() < 2 {
        return Err(format!(
            "{} grid(s): an extrapolation to Δx → 0 needs two grids or more (three to estimate \
             the order)",
            grids.len()
        ));
    }
    if let Some(g) = grids
        .iter()
        .find(|g| !(g.dx.is_finite() && g.dx > 0.0) || g.values.iter().any(|v| !v.is_finite()))
    {
        return Err(format!(
            "the {} grid has a value that is not finite",
            g.label
        ));
    }
    if let Some(g) = grids.iter().find(|g| g.values.len() < MIN_PHASES) {
        return Err(format!(
            "the {} grid has {} grid phase(s): the phase scatter needs {MIN_PHASES} or more per \
             grid",
            g.label,
            g.values.len()
        ));
    }
    grids.sort_by(|a, b| b.dx.total_cmp(&a.dx));
    if let Some(w) = grids.windows(2).find(|w| w[1].dx >= w[0].dx) {
        return Err(format!(
            "the {} and {} grids have the same Δx: give grids of different Δx",
            w[0].label, w[1].label
        ));
    }
    let finest_dx = grids[grids.len() - 1].dx;
    let means: Vec<GridMean> = grids
        .iter()
        .map(|g| {
            let n = g.values.len() as f64;
            let mean = g.values.iter().sum::<f64>() / n;
            let sd = (g.values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
            GridMean {
                h: g.dx / finest_dx,
                mean,
                se: (sd / n.sqrt()).max(MIN_RELATIVE_SE * mean.abs().max(f64::MIN_POSITIVE)),
                sd,
            }
        })
        .collect();
    converging(&grids, &means)?;
    let data_order = (means.len() >= 3)
        .then(|| best_order(&means, (MIN_ORDER, MAX_ORDER)))
        .flatten();
    if let (Some((p_in, chi2_in)), Some((p_out, chi2_out))) = (
        data_order,
        (means.len() >= 3)
            .then(|| best_order(&means, SEARCH_RANGE))
            .flatten(),
    ) {
        if chi2_in - chi2_out > OUTSIDE_CHI2 {
            return Err(format!(
                "the grids converge at order p ≈ {p_out:.2} in Δx, outside the plausible \
                 [{MIN_ORDER}, {MAX_ORDER}] (the best plausible order, {p_in:.2}, fits worse by \
                 Δχ² = {:.1}): not an asymptotic first-order convergence; refine the grids",
                chi2_in - chi2_out
            ));
        }
    }
    let w = weighted(&means).ok_or("the grids' values cannot be fitted")?;
    let dof_phase: usize = grids.iter().map(|g| g.values.len() - 1).sum();
    let birge = if means.len() >= 4 {
        (w.chi2_at_mode / (means.len() - 3) as f64).sqrt().max(1.0)
    } else {
        1.0
    };
    let factor = student_t_975(dof_phase) * birge;
    let finest = means[means.len() - 1];
    let correction = (w.value - finest.mean).abs();
    let without_coarsest = if grids.len() >= 4 {
        let rest: Vec<GridPhases> = grids[1..].iter().map(|g| (*g).clone()).collect();
        limit(&rest).ok().map(|l| (l.value - w.value).abs())
    } else {
        None
    };
    let phase_part = factor * w.var_phase.sqrt();
    let order_part = ORDER_FACTOR * birge * w.var_order.sqrt();
    let extrapolation_part = (SAFETY_MARGIN * correction).max(without_coarsest.unwrap_or(0.0));
    // The grids estimate the order where they narrow the prior's spread by half or more.
    let order_estimated = means.len() >= 3 && w.order_sd <= 0.5 * PRIOR_ORDER_SD;
    Ok(GenericLimit {
        value: w.value,
        uncertainty: phase_part.hypot(extrapolation_part).hypot(order_part),
        phase_part,
        extrapolation_part,
        order_part,
        order: w.order,
        order_sd: w.order_sd,
        order_estimated,
        data_order: data_order.map(|d| d.0),
        coverage_factor: factor,
        finest_mean: finest.mean,
        finest_spread: finest.sd,
        grids: grids.iter().map(|g| g.label.clone()).collect(),
        phases: grids.iter().map(|g| g.values.len()).collect(),
    })
}

/// Refuse values that do not converge: a finest difference that stands out of the phase
/// scatter and does not shrink, or that alternates in sign with a coarser one that also
/// stands out.
fn converging(grids: &[&GridPhases], means: &[GridMean]) -> Result<(), String> {
    let n = means.len();
    if n < 3 {
        return Ok(());
    }
    let (a, b, c) = (means[n - 3], means[n - 2], means[n - 1]);
    let (d1, d2) = (a.mean - b.mean, b.mean - c.mean);
    let s1 = a.se.hypot(b.se);
    let s2 = b.se.hypot(c.se);
    let stands = |d: f64, s: f64| d.abs() > SIGNIFICANT * s;
    let labels = format!(
        "{}, {}, {}",
        grids[n - 3].label,
        grids[n - 2].label,
        grids[n - 1].label
    );
    if stands(d2, s2) && stands(d1, s1) && d1 * d2 < 0.0 {
        return Err(format!(
            "the values do not converge: the means of grids {labels} ({:.5}, {:.5}, {:.5}) move \
             by {:+.2e} and then {:+.2e}, each beyond twice its grid-phase scatter (not a \
             monotone convergence); refine the grids",
            a.mean, b.mean, c.mean, -d1, -d2
        ));
    }
    if stands(d2, s2) && d2.abs() >= d1.abs() {
        return Err(format!(
            "the values do not converge: the means of grids {labels} ({:.5}, {:.5}, {:.5}) \
             differ by {:.2e} and then {:.2e}, beyond the grid-phase scatter and not shrinking; \
             refine the grids",
            a.mean,
            b.mean,
            c.mean,
            d1.abs(),
            d2.abs()
        ));
    }
    Ok(())
}

/// The grids of `runs` for [`limit`]: each grid's |min F̄| (dimensionless) at every phase, its
/// Δx the runs' initial one. Fails, saying why, if a run did not reach its force minimum,
/// did not resolve it, or withheld its answer.
pub fn grids_of(runs: &[super::report::RunReport]) -> Result<Vec<GridPhases>, String> {
    let mut grids: Vec<GridPhases> = Vec::new();
    for r in runs {
        let f = match (r.min_reached, r.min_resolved, &r.withheld, r.f_ad_bar) {
            (false, _, _, _) | (_, _, _, None) if r.withheld.is_none() => {
                return Err(format!(
                    "the {} run (apex offset {}, {}) did not reach the force minimum",
                    r.grid, r.apex_offset[0], r.apex_offset[1]
                ))
            }
            (_, false, _, _) => {
                return Err(format!(
                    "the {} run's load steps were too large to resolve the force minimum",
                    r.grid
                ))
            }
            (_, _, Some(why), _) => {
                return Err(format!("the {} run withheld its answer: {why}", r.grid))
            }
            (_, _, _, Some(f)) => f,
            (_, _, _, None) => unreachable!("matched above"),
        };
        match grids.iter_mut().find(|g| g.label == r.grid) {
            Some(g) => g.values.push(f),
            None => grids.push(GridPhases {
                label: r.grid.clone(),
                dx: r.dx,
                values: vec![f],
            }),
        }
    }
    Ok(grids)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Uniform pseudo-random numbers in [0, 1) (a fixed LCG: deterministic).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn normal(&mut self) -> f64 {
            let (u, v) = (self.next().max(1e-300), self.next());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        }
    }

    /// Grids of side `dxs`, `phases` values each: v∞ + k·Δx^p + a phase noise of relative
    /// size `noise`·Δx^q (q = 0: a scatter that does not shrink).
    fn synthetic(
        rng: &mut Lcg,
        dxs: &[f64],
        phases: usize,
        (v_inf, k, p): (f64, f64, f64),
        (noise, q): (f64, f64),
    ) -> Vec<GridPhases> {
        dxs.iter()
            .map(|&dx| GridPhases {
                label: format!("Δx {dx}"),
                dx,
                values: (0..phases)
                    .map(|_| v_inf + k * dx.powf(p) + v_inf * noise * dx.powf(q) * rng.normal())
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn an_exact_power_law_is_extrapolated_exactly_and_its_order_found() {
        let mut rng = Lcg(1);
        for p in [0.6, 1.0, 1.7] {
            let g = synthetic(
                &mut rng,
                &[0.4, 0.2, 0.1, 0.05],
                3,
                (0.5, 0.3, p),
                (0.0, 0.0),
            );
            let l = limit(&g).unwrap();
            assert!((l.value - 0.5).abs() < 1e-4, "{p}: {l:?}");
            assert!((l.order - p).abs() < 0.01, "{p}: {l:?}");
            assert!(l.order_estimated);
            assert!(l.contains_for_test(0.5));
        }
    }

    impl GenericLimit {
        fn contains_for_test(&self, x: f64) -> bool {
            (x - self.value).abs() <= self.uncertainty
        }
    }

    #[test]
    fn the_stated_interval_holds_the_limit_nine_times_in_ten() {
        // First order (and 0.6, 1.5) with a phase noise shrinking with Δx (power-law-like) or
        // not (the punch's edge), 2 to 4 grids of ratio 2, 4 phases each.
        let mut rng = Lcg(11);
        let (mut held, mut cases, mut refused) = (0, 0, 0);
        let mut widths = Vec::new();
        for &p in &[0.6, 1.0, 1.5] {
            for &(noise, q) in &[(0.15, 1.0), (0.3, 1.0), (0.002, 0.0)] {
                for dxs in [
                    &[0.04, 0.02][..],
                    &[0.08, 0.04, 0.02],
                    &[0.08, 0.04, 0.02, 0.01],
                ] {
                    for _ in 0..40 {
                        let k = 0.5 * (0.5 + rng.next()) * 3.0;
                        let g = synthetic(&mut rng, dxs, 4, (0.5, k, p), (noise, q));
                        match limit(&g) {
                            Ok(l) => {
                                cases += 1;
                                held += usize::from(l.contains_for_test(0.5));
                                widths.push(l.relative());
                            }
                            Err(_) => refused += 1,
                        }
                    }
                }
            }
        }
        let coverage = held as f64 / cases as f64;
        widths.sort_by(f64::total_cmp);
        println!(
            "held {held} of {cases} ({:.1} %), refused {refused}; median relative half-width \
             {:.2} %",
            100.0 * coverage,
            100.0 * widths[widths.len() / 2]
        );
        assert!(coverage >= 0.9, "coverage {coverage}");
        assert!(
            10 * refused <= cases,
            "refused {refused} of {}",
            cases + refused
        );
    }

    #[test]
    fn values_that_do_not_converge_are_refused() {
        // Differences growing as Δx shrinks.
        let grow = [0.4, 0.2, 0.1]
            .iter()
            .zip([0.50, 0.51, 0.53])
            .map(|(&dx, v)| GridPhases {
                label: format!("{dx}"),
                dx,
                values: vec![v, v + 1e-4, v - 1e-4],
            })
            .collect::<Vec<_>>();
        let e = limit(&grow).unwrap_err();
        assert!(e.contains("do not converge"), "{e}");
        // Alternating beyond the scatter.
        let alt = [0.4, 0.2, 0.1]
            .iter()
            .zip([0.50, 0.56, 0.53])
            .map(|(&dx, v)| GridPhases {
                label: format!("{dx}"),
                dx,
                values: vec![v, v + 1e-4],
            })
            .collect::<Vec<_>>();
        assert!(limit(&alt).unwrap_err().contains("monotone"));
        // Converging far faster than any plausible order (p = 6).
        let mut rng = Lcg(3);
        let fast = synthetic(
            &mut rng,
            &[0.8, 0.4, 0.2, 0.1],
            3,
            (0.5, 2.0, 6.0),
            (1e-7, 0.0),
        );
        let e = limit(&fast).unwrap_err();
        assert!(e.contains("outside the plausible"), "{e}");
        // Too few grids or phases, or two grids of one Δx.
        let one = synthetic(&mut rng, &[0.1], 3, (0.5, 1.0, 1.0), (0.01, 0.0));
        assert!(limit(&one).is_err());
        let single = synthetic(&mut rng, &[0.2, 0.1], 1, (0.5, 1.0, 1.0), (0.01, 0.0));
        assert!(limit(&single).unwrap_err().contains("grid phase"));
        let same = synthetic(&mut rng, &[0.1, 0.1], 2, (0.5, 1.0, 1.0), (0.01, 0.0));
        assert!(limit(&same).unwrap_err().contains("same Δx"));
    }

    #[test]
    fn two_grids_assume_first_order_and_say_so() {
        let mut rng = Lcg(5);
        let g = synthetic(&mut rng, &[0.02, 0.01], 4, (0.5, 1.0, 1.0), (0.05, 1.0));
        let l = limit(&g).unwrap();
        assert!(!l.order_estimated && l.data_order.is_none());
        assert!((l.order - 1.0).abs() < 0.2, "{l:?}");
        assert!(l.method().contains("assumed first order"), "{}", l.method());
        assert!(l.order_part > 0.0 && l.extrapolation_part > 0.0);
    }

    /// Measured (CPU, f64, `--measure adhesive-force`, apex offsets 0:0, 0.25:0.25, 0.5:0.5,
    /// −0.25:0.5): the power law n = 3 (JKR: 0.510179) on 32² … 256² and the flat punch
    /// (Kendall: 1) on 32² … 128². Every ladder of three grids holds its closed form.
    #[test]
    fn measured_ladders_hold_their_closed_forms() {
        let power_law: [(usize, [f64; 4]); 4] = [
            (32, [0.597364, 0.560463, 0.608059, 0.566287]),
            (64, [0.556038, 0.538748, 0.552078, 0.53873]),
            (128, [0.535095, 0.52553, 0.533076, 0.527342]),
            (256, [0.522087, 0.518691, 0.52199, 0.518462]),
        ];
        let punch: [(usize, [f64; 4]); 3] = [
            (32, [1.022663, 1.010631, 0.991822, 1.002291]),
            (64, [1.013433, 1.003971, 1.003971, 1.003971]),
            (128, [1.001709, 1.001026, 1.005979, 1.001143]),
        ];
        let grids = |rows: &[(usize, [f64; 4])]| -> Vec<GridPhases> {
            rows.iter()
                .map(|(n, v)| GridPhases {
                    label: format!("{n}×{n}"),
                    dx: 1.0 / *n as f64,
                    values: v.to_vec(),
                })
                .collect()
        };
        for (rows, exact) in [
            (&power_law[..3], 0.510179),
            (&power_law[1..], 0.510179),
            (&power_law[..], 0.510179),
            (&punch[..], 1.0),
        ] {
            let l = limit(&grids(rows)).unwrap();
            println!(
                "{:?}: {:.5} ± {:.5} ({:.2} %), p = {:.2} ± {:.2} (estimated: {}), error {:+.2} %; parts {:.5} {:.5} {:.5} factor {:.2}",
                l.grids,
                l.value,
                l.uncertainty,
                100.0 * l.relative(),
                l.order,
                l.order_sd,
                l.order_estimated,
                100.0 * (l.value / exact - 1.0),
                l.phase_part,
                l.extrapolation_part,
                l.order_part,
                l.coverage_factor
            );
            assert!(l.contains_for_test(exact), "{l:?}");
        }
    }

    #[test]
    fn student_t_shrinks_to_the_normal() {
        assert!(student_t_975(0).is_infinite());
        assert!((student_t_975(3) - 3.182).abs() < 1e-9);
        assert!(student_t_975(1000) == 1.96);
        assert!((1..100).all(|d| student_t_975(d) >= student_t_975(d + 1)));
    }
}
