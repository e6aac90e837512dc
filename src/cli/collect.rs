//! `jkrbem collect DIR`: merge the shard summaries sweep-shard-K-of-N.csv of a split sweep
//! into DIR/sweep.csv.

use super::{failed, input, CliError};
use jkrbem::output::sweep_charts::write_sweep_charts;
use jkrbem::output::sweep_csv::{self, CollectError};
use std::path::PathBuf;

/// Arguments of `jkrbem collect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The folder the shards wrote to (their common --out).
    pub dir: PathBuf,
    /// Merge even if some shards are missing (their ratios are then absent from sweep.csv).
    #[arg(long)]
    pub allow_missing: bool,
}

/// Run `jkrbem collect`.
pub fn run(args: Args) -> Result<(), CliError> {
    let c = sweep_csv::collect(&args.dir).map_err(|e| match e {
        CollectError::Empty(_) | CollectError::Mixed(..) | CollectError::Io(..) => input(e),
        CollectError::Csv(..) => failed(e),
    })?;
    if !c.missing.is_empty() && !args.allow_missing {
        return Err(failed(format!(
            "shards {:?} of {} have not written their summary yet (rerun them, or pass \
             --allow-missing)",
            c.missing, c.shards
        )));
    }
    let path = sweep_csv::sweep_csv_path(&args.dir, None);
    sweep_csv::write_rows(&path, &c.rows).map_err(failed)?;
    println!(
        "merged {} ratio(s) from {} shard(s) into {}",
        c.rows.len(),
        c.shards - c.missing.len(),
        path.display()
    );
    write_sweep_charts(&args.dir, &c.rows).map_err(failed)?;
    println!(
        "charts written to {0}/force_vs_ratio.svg and {0}/pulloff_curves.svg",
        args.dir.display()
    );
    Ok(())
}
