//! The parameters of the commands beyond a simulation (sweep, reference, coverage, accuracy,
//! crossed, reproduce, bench, collect) that the library's messages name: one `const` [`Spec`]
//! each, and [`STUDY_SPECS`]. A simulation's own parameters, which these commands share
//! (`--grid`, `--margin`, `--backend`, `--out`, …), are those of [`SPECS`](super::SPECS).
//!
//! These are no request's parameters: their commands parse them (clap), and a message names
//! them by their marker as it names any other. A list parameter (`--ratios 1,2,5`) is declared
//! with the kind and range of each of its values, and its default where its commands differ
//! is said in words ([`Fallback::Chosen`]).

use super::limits::{
    MAX_CURVE_POINTS, MAX_EXPONENT, MAX_HALF_ANGLE, MAX_INPUT, MAX_MARGIN, MAX_MESH_ANGLE,
    MAX_RATIO, MAX_REFERENCE_PHASES, MAX_REFERENCE_TARGET, MAX_REPEATS, MAX_RUNS_PER_CASE,
    MAX_SHARDS, MAX_TIMED_CG_ITERATIONS, MIN_EXPONENT, MIN_FIRST_GRID, MIN_GRID, MIN_HALF_ANGLE,
    MIN_INPUT, MIN_POISSON, MIN_REFERENCE_TARGET,
};
use super::{cli_only, spec, Fallback, Fronts, Group, Kind, Range, Spec};

/// Most pull-offs a command runs at the same time (`--jobs`).
pub const MAX_JOBS: usize = 256;

/// A dimensional input's range (the cylinders' E).
const INPUT: Kind = Kind::Real(Range::closed(MIN_INPUT, MAX_INPUT));
/// A crossing angle's range (degrees): (0, 90]; below about 3.62° R1/R2 exceeds
/// [`MAX_RATIO`], which the pair's own check refuses.
const CROSSING_ANGLE: Kind = Kind::Real(Range {
    lo: 0.0,
    hi: 90.0,
    lo_open: true,
    hi_open: false,
});
/// A grid side of a list of grids (`--grids`).
const GRID_SIDE: Kind = Kind::PowerOfTwo(MIN_GRID as u64, super::limits::MAX_GRID as u64);
/// The first grid of a reference ladder and its finest.
const LADDER_GRID: Kind = Kind::PowerOfTwo(MIN_FIRST_GRID as u64, super::limits::MAX_GRID as u64);

/// A parameter of one or more of these commands, which only the command line takes.
const fn cli(
    name: &'static str,
    flag: &'static str,
    unit: &'static str,
    kind: Kind,
    fallback: Fallback,
    help: &'static str,
) -> Spec {
    cli_only(spec(name, flag, Group::Study, unit, kind, fallback, help))
}

/// A parameter of the crossed cylinders that Python's crossed scene takes too.
const fn both(spec: Spec) -> Spec {
    Spec {
        fronts: Fronts::Both,
        ..spec
    }
}

use Fallback::{Chosen, Value};

/// The axis ratios of a sweep, a reference table or a coverage run.
pub const RATIOS: &Spec = &cli(
    "ratios",
    "--ratios",
    "",
    Kind::Real(Range::closed(1.0, MAX_RATIO)),
    Chosen("sweep: 1, 2, 5, 10, 25, 50; reference and coverage: every tabled ratio"),
    "Axis ratios R1/R2, comma-separated, none repeated: one pull-off (sweep), one ladder \
     (reference) or one set of cases (coverage) per ratio.",
);
/// The grids of accuracy, bench and coverage.
pub const GRIDS: &Spec = &cli(
    "grids",
    "--grids",
    "elements",
    GRID_SIDE,
    Chosen(
        "accuracy: 32, 64, 128; bench: 64, 128, 256; coverage: the finest grid of the ratio's \
         reference ladder over 8 and over 4",
    ),
    "Grids Nx, comma-separated powers of two: accuracy runs the scene on each, bench times \
     each, coverage runs its cases on each.",
);
/// The finest grid of a reference ladder.
pub const MAX_GRID: &Spec = &cli(
    "max_grid",
    "--max-grid",
    "elements",
    LADDER_GRID,
    Value("2048"),
    "Reference: Nx of the finest grid a ratio's ladder may use. Every ladder is checked before \
     any work: at least three grids must fit below it and in the memory available.",
);
/// The first grid of a reference ladder.
pub const FIRST_GRID: &Spec = &cli(
    "first_grid",
    "--first-grid",
    "elements",
    LADDER_GRID,
    Chosen("the grid a 5 % accuracy plan takes for the ratio"),
    "Reference: Nx of the first (coarsest) grid of every ladder; a coarser start gives a \
     slender ratio its three grids below max_grid.",
);
/// The runs per grid of a reference ladder.
pub const PHASES: &Spec = &cli(
    "phases",
    "--phases",
    "",
    Kind::Count(1, MAX_REFERENCE_PHASES as u64),
    Value("1"),
    "Reference: runs per grid, each at another domain margin (0.08, 0.13, 0.18, …), so that \
     the fit averages the grid phase's scatter.",
);
/// The uncertainty a reference ladder aims at.
pub const TARGET: &Spec = &cli(
    "target",
    "--target",
    "",
    Kind::Fraction(MIN_REFERENCE_TARGET, MAX_REFERENCE_TARGET),
    Value("0.3%"),
    "Reference: the relative uncertainty wanted of each |min F̄| at Δx → 0 (a percentage, the \
     unit required); each ladder's grids double until it is reached. Tighter than 0.1 % takes \
     grids past any memory, looser than 50 % is no reference.",
);
/// The domain margins of coverage's cases.
pub const MARGINS: &Spec = &cli(
    "margins",
    "--margins",
    "relative",
    Kind::Real(Range::closed(0.0, MAX_MARGIN)),
    Chosen("0.08, 0.13, 0.18, 0.23, 0.28"),
    "Coverage: domain margins, comma-separated; each moves where the contact's edge falls \
     between element centres (the grid phase).",
);
/// How accuracy and coverage run each grid.
pub const VARIANTS: &Spec = &cli(
    "variants",
    "--variants",
    "",
    Kind::Choice(&["fixed", "regrid", "plain", "measure"]),
    Chosen("coverage: fixed, regrid; accuracy: plain, measure, regrid"),
    "How each grid is run, comma-separated, none repeated. Coverage: `fixed` (one Δx) and \
     `regrid`; accuracy: `plain` (the whole curve), `measure` (measure adhesive-force) and \
     `regrid` (also re-gridded).",
);
/// The mesh angles of coverage's cases.
pub const MESH_ANGLES: &Spec = &cli(
    "mesh_angles",
    "--mesh-angles",
    "degrees",
    Kind::Real(Range::closed(-MAX_MESH_ANGLE, MAX_MESH_ANGLE)),
    Value("0"),
    "Coverage: mesh angles θ, comma-separated; every case runs at each.",
);
/// The apex offsets of coverage's cases.
pub const APEX_OFFSETS: &Spec = &cli(
    "apex_offsets",
    "--apex-offsets",
    "elements",
    Kind::Pair(Range::closed(-0.5, 0.5)),
    Chosen("0:0, the apex on an element corner"),
    "Coverage: apex offsets within the element grid, comma-separated `x:y` pairs; every case \
     runs at each.",
);
/// The shapes of coverage's cases.
pub const SHAPES: &Spec = &cli(
    "shapes",
    "--shapes",
    "",
    Kind::Choice(&["cone", "ellipsoid", "flat-punch", "power-law"]),
    Value("ellipsoid"),
    "Coverage: the shapes, comma-separated: `ellipsoid` (its convergence law, against JKR or \
     the reference table), `flat-punch` (against Kendall's 1), `power-law` and `cone` (against \
     their JKR solutions), the last three extrapolated over grids and grid phases without a law.",
);
/// The power-law exponents of coverage's cases.
pub const EXPONENTS: &Spec = &cli(
    "exponents",
    "--exponents",
    "",
    Kind::Real(Range::closed(MIN_EXPONENT, MAX_EXPONENT)),
    Chosen("1.5, 3, 8"),
    "Coverage: the power law's exponents n, comma-separated.",
);
/// The cone half-angles of coverage's cases.
pub const HALF_ANGLES: &Spec = &cli(
    "half_angles",
    "--half-angles",
    "degrees",
    Kind::Real(Range::closed(MIN_HALF_ANGLE, MAX_HALF_ANGLE)),
    Chosen("70"),
    "Coverage: the cone's half-angles α, comma-separated (in its own normalisation every cone \
     is one problem: other angles check only round-off).",
);
/// The runs of one coverage case.
pub const RUNS_PER_CASE: &Spec = &cli(
    "runs_per_case",
    "--runs-per-case",
    "",
    Kind::Count(1, MAX_RUNS_PER_CASE as u64),
    Value("1"),
    "Coverage: runs per case, at consecutive margins of one grid (up to the number of \
     margins); every window of consecutive margins is a case.",
);
/// The backends of accuracy and bench.
pub const BACKENDS: &Spec = &cli(
    "backends",
    "--backends",
    "",
    Kind::Choice(&["auto", "cpu", "gpu"]),
    Chosen("accuracy: cpu; bench: cpu, plus gpu when a GPU backend can be opened"),
    "Backends, comma-separated, none repeated: accuracy runs on each, bench times each.",
);
/// The arithmetics of bench.
pub const PRECISIONS: &Spec = &cli(
    "precisions",
    "--precisions",
    "",
    Kind::Choice(&["auto", "f64", "f32"]),
    Chosen("auto: each backend's own"),
    "Bench: the arithmetic each backend is timed in, comma-separated (the GPU has no f64 and \
     skips it).",
);
/// One shard of a sweep.
pub const SHARD: &Spec = &cli(
    "shard",
    "--shard",
    "",
    Kind::Count(1, MAX_SHARDS as u64),
    Chosen("none: the whole sweep"),
    "Sweep: run only shard K of N, written K/N (1 ≤ K ≤ N ≤ 10000): the ratios at positions \
     K, K+N, K+2N, … of ratios; `jkrbem collect` merges the shards' files.",
);
/// Merging an incomplete sweep.
pub const ALLOW_MISSING: &Spec = &cli(
    "allow_missing",
    "--allow-missing",
    "",
    Kind::Switch,
    Value("false"),
    "Collect: merge even if some ratios are missing or incomplete.",
);
/// Resuming a batch.
pub const RESUME: &Spec = &cli(
    "resume",
    "--resume",
    "",
    Kind::Switch,
    Value("false"),
    "Batch: skip the scenes whose summary is complete and records the same request; run the rest.",
);
/// Pull-offs at the same time.
pub const JOBS: &Spec = &cli(
    "jobs",
    "--jobs",
    "",
    Kind::Count(1, MAX_JOBS as u64),
    Value("1"),
    "Sweep, crossed and reproduce: pull-offs run at the same time (each opens its own \
     backend; together they must fit in memory).",
);
/// The quick study.
pub const QUICK: &Spec = &cli(
    "quick",
    "--quick",
    "",
    Kind::Switch,
    Value("false"),
    "Reproduce: one coarse grid per ratio (Nx 64 … 256) instead of the full study's three.",
);
/// Timed samples of bench.
pub const REPEATS: &Spec = &cli(
    "repeats",
    "--repeats",
    "",
    Kind::Count(1, MAX_REPEATS as u64),
    Value("5"),
    "Bench: timed samples of the convolution and of the CG solve; the median is reported.",
);
/// CG iterations of one timed solve.
pub const CG_ITERATIONS: &Spec = &cli(
    "cg_iterations",
    "--cg-iterations",
    "",
    Kind::Count(1, MAX_TIMED_CG_ITERATIONS as u64),
    Value("20"),
    "Bench: CG iterations per timed solve (tolerance 0, so exactly this many).",
);
/// The GPU's kernel profile.
pub const PROFILE: &Spec = &cli(
    "profile",
    "--profile",
    "",
    Kind::Switch,
    Value("false"),
    "Bench: also profile the GPU's kernels with timestamp queries (where the adapter has \
     them).",
);
/// The largest grid of bench's timed pull-offs.
pub const PULLOFF_MAX_GRID: &Spec = &cli(
    "pulloff_max_grid",
    "--pulloff-max-grid",
    "elements",
    // 0 times no pull-off; no grid is finer than the largest a run takes.
    Kind::Count(0, super::limits::MAX_GRID as u64),
    Value("128"),
    "Bench: time a whole pull-off only on grids up to this Nx (0: none).",
);
/// The seeds of coverage's rough spheres.
pub const SEEDS: &Spec = &cli(
    "seeds",
    "--seeds",
    "",
    // Every seed the generator takes (its own seed's range).
    Kind::Count(0, u64::MAX),
    Chosen("1, 2, 3"),
    "Coverage: the seeds of the rough spheres' roughness, comma-separated; one scene per seed.",
);
/// The points of a closed-form curve.
pub const POINTS: &Spec = &cli(
    "points",
    "--points",
    "",
    // A curve needs two points; a million already resolves it far below plotting.
    Kind::Count(2, MAX_CURVE_POINTS as u64),
    Value("400"),
    "Theory: the number of points on the curve.",
);
/// The closed form of `theory`.
pub const MODEL: &Spec = &cli(
    "model",
    "--model",
    "",
    Kind::Choice(&["hertz", "jkr", "jg"]),
    Chosen("none: required"),
    "Theory: the closed form: `hertz` (non-adhesive elliptic Hertz), `jkr` (the sphere) or \
     `jg` (Johnson–Greenwood).",
);
/// Replacing write-protected outputs.
pub const FORCE: &Spec = &Spec {
    group: Group::Output,
    ..cli(
        "force",
        "--force",
        "",
        Kind::Switch,
        Value("false"),
        "Replace output files that are write-protected (without it they are refused, as the \
         shell's `>` refuses them).",
    )
};
/// The crossing angle of one pair of cylinders.
pub const ANGLE: &Spec = &both(cli(
    "angle",
    "--angle",
    "degrees",
    CROSSING_ANGLE,
    Chosen("none: required"),
    "Crossed cylinders: the angle θ between the axes (90 is sphere-like; R1/R2 = cot²(θ/2) must \
     stay ≤ 1000, so θ ≥ 3.63). The command line gives several (angles).",
));
/// The crossing angles of `crossed`.
pub const ANGLES: &Spec = &cli(
    "angles",
    "--angles",
    "degrees",
    CROSSING_ANGLE,
    Chosen("90, 70, 50, 30, 16.1"),
    "Crossed: crossing angles θ, comma-separated, 1 to 100 values, none repeated; one \
     pull-off per angle.",
);
/// The cylinders' Young's modulus.
pub const YOUNG: &Spec = &both(cli(
    "young",
    "--young",
    "force/length²",
    INPUT,
    Value("1e6"),
    "Crossed cylinders: Young's modulus E of both (the command line's e).",
));
/// The cylinders' Poisson's ratio.
pub const POISSON: &Spec = &both(cli(
    "poisson",
    "--poisson",
    "",
    Kind::Real(Range::closed(MIN_POISSON, 0.5)),
    Value("0.5"),
    "Crossed cylinders: Poisson's ratio ν of both (0.5 is incompressible; the command line's \
     nu).",
));
/// `crossed`'s flag for the cylinders' Young's modulus.
pub const E: &Spec = &cli(
    "e",
    "--e",
    "force/length²",
    INPUT,
    Value("1e6"),
    "Crossed: Young's modulus E of both cylinders (young).",
);
/// `crossed`'s flag for the cylinders' Poisson's ratio.
pub const NU: &Spec = &cli(
    "nu",
    "--nu",
    "",
    Kind::Real(Range::closed(MIN_POISSON, 0.5)),
    Value("0.5"),
    "Crossed: Poisson's ratio ν of both cylinders (poisson).",
);

/// Every parameter of the other commands that a message names.
pub const STUDY_SPECS: &[&Spec] = &[
    RATIOS,
    GRIDS,
    MAX_GRID,
    FIRST_GRID,
    PHASES,
    TARGET,
    MARGINS,
    VARIANTS,
    MESH_ANGLES,
    APEX_OFFSETS,
    RUNS_PER_CASE,
    SHAPES,
    EXPONENTS,
    HALF_ANGLES,
    BACKENDS,
    PRECISIONS,
    SHARD,
    ALLOW_MISSING,
    RESUME,
    JOBS,
    QUICK,
    REPEATS,
    CG_ITERATIONS,
    PROFILE,
    PULLOFF_MAX_GRID,
    SEEDS,
    POINTS,
    MODEL,
    FORCE,
    ANGLE,
    ANGLES,
    YOUNG,
    POISSON,
    E,
    NU,
];
