//! The session: what a user asks for as one typed request, checked, planned and run on a
//! backend (one pull-off, an adhesive force to an accuracy, a batch of any scenes), its
//! outputs claimed and written through `output`. Each front end (the `jkrbem` command line,
//! Python, a test) only builds a request, calls one function here and shows what comes back;
//! the studies build on it, never the reverse.
//!
//! Errors say whether the request was refused before any work ([`RunError::Input`]) or the
//! work failed ([`RunError::Failed`]), and name the parameter or value to change: a parameter
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
use crate::solver::State;
use std::fmt;

/// Why a request did not produce its results.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum RunError {
    /// The request was refused before any work (bad input, an output that cannot be written).
    Input(String),
    /// The work started and failed.
    Failed(String),
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RunError::Input(m) | RunError::Failed(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RunError {}

/// A refusal, from any layer's error.
pub fn input(e: impl fmt::Display) -> RunError {
    RunError::Input(e.to_string())
}

/// A failure, from any layer's error.
pub fn failed(e: impl fmt::Display) -> RunError {
    RunError::Failed(e.to_string())
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
