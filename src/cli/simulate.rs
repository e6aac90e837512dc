//! `jkrbem simulate`: one pull-off of one scene.

use super::outputs::{write_error, Outputs};
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
use jkrbem::solver::{self, Phase, State};
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
    /// expected 4 at the force minimum) is refused with the grid that resolves it.
    #[arg(long, default_value_t = 256)]
    pub grid: usize,
    /// Elements along y, Ny (a power of two from 16 to 65536); by default fitted to the
    /// contact's aspect.
    #[arg(long)]
    pub grid_y: Option<usize>,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r, in [1, 20]): the JKR
    /// branch is traced for all c̄ ≤ c̄0.
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
    /// Load steps from the initial approach d̄0 to the expected end of contact (1 to 100000).
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
    /// 1 on the CPU, 2 on the GPU, where each readback waits for the device].
    #[arg(long, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=100_000))]
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
    /// Run the scene on the grids of --extrapolate-grids (instead of --grid) and extrapolate
    /// |min F̄|, c̄ and d̄ at the minimum to Δx → 0 (first order, SPEC §7), with an error bar
    /// from the spread of the two finest pairs.
    #[arg(long)]
    pub extrapolate: bool,
    /// Grids Nx for --extrapolate, coarse to fine (2 to 8 increasing powers of two, each as
    /// --grid).
    #[arg(long, value_delimiter = ',', default_value = "64,128,256")]
    pub extrapolate_grids: Vec<usize>,
    /// Reach this relative accuracy of the adhesive force |min F̄| (a percentage in
    /// [0.1 %, 50 %]: `5%`, `1%`)
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
    if (0.1..=50.0).contains(&v) {
        Ok(v / 100.0)
    } else {
        Err(format!(
            "{}: give a percentage in [0.1, 50], e.g. 5% or 1%",
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
            // Two values, checked by the model ([0, 1) each); a wrong count gives NaN there.
            apex_offset: match self.apex_offset[..] {
                [x, y] => (x, y),
                _ => (f64::NAN, f64::NAN),
            },
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
    if args.apex_offset.len() != 2 {
        return Err(input(
            "--apex-offset takes two fractions of an element, along x and y: e.g. 0.25,0.5",
        ));
    }
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
    jkrbem::plan::check_memory(&[&model], 1, "--grid").map_err(input)?;
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
    let mut targets = vec![(out.clone(), "--out".to_string())];
    if let Some(p) = &args.summary {
        targets.push((p.clone(), "--summary".to_string()));
    }
    Outputs::check(&targets)?;
    let setup = GridSetup::for_model(&model);
    let opened = open_backend(&args, &setup)?;
    check_precision(&opened.backend, &model)?;
    let _claimed = Outputs::claim(&targets)?;
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

/// Refuse a model whose scales the opened backend's arithmetic cannot hold (the GPU's f32).
pub fn check_precision(backend: &AnyBackend, model: &Model) -> Result<(), CliError> {
    if matches!(backend, AnyBackend::Gpu(_)) {
        model
            .check_scales("f32", jkrbem::model::F32_SAFE_RANGE)
            .map_err(input)?;
    }
    Ok(())
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
    let (summary, outcome, path) = pulloff_to_file(backend, model, out, "--out", None)?;
    print!("{}", summary.to_text());
    println!("states written to {}", path.display());
    if let Some(p) = &args.summary {
        summary.write_json(p).map_err(write_error("--summary"))?;
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

/// Run a model's pull-off on an opened backend, streaming its states to `out` (under this
/// run's partial name `<stem>.incomplete-<pid>.csv` until the run completes; `flag` names
/// `out` in messages), with a progress line on a terminal. `capture`, if given, sees every
/// state with its contact mask. Returns the summary, the outcome and the path the states
/// ended up at. If the states cannot be written, the run stops and this is the error.
pub fn pulloff_to_file<B: Backend>(
    backend: &mut B,
    model: &Model,
    out: &std::path::Path,
    flag: &str,
    mut capture: Option<&mut ContactCapture>,
) -> Result<(Summary, solver::Outcome, PathBuf), CliError> {
    let mut writer = StateWriter::create(out).map_err(write_error(flag))?;
    let progress = progress_bar(model.expected_steps());
    let mut write_error_at = None;
    let start = Instant::now();
    let outcome = solver::run_until(backend, model, &mut |s, mask| {
        if let Some(c) = capture.as_deref_mut() {
            c.observe(s, mask);
        }
        progress.set_position(s.step as u64);
        progress.set_message(progress_message(model, s));
        if let Err(e) = writer.write(s) {
            write_error_at.get_or_insert(e);
            return false;
        }
        true
    });
    let wall = start.elapsed().as_secs_f64();
    progress.finish_and_clear();
    for w in &outcome.warnings {
        eprintln!("jkrbem: warning: {w}");
    }
    if let Some(e) = write_error_at {
        let partial = writer.partial_path().display().to_string();
        let _ = writer.finish(false);
        return Err(failed(format!(
            "{}; the run stopped after {} states, and what could be written is in {partial} \
             (incomplete); nothing was written to {}",
            e.with_flag(flag),
            outcome.states.len(),
            out.display()
        )));
    }
    let path = writer
        .finish(outcome.complete())
        .map_err(write_error(flag))?;
    let summary = Summary::new(
        model,
        &outcome,
        (backend.name(), backend.precision()),
        wall,
        &path,
    );
    Ok((summary, outcome, path))
}

/// The progress line's text for the latest state: the load step of all expected, and where
/// the pull-off is (the bar, percentage and ETA are drawn beside it).
pub fn progress_message(model: &Model, s: &State) -> String {
    let phase = match s.phase {
        Phase::Approach => "approach",
        Phase::Pulloff => "pull-off",
        Phase::Onset => "onset",
        Phase::Regrid => "re-grid",
    };
    format!(
        "R1/R2 = {}, step {}/{} ({phase}): d̄ = {}, F̄ = {}, c̄ = {}",
        jkrbem::text::compact(model.scene.ratio()),
        s.step,
        model.expected_steps(),
        jkrbem::text::fixed(s.d_bar, 4),
        jkrbem::text::fixed(s.f_bar, 4),
        jkrbem::text::fixed(s.c_bar, 4)
    )
}

/// The progress line's layout: elapsed time, a bar of the load steps, the fraction done and
/// the estimated time left, then [`progress_message`].
pub const PROGRESS_TEMPLATE: &str = "[{elapsed_precise}] {bar:20} {percent:>3}% ETA {eta} {msg}";

/// Mean contact radii c̄ at which the pull-off's contact is kept for contours.
pub const SNAPSHOT_RADII: [f64; 4] = [1.4, 1.1, 0.8, 0.5];

/// A progress bar of `steps` load steps on stderr, hidden when stderr is not a terminal.
fn progress_bar(steps: usize) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::new(steps as u64);
    pb.set_style(
        ProgressStyle::with_template(PROGRESS_TEMPLATE)
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    pb
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_progress_line_shows_the_step_of_all_and_an_eta() {
        // Before: "state 57" (the load step, repeated by its onsets), no fraction, no ETA.
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert_eq!(model.expected_steps(), 200);
        let state = State {
            step: 57,
            phase: Phase::Onset,
            d: 0.1,
            force: -0.3,
            area: 1.0,
            mean_radius: 1.0,
            a_axis: 1.0,
            b_axis: 1.0,
            n_contact: 100,
            cg_iterations: 5,
            detach_sweeps: 1,
            d_bar: -0.00001,
            f_bar: -0.4321,
            c_bar: 0.9,
            a_bar: 0.9,
            b_bar: 0.9,
            cg_residual: 1e-9,
            dx: 0.1,
        };
        let text = progress_message(&model, &state);
        assert!(text.contains("step 57/200 (onset)"), "{text}");
        assert!(
            text.contains("d̄ = 0.0000") && text.contains("F̄ = -0.4321"),
            "{text}"
        );
        assert!(!text.contains("state"), "{text}");
        for part in ["{bar", "{percent", "{eta}"] {
            assert!(PROGRESS_TEMPLATE.contains(part), "{part}");
        }
        assert!(ProgressStyle::with_template(PROGRESS_TEMPLATE).is_ok());
        // A final approach stops the bar's length early.
        let short = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                steps: 200,
                final_d_bar: Some(0.0),
                ..ModelOptions::default()
            },
        )
        .unwrap();
        assert!(short.expected_steps() < 200);
    }

    #[test]
    fn percentages_are_bounded() {
        assert_eq!(parse_percentage("5%"), Ok(0.05));
        for bad in ["0%", "0.01", "60%", "-5", "NaN", "1e300"] {
            let e = parse_percentage(bad).unwrap_err();
            assert!(
                e.contains("[0.1, 50]") || e.contains("not a percentage"),
                "{e}"
            );
            assert!(e.len() < 100, "{e}");
        }
    }
}
