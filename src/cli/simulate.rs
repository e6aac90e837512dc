//! `jkrbem simulate`: one scene's pull-off (one grid, several extrapolated, or the grids an
//! accuracy needs). Parses the flags into a request for [`jkrbem::run::simulate`] and prints
//! what comes back.

use super::progress::Progress;
use super::{run_error, CliError};
use jkrbem::backend::select::BackendKind;
use jkrbem::backend::Preconditioner;
use jkrbem::model::{Measure, ModelOptions, Onsets};
use jkrbem::run::open::{BackendRequest, Convolution};
use jkrbem::run::simulate::{failure_error, simulate, Mode, SimulateRequest};
use jkrbem::scene::Scene;
use std::path::PathBuf;
use std::time::Duration;

/// Arguments of `jkrbem simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratio R1/R2 of the ellipsoid, in [1, 1000] (1 is a sphere). Ignored if --r1 is
    /// given.
    #[arg(long, default_value_t = 5.0)]
    pub ratio: f64,
    /// Radius of curvature along x, the major axis (length L, in [1e-30, 1e30], R2 ≤ R1 ≤
    /// 1000 R2). Overrides --ratio.
    #[arg(long)]
    pub r1: Option<f64>,
    /// Radius of curvature along y, the minor axis (length L, in [1e-30, 1e30]).
    #[arg(long, default_value_t = 1.0)]
    pub r2: f64,
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
    /// branch is traced for all c̄ ≤ c̄0.
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
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
    #[arg(long, allow_hyphen_values = true)]
    pub final_d: Option<f64>,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10]).
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Angle between the ellipsoid's major axis and the grid's x axis (degrees). The domain
    /// is the box around the turned initial contact (square at 45°), and ā, b̄ are measured
    /// along the turned axes. Use it to check results where crack fronts run along grid
    /// lines, at the ends of a slender ellipse's axes (e.g. 45). In [−360, 360].
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub mesh_angle: f64,
    /// Where the apex lies within the element grid, as two fractions of an element along x
    /// and y, each in [−0.5, 0.5] (default 0,0: on the corner between the four middle
    /// elements; 0.5,0.5 puts it on the centre of one).
    /// It moves where the contact's edge falls between element centres (the "grid phase"),
    /// which shifts |min F̄| by a few tenths of a per cent on any grid.
    #[arg(long, value_delimiter = ',', default_values_t = [0.0, 0.0], allow_hyphen_values = true)]
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
    /// Solve every round of a detachment cascade to --cg-tolerance. By default the rounds
    /// between are solved only as far as needed to tell which elements are over σ_c (1e-4,
    /// detaching only those beyond it by 2 %) and the last round exactly: the same states at a
    /// fraction of the CG iterations.
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
    /// this one holds it.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write the summary as JSON to this file (not the --out file).
    #[arg(long)]
    pub summary: Option<PathBuf>,
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
    #[arg(long, value_parser = parse_percentage)]
    pub accuracy: Option<f64>,
    /// Wall-clock time an --accuracy run may take (`90s`, `20min`, `2h`; the unit is
    /// required; in [1 s, 30 days]). The coarsest grid that resolves the contact then runs
    /// first; a grid still running at the limit is stopped (its states kept under their
    /// partial name), and the answer comes from the grids that finished: printed with its
    /// stated uncertainty, `target_met: false` if that misses the target, exit status 0.
    #[arg(long, value_parser = parse_duration)]
    pub time_limit: Option<Duration>,
}

/// The accuracy of a bare `simulate` (relative): the adhesive force to 2 %.
pub const DEFAULT_ACCURACY: f64 = 0.02;

/// Nx of a one-grid run that names no --grid.
pub const DEFAULT_GRID: usize = 256;

/// A percentage such as `5%` as a fraction (0.05). The `%` is required: a bare `0.05` could
/// mean 5 % or 0.05 %.
pub fn parse_percentage(text: &str) -> Result<f64, String> {
    let Some(number) = text.trim().strip_suffix('%') else {
        return Err(format!(
            "{text:?} is not a percentage: write the unit, e.g. 5% or 1% (a bare number could \
             mean a fraction or a per cent)"
        ));
    };
    let v: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a percentage (e.g. 5% or 1%)"))?;
    if (0.1..=50.0).contains(&v) {
        Ok(v / 100.0)
    } else {
        Err(format!(
            "{}: give a percentage in [0.1, 50], e.g. 5% or 1%",
            jkrbem::text::compact(v)
        ))
    }
}

/// A duration such as `90s`, `20min` or `2h`. The unit is required (s, min, h); the value
/// lies in [1 s, 30 days].
pub fn parse_duration(text: &str) -> Result<Duration, String> {
    let t = text.trim();
    let (number, unit) = [("min", 60.0), ("h", 3600.0), ("s", 1.0)]
        .iter()
        .find_map(|&(u, scale)| t.strip_suffix(u).map(|n| (n, scale)))
        .ok_or_else(|| {
            format!("{text:?} is not a duration: write the unit, e.g. 90s, 20min or 2h")
        })?;
    let v: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a duration (e.g. 90s, 20min or 2h)"))?;
    let seconds = v * unit;
    if (1.0..=30.0 * 86400.0).contains(&seconds) {
        Ok(Duration::from_secs_f64(seconds))
    } else {
        Err(format!(
            "{}: give a duration in [1 s, 30 days], e.g. 90s, 20min or 2h",
            jkrbem::text::compact(v)
        ))
    }
}

impl Args {
    /// The scene of these arguments.
    pub fn scene(&self) -> Result<Scene, CliError> {
        match self.r1 {
            Some(r1) => Scene::new(r1, self.r2, self.e_star, self.work_of_adhesion),
            None => Scene::from_ratio(self.ratio, self.r2, self.e_star, self.work_of_adhesion),
        }
        .map_err(super::input)
    }

    /// The request these arguments make.
    pub fn request(&self) -> Result<SimulateRequest, CliError> {
        if self.apex_offset.len() != 2 {
            return Err(super::input(
                "--apex-offset takes two fractions of an element, along x and y: e.g. 0.25,0.5",
            ));
        }
        let one_grid = self.grid.is_some()
            || self.grid_y.is_some()
            || self.steps.is_some()
            || self.onsets.is_some()
            || self.measure.is_some()
            || self.regrid
            || self.final_d.is_some();
        let mode = match (self.accuracy, self.extrapolate, one_grid) {
            (Some(target), _, _) => Mode::Accuracy(target),
            (None, true, _) => Mode::Extrapolate(self.extrapolate_grids.clone()),
            (None, false, true) => Mode::Single,
            (None, false, false) => Mode::Accuracy(DEFAULT_ACCURACY),
        };
        if self.time_limit.is_some() && !matches!(mode, Mode::Accuracy(_)) {
            return Err(super::input(
                "--time-limit applies to an --accuracy run (the default without --grid and \
                 the other one-grid flags, or --accuracy given)",
            ));
        }
        Ok(SimulateRequest {
            scene: self.scene()?,
            options: self.options(),
            backend: BackendRequest {
                kind: self.backend,
                convolution: self.convolution,
                check_every: self.cg_check_every,
            },
            mode,
            out: self.out.clone(),
            summary: self.summary.clone(),
            time_limit: self.time_limit,
        })
    }

    /// The model options of these arguments.
    pub fn options(&self) -> ModelOptions {
        ModelOptions {
            nx: self.grid.unwrap_or(DEFAULT_GRID),
            ny: self.grid_y,
            start_radius_bar: self.start_radius,
            steps: self.steps.unwrap_or(jkrbem::model::default_steps(
                self.measure.unwrap_or(Measure::Curve),
                self.onsets.unwrap_or(Onsets::NearMinimum),
                self.regrid,
            )),
            final_d_bar: self.final_d,
            margin: self.margin,
            mesh_angle_deg: self.mesh_angle,
            // Two values, checked by the model ([0, 1) each); a wrong count gives NaN there.
            apex_offset: match self.apex_offset[..] {
                [x, y] => (x, y),
                _ => (f64::NAN, f64::NAN),
            },
            cg_tolerance: self.cg_tolerance,
            cg_max_iterations: self.cg_max_iterations,
            cg_accept: self.cg_accept,
            preconditioner: self.preconditioner,
            onsets: self.onsets.unwrap_or(Onsets::NearMinimum),
            loose_rounds: !self.exact_cascade,
            measure: self.measure.unwrap_or(Measure::Curve),
            regrid: self.regrid,
            ..ModelOptions::default()
        }
    }
}

/// Run `jkrbem simulate`.
pub fn run(args: Args) -> Result<(), CliError> {
    let request = args.request()?;
    let mut progress = Progress::new();
    let done = simulate(&request, &mut progress).map_err(run_error)?;
    if let Some(plan) = &done.plan {
        errln!("jkrbem: {plan}");
    }
    out!("{}", done.summary.to_text());
    for path in &done.states {
        outln!("states written to {}", path.display());
    }
    failure_error(done.failure).map_err(run_error)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_need_a_unit_and_are_bounded() {
        assert_eq!(parse_duration("90s"), Ok(Duration::from_secs(90)));
        assert_eq!(parse_duration("20min"), Ok(Duration::from_secs(1200)));
        assert_eq!(parse_duration("1.5h"), Ok(Duration::from_secs(5400)));
        assert!(parse_duration("90").unwrap_err().contains("write the unit"));
        for bad in ["0s", "0.5s", "31h0", "-5min", "NaNs", "1e300h", "800h"] {
            let e = parse_duration(bad).unwrap_err();
            assert!(
                e.contains("[1 s, 30 days]") || e.contains("not a duration"),
                "{bad}: {e}"
            );
            assert!(e.len() < 100, "{e}");
        }
    }

    #[test]
    fn percentages_are_bounded() {
        assert_eq!(parse_percentage("5%"), Ok(0.05));
        assert!(parse_percentage("0.05")
            .unwrap_err()
            .contains("write the unit"));
        for bad in ["0%", "60%", "-5%", "NaN%", "1e300%"] {
            let e = parse_percentage(bad).unwrap_err();
            assert!(
                e.contains("[0.1, 50]") || e.contains("not a percentage"),
                "{e}"
            );
            assert!(e.len() < 100, "{e}");
        }
    }
}
