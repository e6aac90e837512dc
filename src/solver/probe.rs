//! What a probe of a stretch of the load finds, how a walk through its onsets is asked for,
//! and the bound the probe gives: shared by the walk ([`super::onsets`]) and the window of
//! steps gone back to ([`super::window`], [`super::search`]).

/// What a probe found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Probe {
    /// Force of the step's start state (force; NaN where the walk did not measure it).
    pub base: f64,
    /// Force of the probe (force): no onset of the step lies below it.
    pub lower: f64,
    /// Fraction of the step at which the first element reaches σ_c (1: none does).
    pub t: f64,
    /// The probe's relative CG residual (dimensionless).
    pub residual: f64,
}

impl Probe {
    /// Force (force) of the step's first onset, if it has one: exact, an interpolation.
    pub fn first_onset(&self) -> Option<f64> {
        (self.t < 1.0).then_some(self.base + self.t * (self.lower - self.base))
    }
}

/// How a walk through a step's onsets is done.
#[derive(Debug, Clone, Copy)]
pub(super) struct Through {
    /// The load step.
    pub step: usize,
    /// Approach at its start (length).
    pub d_from: f64,
    /// Approach at its end (length).
    pub d_to: f64,
    /// Stop once the rest of the step cannot hold an onset below the lowest located.
    pub prune: bool,
    /// Resolve the cascade at the step's end (else the walk stops at its last onset: the
    /// step's end state is already known).
    pub finish: bool,
    /// Hold the onset states back (they are handed on in the order of the load later).
    pub hold: bool,
    /// Record the first onset (false: it was recorded already).
    pub record_first: bool,
}

/// Where a part is split (`split_at` in [`super::search`]) or a walk skips ahead
/// ([`bound_meets`]), the bound of the stretch left behind lies this fraction of the force
/// above the lowest onset found: the bound's CG error is covered by the window's
/// `BOUND_TOLERANCE`, a hundredth of this.
pub(super) const MEET_ABOVE: f64 = 1e-5;

/// The fraction of a stretch of the load at which its bound, the line from the force `base`
/// at its start to its probe's `lower` (forces), reaches `level` (force) raised by
/// [`MEET_ABOVE`]: none of the stretch's onsets before it lies below that (dimensionless;
/// not finite, or outside (0, 1), where the line does not cross it inside).
pub(super) fn bound_meets(base: f64, lower: f64, level: f64) -> f64 {
    let level = level + MEET_ABOVE * level.abs();
    (base - level) / (base - lower)
}
