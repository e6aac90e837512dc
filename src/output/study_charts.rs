//! The charts of the study (physics §8.2, §8.4–§8.6) made from pull-off states: the axis ratio
//! b/a against F̄, the branch laws d̄(c̄), F̄(c̄), F̄(d̄) with their fits, the fitted
//! coefficients against R1/R2, and the adhesive force with its fitted law.

use super::line_chart::{LineChart, Style};
use crate::analysis::adhesive_branch;
use crate::analysis::study_fits::{BranchFits, CoefficientLaw, RatioRun};
use crate::solver::Phase;
use crate::theory::{self, TheoryModel, TheoryPoint};

/// Points of closed-form and fitted curves.
const CURVE_POINTS: usize = 200;

fn reference(ratio: f64) -> (TheoryModel, String) {
    let model = TheoryModel::adhesive_reference(ratio);
    (model, model.name().to_uppercase())
}

fn theory_points(ratio: f64) -> Vec<TheoryPoint> {
    theory::curve(reference(ratio).0, ratio, CURVE_POINTS).unwrap_or_default()
}

/// b/a against F̄ for each run (pull-off states in contact) beside JG's g(F̄).
pub fn axis_ratio_chart(runs: &[RatioRun]) -> LineChart {
    let mut chart = LineChart::new(
        "Contact axis ratio against force (markers: jkrbem, lines: JG)",
        "force F̄",
        "axis ratio b_simu / a_simu",
    );
    for (i, run) in runs.iter().enumerate() {
        let sim = run
            .states
            .iter()
            .filter(|s| s.phase != Phase::Approach && s.n_contact > 0 && s.a_bar > 0.0)
            .map(|s| (s.f_bar, s.b_bar / s.a_bar))
            .collect();
        chart.push(
            &format!("R1/R2 = {} ({}×{})", run.ratio, run.grid.0, run.grid.1),
            sim,
            i,
            Style::Markers,
        );
        let f_max = run.states.iter().map(|s| s.f_bar).fold(0.0, f64::max);
        let jg = theory_points(run.ratio)
            .iter()
            .filter(|p| p.f_bar <= f_max && p.a_bar > 0.0)
            .map(|p| (p.f_bar, p.b_bar / p.a_bar))
            .collect();
        chart.push(&format!("JG, R1/R2 = {}", run.ratio), jg, i, Style::Line);
    }
    chart
}

/// Which law of the branch a chart shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BranchLaw {
    /// d̄(c̄).
    DOfC,
    /// F̄(c̄).
    FOfC,
    /// F̄(d̄).
    FOfD,
}

/// One branch law for several runs: the adhesive branch (markers), the closed form (line) and
/// the fitted law (dashed).
pub fn branch_chart(runs: &[RatioRun], fits: &[BranchFits], law: BranchLaw) -> LineChart {
    let (title, x, y) = match law {
        BranchLaw::DOfC => ("Approach against contact radius", "c̄", "d̄"),
        BranchLaw::FOfC => ("Force against contact radius", "c̄", "F̄"),
        BranchLaw::FOfD => ("Force against approach", "d̄", "F̄"),
    };
    let mut chart = LineChart::new(
        &format!("{title} (markers: jkrbem, lines: JKR/JG, dashed: fit)"),
        x,
        y,
    );
    let pick = |c: f64, d: f64, f: f64| match law {
        BranchLaw::DOfC => (c, d),
        BranchLaw::FOfC => (c, f),
        BranchLaw::FOfD => (d, f),
    };
    for (i, (run, fit)) in runs.iter().zip(fits).enumerate() {
        let branch = adhesive_branch(&run.states);
        let c_max = branch.iter().map(|p| p.c_bar).fold(0.0, f64::max);
        let c_min = branch.iter().map(|p| p.c_bar).fold(f64::INFINITY, f64::min);
        chart.push(
            &format!("R1/R2 = {} ({}×{})", run.ratio, run.grid.0, run.grid.1),
            branch
                .iter()
                .map(|p| pick(p.c_bar, p.d_bar, p.f_bar))
                .collect(),
            i,
            Style::Markers,
        );
        let (_, name) = reference(run.ratio);
        chart.push(
            &format!("{name}, R1/R2 = {}", run.ratio),
            theory_points(run.ratio)
                .iter()
                .filter(|p| p.c_bar <= c_max && p.c_bar >= c_min)
                .map(|p| pick(p.c_bar, p.d_bar, p.f_bar))
                .collect(),
            i,
            Style::Line,
        );
        if let (Some(d), Some(f)) = (&fit.d_of_c, &fit.f_of_c) {
            let fitted = (0..=CURVE_POINTS)
                .map(|k| c_min + (c_max - c_min) * k as f64 / CURVE_POINTS as f64)
                .map(|c| pick(c, d.eval(c), f.eval(c)))
                .collect();
            chart.push(
                &format!("fit, R1/R2 = {}", run.ratio),
                fitted,
                i,
                Style::Dashed,
            );
        }
    }
    chart
}

/// The fitted coefficients against R1/R2 (log axis) with their laws (dashed).
pub fn coefficients_chart(laws: &[CoefficientLaw]) -> LineChart {
    let mut chart = LineChart::new(
        "Branch-law coefficients against axis ratio (dashed: k1·(R1/R2)^k2 + k3)",
        "R1/R2",
        "coefficient",
    );
    chart.x_log = true;
    for (i, c) in laws.iter().enumerate() {
        let hi = c.points.iter().map(|p| p.0).fold(1.0, f64::max);
        let pts: Vec<(f64, f64)> = c.points.iter().map(|p| (p.0, p.1)).collect();
        match c.points.iter().map(|p| p.2).collect::<Option<Vec<f64>>>() {
            Some(errors) => chart.push_with_errors(c.name, pts, errors, i),
            None => chart.push(c.name, pts, i, Style::Markers),
        }
        if let Some(law) = c.law {
            let curve = (0..=CURVE_POINTS)
                .map(|k| hi.powf(k as f64 / CURVE_POINTS as f64))
                .map(|x| (x, law.eval(x)))
                .collect();
            chart.push(
                &format!(
                    "{} = {}",
                    c.name,
                    crate::text::power_law(law.k1, law.k2, law.k3)
                ),
                curve,
                i,
                Style::Dashed,
            );
        }
    }
    chart
}

/// Quarter contours of the contact at the captured states of one run (markers) beside the
/// ellipses with the same half-axes (lines), in c_r units (physics §8.1 snapshots, §8.3).
pub fn contour_chart(ratio: f64, rows: &[crate::analysis::capture::ContourRow]) -> LineChart {
    let mut chart = LineChart::new(
        &format!(
            "Quarter contours during pull-off, R1/R2 = {ratio} (x, y in c_r, equal scales; \
             lines: ellipses ā, b̄)"
        ),
        "x / c_r",
        "y / c_r",
    );
    chart.equal_scales = true;
    let mut labels: Vec<&str> = rows.iter().map(|r| r.label.as_str()).collect();
    labels.dedup();
    for (i, label) in labels.iter().enumerate() {
        let group: Vec<_> = rows.iter().filter(|r| r.label == *label).collect();
        let first = group[0];
        chart.push(
            &format!(
                "{label}: c̄ = {:.2}, F̄ = {:.3}, departure rms {:.1} %",
                first.c_bar,
                first.f_bar,
                100.0 * first.departure_rms
            ),
            group.iter().map(|r| (r.x_bar, r.y_bar)).collect(),
            i,
            Style::Markers,
        );
        let ellipse = (0..=CURVE_POINTS)
            .map(|k| k as f64 / CURVE_POINTS as f64 * std::f64::consts::FRAC_PI_2)
            .map(|t| (first.a_bar * t.cos(), first.b_bar * t.sin()))
            .collect();
        chart.push(&format!("ellipse {label}"), ellipse, i, Style::Line);
    }
    chart
}
