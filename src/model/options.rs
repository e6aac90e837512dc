//! What a caller chooses of a model: the grid, the protocol (steps, onsets, measure,
//! re-gridding) and the CG settings.

use crate::scene::PullOffHint;
use crate::setup::Preconditioner;

/// Which detachment onsets (the local minima of the sawtooth F(d)) a pull-off locates. The
/// contact set at the end of every load step does not depend on this: the detachment rule is
/// monotone, so a step ends on the greatest stable subset of the set it started from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Onsets {
    /// Whole load steps; the onsets of a step are located only where they can hold the force
    /// minimum: where the step's lower bound (its unchanged contact set solved at the step's
    /// end) lies below the lowest onset found. The force minimum is the same as with `all`.
    #[default]
    NearMinimum,
    /// Every onset of every step, recorded: today's full sawtooth (the most states and
    /// solves).
    All,
    /// None: whole steps only, the detachment cascade of a step resolved at its end. The
    /// force minimum then depends on the step size; kept to show what that costs.
    None,
}

impl Onsets {
    /// The name the CLI and the states CSV use ("near-minimum", "all", "none").
    pub fn name(self) -> &'static str {
        match self {
            Onsets::NearMinimum => "near-minimum",
            Onsets::All => "all",
            Onsets::None => "none",
        }
    }
}

/// What a run is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    /// The whole pull-off curve, to the end of contact.
    #[default]
    Curve,
    /// Only the adhesive force |min F̄|: the run stops once the force minimum is confirmed
    /// (and, with [`Onsets::NearMinimum`], its onsets located).
    AdhesiveForce,
}

/// The user's choices that shape a model; `None` means "choose for the scene". Serialised as
/// provenance and the reuse check record it (every field but the planner's hint).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ModelOptions {
    /// Elements along x (power of two).
    pub nx: usize,
    /// Elements along y (power of two), or fit to the contact's aspect.
    pub ny: Option<usize>,
    /// Mean radius of the initial non-adhesive contact, c̄0 (dimensionless, in c_r).
    pub start_radius_bar: f64,
    /// Number of load steps from d0 to the expected end of contact.
    pub steps: usize,
    /// Final approach d̄ at which to stop if the contact is still there (dimensionless).
    pub final_d_bar: Option<f64>,
    /// Relative free margin around the initial contact on each side (dimensionless).
    pub margin: f64,
    /// Relative residual at which CG stops (dimensionless).
    pub cg_tolerance: f64,
    /// CG iteration limit per solve.
    pub cg_max_iterations: usize,
    /// Relative residual up to which a solve that missed the tolerance even in CG's safer
    /// retry is accepted, and its state marked (dimensionless).
    pub cg_accept: f64,
    /// Read the residual back every this many CG iterations.
    pub cg_check_every: usize,
    /// Preconditioner.
    pub preconditioner: Preconditioner,
    /// Limit on detachment/attachment sweeps per load step.
    pub max_sweeps: usize,
    /// Which detachment onsets are located.
    pub onsets: Onsets,
    /// Whether a cascade's intermediate rounds are solved only as far as needed to decide
    /// which elements are over σ_c (the last round is always exact; the states are the same).
    pub loose_rounds: bool,
    /// What the run is for.
    pub measure: Measure,
    /// Re-grid as the contact shrinks: the same Nx × Ny on a smaller domain (finer Δx).
    pub regrid: bool,
    /// Angle θ between the ellipsoid's major axis and the grid's x axis (degrees); 0 aligns
    /// them. A rotated mesh checks results where crack fronts run along grid lines (physics §7).
    pub mesh_angle_deg: f64,
    /// Where the apex lies within the element grid (elements along x and y, each in
    /// [−0.5, 0.5], so that it moves by half an element at most): (0, 0) puts it on the
    /// corner between the four middle elements, (0.5, 0.5) on the centre of one. Changing it changes
    /// where the contact's edge falls between element centres (the grid phase) and nothing
    /// else; the extrapolation in Δx averages over it.
    pub apex_offset: (f64, f64),
    /// Where a planner expects the pull-off to end and how small the contact gets at the
    /// force minimum: the load path and the resolution check are sized from it. `None`: the
    /// scene's own closed form (the sphere's values where the indenter has none).
    #[serde(skip)]
    pub hint: Option<PullOffHint>,
    /// How far the loading phase presses before the pull-off ([`Preload`]); `None`: the
    /// scene's default (a smooth closed-form shape starts from its non-adhesive first
    /// contact of c̄0 built in one piece; a height map or a rough shape is pressed on).
    #[serde(default)]
    pub preload: Option<Preload>,
}

/// Where the loading phase stops: the pull-off starts from the contact pressed on to it,
/// elements attaching where their gap closes.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Preload {
    /// At this approach d (length, as the states' d: from the indenter's reference point,
    /// its apex or, for a height map, the lowest node of the domain).
    Depth(f64),
    /// Once the compressive force reaches this (force).
    Force(f64),
    /// Once the contact covers this fraction of the domain (dimensionless, in (0, 1)).
    AreaFraction(f64),
    /// At the approach of the scene's own first contact of c̄0 (length: today's d0), pressed
    /// on instead of built in one piece.
    StartRadius,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions {
            nx: 256,
            ny: None,
            start_radius_bar: 1.5,
            steps: 200,
            final_d_bar: None,
            margin: super::limits::DEFAULT_MARGIN,
            cg_tolerance: 1e-8,
            cg_max_iterations: 5000,
            cg_accept: 1e-5,
            cg_check_every: 1,
            preconditioner: Preconditioner::Stiffness,
            max_sweeps: 2000,
            onsets: Onsets::NearMinimum,
            loose_rounds: true,
            measure: Measure::Curve,
            regrid: false,
            mesh_angle_deg: 0.0,
            apex_offset: (0.0, 0.0),
            hint: None,
            preload: None,
        }
    }
}

/// Conjugate-gradient settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgSettings {
    /// Stop when ‖r‖ ≤ tolerance · ‖d − h‖ on C (dimensionless).
    pub tolerance: f64,
    /// Iteration limit per solve (and again for its safer retry).
    pub max_iterations: usize,
    /// Read the residual every this many iterations.
    pub check_every: usize,
    /// A solve that misses the tolerance even in the safer retry is still accepted, and its
    /// state marked, if ‖r‖ ≤ accept · ‖d − h‖ on C (dimensionless).
    pub accept: f64,
}

impl CgSettings {
    /// The relative residual up to which a solve is accepted: `accept`, or the tolerance
    /// if that is looser.
    pub fn acceptable(&self) -> f64 {
        self.accept.max(self.tolerance)
    }
}
