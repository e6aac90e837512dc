//! `jkrbem sweep`: one pull-off per axis ratio R1/R2, with per-ratio states and summaries and
//! a summary CSV; `--shard K/N` runs every N-th ratio so a cluster can split the sweep, and
//! `jkrbem collect` merges the shards.

use super::simulate::{
    backend_error, pulloff_to_file, BackendChoice, GPU_CHECK_EVERY, SNAPSHOT_RADII,
};
use super::{failed, input, CliError};
use jkrbem::analysis::capture::{contour_rows, ContactCapture, ContourRow};
use jkrbem::backend::cpu::GridSetup;
use jkrbem::backend::select::{self, AnyBackend};
use jkrbem::model::{Model, ModelOptions};
use jkrbem::output::summary::Summary;
use jkrbem::output::sweep_charts::write_sweep_charts;
use jkrbem::output::sweep_csv::{self, SweepRow};
use jkrbem::scene::Scene;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Arguments of `jkrbem sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratios R1/R2 (≥ 1), comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "1,2,5,10,25,50")]
    pub ratios: Vec<f64>,
    /// Elements along x, Nx, for every ratio (a power of two ≥ 16); Ny is fitted per ratio.
    #[arg(long, default_value_t = 128)]
    pub grid: usize,
    /// Load steps from the initial approach to the expected end of contact.
    #[arg(long, default_value_t = 200)]
    pub steps: usize,
    /// Mean radius c̄0 of the initial non-adhesive contact (in c_r).
    #[arg(long, default_value_t = 1.5)]
    pub start_radius: f64,
    /// Free margin around the initial contact, relative to its half-axes.
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Backend: `cpu`, `gpu` or `auto` (a hardware GPU if present, else the CPU).
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Run only shard K of N (1 ≤ K ≤ N): the ratios at positions K, K+N, K+2N, … of --ratios.
    /// Each shard writes sweep-shard-K-of-N.csv; `jkrbem collect DIR` merges them.
    #[arg(long)]
    pub shard: Option<String>,
    /// Pull-offs run at the same time (each opens its own backend).
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Output folder: r<ratio>-n<grid>.csv (states) and .json (summary) per ratio, and
    /// sweep.csv (or sweep-shard-K-of-N.csv).
    #[arg(long, default_value = "jkrbem-out/sweep")]
    pub out: PathBuf,
}

/// The model of one ratio (R2 = E* = Δγ = 1: the normalised results do not depend on them).
fn model_for(args: &Args, ratio: f64) -> Result<Model, String> {
    let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(|e| e.to_string())?;
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

/// Run `jkrbem sweep`.
pub fn run(args: Args) -> Result<(), CliError> {
    if args.ratios.is_empty() {
        return Err(input("--ratios: give at least one ratio"));
    }
    if args.jobs == 0 {
        return Err(input("--jobs must be at least 1"));
    }
    let shard = args
        .shard
        .as_deref()
        .map(sweep_csv::parse_shard)
        .transpose()
        .map_err(input)?;
    // Every model is built (and so every input checked) before any work starts.
    let mut models = Vec::new();
    for &ratio in &sweep_csv::shard_ratios(&args.ratios, shard) {
        let m = model_for(&args, ratio).map_err(|e| input(format!("--ratios {ratio}: {e}")))?;
        models.push(m);
    }
    eprintln!(
        "jkrbem sweep: {} ratio(s) {:?} on grid {}{}, {} at a time",
        models.len(),
        models.iter().map(|m| m.scene.ratio()).collect::<Vec<_>>(),
        args.grid,
        shard.map_or(String::new(), |(k, n)| format!(", shard {k} of {n}")),
        args.jobs
    );
    let jobs: Vec<(Model, PathBuf)> = models
        .into_iter()
        .map(|m| {
            let out = states_path(&args.out, m.scene.ratio(), args.grid);
            (m, out)
        })
        .collect();
    let (summaries, failures) = run_all(jobs, args.jobs, args.backend);
    let rows: Vec<SweepRow> = summaries.iter().map(SweepRow::from_summary).collect();
    let path = sweep_csv::sweep_csv_path(&args.out, shard);
    sweep_csv::write_rows(&path, &rows).map_err(failed)?;
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
    println!("summary written to {}", path.display());
    if shard.is_none() {
        write_sweep_charts(&args.out, &sorted).map_err(failed)?;
        println!(
            "charts written to {0}/force_vs_ratio.svg and {0}/pulloff_curves.svg",
            args.out.display()
        );
    }
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} of the pull-offs failed:\n  {}",
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

/// Write quarter-contour rows as CSV.
fn write_contours(path: &Path, rows: &[ContourRow]) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_path(path)?;
    for r in rows {
        w.serialize(r)?;
    }
    w.flush()?;
    Ok(())
}

/// Run every (model, states path) pull-off, `jobs` at a time, each on its own backend of
/// `choice`; every summary is also written as JSON beside its states. Returns the summaries
/// of the runs that started (complete or not) and the failures, in words.
pub fn run_all(
    work: Vec<(Model, PathBuf)>,
    jobs: usize,
    choice: BackendChoice,
) -> (Vec<Summary>, Vec<String>) {
    let queue = Mutex::new(work.into_iter());
    let summaries = Mutex::new(Vec::new());
    let failures = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..jobs.max(1) {
            scope.spawn(|| loop {
                let next = queue.lock().expect("queue").next();
                let Some((model, out)) = next else { break };
                match run_one(choice, model, &out) {
                    Ok((summary, error)) => {
                        if let Some(e) = error {
                            failures.lock().expect("failures").push(e);
                        }
                        summaries.lock().expect("summaries").push(summary);
                    }
                    Err(e) => failures.lock().expect("failures").push(e.to_string()),
                }
            });
        }
    });
    (
        summaries.into_inner().expect("summaries"),
        failures.into_inner().expect("failures"),
    )
}

/// One pull-off: open the backend, run, write states and summary. Returns the summary and
/// the run's error, if it stopped early.
fn run_one(
    choice: BackendChoice,
    mut model: Model,
    out: &Path,
) -> Result<(Summary, Option<String>), CliError> {
    let ratio = model.scene.ratio();
    let opened =
        select::open(choice.kind(), &GridSetup::for_model(&model)).map_err(backend_error)?;
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
        backend => pulloff_to_file(backend, &model, out, Some(&mut capture))
    )?;
    summary
        .write_json(&path.with_extension("json"))
        .map_err(failed)?;
    write_contours(
        &contours_path(out),
        &contour_rows(&model, &capture.into_snapshots()),
    )
    .map_err(failed)?;
    let error = outcome
        .error
        .map(|e| format!("R1/R2 = {ratio}: {e} (states so far in {})", path.display()));
    Ok((summary, error))
}
