//! `jkrbem collect DIR`: merge the shard files sweep-shard-K-of-N.json of a split sweep into
//! DIR/sweep.csv, after checking that they are of one sweep, that no ratio appears twice and
//! that each row holds what its ratio's own summary (beside the shards) says; missing and
//! incomplete ratios are named by value, and rows that could not be checked or drawn are
//! warned of. The work is
//! [`jkrbem::run::sweep::collect_shards`].

use super::{run_error, CliError};
use jkrbem::run::sweep::collect_shards;
use std::path::PathBuf;

/// Arguments of `jkrbem collect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The folder the shards wrote to (their common --out).
    pub dir: PathBuf,
    /// Merge even if some ratios are missing (their shard has not written its file) or
    /// incomplete (failed, or no force minimum reached); they are then absent from, or marked
    /// in, sweep.csv, and the exit code is 0.
    #[arg(long)]
    pub allow_missing: bool,
}

/// Run `jkrbem collect`.
pub fn run(args: Args) -> Result<(), CliError> {
    let m = collect_shards(&args.dir, args.allow_missing).map_err(run_error)?;
    outln!(
        "merged {} ratio(s) from {} of {} shard(s) into {}",
        m.rows,
        m.shards_found,
        m.shards,
        m.path.display()
    );
    for p in &m.problems {
        errln!("warning (--allow-missing): {p}");
    }
    for w in &m.warnings {
        errln!("warning: {w}");
    }
    outln!(
        "charts written to {} and {}",
        m.charts[0].display(),
        m.charts[1].display()
    );
    Ok(())
}
