//! The accuracy–cost chart of one scene: each grid run on each backend in each way (whole
//! curve, adhesive force only, adhesive force with re-grids), its |min F̄| against the Δx → 0
//! limit (JKR's exact 1/2 for the sphere, else the first backend's own extrapolation, with its
//! uncertainty), and the same for first-order extrapolations of consecutive grids, against
//! the wall time each cost.

use crate::analysis::estimate::{from_runs, Estimate};
use crate::analysis::extrapolate::extrapolate_first_order;
use crate::analysis::report::RunReport;
use crate::backend::select::BackendKind;
use crate::model::{Measure, Model, ModelOptions};
use crate::output::chart::{LogLogChart, Series};
use crate::output::figure::FigureFormats;
use crate::output::names;
use crate::params::{BACKENDS, GRIDS, MEASURE, OUT, REGRID, VARIANTS};
use crate::scene::Scene;
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::pulloffs::{run_files, run_jobs, Job};
use crate::session::refuse;
use crate::session::Watch;
use crate::session::{input, RunError};
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

/// A way of running each grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Variant {
    /// The whole curve on a fixed grid.
    Plain,
    /// `--measure adhesive-force`: stop once the minimum is confirmed.
    Measure,
    /// `--measure adhesive-force --regrid`: also refine Δx as the contact shrinks.
    Regrid,
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl Variant {
    /// "plain", "measure" or "regrid".
    pub fn name(self) -> &'static str {
        match self {
            Variant::Plain => "plain",
            Variant::Measure => "measure",
            Variant::Regrid => "regrid",
        }
    }

    /// The parameters this variant sets, for labels.
    fn flags(self) -> String {
        match self {
            Variant::Plain => "whole curve".to_string(),
            Variant::Measure => format!("{MEASURE} adhesive-force"),
            Variant::Regrid => format!("{MEASURE} adhesive-force {REGRID}"),
        }
    }

    fn options(self, nx: usize) -> ModelOptions {
        ModelOptions {
            nx,
            measure: if self == Variant::Plain {
                Measure::Curve
            } else {
                Measure::AdhesiveForce
            },
            regrid: self == Variant::Regrid,
            ..ModelOptions::default()
        }
    }
}

/// A request for the accuracy–cost chart.
#[derive(Debug, Clone)]
pub struct AccuracyRequest {
    /// R1/R2 (1: the sphere).
    pub ratio: f64,
    /// Grids Nx, coarse to fine (2 to 12 increasing).
    pub grids: Vec<usize>,
    /// Backends (none repeated); the precision follows the backend.
    pub backends: Vec<BackendKind>,
    /// Ways of running each grid (none repeated, at least one).
    pub variants: Vec<Variant>,
    /// Output folder: states per run, accuracy.csv and accuracy.svg.
    pub out: PathBuf,
    /// The formats of the chart, with its `accuracy.plot.csv`.
    pub figures: FigureFormats,
}

/// The header of accuracy.csv, one column per [`AccuracyRow`] field.
pub const ROW_HEADER: &str = "variant,backend,precision,grid,n_d,f_ad_bar,error,wall_s,\
                              cg_iterations,reference,reference_uncertainty,stated,\
                              stated_uncertainty,stated_error";

/// One point of the chart.
#[derive(Debug, Clone, Serialize)]
pub struct AccuracyRow {
    /// plain, measure or regrid.
    pub variant: &'static str,
    /// cpu, gpu or auto, as asked.
    pub backend: String,
    /// f64 or f32.
    pub precision: String,
    /// "Nx×Ny", or "extrapolated from A and B".
    pub grid: String,
    /// Elements across the minor axis at the minimum.
    pub n_d: Option<f64>,
    /// |min F̄| of the grid (dimensionless; raw, not corrected), or the extrapolated value.
    pub f_ad_bar: Option<f64>,
    /// f_ad_bar / reference − 1 (dimensionless, signed).
    pub error: Option<f64>,
    /// Wall time (s); an extrapolation costs both of its grids.
    pub wall_s: f64,
    /// CG iterations.
    pub cg_iterations: usize,
    /// The Δx → 0 limit the error is measured against.
    pub reference: Option<f64>,
    /// Its uncertainty (absolute; 0 for JKR's exact 1/2).
    pub reference_uncertainty: Option<f64>,
    /// The |min F̄| the program states from these grids: one grid's force corrected by the
    /// convergence law, or several grids' extrapolated to Δx → 0 (dimensionless).
    pub stated: Option<f64>,
    /// The half-width of its stated interval (absolute).
    pub stated_uncertainty: Option<f64>,
    /// stated / reference − 1 (dimensionless, signed).
    pub stated_error: Option<f64>,
}

/// What the chart request produced.
#[derive(Debug, Clone)]
pub struct AccuracyDone {
    /// Every point, in the order written.
    pub rows: Vec<AccuracyRow>,
    /// The reference, in words.
    pub reference: String,
    /// accuracy.csv.
    pub csv: PathBuf,
    /// The chart, by its SVG path (its files in the formats asked for:
    /// [`FigureFormats::files`]).
    pub svg: PathBuf,
    /// The same chart against CG iterations, by its SVG path.
    pub iterations_svg: PathBuf,
    /// The runs that failed, in words.
    pub failures: Vec<String>,
}

/// One backend × variant: its runs, coarse to fine.
pub(super) struct RunSeries {
    /// The backend, as asked.
    pub(super) backend: String,
    /// The way each grid ran.
    pub(super) variant: Variant,
    /// The runs, coarse to fine.
    pub(super) runs: Vec<RunReport>,
}

fn backend_name(kind: BackendKind) -> &'static str {
    match kind {
        BackendKind::Auto => "auto",
        BackendKind::Cpu => "cpu",
        BackendKind::Gpu => "gpu",
    }
}

/// Check the request, claim its outputs, run every grid and write the chart.
pub fn accuracy(req: &AccuracyRequest, watch: &dyn Watch) -> Result<AccuracyDone, RunError> {
    if !(2..=12).contains(&req.grids.len()) || req.grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(refuse(
            GRIDS,
            format!("{GRIDS}: give 2 to 12 increasing grids, e.g. 32,64,128"),
        ));
    }
    if req.variants.is_empty() || req.backends.is_empty() {
        return Err(refuse(
            VARIANTS,
            format!("{VARIANTS} and {BACKENDS}: give at least one of each"),
        ));
    }
    let scene = Scene::from_ratio(req.ratio, 1.0, 1.0, 1.0).map_err(input)?;
    // Every model is built, and every output claimed, before any work.
    let mut plan = Vec::new();
    for &kind in &req.backends {
        for &variant in &req.variants {
            let mut jobs = Vec::new();
            for &nx in &req.grids {
                let model = Model::build(&scene, &variant.options(nx))
                    .map_err(|e| refuse(GRIDS, format!("{GRIDS} {nx}: {e}")))?;
                let file = format!("{}-{}-n{nx}.csv", backend_name(kind), variant.name());
                jobs.push(Job {
                    target: None,
                    model,
                    out: req.out.join(file),
                });
            }
            plan.push((kind, variant, jobs));
        }
    }
    let refs: Vec<&Model> = plan
        .iter()
        .flat_map(|p| p.2.iter().map(|j| &j.model))
        .collect();
    crate::plan::check_memory(&refs, 1, GRIDS).map_err(input)?;
    let csv = req.out.join("accuracy.csv");
    let svg = req.out.join("accuracy.svg");
    let mut targets: Vec<PathBuf> = plan
        .iter()
        .flat_map(|p| p.2.iter().flat_map(|j| run_files(&j.out)))
        .collect();
    targets.push(csv.clone());
    targets.extend(req.figures.files(&svg));
    targets.extend(req.figures.files(&names::iterations_chart(&svg)));
    let _claimed = Outputs::claim(&named(OUT, &targets))?;
    let mut series = Vec::new();
    let mut failures = Vec::new();
    for (kind, variant, jobs) in plan {
        let request = BackendRequest {
            kind,
            ..BackendRequest::default()
        };
        let results = run_jobs(jobs, 1, request, watch);
        failures.extend(results.iter().filter_map(|r| r.error.clone()));
        let mut runs: Vec<RunReport> = results
            .into_iter()
            .filter_map(|r| r.summary)
            .flat_map(|s| s.runs)
            .collect();
        runs.sort_by_key(|r| r.nx);
        series.push(RunSeries {
            backend: backend_name(kind).to_string(),
            variant,
            runs,
        });
    }
    let (reference, reference_text) = reference(req.ratio, &series);
    let rows = chart_rows(&series, reference);
    write_charts(
        req.ratio,
        &series,
        &rows,
        &reference_text,
        &svg,
        req.figures,
    )?;
    crate::output::file::write_csv(&csv, Some(ROW_HEADER), &rows).map_err(write_error(OUT))?;
    Ok(AccuracyDone {
        iterations_svg: names::iterations_chart(&svg),
        rows,
        reference: reference_text,
        csv,
        svg,
        failures,
    })
}

/// The Δx → 0 limit: JKR's exact 1/2 for the sphere, else the first series extrapolated (with
/// its uncertainty).
fn reference(ratio: f64, series: &[RunSeries]) -> (Option<Estimate>, String) {
    if ratio == 1.0 {
        let exact = Estimate {
            value: 0.5,
            uncertainty: 0.0,
        };
        return (Some(exact), "exact JKR value 1/2".into());
    }
    let first = &series[0];
    match from_runs(&first.runs) {
        Ok(e) => (
            Some(e.f_ad_bar),
            format!(
                "{} ({}) extrapolated to Δx → 0: {:.4} ± {:.4}",
                first.backend,
                first.variant.name(),
                e.f_ad_bar.value,
                e.f_ad_bar.uncertainty
            ),
        ),
        Err(why) => (None, format!("no reference ({why})")),
    }
}

/// Every grid's point, every consecutive pair's extrapolation and (from three grids) the
/// extrapolation of all grids, per series; each with the answer the program states from
/// those grids and its uncertainty.
pub(super) fn chart_rows(series: &[RunSeries], reference: Option<Estimate>) -> Vec<AccuracyRow> {
    let error = |f: Option<f64>| Some(f? / reference?.value - 1.0);
    let row = |s: &RunSeries, runs: &[RunReport], grid: String, n_d, f_ad_bar: Option<f64>| {
        let stated = from_runs(runs).ok().map(|e| e.f_ad_bar);
        AccuracyRow {
            variant: s.variant.name(),
            backend: s.backend.clone(),
            precision: runs[0].precision.clone(),
            grid,
            n_d,
            f_ad_bar,
            error: error(f_ad_bar),
            wall_s: runs.iter().map(|r| r.wall_s).sum(),
            cg_iterations: runs.iter().map(|r| r.cg_iterations).sum(),
            reference: reference.map(|e| e.value),
            reference_uncertainty: reference.map(|e| e.uncertainty),
            stated: stated.map(|e| e.value),
            stated_uncertainty: stated.map(|e| e.uncertainty),
            stated_error: error(stated.map(|e| e.value)),
        }
    };
    let mut rows = Vec::new();
    for s in series {
        for r in &s.runs {
            rows.push(row(
                s,
                std::slice::from_ref(r),
                r.grid.clone(),
                r.n_d,
                r.f_ad_bar,
            ));
        }
        for pair in s.runs.windows(2) {
            let dx: Vec<f64> = pair.iter().map(|r| r.dx_at_min.unwrap_or(r.dx)).collect();
            let f: Option<Vec<f64>> = pair.iter().map(|r| r.f_ad_bar).collect();
            let first_order = f.and_then(|f| extrapolate_first_order(&dx, &f));
            rows.push(row(
                s,
                pair,
                format!("extrapolated from {} and {}", pair[0].nx, pair[1].nx),
                None,
                first_order.map(|x| x.value),
            ));
        }
        if s.runs.len() >= 3 {
            let (first, last) = (s.runs[0].nx, s.runs[s.runs.len() - 1].nx);
            let all = row(
                s,
                &s.runs,
                format!(
                    "extrapolated from {first} to {last} ({} grids)",
                    s.runs.len()
                ),
                None,
                None,
            );
            rows.push(AccuracyRow {
                f_ad_bar: all.stated,
                error: all.stated_error,
                ..all
            });
        }
    }
    rows
}

/// What the cost of an answer is counted in.
#[derive(Debug, Clone, Copy)]
pub(super) enum Cost {
    /// Wall time (s): what a user waits, on this machine.
    Wall,
    /// CG iterations: the same on every device.
    Iterations,
}

/// The log–log chart of the error of each stated answer against its `cost`, with its stated
/// uncertainty as a bar (relative to the reference): per backend × variant, one solid series
/// of one-grid answers (the grid's force corrected by the convergence law) and one dashed
/// series of the answers extrapolated from several grids.
pub(super) fn cost_chart(
    title: &str,
    series: &[RunSeries],
    rows: &[AccuracyRow],
    cost: Cost,
) -> LogLogChart {
    let x_label = match cost {
        Cost::Wall => "wall time (s)",
        Cost::Iterations => "CG iterations (all solves; the same on every device)",
    };
    let mut chart = LogLogChart::new(
        title,
        x_label,
        "|error of the stated |min F̄|| (relative), ± stated uncertainty",
    );
    chart.x_data_ticks = false;
    for (i, s) in series.iter().enumerate() {
        let mine = rows
            .iter()
            .filter(|r| r.backend == s.backend && r.variant == s.variant.name());
        let (extra, single): (Vec<&AccuracyRow>, Vec<&AccuracyRow>) =
            mine.partition(|r| r.n_d.is_none() && r.grid.starts_with("extrapolated"));
        // A point at zero error (the reference itself) has no place on a log axis.
        let points = |rows: &[&AccuracyRow]| -> (Vec<(f64, f64)>, Vec<f64>) {
            rows.iter()
                .filter_map(|r| {
                    let x = match cost {
                        Cost::Wall => r.wall_s,
                        Cost::Iterations => r.cg_iterations as f64,
                    };
                    let bar = r.stated_uncertainty? / r.reference?;
                    Some(((x, r.stated_error?.abs()), bar))
                })
                .filter(|p| p.0 .1 > 0.0)
                .unzip()
        };
        let precision = s.runs.first().map_or("", |r| r.precision.as_str());
        let (single_points, single_bars) = points(&single);
        chart.push(Series {
            label: format!(
                "{} ({precision}), {}: one grid",
                s.backend,
                s.variant.flags()
            ),
            points: single_points,
            color: i,
            dashed: false,
            errors: single_bars,
        });
        let (extra_points, extra_bars) = points(&extra);
        if !extra_points.is_empty() {
            chart.push(Series {
                label: format!(
                    "{} ({precision}), {}: extrapolated from grids",
                    s.backend,
                    s.variant.flags()
                ),
                points: extra_points,
                color: i,
                dashed: true,
                errors: extra_bars,
            });
        }
    }
    chart
}

/// The two accuracy–cost charts of `series` against `reference` (in words): `svg` against
/// wall time and [`names::iterations_chart`] of it against CG iterations, in each of `figures`.
pub(super) fn write_charts(
    ratio: f64,
    series: &[RunSeries],
    rows: &[AccuracyRow],
    reference: &str,
    svg: &std::path::Path,
    figures: FigureFormats,
) -> Result<(), RunError> {
    for (cost, path) in [
        (Cost::Wall, svg.to_path_buf()),
        (Cost::Iterations, names::iterations_chart(svg)),
    ] {
        let title = format!("R1/R2 = {ratio}: error of |min F̄| against cost ({reference})");
        cost_chart(&title, series, rows, cost)
            .write_figure(&path, figures)
            .map_err(write_error(OUT))?;
    }
    Ok(())
}
