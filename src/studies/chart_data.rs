//! What the sweep's and the study's charts draw beside the simulation's points: the closed
//! forms (JKR, JG) over each run's range, the laws fitted to the points, and the points
//! themselves as each chart takes them. Computed here, in the session layer that gathers the
//! runs; `output` only draws what it is given.

use crate::analysis::adhesive_branch;
use crate::analysis::capture::ContourRow;
use crate::analysis::study_fits::{BranchFits, CoefficientLaw, RatioRun};
use crate::analysis::PowerLawFit;
use crate::output::series::{LawCurve, Named};
use crate::output::study_charts::{AxisRatioSeries, BranchSeries, CoefficientSeries, MarkedState};
use crate::output::sweep_charts::SweepCurves;
use crate::output::sweep_csv::SweepRow;
use crate::solver::Phase;
use crate::theory::{self, TheoryModel, TheoryPoint};

/// Points of the closed-form curves of the sweep's pull-off chart (per ratio).
const SWEEP_THEORY_POINTS: usize = 300;

/// Points of the curves against R1/R2 on the sweep's force chart.
const RATIO_POINTS: usize = 200;

/// Points of the study's closed-form and fitted curves.
const STUDY_CURVE_POINTS: usize = 200;

/// The closed form a ratio is compared with (JKR for the sphere, JG otherwise), and its name
/// as the charts show it.
fn reference(ratio: f64) -> (TheoryModel, String) {
    let model = TheoryModel::adhesive_reference(ratio);
    (model, model.name().to_uppercase())
}

/// The closed form's curve for `ratio` in `points` points; empty if it cannot be evaluated.
fn theory_points(ratio: f64, points: usize) -> Vec<TheoryPoint> {
    theory::curve(reference(ratio).0, ratio, points).unwrap_or_default()
}

/// A fitted power law as a chart draws it: its coefficients, R² and (x, law(x)) at `xs`.
fn law_curve(law: &PowerLawFit, xs: impl Iterator<Item = f64>) -> LawCurve {
    LawCurve {
        k: [law.k1, law.k2, law.k3],
        r_squared: law.quality.r_squared,
        points: xs.map(|x| (x, law.eval(x))).collect(),
    }
}

/// `n` + 1 points from 1 to `hi`, evenly spaced in log.
fn log_range(hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |i| hi.powf(i as f64 / n as f64))
}

/// The closed form of `ratio` (JKR for the sphere, JG otherwise) as F̄(d̄) on the adhesive
/// branch up to the approach `d_max`, named as the charts show it.
pub fn reference_curve(ratio: f64, d_max: f64) -> Named {
    let (model, name) = reference(ratio);
    let points = theory::curve(model, ratio, SWEEP_THEORY_POINTS)
        .map(|pts| {
            pts.iter()
                .filter(|p| p.d_bar <= d_max)
                .map(|p| (p.d_bar, p.f_bar))
                .collect()
        })
        .unwrap_or_default();
    Named { name, points }
}

/// A sweep's charts' curves: each row's `pulloffs` (its (d̄, F̄) points, or why there are
/// none), its closed form on the adhesive branch up to its last approach (1 where it has no
/// points), JG's adhesive force over the sweep's ratios, and the law fitted to its forces
/// (those of rows not too coarse for their estimate: `sweep_charts::too_coarse`; more than
/// three, as the law has three coefficients), over the ratios fitted.
pub fn sweep_curves(
    rows: &[SweepRow],
    pulloffs: Vec<Result<Vec<(f64, f64)>, String>>,
) -> SweepCurves {
    let references = rows
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let d_max = match pulloffs.get(i) {
                Some(Ok(points)) => points.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
                _ => 1.0,
            };
            reference_curve(r.ratio, d_max)
        })
        .collect();
    let hi = rows.iter().map(|r| r.ratio).fold(2.0, f64::max);
    let jg_force = log_range(hi, RATIO_POINTS)
        .filter_map(|ratio| Some((ratio, theory::reference_adhesive_force(ratio).ok()?)))
        .collect();
    // Only answers are fitted: a grid too coarse for its estimate is drawn apart.
    let (x, y): (Vec<f64>, Vec<f64>) = rows
        .iter()
        .filter(|r| !crate::output::sweep_charts::too_coarse(r))
        .filter_map(|r| Some((r.ratio, r.f_ad_bar?)))
        .unzip();
    // A law of three coefficients through three points or fewer says nothing: no fit then.
    // It is drawn over the ratios it was fitted to, not beyond.
    let fitted_hi = x.iter().copied().fold(1.0, f64::max);
    let fit = (x.len() > 3)
        .then(|| crate::analysis::fit_power_law(&x, &y).ok())
        .flatten()
        .map(|law| law_curve(&law, log_range(fitted_hi, RATIO_POINTS)));
    SweepCurves {
        pulloffs,
        references,
        jg_force,
        fit,
    }
}

/// Each run's (F̄, b/a) over its pull-off states in contact, beside JG's over the run's range
/// of F̄; the runs of the ratios in `coarse` (grids too coarse for their estimate) marked so.
pub fn axis_ratio_series(runs: &[RatioRun], coarse: &[f64]) -> Vec<AxisRatioSeries> {
    runs.iter()
        .map(|run| {
            let points = run
                .states
                .iter()
                .filter(|s| s.phase != Phase::Approach && s.n_contact > 0 && s.a_bar > 0.0)
                .map(|s| (s.f_bar, s.b_bar / s.a_bar))
                .collect();
            let f_max = run.states.iter().map(|s| s.f_bar).fold(0.0, f64::max);
            let jg = theory_points(run.ratio, STUDY_CURVE_POINTS)
                .iter()
                .filter(|p| p.f_bar <= f_max && p.a_bar > 0.0)
                .map(|p| (p.f_bar, p.b_bar / p.a_bar))
                .collect();
            AxisRatioSeries {
                ratio: run.ratio,
                grid: run.grid,
                coarse: coarse.contains(&run.ratio),
                points,
                jg,
            }
        })
        .collect()
}

/// Each run's adhesive branch as (c̄, d̄, F̄), with its closed form and its fitted laws over
/// the branch's range of c̄; the runs of the ratios in `coarse` marked so (their fits are not
/// drawn).
pub fn branch_series(runs: &[RatioRun], fits: &[BranchFits], coarse: &[f64]) -> Vec<BranchSeries> {
    runs.iter()
        .zip(fits)
        .map(|(run, fit)| {
            let branch = adhesive_branch(&run.states);
            let c_max = branch.iter().map(|p| p.c_bar).fold(0.0, f64::max);
            let c_min = branch.iter().map(|p| p.c_bar).fold(f64::INFINITY, f64::min);
            let (_, reference_name) = reference(run.ratio);
            let reference = theory_points(run.ratio, STUDY_CURVE_POINTS)
                .iter()
                .filter(|p| p.c_bar <= c_max && p.c_bar >= c_min)
                .map(|p| [p.c_bar, p.d_bar, p.f_bar])
                .collect();
            let fit = match (&fit.d_of_c, &fit.f_of_c) {
                (Some(d), Some(f)) => Some(
                    (0..=STUDY_CURVE_POINTS)
                        .map(|k| c_min + (c_max - c_min) * k as f64 / STUDY_CURVE_POINTS as f64)
                        .map(|c| [c, d.eval(c), f.eval(c)])
                        .collect(),
                ),
                _ => None,
            };
            BranchSeries {
                ratio: run.ratio,
                grid: run.grid,
                coarse: coarse.contains(&run.ratio),
                branch: branch.iter().map(|p| [p.c_bar, p.d_bar, p.f_bar]).collect(),
                reference_name,
                reference,
                fit,
            }
        })
        .collect()
}

/// Each coefficient's points against R1/R2 and its law drawn from 1 to its largest ratio.
pub fn coefficient_series(laws: &[CoefficientLaw]) -> Vec<CoefficientSeries> {
    laws.iter()
        .map(|c| {
            let hi = c.points.iter().map(|p| p.0).fold(1.0, f64::max);
            CoefficientSeries {
                name: c.name,
                points: c.points.clone(),
                coarse: c.coarse.clone(),
                law: c
                    .law
                    .as_ref()
                    .map(|law| law_curve(law, log_range(hi, STUDY_CURVE_POINTS))),
            }
        })
        .collect()
}

/// The states a pull-off figure marks (the study's Fig. 2b), from a run's captured contours:
/// at most `max` of them, in the order of the pull-off (c̄ falling), the force minimum always
/// among them and the others those farthest from it in c̄ (without a minimum: the largest
/// c̄); each with its contact's outline, the quarter contour mirrored into a closed
/// loop.
pub fn marked_states(contours: &[ContourRow], max: usize) -> Vec<MarkedState> {
    let mut labels: Vec<&str> = Vec::new();
    for c in contours {
        if !labels.contains(&c.label.as_str()) {
            labels.push(&c.label);
        }
    }
    let mut marked: Vec<MarkedState> = labels
        .iter()
        .map(|label| {
            let group: Vec<&ContourRow> = contours.iter().filter(|c| c.label == *label).collect();
            let first = group[0];
            MarkedState {
                d_bar: first.d_bar,
                f_bar: first.f_bar,
                c_bar: first.c_bar,
                minimum: label.contains(crate::analysis::fields::minimum_label(true)),
                outline: closed_outline(group.iter().map(|c| (c.x_bar, c.y_bar)).collect()),
            }
        })
        .collect();
    // The force minimum stays; of the others, the one nearest it in c̄ goes first (it would
    // draw nearly the same outline), so that the marks spread along the curve.
    let c_min = marked.iter().find(|m| m.minimum).map(|m| m.c_bar);
    while marked.len() > max {
        let nearest = marked
            .iter()
            .enumerate()
            .filter(|(_, m)| !m.minimum)
            .min_by(|(_, a), (_, b)| {
                let gap = |m: &MarkedState| c_min.map_or(-m.c_bar, |c| (m.c_bar - c).abs());
                gap(a).total_cmp(&gap(b))
            })
            .map_or(marked.len() - 1, |(k, _)| k);
        marked.remove(nearest);
    }
    marked.sort_by(|a, b| b.c_bar.total_cmp(&a.c_bar));
    marked
}

/// A quarter contour (x, y ≥ 0) mirrored into the closed outline of the whole contact, by
/// angle from the x axis round the four quadrants.
fn closed_outline(mut quarter: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    quarter.sort_by(|a, b| a.1.atan2(a.0).total_cmp(&b.1.atan2(b.0)));
    let mut loop_ = quarter.clone();
    loop_.extend(quarter.iter().rev().map(|&(x, y)| (-x, y)));
    loop_.extend(quarter.iter().map(|&(x, y)| (-x, -y)));
    loop_.extend(quarter.iter().rev().map(|&(x, y)| (x, -y)));
    loop_.extend(quarter.first().copied());
    loop_
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(ratio: f64, f_ad_bar: f64) -> SweepRow {
        SweepRow::sample(ratio, f_ad_bar)
    }

    #[test]
    fn a_sweep_gets_its_closed_forms_jg_and_the_law_fitted_to_its_forces() {
        let mut rows: Vec<SweepRow> = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0]
            .iter()
            .map(|&r: &f64| row(r, 0.3 + 0.25 * r.powf(-0.4)))
            .collect();
        // A grid too coarse for its estimate (10 elements across the contact) over-predicts:
        // it is drawn apart and not fitted, so the law still comes back.
        rows.push(SweepRow {
            n_d: Some(10.0),
            ..row(100.0, 0.6)
        });
        let pulloffs = rows
            .iter()
            .map(|_| Ok(vec![(0.5, -0.1), (-0.3, -0.5)]))
            .collect();
        let c = sweep_curves(&rows, pulloffs);
        let chart = crate::output::sweep_charts::force_vs_ratio_chart(&rows, &c);
        let hollow: Vec<_> = chart
            .curves
            .iter()
            .filter(|k| k.style == crate::output::line_chart::Style::Hollow)
            .collect();
        assert_eq!(hollow.len(), 1);
        assert_eq!(hollow[0].points, vec![(100.0, 0.6)]);
        assert!(hollow[0].label.starts_with("coarse grid"));
        // JKR for the sphere, JG otherwise, each cut at the run's last approach (d̄ ≤ 0.5).
        assert_eq!(c.references[0].name, "JKR");
        assert_eq!(c.references[1].name, "JG");
        assert!(c
            .references
            .iter()
            .all(|r| !r.points.is_empty() && r.points.iter().all(|p| p.0 <= 0.5)));
        // JG's force from 1 to the largest ratio; JKR's 1/2 at 1.
        assert_eq!(c.jg_force.len(), RATIO_POINTS + 1);
        assert!((c.jg_force[0].1 - 0.5).abs() < 1e-9, "{:?}", c.jg_force[0]);
        assert!((c.jg_force.last().unwrap().0 - 100.0).abs() < 1e-9);
        // The law the points were made from comes back.
        let law = c.fit.expect("a fitted law");
        let [k1, k2, k3] = law.k;
        assert!((k1 - 0.25).abs() < 1e-6 && (k2 + 0.4).abs() < 1e-6 && (k3 - 0.3).abs() < 1e-6);
        assert!(law.r_squared > 0.999_999);
        // Over the ratios fitted (to 50), not to the coarse row's 100.
        assert!((law.points.last().unwrap().0 - 50.0).abs() < 1e-9);
        // Three answers fit no law of three coefficients.
        let three = sweep_curves(&rows[..3], vec![Err("none".into()); 3]);
        assert!(three.fit.is_none());
        assert!(law
            .points
            .iter()
            .all(|&(x, y)| (y - (0.3 + 0.25 * x.powf(-0.4))).abs() < 1e-6));
    }

    #[test]
    fn a_row_without_states_has_its_closed_form_up_to_d_1() {
        let rows = vec![row(2.0, 0.45)];
        let c = sweep_curves(&rows, vec![Err("no states".into())]);
        let jg = &c.references[0].points;
        assert!(!jg.is_empty() && jg.iter().all(|p| p.0 <= 1.0));
        assert!(c.fit.is_none(), "one point fits no law");
    }

    /// Quarter-circle contour rows of radius `c` for a capture labelled `label`.
    fn capture(label: &str, c: f64, f: f64) -> Vec<ContourRow> {
        (0..=8)
            .rev()
            .map(|k| {
                let t = k as f64 / 8.0 * std::f64::consts::FRAC_PI_2;
                ContourRow {
                    label: label.into(),
                    c_bar: c,
                    f_bar: f,
                    a_bar: c,
                    b_bar: c,
                    departure_rms: 0.0,
                    departure_max: 0.0,
                    x_bar: c * t.cos(),
                    y_bar: c * t.sin(),
                    d_bar: c * c - 1.0,
                }
            })
            .collect()
    }

    #[test]
    fn the_marked_states_keep_the_minimum_and_spread_along_the_pull_off() {
        let mut rows = Vec::new();
        for (label, c, f) in [
            ("c̄ ≤ 1.4", 1.4, 0.5),
            ("c̄ ≤ 1.1", 1.1, -0.2),
            ("c̄ ≤ 0.8", 0.79, -0.49),
            ("c̄ ≤ 0.5", 0.48, -0.3),
            ("force minimum", 0.77, -0.5),
        ] {
            rows.extend(capture(label, c, f));
        }
        let marked = marked_states(&rows, 4);
        let c: Vec<f64> = marked.iter().map(|m| m.c_bar).collect();
        // 0.79 draws nearly the minimum's outline (0.77): it is the one left out.
        assert_eq!(c, vec![1.4, 1.1, 0.77, 0.48]);
        assert!(marked[2].minimum && marked.iter().filter(|m| m.minimum).count() == 1);
        // A closed loop round the whole contact, every point at the capture's radius.
        let o = &marked[0].outline;
        assert_eq!(o.len(), 4 * 9 + 1);
        assert_eq!(o.first(), o.last());
        assert!(o.iter().all(|p| (p.0.hypot(p.1) - 1.4).abs() < 1e-12));
        let quadrants = |sx: f64, sy: f64| {
            o.iter()
                .filter(|p| p.0 * sx > 0.0 && p.1 * sy > 0.0)
                .count()
        };
        assert!([(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .iter()
            .all(|&(sx, sy)| quadrants(sx, sy) >= 7));
        // The outline turns one way round: the angle never steps back by more than a step.
        let angles: Vec<f64> = o
            .iter()
            .map(|p| p.1.atan2(p.0).rem_euclid(std::f64::consts::TAU))
            .collect();
        let backwards = angles
            .windows(2)
            .filter(|w| w[1] < w[0] - 1e-9 && w[0] - w[1] < 3.0)
            .count();
        assert_eq!(backwards, 0, "{angles:?}");
    }
}
