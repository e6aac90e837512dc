//! Many independent pull-offs (the ratios of a sweep, the angles of crossed cylinders), each on
//! its own backend, several at a time in a rayon pool. Each writes its states, its summary
//! JSON and its contours beside each other.

use super::claim::write_error;
use super::open::{open_for, BackendRequest};
use super::pulloff::{pulloff, StatesFile};
use super::{RunError, Watch};
use crate::analysis::capture::{contour_rows, ContactCapture, ContourRow};
use crate::analysis::estimate::AdhesiveResult;
use crate::model::{Model, ModelOptions};
use crate::output::summary::Summary;
use crate::output::sweep_csv::SweepRow;
use crate::params::{ACCURACY, OUT};
use crate::solver::State;
use rayon::prelude::*;
use std::path::PathBuf;

/// Mean contact radii c̄ at which a pull-off's contact is kept for contours.
pub const SNAPSHOT_RADII: [f64; 4] = [1.4, 1.1, 0.8, 0.5];

/// One pull-off of a batch: its model, its states file and the accuracy it is held to.
#[derive(Debug, Clone)]
pub struct Job {
    /// The model to run.
    pub model: Model,
    /// Its states CSV (its summary and contours go beside it, see [`run_files`]).
    pub out: PathBuf,
    /// The relative uncertainty asked for, if the grid was planned for one.
    pub target: Option<f64>,
}

/// How a batch chooses each scene's grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridChoice {
    /// The same Nx for every scene (`--grid`); each estimate states its expected bias.
    Fixed(usize),
    /// The one grid that reaches this relative accuracy of |min F̄| at Δx → 0 (`--accuracy`).
    Accuracy(f64),
}

impl GridChoice {
    /// "grid 256" or "⟨accuracy⟩ 2 %", for progress lines and captions.
    pub fn describe(&self) -> String {
        match self {
            GridChoice::Fixed(nx) => format!("grid {nx}"),
            GridChoice::Accuracy(t) => format!("{ACCURACY} {} %", crate::text::compact(100.0 * t)),
        }
    }
}

/// The model of one scene of a batch and the target it is held to: on a fixed grid, or on the
/// one grid the accuracy planner chooses, re-gridded, with the whole curve computed (a batch
/// draws the curves and contours). `base` holds the steps, c̄0 and margin.
pub fn batch_model(
    scene: &crate::scene::Scene,
    choice: GridChoice,
    base: &ModelOptions,
) -> Result<(Model, Option<f64>), crate::model::ModelError> {
    match choice {
        GridChoice::Fixed(nx) => Ok((
            Model::build(scene, &ModelOptions { nx, ..base.clone() })?,
            None,
        )),
        GridChoice::Accuracy(target) => {
            let p = crate::plan::for_accuracy_one_grid(scene, target, base)?;
            let options = ModelOptions {
                nx: p.grids[0],
                steps: base.steps,
                measure: crate::model::Measure::Curve,
                ..p.options
            };
            Ok((Model::build(scene, &options)?, Some(target)))
        }
    }
}

/// What became of one job.
#[derive(Debug, Clone)]
pub struct JobResult {
    /// R1/R2.
    pub ratio: f64,
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// Element side Δx (length).
    pub dx: f64,
    /// Its summary, if the run started (complete or not).
    pub summary: Option<Summary>,
    /// Why it failed, in words, if it did.
    pub error: Option<String>,
    /// The states it recorded (those before its error, if it stopped early), as written.
    pub states: Vec<State>,
    /// Whether its states file is complete (at its own name, not a partial one).
    pub complete: bool,
    /// The quarter contours of the states it kept, as written beside its states.
    pub contours: Vec<ContourRow>,
}

impl JobResult {
    /// Its summary's warnings, each prefixed with the ratio.
    pub fn warnings(&self) -> Vec<String> {
        self.summary.as_ref().map_or(Vec::new(), |s| {
            s.warnings
                .iter()
                .map(|w| format!("R1/R2 = {}: {w}", crate::text::compact(self.ratio)))
                .collect()
        })
    }

    /// Its row of a sweep's summary: from the summary, or marked failed.
    pub fn row(&self) -> SweepRow {
        match &self.summary {
            Some(s) => SweepRow::from_summary(s),
            None => SweepRow::failed(
                self.ratio,
                self.grid,
                self.dx,
                self.error.clone().unwrap_or_default(),
                jg_of(self.ratio),
            ),
        }
    }
}

pub use crate::output::names::run_files;

/// Johnson–Greenwood's |min F̄| for `ratio` (JKR's 1/2 at 1), the comparison a sweep row
/// carries; `None` where it cannot be evaluated.
pub fn jg_of(ratio: f64) -> Option<f64> {
    crate::theory::reference_adhesive_force(ratio).ok()
}

/// The notes and warnings of a [`Watch`], without its progress line: jobs run on several
/// threads at once, so they show none.
struct NotesOnly<'a>(&'a dyn Watch);

impl Watch for NotesOnly<'_> {
    fn note(&self, line: &str) {
        self.0.note(line)
    }
    fn warning(&self, line: &str) {
        self.0.warning(line)
    }
    fn keep_going(&self) -> bool {
        self.0.keep_going()
    }
}

/// Run every job, `threads` at a time (1: one after another, each using every core), each on
/// its own backend of `backend`, and write its summary and contours beside its states.
/// `watch` receives the notes and warnings. Returns one result per job, in the order given.
pub fn run_jobs(
    jobs: Vec<Job>,
    threads: usize,
    backend: BackendRequest,
    watch: &dyn Watch,
) -> Vec<JobResult> {
    let one = |job: Job| {
        let (ratio, grid, dx) = (
            job.model.scene.ratio(),
            (job.model.nx, job.model.ny),
            job.model.dx,
        );
        match run_one(&backend, job, watch) {
            Ok(ran) => JobResult {
                ratio,
                grid,
                dx,
                summary: Some(ran.summary),
                error: ran.error,
                states: ran.states,
                complete: ran.complete,
                contours: ran.contours,
            },
            Err(e) => JobResult {
                ratio,
                grid,
                dx,
                summary: None,
                error: Some(format!("R1/R2 = {ratio}: {e}")),
                states: Vec::new(),
                complete: false,
                contours: Vec::new(),
            },
        }
    };
    if threads <= 1 {
        return jobs.into_iter().map(one).collect();
    }
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(|| jobs.into_par_iter().map(one).collect()),
        Err(_) => jobs.into_iter().map(one).collect(),
    }
}

/// What one job produced besides its files.
struct Ran {
    summary: Summary,
    error: Option<String>,
    states: Vec<State>,
    complete: bool,
    contours: Vec<ContourRow>,
}

/// One job: open the backend, run, write states, summary and contours. Returns them, with
/// the run's error, if it stopped early.
fn run_one(backend: &BackendRequest, mut job: Job, watch: &dyn Watch) -> Result<Ran, RunError> {
    let ratio = job.model.scene.ratio();
    let opened = open_for(backend, &mut job.model)?;
    watch.note(&format!(
        "R1/R2 = {ratio}: grid {}×{}, {}",
        job.model.nx, job.model.ny, opened.note
    ));
    let mut any = opened.backend;
    let mut capture = ContactCapture::new(&SNAPSHOT_RADII);
    let notes = NotesOnly(watch);
    let run = crate::with_backend!(
        &mut any,
        b => pulloff(b, &job.model, Some(StatesFile { path: &job.out, param: OUT }), &notes, Some(&mut capture), None)
    )?;
    let [_, json, contours] = run_files(&job.out);
    let shown = run.states_shown();
    let mut report = run.report;
    report.device = Some(any.device_summary());
    let mut summary = Summary::new(&AdhesiveResult::single(report, job.target));
    summary.provenance = Some(super::provenance::provenance(
        &job.model.scene,
        super::provenance::model_json(
            &job.model,
            serde_json::json!({"kind": "batch job", "target": job.target}),
        ),
        super::provenance::backend_json(backend, &summary.runs),
    ));
    summary.write_json(&json).map_err(write_error(OUT))?;
    let rows = contour_rows(
        &job.model,
        &capture.into_snapshots(run.outcome.min_reached()),
    );
    crate::output::file::write_csv(&contours, None, rows.clone()).map_err(write_error(OUT))?;
    let error = run
        .outcome
        .error
        .map(|e| format!("R1/R2 = {ratio}: {e} (states so far in {shown})"));
    Ok(Ran {
        summary,
        error,
        complete: run.states.as_deref() == Some(job.out.as_path()),
        states: run.outcome.states,
        contours: rows,
    })
}
