//! One pull-off of one model on an opened backend, its states kept in memory and, where a
//! file is asked for, streamed to it under this run's partial name until it completes.

use super::claim::write_error;
use super::{failed, RunError, Watch};
use crate::analysis::capture::MaskObserver;
use crate::analysis::report::RunReport;
use crate::backend::Backend;
use crate::model::Model;
use crate::output::data::{state_stream, StateStream};
use crate::params::Spec;
use crate::solver::{self, Outcome};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A finished (or stopped) pull-off: its report, its outcome and where its states are.
pub struct Pulloff {
    /// What it found, as numbers.
    pub report: RunReport,
    /// The states and how the run ended.
    pub outcome: Outcome,
    /// The states CSV: `out` if the run completed, else its partial name; `None` where no
    /// file was asked for.
    pub states: Option<PathBuf>,
    /// Whether the run was stopped at its deadline (its states are kept under the partial
    /// name).
    pub timed_out: bool,
    /// Whether the watch stopped the run ([`Watch::keep_going`]) before it ended.
    pub stopped: bool,
}

impl Pulloff {
    /// Where its states are, in words: the file, or "memory".
    pub fn states_shown(&self) -> String {
        self.states
            .as_ref()
            .map_or("memory".to_string(), |p| p.display().to_string())
    }
}

/// Where a pull-off's states go besides memory: a CSV file, with the parameter that named it.
#[derive(Debug, Clone, Copy)]
pub struct StatesFile<'a> {
    /// The file's name (the run's states are written under its partial name until it
    /// completes).
    pub path: &'a Path,
    /// The parameter that named it, for messages.
    pub param: &'static Spec,
}

/// Run `model`'s pull-off on `backend`, its states kept in [`Pulloff::outcome`] and, if
/// `file` is given, streamed to it (under this run's partial name `<stem>.incomplete-<pid>.csv`
/// until the run completes). `watch` sees every state and may stop the run
/// ([`Watch::keep_going`]); `capture`, if given, sees every state with its contact mask (masks
/// are read back from the device only then). If the states cannot be written, the run stops
/// and that is the error. At `deadline`, if given, the run stops after the state it is
/// computing (`timed_out`).
pub fn pulloff<B: Backend>(
    backend: &mut B,
    model: &Model,
    file: Option<StatesFile>,
    watch: &dyn Watch,
    mut capture: Option<&mut dyn MaskObserver>,
    deadline: Option<Instant>,
) -> Result<Pulloff, RunError> {
    let mut writer: Option<Box<dyn StateStream>> = match file {
        Some(f) => Some(state_stream(f.path, model.onsets.name()).map_err(write_error(f.param))?),
        None => None,
    };
    let mut write_error_at = None;
    watch.pulloff_started(model);
    let start = Instant::now();
    let with_contact = capture.is_some();
    let timed_out = std::cell::Cell::new(false);
    let stopped = std::cell::Cell::new(false);
    // Whether to go on after a state, handed on or held.
    let go_on = || {
        timed_out.set(deadline.is_some_and(|d| Instant::now() >= d));
        stopped.set(!watch.keep_going());
        !(timed_out.get() || stopped.get())
    };
    let outcome = solver::run_watched(
        backend,
        model,
        with_contact,
        &mut |s, mask| {
            if let (Some(c), Some(mask)) = (capture.as_deref_mut(), mask) {
                c.observe(s, mask);
            }
            watch.state(model, s);
            if let Some(Err(e)) = writer.as_mut().map(|w| w.write(s)) {
                write_error_at.get_or_insert(e);
                return false;
            }
            go_on()
        },
        &mut |s| {
            watch.state_held(model, s);
            go_on()
        },
    );
    let (timed_out, stopped) = (timed_out.get(), stopped.get());
    let wall = start.elapsed().as_secs_f64();
    watch.pulloff_ended();
    for w in &outcome.warnings {
        watch.warning(w);
    }
    let path = match (writer, file) {
        (Some(writer), Some(f)) => {
            if let Some(e) = write_error_at {
                let partial = writer.partial_path().display().to_string();
                let _ = writer.finish(false);
                return Err(failed(format!(
                    "{}; the run stopped after {} states, and what could be written is in \
                     {partial} (incomplete); nothing was written to {}",
                    e.with_param(f.param),
                    outcome.states.len(),
                    f.path.display()
                )));
            }
            Some(
                writer
                    .finish(outcome.complete())
                    .map_err(write_error(f.param))?,
            )
        }
        _ => None,
    };
    let report = RunReport::new(
        model,
        &outcome,
        (backend.name(), backend.precision()),
        wall,
        path.as_deref(),
    );
    // A run that reached its end (or its confirmed minimum) at the deadline was not cut.
    let cut = !outcome.complete();
    Ok(Pulloff {
        timed_out: timed_out && cut,
        stopped: stopped && cut && !timed_out,
        report,
        outcome,
        states: path,
    })
}
