//! `jkrbem._jkrbem`: the compiled part of the Python package. It takes a request as JSON
//! (built by the pure-Python `jkrbem` package from its keyword arguments), runs the solver's
//! session layer in memory with the GIL released, and answers in JSON, which the Python side
//! turns into numpy arrays. Errors name the Python keyword, never a CLI flag.

use jkrbem::model::{Measure, Model};
use jkrbem::params::{self, words::keywords};
use jkrbem::scene::height_map::HeightMap;
use jkrbem::session::request::Request;
use jkrbem::session::simulate::{simulate as run_simulate, Simulated, Sink, DEFAULT_ACCURACY};
use jkrbem::session::{RunError, Watch};
use jkrbem::solver::State;
use jkrbem::theory::{self, TheoryModel};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use serde::Deserialize;
use serde_json::{json, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

create_exception!(
    jkrbem,
    InputError,
    PyValueError,
    "A parameter is out of its range or the combination cannot run; the message names the keyword."
);
create_exception!(
    jkrbem,
    SolveError,
    PyRuntimeError,
    "A run failed after it started; the partial states are kept on the exception."
);

// The library's limits and defaults, as the CLI's: the longest `time_limit` (s), the most
// points of a closed-form curve and the power law's default factor s of h = s·rⁿ.
use jkrbem::scene::DEFAULT_POWER_LAW_SCALE as DEFAULT_SCALE;
use jkrbem::session::simulate::MAX_TIME_LIMIT_S;
use jkrbem::theory::MAX_CURVE_POINTS as MAX_THEORY_POINTS;

/// A run's error as Python's: an [`InputError`] for a refusal, a [`SolveError`] for a failure,
/// the message in keywords and the keyword of the parameter to change as the exception's
/// `parameter` (None where the error blames none).
fn run_error(e: &RunError) -> PyErr {
    let err = if e.is_input() {
        input_error(&e.message)
    } else {
        SolveError::new_err(keywords(&e.message))
    };
    naming(err, e.param)
}

/// A request's refusal as an [`InputError`] naming its keywords, with the keyword it
/// blames as `parameter`.
fn refused(e: &RunError) -> PyErr {
    naming(input_error(e), e.param)
}

/// A refusal naming Python keywords.
fn input_error(message: impl std::fmt::Display) -> PyErr {
    InputError::new_err(keywords(&message.to_string()))
}

/// The message a panic carried.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "(no message)".into())
}

/// Runs `f`, turning a panic into a [`SolveError`] that says it is a bug. Every input is
/// checked before it reaches the library, so this is the last line of defence only: a
/// `PanicException` derives from `BaseException`, which `except Exception` misses.
fn guarded<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|payload| {
        Err(SolveError::new_err(format!(
            "internal error in jkrbem (a bug; please report it with the call that raised it): \
             {}",
            panic_message(payload.as_ref())
        )))
    })
}

/// `m` locked, also after a panic elsewhere poisoned it (its data stays usable here).
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Parse the package's JSON request.
fn parse<T: for<'de> Deserialize<'de>>(json: &str) -> PyResult<T> {
    serde_json::from_str(json).map_err(|e| input_error(format!("bad request: {e}")))
}

/// The request of the keywords given (a JSON object: keyword → value), checked against the
/// schema; every keyword not given takes the schema's default.
fn request(json: &str) -> PyResult<Request> {
    let given: serde_json::Map<String, Value> = parse(json)?;
    let values = Request::check_json(given.iter().map(|(k, v)| (k.as_str(), v)))
        .map_err(|r| naming(refusal(&r.message, r.wrong_type), r.param))?;
    Request::from_values(values).map_err(|e| refused(&e))
}

/// `err` with the keyword of `param` as its `parameter` (None where no parameter is blamed).
fn naming(err: PyErr, param: Option<&'static params::Spec>) -> PyErr {
    Python::attach(|py| {
        // Setting an attribute on a fresh exception instance cannot fail short of memory.
        let _ = err.value(py).setattr("parameter", param.map(|p| p.name));
    });
    err
}

/// A refused value in Python's words: a TypeError where it was of the wrong type (or no
/// keyword), else an [`InputError`].
fn refusal(message: &str, wrong_type: bool) -> PyErr {
    if wrong_type {
        pyo3::exceptions::PyTypeError::new_err(keywords(message))
    } else {
        input_error(message)
    }
}

/// A height map given as an array: its heights (native-endian f64, rows along y) and shape.
type Heights<'py> = (Bound<'py, PyBytes>, usize, usize);

/// The map of an array given as `height_map` (or as the `roughness` of a base shape), with
/// the request's `spacing`.
fn array_map(req: &Request, heights: Option<Heights<'_>>) -> PyResult<Option<HeightMap>> {
    let Some((bytes, ny, nx)) = heights else {
        return Ok(None);
    };
    let Some(spacing) = req.spacing else {
        return Err(input_error(
            "a height_map or roughness array needs spacing (the nodes' spacing, length)",
        ));
    };
    let values: Vec<f64> = bytes
        .as_bytes()
        .chunks_exact(8)
        .map(|c| f64::from_ne_bytes(c.try_into().unwrap_or([0; 8])))
        .collect();
    HeightMap::new(nx, ny, spacing, values)
        .map(Some)
        .map_err(|e| {
            let name = if req.indenter == jkrbem::session::request::Shape::HeightMap {
                "height_map"
            } else {
                "roughness"
            };
            input_error(format!("{name}: {e}"))
        })
}

/// Shortest wall time between two "state" events a progress callback sees.
const STATE_EVERY: Duration = Duration::from_millis(200);

/// Largest share of a run's wall time its progress callback may take: after a callback that
/// took t, "state" events wait at least t·(1 − share)/share before the next one.
const CALLBACK_SHARE: f64 = 0.1;

/// A "state" event, kept until it can be delivered.
#[derive(Debug, Clone, Copy)]
struct StateEvent {
    grid: (usize, usize),
    step: usize,
    expected_steps: usize,
    held: bool,
    d_bar: f64,
    f_bar: f64,
    c_bar: f64,
}

impl StateEvent {
    fn json(&self) -> Value {
        json!({"event": "state", "grid": [self.grid.0, self.grid.1], "step": self.step,
               "expected_steps": self.expected_steps, "held": self.held,
               "d_bar": self.d_bar, "f_bar": self.f_bar, "c_bar": self.c_bar})
    }
}

/// When the next "state" event may reach the callback, and the latest one held back.
#[derive(Debug, Default)]
struct Throttle {
    next: Option<Instant>,
    pending: Option<StateEvent>,
    grid: (usize, usize),
}

/// A progress callback (a callable taking a dict, or none) and what stopped it: Ctrl-C
/// (inside the callback or, for a run, anywhere) or an exception the callback raised, kept to
/// be raised once the run returns.
struct Callback {
    progress: Option<Py<PyAny>>,
    interrupted: AtomicBool,
    error: Mutex<Option<PyErr>>,
}

impl Callback {
    fn new(progress: Option<Py<PyAny>>) -> Self {
        Callback {
            progress,
            interrupted: AtomicBool::new(false),
            error: Mutex::new(None),
        }
    }

    /// Whether the work is being stopped (Ctrl-C, or the callback raised).
    fn stopping(&self) -> bool {
        self.interrupted.load(Ordering::SeqCst) || lock(&self.error).is_some()
    }

    /// Whether Ctrl-C stopped it.
    fn interrupted(&self) -> bool {
        self.interrupted.load(Ordering::SeqCst)
    }

    /// The exception the callback raised, if it did.
    fn take_error(&self) -> Option<PyErr> {
        lock(&self.error).take()
    }

    /// Hands `event` to the callback as a dict, unless the work is stopping. Ctrl-C inside
    /// the callback stops the work as Ctrl-C anywhere else does; another exception is kept.
    fn deliver(&self, event: &Value) {
        let Some(cb) = &self.progress else { return };
        if self.stopping() {
            return;
        }
        Python::attach(|py| {
            let result = py
                .import("json")
                .and_then(|json| json.call_method1("loads", (event.to_string(),)))
                .and_then(|dict| cb.call1(py, (dict,)));
            match result {
                Err(e) if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) => {
                    self.interrupted.store(true, Ordering::SeqCst)
                }
                Err(e) => {
                    lock(&self.error).get_or_insert(e);
                }
                Ok(_) => {}
            }
        });
    }
}

/// What the Python side watches a run with: its progress callback (a callable taking a dict)
/// and Ctrl-C (SIGINT), which stops the run. The callback sees every "note", "start",
/// "warning" and "end", and of the "state" events the latest one at most every
/// [`STATE_EVERY`], less often where the callback itself is slow (it may take at most
/// [`CALLBACK_SHARE`] of the run), and the last state of each grid before its "end".
struct PyWatch {
    callback: Callback,
    throttle: Mutex<Throttle>,
}

impl PyWatch {
    fn new(progress: Option<Py<PyAny>>) -> Self {
        PyWatch {
            callback: Callback::new(progress),
            throttle: Mutex::new(Throttle::default()),
        }
    }

    /// Hands `event` to the callback (unless the run is stopping), and sets when the next
    /// state event may follow: after `floor` at least, later where the callback was slow.
    fn call(&self, event: Value, floor: Duration) {
        if self.callback.progress.is_none() || self.callback.stopping() {
            return;
        }
        let started = Instant::now();
        self.callback.deliver(&event);
        let took = started.elapsed();
        let rest = took.mul_f64((1.0 - CALLBACK_SHARE) / CALLBACK_SHARE);
        lock(&self.throttle).next = Some(Instant::now() + rest.max(floor));
    }

    /// A "state" event: delivered if its time has come, else kept as the latest.
    /// `held`: found but held back while the search for the force minimum may still go back
    /// to earlier steps (it is recorded later).
    fn state_event(&self, model: &Model, s: &State, held: bool) {
        if self.callback.progress.is_none() {
            return;
        }
        let event = StateEvent {
            grid: (model.nx, model.ny),
            step: s.step,
            expected_steps: model.expected_steps(),
            held,
            d_bar: s.d_bar,
            f_bar: s.f_bar,
            c_bar: s.c_bar,
        };
        let mut t = lock(&self.throttle);
        if t.next.is_some_and(|next| Instant::now() < next) {
            t.pending = Some(event);
            return;
        }
        t.pending = None;
        drop(t);
        self.call(event.json(), STATE_EVERY);
    }

    /// An event other than a state: always delivered; it holds the next state back only as
    /// long as the callback's share needs.
    fn event(&self, event: Value) {
        self.call(event, Duration::ZERO);
    }
}

impl Watch for PyWatch {
    fn note(&self, line: &str) {
        self.event(json!({"event": "note", "text": keywords(line)}));
    }
    fn pulloff_started(&self, model: &Model) {
        {
            let mut t = lock(&self.throttle);
            t.grid = (model.nx, model.ny);
            t.pending = None;
        }
        self.event(json!({"event": "start", "grid": [model.nx, model.ny],
                         "expected_steps": model.expected_steps()}));
    }
    fn state(&self, model: &Model, s: &State) {
        self.state_event(model, s, false);
    }
    fn state_held(&self, model: &Model, s: &State) {
        self.state_event(model, s, true);
    }
    fn pulloff_ended(&self) {
        let (pending, grid) = {
            let mut t = lock(&self.throttle);
            (t.pending.take(), t.grid)
        };
        if let Some(last) = pending {
            self.event(last.json());
        }
        self.event(json!({"event": "end", "grid": [grid.0, grid.1]}));
    }
    fn warning(&self, line: &str) {
        self.event(json!({"event": "warning", "text": keywords(line)}));
    }
    fn keep_going(&self) -> bool {
        if self.callback.stopping() {
            return false;
        }
        let signalled = Python::attach(|py| py.check_signals().is_err());
        if signalled {
            self.callback.interrupted.store(true, Ordering::SeqCst);
        }
        !signalled
    }
}

/// The fields of every run as Python dicts: the arrays as raw bytes (native-endian f64,
/// contact as u8; numpy reads them with `frombuffer`), the rest as JSON text.
fn fields_out<'py>(py: Python<'py>, done: &Simulated) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let mut all = Vec::new();
    for (run, r) in done.runs.iter().enumerate() {
        for f in &r.fields {
            let d = PyDict::new(py);
            let meta = json!({"run": run, "index": f.index, "label": f.label, "state": f.state,
                              "nx": f.nx, "ny": f.ny, "dx": f.dx, "sigma_c": f.sigma_c});
            d.set_item("meta", meta.to_string())?;
            let bytes = |v: &[f64]| -> Vec<u8> { v.iter().flat_map(|x| x.to_ne_bytes()).collect() };
            d.set_item("pressure", PyBytes::new(py, &bytes(&f.pressure)))?;
            d.set_item("gap", PyBytes::new(py, &bytes(&f.gap)))?;
            d.set_item("x", PyBytes::new(py, &bytes(&f.x)))?;
            d.set_item("y", PyBytes::new(py, &bytes(&f.y)))?;
            let contact: Vec<u8> = f.contact.iter().map(|c| *c as u8).collect();
            d.set_item("contact", PyBytes::new(py, &contact))?;
            all.push(d);
        }
    }
    Ok(all)
}

/// `v` with every parameter its strings name worded as a Python keyword.
fn worded(v: Value) -> Value {
    match v {
        Value::String(s) => Value::String(keywords(&s)),
        Value::Array(a) => Value::Array(a.into_iter().map(worded).collect()),
        Value::Object(o) => Value::Object(o.into_iter().map(|(k, v)| (k, worded(v))).collect()),
        other => other,
    }
}

/// The answer as JSON: the summary, the plan, why it fell short, every grid's states, and the
/// request as the schema completed it; every parameter named in Python's words.
fn answer(done: &Simulated, req: &Request, interrupted: bool) -> Value {
    let runs: Vec<Value> = done
        .runs
        .iter()
        .map(|r| {
            json!({"grid": [r.grid.0, r.grid.1], "dx": r.dx, "complete": r.complete,
                   "states": r.states})
        })
        .collect();
    // The states name no parameter: only the rest is worded.
    let mut answer = worded(json!({
        "summary": done.summary,
        "plan": done.plan,
        "failure": done.failure,
        "warnings": done.summary.warnings,
        "stopped": done.stopped,
        "interrupted": interrupted,
        "request": req.to_json(),
        "version": env!("CARGO_PKG_VERSION"),
    }));
    answer["runs"] = Value::from(runs);
    answer
}

/// A rayon pool of this process: a process forked from one that ran jkrbem gets a pool of its
/// own (the parent's worker threads do not survive `fork`, and its global pool would wait on
/// them forever).
fn process_pool() -> PyResult<std::sync::Arc<rayon::ThreadPool>> {
    static POOL: Mutex<Option<(u32, std::sync::Arc<rayon::ThreadPool>)>> = Mutex::new(None);
    let pid = std::process::id();
    let mut pool = lock(&POOL);
    if let Some((owner, p)) = pool.as_ref() {
        if *owner == pid {
            return Ok(p.clone());
        }
    }
    let fresh = rayon::ThreadPoolBuilder::new()
        .build()
        .map(std::sync::Arc::new)
        .map_err(|e| SolveError::new_err(format!("cannot start jkrbem's threads: {e}")))?;
    *pool = Some((pid, fresh.clone()));
    Ok(fresh)
}

/// Run `work` on a thread of its own while the calling thread waits with the GIL released,
/// taking the GIL back every few milliseconds (at most 50) to run Python's signal handlers:
/// a Ctrl-C (SIGINT, or any handler that raises) marks `callback` interrupted, which the run's
/// watch sees at its next state and stops at, keeping what it computed. Python runs its
/// signal handlers only on its main thread, so a check made from the solver's threads alone
/// never sees a Ctrl-C: the run went on to its end and the interrupt then discarded it.
fn interruptible<T: Send>(
    py: Python<'_>,
    callback: &Callback,
    work: impl FnOnce() -> T + Send,
) -> T {
    std::thread::scope(|scope| {
        let handle = scope.spawn(work);
        let mut wait = Duration::from_millis(1);
        loop {
            if handle.is_finished() {
                return handle
                    .join()
                    .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            }
            if py.check_signals().is_err() {
                callback.interrupted.store(true, Ordering::SeqCst);
            }
            py.detach(|| std::thread::sleep(wait));
            wait = (wait * 2).min(Duration::from_millis(50));
        }
    })
}

/// Run a simulation: `request` is a JSON object of the keywords given (every other keyword
/// takes the schema's default), `height_map` an array's heights (native-endian f64 bytes, ny,
/// nx) where one is given in memory. Returns the answer as JSON and the fields (a list of
/// dicts of bytes). The GIL is released while the solver runs; `progress` (a callable, or
/// None) sees the run's events.
#[pyfunction]
#[pyo3(signature = (request, progress=None, height_map=None))]
fn simulate<'py>(
    py: Python<'py>,
    request: &str,
    progress: Option<Py<PyAny>>,
    height_map: Option<Heights<'py>>,
) -> PyResult<(String, Vec<Bound<'py, PyDict>>)> {
    guarded(|| {
        let req = self::request(request)?;
        let map = array_map(&req, height_map)?;
        let sim = req
            .simulate_request(Sink::Memory, map)
            .map_err(|e| refused(&e))?;
        let watch = PyWatch::new(progress);
        let pool = process_pool()?;
        let done = interruptible(py, &watch.callback, || {
            pool.install(|| run_simulate(&sim, &watch))
        });
        if let Some(e) = watch.callback.take_error() {
            return Err(e);
        }
        let done = done.map_err(|e| run_error(&e))?;
        let fields = fields_out(py, &done)?;
        Ok((
            answer(&done, &req, watch.callback.interrupted()).to_string(),
            fields,
        ))
    })
}

/// What a run to `accuracy` would do (the grids, the domain and the uncertainty it predicts),
/// without running it; the request as JSON (as for [`simulate`]), the plan as JSON.
#[pyfunction]
#[pyo3(signature = (request, height_map=None))]
fn plan(request: &str, height_map: Option<Heights<'_>>) -> PyResult<String> {
    guarded(|| {
        let req = self::request(request)?;
        let scene = req
            .scene(array_map(&req, height_map)?)
            .map_err(|e| refused(&e))?;
        let target = req.accuracy.unwrap_or(DEFAULT_ACCURACY);
        let p = jkrbem::plan::for_accuracy(&scene, target, &req.options())
            .map_err(|e| input_error(e.to_string()))?;
        let measure = match p.options.measure {
            Measure::AdhesiveForce => "adhesive_force",
            Measure::Curve => "curve",
        };
        Ok(json!({
            "grids": p.grids,
            "extrapolates": p.extrapolates(),
            "margin": p.options.margin,
            "measure": measure,
            "n_d": p.n_d,
            "predicted_uncertainty": p.predicted_uncertainty,
            "target": p.target,
            "description": keywords(&p.describe(scene.ratio())),
        })
        .to_string())
    })
}

/// The request schema: every keyword of a simulation with its unit, kind and range, default
/// and help (in Python's words), as JSON.
#[pyfunction]
#[pyo3(name = "schema")]
fn schema_json() -> String {
    let specs: Vec<Value> = params::SPECS
        .iter()
        .filter(|s| s.fronts == params::Fronts::Both)
        .map(|s| {
            let default = match s.fallback {
                params::Fallback::Value(text) => params::values::from_text(s, text).ok(),
                params::Fallback::Chosen(_) => None,
            };
            json!({"name": s.name, "unit": s.unit, "kind": format!("{:?}", s.kind),
                   "default": default, "terms": keywords(&s.terms()),
                   "cli_terms": params::words::flags(&s.terms()),
                   "help": keywords(s.help), "cli_flag": s.flag})
        })
        .collect();
    Value::from(specs).to_string()
}

/// The theory named `model` ("hertz", "jkr", "jg").
fn theory_model(model: &str) -> PyResult<TheoryModel> {
    match model {
        "hertz" => Ok(TheoryModel::Hertz),
        "jkr" => Ok(TheoryModel::Jkr),
        "jg" => Ok(TheoryModel::Jg),
        m => Err(input_error(format!(
            "model = {} is invalid: \"hertz\", \"jkr\" or \"jg\"",
            params::values::shown(m)
        ))),
    }
}

/// A closed-form point as JSON.
fn point(p: &theory::TheoryPoint) -> Value {
    json!({"c_bar": p.c_bar, "f_bar": p.f_bar, "d_bar": p.d_bar, "a_bar": p.a_bar, "b_bar": p.b_bar})
}

/// `points` points (2 to [`MAX_THEORY_POINTS`]) of a closed-form curve for R1/R2 = `ratio`,
/// normalised (c̄, F̄, d̄, ā, b̄), as JSON.
#[pyfunction]
fn theory_curve(model: &str, ratio: f64, points: usize) -> PyResult<String> {
    guarded(|| {
        // The closed forms check R1/R2 and the count of points, naming them.
        let model = theory_model(model)?;
        let curve = theory::curve(model, ratio, points).map_err(input_error)?;
        Ok(Value::from(curve.iter().map(point).collect::<Vec<_>>()).to_string())
    })
}

/// The closed form's force minimum and end of contact for R1/R2 = `ratio`, normalised, as
/// JSON.
#[pyfunction]
fn theory_pull_off(model: &str, ratio: f64) -> PyResult<String> {
    guarded(|| {
        let model = theory_model(model)?;
        if model == TheoryModel::Hertz {
            return Err(input_error(
                "model = \"hertz\" has no pull-off (Hertz's contact has no adhesion): use \
                 \"jkr\" or \"jg\"",
            ));
        }
        let p = theory::pull_off(model, ratio).map_err(input_error)?;
        Ok(
            json!({"force_min": point(&p.force_min), "end_of_contact": point(&p.end_of_contact)})
                .to_string(),
        )
    })
}

/// The reference table of converged adhesive forces, as its CSV text.
#[pyfunction]
fn reference_table_csv() -> PyResult<&'static str> {
    guarded(|| Ok(jkrbem::analysis::convergence::reference_table_csv()))
}

/// The GPU adapters wgpu sees, best first, as JSON.
#[pyfunction]
fn devices(py: Python<'_>) -> PyResult<String> {
    guarded(|| {
        let adapters = py.detach(jkrbem::backend::gpu::list_adapters);
        let adapters: Vec<Value> = adapters
            .iter()
            .map(|a| {
                json!({"name": a.name, "device_type": a.device_type, "api": a.backend,
                       "largest_grid": a.largest_grid, "max_buffer_size": a.max_buffer_size})
            })
            .collect();
        Ok(Value::from(adapters).to_string())
    })
}

/// The equivalent ellipsoid of two identical cylinders of `radius` (length), Young's modulus
/// `young` (force/length²) and Poisson's ratio `poisson` crossed at `angle` (degrees), with
/// `work_of_adhesion` (force/length): R1, R2, E* and the force scale 3π Re Δγ, as JSON.
/// Errors name `angles`, the Python keyword that gives the angle.
#[pyfunction]
fn crossed_scene(
    radius: f64,
    young: f64,
    poisson: f64,
    work_of_adhesion: f64,
    angle: f64,
) -> PyResult<String> {
    guarded(|| {
        let c = jkrbem::analysis::crossed::CrossedCylinders {
            radius,
            angle_deg: angle,
            young,
            poisson,
            work_of_adhesion,
        };
        let refused = |e: jkrbem::scene::SceneError| {
            input_error(e.renamed(&|p| {
                if p == params::ANGLE {
                    params::ANGLES
                } else {
                    p
                }
            }))
        };
        c.validate().map_err(refused)?;
        let (r1, r2) = c.radii().map_err(refused)?;
        Ok(
            json!({"r1": r1, "r2": r2, "e_star": c.e_star().map_err(refused)?,
                  "force_scale": c.force_scale().map_err(refused)?, "ratio": r1 / r2})
            .to_string(),
        )
    })
}

/// The library's ranges the Python package checks its keywords against, as JSON: grid
/// sides, load steps, R1/R2, closed-form points, `time_limit` (s), the inputs' range.
#[pyfunction]
fn limits() -> String {
    json!({
        "min_grid": jkrbem::model::MIN_GRID,
        "max_grid": jkrbem::model::MAX_GRID,
        "max_steps": jkrbem::model::MAX_STEPS,
        "max_ratio": jkrbem::scene::MAX_RATIO,
        "max_theory_points": MAX_THEORY_POINTS,
        "max_time_limit_s": MAX_TIME_LIMIT_S,
        "default_scale": DEFAULT_SCALE,
    })
    .to_string()
}

/// A random self-affine surface from its parameters (JSON: the keywords of
/// `jkrbem.roughness`, checked by the library, which names them): the generator's version,
/// the parameters with their defaults filled in and the achieved statistics as JSON, and the
/// heights as native-endian f64 bytes, row-major (ny, nx). The GIL is released meanwhile.
#[pyfunction]
fn roughness<'py>(py: Python<'py>, request: &str) -> PyResult<(String, Bound<'py, PyBytes>)> {
    use jkrbem::scene::roughness::{generate, statistics, RoughnessParams, GENERATOR_VERSION};
    guarded(|| {
        let params: RoughnessParams = parse(request)?;
        let resolved = params.resolved().map_err(input_error)?;
        // Before any work: the surface must fit in the memory (JKRBEM_MEMORY_LIMIT honoured).
        jkrbem::plan::check_roughness_memory(&params).map_err(input_error)?;
        let map = py.detach(|| generate(&params)).map_err(input_error)?;
        let bytes: Vec<u8> = map.heights().iter().flat_map(|h| h.to_ne_bytes()).collect();
        let answer = json!({"generator": GENERATOR_VERSION, "params": resolved,
                            "statistics": statistics(&map)});
        Ok((answer.to_string(), PyBytes::new(py, &bytes)))
    })
}

/// Panics on purpose, inside [`guarded`]: lets the tests check that a panic (a bug) reaches
/// Python as a [`SolveError`], never as a `PanicException`.
#[pyfunction]
fn _panic_for_tests() -> PyResult<()> {
    guarded(|| panic!("a deliberate panic (jkrbem's own test of its last line of defence)"))
}

/// What Python's [`batch`] watches its scenes with: the progress callback (a callable taking a
/// dict, or None) sees each scene's notes and warnings (named `scenes[i]`) and its end; once
/// the callback raises (Ctrl-C in it included), the scenes not yet started do not run.
struct BatchWatch(Callback);

impl BatchWatch {
    /// Hands `event` to the callback ([`Callback::deliver`]).
    fn event(&self, event: Value) {
        self.0.deliver(&event);
    }
}

impl Watch for BatchWatch {
    fn note(&self, line: &str) {
        self.event(json!({"event": "note", "text": keywords(line)}));
    }
    fn warning(&self, line: &str) {
        self.event(json!({"event": "warning", "text": keywords(line)}));
    }
    fn scene_ended(&self, s: &jkrbem::session::batch::pool::SceneEnded) {
        self.event(
            json!({"event": "scene", "index": s.index, "done": s.done, "total": s.total,
                          "adhesive_force": s.f_ad_bar, "grid_adhesive_force": s.grid_f_ad_bar,
                          "failure": s.failure.map(keywords)}),
        );
    }
    fn keep_going(&self) -> bool {
        !self.0.stopping()
    }
}

/// One scene's outcome for Python: its answer as JSON and its fields, or none and why
/// ("input" or "failed", and the message in Python's words).
type SceneAnswer<'py> = (
    Option<String>,
    Vec<Bound<'py, PyDict>>,
    Option<(String, String)>,
);

/// Run a batch of simulations: `requests` is a JSON list of requests, each as for
/// [`simulate`] (no height map array); every one is checked before any runs, a refusal naming
/// the scene (`scenes[i]`) and the keyword. `processes` scenes run at a time, each on its own
/// backend, in the process's rayon pool (1) or a pool of that many threads, with the GIL
/// released; `progress` (a callable, or None) sees the scenes' notes, warnings and ends.
/// Returns, per scene in order, its answer and fields, or why it has none.
#[pyfunction]
#[pyo3(signature = (requests, processes=1, progress=None))]
fn batch<'py>(
    py: Python<'py>,
    requests: &str,
    processes: usize,
    progress: Option<Py<PyAny>>,
) -> PyResult<Vec<SceneAnswer<'py>>> {
    use jkrbem::session::batch::pool::{run_all, SceneJob};
    guarded(|| {
        let given: Vec<serde_json::Map<String, Value>> = parse(requests)?;
        let mut requests = Vec::with_capacity(given.len());
        let mut jobs = Vec::with_capacity(given.len());
        // Each file the scenes name is read once, its map shared by the scenes naming it.
        let mut reads = jkrbem::session::request::MapReads::default();
        for (i, g) in given.iter().enumerate() {
            let at = |e: RunError| naming(input_error(format!("scenes[{i}]: {e}")), e.param);
            let values = Request::check_json(g.iter().map(|(k, v)| (k.as_str(), v)))
                .map_err(|r| refusal(&format!("scenes[{i}]: {}", r.message), r.wrong_type))?;
            let req = Request::from_values(values).map_err(at)?;
            let sim = req
                .simulate_request_sharing(Sink::Memory, None, &mut reads)
                .map_err(at)?;
            jkrbem::session::simulate::planned_outputs(&sim).map_err(at)?;
            jobs.push(SceneJob {
                request: sim,
                label: format!("scenes[{i}]"),
            });
            requests.push(req);
        }
        let watch = BatchWatch(Callback::new(progress));
        let pool = process_pool()?;
        let threads = processes.max(1);
        let done = interruptible(py, &watch.0, || {
            pool.install(|| run_all(jobs, threads, &watch, &|_, o| o))
        });
        if let Some(e) = watch.0.take_error() {
            return Err(e);
        }
        let interrupted = watch.0.interrupted();
        done.into_iter()
            .zip(&requests)
            .map(|(outcome, req)| match outcome {
                Ok(d) => Ok((
                    Some(answer(&d, req, interrupted).to_string()),
                    fields_out(py, &d)?,
                    None,
                )),
                Err(e) => {
                    let kind = if e.is_input() { "input" } else { "failed" };
                    Ok((
                        None,
                        Vec::new(),
                        Some((kind.into(), keywords(&e.to_string()))),
                    ))
                }
            })
            .collect()
    })
}

/// The compiled module.
#[pymodule]
fn _jkrbem(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // On import, before jkrbem starts a thread or opens a GPU: quiet the display probe of a
    // machine without a display (it sets an environment variable).
    jkrbem::backend::gpu::headless::quiet_display_probe();
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("SolveError", m.py().get_type::<SolveError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(schema_json, m)?)?;
    m.add_function(wrap_pyfunction!(theory_curve, m)?)?;
    m.add_function(wrap_pyfunction!(theory_pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(reference_table_csv, m)?)?;
    m.add_function(wrap_pyfunction!(devices, m)?)?;
    m.add_function(wrap_pyfunction!(crossed_scene, m)?)?;
    m.add_function(wrap_pyfunction!(limits, m)?)?;
    m.add_function(wrap_pyfunction!(roughness, m)?)?;
    m.add_function(wrap_pyfunction!(_panic_for_tests, m)?)?;
    Ok(())
}
