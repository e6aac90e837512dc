//! `jkrbem._jkrbem`: the compiled part of the Python package. It takes a request as JSON
//! (built by the pure-Python `jkrbem` package from its keyword arguments), runs the solver's
//! session layer in memory with the GIL released, and answers in JSON, which the Python side
//! turns into numpy arrays. Errors name the Python keyword, never a CLI flag.

use jkrbem::analysis::fields::FieldChoice;
use jkrbem::backend::select::BackendKind;
use jkrbem::model::{Measure, Model, ModelOptions, Onsets};
use jkrbem::parameters::as_keywords;
use jkrbem::run::open::BackendRequest;
use jkrbem::run::simulate::{
    simulate as run_simulate, Mode, SimulateRequest, Simulated, Sink, DEFAULT_ACCURACY,
};
use jkrbem::run::{RunError, Watch};
use jkrbem::scene::{Indenter, Scene};
use jkrbem::solver::State;
use jkrbem::theory::{self, TheoryModel};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};
use serde::Deserialize;
use serde_json::{json, Value};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
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

/// A simulation's request, as the Python package sends it (its keywords, in the user's units).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    /// R1/R2 (dimensionless), where `r1` is not given.
    ratio: f64,
    /// R1 (length), or `None` for `ratio`·`r2`.
    r1: Option<f64>,
    /// R2 (length).
    r2: f64,
    /// E* (force/length²).
    e_star: f64,
    /// Δγ (force/length).
    work_of_adhesion: f64,
    /// "ellipsoid", "flat_punch" or "power_law".
    indenter: String,
    /// The flat punch's radius (length).
    radius: Option<f64>,
    /// The power law's exponent n.
    exponent: Option<f64>,
    /// The power law's height at r = 1 (length).
    scale: Option<f64>,
    /// Elements along x, for one grid.
    grid: Option<usize>,
    /// Elements along y.
    grid_y: Option<usize>,
    /// The relative accuracy aimed at (0.02 for 2 %).
    accuracy: Option<f64>,
    /// Extrapolate from several grids (`extrapolate_grids`, or those that fit).
    extrapolate: bool,
    extrapolate_grids: Option<Vec<usize>>,
    mesh_angle: f64,
    apex_offset: [f64; 2],
    margin: f64,
    start_radius: f64,
    steps: Option<usize>,
    /// "curve" or "adhesive_force".
    measure: Option<String>,
    /// "near_minimum", "all" or "none".
    onsets: Option<String>,
    /// "auto", "cpu" or "gpu".
    backend: String,
    /// Seconds an accuracy run may take.
    time_limit: Option<f64>,
    /// Which states' fields to keep: "none", "minimum", "every:K", "states:I,J".
    fields: String,
}

/// A refusal naming Python keywords.
fn input_error(message: impl std::fmt::Display) -> PyErr {
    InputError::new_err(as_keywords(&message.to_string()))
}

/// Parse the package's JSON request.
fn parse<T: for<'de> Deserialize<'de>>(json: &str) -> PyResult<T> {
    serde_json::from_str(json).map_err(|e| input_error(format!("bad request: {e}")))
}

impl Request {
    fn scene(&self) -> PyResult<Scene> {
        let (e, w) = (self.e_star, self.work_of_adhesion);
        let need = |v: Option<f64>, name: &str| {
            v.ok_or_else(|| {
                input_error(format!(
                    "{name} is needed with indenter={:?}",
                    self.indenter
                ))
            })
        };
        let scene = match self.indenter.as_str() {
            "ellipsoid" => match self.r1 {
                Some(r1) => Scene::new(r1, self.r2, e, w),
                None => Scene::from_ratio(self.ratio, self.r2, e, w),
            },
            "flat_punch" => Indenter::FlatPunch {
                radius: need(self.radius, "radius")?,
            }
            .checked()
            .and_then(|i| Scene::with_indenter(i, e, w)),
            "power_law" => Indenter::PowerLaw {
                n: need(self.exponent, "exponent")?,
                scale: self.scale.unwrap_or(1.0),
            }
            .checked()
            .and_then(|i| Scene::with_indenter(i, e, w)),
            other => {
                return Err(input_error(format!(
                "indenter = {other:?} is invalid: \"ellipsoid\", \"flat_punch\" or \"power_law\""
            )))
            }
        };
        scene.map_err(input_error)
    }

    fn options(&self) -> PyResult<ModelOptions> {
        let base = ModelOptions::default();
        let onsets = match self.onsets.as_deref() {
            None | Some("near_minimum") => Onsets::NearMinimum,
            Some("all") => Onsets::All,
            Some("none") => Onsets::None,
            Some(o) => {
                return Err(input_error(format!(
                    "onsets = {o:?} is invalid: \"near_minimum\", \"all\" or \"none\""
                )))
            }
        };
        let measure = match self.measure.as_deref() {
            None | Some("curve") => Measure::Curve,
            Some("adhesive_force") => Measure::AdhesiveForce,
            Some(m) => {
                return Err(input_error(format!(
                    "measure = {m:?} is invalid: \"curve\" or \"adhesive_force\""
                )))
            }
        };
        Ok(ModelOptions {
            nx: self.grid.unwrap_or(256),
            ny: self.grid_y,
            start_radius_bar: self.start_radius,
            // As the CLI: the steps the measure and onsets need, unless given.
            steps: self
                .steps
                .unwrap_or(jkrbem::model::default_steps(measure, onsets, base.regrid)),
            margin: self.margin,
            mesh_angle_deg: self.mesh_angle,
            apex_offset: (self.apex_offset[0], self.apex_offset[1]),
            onsets,
            measure,
            ..base
        })
    }

    fn backend(&self) -> PyResult<BackendRequest> {
        let kind = match self.backend.as_str() {
            "auto" => BackendKind::Auto,
            "cpu" => BackendKind::Cpu,
            "gpu" => BackendKind::Gpu,
            b => {
                return Err(input_error(format!(
                    "backend = {b:?} is invalid: \"auto\", \"cpu\" or \"gpu\""
                )))
            }
        };
        Ok(BackendRequest {
            kind,
            ..BackendRequest::default()
        })
    }

    fn mode(&self) -> PyResult<Mode> {
        let one_grid = self.indenter != "ellipsoid"
            || self.grid.is_some()
            || self.grid_y.is_some()
            || self.steps.is_some()
            || self.onsets.is_some()
            || self.measure.is_some();
        let extrapolate = self.extrapolate.then(|| self.extrapolate_grids.clone());
        let mode = Mode::choose(self.accuracy, extrapolate, one_grid);
        if self.time_limit.is_some() && !matches!(mode, Mode::Accuracy(_)) {
            return Err(input_error(
                "time_limit applies to a run to an accuracy (accuracy given, or neither grid nor \
                 the other one-grid keywords)",
            ));
        }
        Ok(mode)
    }

    fn simulate_request(&self) -> PyResult<SimulateRequest> {
        let time_limit = match self.time_limit {
            Some(t) if !(t.is_finite() && t > 0.0) => {
                return Err(input_error(format!(
                    "time_limit = {t} is invalid: a positive number of seconds"
                )))
            }
            t => t.map(Duration::from_secs_f64),
        };
        Ok(SimulateRequest {
            scene: self.scene()?,
            options: self.options()?,
            backend: self.backend()?,
            mode: self.mode()?,
            sink: Sink::Memory,
            fields: FieldChoice::parse(&self.fields)
                .map_err(|e| input_error(format!("fields = {e}")))?,
            time_limit,
        })
    }
}

/// What the Python side watches a run with: its progress callback (a callable taking a dict,
/// called at most every 0.2 s and at every note), and Ctrl-C (SIGINT), which stops the run.
struct PyWatch {
    progress: Option<Py<PyAny>>,
    last: Mutex<Option<Instant>>,
    interrupted: AtomicBool,
    callback_error: Mutex<Option<PyErr>>,
}

impl PyWatch {
    fn call(&self, event: Value) {
        let Some(cb) = &self.progress else { return };
        Python::attach(|py| {
            let text = event.to_string();
            let result = py
                .import("json")
                .and_then(|json| json.call_method1("loads", (text,)))
                .and_then(|dict| cb.call1(py, (dict,)));
            match result {
                // Ctrl-C inside the callback stops the run as Ctrl-C anywhere else does.
                Err(e) if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) => {
                    self.interrupted.store(true, Ordering::SeqCst)
                }
                Err(e) => {
                    self.callback_error.lock().unwrap().get_or_insert(e);
                }
                Ok(_) => {}
            }
        });
    }

    /// A "state" event, at most every 0.2 s; `held`: found but held back while the search
    /// for the force minimum may still go back to earlier steps (it is recorded later).
    fn state_event(&self, model: &Model, s: &State, held: bool) {
        let mut last = self.last.lock().unwrap();
        if last.is_some_and(|t| t.elapsed() < Duration::from_millis(200)) {
            return;
        }
        *last = Some(Instant::now());
        drop(last);
        self.call(
            json!({"event": "state", "grid": [model.nx, model.ny], "step": s.step,
                         "expected_steps": model.expected_steps(), "held": held,
                         "d_bar": s.d_bar, "f_bar": s.f_bar, "c_bar": s.c_bar}),
        );
    }
}

impl Watch for PyWatch {
    fn note(&self, line: &str) {
        self.call(json!({"event": "note", "text": as_keywords(line)}));
    }
    fn pulloff_started(&self, model: &Model) {
        self.call(json!({"event": "start", "grid": [model.nx, model.ny],
                         "expected_steps": model.expected_steps()}));
    }
    fn state(&self, model: &Model, s: &State) {
        self.state_event(model, s, false);
    }
    fn state_held(&self, model: &Model, s: &State) {
        self.state_event(model, s, true);
    }
    fn warning(&self, line: &str) {
        self.call(json!({"event": "warning", "text": as_keywords(line)}));
    }
    fn keep_going(&self) -> bool {
        if self.interrupted.load(Ordering::SeqCst) || self.callback_error.lock().unwrap().is_some()
        {
            return false;
        }
        let signalled = Python::attach(|py| py.check_signals().is_err());
        if signalled {
            self.interrupted.store(true, Ordering::SeqCst);
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

/// The answer as JSON: the summary, the plan, why it fell short, and every grid's states.
fn answer(done: &Simulated, interrupted: bool) -> Value {
    let runs: Vec<Value> = done
        .runs
        .iter()
        .map(|r| {
            json!({"grid": [r.grid.0, r.grid.1], "dx": r.dx, "complete": r.complete,
                   "states": r.states})
        })
        .collect();
    json!({
        "summary": done.summary,
        "plan": done.plan.as_deref().map(as_keywords),
        "failure": done.failure.as_deref().map(as_keywords),
        "stopped": done.stopped,
        "interrupted": interrupted,
        "runs": runs,
        "version": env!("CARGO_PKG_VERSION"),
    })
}

/// Run a simulation (the request as JSON); returns the answer as JSON and the fields (a list
/// of dicts of bytes). The GIL is released while the solver runs; `progress` (a callable, or
/// None) sees the run's events.
#[pyfunction]
#[pyo3(signature = (request, progress=None))]
fn simulate<'py>(
    py: Python<'py>,
    request: &str,
    progress: Option<Py<PyAny>>,
) -> PyResult<(String, Vec<Bound<'py, PyDict>>)> {
    let req: Request = parse(request)?;
    let sim = req.simulate_request()?;
    let watch = PyWatch {
        progress,
        last: Mutex::new(None),
        interrupted: AtomicBool::new(false),
        callback_error: Mutex::new(None),
    };
    let done = py.detach(|| run_simulate(&sim, &watch));
    if let Some(e) = watch.callback_error.lock().unwrap().take() {
        return Err(e);
    }
    let done = done.map_err(|e| match e {
        RunError::Input(m) => input_error(m),
        other => SolveError::new_err(as_keywords(&other.to_string())),
    })?;
    let fields = fields_out(py, &done)?;
    Ok((
        answer(&done, watch.interrupted.load(Ordering::SeqCst)).to_string(),
        fields,
    ))
}

/// What a run to `accuracy` would do (the grids, the domain and the uncertainty it predicts),
/// without running it; the request as JSON, the plan as JSON.
#[pyfunction]
fn plan(request: &str) -> PyResult<String> {
    let req: Request = parse(request)?;
    let scene = req.scene()?;
    let target = req.accuracy.unwrap_or(DEFAULT_ACCURACY);
    let p = jkrbem::plan::for_accuracy(&scene, target, &req.options()?).map_err(input_error)?;
    Ok(json!({
        "grids": p.grids,
        "extrapolates": p.extrapolates(),
        "margin": p.options.margin,
        "measure": if p.options.measure == Measure::AdhesiveForce { "adhesive_force" } else { "curve" },
        "n_d": p.n_d,
        "predicted_uncertainty": p.predicted_uncertainty,
        "target": p.target,
        "description": as_keywords(&p.describe(scene.ratio())),
    })
    .to_string())
}

/// The theory named `model` ("hertz", "jkr", "jg") for R1/R2 = `ratio`.
fn theory_model(model: &str) -> PyResult<TheoryModel> {
    match model {
        "hertz" => Ok(TheoryModel::Hertz),
        "jkr" => Ok(TheoryModel::Jkr),
        "jg" => Ok(TheoryModel::Jg),
        m => Err(input_error(format!(
            "model = {m:?} is invalid: \"hertz\", \"jkr\" or \"jg\""
        ))),
    }
}

/// A closed-form point as JSON.
fn point(p: &theory::TheoryPoint) -> Value {
    json!({"c_bar": p.c_bar, "f_bar": p.f_bar, "d_bar": p.d_bar, "a_bar": p.a_bar, "b_bar": p.b_bar})
}

/// `points` points of a closed-form curve, normalised (c̄, F̄, d̄, ā, b̄), as JSON.
#[pyfunction]
fn theory_curve(model: &str, ratio: f64, points: usize) -> PyResult<String> {
    let curve = theory::curve(theory_model(model)?, ratio, points).map_err(input_error)?;
    Ok(Value::from(curve.iter().map(point).collect::<Vec<_>>()).to_string())
}

/// The closed form's force minimum and end of contact, normalised, as JSON.
#[pyfunction]
fn theory_pull_off(model: &str, ratio: f64) -> PyResult<String> {
    let p = theory::pull_off(theory_model(model)?, ratio).map_err(input_error)?;
    Ok(
        json!({"force_min": point(&p.force_min), "end_of_contact": point(&p.end_of_contact)})
            .to_string(),
    )
}

/// The reference table of converged adhesive forces, as its CSV text.
#[pyfunction]
fn reference_table_csv() -> &'static str {
    jkrbem::analysis::convergence::reference_table_csv()
}

/// The GPU adapters wgpu sees, best first, as JSON.
#[pyfunction]
fn devices() -> String {
    let adapters: Vec<Value> = jkrbem::backend::gpu::list_adapters()
        .iter()
        .map(|a| {
            json!({"name": a.name, "device_type": a.device_type, "api": a.backend,
                   "largest_grid": a.largest_grid, "max_buffer_size": a.max_buffer_size})
        })
        .collect();
    Value::from(adapters).to_string()
}

/// The equivalent ellipsoid of two identical cylinders of `radius` (length), Young's modulus
/// `young` (force/length²) and Poisson's ratio `poisson` crossed at `angle` (degrees), with
/// `work_of_adhesion` (force/length): R1, R2, E* and the force scale 3π Re Δγ, as JSON.
#[pyfunction]
fn crossed_scene(
    radius: f64,
    young: f64,
    poisson: f64,
    work_of_adhesion: f64,
    angle: f64,
) -> PyResult<String> {
    let c = jkrbem::analysis::crossed::CrossedCylinders {
        radius,
        angle_deg: angle,
        young,
        poisson,
        work_of_adhesion,
    };
    c.validate().map_err(input_error)?;
    let (r1, r2) = c.radii().map_err(input_error)?;
    Ok(
        json!({"r1": r1, "r2": r2, "e_star": c.e_star().map_err(input_error)?,
              "force_scale": c.force_scale().map_err(input_error)?, "ratio": r1 / r2})
        .to_string(),
    )
}

/// The compiled module.
#[pymodule]
fn _jkrbem(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("InputError", m.py().get_type::<InputError>())?;
    m.add("SolveError", m.py().get_type::<SolveError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(theory_curve, m)?)?;
    m.add_function(wrap_pyfunction!(theory_pull_off, m)?)?;
    m.add_function(wrap_pyfunction!(reference_table_csv, m)?)?;
    m.add_function(wrap_pyfunction!(devices, m)?)?;
    m.add_function(wrap_pyfunction!(crossed_scene, m)?)?;
    Ok(())
}
