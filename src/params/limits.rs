//! Every range the parameter tables hold a value to, owned here so that the rooms below
//! (the scene, the model, the solver, the outputs, the studies) read their limits from the
//! ground floor rather than the tables reading them from above. Each room re-exports the
//! ones it enforces under the name it always used.

/// Smallest grid side accepted (elements).
pub const MIN_GRID: usize = 16;

/// Largest grid side accepted (elements); the machine's memory usually refuses smaller ones
/// first (the plan's memory check).
pub const MAX_GRID: usize = 65_536;

/// Valid mean radii c̄0 of the first contact (dimensionless). The lower end lies above the
/// contact radius at the force minimum (c̄ = 0.63–0.79 in the closed forms, 0.74–0.84 in our
/// runs), since the contact cannot grow past its first, pinned size: the branch must start
/// above the minimum to pass through it.
pub const START_RADIUS_RANGE: (f64, f64) = (1.0, 20.0);

/// Most load steps.
pub const MAX_STEPS: usize = 100_000;

/// Largest relative margin around the first contact.
pub const MAX_MARGIN: f64 = 10.0;

/// Most CG iterations per solve.
pub const MAX_CG_ITERATIONS: usize = 10_000_000;

/// Loosest CG tolerance accepted (relative residual, dimensionless). The stated
/// uncertainties take each state's solve as exact: they hold only while the solves' error is
/// far below them. Measured on the sphere at its default grid (64², CPU, the grid's |min F̄|
/// against the default 1e-8's): 1e-6 and 1e-5 moved it by less than 5e-6 relative, 1e-4 by
/// 1.4e-4, 1e-3 by 0.13 %, 1e-2 by 2.7 % (the estimate by as much); the loose cascade rounds
/// are solved to 1e-5 themselves.
pub const MAX_CG_TOLERANCE: f64 = 1e-5;

/// Largest |mesh angle| (degrees).
pub const MAX_MESH_ANGLE: f64 = 360.0;

/// Lowest final approach d̄ accepted (dimensionless; the contact jumps off at d̄ ≈ −0.44
/// for the sphere, so anything far below only means "run to the end").
pub const MIN_FINAL_D_BAR: f64 = -1000.0;

/// Largest axis ratio R1/R2 accepted (dimensionless). The study goes to 50; beyond about
/// 1000 the contact is a thin strip that no grid of [`MAX_GRID`] columns
/// resolves across its minor axis from the default c̄0.
pub const MAX_RATIO: f64 = 1000.0;

/// Smallest dimensional input accepted (R1, R2, E*, Δγ, in the user's units). With every
/// input in [`MIN_INPUT`, `MAX_INPUT`] every scale of the problem (c_r, the approach scale,
/// σ_c, forces) and its square stay far inside the range of f64.
pub const MIN_INPUT: f64 = 1e-30;

/// Largest dimensional input accepted (see [`MIN_INPUT`]).
pub const MAX_INPUT: f64 = 1e30;

/// Largest power-law exponent n accepted (dimensionless): beyond it h = s·rⁿ is a flat punch
/// for every grid (use the flat punch).
pub const MAX_EXPONENT: f64 = 64.0;

/// Smallest power-law exponent n accepted (dimensionless): n ≤ 1 (a cone or sharper) has an
/// infinite pressure at its tip and no finite peak pressure to check scales with (the cone,
/// n = 1, is a shape of its own, checked with its mean pressure).
pub const MIN_EXPONENT: f64 = 1.25;

/// Smallest cone half-angle α accepted (degrees, between the axis and the flank): sharper
/// cones leave the half-space's small-slope theory far behind (its flank rises 5.7 per unit
/// run at 10°).
pub const MIN_HALF_ANGLE: f64 = 10.0;

/// Largest cone half-angle α accepted (degrees): beyond it the cone is a plane for every
/// grid (its flank rises 0.017 per unit run at 89°).
pub const MAX_HALF_ANGLE: f64 = 89.0;

/// Fewest nodes along either axis of a generated roughness (a count), as of a height map.
pub const MIN_ROUGHNESS_NODES: usize = 4;

/// Most nodes along either axis of a generated roughness (a count).
pub const MAX_ROUGHNESS_NODES: usize = 16384;

/// The most shards a sweep or a batch is split into.
pub const MAX_SHARDS: usize = 10_000;

/// The most points a closed-form curve is evaluated at (a count).
pub const MAX_CURVE_POINTS: usize = 1_000_000;

/// Smallest Poisson's ratio accepted (dimensionless): ν → −1 makes E* = E/(2(1 − ν²))
/// unbounded.
pub const MIN_POISSON: f64 = -0.99;

/// Most runs one case is estimated from (`runs_per_case`; also at most the number of margins):
/// more than any list of margins a study gives (the default has 5).
pub const MAX_RUNS_PER_CASE: usize = 100;

/// Smallest grid side a plan uses (elements): coarser grids are not yet in the first-order
/// regime (the observed order from 32/64/128 was 1.1, from 64/128/256 without re-gridding 0.6).
pub const MIN_PLAN_GRID: usize = 32;

/// The coarsest first grid of a ladder (Nx): coarser grids are not yet first order.
pub const MIN_FIRST_GRID: usize = MIN_PLAN_GRID;

/// Runs per grid of a reference ladder at the most (its phases).
pub const MAX_REFERENCE_PHASES: usize = 8;

/// The tightest target a reference ladder may aim at (relative uncertainty, 0.1 %): tighter takes grids
/// past any machine's memory.
pub const MIN_REFERENCE_TARGET: f64 = 0.001;

/// The loosest target (relative uncertainty, 50 %): a looser one is no reference.
pub const MAX_REFERENCE_TARGET: f64 = 0.5;

/// The longest time limit an accuracy run takes (s): 30 days. Longer ones are no limit in
/// practice, and far longer ones overflow a clock.
pub const MAX_TIME_LIMIT_S: f64 = 30.0 * 86400.0;

/// Most timed samples of one measurement (`repeats`): each is at least 20 ms after 0.2 s of
/// warm-up, so a thousand already take minutes per grid and backend; the median of more moves
/// no further.
pub const MAX_REPEATS: usize = 1000;

/// Most CG iterations of one timed solve (`cg_iterations`): a hundred thousand take about a
/// minute at 256² on two cores; more time the same iteration for longer.
pub const MAX_TIMED_CG_ITERATIONS: usize = 100_000;
