//! `jkrbem sweep`: one pull-off per axis ratio R1/R2, with per-ratio states and summaries and
//! a summary CSV; `--shard K/N` runs every N-th ratio so a cluster can split the sweep, and
//! `jkrbem collect` merges the shards.

use super::outputs::{named, write_error, Outputs};
use super::simulate::{
    backend_error, check_precision, pulloff_to_file, BackendChoice, GPU_CHECK_EVERY, SNAPSHOT_RADII,
};
use super::{count_in, failed, input, no_repeats, CliError, MAX_JOBS};
use jkrbem::analysis::capture::{contour_rows, ContactCapture};
use jkrbem::backend::cpu::GridSetup;
use jkrbem::backend::select::{self, AnyBackend};
use jkrbem::model::{Model, ModelOptions};
use jkrbem::output::summary::Summary;
use jkrbem::output::sweep_charts::write_sweep_charts;
use jkrbem::output::sweep_csv::{self, Shard, SweepRow, SweepSettings};
use jkrbem::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Arguments of `jkrbem sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratios R1/R2, comma-separated: 1 to 1000 values, each in [1, 1000], none repeated.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "1,2,5,10,25,50",
        allow_hyphen_values = true
    )]
    pub ratios: Vec<f64>,
    /// Elements along x, Nx, for every ratio (a power of two from 16 to 65536); Ny is fitted
    /// per ratio. Each ratio's contact must be resolved (see `simulate --grid`).
    #[arg(long, default_value_t = 128)]
    pub grid: usize,
    /// Load steps from the initial approach to the expected end of contact (1 to 100000).
    #[arg(long, default_value_t = 200)]
    pub steps: usize,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r, in [1, 20]).
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10]).
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Backend: `cpu`, `gpu` or `auto` (a hardware GPU if present, else the CPU).
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Run only shard K of N (1 ≤ K ≤ N ≤ 10000): the ratios at positions K, K+N, K+2N, … of
    /// --ratios. Each shard writes sweep-shard-K-of-N.json, which records the whole sweep, its
    /// position and its rows (none if it got no ratio); `jkrbem collect DIR` merges them.
    #[arg(long)]
    pub shard: Option<String>,
    /// Pull-offs run at the same time, 1 to 256 (each opens its own backend; together they
    /// must fit in memory).
    #[arg(long, default_value_t = 1, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=MAX_JOBS as u64))]
    pub jobs: usize,
    /// Output folder: r<ratio>-n<grid>.csv (states), .json (summary) and .contours.csv per
    /// ratio, and sweep.csv (or sweep-shard-K-of-N.json) with the charts.
    #[arg(long, default_value = "jkrbem-out/sweep")]
    pub out: PathBuf,
}

/// The model of one ratio (R2 = E* = Δγ = 1: the normalised results do not depend on them).
fn model_for(args: &Args, ratio: f64) -> Result<Model, String> {
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0)
        .map_err(|e| e.to_string().replacen("--ratio = ", "R1/R2 = ", 1))?;
    Model::build(
        &scene,
        &ModelOptions {
            nx: args.grid,
            steps: args.steps,
            start_radius_bar: args.start_radius,
            margin: args.margin,
            ..ModelOptions::default()
        },
    )
    .map_err(|e| e.to_string())
}

/// States file of one ratio in `dir`.
pub fn states_path(dir: &Path, ratio: f64, grid: usize) -> PathBuf {
    dir.join(format!("r{ratio}-n{grid}.csv"))
}

/// The files one pull-off writes beside its states `out`: the states, the summary JSON and
/// the contours.
pub fn run_files(out: &Path) -> [PathBuf; 3] {
    [
        out.to_path_buf(),
        out.with_extension("json"),
        contours_path(out),
    ]
}

/// The sweep charts' files in `dir`.
pub fn chart_files(dir: &Path) -> [PathBuf; 2] {
    [
        dir.join("force_vs_ratio.svg"),
        dir.join("pulloff_curves.svg"),
    ]
}

/// Run `jkrbem sweep`.
pub fn run(args: Args) -> Result<(), CliError> {
    count_in("--ratios", args.ratios.len(), 1, 1000)?;
    no_repeats("--ratios", &args.ratios)?;
    let shard = args
        .shard
        .as_deref()
        .map(sweep_csv::parse_shard)
        .transpose()
        .map_err(input)?;
    // Every model is built (and so every input checked) before any work starts.
    let mut models = Vec::new();
    for &ratio in &sweep_csv::shard_ratios(&args.ratios, shard) {
        let m = model_for(&args, ratio)
            .map_err(|e| input(format!("--ratios {}: {e}", jkrbem::text::compact(ratio))))?;
        models.push(m);
    }
    for &ratio in &args.ratios {
        // The other shards' ratios are checked too, so that every shard refuses a bad sweep.
        model_for(&args, ratio)
            .map_err(|e| input(format!("--ratios {}: {e}", jkrbem::text::compact(ratio))))?;
    }
    let refs: Vec<&Model> = models.iter().collect();
    jkrbem::plan::check_memory(&refs, args.jobs, "--grid").map_err(input)?;
    let jobs: Vec<(Model, PathBuf)> = models
        .into_iter()
        .map(|m| {
            let out = states_path(&args.out, m.scene.ratio(), args.grid);
            (m, out)
        })
        .collect();
    let summary_path = match shard {
        Some(kn) => sweep_csv::shard_path(&args.out, kn),
        None => sweep_csv::sweep_csv_path(&args.out),
    };
    let mut targets: Vec<PathBuf> = jobs.iter().flat_map(|(_, out)| run_files(out)).collect();
    targets.push(summary_path.clone());
    if shard.is_none() {
        targets.extend(chart_files(&args.out));
    }
    let _claimed = Outputs::claim(&named("--out", &targets))?;
    eprintln!(
        "jkrbem sweep: {} ratio(s) {:?} on grid {}{}, {} at a time",
        jobs.len(),
        jobs.iter()
            .map(|(m, _)| m.scene.ratio())
            .collect::<Vec<_>>(),
        args.grid,
        shard.map_or(String::new(), |(k, n)| format!(", shard {k} of {n}")),
        args.jobs
    );
    let results = run_all(jobs, args.jobs, args.backend);
    let rows: Vec<SweepRow> = results.iter().map(RunResult::row).collect();
    let failures: Vec<String> = results.iter().filter_map(|r| r.error.clone()).collect();
    match shard {
        Some(kn) => {
            let settings = SweepSettings {
                ratios: args.ratios.clone(),
                grid: args.grid,
                steps: args.steps,
                start_radius: args.start_radius,
                margin: args.margin,
            };
            Shard::new(settings, kn, rows.clone())
                .write(&summary_path)
                .map_err(write_error("--out"))?;
        }
        None => sweep_csv::write_rows(&summary_path, &rows).map_err(write_error("--out"))?,
    }
    println!("ratio   |min F̄|   JG      n_d    wall (s)");
    let mut sorted = rows.clone();
    sorted.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    for r in &sorted {
        let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4}"));
        println!(
            "{:<7} {:<9} {:<7} {:<6} {:.1}",
            r.ratio,
            f(r.f_ad_bar),
            f(r.jg_f_ad_bar),
            r.n_d.map_or("—".into(), |v| format!("{v:.0}")),
            r.wall_s
        );
    }
    if sorted.is_empty() {
        println!(
            "(this shard got no ratio: --ratios has only {} value(s))",
            args.ratios.len()
        );
    }
    println!("summary written to {}", summary_path.display());
    if shard.is_none() {
        write_sweep_charts(&args.out, &sorted).map_err(write_error("--out"))?;
        println!(
            "charts written to {0}/force_vs_ratio.svg and {0}/pulloff_curves.svg",
            args.out.display()
        );
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} of the pull-offs failed (marked complete = false in the summary):\n  {}",
            failures.len(),
            failures.join("\n  ")
        )))
    }
}

/// The contours file beside a states file: `<stem>.contours.csv`.
pub fn contours_path(states: &Path) -> PathBuf {
    let stem = states
        .file_stem()
        .map_or_else(|| "states".into(), |s| s.to_string_lossy().into_owned());
    states.with_file_name(format!("{stem}.contours.csv"))
}

/// What became of one pull-off of [`run_all`].
pub struct RunResult {
    /// R1/R2.
    pub ratio: f64,
    /// Elements along x and y.
    pub grid: (usize, usize),
    /// Element side Δx (length).
    pub dx: f64,
    /// Its summary, if the run started (complete or not).
    pub summary: Option<Summary>,
    /// Why it failed, in words, if it did.
    pub error: Option<String>,
}

impl RunResult {
    /// Its row of a sweep's summary: from the summary, or marked failed.
    pub fn row(&self) -> SweepRow {
        match &self.summary {
            Some(s) => SweepRow::from_summary(s),
            None => SweepRow::failed(
                self.ratio,
                self.grid,
                self.dx,
                self.error.clone().unwrap_or_default(),
            ),
        }
    }
}

/// Run every (model, states path) pull-off, `jobs` at a time, each on its own backend of
/// `choice`; every summary is also written as JSON beside its states. Returns one result per
/// pull-off, in the order given.
pub fn run_all(work: Vec<(Model, PathBuf)>, jobs: usize, choice: BackendChoice) -> Vec<RunResult> {
    let n = work.len();
    let queue = Mutex::new(work.into_iter().enumerate());
    let results = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..jobs.max(1) {
            scope.spawn(|| loop {
                let next = queue.lock().expect("queue").next();
                let Some((k, (model, out))) = next else { break };
                let (ratio, grid, dx) = (model.scene.ratio(), (model.nx, model.ny), model.dx);
                let result = match run_one(choice, model, &out) {
                    Ok((summary, error)) => RunResult {
                        ratio,
                        grid,
                        dx,
                        summary: Some(summary),
                        error,
                    },
                    Err(e) => RunResult {
                        ratio,
                        grid,
                        dx,
                        summary: None,
                        error: Some(format!("R1/R2 = {ratio}: {e}")),
                    },
                };
                results.lock().expect("results").push((k, result));
            });
        }
    });
    let mut results = results.into_inner().expect("results");
    results.sort_by_key(|(k, _)| *k);
    debug_assert_eq!(results.len(), n);
    results.into_iter().map(|(_, r)| r).collect()
}

/// One pull-off: open the backend, run, write states, summary and contours. Returns the
/// summary and the run's error, if it stopped early.
fn run_one(
    choice: BackendChoice,
    mut model: Model,
    out: &Path,
) -> Result<(Summary, Option<String>), CliError> {
    let ratio = model.scene.ratio();
    let opened =
        select::open(choice.kind(), &GridSetup::for_model(&model)).map_err(backend_error)?;
    check_precision(&opened.backend, &model)?;
    eprintln!(
        "R1/R2 = {ratio}: grid {}×{}, {}",
        model.nx, model.ny, opened.note
    );
    let mut any = opened.backend;
    if matches!(any, AnyBackend::Gpu(_)) {
        model.cg.check_every = GPU_CHECK_EVERY;
    }
    let mut capture = ContactCapture::new(&SNAPSHOT_RADII);
    let (summary, outcome, path) = jkrbem::with_backend!(
        &mut any,
        backend => pulloff_to_file(backend, &model, out, "--out", Some(&mut capture))
    )?;
    let [_, json, contours] = run_files(out);
    summary.write_json(&json).map_err(write_error("--out"))?;
    jkrbem::output::file::write_csv(
        &contours,
        None,
        contour_rows(&model, &capture.into_snapshots()),
    )
    .map_err(write_error("--out"))?;
    let error = outcome
        .error
        .map(|e| format!("R1/R2 = {ratio}: {e} (states so far in {})", path.display()));
    Ok((summary, error))
}
