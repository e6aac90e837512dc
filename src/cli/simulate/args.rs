//! The flags of `jkrbem simulate`, with their units and ranges (`--help` shows these
//! comments).

use super::super::parse;
use super::indenter::IndenterArgs;
use jkrbem::analysis::fields::FieldChoice;
use jkrbem::backend::select::BackendKind;
use jkrbem::backend::Preconditioner;
use jkrbem::model::{Measure, Onsets};
use jkrbem::run::open::Convolution;
use std::path::PathBuf;
use std::time::Duration;

/// Arguments of `jkrbem simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The indenter (--indenter and its shape's parameters).
    #[command(flatten)]
    pub shape: IndenterArgs,
    /// Axis ratio R1/R2 of the ellipsoid, in [1, 1000] (1 is a sphere) [default: 5]. Not
    /// with --r1, which sets it.
    #[arg(long)]
    pub ratio: Option<f64>,
    /// Radius of curvature along x, the major axis (length L, in [1e-30, 1e30], R2 ≤ R1 ≤
    /// 1000 R2). Overrides --ratio.
    #[arg(long)]
    pub r1: Option<f64>,
    /// Radius of curvature along y, the minor axis (length L, in [1e-30, 1e30]) [default: 1].
    #[arg(long)]
    pub r2: Option<f64>,
    /// Effective modulus E* = E/(1−ν²) of the half-space (force/length², F/L², in
    /// [1e-30, 1e30]).
    #[arg(long, default_value_t = 1.0)]
    pub e_star: f64,
    /// Work of adhesion Δγ (energy per area, F/L, in [1e-30, 1e30]).
    #[arg(long, default_value_t = 1.0)]
    pub work_of_adhesion: f64,
    /// Elements along x, Nx (a power of two from 16 to 65536, within the machine's memory).
    /// The domain is the initial contact plus the margin, so Δx = 2·a0·(1 + margin)/Nx. A grid
    /// that leaves fewer than 8 elements across the first contact's minor axis (or an
    /// expected 4 at the force minimum) is refused with the grid that resolves it. Giving it
    /// (or any of --grid-y, --steps, --onsets, --measure, --regrid, --final-d) runs that one
    /// grid, whose estimate states its expected bias [default: 256 with those flags; without
    /// any of them, `--accuracy 2%`].
    #[arg(long)]
    pub grid: Option<usize>,
    /// Elements along y, Ny (a power of two from 16 to 65536); by default fitted to the
    /// contact's aspect.
    #[arg(long)]
    pub grid_y: Option<usize>,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r, in [1, 20]): the JKR
    /// branch is traced for all c̄ ≤ c̄0 [default: 1.5]. Not for the flat punch, whose first
    /// contact is its face.
    #[arg(long)]
    pub start_radius: Option<f64>,
    /// Load steps from the initial approach d̄0 to the expected end of contact (1 to 100000)
    /// [default: 200; 20 with --measure adhesive-force without --regrid, whose answer does not
    /// depend on them: the steps that can hold the minimum are searched for their onsets].
    #[arg(long)]
    pub steps: Option<usize>,
    /// Which detachment onsets (the sawtooth's local minima) to locate and record. Every
    /// step's end state is the same whichever is chosen. `near-minimum`: steps are taken
    /// whole and only the onsets of the steps that can hold the force minimum are located
    /// (the force minimum is the same as with `all`; the cheapest); `all`: every onset of every
    /// step, the full sawtooth; `none`: whole steps only (the force minimum then depends on
    /// --steps) [default: near-minimum]. The states CSV says which it holds (`onsets` column).
    #[arg(long, value_enum)]
    pub onsets: Option<Onsets>,
    /// What to compute: the whole `curve`, or only the `adhesive-force` (stops once the force
    /// minimum is confirmed, refining load steps only near it; cheaper) [default: curve].
    #[arg(long, value_enum)]
    pub measure: Option<Measure>,
    /// Re-grid as the contact shrinks: once the contact and its margin fit in 80 % of the
    /// domain, the same Nx × Ny is laid over a domain fitted to it (finer Δx, σ_c recomputed,
    /// the contact carried over and re-equilibrated).
    #[arg(long)]
    pub regrid: bool,
    /// Stop at this approach d̄ if the contact has not vanished by then (dimensionless, in
    /// [−1000, d̄0)). A run stopped before the force minimum says so and reports no adhesive
    /// force (`min_reached: false`).
    #[arg(long)]
    pub final_d: Option<f64>,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10])
    /// [default: 0.08, or at least one element on each side: 0.143 on a 16-element grid].
    #[arg(long)]
    pub margin: Option<f64>,
    /// Angle between the ellipsoid's major axis and the grid's x axis (degrees). The domain
    /// is the box around the turned initial contact (square at 45°), and ā, b̄ are measured
    /// along the turned axes. Use it to check results where crack fronts run along grid
    /// lines, at the ends of a slender ellipse's axes (e.g. 45). In [−360, 360].
    #[arg(long, default_value_t = 0.0)]
    pub mesh_angle: f64,
    /// Where the apex lies within the element grid, as two fractions of an element along x
    /// and y, each in [−0.5, 0.5] (default 0,0: on the corner between the four middle
    /// elements; 0.5,0.5 puts it on the centre of one).
    /// It moves where the contact's edge falls between element centres (the "grid phase"),
    /// which shifts |min F̄| by a few tenths of a per cent on any grid.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 0.0])]
    pub apex_offset: Vec<f64>,
    /// CG stops when its relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ reaches this
    /// (dimensionless). A solve that stagnates, diverges, reaches --cg-max-iterations, or
    /// whose true residual (recomputed from p) stays above 100 × this is retried once in a
    /// safer mode; f32 (the GPU backend) cannot bring the true residual much below 1e-7.
    #[arg(long, default_value_t = 1e-8)]
    pub cg_tolerance: f64,
    /// CG iteration limit per solve, 1 to 10000000 (its safer retry gets as many again).
    #[arg(long, default_value_t = 5000)]
    pub cg_max_iterations: usize,
    /// Relative residual (dimensionless) up to which a CG solve that missed --cg-tolerance
    /// even in the safer retry is accepted: the run goes on, warns, and writes the residual
    /// of each state in the cg_residual column. Above it the run stops with an error.
    #[arg(long, default_value_t = 1e-5)]
    pub cg_accept: f64,
    /// Read CG's residual back to the host every this many iterations, 1 to 100000 [default:
    /// the backend's own: 1 on the CPU, 8 on the GPU, which stops the iterations queued past
    /// convergence itself].
    #[arg(long, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=100_000))]
    pub cg_check_every: Option<usize>,
    /// CG preconditioner.
    #[arg(long, value_enum, default_value_t = Preconditioner::Stiffness)]
    pub preconditioner: Preconditioner,
    /// Solve every round of a detachment cascade to --cg-tolerance, each from p as the sweep
    /// left it. By default the rounds between are solved only as far as needed to tell which
    /// elements are over σ_c (to 1e-5, detaching only those beyond it by twice CG's error
    /// estimate; a round that detaches nothing is solved again to 1e-6 before the exact
    /// solve), each starts from the detached load handed on, the elements a bound proves to
    /// follow are detached without a solve, and the last round is exact: the same states at
    /// a fraction of the CG iterations.
    #[arg(long)]
    pub exact_cascade: bool,
    /// Backend: `cpu` (f64, rustfft), `gpu` (f32, wgpu; the best adapter, a software one such
    /// as lavapipe included) or `auto` (a hardware GPU if present, else the CPU).
    #[arg(long, value_enum, default_value_t = BackendKind::Auto)]
    pub backend: BackendKind,
    /// Convolution: `padded` (exact) or `periodic` (no padding, so the contact interacts with
    /// its periodic images a margin away: only to see the error padding removes; CPU only).
    #[arg(long, value_enum, default_value_t = Convolution::Padded)]
    pub convolution: Convolution,
    /// States CSV [default: jkrbem-out/simulate-r<ratio>-n<grid>.csv]. While running, the
    /// states go to <stem>.incomplete-<pid>.csv beside it (unique to the run); only a complete
    /// run renames that to this name, and an existing file here is untouched until then. A
    /// run that fails keeps the partial name. A second run on the same file is refused while
    /// this one holds it. `-` writes the states CSV to standard output once the run ends (one
    /// grid only; the other lines then go to standard error).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write the summary as JSON to this file (not the --out file). `-` writes it to
    /// standard output, and the summary's text then goes to standard error.
    #[arg(long)]
    pub summary: Option<PathBuf>,
    /// Also write the fields of chosen states of the last grid's run: `minimum` (the state of
    /// the force minimum), `every:K` (every K-th state, and the minimum) or `states:I,J` (those
    /// states, counted from 0 as the states CSV's rows, and the minimum). They go to
    /// <out>.fields.npz (numpy's format: pressure p in force/length², gap g in length and the
    /// contact set, shape (states, ny, nx), with x and y in length and the units inside), and
    /// the pressure at the minimum to <out>.pressure.svg (a heat map with the contact's outline).
    /// Each field is the state's contact set solved again on the CPU (f64) at its approach.
    #[arg(long, value_parser = parse_fields, default_value = "none")]
    pub fields: FieldChoice,
    /// Run the scene on the grids of --extrapolate-grids (instead of --grid) and fit |min F̄|,
    /// c̄ and d̄ at the minimum together to their Δx → 0 limits (first order in 1/n_d, the
    /// law's k as a prior; physics §7), each with its stated uncertainty.
    #[arg(long)]
    pub extrapolate: bool,
    /// Grids Nx for --extrapolate, coarse to fine (2 to 8 increasing powers of two, each as
    /// --grid) [default: the grids that fit the scene: the coarsest predicted to resolve the
    /// contact at the force minimum (about 20 elements across its minor axis, as --accuracy
    /// asks of its grids) and its two doublings; 64,128,256 for a sphere].
    #[arg(long, value_delimiter = ',')]
    pub extrapolate_grids: Option<Vec<usize>>,
    /// Reach this relative accuracy of the adhesive force |min F̄| at Δx → 0 (a percentage in
    /// [0.1 %, 50 %]: `5%`, `1%`; the unit is required) at the least cost: chooses the grid
    /// (or two grids fitted together), the domain, the load steps and what to compute so that
    /// the stated uncertainty is predicted within it (physics §7), says what it chose, and
    /// overrides --grid, --grid-y, --steps, --onsets, --measure, --regrid and --extrapolate.
    /// A target no grid that fits in memory reaches is refused, naming the finest reachable
    /// [default: 2% unless one grid or --extrapolate is asked for].
    #[arg(long, value_parser = parse::percentage)]
    pub accuracy: Option<f64>,
    /// Wall-clock time an --accuracy run may take (`90s`, `20min`, `2h`; the unit is
    /// required; in [1 s, 30 days]). The coarsest grid that resolves the contact then runs
    /// first; a grid still running at the limit is stopped (its states kept under their
    /// partial name), and the answer comes from the grids that finished: printed with its
    /// stated uncertainty, `target_met: false` if that misses the target, exit status 0.
    #[arg(long, value_parser = parse::duration)]
    pub time_limit: Option<Duration>,
}

/// `--fields`: see [`FieldChoice::parse`].
fn parse_fields(text: &str) -> Result<FieldChoice, String> {
    FieldChoice::parse(text)
}
