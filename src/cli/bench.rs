//! `jkrbem bench`: time the convolution, one CG iteration and whole pull-offs per backend and
//! grid; print a table and GPU/CPU ratios, write a CSV and an SVG chart. The work is
//! [`jkrbem::studies::bench`].

use super::parse::value;
use super::progress::Progress;
use super::{failures, run_error, CliError};
use jkrbem::backend::select::{BackendKind, Precision};
use jkrbem::model::Measure;
use jkrbem::output::bench as bench_text;
use jkrbem::params::{
    CG_ITERATIONS, GRIDS, MARGIN, PULLOFF_MAX_GRID, RATIO, REPEATS, START_RADIUS,
};
use jkrbem::studies::bench::{bench, BenchRequest};
use std::path::PathBuf;

/// Arguments of `jkrbem bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Backends to time, comma-separated (cpu, gpu, or auto: the one `simulate` would pick)
    /// [default: cpu, plus gpu when a GPU backend can be opened].
    #[arg(long, value_enum, value_delimiter = ',')]
    pub backends: Vec<BackendKind>,
    /// The arithmetic each backend is timed in, comma-separated: `auto` (the backend's own),
    /// `f64` (the CPU only; the GPU skips it) or `f32` (the GPU, or the CPU's FFT passes in
    /// f32) [default: auto].
    #[arg(long, value_enum, value_delimiter = ',')]
    pub precisions: Vec<Precision>,
    /// Grids to time, Nx (elements along x), comma-separated powers of two from 16 to 65536.
    /// Ny is fitted to the contact (Ny = Nx for the sphere).
    #[arg(long, value_delimiter = ',', default_values_t = [64, 128, 256], value_parser = value::<usize>(GRIDS))]
    pub grids: Vec<usize>,
    /// Time a whole pull-off only on grids up to this Nx (they are slow: about 1 s at 64, 7 s
    /// at 128 and 140 s at 256 on two CPU cores). 0 skips them; at most 65536.
    #[arg(long, default_value_t = 128, value_parser = value::<usize>(PULLOFF_MAX_GRID))]
    pub pulloff_max_grid: usize,
    /// What the timed pull-off computes: the whole `curve`, or only the `adhesive-force` (it
    /// stops once the force minimum is confirmed; 20 load steps, as `simulate` takes them).
    #[arg(long, value_enum, default_value_t = Measure::Curve)]
    pub measure: Measure,
    /// Timed samples of the convolution and of the CG solve, after 0.2 s of untimed warm-up
    /// each; a sample is the mean over calls lasting ≥ 20 ms. The median is reported. 1 to
    /// 1000.
    #[arg(long, default_value_t = 5, value_parser = value::<usize>(REPEATS))]
    pub repeats: usize,
    /// CG iterations per timed solve (tolerance 0, so exactly this many), 1 to 100000.
    #[arg(long, default_value_t = 20, value_parser = value::<usize>(CG_ITERATIONS))]
    pub cg_iterations: usize,
    /// Axis ratio R1/R2 of the scene (≥ 1; 1 is a sphere); R2 = E* = Δγ = 1.
    #[arg(long, default_value_t = 1.0, value_parser = value::<f64>(RATIO))]
    pub ratio: f64,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r), as in `simulate`.
    #[arg(long, default_value_t = 1.5, value_parser = value::<f64>(START_RADIUS))]
    pub start_radius: f64,
    /// Free margin around the initial contact, relative to its half-axes, as in `simulate`
    /// [default: 0.08, or at least one element on each side: 0.143 on a 16-element grid].
    #[arg(long, value_parser = value::<f64>(MARGIN))]
    pub margin: Option<f64>,
    /// Also profile the GPU's kernels with timestamp queries (where the adapter has them):
    /// per kernel, its time, bytes and achieved bandwidth per CG iteration, printed and
    /// written to profile.csv; where a pull-off is timed (`--pulloff-max-grid`), it is run
    /// again profiled: the host's time blocked on readbacks and submitting, and each kernel's
    /// GPU time over the whole pull-off, printed and written to pulloff-profile.csv.
    #[arg(long)]
    pub profile: bool,
    /// Folder for bench.csv and bench.svg (and profile.csv).
    #[arg(long, default_value = "jkrbem-out/bench")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// Run `jkrbem bench`.
pub fn run(args: Args) -> Result<(), CliError> {
    super::stdout::not_stdout("--out", &args.out, "bench")?;
    let req = BenchRequest {
        backends: args.backends,
        precisions: args.precisions,
        grids: args.grids,
        pulloff_max_grid: args.pulloff_max_grid,
        measure: args.measure,
        repeats: args.repeats,
        cg_iterations: args.cg_iterations,
        ratio: args.ratio,
        start_radius: args.start_radius,
        margin: args.margin,
        profile: args.profile,
        out: args.out,
        figures: args.figures.figure_format,
    };
    let done = bench(&req, &Progress::new()).map_err(run_error)?;
    for p in &done.profiles {
        out!("{}", bench_text::profile_text(p));
    }
    for p in &done.pulloff_profiles {
        out!("{}", bench_text::pulloff_profile_text(p));
    }
    out!("{}", bench_text::table_text(&done.rows, &done.measured));
    out!("{}", bench_text::ratios_text(&done.rows));
    out!("{}", bench_text::cost_text(&done.rows));
    let names: Vec<String> = done.files.iter().map(|f| f.display().to_string()).collect();
    outln!("written: {}", names.join(", "));
    failures("measurements", &done.problems, " or stopped early")
}
