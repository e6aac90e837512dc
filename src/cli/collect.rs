//! `jkrbem collect DIR`: merge the shard files sweep-shard-K-of-N.json of a split sweep into
//! DIR/sweep.csv, after checking that they are of one sweep and that no ratio appears twice;
//! missing and incomplete ratios are named by value.

use super::outputs::{named, write_error, Outputs};
use super::sweep::chart_files;
use super::{failed, input, CliError};
use jkrbem::output::sweep_charts::write_sweep_charts;
use jkrbem::output::sweep_csv::{self, CollectError};
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

/// Ratios as text: "2, 25".
fn listed(ratios: &[f64]) -> String {
    ratios
        .iter()
        .map(|r| jkrbem::text::compact(*r))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Run `jkrbem collect`.
pub fn run(args: Args) -> Result<(), CliError> {
    let c = sweep_csv::collect(&args.dir).map_err(|e| match e {
        CollectError::Empty(_) | CollectError::Io(..) => input(e),
        CollectError::Corrupt(..) | CollectError::Mixed(..) | CollectError::Duplicate { .. } => {
            failed(e)
        }
    })?;
    let mut problems = Vec::new();
    if !c.missing.is_empty() {
        problems.push(format!(
            "R1/R2 = {} missing{}",
            listed(&c.missing),
            if c.missing_shards.is_empty() {
                String::new()
            } else {
                format!(
                    " (shards {:?} of {} have not written their file: run them)",
                    c.missing_shards, c.shards
                )
            }
        ));
    }
    if !c.incomplete.is_empty() {
        problems.push(format!(
            "R1/R2 = {} incomplete (failed, no force minimum reached, or not finite: see their \
             complete, min_reached and error columns)",
            listed(&c.incomplete)
        ));
    }
    if !problems.is_empty() && !args.allow_missing {
        return Err(failed(format!(
            "{}; nothing was written (pass --allow-missing to merge what there is)",
            problems.join("; ")
        )));
    }
    let path = sweep_csv::sweep_csv_path(&args.dir);
    let mut targets = vec![path.clone()];
    targets.extend(chart_files(&args.dir));
    let _claimed = Outputs::claim(&named("DIR", &targets))?;
    sweep_csv::write_rows(&path, &c.rows).map_err(write_error("DIR"))?;
    println!(
        "merged {} ratio(s) from {} of {} shard(s) into {}",
        c.rows.len(),
        c.shards - c.missing_shards.len(),
        c.shards,
        path.display()
    );
    for p in &problems {
        println!("warning (--allow-missing): {p}");
    }
    write_sweep_charts(&args.dir, &c.rows).map_err(write_error("DIR"))?;
    println!(
        "charts written to {0}/force_vs_ratio.svg and {0}/pulloff_curves.svg",
        args.dir.display()
    );
    Ok(())
}
