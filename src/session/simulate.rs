//! One scene's pull-off: on one grid, on several grids extrapolated to Δx → 0, or on the grids
//! a requested accuracy needs. Every run's states and the summary (one shape for all three) are
//! returned in memory; where the caller's [`Sink`] asks for files, the states also go to CSVs
//! and the summary to JSON.

use super::claim::Outputs;
use super::open::{open_for, BackendRequest};
use super::pulloff::{pulloff, Pulloff, StatesFile};
use super::{failed, input, provenance, refuse, RunError, Watch};
use crate::analysis::capture::MaskObserver;
use crate::analysis::estimate::{self, AdhesiveResult};
use crate::analysis::fields::{
    minimum_label, FieldChoice, FieldPicks, StateFields, LOWEST_NOT_MINIMUM,
};
use crate::analysis::generic_limit;
use crate::analysis::jkr_sphere::JkrSphere;
use crate::model::{Measure, Model, ModelOptions, Onsets};
use crate::output::digest::InputFile;
use crate::output::figure::FigureFormats;
use crate::output::pressure_profile::{self, ClosedFormPressure};
use crate::output::provenance::Provenance;
use crate::output::summary::Summary;
use crate::output::{data, names, pressure_chart, NamedBy};
use crate::params::{Spec, ACCURACY, EXTRAPOLATE_GRIDS, FIELDS, GRID, OUT, SUMMARY, TIME_LIMIT};
use crate::plan;
use crate::scene::Scene;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// What to do with the scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Mode {
    /// One run on the options' grid, its estimate corrected by the convergence law.
    Single,
    /// One run per grid Nx (2 to 8, increasing), extrapolated to Δx → 0; `None`: the grids that
    /// fit the scene, the coarsest that resolves it and its two doublings
    /// ([`plan::extrapolation_grids`]).
    Extrapolate(Option<Vec<usize>>),
    /// The grids, domain, steps and measure the convergence law says this relative accuracy
    /// needs (e.g. 0.02 for 2 %).
    Accuracy(f64),
}

pub use crate::params::limits::MAX_TIME_LIMIT_S;

/// The accuracy a simulation aims at when neither a grid nor an accuracy is asked for (2 %).
pub const DEFAULT_ACCURACY: f64 = 0.02;

impl Mode {
    /// What a front end's choices ask for: the accuracy given; else an extrapolation where
    /// asked (`extrapolate`: its grids, or `None` for those that fit); else one grid where an
    /// option that only a single grid takes was given (`one_grid`: a grid, load steps, a
    /// measure, an indenter without a convergence law …); else [`DEFAULT_ACCURACY`].
    pub fn choose(
        accuracy: Option<f64>,
        extrapolate: Option<Option<Vec<usize>>>,
        one_grid: bool,
    ) -> Mode {
        match (accuracy, extrapolate, one_grid) {
            (Some(target), _, _) => Mode::Accuracy(target),
            (None, Some(grids), _) => Mode::Extrapolate(grids),
            (None, None, true) => Mode::Single,
            (None, None, false) => Mode::Accuracy(DEFAULT_ACCURACY),
        }
    }
}

/// A request to simulate one scene.
#[derive(Debug, Clone)]
pub struct SimulateRequest {
    /// The scene.
    pub scene: Scene,
    /// The user's model options (the grid of a single run).
    pub options: ModelOptions,
    /// The backend.
    pub backend: BackendRequest,
    /// One grid, several, or an accuracy.
    pub mode: Mode,
    /// Where the states and the summary go besides memory.
    pub sink: Sink,
    /// Which states' fields (pressure, gap, contact set) each run keeps, in memory (the CLI
    /// writes the last run's beside its states).
    pub fields: FieldChoice,
    /// Wall-clock time the request may take (with [`Mode::Accuracy`]): a grid still running
    /// then is stopped, and the answer comes from the grids that finished (the coarsest grid
    /// that resolves the contact runs first, so that there is one), with `target_met: false`
    /// where that falls short. `None`: no limit.
    pub time_limit: Option<Duration>,
    /// The request this was built from, as JSON ([`super::request::Request::to_json`]),
    /// recorded in the summary's provenance where given.
    pub request: Option<serde_json::Value>,
    /// Every file the scene was read from (height map, roughness), with its digest: recorded
    /// in the summary's provenance, so that a later run can tell it was replaced.
    pub input_files: Vec<InputFile>,
    /// The formats of the pressure map drawn beside each states file where fields are kept
    /// (with [`Sink::Files`]); its data goes to `<stem>.plot.csv` whatever they are.
    pub figures: FigureFormats,
}

/// Where a simulation's results go besides memory.
#[derive(Debug, Clone, PartialEq)]
pub enum Sink {
    /// Files: the states CSV (one grid), or the stem of the per-grid CSVs
    /// (`<stem>-n<Nx>.csv`), `None` putting them under `jkrbem-out/`; and the summary JSON
    /// where `summary` names it.
    Files {
        /// The states CSV or the per-grid stem.
        out: Option<PathBuf>,
        /// The summary JSON, if wanted.
        summary: Option<PathBuf>,
    },
    /// The states returned only, for the caller to send on as one CSV (the command line's
    /// `--out -`, standard output): a request that runs more than one grid, or keeps fields
    /// (written beside a states file), is refused. The summary JSON where `summary` names it.
    OneRunReturned {
        /// The summary JSON, if wanted.
        summary: Option<PathBuf>,
    },
    /// Nothing written: the states and the summary are returned only.
    Memory,
}

impl Sink {
    /// The summary JSON file, where one is asked for.
    fn summary(&self) -> Option<&PathBuf> {
        match self {
            Sink::Files { summary, .. } | Sink::OneRunReturned { summary } => summary.as_ref(),
            Sink::Memory => None,
        }
    }
}

/// One grid's run of a simulation, in memory.
pub struct GridRun {
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// Element side Δx at the start (length).
    pub dx: f64,
    /// Every state it recorded, in order.
    pub states: Vec<crate::solver::State>,
    /// Whether it reached its end (or its confirmed minimum); `false` for a run that failed,
    /// ran out of time or was stopped by its watch.
    pub complete: bool,
    /// The fields of the states [`SimulateRequest::fields`] picked, by state index.
    pub fields: Vec<StateFields>,
    /// Which onsets its states hold (the states CSV's `onsets` column).
    pub onsets: Onsets,
}

/// What a simulation produced.
pub struct Simulated {
    /// The summary (also written as JSON where asked).
    pub summary: Summary,
    /// What the accuracy plan chose, in words (with [`Mode::Accuracy`]).
    pub plan: Option<String>,
    /// The states CSV of every run (none with [`Sink::Memory`]).
    pub states: Vec<PathBuf>,
    /// Every grid's run, in the order run.
    pub runs: Vec<GridRun>,
    /// Whether the watch stopped a run ([`Watch::keep_going`]): the answer is from what
    /// finished before, and the stopped run's states are in [`Simulated::runs`].
    pub stopped: bool,
    /// Why a run stopped early, if one did (its states and the summary were written).
    pub failure: Option<String>,
    /// The fields files written (with [`Sink::Files`] and fields asked for).
    pub field_files: Vec<PathBuf>,
}

/// The files the request would write (each with the flag that names it), after every check
/// [`simulate`] makes before any work (the backend asked for, the plan, the memory), creating
/// nothing: what a batch checks of every scene before it runs any. None with [`Sink::Memory`].
pub fn planned_outputs(req: &SimulateRequest) -> Result<Vec<(PathBuf, NamedBy)>, RunError> {
    req.backend.check()?;
    let planned = plan_models(req)?;
    check_memory(req, &planned.models)?;
    match &req.sink {
        Sink::Files { out, summary } => {
            let outs = output_paths(req, out, &planned.all_models())?;
            Ok(targets(req, &outs, summary))
        }
        Sink::OneRunReturned { .. } | Sink::Memory => Ok(Vec::new()),
    }
}

/// Refuse models that, with the fields asked for, do not fit in memory.
fn check_memory(req: &SimulateRequest, models: &[Model]) -> Result<(), RunError> {
    let refs: Vec<&Model> = models.iter().collect();
    let param = match req.mode {
        Mode::Single => GRID,
        _ => EXTRAPOLATE_GRIDS,
    };
    plan::check_memory_with_fields(&refs, 1, param, &req.fields).map_err(input)
}

/// Every file written for the states files `outs`: each, its fields where asked, and the
/// summary where asked.
fn targets(
    req: &SimulateRequest,
    outs: &[PathBuf],
    summary: &Option<PathBuf>,
) -> Vec<(PathBuf, NamedBy)> {
    let mut targets: Vec<(PathBuf, NamedBy)> =
        outs.iter().map(|p| (p.clone(), OUT.into())).collect();
    if !req.fields.is_none() {
        for o in outs {
            targets.push((data::fields_path(o), FIELDS.into()));
            for chart in [names::pressure_chart(o), names::profile_chart(o)] {
                for file in req.figures.files(&chart) {
                    targets.push((file, FIELDS.into()));
                }
            }
        }
    }
    if let Some(p) = summary {
        targets.push((p.clone(), SUMMARY.into()));
    }
    targets
}

/// Run the request: check every input, claim the outputs, run, estimate, write the summary.
pub fn simulate(req: &SimulateRequest, watch: &dyn Watch) -> Result<Simulated, RunError> {
    req.backend.check()?;
    let planned = plan_models(req)?;
    let all = planned.all_models();
    let Planned {
        models,
        target,
        note: plan_note,
        fallback,
        more,
    } = planned;
    let planned_runs = models.len();
    check_memory(req, &models)?;
    let (outs, _claimed) = match &req.sink {
        Sink::Files { out, summary } => {
            let outs = output_paths(req, out, &all)?;
            let targets = targets(req, &outs, summary);
            Outputs::check(&targets)?;
            let claimed = Outputs::claim(&targets)?;
            (outs.into_iter().map(Some).collect(), Some(claimed))
        }
        Sink::OneRunReturned { summary } => {
            one_run_returned(req, &models)?;
            let targets: Vec<(PathBuf, NamedBy)> = summary
                .iter()
                .map(|p| (p.clone(), SUMMARY.into()))
                .collect();
            Outputs::check(&targets)?;
            let claimed = Outputs::claim(&targets)?;
            (vec![None; all.len()], Some(claimed))
        }
        Sink::Memory => (vec![None; all.len()], None),
    };
    // A limit past what a clock holds (centuries) is no limit.
    let deadline = req.time_limit.and_then(|t| Instant::now().checked_add(t));
    let first = models.len();
    let mut ran = run_grids(req, models, &outs[..first], watch, deadline)?;
    if !more.is_empty() {
        ran = refine_generic(req, ran, more, &outs[first..], watch, deadline)?;
    }
    let reports: Vec<_> = ran.runs.iter().map(|r| r.report.clone()).collect();
    let mut provenance = provenance::provenance(
        &req.scene,
        provenance::options_json(&req.options, mode_json(req)),
        provenance::backend_json(&req.backend, &reports),
    );
    provenance.request = req.request.clone();
    provenance.input_files = req.input_files.clone();
    let (field_files, unwritten) =
        write_fields(&ran.kept, &outs, &provenance, req.figures, &req.scene);
    if !unwritten.is_empty() {
        let e = unwritten.join("\n  ");
        ran.failure = Some(match ran.failure.take() {
            Some(f) => format!("{f}\n  {e}"),
            None => e,
        });
    }
    let mut done = conclude(
        req,
        ran,
        Concluding {
            target,
            plan_note,
            fallback,
            planned_runs,
            provenance,
            unwritten,
        },
    );
    done.field_files = field_files;
    Ok(done)
}

/// Refuse a [`Sink::OneRunReturned`] request that runs several grids or keeps fields.
fn one_run_returned(req: &SimulateRequest, models: &[Model]) -> Result<(), RunError> {
    if models.len() != 1 || matches!(req.mode, Mode::Extrapolate(_)) {
        return Err(refuse(
            OUT,
            format!(
                "{OUT} -: standard output takes the states of one run, and this request runs {} \
             grids; give {OUT} a file name (the stem of one states file per grid)",
                models.len()
            ),
        ));
    }
    if !req.fields.is_none() {
        return Err(refuse(
            FIELDS,
            format!(
                "{FIELDS}: the fields are written beside the states file, and {OUT} - sends the \
             states to standard output; give {OUT} a file name"
            ),
        ));
    }
    Ok(())
}

/// Write each run's fields beside its states file (where it has a file and fields): the
/// `.npz` archive, and the pressure at the force minimum as a picture and as profiles along x
/// and y (beside JKR's closed form for a sphere of `scene`) in each of `figures` with their
/// data. Returns the files written and why each one that could not be was not (the others
/// are still written).
fn write_fields(
    runs: &[GridRun],
    outs: &[Option<PathBuf>],
    provenance: &Provenance,
    figures: FigureFormats,
    scene: &Scene,
) -> (Vec<PathBuf>, Vec<String>) {
    let mut written = Vec::new();
    let mut unwritten = Vec::new();
    for (run, out) in runs.iter().zip(outs) {
        let (Some(out), false) = (out, run.fields.is_empty()) else {
            continue;
        };
        let about = serde_json::json!({
            "grid": [run.grid.0, run.grid.1],
            "states_csv": out.display().to_string(),
            "provenance": provenance,
        });
        match data::write_fields(out, &run.fields, about) {
            Ok(path) => written.push(path),
            Err(e) => unwritten.push(e.with_param(FIELDS).to_string()),
        }
        // The run's lowest state: its force minimum, or only the lowest force it recorded.
        let lowest = |f: &&StateFields| {
            f.label.contains(minimum_label(true)) || f.label.contains(LOWEST_NOT_MINIMUM)
        };
        if let Some(min) = run.fields.iter().find(lowest) {
            let chart = names::pressure_chart(out);
            // Where the state lies, in full (the heat map's title) and short (the profiles').
            let (what, at) = if min.label.contains(LOWEST_NOT_MINIMUM) {
                (
                    "the lowest force recorded (not the minimum: the run did not reach it)",
                    "the lowest force recorded",
                )
            } else {
                ("the force minimum", "the force minimum")
            };
            let title = format!(
                "p at {what} (state {}): F̄ = {:.4}, c̄ = {:.3}, {}×{}",
                min.index, min.state.f_bar, min.state.c_bar, run.grid.0, run.grid.1
            );
            match pressure_chart::write_pressure_chart(&chart, min, &title, figures) {
                Ok(()) => written.extend(figures.files(&chart)),
                Err(e) => unwritten.push(e.with_param(FIELDS).to_string()),
            }
            let chart = names::profile_chart(out);
            let title = format!(
                "p along x and y at {at} (state {}), {}×{}",
                min.index, run.grid.0, run.grid.1
            );
            let jkr = JkrSphere::of(scene).map(|j| move |r, a, d| j.pressure(r, a, d));
            let closed = jkr.as_ref().map(|p| ClosedFormPressure {
                name: "JKR",
                pressure: p,
            });
            match pressure_profile::write_profile_chart(&chart, min, closed, &title, figures) {
                Ok(()) => written.extend(figures.files(&chart)),
                Err(e) => unwritten.push(e.with_param(FIELDS).to_string()),
            }
        }
    }
    (written, unwritten)
}

/// The states files of the request's models: `--out` itself for one grid (asked for, or the
/// one an accuracy plan chose); for several, one file per grid from `--out` as a stem.
fn output_paths(
    req: &SimulateRequest,
    out: &Option<PathBuf>,
    models: &[Model],
) -> Result<Vec<PathBuf>, RunError> {
    let one_grid = models.len() == 1 && !matches!(req.mode, Mode::Extrapolate(_));
    Ok(match (one_grid, out) {
        (true, Some(out)) => vec![out.clone()],
        (true, None) => vec![names::simulate_default(
            &req.scene.tag(),
            models[0].nx,
            (!models[0].mesh.is_aligned()).then_some(models[0].mesh.degrees),
        )],
        (false, stem) => {
            let name = match req.mode {
                Mode::Accuracy(_) => "simulate",
                _ => "extrapolate",
            };
            let stem = stem
                .clone()
                .unwrap_or_else(|| names::simulate_stem(name, &req.scene.tag()));
            if stem.is_dir() || stem.file_stem().is_none() {
                return Err(refuse(
                    OUT,
                    format!(
                        "{OUT} {}: with several grids {OUT} is the stem of one states file per \
                     grid (e.g. runs/r5.csv gives runs/r5-n128.csv, …); give a file name, not a \
                     folder",
                        stem.display()
                    ),
                ));
            }
            if req.scene.is_ellipsoid() {
                models
                    .iter()
                    .map(|m| names::grid_states(&stem, m.nx))
                    .collect()
            } else {
                // Several grid phases per grid: one file per grid and phase.
                models
                    .iter()
                    .map(|m| {
                        let phase = plan::GENERIC_PHASES
                            .iter()
                            .position(|&o| o == m.apex_offset)
                            .unwrap_or(0);
                        names::grid_phase_states(&stem, m.nx, phase)
                    })
                    .collect()
            }
        }
    })
}

/// The grids' runs, in order, until one fails, times out or (extrapolating) misses the
/// minimum.
struct Ran {
    runs: Vec<Pulloff>,
    /// Every run's states, those cut off by the time limit included.
    kept: Vec<GridRun>,
    failure: Option<String>,
    timed_out: Option<String>,
    stopped: bool,
}

/// Run every model (into its states file, where one is given), within the request's time
/// limit, until the watch stops one.
fn run_grids(
    req: &SimulateRequest,
    models: Vec<Model>,
    outs: &[Option<PathBuf>],
    watch: &dyn Watch,
    deadline: Option<Instant>,
) -> Result<Ran, RunError> {
    let mut runs = Vec::new();
    let mut kept = Vec::new();
    let mut failure = None;
    let mut timed_out = None;
    let mut stopped = false;
    for (mut model, out) in models.into_iter().zip(outs) {
        if deadline.is_some_and(|d| Instant::now() >= d) {
            timed_out = Some(format!(
                "the {}×{} grid was not started",
                model.nx, model.ny
            ));
            break;
        }
        let opened = open_for(&req.backend, &mut model)?;
        watch.note(&format!(
            "{}, grid {}×{}, Δx = {:.4e}{}, backend {}",
            req.scene.headline(),
            model.nx,
            model.ny,
            model.dx,
            angle_note(&model),
            opened.note
        ));
        let mut any = opened.backend;
        let file = out.as_deref().map(|path| StatesFile { path, param: OUT });
        let mut picks = FieldPicks::new(req.fields.clone());
        let observer: Option<&mut dyn MaskObserver> = match req.fields.is_none() {
            true => None,
            false => Some(&mut picks),
        };
        let mut run: Pulloff = crate::with_backend!(
            &mut any,
            backend => pulloff(backend, &model, file, watch, observer, deadline)
        )?;
        run.report.device = Some(any.device_summary());
        let mut fields = Vec::new();
        let unrecorded = picks.unrecorded();
        if !unrecorded.is_empty() {
            watch.warning(&format!(
                "{FIELDS}: no fields for state(s) {}: the {}×{} run recorded {} states \
                 (numbered from 0)",
                crate::text::listed(&unrecorded),
                model.nx,
                model.ny,
                run.outcome.states.len()
            ));
        }
        for f in super::fields::rebuild(&model, picks.into_picks(run.outcome.min_reached())) {
            match f {
                Ok(f) => fields.push(f),
                Err(e) => watch.warning(&e.to_string()),
            }
        }
        // The run's states move to its grid's record; the messages below need only their count.
        let recorded = run.outcome.states.len();
        kept.push(GridRun {
            grid: (model.nx, model.ny),
            dx: model.dx,
            states: std::mem::take(&mut run.outcome.states),
            complete: run.outcome.complete(),
            fields,
            onsets: model.onsets,
        });
        if run.timed_out {
            timed_out = Some(format!(
                "the {} grid was stopped after {} states (kept, incomplete, in {})",
                run.report.grid,
                recorded,
                run.states_shown()
            ));
            break;
        }
        if run.stopped {
            stopped = true;
            failure = Some(format!(
                "the {} run was stopped by its caller after {} states (kept, incomplete, in {})",
                run.report.grid,
                recorded,
                run.states_shown()
            ));
        } else if let Some(e) = &run.outcome.error {
            failure = Some(format!(
                "the {} run stopped early: {e}\n  the {} states computed so far are in {} \
                 (incomplete)",
                run.report.grid,
                recorded,
                run.states_shown()
            ));
        }
        let reached = run.report.min_reached;
        runs.push(run);
        if failure.is_some() || (!reached && !matches!(req.mode, Mode::Single)) {
            break;
        }
    }
    Ok(Ran {
        runs,
        kept,
        failure,
        timed_out,
        stopped,
    })
}

/// What the request ran, for the provenance: one grid, several, or an accuracy (with its
/// time limit), and the fields kept.
fn mode_json(req: &SimulateRequest) -> serde_json::Value {
    let mode = match &req.mode {
        Mode::Single => serde_json::json!({"kind": "single"}),
        Mode::Extrapolate(g) => serde_json::json!({"kind": "extrapolate", "grids": g}),
        Mode::Accuracy(t) => serde_json::json!({"kind": "accuracy", "target": t}),
    };
    let mut mode = mode;
    mode["time_limit_s"] = serde_json::json!(req.time_limit.map(|t| t.as_secs_f64()));
    mode["fields"] = serde_json::json!(req.fields.name());
    if matches!(req.mode, Mode::Accuracy(_)) {
        mode["note"] = serde_json::json!(
            "the plan chose each run's grid, margin, load steps and measure: see the runs"
        );
    }
    mode
}

/// What the plan said that the conclusion needs.
struct Concluding {
    target: Option<f64>,
    plan_note: Option<String>,
    fallback: usize,
    planned_runs: usize,
    provenance: Provenance,
    /// Why each output asked for that was not written (the fields) was not.
    unwritten: Vec<String>,
}

/// The answer from the runs that finished: the estimate, its summary (written where asked)
/// and why the request fell short, if it did.
fn conclude(req: &SimulateRequest, ran: Ran, plan: Concluding) -> Simulated {
    let Ran {
        runs,
        kept,
        mut failure,
        timed_out,
        stopped,
    } = ran;
    let Concluding {
        target,
        mut plan_note,
        fallback,
        planned_runs,
        provenance,
        unwritten,
    } = plan;
    let states: Vec<PathBuf> = runs.iter().filter_map(|r| r.states.clone()).collect();
    let mut reports: Vec<_> = runs.into_iter().map(|r| r.report).collect();
    // Every planned grid finished: the answer is the plan's, the fallback grid is not used
    // (pooling it would change the estimator the plan chose after seeing the data).
    if fallback > 0 && reports.len() == planned_runs && timed_out.is_none() && failure.is_none() {
        let unused: Vec<String> = reports.drain(..fallback).map(|r| r.grid).collect();
        if let Some(note) = &mut plan_note {
            note.push_str(&format!(
                "; the planned grids finished, so the answer is theirs (the fallback {} is \
                 not used; its states are kept)",
                unused.join(", ")
            ));
        }
    }
    if let (Some(why), true) = (&timed_out, reports.is_empty()) {
        let limit = req.time_limit.unwrap_or_default().as_secs_f64();
        failure = Some(format!(
            "{TIME_LIMIT} {}: {why}, and no grid had reached the force minimum; allow more \
             time",
            crate::text::duration(limit)
        ));
    }
    // One run (one grid, or the one grid an accuracy plan chose): its single-grid estimate.
    let one_grid = !matches!(req.mode, Mode::Extrapolate(_));
    let exact = req
        .scene
        .indenter
        .exact_adhesive_force(req.scene.e_star, req.scene.work_of_adhesion);
    // The ellipsoid's convergence law holds for a minimum a receding front reached; a run
    // whose minimum is a pinned contact's first onset is answered as a shape without one.
    // (Nor is the closed form of the receding branch the limit: JKR's 1/2, the power law's.)
    let pinned = reports.iter().any(|r| r.min_pinned);
    let law = req.scene.is_ellipsoid() && !pinned;
    let exact = exact.filter(|_| !pinned);
    let result = if !law && req.mode == Mode::Single && reports.len() == 1 {
        AdhesiveResult::beside_limit(reports.into_iter().next().expect("one run"), exact)
    } else if !law {
        // A deadline (or a stop) that cut a grid between its phases leaves it too few for the
        // phase scatter: the answer comes from the grids that finished, as the time limit's
        // warning says.
        let cut = if timed_out.is_some() || stopped {
            drop_unfinished_grid(&mut reports)
        } else {
            None
        };
        if let (Some(cut), Some(note)) = (&cut, &mut plan_note) {
            note.push_str(&format!("; {cut}"));
        } else if let Some(cut) = cut {
            plan_note = Some(cut);
        }
        // No convergence law: the grids and their phases extrapolated (every run, the
        // accuracy loop's finer grids included).
        let limit = generic_limit::grids_of(&reports).and_then(|g| generic_limit::limit(&g));
        if let (Err(why), None) = (&limit, &failure) {
            failure = Some(if pinned {
                format!(
                    "no estimate with an uncertainty: the force minimum is a pinned contact's \
                     first onset, where the convergence law does not apply, and the grids \
                     cannot be extrapolated without it ({why})"
                )
            } else {
                format!("no extrapolation: {why}")
            });
        }
        let result = AdhesiveResult::generic(reports, limit.ok(), exact, target);
        if let (Some(t), None, Some(note)) = (result.target, &failure, &plan_note) {
            if !t.met && timed_out.is_none() {
                failure = Some(format!(
                    "{ACCURACY} {}%: not reached within this machine's limits ({note})",
                    crate::text::compact(100.0 * t.target)
                ));
            }
        }
        result
    } else if reports.len() == 1 && one_grid {
        AdhesiveResult::single(reports.into_iter().next().expect("one run"), target)
    } else {
        let est = estimate::from_runs(&reports);
        if let (Err(why), None) = (&est, &failure) {
            failure = Some(format!("no extrapolation: {why}"));
        }
        AdhesiveResult::assemble(req.scene.ratio(), est.ok(), target, reports)
    };
    let mut summary = Summary::new(&result);
    summary.set_force_scale(req.scene.scales().force);
    summary.provenance = Some(provenance);
    if let (Some(why), false) = (&timed_out, summary.runs.is_empty()) {
        let limit = req.time_limit.unwrap_or_default().as_secs_f64();
        summary.warnings.push(format!(
            "{TIME_LIMIT} {} reached: {why}; the answer is from the grids that finished",
            crate::text::duration(limit)
        ));
    }
    // Not every output asked for exists: the summary says so, naming each.
    for why in unwritten {
        summary.warnings.push(format!("outputs incomplete: {why}"));
    }
    if let Some(p) = req.sink.summary() {
        // The answer is computed and the states are written: a summary that cannot be
        // written fails the run, but the answer is still given and the files already
        // replaced are named.
        if let Err(e) = summary.write_json(p) {
            let written: Vec<String> = states.iter().map(|s| s.display().to_string()).collect();
            let why = format!(
                "{}; the states were written (complete): {}",
                e.with_param(SUMMARY),
                written.join(", ")
            );
            failure = Some(match failure {
                Some(f) => format!("{f}\n  {why}"),
                None => why,
            });
        }
    }
    Simulated {
        summary,
        plan: plan_note,
        states,
        runs: kept,
        stopped,
        failure,
        field_files: Vec::new(),
    }
}

/// What a request runs: the models (every input checked), the accuracy target (if any) and,
/// for an accuracy, what the plan chose.
struct Planned {
    models: Vec<Model>,
    target: Option<f64>,
    note: Option<String>,
    /// Leading models that are only a fallback (the coarse grid a time-limited accuracy run
    /// takes first): their runs count only if the planned grids do not all finish.
    fallback: usize,
    /// A shape without a convergence law run to an accuracy: the finer grids (each its runs
    /// at every grid phase) added one at a time while the stated uncertainty exceeds the
    /// target.
    more: Vec<Vec<Model>>,
}

impl Planned {
    /// Just `models`: no target, note, fallback or finer grids.
    fn of(models: Vec<Model>) -> Planned {
        Planned {
            models,
            target: None,
            note: None,
            fallback: 0,
            more: Vec::new(),
        }
    }

    /// Every model the request may run: the planned ones, then the finer grids that may
    /// follow.
    fn all_models(&self) -> Vec<Model> {
        self.models
            .iter()
            .chain(self.more.iter().flatten())
            .cloned()
            .collect()
    }
}

/// Refuse an extrapolation's ladder `grids` unless it is 2 to 8 increasing grids.
fn check_ladder(grids: &[usize]) -> Result<(), RunError> {
    if !(2..=8).contains(&grids.len()) || grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(refuse(
            EXTRAPOLATE_GRIDS,
            format!("{EXTRAPOLATE_GRIDS}: give 2 to 8 increasing grids, e.g. 64,128,256"),
        ));
    }
    Ok(())
}

/// The models the request runs.
fn plan_models(req: &SimulateRequest) -> Result<Planned, RunError> {
    let build = |options: &ModelOptions, param: Option<&'static Spec>| {
        Model::build(&req.scene, options).map_err(|e| match param {
            None => input(e),
            Some(p) => refuse(p, format!("{p} {}: {e}", options.nx)),
        })
    };
    // One model per grid Nx (Ny fitted to the contact), a refusal naming `param` and the grid.
    let per_grid = |grids: &[usize], options: &ModelOptions, param: &'static Spec| {
        grids
            .iter()
            .map(|&nx| {
                let options = ModelOptions {
                    nx,
                    ny: None,
                    ..options.clone()
                };
                build(&options, Some(param))
            })
            .collect::<Result<Vec<_>, _>>()
    };
    if !req.scene.is_ellipsoid() && req.mode != Mode::Single {
        return plan_generic(req);
    }
    match &req.mode {
        Mode::Single => Ok(Planned::of(vec![build(&req.options, None)?])),
        Mode::Extrapolate(grids) => {
            let grids = match grids {
                Some(g) => g.clone(),
                None => plan::extrapolation_grids(&req.scene, &req.options).map_err(input)?,
            };
            check_ladder(&grids)?;
            let models = per_grid(&grids, &req.options, EXTRAPOLATE_GRIDS)?;
            Ok(Planned::of(models))
        }
        Mode::Accuracy(target) => {
            let p = plan::for_accuracy(&req.scene, *target, &req.options).map_err(input)?;
            let note = p.describe(req.scene.ratio());
            let options = ModelOptions {
                onsets: Onsets::NearMinimum,
                measure: Measure::AdhesiveForce,
                ..p.options.clone()
            };
            let mut grids = p.grids.clone();
            let mut note = note;
            let mut fallback = 0;
            if req.time_limit.is_some() {
                let first =
                    plan::coarsest_resolving_grid(&req.scene, &req.options).map_err(input)?;
                if first < grids[0] {
                    grids.insert(0, first);
                    fallback = 1;
                    note.push_str(&format!(
                        "; with {TIME_LIMIT}, grid {first} first (the coarsest that resolves \
                         the contact), so that an answer exists however early the limit comes \
                         (used only if the planned grids do not finish)"
                    ));
                }
            }
            let models = per_grid(&grids, &options, ACCURACY)?;
            Ok(Planned {
                models,
                target: Some(*target),
                note: Some(note),
                fallback,
                more: Vec::new(),
            })
        }
    }
}

/// The models of a shape without a convergence law ([`generic_limit`]): every grid of an
/// extrapolation (given, or [`plan::generic_grids`]) or of an accuracy plan
/// ([`plan::for_generic_accuracy`]) at every grid phase ([`plan::GENERIC_PHASES`]), grid by
/// grid; for an accuracy, the finer grids that may follow.
fn plan_generic(req: &SimulateRequest) -> Result<Planned, RunError> {
    let phases = |nx: usize, options: &ModelOptions, param: &'static Spec| {
        plan::GENERIC_PHASES
            .iter()
            .map(|&apex_offset| {
                let options = ModelOptions {
                    nx,
                    ny: None,
                    apex_offset,
                    ..options.clone()
                };
                Model::build(&req.scene, &options)
                    .map_err(|e| refuse(param, format!("{param} {nx}: {e}")))
            })
            .collect::<Result<Vec<_>, _>>()
    };
    match &req.mode {
        Mode::Single => Err(refuse(
            GRID,
            format!(
                "{GRID}: one grid of the {} has no uncertainty to extrapolate",
                req.scene.indenter.name()
            ),
        )),
        Mode::Extrapolate(grids) => {
            let grids = match grids {
                Some(g) => g.clone(),
                None => plan::generic_grids(&req.scene, &req.options).map_err(input)?,
            };
            check_ladder(&grids)?;
            let mut models = Vec::new();
            for &nx in &grids {
                models.extend(phases(nx, &req.options, EXTRAPOLATE_GRIDS)?);
            }
            Ok(Planned::of(models))
        }
        Mode::Accuracy(target) => {
            let p = plan::for_generic_accuracy(&req.scene, *target, &req.options).map_err(input)?;
            let mut models = Vec::new();
            for &nx in &p.grids {
                models.extend(phases(nx, &p.options, ACCURACY)?);
            }
            let more = p
                .more
                .iter()
                .map(|&nx| phases(nx, &p.options, ACCURACY))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(Planned {
                models,
                target: Some(*target),
                note: Some(p.describe()),
                fallback: 0,
                more,
            })
        }
    }
}

/// The accuracy loop of a shape without a convergence law: while the runs so far finished,
/// and their extrapolation states more than the target (or is refused), run the next finer
/// grid at every phase (`more`, with their states files `outs`), within the deadline.
fn refine_generic(
    req: &SimulateRequest,
    mut ran: Ran,
    more: Vec<Vec<Model>>,
    outs: &[Option<PathBuf>],
    watch: &dyn Watch,
    deadline: Option<Instant>,
) -> Result<Ran, RunError> {
    let Mode::Accuracy(target) = req.mode else {
        return Ok(ran);
    };
    let mut at = 0;
    for level in more {
        if ran.failure.is_some() || ran.timed_out.is_some() || ran.stopped {
            break;
        }
        let reports: Vec<_> = ran.runs.iter().map(|r| r.report.clone()).collect();
        let stated = generic_limit::grids_of(&reports).and_then(|g| generic_limit::limit(&g));
        match &stated {
            Ok(l) if l.relative() <= target => break,
            Ok(l) => watch.note(&format!(
                "{ACCURACY}: ± {:.2} % stated from grids {}, more than the target ± {:.2} %: \
                 a finer grid",
                100.0 * l.relative(),
                l.grids.join(", "),
                100.0 * target
            )),
            Err(why) => watch.note(&format!(
                "{ACCURACY}: no estimate yet ({why}): a finer grid"
            )),
        }
        let n = level.len();
        let next = run_grids(req, level, &outs[at..at + n], watch, deadline)?;
        at += n;
        ran.runs.extend(next.runs);
        ran.kept.extend(next.kept);
        ran.failure = next.failure;
        ran.timed_out = next.timed_out;
        ran.stopped = next.stopped;
    }
    Ok(ran)
}

/// Drop the finest grid's runs where it finished fewer grid phases than the extrapolation
/// needs ([`generic_limit::MIN_PHASES`]) and coarser grids remain: what a deadline that cut the
/// grid between its phases leaves. Says what was left out; `None` where nothing was.
fn drop_unfinished_grid(reports: &mut Vec<crate::analysis::report::RunReport>) -> Option<String> {
    let labels: Vec<&str> = reports.iter().map(|r| r.grid.as_str()).collect();
    let (finest, phases) = unfinished_finest(&labels)?;
    reports.retain(|r| r.grid != finest);
    Some(format!(
        "the {finest} grid finished {phases} grid phase(s), fewer than the {} its phase \
         scatter needs, so the answer is from the coarser grids",
        generic_limit::MIN_PHASES
    ))
}

/// Of runs' grids (`labels`, coarse to fine), the finest and its count where it has fewer
/// runs than [`generic_limit::MIN_PHASES`] and a coarser grid ran too.
fn unfinished_finest(labels: &[&str]) -> Option<(String, usize)> {
    let finest = *labels.last()?;
    let phases = labels.iter().filter(|&&l| l == finest).count();
    (phases < generic_limit::MIN_PHASES && phases < labels.len())
        .then(|| (finest.to_string(), phases))
}

/// ", mesh turned by θ°" for a rotated mesh, else nothing.
pub fn angle_note(model: &Model) -> String {
    if model.mesh.is_aligned() {
        String::new()
    } else {
        format!(", mesh turned by {}°", model.mesh.degrees)
    }
}

/// A run that stopped early as the request's failure (after its outputs were written).
pub fn failure_error(failure: Option<String>) -> Result<(), RunError> {
    match failure {
        None => Ok(()),
        Some(f) => Err(failed(f)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_cut_between_its_phases_is_left_out_of_the_extrapolation() {
        // The 256² grid finished one phase before the deadline: the answer is from 64² and 128².
        let cut = ["64×64", "64×64", "128×128", "128×128", "256×256"];
        assert_eq!(unfinished_finest(&cut), Some(("256×256".to_string(), 1)));
        // Every grid at two phases or more, or a single grid: nothing is left out.
        assert_eq!(
            unfinished_finest(&["64×64", "64×64", "128×128", "128×128"]),
            None
        );
        assert_eq!(unfinished_finest(&["64×64"]), None);
        assert_eq!(unfinished_finest(&[]), None);
    }
}
