//! One pull-off of one model on an opened backend, its states streamed to a file under this
//! run's partial name until it completes.

use super::claim::write_error;
use super::{failed, RunError, Watch};
use crate::analysis::capture::ContactCapture;
use crate::analysis::report::RunReport;
use crate::backend::Backend;
use crate::model::Model;
use crate::output::states_csv::StateWriter;
use crate::solver::{self, Outcome};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// A finished (or stopped) pull-off: its report, its outcome and where its states are.
pub struct Pulloff {
    /// What it found, as numbers.
    pub report: RunReport,
    /// The states and how the run ended.
    pub outcome: Outcome,
    /// The states CSV: `out` if the run completed, else its partial name.
    pub states: PathBuf,
    /// Whether the run was stopped at its deadline (its states are kept under the partial
    /// name).
    pub timed_out: bool,
}

/// Run `model`'s pull-off on `backend`, streaming its states to `out` (under this run's
/// partial name `<stem>.incomplete-<pid>.csv` until the run completes; `flag` names `out` in
/// messages). `watch` sees every state; `capture`, if given, sees every state with its
/// contact mask (masks are read back from the device only then). If the states cannot be
/// written, the run stops and that is the error. At
/// `deadline`, if given, the run stops after the state it is computing (`timed_out`).
pub fn pulloff_to_file<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &Path,
    flag: &str,
    watch: &dyn Watch,
    mut capture: Option<&mut ContactCapture>,
    deadline: Option<Instant>,
) -> Result<Pulloff, RunError> {
    let mut writer = StateWriter::create(out, model.onsets.name()).map_err(write_error(flag))?;
    let mut write_error_at = None;
    let mut timed_out = false;
    watch.pulloff_started(model);
    let start = Instant::now();
    let with_contact = capture.is_some();
    let outcome = solver::run_until(backend, model, with_contact, &mut |s, mask| {
        if let (Some(c), Some(mask)) = (capture.as_deref_mut(), mask) {
            c.observe(s, mask);
        }
        watch.state(model, s);
        if let Err(e) = writer.write(s) {
            write_error_at.get_or_insert(e);
            return false;
        }
        timed_out = deadline.is_some_and(|d| Instant::now() >= d);
        !timed_out
    });
    let wall = start.elapsed().as_secs_f64();
    watch.pulloff_ended();
    for w in &outcome.warnings {
        watch.warning(w);
    }
    if let Some(e) = write_error_at {
        let partial = writer.partial_path().display().to_string();
        let _ = writer.finish(false);
        return Err(failed(format!(
            "{}; the run stopped after {} states, and what could be written is in {partial} \
             (incomplete); nothing was written to {}",
            e.with_flag(flag),
            outcome.states.len(),
            out.display()
        )));
    }
    let path = writer
        .finish(outcome.complete())
        .map_err(write_error(flag))?;
    let report = RunReport::new(
        model,
        &outcome,
        (backend.name(), backend.precision()),
        wall,
        &path,
    );
    Ok(Pulloff {
        // A run that reached its end (or its confirmed minimum) at the deadline was not cut.
        timed_out: timed_out && !outcome.complete(),
        report,
        outcome,
        states: path,
    })
}
