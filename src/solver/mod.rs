//! The solver: CG on a fixed contact set, the detachment/attachment loop and the
//! approach/pull-off protocol. Generic over [`Backend`](crate::backend::Backend); it never
//! knows which backend runs it.

pub mod cg;
pub mod equilibrium;
pub mod protocol;
pub mod state;

pub use protocol::{run, run_with_contact, Outcome};
pub use state::{Phase, State};

use crate::backend::BackendError;
use thiserror::Error;

/// Why a run stopped before it was complete.
#[derive(Debug, Error)]
pub enum SolverError {
    /// The backend failed.
    #[error(transparent)]
    Backend(#[from] BackendError),
    /// CG did not reach its tolerance.
    #[error(
        "conjugate gradients did not converge at d̄ = {d_bar:.5}: relative residual {residual:.3e} \
         after {iterations} iterations (tolerance {tolerance:.1e}); try a looser --cg-tolerance or a \
         higher --cg-max-iterations"
    )]
    CgNotConverged {
        /// Approach at which it failed (dimensionless).
        d_bar: f64,
        /// Relative residual reached.
        residual: f64,
        /// Iterations spent.
        iterations: usize,
        /// Tolerance asked for.
        tolerance: f64,
    },
    /// A NaN or infinity appeared in CG.
    #[error("conjugate gradients produced a non-finite value at d̄ = {d_bar:.5} after {iterations} iterations")]
    NonFinite {
        /// Approach at which it failed (dimensionless).
        d_bar: f64,
        /// Iterations spent.
        iterations: usize,
    },
    /// The contact reached the outer ring of the domain.
    #[error(
        "the contact reached the edge of the domain at d̄ = {d_bar:.5} ({elements} elements on the \
         outer ring): use a larger --margin or a smaller --start-radius"
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
    /// The user stopped the run.
    #[error("interrupted")]
    Interrupted,
}
