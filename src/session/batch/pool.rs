//! Many scenes' simulations, each on its own backend, one after another or several at a time
//! in a rayon pool: the one runner of a batch, whether its scenes go to files (the CLI's
//! `jkrbem batch`) or stay in memory (Python's `jkrbem.batch`).

use crate::model::Model;
use crate::session::simulate::{simulate, SimulateRequest, Simulated};
use crate::session::{failed, RunError, Watch};
use crate::solver::State;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// One scene to run: its request, and how messages name it ("scene a1", "scenes\[3\]").
#[derive(Debug, Clone)]
pub struct SceneJob {
    /// The scene's simulation.
    pub request: SimulateRequest,
    /// Its name in messages.
    pub label: String,
}

/// A scene that ended, as [`Watch::scene_ended`] hears of it.
#[derive(Debug, Clone)]
pub struct SceneEnded<'a> {
    /// Its place among the jobs given, from 0.
    pub index: usize,
    /// Its name in messages.
    pub label: &'a str,
    /// Scenes ended so far, this one included.
    pub done: usize,
    /// Scenes of the run.
    pub total: usize,
    /// Its estimate of |min F̄| (dimensionless), if it has one.
    pub f_ad_bar: Option<f64>,
    /// Its finest grid's own |min F̄| (dimensionless, uncorrected), if that reached it: the
    /// answer of an indenter without a convergence law.
    pub grid_f_ad_bar: Option<f64>,
    /// Why it fell short or failed, if it did.
    pub failure: Option<&'a str>,
}

/// The watch of one scene: its notes and warnings named by the scene, its progress only
/// where scenes run one at a time (several progress lines at once would mix).
struct SceneWatch<'a> {
    inner: &'a dyn Watch,
    label: &'a str,
    progress: bool,
}

impl Watch for SceneWatch<'_> {
    fn note(&self, line: &str) {
        self.inner.note(&format!("{}: {line}", self.label))
    }
    fn pulloff_started(&self, model: &Model) {
        if self.progress {
            self.inner.pulloff_started(model)
        }
    }
    fn state(&self, model: &Model, state: &State) {
        if self.progress {
            self.inner.state(model, state)
        }
    }
    fn state_held(&self, model: &Model, state: &State) {
        if self.progress {
            self.inner.state_held(model, state)
        }
    }
    fn pulloff_ended(&self) {
        if self.progress {
            self.inner.pulloff_ended()
        }
    }
    fn warning(&self, line: &str) {
        self.inner.warning(&format!("{}: {line}", self.label))
    }
    fn keep_going(&self) -> bool {
        self.inner.keep_going()
    }
}

/// Run every job, `threads` at a time (1: one after another, each using every core of the
/// pool it is called in; more: a pool of that many threads, shared by the scenes' own work),
/// each on its own backend. `watch` hears each scene's notes and warnings (named by its
/// label) and its end ([`Watch::scene_ended`]); once its [`Watch::keep_going`] says no, the
/// scenes not yet started fail without running. `keep` turns each scene's outcome into what
/// is kept of it, as it ends (so that a large batch need not hold every scene's states).
/// Returns what was kept, in the order of `jobs`.
pub fn run_all<T: Send>(
    jobs: Vec<SceneJob>,
    threads: usize,
    watch: &dyn Watch,
    keep: &(dyn Fn(usize, Result<Simulated, RunError>) -> T + Sync),
) -> Vec<T> {
    let total = jobs.len();
    let done = AtomicUsize::new(0);
    let one = |(index, job): (usize, SceneJob)| {
        let outcome = if watch.keep_going() {
            let scene = SceneWatch {
                inner: watch,
                label: &job.label,
                progress: threads <= 1,
            };
            simulate(&job.request, &scene)
        } else {
            Err(failed("not started (the batch was stopped)"))
        };
        let (f_ad_bar, grid_f_ad_bar, failure) = match &outcome {
            Ok(s) => (
                s.summary.f_ad_bar,
                s.summary.runs.last().and_then(|r| r.f_ad_bar),
                s.failure.clone(),
            ),
            Err(e) => (None, None, Some(e.to_string())),
        };
        watch.scene_ended(&SceneEnded {
            index,
            label: &job.label,
            done: done.fetch_add(1, Ordering::SeqCst) + 1,
            total,
            f_ad_bar,
            grid_f_ad_bar,
            failure: failure.as_deref(),
        });
        keep(index, outcome)
    };
    if threads <= 1 {
        return jobs.into_iter().enumerate().map(one).collect();
    }
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(|| jobs.into_par_iter().enumerate().map(one).collect()),
        Err(_) => jobs.into_iter().enumerate().map(one).collect(),
    }
}
