//! A recorded, converged state of the pull-off, dimensional and normalised.

use serde::{Deserialize, Serialize};

/// Which part of the protocol a state belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Phase {
    /// The first, non-adhesive press to d0.
    #[default]
    Approach,
    /// A step of the adhesive pull-off.
    Pulloff,
    /// Inside a pull-off step, the approach at which the first element of the unchanged
    /// contact set reaches σ_c: a local minimum of the sawtooth F(d), recorded so that the
    /// force minimum does not depend on the step size.
    Onset,
    /// The state just after re-gridding: the contact carried to a finer grid and
    /// re-equilibrated at the same approach.
    Regrid,
    /// The state a detachment cascade left just past an onset whose force it changed by
    /// more than [`crate::solver::protocol::JUMP_FRACTION`] (a patch snapping off): with the
    /// onset before it, the two sides of the jump at (nearly) the same approach.
    Jump,
    /// A step of the loading phase: the indenter pressed on, elements attaching where their
    /// gap closes (the pull-off starts from its last state).
    Loading,
    /// A step of the loading phase whose cascade moved the force by more than
    /// [`crate::solver::protocol::JUMP_FRACTION`] however short it was taken (a patch snapping
    /// in, the first touch snapping to a finite contact): with the loading state before it,
    /// within 1/64 of a load step, the two sides of the jump.
    #[serde(rename = "loading-jump")]
    LoadingJump,
}

impl Phase {
    /// Whether the state belongs to the loading phase ([`Phase::Loading`] or
    /// [`Phase::LoadingJump`]).
    pub fn is_loading(self) -> bool {
        matches!(self, Phase::Loading | Phase::LoadingJump)
    }
}

/// One converged state. Dimensional values are in the scene's units; `*_bar` values are
/// normalised as in physics §2.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct State {
    /// Load step (0 for the approach).
    pub step: usize,
    /// Protocol phase.
    pub phase: Phase,
    /// Approach d (length; > 0 presses in).
    pub d: f64,
    /// Force F = Σ p Δx² (force; > 0 compressive).
    pub force: f64,
    /// Contact area A (length²).
    pub area: f64,
    /// Mean contact radius c = √(A/π) (length).
    pub mean_radius: f64,
    /// Half-length of the contact along the indenter's x axis through the grid centre (length):
    /// an ellipsoid's major axis (R1's direction), a height map's x axis; the grid's x axis
    /// unless the mesh is rotated.
    pub a_axis: f64,
    /// Half-length of the contact along the indenter's y axis through the grid centre (length):
    /// an ellipsoid's minor axis (R2's direction), a height map's y axis; the grid's y axis
    /// unless the mesh is rotated.
    pub b_axis: f64,
    /// Elements in contact.
    pub n_contact: usize,
    /// CG iterations spent on this state.
    pub cg_iterations: usize,
    /// Detachment/attachment sweeps that changed the contact set at this state.
    pub detach_sweeps: usize,
    /// d̄ (dimensionless).
    pub d_bar: f64,
    /// F̄ (dimensionless).
    pub f_bar: f64,
    /// c̄ (dimensionless).
    pub c_bar: f64,
    /// ā (dimensionless).
    pub a_bar: f64,
    /// b̄ (dimensionless).
    pub b_bar: f64,
    /// The largest relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ of the CG solves behind
    /// this state, recomputed from p (dimensionless). Normally below the CG tolerance (or
    /// near 1e-7 in f32); above it, the state was accepted after CG's safer retry fell
    /// short. NaN when read from a file written before the column existed.
    #[serde(default = "not_recorded")]
    pub cg_residual: f64,
    /// Element side Δx of the grid this state was computed on (length); it changes only
    /// when the run re-grids.
    #[serde(default)]
    pub dx: f64,
}

/// The value of a column missing from an older file.
fn not_recorded() -> f64 {
    f64::NAN
}

/// One change of grid during a run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RegridEvent {
    /// Approach at which the grid changed (dimensionless).
    pub d_bar: f64,
    /// Element side before (length).
    pub dx_from: f64,
    /// Element side after (length).
    pub dx_to: f64,
}
