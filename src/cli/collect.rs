//! `jkrbem collect DIR`: merge what a split run left in DIR. For a sweep, the shard files
//! sweep-shard-K-of-N.json into DIR/sweep.csv, after checking that they are of one sweep, that
//! no ratio appears twice and that each row holds what its ratio's own summary (beside the
//! shards) says; missing and incomplete ratios are named by value, and rows that could not be
//! checked or drawn are warned of. For a batch, its records and every scene's summary into
//! DIR/batch.csv (and the wall times into DIR/batch-timings.csv); missing, stale and
//! incomplete scenes are named by id. The work is [`jkrbem::studies::collect::collect`].

use super::{run_error, CliError};
use jkrbem::session::batch::collect::BatchMerged;
use jkrbem::studies::collect::{collect, Collected};
use jkrbem::studies::sweep::Merged;
use std::path::PathBuf;

/// Arguments of `jkrbem collect`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The folder the shards wrote to (their common --out).
    pub dir: PathBuf,
    /// Merge even if some ratios or scenes are missing (their shard has not written them) or
    /// incomplete (failed, or no force minimum reached); they are then absent from, or marked
    /// in, sweep.csv or batch.csv, and the exit code is 0.
    #[arg(long)]
    pub allow_missing: bool,
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// Run `jkrbem collect`.
pub fn run(args: Args) -> Result<(), CliError> {
    let formats = args.figures.figure_format;
    match collect(&args.dir, args.allow_missing, formats).map_err(run_error)? {
        Collected::Sweep(m) => sweep(&m, formats),
        Collected::Batch(m) => batch(&m),
    }
    Ok(())
}

/// What merging a sweep did.
fn sweep(m: &Merged, formats: jkrbem::output::figure::FigureFormats) {
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
        formats.shown(&m.charts[0]),
        formats.shown(&m.charts[1])
    );
}

/// What merging a batch did.
fn batch(m: &BatchMerged) {
    outln!(
        "merged {} of {} scene(s) from {} record(s) into {}",
        m.rows,
        m.scenes,
        m.records.len(),
        m.path.display()
    );
    for p in &m.problems {
        outln!("warning (--allow-missing): {p}");
    }
    outln!("wall times written to {}", m.timings.display());
}
