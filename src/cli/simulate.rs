//! `jkrbem simulate`: one pull-off of one scene.

use super::{failed, input, CliError};
use clap::ValueEnum;
use indicatif::{ProgressBar, ProgressStyle};
use jkrbem::analysis::capture::ContactCapture;
use jkrbem::backend::cpu::{CpuBackend, GridSetup};
use jkrbem::backend::select::{self, AnyBackend, BackendKind, Opened};
use jkrbem::backend::{Backend, BackendError, Preconditioner};
use jkrbem::model::{Measure, Model, ModelOptions, Stepping};
use jkrbem::output::states_csv::StateWriter;
use jkrbem::output::summary::Summary;
use jkrbem::scene::Scene;
use jkrbem::solver;
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

/// Default CG readback interval on the GPU (iterations). The GPU stops the iterations it has
/// queued once CG has converged, so reading rarely costs no extra iterations, only the launches
/// of the stopped ones.
pub const GPU_CHECK_EVERY: usize = 8;

/// Which backend runs the solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// A hardware GPU if there is one, else the CPU.
    Auto,
    /// The rustfft CPU backend (f64).
    Cpu,
    /// The wgpu GPU backend (f32).
    Gpu,
}

impl BackendChoice {
    /// The library's name for this choice.
    pub fn kind(self) -> BackendKind {
        match self {
            BackendChoice::Auto => BackendKind::Auto,
            BackendChoice::Cpu => BackendKind::Cpu,
            BackendChoice::Gpu => BackendKind::Gpu,
        }
    }
}

/// How load steps are taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SteppingChoice {
    /// Each step refined to the exact approach of every detachment onset inside it, so the
    /// force minimum does not depend on --steps.
    Adaptive,
    /// Whole steps only, the detachment cascade resolved at each step's end (shows what too
    /// large a step costs).
    Fixed,
}

/// What the run is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MeasureChoice {
    /// The whole pull-off curve, to the end of contact.
    Curve,
    /// Only the adhesive force: whole steps while the force falls, onsets refined from three
    /// steps before its minimum, and a stop once the minimum is confirmed.
    AdhesiveForce,
}

/// Preconditioner of the CG solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum PreconditionerChoice {
    /// The half-space stiffness E*|q|/2 in Fourier space (an approximate inverse of K).
    Stiffness,
    /// None: plain CG.
    None,
}

/// How the displacements u = K ∗ p are convolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ConvolutionChoice {
    /// Zero-padded to 2Nx × 2Ny: the exact non-periodic sum (SPEC §4).
    Padded,
    /// Unpadded Nx × Ny: the contact feels its periodic images. Wrong on purpose, to show
    /// what padding removes; CPU only.
    Periodic,
}

/// Arguments of `jkrbem simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratio R1/R2 of the ellipsoid (≥ 1; 1 is a sphere). Ignored if --r1 is given.
    #[arg(long, default_value_t = 5.0)]
    pub ratio: f64,
    /// Radius of curvature along x, the major axis (length L). Overrides --ratio.
    #[arg(long)]
    pub r1: Option<f64>,
    /// Radius of curvature along y, the minor axis (length L).
    #[arg(long, default_value_t = 1.0)]
    pub r2: f64,
    /// Effective modulus E* = E/(1−ν²) of the half-space (force/length², F/L²).
    #[arg(long, default_value_t = 1.0)]
    pub e_star: f64,
    /// Work of adhesion Δγ (energy per area, F/L).
    #[arg(long, default_value_t = 1.0)]
    pub work_of_adhesion: f64,
    /// Elements along x, Nx (a power of two ≥ 16). The domain is the initial contact plus the
    /// margin, so Δx = 2·a0·(1 + margin)/Nx.
    #[arg(long, default_value_t = 256)]
    pub grid: usize,
    /// Elements along y, Ny (a power of two ≥ 16); by default fitted to the contact's aspect.
    #[arg(long)]
    pub grid_y: Option<usize>,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r): the JKR branch is traced
    /// for all c̄ ≤ c̄0.
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
    /// Load steps from the initial approach d̄0 to the expected end of contact.
    #[arg(long, default_value_t = 200)]
    pub steps: usize,
    /// How load steps are taken: `adaptive` refines each step to every detachment onset in it
    /// (the force minimum is then independent of --steps); `fixed` does not.
    #[arg(long, value_enum, default_value_t = SteppingChoice::Adaptive)]
    pub stepping: SteppingChoice,
    /// What to compute: the whole `curve`, or only the `adhesive-force` (stops once the force
    /// minimum is confirmed, refining load steps only near it; cheaper).
    #[arg(long, value_enum, default_value_t = MeasureChoice::Curve)]
    pub measure: MeasureChoice,
    /// Re-grid as the contact shrinks: once the contact and its margin fit in 80 % of the
    /// domain, the same Nx × Ny is laid over a domain fitted to it (finer Δx, σ_c recomputed,
    /// the contact carried over and re-equilibrated).
    #[arg(long)]
    pub regrid: bool,
    /// Stop at this approach d̄ if the contact has not vanished by then (dimensionless).
    #[arg(long, allow_hyphen_values = true)]
    pub final_d: Option<f64>,
    /// Free margin around the initial contact, relative to its half-axes.
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Angle between the ellipsoid's major axis and the grid's x axis (degrees). The domain
    /// is the box around the turned initial contact (square at 45°), and ā, b̄ are measured
    /// along the turned axes. Use it to check results where crack fronts run along grid
    /// lines, at the ends of a slender ellipse's axes (e.g. 45).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub mesh_angle: f64,
    /// CG stops when its relative residual ‖(d − h − K p)_C‖/‖(d − h)_C‖ reaches this
    /// (dimensionless). A solve that stagnates, diverges, reaches --cg-max-iterations, or
    /// whose true residual (recomputed from p) stays above 100 × this is retried once in a
    /// safer mode; f32 (the GPU backend) cannot bring the true residual much below 1e-7.
    #[arg(long, default_value_t = 1e-8)]
    pub cg_tolerance: f64,
    /// CG iteration limit per solve (its safer retry gets as many again).
    #[arg(long, default_value_t = 5000)]
    pub cg_max_iterations: usize,
    /// Relative residual (dimensionless) up to which a CG solve that missed --cg-tolerance
    /// even in the safer retry is accepted: the run goes on, warns, and writes the residual
    /// of each state in the cg_residual column. Above it the run stops with an error.
    #[arg(long, default_value_t = 1e-5)]
    pub cg_accept: f64,
    /// Read CG's residual back to the host every this many iterations [default: 1 on the CPU,
    /// 2 on the GPU, where each readback waits for the device].
    #[arg(long)]
    pub cg_check_every: Option<usize>,
    /// CG preconditioner.
    #[arg(long, value_enum, default_value_t = PreconditionerChoice::Stiffness)]
    pub preconditioner: PreconditionerChoice,
    /// Backend: `cpu` (f64, rustfft), `gpu` (f32, wgpu; the best adapter, a software one such
    /// as lavapipe included) or `auto` (a hardware GPU if present, else the CPU).
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Convolution: `padded` (exact) or `periodic` (no padding, so the contact interacts with
    /// its periodic images a margin away: only to see the error padding removes; CPU only).
    #[arg(long, value_enum, default_value_t = ConvolutionChoice::Padded)]
    pub convolution: ConvolutionChoice,
    /// States CSV [default: jkrbem-out/simulate-r<ratio>-n<grid>.csv]. While running it is named
    /// <stem>.incomplete.csv; a run that fails keeps that name.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write the summary as JSON to this file.
    #[arg(long)]
    pub summary: Option<PathBuf>,
    /// Run the scene on the grids of --extrapolate-grids (instead of --grid) and extrapolate
    /// |min F̄|, c̄ and d̄ at the minimum to Δx → 0 (first order, SPEC §7), with an error bar
    /// from the spread of the two finest pairs.
    #[arg(long)]
    pub extrapolate: bool,
    /// Grids Nx for --extrapolate, coarse to fine (powers of two, at least two).
    #[arg(long, value_delimiter = ',', default_value = "64,128,256")]
    pub extrapolate_grids: Vec<usize>,
    /// Reach this relative accuracy of the adhesive force |min F̄| (a percentage: `5%`, `1%`)
    /// at the least cost: chooses the grid (or grids to extrapolate), the domain, the load
    /// steps and what to compute from the convergence law (SPEC §7), says what it chose, and
    /// overrides --grid, --grid-y, --steps, --stepping, --measure, --regrid and --extrapolate.
    #[arg(long, value_parser = parse_percentage)]
    pub accuracy: Option<f64>,
}

/// A percentage such as `5%` or `5` as a fraction (0.05).
fn parse_percentage(text: &str) -> Result<f64, String> {
    let number = text.trim().trim_end_matches('%').trim();
    let v: f64 = number
        .parse()
        .map_err(|_| format!("{text:?} is not a percentage (e.g. 5% or 1%)"))?;
    if v.is_finite() && v > 0.0 && v < 100.0 {
        Ok(v / 100.0)
    } else {
        Err(format!(
            "{text:?}: give a percentage in (0, 100), e.g. 5% or 1%"
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
        .map_err(input)
    }

    /// The model options of these arguments.
    pub fn options(&self) -> ModelOptions {
        ModelOptions {
            nx: self.grid,
            ny: self.grid_y,
            start_radius_bar: self.start_radius,
            steps: self.steps,
            final_d_bar: self.final_d,
            margin: self.margin,
            mesh_angle_deg: self.mesh_angle,
            cg_tolerance: self.cg_tolerance,
            cg_max_iterations: self.cg_max_iterations,
            cg_accept: self.cg_accept,
            preconditioner: match self.preconditioner {
                PreconditionerChoice::Stiffness => Preconditioner::Stiffness,
                PreconditionerChoice::None => Preconditioner::None,
            },
            stepping: match self.stepping {
                SteppingChoice::Adaptive => Stepping::Adaptive,
                SteppingChoice::Fixed => Stepping::Fixed,
            },
            measure: match self.measure {
                MeasureChoice::Curve => Measure::Curve,
                MeasureChoice::AdhesiveForce => Measure::AdhesiveForce,
            },
            regrid: self.regrid,
            ..ModelOptions::default()
        }
    }
}

/// Run `jkrbem simulate`.
pub fn run(mut args: Args) -> Result<(), CliError> {
    if let Some(target) = args.accuracy {
        let scene = args.scene()?;
        let plan = jkrbem::plan::for_accuracy(&scene, target, &args.options()).map_err(input)?;
        eprintln!("jkrbem: {}", plan.describe(scene.ratio()));
        args.grid = plan.grids[plan.grids.len() - 1];
        args.grid_y = None;
        args.steps = plan.options.steps;
        args.stepping = SteppingChoice::Adaptive;
        args.measure = MeasureChoice::AdhesiveForce;
        args.regrid = plan.options.regrid;
        args.extrapolate = plan.extrapolates();
        args.extrapolate_grids = plan.grids;
    }
    if args.extrapolate {
        return super::extrapolate::run(&args);
    }
    let scene = args.scene()?;
    let mut model = Model::build(&scene, &args.options()).map_err(input)?;
    if args.cg_check_every == Some(0) {
        return Err(input("--cg-check-every must be at least 1"));
    }
    let out = args.out.clone().unwrap_or_else(|| {
        let angle = if model.mesh.is_aligned() {
            String::new()
        } else {
            format!("-a{}", model.mesh.degrees)
        };
        PathBuf::from(format!(
            "jkrbem-out/simulate-r{}-n{}{angle}.csv",
            scene.ratio(),
            model.nx
        ))
    });
    let setup = GridSetup::for_model(&model);
    let opened = open_backend(&args, &setup)?;
    eprintln!(
        "jkrbem: R1/R2 = {}, grid {}×{}, Δx = {:.4e}{}, backend {}",
        scene.ratio(),
        model.nx,
        model.ny,
        model.dx,
        angle_note(&model),
        opened.note
    );
    let mut any = opened.backend;
    model.cg.check_every =
        args.cg_check_every
            .unwrap_or(if matches!(any, select::AnyBackend::Gpu(_)) {
                GPU_CHECK_EVERY
            } else {
                1
            });
    jkrbem::with_backend!(&mut any, backend => run_on(backend, &args, &model, &out))
}

/// ", mesh turned by θ°" for a rotated mesh, else nothing.
pub fn angle_note(model: &Model) -> String {
    if model.mesh.is_aligned() {
        String::new()
    } else {
        format!(", mesh turned by {}°", model.mesh.degrees)
    }
}

/// Open the backend the arguments ask for, with the periodic convolution if asked.
pub fn open_backend(args: &Args, setup: &GridSetup) -> Result<Opened, CliError> {
    match args.convolution {
        ConvolutionChoice::Padded => {
            select::open(args.backend.kind(), setup).map_err(backend_error)
        }
        ConvolutionChoice::Periodic if args.backend == BackendChoice::Gpu => Err(input(
            "--convolution periodic runs on the CPU backend only: use --backend cpu",
        )),
        ConvolutionChoice::Periodic => Ok(Opened {
            backend: AnyBackend::Cpu(Box::new(CpuBackend::new_periodic(setup))),
            note: "cpu (f64, rustfft) with a PERIODIC convolution (no padding: wrong on purpose)"
                .into(),
        }),
    }
}

/// A backend that could not be opened: a refused grid or a missing device is bad input.
pub fn backend_error(e: BackendError) -> CliError {
    match e {
        BackendError::GridTooLarge { .. } | BackendError::Unavailable(_) => input(e),
        BackendError::DeviceLost { .. } => failed(e),
    }
}

/// Run the model on an opened backend, writing the states CSV at `out` and the summary.
fn run_on<B: Backend>(
    backend: &mut B,
    args: &Args,
    model: &Model,
    out: &std::path::Path,
) -> Result<(), CliError> {
    let (summary, outcome, path) = pulloff_to_file(backend, model, out, None)?;
    print!("{}", summary.to_text());
    println!("states written to {}", path.display());
    if let Some(p) = &args.summary {
        summary.write_json(p).map_err(failed)?;
    }
    match outcome.error {
        None => Ok(()),
        Some(e) => Err(failed(format!(
            "the run stopped early: {e}\n  the {} states computed so far are in {} (incomplete)",
            outcome.states.len(),
            path.display()
        ))),
    }
}

/// Run a model's pull-off on an opened backend, streaming its states to `out` (named
/// `<stem>.incomplete.csv` until the run completes), with a progress line on a terminal.
/// `capture`, if given, sees every state with its contact mask. Returns the summary, the
/// outcome and the path the states ended up at.
pub fn pulloff_to_file<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &std::path::Path,
    mut capture: Option<&mut ContactCapture>,
) -> Result<(Summary, solver::Outcome, PathBuf), CliError> {
    let mut writer = StateWriter::create(out).map_err(failed)?;
    let progress = progress_bar();
    let mut write_error = None;
    let start = Instant::now();
    let outcome = solver::run_with_contact(backend, model, &mut |s, mask| {
        if let Some(c) = capture.as_deref_mut() {
            c.observe(s, mask);
        }
        progress.set_message(format!(
            "R1/R2 = {}, state {}: d̄ = {:+.4}, F̄ = {:+.4}, c̄ = {:.4}",
            model.scene.ratio(),
            s.step,
            s.d_bar,
            s.f_bar,
            s.c_bar
        ));
        progress.tick();
        if let Err(e) = writer.write(s) {
            write_error.get_or_insert(e);
        }
    });
    let wall = start.elapsed().as_secs_f64();
    progress.finish_and_clear();
    for w in &outcome.warnings {
        eprintln!("jkrbem: warning: {w}");
    }
    if let Some(e) = write_error {
        return Err(failed(e));
    }
    let path = writer.finish(outcome.complete()).map_err(failed)?;
    let summary = Summary::new(
        model,
        &outcome,
        (backend.name(), backend.precision()),
        wall,
        &path,
    );
    Ok((summary, outcome, path))
}

/// Mean contact radii c̄ at which the pull-off's contact is kept for contours.
pub const SNAPSHOT_RADII: [f64; 4] = [1.4, 1.1, 0.8, 0.5];

/// A spinner with the current state on stderr, hidden when stderr is not a terminal.
fn progress_bar() -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new_spinner();
    pb.set_style(
        ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    pb
}
