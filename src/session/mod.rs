//! The session: what a user asks for as one typed request, checked, planned and run on a
//! backend (one pull-off, an adhesive force to an accuracy, a batch of any scenes), its
//! outputs claimed and written through `output`. Each front end (the `jkrbem` command line,
//! Python, a test) only builds a request, calls one function here and shows what comes back;
//! the studies build on it, never the reverse.
//!
//! Errors say whether the request was refused before any work ([`ErrorKind::Input`]) or the
//! work failed ([`ErrorKind::Failed`]), and name the parameter or value to change: a parameter
//! by its [`crate::params::Spec`]'s marker, which each front end words (the command line as
//! its flag, Python as its keyword; [`crate::params::words`]).

pub mod batch;
pub mod claim;
pub mod fields;
pub mod open;
pub mod provenance;
pub mod pulloff;
pub mod pulloffs;
pub mod request;
pub mod simulate;

use crate::model::Model;
use crate::params::Spec;
use crate::solver::State;
use std::fmt;

/// Why a request did not produce its results: whether it was refused before any work
/// ([`ErrorKind::Input`]) or the work failed ([`ErrorKind::Failed`]), the parameter to change
/// where one is to blame (a front end shows it in its own words: Python as the exception's
/// `parameter`), and the message.
#[derive(Debug, Clone, PartialEq)]
pub struct RunError {
    /// Refused before any work, or failed in it.
    pub kind: ErrorKind,
    /// The parameter to change, where the error names one as its cause.
    pub param: Option<&'static Spec>,
    /// What is wrong, with every parameter written as its marker.
    pub message: String,
}

/// Whether a request was refused or its work failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The request was refused before any work (bad input, an output that cannot be written).
    Input,
    /// The work started and failed.
    Failed,
}

impl RunError {
    /// Whether the request was refused before any work.
    pub fn is_input(&self) -> bool {
        self.kind == ErrorKind::Input
    }

    /// The same error blaming `param` (where it is `Some`), its message and kind kept.
    pub fn blaming(self, param: Option<&'static Spec>) -> Self {
        RunError {
            param: param.or(self.param),
            ..self
        }
    }

    /// The same error, its message passed through `f` (the parameter and the kind kept).
    pub fn map_message(self, f: impl FnOnce(String) -> String) -> Self {
        RunError {
            message: f(self.message),
            ..self
        }
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for RunError {}

/// What an error of any layer says of its cause: its message, and the parameter it names as
/// the one to change, where its type carries one (the model's, the scene's and the height
/// map's errors do; free text does not).
pub trait Reason: fmt::Display {
    /// The parameter the error blames, if its type records one.
    fn param(&self) -> Option<&'static Spec> {
        None
    }
}

impl Reason for String {}
impl Reason for &str {}
impl Reason for crate::backend::BackendError {}
impl Reason for crate::solver::SolverError {}
impl Reason for crate::output::OutputError {}
impl Reason for crate::scene::height_map::HeightMapError {}
impl Reason for crate::params::values::Refusal {
    fn param(&self) -> Option<&'static Spec> {
        self.param
    }
}
impl Reason for serde_json::Error {}
impl Reason for std::io::Error {}
impl Reason for crate::output::sweep_csv::CollectError {}

impl Reason for crate::scene::SceneError {
    fn param(&self) -> Option<&'static Spec> {
        Some(crate::scene::SceneError::param(self))
    }
}

impl Reason for crate::model::ModelError {
    fn param(&self) -> Option<&'static Spec> {
        use crate::model::ModelError as E;
        match self {
            E::Grid { param, .. } | E::Invalid { param, .. } => Some(param),
            E::TooCoarse { .. } => Some(crate::params::GRID),
            E::MapTooCoarse { .. } | E::WindowMapTooCoarse { .. } => {
                Some(crate::params::HEIGHT_MAP)
            }
            E::Environment { .. } | E::Scale { .. } => None,
        }
    }
}

/// A refusal, from any layer's error, naming its parameter where the error's type records one.
pub fn input(e: impl Reason) -> RunError {
    RunError {
        kind: ErrorKind::Input,
        param: e.param(),
        message: e.to_string(),
    }
}

/// A refusal that blames `param`, the parameter to change, whose marker its `message` names:
/// Python's exception carries it as `parameter`, as it does a typed error's.
pub fn refuse(param: &'static Spec, message: impl fmt::Display) -> RunError {
    RunError {
        kind: ErrorKind::Input,
        param: Some(param),
        message: message.to_string(),
    }
}

/// A failure, from any layer's error, naming its parameter where the error's type records one.
pub fn failed(e: impl Reason) -> RunError {
    RunError {
        kind: ErrorKind::Failed,
        param: e.param(),
        message: e.to_string(),
    }
}

/// What watches a run as it goes (a progress line for a person; nothing for a script or a
/// test): the one way every command reports its progress. Shared by the pull-offs a batch runs
/// at the same time, so it takes `&self` and is `Sync`. Every method does nothing by default.
pub trait Watch: Sync {
    /// A line about what starts now (the backend opened, the grid).
    fn note(&self, _line: &str) {}
    /// A pull-off of `model` begins.
    fn pulloff_started(&self, _model: &Model) {}
    /// The pull-off of `model` recorded `state`.
    fn state(&self, _model: &Model, _state: &State) {}
    /// The pull-off of `model` found `state` but holds it back while its search for the force
    /// minimum may still go back to earlier steps: for progress only (it reaches
    /// [`Watch::state`] later, in the order of the load). [`Watch::keep_going`] is asked after
    /// it too.
    fn state_held(&self, _model: &Model, _state: &State) {}
    /// The pull-off ended.
    fn pulloff_ended(&self) {}
    /// A warning about a result.
    fn warning(&self, _line: &str) {}
    /// A scene of a batch ended ([`batch::pool`]), with its answer or why it has none.
    fn scene_ended(&self, _scene: &batch::pool::SceneEnded) {}
    /// Asked after every state, held ones included: `false` stops the pull-off there (what an
    /// interrupt from a notebook needs); the run then returns the states it had handed on,
    /// marked incomplete.
    fn keep_going(&self) -> bool {
        true
    }
}

/// A [`Watch`] that shows nothing.
#[derive(Debug, Default, Clone, Copy)]
pub struct Quiet;

impl Watch for Quiet {}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ModelError;
    use crate::params::{GRID, HEIGHT_MAP};

    #[test]
    fn a_run_error_carries_the_parameter_its_cause_names() {
        let e = input(ModelError::Invalid {
            param: GRID,
            value: "20".into(),
            expected: "a power of two".into(),
        });
        assert!(e.is_input());
        assert_eq!(e.param.map(|p| p.name), Some("grid"));
        assert!(e.message.starts_with(&GRID.to_string()), "{}", e.message);
        let e = failed(ModelError::WindowMapTooCoarse {
            map: "map.txt".into(),
            across: 8.0,
            width: 0.016,
            needed_spacing: 0.001,
        });
        assert!(!e.is_input());
        assert_eq!(e.param.map(|p| p.name), Some(HEIGHT_MAP.name));
        // Free text blames nothing, and a message passed on keeps the parameter.
        assert_eq!(input("no such thing").param, None);
        let e = input(ModelError::Invalid {
            param: GRID,
            value: "20".into(),
            expected: "x".into(),
        })
        .map_message(|m| format!("r1: {m}"));
        assert_eq!(e.param.map(|p| p.name), Some("grid"));
        assert!(e.message.starts_with("r1: "));
    }

    /// A refusal the session words itself blames the parameter it names first: the request's
    /// own checks (a shape's parameter given with another shape, two that exclude each other).
    #[test]
    fn the_sessions_own_refusals_blame_their_parameter() {
        use crate::params::{EXTRAPOLATE_GRIDS, HALF_ANGLE, RATIO};
        use serde_json::json;
        for (given, param) in [
            (
                json!({"indenter": "power-law", "half_angle": 60.0}),
                HALF_ANGLE,
            ),
            (json!({"ratio": 2.0, "r1": 3.0}), RATIO),
            (json!({"extrapolate_grids": [32, 64]}), EXTRAPOLATE_GRIDS),
        ] {
            let given = given.as_object().unwrap().clone();
            let e = request::Request::from_json(given.iter().map(|(k, v)| (k.as_str(), v)))
                .and_then(|r| r.simulate_request(simulate::Sink::Memory, None).map(|_| ()))
                .unwrap_err();
            assert!(e.is_input(), "{e}");
            assert_eq!(e.param.map(|p| p.name), Some(param.name), "{e}");
        }
    }
}
