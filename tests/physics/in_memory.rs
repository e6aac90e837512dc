//! The session layer in memory: a simulation with no files returns the same answer and
//! states as one that writes them, and a watch can stop a run, which then returns the states
//! it had, marked incomplete.

use jkrbem::backend::select::BackendKind;
use jkrbem::model::ModelOptions;
use jkrbem::scene::Scene;
use jkrbem::session::open::BackendRequest;
use jkrbem::session::simulate::{simulate, Mode, SimulateRequest, Sink};
use jkrbem::session::Watch;
use jkrbem::solver::State;
use std::sync::atomic::{AtomicUsize, Ordering};

fn request(sink: Sink) -> SimulateRequest {
    SimulateRequest {
        scene: Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap(),
        options: ModelOptions {
            nx: 64,
            ..ModelOptions::default()
        },
        backend: BackendRequest {
            kind: BackendKind::Cpu,
            ..BackendRequest::default()
        },
        mode: Mode::Single,
        sink,
        fields: Default::default(),
        time_limit: None,
        request: None,
        input_files: Vec::new(),
        figures: Default::default(),
    }
}

#[test]
fn a_run_in_memory_equals_the_run_to_files_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("s.csv");
    let filed = simulate(
        &request(Sink::Files {
            out: Some(out.clone()),
            summary: None,
        }),
        &jkrbem::session::Quiet,
    )
    .unwrap();
    let kept = simulate(&request(Sink::Memory), &jkrbem::session::Quiet).unwrap();
    assert!(kept.states.is_empty(), "no file named");
    assert_eq!(filed.states, vec![out.clone()]);
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    let (a, b) = (&filed.runs[0], &kept.runs[0]);
    assert!(a.complete && b.complete && !kept.stopped);
    assert_eq!(a.states.len(), b.states.len());
    for (x, y) in a.states.iter().zip(&b.states) {
        assert_eq!((x.d_bar, x.f_bar, x.c_bar), (y.d_bar, y.f_bar, y.c_bar));
    }
    // The file holds exactly the states kept in memory.
    let rows = std::fs::read_to_string(&out).unwrap().lines().count() - 1;
    assert_eq!(rows, b.states.len());
    assert_eq!(filed.summary.f_ad_bar, kept.summary.f_ad_bar);
    assert!(kept.summary.runs[0].states_csv.is_none());
    // The sphere's adhesive force on 64²: JKR's 1/2 within the stated uncertainty.
    let s = &kept.summary;
    let (f, u) = (s.f_ad_bar.unwrap(), s.f_ad_bar_uncertainty.unwrap());
    assert!((f - 0.5).abs() <= u, "{f} ± {u}");
}

/// Stops the run after `limit` states.
struct StopAfter {
    limit: usize,
    seen: AtomicUsize,
}

impl Watch for StopAfter {
    fn state(&self, _model: &jkrbem::model::Model, _state: &State) {
        self.seen.fetch_add(1, Ordering::SeqCst);
    }
    fn keep_going(&self) -> bool {
        self.seen.load(Ordering::SeqCst) < self.limit
    }
}

#[test]
fn a_watch_stops_a_run_which_returns_its_states_marked_incomplete() {
    let watch = StopAfter {
        limit: 12,
        seen: AtomicUsize::new(0),
    };
    let done = simulate(&request(Sink::Memory), &watch).unwrap();
    assert!(done.stopped);
    let run = &done.runs[0];
    assert_eq!(run.states.len(), 12);
    assert!(!run.complete);
    let why = done.failure.expect("a stopped run says so");
    assert!(
        why.contains("stopped by its caller after 12 states"),
        "{why}"
    );
    assert!(!done.summary.runs[0].complete);
}

/// Keeps the states recorded and those held back, and stops the run at the `stop_at`-th
/// state held back (never if 0).
#[derive(Default)]
struct SeesHeld {
    recorded: std::sync::Mutex<Vec<State>>,
    held: std::sync::Mutex<Vec<State>>,
    stop_at: usize,
}

impl Watch for SeesHeld {
    fn state(&self, _model: &jkrbem::model::Model, s: &State) {
        self.recorded.lock().unwrap().push(s.clone());
    }
    fn state_held(&self, _model: &jkrbem::model::Model, s: &State) {
        self.held.lock().unwrap().push(s.clone());
    }
    fn keep_going(&self) -> bool {
        self.stop_at == 0 || self.held.lock().unwrap().len() < self.stop_at
    }
}

#[test]
fn a_watch_sees_the_states_held_for_the_search_and_can_stop_the_run_there() {
    // 5:1, adhesive force: the step ends are held while the search for the minimum may still
    // go back to them, and so are the onsets it locates on going back. A watch sees each as it
    // is found (for progress; recorded later, the same state, in the order of the load), and
    // can stop the run while it searches, when no state is recorded for a long time.
    let mut req = request(Sink::Memory);
    req.scene = Scene::from_ratio(5.0, 1.0, 1.0, 1.0).unwrap();
    req.options = ModelOptions {
        nx: 128,
        ny: Some(64),
        measure: jkrbem::model::Measure::AdhesiveForce,
        ..ModelOptions::default()
    };
    let all = SeesHeld::default();
    let done = simulate(&req, &all).unwrap();
    assert!(!done.stopped && done.runs[0].complete);
    let (held, recorded) = (all.held.lock().unwrap(), all.recorded.lock().unwrap());
    let onsets = held
        .iter()
        .filter(|s| s.phase == jkrbem::solver::Phase::Onset)
        .count();
    assert!(onsets > 0, "{} states held, none an onset", held.len());
    for s in held.iter() {
        assert!(
            recorded
                .iter()
                .any(|r| (r.step, r.phase, r.d, r.force) == (s.step, s.phase, s.d, s.force)),
            "held state of step {} at d̄ = {} not recorded",
            s.step,
            s.d_bar
        );
    }
    // Stopped at the first onset located on going back: before any of them is recorded.
    let first = held
        .iter()
        .position(|s| s.phase == jkrbem::solver::Phase::Onset)
        .unwrap();
    let stop = SeesHeld {
        stop_at: first + 1,
        ..SeesHeld::default()
    };
    let stopped = simulate(&req, &stop).unwrap();
    assert!(stopped.stopped && !stopped.runs[0].complete);
    assert!(stopped.runs[0].states.len() < recorded.len());
    assert_eq!(stop.held.lock().unwrap().len(), first + 1);
}
