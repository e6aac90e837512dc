//! The charts of a sweep (physics §8.1 and §8.6): the pull-off curves F̄(d̄) of every ratio beside
//! JKR/JG, and the adhesive force |min F̄| against R1/R2 beside JG.

use super::line_chart::{LineChart, Style};
use super::sweep_csv::SweepRow;
use super::OutputError;
use crate::theory::{self, TheoryModel};
use std::path::Path;

/// Points of the closed-form curves (per ratio).
const THEORY_POINTS: usize = 300;

/// (d̄, F̄) of the pull-off and onset states in a states CSV.
///
/// The file may be a run's partial states, cut off mid-row by a write error: the rows up to the
/// first one that is not whole (fewer fields than the header) are read, and the rest ignored.
pub fn pulloff_points(states_csv: &Path) -> Result<Vec<(f64, f64)>, OutputError> {
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_path(states_csv)
        .map_err(|e| OutputError::csv(states_csv, e))?;
    let header = reader
        .headers()
        .cloned()
        .map_err(|e| OutputError::csv(states_csv, e))?;
    let col = |name: &str| header.iter().position(|h| h == name);
    let (Some(phase), Some(d), Some(f)) = (col("phase"), col("d_bar"), col("f_bar")) else {
        return Ok(Vec::new());
    };
    Ok(reader
        .records()
        .map_while(|r| r.ok().filter(|r| r.len() == header.len()))
        .filter(|r| r.get(phase) != Some("approach"))
        .filter_map(|r| Some((r.get(d)?.parse().ok()?, r.get(f)?.parse().ok()?)))
        .collect())
}

/// The newest partial states file of `target_name` in `dir` (see
/// [`super::file::PartialFile`]), if any.
fn newest_partial(dir: &Path, target_name: &str) -> Option<std::path::PathBuf> {
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .filter(|e| super::file::is_partial_of(&e.file_name().to_string_lossy(), target_name))
        .max_by_key(|e| e.metadata().and_then(|m| m.modified()).ok())
        .map(|e| e.path())
}

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

/// F̄(d̄) of every ratio of a sweep (states read from `dir`), with the closed forms dashed.
pub fn pulloff_curves_chart(dir: &Path, rows: &[SweepRow]) -> Result<LineChart, OutputError> {
    pulloff_curves_chart_noting(dir, rows).map(|(chart, _)| chart)
}

/// The states file of `row` in `dir`: its complete file if that is a regular file, else its
/// newest partial file; or why there is none, in words.
fn states_file(dir: &Path, row: &SweepRow) -> Result<std::path::PathBuf, String> {
    let name = format!("r{}-n{}.csv", row.ratio, row.grid);
    let complete = dir.join(&name);
    match std::fs::metadata(&complete) {
        Ok(m) if m.is_file() => return Ok(complete),
        Ok(_) => {
            return Err(format!(
                "{} is not a regular file (a FIFO, a device or a folder)",
                complete.display()
            ))
        }
        Err(_) => {}
    }
    newest_partial(dir, &name)
        .filter(|p| p.metadata().is_ok_and(|m| m.is_file()))
        .ok_or_else(|| format!("its states file {} is missing", complete.display()))
}

/// [`pulloff_curves_chart`], and one line per ratio whose states it could not draw (its
/// states file missing or not a regular file): that ratio's legend entry says so and only
/// its closed form is drawn.
pub fn pulloff_curves_chart_noting(
    dir: &Path,
    rows: &[SweepRow],
) -> Result<(LineChart, Vec<String>), OutputError> {
    let mut chart = LineChart::new(
        "Pull-off: force against approach (markers: jkrbem, dashed: JKR / JG)",
        "approach d̄ = d·Re/c_r²",
        "force F̄ = F/(3π Re Δγ)",
    );
    let mut notes = Vec::new();
    for (i, r) in rows.iter().enumerate() {
        let mut d_max = 1.0;
        let label = format!("R1/R2 = {} ({}×{})", r.ratio, r.grid, r.ny);
        match states_file(dir, r) {
            Ok(path) => {
                let points = pulloff_points(&path)?;
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
    Ok((chart, notes))
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
/// whose pull-off curve could not be drawn (see [`pulloff_curves_chart_noting`]).
pub fn write_sweep_charts(dir: &Path, rows: &[SweepRow]) -> Result<Vec<String>, OutputError> {
    force_vs_ratio_chart(rows).write_svg(&dir.join("force_vs_ratio.svg"))?;
    let (chart, notes) = pulloff_curves_chart_noting(dir, rows)?;
    chart.write_svg(&dir.join("pulloff_curves.svg"))?;
    Ok(notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_states_file_cut_off_mid_row_gives_its_whole_rows() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r1-n32.incomplete-7.csv");
        let header = crate::output::states_csv::HEADER;
        let row = |d: f64, f: f64| {
            format!("1,pulloff,0,0,0,0,0,0,0,0,0,{d},{f},0,0,0,0,0,near-minimum\n")
        };
        // The third row was cut off by a write error.
        let text = format!(
            "{header}\n{}{}1,pulloff,0,0,0,0,0,0,0,0,0,0.5,-0.4",
            row(1.0, -0.1),
            row(0.9, -0.2)
        );
        std::fs::write(&path, text).unwrap();
        assert_eq!(
            pulloff_points(&path).unwrap(),
            vec![(1.0, -0.1), (0.9, -0.2)]
        );
    }

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
