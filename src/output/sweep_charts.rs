//! The charts of a sweep (physics §8.1 and §8.6): the pull-off curves F̄(d̄) of every ratio beside
//! JKR/JG, and the adhesive force |min F̄| against R1/R2 beside JG.

use super::line_chart::{LineChart, Style};
use super::sweep_csv::SweepRow;
use super::OutputError;
use crate::theory::{self, TheoryModel};
use std::path::Path;

/// Points of the closed-form curves (per ratio).
const THEORY_POINTS: usize = 300;

/// The closed form for a ratio: JKR for the sphere, JG otherwise, as (d̄, F̄) on its adhesive
/// branch up to approach `d_max`; empty if the theory cannot be evaluated.
fn theory_curve(ratio: f64, d_max: f64) -> Vec<(f64, f64)> {
    let model = TheoryModel::adhesive_reference(ratio);
    theory::curve(model, ratio, THEORY_POINTS)
        .map(|pts| {
            pts.iter()
                .filter(|p| p.d_bar <= d_max)
                .map(|p| (p.d_bar, p.f_bar))
                .collect()
        })
        .unwrap_or_default()
}

/// F̄(d̄) of every ratio of a sweep, with the closed forms dashed: `curves[i]` holds the
/// (d̄, F̄) points of `rows[i]`'s states, or why there are none. Also one line per ratio whose
/// states it could not draw: that ratio's legend entry says so and only its closed form is
/// drawn.
pub fn pulloff_curves_chart(
    rows: &[SweepRow],
    curves: &[Result<Vec<(f64, f64)>, String>],
) -> (LineChart, Vec<String>) {
    let mut chart = LineChart::new(
        "Pull-off: force against approach (markers: jkrbem, dashed: JKR / JG)",
        "approach d̄ = d·Re/c_r²",
        "force F̄ = F/(3π Re Δγ)",
    );
    let mut notes = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let mut d_max = 1.0;
        let label = format!("R1/R2 = {} ({}×{})", r.ratio, r.grid, r.ny);
        let curve = curves
            .get(i)
            .cloned()
            .unwrap_or_else(|| Err("its states were not given".into()));
        match curve {
            Ok(points) => {
                d_max = points.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
                chart.push(&label, points, i, Style::Markers);
            }
            Err(why) => {
                notes.push(format!(
                    "R1/R2 = {}: {why}, so pulloff_curves.svg draws only its closed form \
                     (its legend says so)",
                    r.ratio
                ));
                chart.push(
                    &format!("{label}: no states file"),
                    Vec::new(),
                    i,
                    Style::Markers,
                );
            }
        }
        let reference = TheoryModel::adhesive_reference(r.ratio)
            .name()
            .to_uppercase();
        chart.push(
            &format!("{reference}, R1/R2 = {}", r.ratio),
            theory_curve(r.ratio, d_max),
            i,
            Style::Dashed,
        );
    }
    (chart, notes)
}

/// |min F̄| against R1/R2 (log axis): the sweep's points beside JG's pull-off force.
pub fn force_vs_ratio_chart(rows: &[SweepRow]) -> LineChart {
    let mut chart = LineChart::new(
        "Adhesive force against axis ratio (normalised: F̄ = F/(3π Re Δγ))",
        "R1/R2",
        "adhesive force |min F̄|",
    );
    chart.x_log = true;
    let hi = rows.iter().map(|r| r.ratio).fold(2.0, f64::max);
    let jg: Vec<(f64, f64)> = (0..=200)
        .map(|i| hi.powf(i as f64 / 200.0))
        .filter_map(|ratio| Some((ratio, theory::reference_adhesive_force(ratio).ok()?)))
        .collect();
    chart.push("Johnson–Greenwood (JKR at 1)", jg, 1, Style::Line);
    let sim: Vec<(f64, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.ratio, r.f_ad_bar?)))
        .collect();
    let (x, y): (Vec<f64>, Vec<f64>) = sim.iter().copied().unzip();
    if let Ok(law) = crate::analysis::fit_power_law(&x, &y) {
        let curve = (0..=200)
            .map(|i| hi.powf(i as f64 / 200.0))
            .map(|r| (r, law.eval(r)))
            .collect();
        chart.push(
            &format!(
                "fit {} (R² = {:.4})",
                crate::text::power_law(law.k1, law.k2, law.k3),
                law.quality.r_squared
            ),
            curve,
            0,
            Style::Dashed,
        );
    }
    let errors = rows
        .iter()
        .filter(|r| r.f_ad_bar.is_some())
        .map(|r| r.f_ad_bar_uncertainty.unwrap_or(0.0))
        .collect();
    chart.push_with_errors(
        &format!(
            "jkrbem at Δx → 0, ± stated uncertainty (Nx = {})",
            grids_text(rows)
        ),
        sim,
        errors,
        0,
    );
    chart
}

/// The grids Nx of a sweep's rows in a few words: each distinct one ("64, 128") when there are
/// at most four, else their range ("64 to 2048, 9 grids").
fn grids_text(rows: &[SweepRow]) -> String {
    let mut grids: Vec<usize> = rows.iter().map(|r| r.grid).collect();
    grids.sort_unstable();
    grids.dedup();
    match grids.as_slice() {
        [] => "—".into(),
        g if g.len() <= 4 => g
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        g => format!("{} to {}, {} grids", g[0], g[g.len() - 1], g.len()),
    }
}

/// Write `force_vs_ratio.svg` and `pulloff_curves.svg` into `dir`; returns one line per ratio
/// whose pull-off curve could not be drawn (see [`pulloff_curves_chart`]).
pub fn write_sweep_charts(
    dir: &Path,
    rows: &[SweepRow],
    curves: &[Result<Vec<(f64, f64)>, String>],
) -> Result<Vec<String>, OutputError> {
    let [force_svg, curves_svg] = super::names::sweep_charts(dir);
    force_vs_ratio_chart(rows).write_svg(&force_svg)?;
    let (chart, notes) = pulloff_curves_chart(rows, curves);
    chart.write_svg(&curves_svg)?;
    Ok(notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fitted_law_is_written_with_proper_signs() {
        // Before: laws were printed as "… + -1.010".
        let rows: Vec<SweepRow> = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0]
            .iter()
            .map(|&ratio: &f64| SweepRow {
                ratio,
                f_ad_bar: Some(0.3 + 0.25 * ratio.powf(-0.4)),
                f_ad_bar_uncertainty: Some(0.01),
                estimate: Some("single-grid".into()),
                c_bar_at_min: Some(0.8),
                d_bar_at_min: Some(-0.2),
                jg_f_ad_bar: Some(0.5),
                n_d: Some(30.0),
                grid: 64,
                dx: 0.1,
                wall_s: 1.0,
                ny: 64,
                backend: "cpu-f64".into(),
                complete: true,
                min_reached: true,
                error: None,
            })
            .collect();
        let chart = force_vs_ratio_chart(&rows);
        let law = chart
            .curves
            .iter()
            .find(|c| c.label.starts_with("fit "))
            .expect("a fitted law");
        assert!(
            !law.label.contains("+ -") && !law.label.contains("^-"),
            "{}",
            law.label
        );
        assert!(law.label.contains('−'), "{}", law.label);
    }
}
