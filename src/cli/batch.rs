//! `jkrbem batch SCENES --out DIR`: every scene of a table (one per row, any parameter of
//! `simulate` as a column) simulated to `DIR/scene-<id>.csv` and `.json`; `--shard K/N` runs
//! every N-th row so a cluster can split the batch, `--resume` skips the scenes already done,
//! and `jkrbem collect DIR` merges them into `DIR/batch.csv`. The work is
//! [`jkrbem::session::batch::run`].

use super::parse::value;
use super::progress::Progress;
use super::{run_error, CliError};
use jkrbem::params::JOBS;
use jkrbem::session::batch::run::{batch, BatchRequest};
use std::path::PathBuf;

/// Arguments of `jkrbem batch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The table of scenes (CSV): a header naming the columns, then one scene per row. Any
    /// parameter of `simulate` may be a column, by its name (`mesh_angle`) or its flag
    /// (`--mesh-angle`, `mesh-angle`), written as `simulate` takes it (`2%`, `90s`, `0.25,-0.5`);
    /// an empty cell takes the default. An optional `id` column names each scene (letters,
    /// digits, `.`, `_`, `-`, differing in more than case; default: its row number, from 1).
    /// At most 10000 scenes (split a larger table). Every row is checked before any scene
    /// runs.
    pub scenes: PathBuf,
    /// Output folder: scene-<id>.csv (states) and scene-<id>.json (summary) per scene, and the
    /// batch's record batch.json (or batch-shard-K-of-N.json: its own rows and the table's
    /// digest) for `jkrbem collect`.
    #[arg(long, default_value = "jkrbem-out/batch")]
    pub out: PathBuf,
    /// Run only shard K of N (1 ≤ K ≤ N ≤ 10000): the rows at positions K, K+N, K+2N, … of the
    /// table. Every shard checks every row; `jkrbem collect DIR` merges the shards' scenes.
    #[arg(long)]
    pub shard: Option<String>,
    /// Skip each scene whose summary exists, is complete and records the same request (the
    /// others run again, replacing their files): rerun a killed or failed batch, or one whose
    /// table changed, at the cost of what is left to do.
    #[arg(long)]
    pub resume: bool,
    /// Scenes run at the same time, 1 to 256 (each opens its own backend; together they must
    /// fit in memory).
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(JOBS))]
    pub jobs: usize,
}

/// Run `jkrbem batch`.
pub fn run(args: Args) -> Result<(), CliError> {
    super::stdout::not_stdout("--out", &args.out, "batch")?;
    let shard = super::shard(args.shard.as_deref())?;
    let request = BatchRequest {
        scenes: args.scenes,
        out: args.out,
        shard,
        resume: args.resume,
        jobs: args.jobs,
    };
    let done = batch(&request, &Progress::new()).map_err(run_error)?;
    let failures = done.failures();
    outln!(
        "batch: {} scene(s){}: {} ran ({} failed), {} skipped (complete, with the same request)",
        done.total,
        shard.map_or(String::new(), |(k, n)| format!(
            ", shard {k} of {n} has {}",
            done.in_shard
        )),
        done.ran.len(),
        failures.len(),
        done.skipped.len()
    );
    outln!("record written to {}", done.manifest.display());
    if let Some(dir) = done.manifest.parent() {
        outln!(
            "summaries in {}/scene-<id>.json; merge them with `jkrbem collect {}`",
            dir.display(),
            dir.display()
        );
    }
    super::failures(
        "scenes",
        &failures,
        " (their summaries say how far they got; rerun with --resume)",
    )
}
