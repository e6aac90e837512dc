//! Two identical elastic cylinders crossed at angles θ, each mapped to an ellipsoid (physics
//! §1), one pull-off per angle; the adhesive force in the inputs' force unit beside
//! Johnson–Greenwood's, as CSV and a chart.

use crate::analysis::CrossedCylinders;
use crate::model::{Model, ModelOptions};
use crate::output::figure::FigureFormats;
use crate::output::line_chart::{LineChart, Style};
use crate::params::{Spec, ANGLE, GRID, OUT};
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::pulloffs::{batch_model, run_files, run_jobs, GridChoice, Job};
use crate::session::Watch;
use crate::session::{input, RunError};
use crate::theory;
use serde::Serialize;
use std::path::PathBuf;

/// A request for crossed cylinders.
#[derive(Debug, Clone)]
pub struct CrossedRequest {
    /// Radius R of both cylinders (length).
    pub radius: f64,
    /// Crossing angles (degrees).
    pub angles: Vec<f64>,
    /// Young's modulus E of both (force/length²).
    pub young: f64,
    /// Poisson's ratio ν of both.
    pub poisson: f64,
    /// Work of adhesion Δγ (energy/area).
    pub work_of_adhesion: f64,
    /// How each angle's grid is chosen: a fixed Nx, or the accuracy wanted.
    pub grid: GridChoice,
    /// Load steps.
    pub steps: usize,
    /// Free margin around the first contact.
    pub margin: f64,
    /// The backend.
    pub backend: BackendRequest,
    /// Pull-offs at the same time.
    pub jobs: usize,
    /// Output folder.
    pub out: PathBuf,
    /// The formats of the chart, with its `crossed.plot.csv`.
    pub figures: FigureFormats,
}

/// One angle's result (forces in the inputs' force unit, e.g. N).
#[derive(Debug, Clone, Serialize)]
pub struct CrossedRow {
    /// θ (degrees).
    pub angle_deg: f64,
    /// R1/R2 of the equivalent ellipsoid.
    pub ratio: f64,
    /// The adhesive force (best estimate), in the inputs' force unit.
    pub f_ad: Option<f64>,
    /// Its uncertainty, same unit.
    pub f_ad_uncertainty: Option<f64>,
    /// Johnson–Greenwood's (JKR's at 90°), same unit.
    pub jg_f_ad: Option<f64>,
    /// |min F̄| (dimensionless).
    pub f_ad_bar: Option<f64>,
    /// JG's |min F̄|.
    pub jg_f_ad_bar: Option<f64>,
    /// Elements across the minor axis at the minimum.
    pub n_d: Option<f64>,
    /// Elements along x.
    pub grid: usize,
    /// Wall time (s).
    pub wall_s: f64,
    /// Whether the pull-off completed.
    pub complete: bool,
}

/// What the request produced.
pub struct CrossedDone {
    /// One row per angle, largest angle first.
    pub rows: Vec<CrossedRow>,
    /// crossed.csv and the chart, by its SVG path crossed.svg (its files in the formats asked
    /// for: [`FigureFormats::files`]).
    pub files: [PathBuf; 2],
    /// Why pull-offs failed, one line each.
    pub failures: Vec<String>,
    /// Every angle's warnings (coarse grid, missed target, CG retries), one line each.
    pub warnings: Vec<String>,
}

/// JG's (JKR's at 90°) adhesive force |min F̄| at a ratio.
fn jg_force_bar(ratio: f64) -> Option<f64> {
    theory::reference_adhesive_force(ratio).ok()
}

impl CrossedRequest {
    fn pair(&self, angle_deg: f64) -> CrossedCylinders {
        CrossedCylinders {
            radius: self.radius,
            angle_deg,
            young: self.young,
            poisson: self.poisson,
            work_of_adhesion: self.work_of_adhesion,
        }
    }
}

/// Run the request: check every angle, claim the outputs, run, write crossed.csv and the chart.
/// `rename` maps the analysis layer's parameters ([`ANGLE`], the cylinders' modulus, …) to
/// those the front end names in messages (e.g. `crossed`'s
/// [`ANGLES`](crate::params::ANGLES)).
pub fn crossed(
    req: &CrossedRequest,
    rename: &dyn Fn(&'static Spec) -> &'static Spec,
    watch: &dyn Watch,
) -> Result<CrossedDone, RunError> {
    req.backend.check()?;
    let mut jobs = Vec::new();
    let mut scales = Vec::new();
    for &angle in &req.angles {
        let c = req.pair(angle);
        let scene = c.scene().map_err(|e| input(e.renamed(rename)))?;
        let base = ModelOptions {
            steps: req.steps,
            margin: req.margin,
            ..ModelOptions::default()
        };
        let (model, target) = batch_model(&scene, req.grid, &base).map_err(|e| {
            input(format!(
                "{} {}: {e}",
                rename(ANGLE),
                crate::text::compact(angle)
            ))
        })?;
        scales.push((
            angle,
            scene.ratio(),
            c.force_scale().map_err(|e| input(e.renamed(rename)))?,
        ));
        let out = crate::output::names::crossed_states(&req.out, angle, model.nx);
        jobs.push(Job { model, out, target });
    }
    let refs: Vec<&Model> = jobs.iter().map(|j| &j.model).collect();
    crate::plan::check_memory(&refs, req.jobs, GRID).map_err(input)?;
    let files = [req.out.join("crossed.csv"), req.out.join("crossed.svg")];
    let mut targets: Vec<PathBuf> = jobs.iter().flat_map(|j| run_files(&j.out)).collect();
    targets.push(files[0].clone());
    targets.extend(req.figures.files(&files[1]));
    let _claimed = Outputs::claim(&named(OUT, &targets))?;
    let results = run_jobs(jobs, req.jobs, req.backend, watch);
    let failures = results.iter().filter_map(|r| r.error.clone()).collect();
    let warnings = results.iter().flat_map(|r| r.warnings()).collect();
    let mut rows: Vec<CrossedRow> = scales
        .iter()
        .zip(&results)
        .map(|(&(angle, ratio, scale), r)| {
            let grid = r.grid.0;
            let s = r.summary.as_ref();
            let f_ad_bar = s.and_then(|s| s.f_ad_bar);
            let jg = jg_force_bar(ratio);
            CrossedRow {
                angle_deg: angle,
                ratio,
                f_ad: f_ad_bar.map(|f| f * scale),
                f_ad_uncertainty: s.and_then(|s| s.f_ad_bar_uncertainty).map(|u| u * scale),
                jg_f_ad: jg.map(|f| f * scale),
                f_ad_bar,
                jg_f_ad_bar: jg,
                n_d: s.and_then(|s| s.runs.last()).and_then(|r| r.n_d),
                grid,
                wall_s: s.map_or(0.0, |s| s.wall_s),
                complete: s.is_some_and(|s| s.complete),
            }
        })
        .collect();
    rows.sort_by(|a, b| b.angle_deg.total_cmp(&a.angle_deg));
    crate::output::file::write_csv(&files[0], None, &rows).map_err(write_error(OUT))?;
    chart(req, &rows)
        .write_figure(&files[1], req.figures)
        .map_err(write_error(OUT))?;
    Ok(CrossedDone {
        rows,
        files,
        failures,
        warnings,
    })
}

/// The unit a force axis reads best in for forces up to `largest` (N): N, mN, µN or nN, and
/// how many of it make a newton.
fn force_unit(largest: f64) -> (&'static str, f64) {
    [("N", 1.0), ("mN", 1e3), ("µN", 1e6), ("nN", 1e9)]
        .into_iter()
        .find(|&(_, k)| largest * k >= 1.0)
        .unwrap_or(("nN", 1e9))
}

/// Adhesive force against crossing angle: the runs (with their uncertainty) beside JG over
/// (θ_min, 90°], in N or the SI prefix that reads best ([`force_unit`]); runs too coarse for
/// their estimate are drawn hollow, apart from the answers. The title gives the inputs in SI
/// units (the documented use: m, Pa, J/m², so forces in N).
fn chart(req: &CrossedRequest, rows: &[CrossedRow]) -> LineChart {
    use crate::analysis::convergence::{answer_too_coarse, COARSE_N_D};
    use crate::text::compact;
    let largest = rows
        .iter()
        .filter_map(|r| r.f_ad)
        .fold(0.0f64, |m, f| m.max(f.abs()));
    let (unit, per_newton) = force_unit(largest);
    let mut chart = LineChart::new(
        &format!(
            "Crossed cylinders: R = {} m, E = {} Pa, ν = {}, Δγ = {} J/m²",
            compact(req.radius),
            compact(req.young),
            compact(req.poisson),
            compact(req.work_of_adhesion)
        ),
        "crossing angle θ (degrees)",
        &format!("adhesive force |F_min| ({unit})"),
    );
    let lo = rows.iter().map(|r| r.angle_deg).fold(90.0, f64::min);
    let jg: Vec<(f64, f64)> = (0..=200)
        .map(|i| lo + (90.0 - lo) * i as f64 / 200.0)
        .filter_map(|a| {
            let c = req.pair(a);
            let ratio = c.scene().ok()?.ratio();
            Some((a, jg_force_bar(ratio)? * c.force_scale().ok()? * per_newton))
        })
        .collect();
    chart.push("Johnson–Greenwood", jg, 1, Style::Line);
    let (coarse, resolved): (Vec<&CrossedRow>, Vec<&CrossedRow>) =
        rows.iter().partition(|r| answer_too_coarse(r.n_d));
    let points = |rows: &[&CrossedRow]| -> Vec<((f64, f64), f64)> {
        rows.iter()
            .filter_map(|r| {
                let e = r.f_ad_uncertainty.unwrap_or(0.0) * per_newton;
                Some(((r.angle_deg, r.f_ad? * per_newton), e))
            })
            .collect()
    };
    let grids = |rows: &[&CrossedRow]| {
        let mut g: Vec<usize> = rows.iter().map(|r| r.grid).collect();
        g.sort_unstable();
        g.dedup();
        g.iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    chart.push_estimates(
        (
            &format!(
                "jkrbem at Δx → 0, ± stated uncertainty (Nx = {})",
                grids(&resolved)
            ),
            points(&resolved),
        ),
        (
            &format!(
                "coarse grid (< {COARSE_N_D:.0} elements across the contact, Nx = {}): not an \
                 answer",
                grids(&coarse)
            ),
            points(&coarse),
        ),
        0,
    );
    chart
}

#[cfg(test)]
mod tests {
    use super::force_unit;

    #[test]
    fn a_force_axis_reads_in_the_prefix_that_keeps_its_numbers_above_one() {
        // Before: the study's 0.002 … 0.008 N read as such.
        assert_eq!(force_unit(0.0073), ("mN", 1e3));
        assert_eq!(force_unit(2.5), ("N", 1.0));
        assert_eq!(force_unit(4e-5), ("µN", 1e6));
        assert_eq!(force_unit(0.0), ("nN", 1e9));
    }
}
