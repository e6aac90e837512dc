//! The solver: CG on a fixed contact set, the detachment/attachment loop and the
//! approach/pull-off protocol. Generic over [`Backend`](crate::backend::Backend); it never
//! knows which backend runs it.

pub mod cg;
pub mod cost;
mod emit;
pub mod equilibrium;
mod loading;
mod onsets;
mod probe;
pub mod protocol;
pub mod retry;
mod search;
pub mod state;
pub mod window;

pub use protocol::{run, run_until, run_watched, run_with_contact, Outcome};
pub use state::{Phase, State};

use crate::backend::BackendError;
use crate::params::{CG_ACCEPT, CG_TOLERANCE, MARGIN, START_RADIUS};
use cg::CgEnd;
use thiserror::Error;

/// The advice of [`SolverError::ContactAtEdge`]: more room around the contact, in a
/// simulation's parameters. A command that sets the domain otherwise (coverage, whose cases
/// take their margins from a list) gives its own advice in place of this piece.
pub fn edge_advice() -> String {
    format!("use a larger {MARGIN} or a smaller {START_RADIUS}")
}

/// Why a run stopped before it was complete.
#[derive(Debug, Error)]
pub enum SolverError {
    /// The backend failed.
    #[error(transparent)]
    Backend(#[from] BackendError),
    /// CG did not reach an acceptable residual, even in its safer retry.
    #[error(
        "conjugate gradients did not converge at d̄ = {d_bar:.5}: CG {first}; retried in the \
         safer mode it {end}. The best relative residual reached was {residual:.2e} after \
         {iterations} iterations in all, above {CG_TOLERANCE} {tolerance:.1e} and {CG_ACCEPT} \
         {accept:.1e}; {}",
        retry::advice(*.end)
    )]
    CgNotConverged {
        /// Approach at which it failed (dimensionless).
        d_bar: f64,
        /// How the normal mode ended.
        first: CgEnd,
        /// How the safer retry ended.
        end: CgEnd,
        /// Best relative residual reached (dimensionless).
        residual: f64,
        /// Iterations spent, both attempts.
        iterations: usize,
        /// Tolerance asked for (dimensionless).
        tolerance: f64,
        /// Acceptable relative residual (dimensionless).
        accept: f64,
    },
    /// The contact reached the outer ring of the domain.
    #[error(
        "the contact reached the edge of the domain at d̄ = {d_bar:.5} ({elements} elements on the \
         outer ring): {}",
        edge_advice()
    )]
    ContactAtEdge {
        /// Approach (dimensionless).
        d_bar: f64,
        /// Contact elements on the outer ring.
        elements: usize,
    },
    /// The detachment/attachment loop did not settle.
    #[error(
        "the detachment loop did not settle at d̄ = {d_bar:.5} after {sweeps} sweeps (last sweep: \
         {detached} detached, {attached} attached): the contact set cycles"
    )]
    DetachmentCycles {
        /// Approach (dimensionless).
        d_bar: f64,
        /// Sweeps made.
        sweeps: usize,
        /// Elements detached in the last sweep.
        detached: usize,
        /// Elements attached in the last sweep.
        attached: usize,
    },
    /// The first press touched nothing: the indenter as sampled on the grid does not reach
    /// the half-space where its closed form puts the first contact.
    #[error(
        "no element came into contact at the first press (d̄ = {d_bar:.5}): the indenter as \
         sampled at the elements' centres does not reach the half-space there (a height map \
         too coarse for its contact, or a shape narrower than an element); nothing can be \
         computed from this run"
    )]
    NoFirstContact {
        /// Approach of the first press (dimensionless).
        d_bar: f64,
    },
    /// The loading phase cannot reach the preload asked for.
    #[error(
        "the preload cannot be reached: {why} (at d̄ = {d_bar:.5}, after {steps} loading \
         steps); ask for a smaller preload ({}, {} or {}) or give a larger domain",
        crate::params::PRELOAD_DEPTH,
        crate::params::PRELOAD_FORCE,
        crate::params::PRELOAD_AREA
    )]
    PreloadUnreachable {
        /// Approach of the last loading state (dimensionless).
        d_bar: f64,
        /// Loading steps recorded.
        steps: usize,
        /// Why, in words.
        why: String,
    },
    /// The run was stopped from outside (the observer of its states asked to stop).
    #[error("interrupted: the run was asked to stop")]
    Interrupted,
}
