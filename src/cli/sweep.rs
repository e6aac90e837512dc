//! `jkrbem sweep`: one pull-off per axis ratio R1/R2, with per-ratio states and summaries and
//! a summary CSV; `--shard K/N` runs every N-th ratio so a cluster can split the sweep, and
//! `jkrbem collect` merges the shards. The work is [`jkrbem::studies::sweep`].

use super::parse::value;
use super::progress::Progress;
use super::stdout::not_stdout;
use super::{count_in, no_repeats, run_error, CliError};
use jkrbem::params::{ACCURACY, GRID, JOBS, MARGIN, RATIOS, START_RADIUS, STEPS};
use jkrbem::studies::sweep::{sweep, SweepRequest};
use std::path::PathBuf;

/// Arguments of `jkrbem sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratios R1/R2, comma-separated: 1 to 1000 values, each in [1, 1000], none repeated.
    #[arg(long, value_delimiter = ',', default_value = "1,2,5,10,25,50", value_parser = value::<f64>(RATIOS))]
    pub ratios: Vec<f64>,
    /// Elements along x, Nx, for every ratio (a power of two from 16 to 65536); Ny is fitted
    /// per ratio. Each ratio's contact must be resolved (see `simulate --grid`). Each
    /// estimate then states its expected bias [default: the grid --accuracy chooses].
    #[arg(long, value_parser = value::<usize>(GRID))]
    pub grid: Option<usize>,
    /// The relative accuracy of each adhesive force |min F̄| at Δx → 0 (a percentage such as
    /// `2%`, the unit required): each ratio gets the one grid, re-gridded, whose estimate is
    /// predicted to state an uncertainty within it [default: 2% unless --grid is given].
    #[arg(long, value_parser = value::<f64>(ACCURACY), conflicts_with = "grid")]
    pub accuracy: Option<f64>,

    /// Load steps from the initial approach to the expected end of contact (1 to 100000).
    #[arg(long, default_value_t = 200, value_parser = value::<usize>(STEPS))]
    pub steps: usize,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r, in [1, 20]).
    #[arg(long, default_value_t = 1.5, value_parser = value::<f64>(START_RADIUS))]
    pub start_radius: f64,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10]).
    #[arg(long, default_value_t = 0.08, value_parser = value::<f64>(MARGIN))]
    pub margin: f64,
    // The backend of every run, and its arithmetic.
    #[command(flatten)]
    pub backend: super::study_backend::StudyBackendArgs,
    /// Run only shard K of N (1 ≤ K ≤ N ≤ 10000): the ratios at positions K, K+N, K+2N, … of
    /// --ratios. Each shard writes sweep-shard-K-of-N.json, which records the whole sweep, its
    /// position and its rows (none if it got no ratio); `jkrbem collect DIR` merges them.
    #[arg(long)]
    pub shard: Option<String>,
    /// Pull-offs run at the same time, 1 to 256 (each opens its own backend; together they
    /// must fit in memory).
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(JOBS))]
    pub jobs: usize,
    /// Output folder: r<ratio>-n<grid>.csv (states), .json (summary) and .contours.csv per
    /// ratio, and sweep.csv (or sweep-shard-K-of-N.json) with the charts.
    #[arg(long, default_value = "jkrbem-out/sweep")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// Run `jkrbem sweep`.
pub fn run(args: Args) -> Result<(), CliError> {
    count_in(
        "--ratios",
        args.ratios.len(),
        1,
        jkrbem::output::sweep_csv::MAX_SWEEP_RATIOS,
    )?;
    no_repeats("--ratios", &args.ratios)?;
    not_stdout("--out", &args.out, "sweep")?;
    let shard = super::shard(args.shard.as_deref())?;
    let request = SweepRequest {
        ratios: args.ratios.clone(),
        grid: super::grid_choice(args.grid, args.accuracy),
        steps: args.steps,
        start_radius: args.start_radius,
        margin: args.margin,
        backend: args.backend.request(),
        shard,
        jobs: args.jobs,
        out: args.out.clone(),
        figures: args.figures.figure_format,
    };
    let done = sweep(&request, &Progress::new()).map_err(run_error)?;
    outln!("ratio   |min F̄|            JG      n_d    wall (s)");
    for r in &done.rows {
        let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
        let u = r
            .f_ad_bar_uncertainty
            .map_or(String::new(), |u| format!(" ± {u:.4}"));
        outln!(
            "{:<7} {:<18} {:<7} {:<6} {:.1}",
            r.ratio,
            format!("{}{u}", f(r.f_ad_bar)),
            f(r.jg_f_ad_bar),
            r.n_d.map_or("—".into(), |v| format!("{v:.0}")),
            r.wall_s
        );
    }
    if done.ran == 0 {
        errln!(
            "jkrbem: this shard got no ratio: --ratios has only {} value(s)",
            args.ratios.len()
        );
    }
    for w in &done.warnings {
        errln!("WARNING: {w}");
    }
    outln!("summary written to {}", done.summary_path.display());
    if let Some([a, b]) = &done.charts {
        let formats = args.figures.figure_format;
        outln!(
            "charts written to {} and {}",
            formats.shown(a),
            formats.shown(b)
        );
    }
    let pulloffs = super::failures(
        "pull-offs",
        &done.failures,
        " (marked complete = false in the summary)",
    );
    match (&done.charts_error, pulloffs) {
        (None, result) => result,
        (Some(e), Ok(())) => Err(super::failed(format!("the charts: {e}"))),
        (Some(e), Err(runs)) => Err(super::failed(format!("{runs}\n  and the charts: {e}"))),
    }
}
