//! `jkrbem collect DIR`: what the folder holds decides what is merged, a split sweep's shard
//! files ([`super::sweep::collect_shards`]) or a batch's records and scene summaries
//! ([`crate::session::batch::collect::collect_batch`]).

use super::sweep::{collect_shards, Merged};
use crate::output::figure::FigureFormats;
use crate::params::OUT;
use crate::session::batch::collect::{collect_batch, records_in, BatchMerged};
use crate::session::{input, RunError};
use std::path::Path;

/// What `collect` merged.
pub enum Collected {
    /// A split sweep's shards, into `sweep.csv` and its charts.
    Sweep(Merged),
    /// A batch's scenes, into `batch.csv`.
    Batch(BatchMerged),
}

/// Whether `dir` holds a sweep's shard files (`sweep-shard-K-of-N.json`).
fn has_sweep_shards(dir: &Path) -> bool {
    std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .any(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.starts_with("sweep-shard-") && name.ends_with(".json")
        })
}

/// Merge what `dir` holds: a batch where it holds a batch's records, else a sweep's shards
/// (whose own checks name what is missing), its charts in `figures`. A folder with both is refused: each run needs a
/// folder of its own.
pub fn collect(
    dir: &Path,
    allow_missing: bool,
    figures: FigureFormats,
) -> Result<Collected, RunError> {
    match (records_in(dir).is_empty(), has_sweep_shards(dir)) {
        (false, true) => Err(input(format!(
            "{} holds both a sweep's shard files (sweep-shard-K-of-N.json) and a batch's \
             records (batch.json, batch-shard-K-of-N.json): give each run its own {OUT} \
             folder, then collect each",
            dir.display()
        ))),
        (false, false) => collect_batch(dir, allow_missing).map(Collected::Batch),
        (true, _) => collect_shards(dir, allow_missing, figures).map(Collected::Sweep),
    }
}
