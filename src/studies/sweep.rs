//! One pull-off per axis ratio R1/R2 (or one shard of them), with each ratio's states, summary
//! and contours, the sweep's summary CSV (or shard file) and its charts.

use super::chart_data;
use super::curves::{row_curves, sweep_curves};
use crate::model::{Model, ModelOptions};
use crate::output::figure::FigureFormats;
use crate::output::sweep_charts::write_sweep_charts;
use crate::output::sweep_csv::{self, Shard, SweepRow, SweepSettings};
use crate::output::NamedBy;
use crate::params::{ALLOW_MISSING, GRID, OUT, RATIO, RATIOS};
use crate::scene::{Scene, SceneError};
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::pulloffs::{batch_model, run_files, run_jobs, GridChoice, Job};
use crate::session::refuse;
use crate::session::Watch;
use crate::session::{input, RunError};
use std::path::{Path, PathBuf};

/// A request for a sweep over R1/R2.
#[derive(Debug, Clone)]
pub struct SweepRequest {
    /// Every ratio of the sweep (the shard takes its share), none repeated.
    pub ratios: Vec<f64>,
    /// How each ratio's grid is chosen: a fixed Nx, or the accuracy wanted.
    pub grid: GridChoice,
    /// Load steps.
    pub steps: usize,
    /// c̄0 of the first contact.
    pub start_radius: f64,
    /// Free margin around the first contact.
    pub margin: f64,
    /// The backend.
    pub backend: BackendRequest,
    /// Run only shard (K, N).
    pub shard: Option<(usize, usize)>,
    /// Pull-offs at the same time.
    pub jobs: usize,
    /// Output folder.
    pub out: PathBuf,
    /// The formats of the charts (a whole sweep's), each with its `.plot.csv`.
    pub figures: FigureFormats,
}

/// What a sweep produced.
pub struct SweepDone {
    /// One row per ratio run, sorted by ratio.
    pub rows: Vec<SweepRow>,
    /// The summary CSV or shard file.
    pub summary_path: PathBuf,
    /// The charts, for a whole sweep (not a shard), by their SVG paths (their files in the
    /// formats asked for: [`FigureFormats::files`]).
    pub charts: Option<[PathBuf; 2]>,
    /// The ratios this run took.
    pub ran: usize,
    /// Why pull-offs failed, one line each.
    pub failures: Vec<String>,
    /// Why the charts could not be drawn or written (after `sweep.csv` was), if they could not.
    pub charts_error: Option<String>,
    /// Every ratio's warnings (coarse grid, missed target, CG retries), one line each.
    pub warnings: Vec<String>,
}

pub use crate::output::names::sweep_states as states_path;

pub use crate::output::names::sweep_charts as chart_files;

/// Every file of a sweep's charts in `dir` ([`chart_files`]) in `formats`, with their data.
pub fn figure_files(dir: &Path, formats: FigureFormats) -> Vec<PathBuf> {
    chart_files(dir)
        .iter()
        .flat_map(|c| formats.files(c))
        .collect()
}

/// The model of one ratio (R2 = E* = Δγ = 1: the normalised results do not depend on them)
/// and the accuracy it is held to.
fn model_for(req: &SweepRequest, ratio: f64) -> Result<(Model, Option<f64>), RunError> {
    let fail = |e: String| {
        refuse(
            RATIOS,
            format!("{RATIOS} {}: {e}", crate::text::compact(ratio)),
        )
    };
    // The ratio out of range is said as R1/R2 (the sweep's ratios are not its own ratio).
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(|e| match e {
        SceneError::Invalid {
            param,
            value,
            expected,
        } if param == RATIO => fail(format!(
            "R1/R2 = {} is invalid: {expected}",
            crate::text::compact(value)
        )),
        other => fail(other.to_string()),
    })?;
    let base = ModelOptions {
        steps: req.steps,
        start_radius_bar: req.start_radius,
        margin: req.margin,
        ..ModelOptions::default()
    };
    batch_model(&scene, req.grid, &base).map_err(|e| fail(e.to_string()))
}

/// Run the sweep: check every ratio (the other shards' too), claim the outputs, run this
/// shard's ratios, write the rows (CSV or shard file) and, for a whole sweep, the charts.
pub fn sweep(req: &SweepRequest, watch: &dyn Watch) -> Result<SweepDone, RunError> {
    req.backend.check()?;
    let jobs = sweep_jobs(req)?;
    let summary_path = match req.shard {
        Some(kn) => sweep_csv::shard_path(&req.out, kn),
        None => sweep_csv::sweep_csv_path(&req.out),
    };
    let mut targets: Vec<PathBuf> = jobs.iter().flat_map(|j| run_files(&j.out)).collect();
    targets.push(summary_path.clone());
    if req.shard.is_none() {
        targets.extend(figure_files(&req.out, req.figures));
    }
    let _claimed = Outputs::claim(&named(OUT, &targets))?;
    watch.note(&format!(
        "sweep: {} ratio(s) {:?} ({}: grids {:?}){}, {} at a time",
        jobs.len(),
        jobs.iter()
            .map(|j| j.model.scene.ratio())
            .collect::<Vec<_>>(),
        req.grid.describe(),
        jobs.iter().map(|j| j.model.nx).collect::<Vec<_>>(),
        req.shard
            .map_or(String::new(), |(k, n)| format!(", shard {k} of {n}")),
        req.jobs
    ));
    let ran = jobs.len();
    let results = run_jobs(jobs, req.jobs, req.backend, watch);
    let rows: Vec<SweepRow> = results.iter().map(|r| r.row()).collect();
    let failures: Vec<String> = results.iter().filter_map(|r| r.error.clone()).collect();
    let mut warnings: Vec<String> = results.iter().flat_map(|r| r.warnings()).collect();
    write_summary(req, &summary_path, &rows)?;
    let mut sorted = rows;
    sorted.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    // The charts come last: one that cannot be drawn or written is reported beside the runs'
    // own failures (which it must not hide); sweep.csv is already written.
    let (charts, charts_error) = match req.shard {
        Some(_) => (None, None),
        None => match write_sweep_charts(
            &req.out,
            &sorted,
            &chart_data::sweep_curves(&sorted, row_curves(&results, &sorted)),
            req.figures,
        ) {
            Ok(w) => {
                warnings.extend(w);
                (Some(chart_files(&req.out)), None)
            }
            Err(e) => (None, Some(e.with_param(OUT).to_string())),
        },
    };
    Ok(SweepDone {
        rows: sorted,
        summary_path,
        charts,
        ran,
        failures,
        charts_error,
        warnings,
    })
}

/// One job per ratio of this shard (every ratio of the sweep is checked, so that every shard
/// refuses a bad sweep), within the memory `--jobs` of them need.
fn sweep_jobs(req: &SweepRequest) -> Result<Vec<Job>, RunError> {
    let mut models = Vec::new();
    for &ratio in &sweep_csv::shard_ratios(&req.ratios, req.shard) {
        models.push(model_for(req, ratio)?);
    }
    for &ratio in &req.ratios {
        model_for(req, ratio)?;
    }
    let refs: Vec<&Model> = models.iter().map(|(m, _)| m).collect();
    crate::plan::check_memory(&refs, req.jobs, GRID).map_err(input)?;
    Ok(models
        .into_iter()
        .map(|(model, target)| {
            let out = states_path(&req.out, model.scene.ratio(), model.nx);
            Job { model, out, target }
        })
        .collect())
}

/// Write the rows: a shard's file (with the sweep's settings, for `collect`) or sweep.csv.
fn write_summary(req: &SweepRequest, path: &Path, rows: &[SweepRow]) -> Result<(), RunError> {
    match req.shard {
        Some(kn) => {
            let (grid, accuracy) = match req.grid {
                GridChoice::Fixed(nx) => (Some(nx), None),
                GridChoice::Accuracy(t) => (None, Some(t)),
            };
            let settings = SweepSettings {
                ratios: req.ratios.clone(),
                grid,
                accuracy,
                steps: req.steps,
                start_radius: req.start_radius,
                margin: req.margin,
            };
            Shard::new(settings, kn, rows.to_vec())
                .write(path)
                .map_err(write_error(OUT))
        }
        None => sweep_csv::write_rows(path, rows).map_err(write_error(OUT)),
    }
}

/// What merging a split sweep's shards produced.
pub struct Merged {
    /// The merged rows.
    pub rows: usize,
    /// Shards found, of all.
    pub shards_found: usize,
    /// Shards of the sweep.
    pub shards: usize,
    /// sweep.csv.
    pub path: PathBuf,
    /// The charts, by their SVG paths (their files in the formats asked for:
    /// [`FigureFormats::files`]).
    pub charts: [PathBuf; 2],
    /// What is missing or incomplete (merged anyway with `allow_missing`).
    pub problems: Vec<String>,
    /// What was merged but could not be checked or drawn: usable rows with no per-ratio
    /// summary to check them against, ratios whose states file is missing from the pull-off
    /// chart. One line each.
    pub warnings: Vec<String>,
}

/// Check every merged row of `c` against the summary its ratio's run wrote beside the shards
/// ([`sweep_csv::check_row`]): a row that disagrees stops the merge (naming the ratio and both
/// files). Returns the usable rows that have no summary, with the file looked for. The row of
/// a pull-off that failed before it had a summary ([`SweepRow::failed`]) is not checked: a
/// summary of that name is an older run's, and the row is reported as incomplete anyway.
fn check_rows(dir: &Path, c: &sweep_csv::Collected) -> Result<Vec<(f64, PathBuf)>, RunError> {
    let mut unchecked = Vec::new();
    for (row, shard) in c.rows.iter().zip(&c.row_files) {
        if row.backend.is_empty() && !row.is_usable() {
            continue;
        }
        let summary = states_path(dir, row.ratio, row.grid).with_extension("json");
        match sweep_csv::check_row(row, shard, &summary).map_err(crate::session::failed)? {
            sweep_csv::RowCheck::Agrees => {}
            sweep_csv::RowCheck::NoSummary => {
                if row.is_usable() {
                    unchecked.push((row.ratio, summary));
                }
            }
        }
    }
    Ok(unchecked)
}

/// Note every file `collect` reads in `dir` as an input of the run (the shards, and each
/// row's summary and states, complete or partial, as the checks and the curves read them),
/// so that no output of it is one of them ([`crate::output::file::note_input`]).
fn note_read_files(dir: &Path, c: &sweep_csv::Collected) {
    use crate::output::file::{is_partial_of, note_input};
    let mut read: Vec<PathBuf> = (1..=c.shards)
        .map(|k| crate::output::names::shard(dir, (k, c.shards)))
        .collect();
    let mut states_names = Vec::new();
    for row in &c.rows {
        let states = states_path(dir, row.ratio, row.grid);
        read.push(states.with_extension("json"));
        if let Some(name) = states.file_name() {
            states_names.push(name.to_string_lossy().into_owned());
        }
        read.push(states);
    }
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if states_names.iter().any(|s| is_partial_of(&name, s)) {
            read.push(entry.path());
        }
    }
    for path in read.iter().filter(|p| p.exists()) {
        note_input(path, "DIR");
    }
}

/// Ratios as text: "2, 25", or the first twenty "and 3 more".
fn listed(ratios: &[f64]) -> String {
    let shown: Vec<String> = ratios.iter().map(|r| crate::text::compact(*r)).collect();
    crate::text::listed(&shown)
}

/// `collect`'s folder, which names its outputs (an argument, not a parameter).
const DIR: NamedBy = NamedBy::Argument("DIR");

/// Merge the shard files in `dir` into `dir/sweep.csv` and its charts (in `figures`), after
/// checking that they are of one sweep with no ratio twice. Missing or incomplete ratios stop
/// the merge (naming them) unless `allow_missing`.
pub fn collect_shards(
    dir: &Path,
    allow_missing: bool,
    figures: FigureFormats,
) -> Result<Merged, RunError> {
    use crate::output::sweep_csv::CollectError;
    let c = sweep_csv::collect(dir).map_err(|e| match e {
        CollectError::Empty(_) | CollectError::Io(..) => input(e),
        CollectError::Corrupt(..)
        | CollectError::Mixed(..)
        | CollectError::Duplicate { .. }
        | CollectError::Mismatch { .. } => crate::session::failed(e),
    })?;
    let unchecked = check_rows(dir, &c)?;
    let mut problems = Vec::new();
    if !c.missing.is_empty() {
        problems.push(format!(
            "R1/R2 = {} missing{}",
            listed(&c.missing),
            if c.missing_shards.is_empty() {
                String::new()
            } else {
                format!(
                    " (shards [{}] of {} have not written their file: run them)",
                    crate::text::listed(&c.missing_shards),
                    c.shards
                )
            }
        ));
    }
    if !c.incomplete.is_empty() {
        problems.push(format!(
            "R1/R2 = {} incomplete (failed, no force minimum reached, or not finite: see their \
             complete, min_reached and error columns)",
            listed(&c.incomplete)
        ));
    }
    if !problems.is_empty() && !allow_missing {
        return Err(crate::session::failed(format!(
            "{}; nothing was written (pass {ALLOW_MISSING} to merge what there is)",
            problems.join("; ")
        )));
    }
    let path = sweep_csv::sweep_csv_path(dir);
    let charts = chart_files(dir);
    let mut targets = vec![path.clone()];
    targets.extend(figure_files(dir, figures));
    note_read_files(dir, &c);
    let _claimed = Outputs::claim(&named(DIR, &targets))?;
    sweep_csv::write_rows(&path, &c.rows).map_err(write_error(DIR))?;
    let mut warnings = Vec::new();
    if !unchecked.is_empty() {
        warnings.push(format!(
            "R1/R2 = {}: no per-ratio summary ({}) beside the shards, so their rows were not \
             checked against it (copy each shard's r<ratio>-n<grid>.* files into {} to check them)",
            listed(&unchecked.iter().map(|u| u.0).collect::<Vec<_>>()),
            unchecked
                .iter()
                .map(|u| u.1.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            dir.display()
        ));
    }
    let curves = chart_data::sweep_curves(&c.rows, sweep_curves(dir, &c.rows));
    warnings.extend(write_sweep_charts(dir, &c.rows, &curves, figures).map_err(write_error(DIR))?);
    Ok(Merged {
        rows: c.rows.len(),
        shards_found: c.shards - c.missing_shards.len(),
        shards: c.shards,
        path,
        charts,
        problems,
        warnings,
    })
}
