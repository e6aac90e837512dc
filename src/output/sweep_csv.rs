//! The summary CSV of a sweep over R1/R2: one row per ratio; shard files that separate
//! machines write, and their merge.

use super::summary::Summary;
use super::OutputError;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One ratio of a sweep (normalised quantities per SPEC §2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// R1/R2.
    pub ratio: f64,
    /// Adhesive force |min F̄| (dimensionless); empty if the run failed before a minimum.
    pub f_ad_bar: Option<f64>,
    /// c̄ at the force minimum.
    pub c_bar_at_min: Option<f64>,
    /// d̄ at the force minimum.
    pub d_bar_at_min: Option<f64>,
    /// Johnson–Greenwood's |min F̄| (JKR's 1/2 for the sphere).
    pub jg_f_ad_bar: Option<f64>,
    /// Elements across the contact's minor axis at the force minimum.
    pub n_d: Option<f64>,
    /// Elements along x, Nx.
    pub grid: usize,
    /// Element side Δx (length).
    pub dx: f64,
    /// Wall time of the pull-off (s).
    pub wall_s: f64,
    /// Elements along y, Ny.
    pub ny: usize,
    /// Backend and precision, e.g. "cpu-f64".
    pub backend: String,
    /// Whether the pull-off completed.
    pub complete: bool,
}

impl SweepRow {
    /// The row of one finished (or failed) pull-off.
    pub fn from_summary(s: &Summary) -> SweepRow {
        SweepRow {
            ratio: s.ratio,
            f_ad_bar: s.f_ad_bar,
            c_bar_at_min: s.c_bar_at_min,
            d_bar_at_min: s.d_bar_at_min,
            jg_f_ad_bar: s.reference_f_ad_bar,
            n_d: s.n_d,
            grid: s.nx,
            dx: s.dx,
            wall_s: s.wall_s,
            ny: s.ny,
            backend: format!("{}-{}", s.backend, s.precision),
            complete: s.complete,
        }
    }
}

/// The summary file of shard `k` of `n` (1-based), or of a whole sweep when `shard` is None.
pub fn sweep_csv_path(dir: &Path, shard: Option<(usize, usize)>) -> PathBuf {
    match shard {
        None => dir.join("sweep.csv"),
        Some((k, n)) => dir.join(format!("sweep-shard-{k}-of-{n}.csv")),
    }
}

/// Write rows (sorted by ratio) to `path`, through a temporary name so that the file is
/// never half-written.
pub fn write_rows(path: &Path, rows: &[SweepRow]) -> Result<(), OutputError> {
    let mut rows = rows.to_vec();
    rows.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| OutputError::io(dir, e))?;
    }
    let tmp = path.with_extension("csv.tmp");
    let csv_err = |source| OutputError::Csv {
        path: tmp.display().to_string(),
        source,
    };
    let mut w = csv::Writer::from_path(&tmp).map_err(csv_err)?;
    for r in &rows {
        w.serialize(r).map_err(csv_err)?;
    }
    w.flush().map_err(|e| OutputError::io(&tmp, e))?;
    std::fs::rename(&tmp, path).map_err(|e| OutputError::io(path, e))
}

/// Read the rows of a sweep or shard CSV.
pub fn read_rows(path: &Path) -> Result<Vec<SweepRow>, csv::Error> {
    csv::Reader::from_path(path)?.deserialize().collect()
}

/// What `collect` found in a folder of shard files.
#[derive(Debug, Clone, PartialEq)]
pub struct Collected {
    /// All rows, sorted by ratio.
    pub rows: Vec<SweepRow>,
    /// Shard count n of the files found.
    pub shards: usize,
    /// Shards (1-based) whose file is missing.
    pub missing: Vec<usize>,
}

/// Errors of [`collect`].
#[derive(Debug, thiserror::Error)]
pub enum CollectError {
    /// The folder could not be read.
    #[error("cannot read {0}: {1}")]
    Io(String, std::io::Error),
    /// No shard file was found.
    #[error("no sweep-shard-K-of-N.csv files in {0}")]
    Empty(String),
    /// Shard files of different sweeps were found.
    #[error("shard files of different shard counts in {0}: {1:?}")]
    Mixed(String, Vec<usize>),
    /// A shard file could not be parsed.
    #[error("cannot read {0}: {1}")]
    Csv(String, csv::Error),
}

/// Gather the shard files `sweep-shard-K-of-N.csv` in `dir` and merge their rows.
pub fn collect(dir: &Path) -> Result<Collected, CollectError> {
    let shown = dir.display().to_string();
    let entries = std::fs::read_dir(dir).map_err(|e| CollectError::Io(shown.clone(), e))?;
    let mut found: Vec<(usize, usize, PathBuf)> = Vec::new();
    for entry in entries {
        let path = entry
            .map_err(|e| CollectError::Io(shown.clone(), e))?
            .path();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        if let Some((k, n)) = name.as_deref().and_then(parse_shard_name) {
            found.push((k, n, path));
        }
    }
    if found.is_empty() {
        return Err(CollectError::Empty(shown));
    }
    let mut counts: Vec<usize> = found.iter().map(|f| f.1).collect();
    counts.sort_unstable();
    counts.dedup();
    if counts.len() > 1 {
        return Err(CollectError::Mixed(shown, counts));
    }
    let n = counts[0];
    let mut rows = Vec::new();
    for (_, _, path) in &found {
        rows.extend(read_rows(path).map_err(|e| CollectError::Csv(path.display().to_string(), e))?);
    }
    rows.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    let missing = (1..=n)
        .filter(|k| !found.iter().any(|f| f.0 == *k))
        .collect();
    Ok(Collected {
        rows,
        shards: n,
        missing,
    })
}

/// (k, n) from "sweep-shard-K-of-N.csv".
fn parse_shard_name(name: &str) -> Option<(usize, usize)> {
    let rest = name.strip_prefix("sweep-shard-")?.strip_suffix(".csv")?;
    let (k, n) = rest.split_once("-of-")?;
    let (k, n) = (k.parse().ok()?, n.parse().ok()?);
    (1..=n).contains(&k).then_some((k, n))
}

/// Parse a shard "K/N" (1 ≤ K ≤ N).
pub fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let err = || format!("--shard {text:?}: expected K/N with 1 ≤ K ≤ N, e.g. 2/8");
    let (k, n) = text.split_once('/').ok_or_else(err)?;
    let (k, n): (usize, usize) = (
        k.trim().parse().map_err(|_| err())?,
        n.trim().parse().map_err(|_| err())?,
    );
    if k == 0 || k > n {
        return Err(err());
    }
    Ok((k, n))
}

/// The ratios (by position) that shard K of N runs: positions j with j mod N = K − 1.
pub fn shard_ratios(ratios: &[f64], shard: Option<(usize, usize)>) -> Vec<f64> {
    match shard {
        None => ratios.to_vec(),
        Some((k, n)) => ratios
            .iter()
            .enumerate()
            .filter(|(j, _)| j % n == k - 1)
            .map(|(_, r)| *r)
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(ratio: f64) -> SweepRow {
        SweepRow {
            ratio,
            f_ad_bar: Some(0.5 / ratio.sqrt()),
            c_bar_at_min: Some(0.8),
            d_bar_at_min: None,
            jg_f_ad_bar: Some(0.5),
            n_d: Some(60.0),
            grid: 128,
            dx: 0.05,
            wall_s: 1.0,
            ny: 64,
            backend: "cpu-f64".into(),
            complete: true,
        }
    }

    #[test]
    fn shards_partition_the_ratios_and_collect_merges_them() {
        let ratios = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0];
        let dir = tempfile::tempdir().unwrap();
        let mut all = Vec::new();
        for k in 1..=4 {
            let mine = shard_ratios(&ratios, Some((k, 4)));
            all.extend(mine.clone());
            let rows: Vec<SweepRow> = mine.iter().map(|&r| row(r)).collect();
            if k != 3 {
                write_rows(&sweep_csv_path(dir.path(), Some((k, 4))), &rows).unwrap();
            }
        }
        all.sort_by(f64::total_cmp);
        assert_eq!(all, ratios);
        let c = collect(dir.path()).unwrap();
        assert_eq!(c.shards, 4);
        assert_eq!(c.missing, vec![3]);
        let got: Vec<f64> = c.rows.iter().map(|r| r.ratio).collect();
        assert_eq!(got, vec![1.0, 2.0, 10.0, 25.0, 50.0]);
        assert_eq!(c.rows[0], row(1.0));
    }

    #[test]
    fn shard_text_is_checked() {
        assert_eq!(parse_shard("2/8"), Ok((2, 8)));
        for bad in ["0/4", "5/4", "x/4", "3", "1/0"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
