//! The table of parameters: one `const` [`Spec`] each (a message names one as `{MARGIN}`), and
//! [`SPECS`], every one of them in the order `--help` shows them.

use super::limits::{
    MAX_CG_ITERATIONS, MAX_CG_TOLERANCE, MAX_EXPONENT, MAX_GRID, MAX_HALF_ANGLE, MAX_INPUT,
    MAX_MARGIN, MAX_MESH_ANGLE, MAX_RATIO, MAX_ROUGHNESS_NODES, MAX_STEPS, MAX_TIME_LIMIT_S,
    MIN_EXPONENT, MIN_FINAL_D_BAR, MIN_GRID, MIN_HALF_ANGLE, MIN_INPUT, MIN_ROUGHNESS_NODES,
    START_RADIUS_RANGE,
};
use super::{cli_only, spec, Fallback, Group, Kind, Range, Spec};

/// A dimensional input's range (R1, R2, E*, Δγ, a, s, the map's spacing).
const INPUT: Kind = Kind::Real(Range::closed(MIN_INPUT, MAX_INPUT));
/// A grid side's range.
const GRID_SIDE: Kind = Kind::PowerOfTwo(MIN_GRID as u64, MAX_GRID as u64);

use Fallback::{Chosen, Value};
use Group::*;

/// The indenter's shape.
pub const INDENTER: &Spec = &spec(
    "indenter",
    "--indenter",
    Scene,
    "",
    Kind::Choice(&["cone", "ellipsoid", "flat-punch", "height-map", "power-law"]),
    Value("ellipsoid"),
    "The indenter's shape: `ellipsoid` (⟨ratio⟩ or ⟨r1⟩, ⟨r2⟩), `flat-punch` (⟨radius⟩), \
     `power-law` (h = s·rⁿ: ⟨exponent⟩, ⟨scale⟩), `cone` (h = r·cot α: ⟨half_angle⟩) or \
     `height-map` (⟨height_map⟩, ⟨spacing⟩). The ellipsoid has a convergence law; the others run \
     one grid by default, set beside the closed form of their Δx → 0 limit where one exists \
     (Kendall; the power law's and the cone's JKR solutions), and \
     ⟨accuracy⟩ or ⟨extrapolate⟩ extrapolate them over grids and grid phases without a law.",
);
/// R1/R2 of the ellipsoid.
pub const RATIO: &Spec = &spec(
    "ratio",
    "--ratio",
    Scene,
    "",
    Kind::Real(Range::closed(1.0, MAX_RATIO)),
    Chosen("5, where ⟨r1⟩ is not given"),
    "Axis ratio R1/R2 of the ellipsoid (1 is a sphere). Not with ⟨r1⟩, which sets it.",
);
/// The ellipsoid's R1.
pub const R1: &Spec = &spec(
    "r1",
    "--r1",
    Scene,
    "length",
    INPUT,
    Chosen("⟨ratio⟩ × ⟨r2⟩"),
    "Radius of curvature along x, the major axis (R2 ≤ R1 ≤ 1000 R2).",
);
/// The ellipsoid's R2.
pub const R2: &Spec = &spec(
    "r2",
    "--r2",
    Scene,
    "length",
    INPUT,
    Chosen("1"),
    "Radius of curvature along y, the minor axis.",
);
/// E*.
pub const E_STAR: &Spec = &spec(
    "e_star",
    "--e-star",
    Scene,
    "force/length²",
    INPUT,
    Value("1"),
    "Effective modulus E* = E/(1−ν²) of the half-space.",
);
/// Δγ.
pub const WORK_OF_ADHESION: &Spec = &spec(
    "work_of_adhesion",
    "--work-of-adhesion",
    Scene,
    "force/length",
    INPUT,
    Value("1"),
    "Work of adhesion Δγ (energy per area).",
);
/// The flat punch's radius.
pub const RADIUS: &Spec = &spec(
    "radius",
    "--radius",
    Scene,
    "length",
    INPUT,
    Chosen("1"),
    "Flat punch: the face's radius a. Forces are normalised by Kendall's pull-off force \
     √(8π E* Δγ a³), lengths by a.",
);
/// The power law's exponent.
pub const EXPONENT: &Spec = &spec(
    "exponent",
    "--exponent",
    Scene,
    "",
    Kind::Real(Range::closed(MIN_EXPONENT, MAX_EXPONENT)),
    Chosen("2"),
    "Power law h = s·rⁿ: the exponent n (2 is the sphere of radius 1/(2s)).",
);
/// The cone's half-angle.
pub const HALF_ANGLE: &Spec = &spec(
    "half_angle",
    "--half-angle",
    Scene,
    "degrees",
    Kind::Real(Range::closed(MIN_HALF_ANGLE, MAX_HALF_ANGLE)),
    Chosen("70"),
    "Cone h = r·cot α: the half-angle α between the axis and the flank. Results are normalised \
     by the cone's exact pull-off: forces by 54 Δγ² tan³α / (π E*), lengths by twice its contact \
     radius there, 36 Δγ tan²α / (π E*), approaches by the way from there to the end of \
     contact, 4 Δγ tan α / E*.",
);
/// The power law's factor.
pub const SCALE: &Spec = &spec(
    "scale",
    "--scale",
    Scene,
    "length^(1−n)",
    INPUT,
    Chosen("0.5: with n = 2, the sphere of radius 1"),
    "Power law h = s·rⁿ: the factor s.",
);
/// The height map.
pub const HEIGHT_MAP: &Spec = &spec(
    "height_map",
    "--height-map",
    Scene,
    "length",
    Kind::File,
    Chosen("none"),
    "Height map: the heights (larger is further from the half-space), a NumPy .npy of \
     float64/float32 or a text grid (one row per line, values separated by spaces or commas, \
     # comments), rows along y; from Python also a 2-D array. Its apex (where a quadratic \
     fitted around the lowest node is lowest) is placed at the domain's centre; the fit's \
     principal radii size the domain and normalise the results like an ellipsoid's.",
);
/// The height map's spacing.
pub const SPACING: &Spec = &spec(
    "spacing",
    "--spacing",
    Scene,
    "length",
    INPUT,
    Chosen("none: required with a height map"),
    "Height map: the spacing of its nodes.",
);
/// Roughness added to a base shape.
pub const ROUGHNESS: &Spec = &spec(
    "roughness",
    "--roughness",
    Scene,
    "length",
    Kind::File,
    Chosen("none"),
    "Roughness added to the indenter (an ellipsoid, power law or flat punch): a height map \
     (.npy or text, as ⟨height_map⟩; from Python also a 2-D array) of node spacing ⟨spacing⟩, \
     centred on the apex, its mean taken off. The base shape still normalises the results. The \
     map must cover the domain. A rough shape is pressed on (⟨preload_depth⟩).",
);
/// The window of a height map that is the domain, along x.
pub const WINDOW_X: &Spec = &spec(
    "window_x",
    "--window-x",
    Scene,
    "length",
    Kind::Pair(Range::closed(-MAX_INPUT, MAX_INPUT)),
    Chosen("the whole map"),
    "Height map: the domain's extent along x, x0,x1, in the map's coordinates (centred on \
     the map). With ⟨window_y⟩; the default is the whole map, unless the map is convex about \
     its lowest node and holds the first contact of c̄0 (then the domain is that contact and \
     its margin, as for an ellipsoid). Under ⟨convolution⟩ periodic the domain is the map's \
     whole period (n nodes at spacing s: n·s), the default; a window given must span it.",
);
/// The window of a height map that is the domain, along y.
pub const WINDOW_Y: &Spec = &spec(
    "window_y",
    "--window-y",
    Scene,
    "length",
    Kind::Pair(Range::closed(-MAX_INPUT, MAX_INPUT)),
    Chosen("the whole map"),
    "Height map: the domain's extent along y, y0,y1 (see ⟨window_x⟩).",
);
/// Nx.
pub const GRID: &Spec = &spec(
    "grid",
    "--grid",
    Model,
    "elements",
    GRID_SIDE,
    Chosen("256 with a one-grid parameter; without any, ⟨accuracy⟩ 2%"),
    "Elements along x, Nx (within the machine's memory). The domain is the initial contact \
     plus the margin, so Δx = 2·a0·(1 + margin)/Nx. A grid that leaves fewer than 8 elements \
     across the first contact's minor axis (or an expected 4 at the force minimum) is refused \
     with the grid that resolves it. Giving it (or ⟨grid_y⟩, ⟨steps⟩, ⟨onsets⟩, ⟨measure⟩, \
     ⟨regrid⟩, ⟨final_d⟩) runs that one grid, whose estimate states its expected bias.",
);
/// Ny.
pub const GRID_Y: &Spec = &spec(
    "grid_y",
    "--grid-y",
    Model,
    "elements",
    GRID_SIDE,
    Chosen("fitted to the contact's aspect"),
    "Elements along y, Ny.",
);
/// c̄0.
pub const START_RADIUS: &Spec = &spec(
    "start_radius",
    "--start-radius",
    Model,
    "c_r",
    Kind::Real(Range::closed(START_RADIUS_RANGE.0, START_RADIUS_RANGE.1)),
    Chosen("1.5"),
    "Mean radius c̄0 of the initial non-adhesive contact: the JKR branch is traced for all \
     c̄ ≤ c̄0. Not for the flat punch, whose first contact is its face.",
);
/// Load steps.
pub const STEPS: &Spec = &spec(
    "steps",
    "--steps",
    Model,
    "",
    Kind::Count(1, MAX_STEPS as u64),
    Chosen("200; 20 with ⟨measure⟩ adhesive-force without ⟨regrid⟩"),
    "Load steps from the initial approach d̄0 to the expected end of contact.",
);
/// Which onsets.
pub const ONSETS: &Spec = &spec(
    "onsets",
    "--onsets",
    Model,
    "",
    Kind::Choice(&["near-minimum", "all", "none"]),
    Chosen("near-minimum"),
    "Which detachment onsets (the sawtooth's local minima) to locate and record. Every step's \
     end state is the same whichever is chosen. `near-minimum`: only the onsets of the steps \
     that can hold the force minimum (the same force minimum as `all`; the cheapest); `all`: \
     every onset of every step; `none`: whole steps only (the force minimum then depends on \
     ⟨steps⟩).",
);
/// What a run is for.
pub const MEASURE: &Spec = &spec(
    "measure",
    "--measure",
    Model,
    "",
    Kind::Choice(&["curve", "adhesive-force"]),
    Chosen("curve"),
    "What to compute: the whole `curve`, or only the `adhesive-force` (stops once the force \
     minimum is confirmed; cheaper).",
);
/// Re-gridding.
pub const REGRID: &Spec = &spec(
    "regrid",
    "--regrid",
    Model,
    "",
    Kind::Switch,
    Value("false"),
    "Re-grid as the contact shrinks: once the contact and its margin fit in 80 % of the \
     domain, the same Nx × Ny is laid over a domain fitted to it (finer Δx).",
);
/// The final approach.
pub const FINAL_D: &Spec = &spec(
    "final_d",
    "--final-d",
    Model,
    "",
    Kind::Real(Range::closed(MIN_FINAL_D_BAR, 1000.0)),
    Chosen("none: to the end of contact"),
    "Stop at this approach d̄ if the contact has not vanished by then (below d̄0). A run \
     stopped before the force minimum says so and reports no adhesive force.",
);
/// The margin.
pub const MARGIN: &Spec = &spec(
    "margin",
    "--margin",
    Model,
    "relative",
    Kind::Real(Range::closed(0.0, MAX_MARGIN)),
    Chosen("0.08, or at least one element on each side: 0.143 on a 16-element grid"),
    "Free margin around the initial contact, relative to its half-axes.",
);
/// The loading phase's depth.
pub const PRELOAD_DEPTH: &Spec = &spec(
    "preload_depth",
    "--preload-depth",
    Model,
    "length",
    Kind::Real(Range::closed(-MAX_INPUT, MAX_INPUT)),
    Chosen(
        "none: a smooth shape starts from its first contact of c̄0 built in one piece; a \
            height map or rough shape is pressed to that approach, or to ⟨preload_area⟩ 0.1",
    ),
    "Press the indenter on to this approach d (the states' d, from the apex or the map's \
     lowest node), elements attaching where their gap closes, then pull it off. One of \
     ⟨preload_depth⟩, ⟨preload_force⟩, ⟨preload_area⟩.",
);
/// The loading phase's force.
pub const PRELOAD_FORCE: &Spec = &spec(
    "preload_force",
    "--preload-force",
    Model,
    "force",
    INPUT,
    Chosen("none"),
    "Press on until the compressive force reaches this (the user's force unit), then pull off.",
);
/// The loading phase's contact area.
pub const PRELOAD_AREA: &Spec = &spec(
    "preload_area",
    "--preload-area",
    Model,
    "fraction of the domain",
    Kind::Real(Range {
        lo: 0.0,
        hi: 1.0,
        lo_open: true,
        hi_open: true,
    }),
    Chosen("none"),
    "Press on until the contact covers this fraction of the domain, then pull off.",
);
/// The mesh angle.
pub const MESH_ANGLE: &Spec = &spec(
    "mesh_angle",
    "--mesh-angle",
    Model,
    "degrees",
    Kind::Real(Range::closed(-MAX_MESH_ANGLE, MAX_MESH_ANGLE)),
    Value("0"),
    "Angle between the ellipsoid's major axis and the grid's x axis. The domain is the box \
     around the turned initial contact. Use it to check results where crack fronts run along \
     grid lines (e.g. 45).",
);
/// The apex's offset.
pub const APEX_OFFSET: &Spec = &spec(
    "apex_offset",
    "--apex-offset",
    Model,
    "elements",
    Kind::Pair(Range::closed(-0.5, 0.5)),
    Value("0,0"),
    "Where the apex lies within the element grid, along x and y: 0,0 on the corner between \
     the four middle elements, 0.5,0.5 on the centre of one. It moves where the contact's edge \
     falls between element centres (the grid phase).",
);
/// CG's tolerance.
pub const CG_TOLERANCE: &Spec = &spec(
    "cg_tolerance",
    "--cg-tolerance",
    Solver,
    "",
    Kind::Real(Range {
        lo: 0.0,
        hi: MAX_CG_TOLERANCE,
        lo_open: true,
        hi_open: false,
    }),
    Value("1e-8"),
    "CG stops when its relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ reaches this. A solve \
     that stagnates, diverges or reaches ⟨cg_max_iterations⟩ is retried once in a safer mode; \
     f32 (the GPU backend) cannot bring the true residual much below 1e-7. At most 1e-5: the \
     stated uncertainty takes each state's solve as exact (on the sphere 1e-4 moves |min F̄| \
     by 1.4e-4 relative, 1e-3 by 0.13 %, 1e-2 by 2.7 %).",
);
/// CG's iteration limit.
pub const CG_MAX_ITERATIONS: &Spec = &spec(
    "cg_max_iterations",
    "--cg-max-iterations",
    Solver,
    "",
    Kind::Count(1, MAX_CG_ITERATIONS as u64),
    Value("5000"),
    "CG iteration limit per solve (its safer retry gets as many again).",
);
/// The residual a failed solve is accepted at.
pub const CG_ACCEPT: &Spec = &spec(
    "cg_accept",
    "--cg-accept",
    Solver,
    "",
    Kind::Real(Range::open(0.0, 1.0)),
    Value("1e-5"),
    "Relative residual up to which a CG solve that missed ⟨cg_tolerance⟩ even in the safer \
     retry is accepted: the run goes on, warns and records the residual. Above it the run \
     stops with an error.",
);
/// How often CG's residual is read.
pub const CG_CHECK_EVERY: &Spec = &spec(
    "cg_check_every",
    "--cg-check-every",
    Solver,
    "iterations",
    Kind::Count(1, 100_000),
    Chosen("the backend's own: 1 on the CPU, 8 on the GPU"),
    "Read CG's residual back to the host every this many iterations.",
);
/// The limit on detachment/attachment sweeps per load step.
pub const MAX_SWEEPS: &Spec = &spec(
    "max_sweeps",
    "--max-sweeps",
    Solver,
    "",
    Kind::Count(1, 1_000_000),
    Value("2000"),
    "Limit on the detachment/attachment sweeps (cascade rounds) of one load step: a step that \
     needs more stops the run with an error rather than loop.",
);
/// The preconditioner.
pub const PRECONDITIONER: &Spec = &spec(
    "preconditioner",
    "--preconditioner",
    Solver,
    "",
    Kind::Choice(&["stiffness", "none"]),
    Value("stiffness"),
    "CG preconditioner: the half-space stiffness in Fourier space, or none.",
);
/// Exact cascades.
pub const EXACT_CASCADE: &Spec = &spec(
    "exact_cascade",
    "--exact-cascade",
    Solver,
    "",
    Kind::Switch,
    Value("false"),
    "Solve every round of a detachment cascade to ⟨cg_tolerance⟩. By default the rounds between \
     are solved only as far as needed to tell which elements are over σ_c, and the last round \
     is exact: the same states at a fraction of the CG iterations.",
);
/// The backend.
pub const BACKEND: &Spec = &spec(
    "backend",
    "--backend",
    Solver,
    "",
    Kind::Choice(&["auto", "cpu", "gpu"]),
    Value("auto"),
    "Backend: `cpu` (f64, rustfft), `gpu` (f32, wgpu; the best adapter, a software one such as \
     lavapipe included) or `auto` (a hardware GPU if present, else the CPU).",
);
/// The convolution's arithmetic.
pub const PRECISION: &Spec = &spec(
    "precision",
    "--precision",
    Solver,
    "",
    Kind::Choice(&["auto", "f64", "f32"]),
    Value("auto"),
    "Arithmetic of the convolution's FFT passes: `auto` (the backend's own: f64 on the CPU, \
     f32 on the GPU), `f64` (the CPU only: the reference; with ⟨backend⟩ auto it takes the \
     CPU) or `f32` (the GPU, or on the CPU the FFT passes at twice the SIMD width, its \
     vectors and sums still f64; CG's tolerance is then raised to f32's floor, 2e-7).",
);
/// The convolution.
pub const CONVOLUTION: &Spec = &spec(
    "convolution",
    "--convolution",
    Solver,
    "",
    Kind::Choice(&["padded", "periodic"]),
    Value("padded"),
    "Convolution: `padded` (an isolated contact: zero padding, the exact non-periodic sum) or \
     `periodic` (a surface periodic over the domain, such as a nominally flat rough surface or \
     a wave: the elements' influence summed over the periodic images, the approach measured \
     from the elastic surface's mean plane; an isolated contact would feel its images). \
     Periodic is for a height map that is one period of its surface: the domain is its period \
     n·s × m·s (heights wrap across the seam), and a map that is not periodic is refused.",
);
/// Extrapolation.
pub const EXTRAPOLATE: &Spec = &spec(
    "extrapolate",
    "--extrapolate",
    Plan,
    "",
    Kind::Switch,
    Value("false"),
    "Run the scene on the grids of ⟨extrapolate_grids⟩ (instead of ⟨grid⟩) and fit |min F̄|, c̄ and \
     d̄ at the minimum together to their Δx → 0 limits, each with its stated uncertainty.",
);
/// The extrapolation's grids.
pub const EXTRAPOLATE_GRIDS: &Spec = &spec(
    "extrapolate_grids",
    "--extrapolate-grids",
    Plan,
    "elements",
    Kind::Grids(MIN_GRID as u64, MAX_GRID as u64),
    Chosen(
        "the coarsest grid that resolves the contact at the force minimum and its two doublings",
    ),
    "Grids Nx for ⟨extrapolate⟩, coarse to fine.",
);
/// The accuracy aimed at.
pub const ACCURACY: &Spec = &spec(
    "accuracy",
    "--accuracy",
    Plan,
    "",
    Kind::Fraction(0.001, 0.5),
    Chosen("2% unless one grid or ⟨extrapolate⟩ is asked for"),
    "Reach this relative accuracy of the adhesive force |min F̄| at Δx → 0 at the least cost: \
     chooses the grids, the domain, the load steps and what to compute, and says what it chose \
     (⟨grid⟩, ⟨grid_y⟩, ⟨steps⟩, ⟨onsets⟩, ⟨measure⟩, ⟨regrid⟩, ⟨final_d⟩ and ⟨extrapolate⟩ are \
     refused beside it). The CLI writes a \
     percentage with its unit (`1%`), Python a fraction (0.01).",
);
/// The time limit.
pub const TIME_LIMIT: &Spec = &spec(
    "time_limit",
    "--time-limit",
    Plan,
    "s",
    Kind::Seconds(1.0, MAX_TIME_LIMIT_S),
    Chosen("none"),
    "Wall-clock time a run to an accuracy may take (the CLI writes it with its unit: `90s`, \
     `20min`, `2h`; Python in seconds). The coarsest grid that resolves the contact runs first; \
     a grid still running at the limit is stopped and the answer comes from the grids that \
     finished, with `target_met` false if that misses the target.",
);
/// The fields kept.
pub const FIELDS: &Spec = &spec(
    "fields",
    "--fields",
    Output,
    "",
    Kind::States,
    Value("none"),
    "The states whose fields (pressure, gap, contact set) are kept: `minimum` (the force \
     minimum), `every:K` (every K-th state and the minimum) or `states:I,J` (those states, \
     counted from 0, and the minimum). The CLI writes them to <⟨out⟩>.fields.npz and the pressure \
     at the minimum to <out>.pressure.svg, with its profiles along x and y (beside JKR's for \
     the sphere) in <out>.profile.svg. Each is the state's contact set solved again on the \
     CPU (f64).",
);
/// The formats every chart is written in.
pub const FIGURE_FORMAT: &Spec = &cli_only(spec(
    "figure_format",
    "--figure-format",
    Output,
    "",
    Kind::Choices(&["svg", "pdf", "png"]),
    Value("svg"),
    "The formats every chart is written in, e.g. `svg,pdf,png`, beside each other with one \
     stem (f_of_d.svg, f_of_d.pdf, f_of_d.png): `svg`; `pdf`, one page at the picture's size \
     (96 pixels per inch), its text in the built-in DejaVu Sans; `png`, 300 dpi on white. \
     Whatever they are, each chart's data goes to <stem>.plot.csv beside it, one row per point \
     drawn (series, style, x, y, error) or, for a pressure map, per cell drawn (x, y, p, \
     width, height). Here the pressure map of ⟨fields⟩; sweep, collect, crossed, accuracy, \
     bench and reproduce take it too.",
));
/// The states CSV.
pub const OUT: &Spec = &cli_only(spec(
    "out",
    "--out",
    Output,
    "",
    Kind::File,
    Chosen("jkrbem-out/simulate-r<ratio>-n<grid>.csv"),
    "States CSV. While running the states go to <stem>.incomplete-<pid>.csv beside it; only a \
     complete run renames that to this name, and an existing file here is untouched until then. \
     `-` writes the states CSV to standard output once the run ends (one grid only; the other \
     lines then go to standard error).",
));
/// The summary JSON.
pub const SUMMARY: &Spec = &cli_only(spec(
    "summary",
    "--summary",
    Output,
    "",
    Kind::File,
    Chosen("none"),
    "Also write the summary as JSON to this file (not the ⟨out⟩ file). `-` writes it to standard \
     output, and the summary's text then goes to standard error.",
));

/// Every parameter of a simulation, in the order `--help` shows them.
pub const SPECS: &[&Spec] = &[
    INDENTER,
    RATIO,
    R1,
    R2,
    E_STAR,
    WORK_OF_ADHESION,
    RADIUS,
    EXPONENT,
    HALF_ANGLE,
    SCALE,
    HEIGHT_MAP,
    SPACING,
    ROUGHNESS,
    WINDOW_X,
    WINDOW_Y,
    GRID,
    GRID_Y,
    START_RADIUS,
    STEPS,
    ONSETS,
    MEASURE,
    REGRID,
    FINAL_D,
    MARGIN,
    PRELOAD_DEPTH,
    PRELOAD_FORCE,
    PRELOAD_AREA,
    MESH_ANGLE,
    APEX_OFFSET,
    CG_TOLERANCE,
    CG_MAX_ITERATIONS,
    CG_ACCEPT,
    CG_CHECK_EVERY,
    MAX_SWEEPS,
    PRECONDITIONER,
    EXACT_CASCADE,
    BACKEND,
    PRECISION,
    CONVOLUTION,
    EXTRAPOLATE,
    EXTRAPOLATE_GRIDS,
    ACCURACY,
    TIME_LIMIT,
    FIELDS,
    FIGURE_FORMAT,
    OUT,
    SUMMARY,
];

// The roughness generator (`jkrbem roughness`, Python's `jkrbem.roughness`): its own parameters.
// It shares ⟨grid⟩, ⟨grid_y⟩ (nodes, any count from 4 to 16384 there) and ⟨spacing⟩ with a
// simulation; these are in [`ROUGHNESS_SPECS`], which no simulation takes.

/// The surface's Hurst exponent.
pub const HURST: &Spec = &spec(
    "hurst",
    "--hurst",
    Study,
    "",
    Kind::Real(Range {
        lo: 0.0,
        hi: 1.0,
        lo_open: true,
        hi_open: false,
    }),
    Chosen("none: required"),
    "Roughness: the Hurst exponent H of the self-affine surface, whose power spectrum falls as \
     q^(−2(1+H)) between the roll-off and the cut-off (fractal dimension 3 − H).",
);
/// The surface's rms height.
pub const RMS_HEIGHT: &Spec = &spec(
    "rms_height",
    "--rms-height",
    Study,
    "length",
    INPUT,
    Chosen("none: give it or ⟨rms_slope⟩"),
    "Roughness: the root-mean-square height of the surface about its mean, met exactly on the \
     grid's nodes. Not with ⟨rms_slope⟩.",
);
/// The surface's rms slope.
pub const RMS_SLOPE: &Spec = &spec(
    "rms_slope",
    "--rms-slope",
    Study,
    "",
    INPUT,
    Chosen("none: give it or ⟨rms_height⟩"),
    "Roughness: the root-mean-square gradient |∇h| of the surface (dimensionless), computed \
     spectrally (of the band-limited surface through the nodes) and met exactly. Not with \
     ⟨rms_height⟩.",
);
/// The roll-off wavelength λ_r.
pub const ROLLOFF: &Spec = &spec(
    "rolloff",
    "--rolloff",
    Study,
    "length",
    INPUT,
    Chosen("⟨largest_wavelength⟩: a power law down to it, no plateau"),
    "Roughness: the roll-off wavelength λ_r: the spectrum is flat for wavelengths from it up to \
     ⟨largest_wavelength⟩ and a power law below it. At most ⟨largest_wavelength⟩, longer than \
     ⟨cutoff⟩.",
);
/// The short-wavelength cut-off λ_s.
pub const CUTOFF: &Spec = &spec(
    "cutoff",
    "--cutoff",
    Study,
    "length",
    INPUT,
    Chosen("4 × ⟨spacing⟩: the shortest wave sampled by 4 nodes"),
    "Roughness: the short-wavelength cut-off λ_s: no wave shorter than it. At least 2 × \
     ⟨spacing⟩ (the grid's Nyquist wavelength); a longer one resolves the surface's slopes \
     and curvatures better on the grid.",
);
/// The largest wavelength λ_L.
pub const LARGEST_WAVELENGTH: &Spec = &spec(
    "largest_wavelength",
    "--largest-wavelength",
    Study,
    "length",
    INPUT,
    Chosen("the domain: max(⟨grid⟩, ⟨grid_y⟩) × ⟨spacing⟩"),
    "Roughness: the longest wavelength with power: no wave longer than it (the surface is \
     periodic over the domain). At most the domain's longer side.",
);
/// The random seed.
pub const SEED: &Spec = &spec(
    "seed",
    "--seed",
    Study,
    "",
    Kind::Count(0, u64::MAX),
    Value("0"),
    "Roughness: the seed of the random numbers. The same seed and parameters give the same \
     surface on every machine (to the rounding of the FFT); another seed an independent one.",
);

/// The roughness generator's ⟨grid⟩: nodes along x, any count (not a simulation's power of
/// two). The same parameter as [`GRID`] in messages (its name and flag); its own range.
pub const ROUGHNESS_GRID: &Spec = &spec(
    "grid",
    "--grid",
    Study,
    "nodes",
    // A map needs 4 nodes a side; past 16384 its transforms leave any machine's memory (and
    // the total is capped lower still, at MAX_TOTAL_NODES).
    Kind::Count(MIN_ROUGHNESS_NODES as u64, MAX_ROUGHNESS_NODES as u64),
    Chosen("none: required"),
    "Roughness: nodes along x, nx (any count, though a power of two transforms fastest).",
);
/// The roughness generator's ⟨grid_y⟩: nodes along y (see [`ROUGHNESS_GRID`]).
pub const ROUGHNESS_GRID_Y: &Spec = &spec(
    "grid_y",
    "--grid-y",
    Study,
    "nodes",
    Kind::Count(MIN_ROUGHNESS_NODES as u64, MAX_ROUGHNESS_NODES as u64),
    Chosen("as ⟨grid⟩"),
    "Roughness: nodes along y, ny.",
);

/// The roughness generator's own parameters (it also takes ⟨grid⟩, ⟨grid_y⟩ and ⟨spacing⟩),
/// in the order its `--help` shows them.
pub const ROUGHNESS_SPECS: &[&Spec] = &[
    HURST,
    RMS_HEIGHT,
    RMS_SLOPE,
    ROLLOFF,
    CUTOFF,
    LARGEST_WAVELENGTH,
    SEED,
];
