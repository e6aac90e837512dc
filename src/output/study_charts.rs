//! The charts of the study (physics §8.1–§8.6) made from pull-off states: the axis ratio
//! b/a against F̄, the branch laws d̄(c̄), F̄(c̄), F̄(d̄) with their fits, the fitted
//! coefficients against R1/R2, the contours, and a pull-off curve beside the contact outlines
//! of its marked states (the study's Fig. 2b). The points, closed forms and fitted laws come
//! computed from the session layer (`studies::chart_data`); this module only draws them.

use super::line_chart::{LineChart, Style};
use super::panels::Panels;
use super::series::LawCurve;

/// Points of the ellipses beside the contours.
const CURVE_POINTS: usize = 200;

/// One ratio's points for the axis-ratio chart, gathered by the session layer.
#[derive(Debug, Clone, PartialEq)]
pub struct AxisRatioSeries {
    /// R1/R2.
    pub ratio: f64,
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// Whether the grid is too coarse for the ratio's estimate (drawn hollow).
    pub coarse: bool,
    /// (F̄, b/a) of the run's pull-off states in contact.
    pub points: Vec<(f64, f64)>,
    /// (F̄, b/a) of Johnson–Greenwood's curve over the run's range of F̄.
    pub jg: Vec<(f64, f64)>,
}

/// b/a against F̄ for each run (pull-off states in contact) beside JG's g(F̄).
pub fn axis_ratio_chart(series: &[AxisRatioSeries]) -> LineChart {
    let mut chart = LineChart::new(
        "Contact axis ratio against force (markers: jkrbem, lines: JG)",
        F_AXIS,
        "contact axis ratio b/a (minor / major half-axis)",
    );
    for (i, run) in series.iter().enumerate() {
        chart.push(
            &run_label(run.ratio, run.grid, run.coarse),
            run.points.clone(),
            i,
            run_style(run.coarse),
        );
        chart.push(
            &format!("JG, R1/R2 = {}", run.ratio),
            run.jg.clone(),
            i,
            Style::Line,
        );
    }
    chart
}

/// A point of an adhesive branch: (c̄, d̄, F̄), each dimensionless.
pub type BranchTriple = [f64; 3];

/// One ratio's adhesive branch, its closed form and its fitted laws, as (c̄, d̄, F̄) points
/// from which each branch chart takes its two coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct BranchSeries {
    /// R1/R2.
    pub ratio: f64,
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// Whether the grid is too coarse for the ratio's estimate: its branch is drawn hollow and
    /// its fit is not drawn.
    pub coarse: bool,
    /// The run's adhesive branch (its onset states).
    pub branch: Vec<BranchTriple>,
    /// The closed form's name ("JKR", "JG").
    pub reference_name: String,
    /// The closed form over the branch's range of c̄.
    pub reference: Vec<BranchTriple>,
    /// The fitted laws d̄(c̄) and F̄(c̄) over that range, where both were fitted.
    pub fit: Option<Vec<BranchTriple>>,
}

/// The mean contact radius's axis, with its definition (physics §2).
const C_AXIS: &str = "mean contact radius c̄ = √(A/π) / c_r";
/// The approach's axis.
const D_AXIS: &str = "approach d̄ = d·Re / c_r²";
/// The force's axis.
const F_AXIS: &str = "force F̄ = F / (3π Re Δγ)";

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
pub fn branch_chart(series: &[BranchSeries], law: BranchLaw) -> LineChart {
    let (title, x, y) = match law {
        BranchLaw::DOfC => ("Approach against contact radius", C_AXIS, D_AXIS),
        BranchLaw::FOfC => ("Force against contact radius", C_AXIS, F_AXIS),
        BranchLaw::FOfD => ("Force against approach", D_AXIS, F_AXIS),
    };
    let mut chart = LineChart::new(
        &format!("{title} (markers: jkrbem, lines: JKR/JG, dashed: fit)"),
        x,
        y,
    );
    let pick = |points: &[BranchTriple]| -> Vec<(f64, f64)> {
        points
            .iter()
            .map(|&[c, d, f]| match law {
                BranchLaw::DOfC => (c, d),
                BranchLaw::FOfC => (c, f),
                BranchLaw::FOfD => (d, f),
            })
            .collect()
    };
    for (i, run) in series.iter().enumerate() {
        chart.push(
            &run_label(run.ratio, run.grid, run.coarse),
            pick(&run.branch),
            i,
            run_style(run.coarse),
        );
        chart.push(
            &format!("{}, R1/R2 = {}", run.reference_name, run.ratio),
            pick(&run.reference),
            i,
            Style::Line,
        );
        if let Some(fitted) = run.fit.as_ref().filter(|_| !run.coarse) {
            chart.push(
                &format!("fit, R1/R2 = {}", run.ratio),
                pick(fitted),
                i,
                Style::Dashed,
            );
        }
    }
    chart
}

/// A run's legend label: its ratio and grid, and "coarse" where the grid is too coarse for
/// the ratio's estimate.
fn run_label(ratio: f64, grid: (usize, usize), coarse: bool) -> String {
    format!(
        "R1/R2 = {ratio} ({}×{}{})",
        grid.0,
        grid.1,
        if coarse { ", coarse" } else { "" }
    )
}

/// Filled markers for a run, hollow for one too coarse for its estimate.
fn run_style(coarse: bool) -> Style {
    if coarse {
        Style::Hollow
    } else {
        Style::Markers
    }
}

/// A coefficient's value at one ratio: (R1/R2, value, half-width if known).
pub type CoefficientPoint = (f64, f64, Option<f64>);

/// One fitted coefficient against R1/R2, and its law.
#[derive(Debug, Clone, PartialEq)]
pub struct CoefficientSeries {
    /// The coefficient's name.
    pub name: &'static str,
    /// (R1/R2, value, half-width if known) per ratio.
    pub points: Vec<CoefficientPoint>,
    /// The ratios whose values rest on grids too coarse for their estimate: drawn hollow,
    /// without error bars, and left out of the law.
    pub coarse: Vec<f64>,
    /// The law k1·(R1/R2)^k2 + k3 fitted to the others, if it could be.
    pub law: Option<LawCurve>,
}

/// The fitted coefficients against R1/R2 (log axis) with their laws (dashed).
pub fn coefficients_chart(series: &[CoefficientSeries]) -> LineChart {
    let mut chart = LineChart::new(
        "Coefficients of d̄ = A c̄² + B c̄^½ and F̄ = c1 c̄³ + c2 c̄^α against R1/R2",
        "R1/R2",
        "coefficient (dimensionless)",
    );
    chart.x_log = true;
    for (i, c) in series.iter().enumerate() {
        let (coarse, resolved): (Vec<&CoefficientPoint>, Vec<_>) =
            c.points.iter().partition(|p| c.coarse.contains(&p.0));
        let pts: Vec<(f64, f64)> = resolved.iter().map(|p| (p.0, p.1)).collect();
        match resolved.iter().map(|p| p.2).collect::<Option<Vec<f64>>>() {
            Some(errors) => chart.push_with_errors(c.name, pts, errors, i),
            None => chart.push(c.name, pts, i, Style::Markers),
        }
        if !coarse.is_empty() {
            chart.push(
                &format!("{} (coarse grid, not fitted)", c.name),
                coarse.iter().map(|p| (p.0, p.1)).collect(),
                i,
                Style::Hollow,
            );
        }
        if let Some(law) = &c.law {
            let [k1, k2, k3] = law.k;
            chart.push(
                &format!("{} = {}", c.name, crate::text::power_law(k1, k2, k3)),
                law.points.clone(),
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
            "Quarter contours during pull-off, R1/R2 = {ratio} (equal scales; lines: \
             ellipses of the same ā, b̄)"
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
        // The capture's own label ("c̄ ≤ 1.4") says only where it was taken; the state's c̄
        // says it better. The force minimum keeps its name.
        let minimum = label.starts_with("force minimum");
        chart.push(
            &format!(
                "{}c̄ = {:.2}, F̄ = {:.3}; r/r_e − 1: {:.1} % rms",
                if minimum { "force minimum: " } else { "" },
                first.c_bar,
                first.f_bar,
                100.0 * first.departure_rms
            )
            .replace('-', "−"),
            group.iter().map(|r| (r.x_bar, r.y_bar)).collect(),
            i,
            Style::Markers,
        );
        let ellipse = (0..=CURVE_POINTS)
            .map(|k| k as f64 / CURVE_POINTS as f64 * std::f64::consts::FRAC_PI_2)
            .map(|t| (first.a_bar * t.cos(), first.b_bar * t.sin()))
            .collect();
        // One legend entry for the ellipses: each has its contour's colour.
        let entry = if i == 0 {
            "ellipses of the same ā, b̄"
        } else {
            ""
        };
        chart.push(entry, ellipse, i, Style::Line);
    }
    chart
}

/// A state marked on a pull-off curve, with its contact's outline (the study's Fig. 2b).
#[derive(Debug, Clone, PartialEq)]
pub struct MarkedState {
    /// d̄ of the state.
    pub d_bar: f64,
    /// F̄ of the state.
    pub f_bar: f64,
    /// c̄ of the state.
    pub c_bar: f64,
    /// Whether it is the force minimum.
    pub minimum: bool,
    /// The contact's outline, a closed loop of (x/c_r, y/c_r).
    pub outline: Vec<(f64, f64)>,
}

/// The study's Fig. 2b: on the left the run's pull-off curve F̄(d̄) (`curve`, its states
/// joined by a line) beside its closed form (`reference`: name and points, dashed), with `marked` states numbered 1, 2, … in
/// their own colours; on the right the contact outlines of those states in the same colours,
/// on equal scales.
pub fn marked_states_figure(
    ratio: f64,
    grid: (usize, usize),
    curve: Vec<(f64, f64)>,
    reference: (&str, Vec<(f64, f64)>),
    marked: &[MarkedState],
) -> Panels {
    // Colours 0–3 for the marked states' markers; the run's curve a sky-blue line (its
    // states are too dense for markers that would leave the marks visible), the closed form
    // black and dashed.
    const CURVE_COLOUR: usize = 6;
    const REFERENCE_COLOUR: usize = 4;
    let mut left = LineChart::new(
        &format!("Pull-off, R1/R2 = {ratio} ({}×{})", grid.0, grid.1),
        D_AXIS,
        F_AXIS,
    );
    left.push(
        "jkrbem (its states joined)",
        curve,
        CURVE_COLOUR,
        Style::Line,
    );
    for (k, m) in marked.iter().enumerate() {
        left.push(
            &format!(
                "{}: c̄ = {:.2}, F̄ = {:.3}{}",
                k + 1,
                m.c_bar,
                m.f_bar,
                if m.minimum { " (force minimum)" } else { "" }
            )
            .replace('-', "−"),
            vec![(m.d_bar, m.f_bar)],
            k,
            Style::Markers,
        );
    }
    left.push(reference.0, reference.1, REFERENCE_COLOUR, Style::Dashed);
    let mut right = LineChart::new(
        &format!("Contact outlines 1–{}", marked.len()),
        "x / c_r",
        "y / c_r",
    );
    right.equal_scales = true;
    for (k, m) in marked.iter().enumerate() {
        right.push(&format!("{}", k + 1), m.outline.clone(), k, Style::Line);
    }
    Panels::new(vec![left, right])
}
