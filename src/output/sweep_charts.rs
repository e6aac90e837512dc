//! The charts of a sweep (physics §8.1 and §8.6): the pull-off curves F̄(d̄) of every ratio beside
//! JKR/JG, and the adhesive force |min F̄| against R1/R2 beside JG.

use super::figure::FigureFormats;
use super::line_chart::{LineChart, Style};
use super::series::{LawCurve, Named};
use super::sweep_csv::SweepRow;
use super::OutputError;
use crate::analysis::convergence::{answer_too_coarse, COARSE_N_D};
use std::path::Path;

/// What a sweep's charts draw beside its rows' own numbers, gathered and computed by the
/// session layer (`studies::curves`): each row's states and closed form, JG's adhesive force and
/// the law fitted to the rows.
#[derive(Debug, Clone, Default)]
pub struct SweepCurves {
    /// Each row's (d̄, F̄) pull-off points, or why there are none, in the rows' order.
    pub pulloffs: Vec<Result<Vec<(f64, f64)>, String>>,
    /// Each row's closed form (JKR for the sphere, JG otherwise) as (d̄, F̄) on its adhesive
    /// branch up to the row's last approach, in the rows' order.
    pub references: Vec<Named>,
    /// Johnson–Greenwood's |min F̄| against R1/R2 (JKR at 1), over the sweep's range.
    pub jg_force: Vec<(f64, f64)>,
    /// The power law fitted to the rows' |min F̄| against R1/R2, if it could be fitted.
    pub fit: Option<LawCurve>,
}

/// F̄(d̄) of every ratio of a sweep, with the closed forms dashed: `curves.pulloffs[i]` holds
/// the (d̄, F̄) points of `rows[i]`'s states, or why there are none. Also one line per ratio
/// whose states it could not draw: that ratio's legend entry says so and only its closed form
/// is drawn.
pub fn pulloff_curves_chart(rows: &[SweepRow], curves: &SweepCurves) -> (LineChart, Vec<String>) {
    let mut chart = LineChart::new(
        "Pull-off: force against approach (markers: jkrbem, dashed: JKR / JG)",
        "approach d̄ = d·Re/c_r²",
        "force F̄ = F/(3π Re Δγ)",
    );
    let mut notes = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let label = format!("R1/R2 = {} ({}×{})", r.ratio, r.grid, r.ny);
        let curve = curves
            .pulloffs
            .get(i)
            .cloned()
            .unwrap_or_else(|| Err("its states were not given".into()));
        match curve {
            Ok(points) => {
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
        let reference = curves.references.get(i).cloned().unwrap_or_default();
        chart.push(
            &format!("{}, R1/R2 = {}", reference.name, r.ratio),
            reference.points,
            i,
            Style::Dashed,
        );
    }
    (chart, notes)
}

/// |min F̄| against R1/R2 (log axis): the sweep's points beside JG's pull-off force and the
/// law fitted to them.
pub fn force_vs_ratio_chart(rows: &[SweepRow], curves: &SweepCurves) -> LineChart {
    let mut chart = LineChart::new(
        "Adhesive force against axis ratio (normalised: F̄ = F/(3π Re Δγ))",
        "R1/R2",
        "adhesive force |min F̄|",
    );
    chart.x_log = true;
    chart.push(
        "Johnson–Greenwood (JKR at 1)",
        curves.jg_force.clone(),
        1,
        Style::Line,
    );
    if let Some(law) = &curves.fit {
        let [k1, k2, k3] = law.k;
        chart.push(
            &format!(
                "fit {} (R² = {:.4})",
                crate::text::power_law(k1, k2, k3),
                law.r_squared
            ),
            law.points.clone(),
            0,
            Style::Dashed,
        );
    }
    // Answers, and the points of grids too coarse to be answers (hollow, not fitted).
    let (coarse, resolved): (Vec<&SweepRow>, Vec<&SweepRow>) = rows
        .iter()
        .filter(|r| r.f_ad_bar.is_some())
        .partition(|r| too_coarse(r));
    let points = |rows: &[&SweepRow]| -> Vec<((f64, f64), f64)> {
        rows.iter()
            .filter_map(|r| {
                Some((
                    (r.ratio, r.f_ad_bar?),
                    r.f_ad_bar_uncertainty.unwrap_or(0.0),
                ))
            })
            .collect()
    };
    chart.push_estimates(
        (
            &format!(
                "jkrbem at Δx → 0, ± stated uncertainty (Nx = {})",
                grids_text(resolved.iter().map(|r| r.grid))
            ),
            points(&resolved),
        ),
        (
            &format!(
                "coarse grid (< {COARSE_N_D:.0} elements across the contact): not an answer, \
                 not fitted"
            ),
            points(&coarse),
        ),
        0,
    );
    chart
}

/// Whether a row's answer rests on a grid too coarse for its estimate (fewer than
/// [`COARSE_N_D`] elements across the contact's minor axis at the minimum): drawn apart and
/// left out of the fit.
pub fn too_coarse(r: &SweepRow) -> bool {
    answer_too_coarse(r.n_d)
}

/// The grids Nx of a sweep's rows (`grids`) in a few words: each distinct one ("64, 128")
/// when there are at most four, else their range ("64 to 2048, 9 grids").
fn grids_text(grids: impl Iterator<Item = usize>) -> String {
    let mut grids: Vec<usize> = grids.collect();
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

/// Write `force_vs_ratio` and `pulloff_curves` into `dir` in each of `formats`, each with its
/// `.plot.csv`; returns one line per ratio whose pull-off curve could not be drawn (see
/// [`pulloff_curves_chart`]).
pub fn write_sweep_charts(
    dir: &Path,
    rows: &[SweepRow],
    curves: &SweepCurves,
    formats: FigureFormats,
) -> Result<Vec<String>, OutputError> {
    let [force_svg, curves_svg] = super::names::sweep_charts(dir);
    force_vs_ratio_chart(rows, curves).write_figure(&force_svg, formats)?;
    let (chart, notes) = pulloff_curves_chart(rows, curves);
    chart.write_figure(&curves_svg, formats)?;
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
            .map(|&ratio: &f64| SweepRow::sample(ratio, 0.3 + 0.25 * ratio.powf(-0.4)))
            .collect();
        let law = LawCurve {
            k: [0.25, -0.4, 0.3],
            r_squared: 0.999,
            points: vec![(1.0, 0.55), (50.0, 0.32)],
        };
        let curves = SweepCurves {
            fit: Some(law),
            ..SweepCurves::default()
        };
        let chart = force_vs_ratio_chart(&rows, &curves);
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
