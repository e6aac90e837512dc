//! `jkrbem bench`: time the convolution, one CG iteration and whole pull-offs per backend and
//! grid; print a table and GPU/CPU ratios, write a CSV and an SVG chart.

use super::outputs::{named, write_error, Outputs};
use super::simulate::backend_error;
use super::{failed, input, CliError};
use clap::ValueEnum;
use jkrbem::backend::cpu::GridSetup;
use jkrbem::backend::select::{self, AnyBackend, BackendKind, Opened};
use jkrbem::bench::{self, BenchOptions, Measurement};
use jkrbem::model::{Model, ModelOptions, MIN_GRID};
use jkrbem::output::bench::{timing_chart, write_csv, BenchRow};
use jkrbem::output::profile::{self, ProfileRow};
use jkrbem::scene::Scene;
use std::path::PathBuf;

/// A backend to time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum BenchBackend {
    /// The rustfft CPU backend (f64).
    Cpu,
    /// The wgpu GPU backend (f32) on the best adapter.
    Gpu,
}

impl BenchBackend {
    fn kind(self) -> BackendKind {
        match self {
            BenchBackend::Cpu => BackendKind::Cpu,
            BenchBackend::Gpu => BackendKind::Gpu,
        }
    }

    fn flag(self) -> &'static str {
        match self {
            BenchBackend::Cpu => "--backends cpu",
            BenchBackend::Gpu => "--backends gpu",
        }
    }
}

/// Arguments of `jkrbem bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Backends to time, comma-separated (cpu, gpu) [default: cpu, plus gpu when a GPU
    /// backend can be opened].
    #[arg(long, value_enum, value_delimiter = ',')]
    pub backends: Vec<BenchBackend>,
    /// Grids to time, Nx (elements along x), comma-separated powers of two ≥ 16. Ny is fitted
    /// to the contact (Ny = Nx for the sphere).
    #[arg(long, value_delimiter = ',', default_values_t = [64, 128, 256])]
    pub grids: Vec<usize>,
    /// Time a whole pull-off only on grids up to this Nx (they are slow: about 1 s at 64, 7 s
    /// at 128 and 140 s at 256 on two CPU cores). 0 skips them.
    #[arg(long, default_value_t = 128)]
    pub pulloff_max_grid: usize,
    /// Timed samples of the convolution and of the CG solve, after 0.2 s of untimed warm-up
    /// each; a sample is the mean over calls lasting ≥ 20 ms. The median is reported.
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// CG iterations per timed solve (tolerance 0, so exactly this many).
    #[arg(long, default_value_t = 20)]
    pub cg_iterations: usize,
    /// Axis ratio R1/R2 of the scene (≥ 1; 1 is a sphere); R2 = E* = Δγ = 1.
    #[arg(long, default_value_t = 1.0)]
    pub ratio: f64,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r), as in `simulate`.
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
    /// Free margin around the initial contact, relative to its half-axes, as in `simulate`.
    /// On a 16² grid the default leaves less than one element: the pull-off reaches the edge
    /// of the domain there unless this is about 0.2 or more.
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Also profile the GPU's kernels with timestamp queries (where the adapter has them):
    /// per kernel, its time, bytes and achieved bandwidth per CG iteration, printed and
    /// written to profile.csv.
    #[arg(long)]
    pub profile: bool,
    /// Folder for bench.csv and bench.svg (and profile.csv).
    #[arg(long, default_value = "jkrbem-out/bench")]
    pub out: PathBuf,
}

/// The grids asked for, sorted and without repeats; refused unless all are powers of two ≥ 16.
fn grids(args: &Args) -> Result<Vec<usize>, CliError> {
    if args.grids.is_empty() {
        return Err(input("--grids is empty: give e.g. --grids 64,128,256"));
    }
    if let Some(bad) = args
        .grids
        .iter()
        .find(|&&g| g < MIN_GRID || !g.is_power_of_two())
    {
        return Err(input(format!(
            "--grids {bad} is invalid: every grid must be a power of two ≥ {MIN_GRID} \
             (e.g. --grids 64,128,256)"
        )));
    }
    let mut g = args.grids.clone();
    g.sort_unstable();
    g.dedup();
    Ok(g)
}

/// The device behind an opened backend, in words.
fn adapter(any: &AnyBackend) -> String {
    match any {
        AnyBackend::Cpu(_) => {
            let model = std::fs::read_to_string("/proc/cpuinfo")
                .ok()
                .and_then(|s| {
                    s.lines()
                        .find(|l| l.starts_with("model name"))
                        .and_then(|l| l.split_once(':'))
                        .map(|(_, v)| v.trim().to_string())
                })
                .unwrap_or_else(|| std::env::consts::ARCH.to_string());
            format!("{model} ({} threads)", rayon::current_num_threads())
        }
        AnyBackend::Gpu(g) => g.adapter_summary(),
    }
}

/// Open `which` for `model`'s grid.
fn open(which: BenchBackend, model: &Model) -> Result<Opened, CliError> {
    select::open(which.kind(), &GridSetup::for_model(model)).map_err(|e| {
        let e = backend_error(e);
        match e {
            CliError::Input(m) => CliError::Input(format!("{}: {m}", which.flag())),
            CliError::Run(m) => CliError::Run(format!("{}: {m}", which.flag())),
        }
    })
}

/// Run `jkrbem bench`.
pub fn run(args: Args) -> Result<(), CliError> {
    let grids = grids(&args)?;
    if args.repeats == 0 {
        return Err(input("--repeats 0 is invalid: give at least 1"));
    }
    if args.cg_iterations == 0 {
        return Err(input("--cg-iterations 0 is invalid: give at least 1"));
    }
    let scene = Scene::from_ratio(args.ratio, 1.0, 1.0, 1.0).map_err(input)?;
    let models = grids
        .iter()
        .map(|&nx| {
            let opt = ModelOptions {
                nx,
                start_radius_bar: args.start_radius,
                margin: args.margin,
                ..ModelOptions::default()
            };
            Model::build(&scene, &opt).map_err(input)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let refs: Vec<&Model> = models.iter().collect();
    jkrbem::plan::check_memory(&refs, 1, "--grids").map_err(input)?;
    let csv = args.out.join("bench.csv");
    let svg = args.out.join("bench.svg");
    let profile_csv = args.out.join("profile.csv");
    let mut targets = vec![csv.clone(), svg.clone()];
    if args.profile {
        targets.push(profile_csv.clone());
    }
    let _claimed = Outputs::claim(&named("--out", &targets))?;

    // Open every backend on the first grid before any work, so a missing one is refused
    // up front; the default takes the GPU only if it opens.
    let mut backends: Vec<(BenchBackend, Option<Opened>)> = Vec::new();
    let requested = if args.backends.is_empty() {
        vec![BenchBackend::Cpu, BenchBackend::Gpu]
    } else {
        args.backends.clone()
    };
    for which in requested {
        if backends.iter().any(|(b, _)| *b == which) {
            continue;
        }
        match open(which, &models[0]) {
            Ok(o) => backends.push((which, Some(o))),
            Err(e) if args.backends.is_empty() => {
                eprintln!("bench: {} skipped: {e}", which.flag());
            }
            Err(e) => return Err(e),
        }
    }

    let mut rows = Vec::new();
    let mut profiles: Vec<ProfileRow> = Vec::new();
    let mut measured: Vec<Measurement> = Vec::new();
    let mut problems = Vec::new();
    for (which, first) in &mut backends {
        for (k, (model, &grid)) in models.iter().zip(&grids).enumerate() {
            let opened = match if k == 0 { first.take() } else { None } {
                Some(o) => o,
                None => match open(*which, model) {
                    Ok(o) => o,
                    Err(e) => {
                        eprintln!("bench: skipped grid {grid}: {e}");
                        problems.push(format!("grid {grid}: {e}"));
                        continue;
                    }
                },
            };
            let mut any = opened.backend;
            let device = adapter(&any);
            let options = BenchOptions {
                repeats: args.repeats,
                cg_iterations: args.cg_iterations,
                pulloff: grid <= args.pulloff_max_grid,
            };
            let label = format!("{} {}×{}", which.flag(), model.nx, model.ny);
            eprintln!("bench: {label}: {}", opened.note);
            let mut progress = |what: &str| eprintln!("bench: {label}: timing {what}");
            let result = jkrbem::with_backend!(&mut any, b =>
                bench::measure(b, model, &options, &mut progress));
            if let (true, AnyBackend::Gpu(g), Ok(_)) = (args.profile, &mut any, &result) {
                eprintln!("bench: {label}: profiling the kernels");
                match bench::profile_cg_iteration(g, model, args.cg_iterations.max(20)) {
                    Ok(p) => {
                        print_profile(&label, &p, model);
                        profiles.extend(profile::rows(grid, model.nx, model.ny, &p));
                    }
                    Err(e) => {
                        eprintln!("bench: {label}: no profile: {e}");
                        problems.push(format!("{label}: no profile: {e}"));
                    }
                }
            }
            match result {
                Ok(m) => {
                    if let Some(e) = m.pulloff.as_ref().and_then(|p| p.error.as_ref()) {
                        eprintln!("bench: {label}: the pull-off stopped early: {e}");
                        problems.push(format!("{label}: the pull-off stopped early: {e}"));
                    }
                    rows.push(BenchRow::new(&m, &device, grid));
                    measured.push(m);
                }
                Err(e) => {
                    eprintln!("bench: {label}: failed: {e}");
                    problems.push(format!("{label}: {e}"));
                }
            }
        }
    }

    print_table(&rows, &measured);
    print_ratios(&rows);
    write_csv(&csv, &rows).map_err(write_error("--out"))?;
    if args.profile {
        profile::write_csv(&profile_csv, &profiles).map_err(write_error("--out"))?;
        println!("written: {}", profile_csv.display());
    }
    let title = format!(
        "jkrbem bench: R1/R2 = {}, medians of {} samples",
        scene.ratio(),
        args.repeats
    );
    timing_chart(&rows, &title)
        .write_svg(&svg)
        .map_err(write_error("--out"))?;
    println!("written: {} and {}", csv.display(), svg.display());
    if problems.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} measurement(s) failed or stopped early:\n  {}",
            problems.len(),
            problems.join("\n  ")
        )))
    }
}

/// An optional value printed with `digits` decimals, or "—".
fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".into(), |v| format!("{v:.digits$}"))
}

fn print_table(rows: &[BenchRow], measured: &[Measurement]) {
    let mut devices: Vec<(&str, &str)> = Vec::new();
    for r in rows {
        if !devices.iter().any(|(b, _)| *b == r.backend) {
            devices.push((&r.backend, &r.adapter));
        }
    }
    for (b, a) in devices {
        println!("{b}: {a}");
    }
    if let Some(m) = measured.first() {
        println!(
            "medians of {} samples (each the mean over ≥ 20 ms of calls); every call ends with one \
             scalar readback; CG: {} iterations per solve, its start excluded",
            m.repeats, m.cg_iterations
        );
    }
    println!(
        "{:<8} {:>9} {:>10} {:>10} {:>8} {:>8} {:>8} {:>11} {:>8} {:>8}",
        "backend",
        "grid",
        "conv (ms)",
        "CG it (ms)",
        "disp/it",
        "read/it",
        "subm/it",
        "pull-off(s)",
        "CG its",
        "f_ad_bar"
    );
    for (r, m) in rows.iter().zip(measured) {
        let w = m.work_per_iteration;
        println!(
            "{:<8} {:>9} {:>10.4} {:>10.4} {:>8.2} {:>8.3} {:>8.2} {:>11} {:>8} {:>8}",
            format!("{} {}", r.backend, r.precision),
            format!("{}×{}", r.nx, r.ny),
            r.convolution_ms,
            r.cg_iteration_ms,
            w.dispatches,
            w.readbacks,
            w.submits,
            opt(r.pulloff_s, 2),
            r.pulloff_cg_iterations
                .map_or_else(|| "—".into(), |n| n.to_string()),
            opt(r.f_ad_bar, 4),
        );
    }
}

/// One grid's kernel profile: time, bytes and bandwidth per CG iteration, and the kernels'
/// bytes against the iteration's floor.
fn print_profile(label: &str, profile: &[jkrbem::bench::KernelProfile], model: &Model) {
    let floor = jkrbem::backend::gpu::traffic::cg_iteration_floor(model.nx, model.ny, true) as f64;
    let time: f64 = profile.iter().map(|k| k.ms_per_iteration).sum();
    let bytes: f64 = profile.iter().map(|k| k.bytes_per_iteration).sum();
    println!("profile {label}, per CG iteration (GPU timestamps around each dispatch):");
    println!(
        "  {:<18} {:>8} {:>10} {:>10} {:>9} {:>7}",
        "kernel", "disp/it", "ms/it", "MB/it", "GB/s", "share"
    );
    for k in profile {
        println!(
            "  {:<18} {:>8.2} {:>10.4} {:>10.2} {:>9.0} {:>6.1}%",
            k.kernel,
            k.dispatches_per_iteration,
            k.ms_per_iteration,
            k.bytes_per_iteration / 1e6,
            k.gb_per_s(),
            100.0 * k.ms_per_iteration / time.max(f64::MIN_POSITIVE)
        );
    }
    println!(
        "  kernels: {time:.4} ms, {:.1} MB ({:.2}× the floor of {:.1} MB), {:.0} GB/s overall",
        bytes / 1e6,
        bytes / floor,
        floor / 1e6,
        bytes / (time * 1e-3).max(f64::MIN_POSITIVE) / 1e9
    );
}

/// GPU/CPU time ratios per grid, when both ran in this invocation.
fn print_ratios(rows: &[BenchRow]) {
    let find = |b: &str, g: usize| rows.iter().find(|r| r.backend == b && r.grid == g);
    let mut header = false;
    for r in rows.iter().filter(|r| r.backend == "cpu") {
        let Some(gpu) = find("gpu", r.grid) else {
            continue;
        };
        if !header {
            println!("GPU/CPU time ratios (below 1: the GPU is faster), measured in this run:");
            println!(
                "{:>9} {:>12} {:>13} {:>9}",
                "grid", "convolution", "CG iteration", "pull-off"
            );
            header = true;
        }
        let pulloff = gpu.pulloff_s.zip(r.pulloff_s).map(|(g, c)| g / c);
        println!(
            "{:>9} {:>12.3} {:>13.3} {:>9}",
            format!("{}×{}", r.nx, r.ny),
            gpu.convolution_ms / r.convolution_ms,
            gpu.cg_iteration_ms / r.cg_iteration_ms,
            opt(pulloff, 3),
        );
    }
}
