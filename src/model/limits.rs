//! The ranges and sizes a model is held to: grid sides, load steps, margins, CG limits,
//! the elements a contact must span, memory per element, and the scales each precision holds.

use super::{Measure, Onsets};

pub use crate::params::limits::MIN_GRID;

pub use crate::params::limits::MAX_GRID;

pub use crate::params::limits::START_RADIUS_RANGE;

pub use crate::params::limits::MAX_STEPS;

/// Load steps of a whole curve unless told otherwise: its resolution in d̄.
pub const CURVE_STEPS: usize = 200;

/// Load steps of an adhesive-force run ([`Measure::AdhesiveForce`] with
/// [`Onsets::NearMinimum`], no re-grid) unless told otherwise: its answer does not depend on
/// them, and fewer, larger steps take fewer cascade rounds in all (measured at 5:1, 512×256:
/// 13 274 CG iterations with 20 steps, 13 740 with 40, 16 641 with 200).
pub const MEASURE_STEPS: usize = 20;

/// The load steps a run takes unless told otherwise: [`MEASURE_STEPS`] where the answer does
/// not depend on them (the adhesive force, onsets near the minimum, no re-grid, whose grid
/// changes at step ends), else [`CURVE_STEPS`].
pub fn default_steps(measure: Measure, onsets: Onsets, regrid: bool) -> usize {
    if measure == Measure::AdhesiveForce && onsets == Onsets::NearMinimum && !regrid {
        MEASURE_STEPS
    } else {
        CURVE_STEPS
    }
}

pub use crate::params::limits::MAX_MARGIN;

pub use crate::params::limits::MAX_CG_ITERATIONS;

/// Most loading steps of a preload (a target the surface never reaches, say an area it
/// cannot cover, stops there with an error; a depth further than that many load steps is
/// refused before any work).
pub const MAX_LOADING_STEPS: usize = 100_000;

pub use crate::params::limits::MAX_CG_TOLERANCE;

pub use crate::params::limits::MAX_MESH_ANGLE;

pub use crate::params::limits::MIN_FINAL_D_BAR;

/// The free margin around the first contact, relative to its half-axes, where none is given
/// (dimensionless; [`default_margin`] raises it on the smallest grids).
pub const DEFAULT_MARGIN: f64 = 0.08;

/// Fewest whole elements the default margin leaves free on each side of the first contact
/// along x.
pub const MIN_FREE_ELEMENTS: usize = 1;

/// The margin a grid of `nx` elements along x takes where none is given: [`DEFAULT_MARGIN`],
/// or more where that leaves fewer than [`MIN_FREE_ELEMENTS`] whole elements free (on 16
/// elements it leaves 0.6, and the adhesive first contact, wider than Hertz's, reaches the
/// domain's edge: 2/14 = 0.143 there; from 32 elements up it is 0.08).
pub fn default_margin(nx: usize) -> f64 {
    let free = MIN_FREE_ELEMENTS as f64;
    DEFAULT_MARGIN.max(2.0 * free / (nx as f64 - 2.0 * free))
}

/// Fewest elements the first (Hertz) contact may span across its minor axis.
pub const MIN_ELEMENTS_FIRST_CONTACT: f64 = 8.0;

/// Fewest elements the contact is expected to span across its minor axis at the force
/// minimum (from the closed form's b̄ there). Below this the detachment front is a couple of
/// elements: the answer would be noise, not an adhesive force.
pub const MIN_ELEMENTS_AT_MINIMUM: f64 = 4.0;

/// Fewest map spacings a height map must have across the contact's minor axis at the force
/// minimum (dimensionless). The solver samples the map bilinearly: where the contact spans few
/// map cells it works on their flat facets, not on the surface's shape. Measured on maps of
/// the sphere (x² + y²)/2 against the sphere itself (E* = Δγ = 1, 64² and 128²
/// grids, the apex on a node, a quarter and half a spacing off it): at 16 spacings and more the
/// map moves the grid's |min F̄| by less than the grid's own phase scatter (within ±0.8 %);
/// at 7–12 by up to +4.7 %, at 4 by +8 %, and a contact inside one map cell makes nonsense.
pub const MIN_MAP_SPACINGS_AT_MINIMUM: f64 = 16.0;

/// Memory a model needs per grid element (bytes), measured on the CPU backend: the padded
/// 2Nx × 2Ny spectra of the convolution and the Nx × Ny ones of the preconditioner, CG's
/// fields, masks and snapshots; about 200 B at 1024², doubled while a re-grid builds the
/// finer backend beside the old one.
pub const BYTES_PER_ELEMENT: u64 = 320;

/// Memory a model needs whatever its grid (bytes): the program, its threads and buffers.
pub const BYTES_FIXED: u64 = 64 << 20;

/// Memory the search for the force minimum may spend on the states it keeps to go back to
/// (bytes; [`snapshot_slots`]).
pub const SNAPSHOT_BYTES: u64 = 512 << 20;

/// Values each kept state holds per element (its pressure, its contact set and its probe's
/// pressure), at 8 bytes each at most.
pub(super) const SNAPSHOT_BYTES_PER_ELEMENT: u64 = 24;

/// How many states the search for the force minimum may keep on a grid of `elements`
/// (`--onsets near-minimum`): as many as [`SNAPSHOT_BYTES`] holds, from 4 to 64.
pub fn snapshot_slots(elements: usize) -> usize {
    let each = SNAPSHOT_BYTES_PER_ELEMENT
        .saturating_mul(elements as u64)
        .max(1);
    (SNAPSHOT_BYTES / each).clamp(4, 64) as usize
}

/// The range within which the numbers a backend holds must lie: σ_c, the element side, the
/// approach and the Hertz pressure. For f64 any scene within the input ranges fits; the f32
/// GPU backend needs [`F32_SAFE_RANGE`].
pub const F64_SAFE_RANGE: (f64, f64) = (1e-150, 1e150);

/// [`F64_SAFE_RANGE`] for f32 fields, whose squares must stay inside f32's 1e-38 … 3e38.
pub const F32_SAFE_RANGE: (f64, f64) = (1e-15, 1e15);

/// The fraction of the domain a height map on a window is pressed on to cover where no
/// preload is given (dimensionless): a contact well inside the domain, of many elements.
pub const DEFAULT_PRELOAD_AREA: f64 = 0.1;

/// How far below the first touch a height map's pull-off is expected to end, in the depth
/// of its default preload (dimensionless): what sizes its load steps.
pub const WINDOW_PULL_BELOW: f64 = 0.5;

/// How far below the first touch a height map's pull-off stops if the contact has not
/// vanished, in the depth of its default preload (dimensionless).
pub const WINDOW_FINAL_BELOW: f64 = 20.0;
