//! The summary CSV of a sweep over R1/R2: one row per ratio; the shard files that separate
//! machines write, and their checked merge.
//!
//! A shard file, `sweep-shard-K-of-N.json`, records the whole sweep it belongs to (every ratio
//! of `--ratios` in order, the grid, the load steps, c̄0 and the margin), its own position K of
//! N, the ratios it was given, and one row per ratio it ran. A shard given no ratio (more
//! shards than ratios) writes the same file with no rows, so it is told apart from a truncated
//! one. [`collect`] refuses shards of different sweeps, a ratio found twice, ratios outside
//! [1, [`MAX_RATIO`]], shard counts above [`MAX_SHARDS`], and files that are not shards (only
//! regular files of at most [`MAX_SHARD_BYTES`] are read, so a FIFO or a device named as a shard
//! neither blocks nor fills memory), and names the ratios that are missing or incomplete.
//! [`check_row`] holds a merged row against the per-ratio summary its run wrote beside it.

use super::file;
use super::summary::Summary;
use super::OutputError;
use crate::params::{ACCURACY, GRID, MARGIN, RATIOS, SHARD, START_RADIUS, STEPS};
use crate::scene::MAX_RATIO;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One ratio of a sweep (normalised quantities per physics §2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// R1/R2.
    pub ratio: f64,
    /// Adhesive force |min F̄|, the best estimate at Δx → 0 (dimensionless); empty if the run
    /// did not reach the minimum.
    pub f_ad_bar: Option<f64>,
    /// Half-width of the interval stated to hold it (absolute).
    #[serde(default)]
    pub f_ad_bar_uncertainty: Option<f64>,
    /// "single-grid" or "extrapolated".
    #[serde(default)]
    pub estimate: Option<String>,
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
    /// Whether the run reached (and confirmed) the force minimum, so that `f_ad_bar` is an
    /// adhesive force.
    #[serde(default = "yes")]
    pub min_reached: bool,
    /// Why the run failed, if it did.
    #[serde(default)]
    pub error: Option<String>,
}

fn yes() -> bool {
    true
}

impl SweepRow {
    /// A complete single-grid row of R1/R2 = `ratio` with |min F̄| = `f_ad_bar` ± 0.01 on a
    /// 64² grid (Δx = 0.1, 30 elements across the minor axis, 1 s): a sample for tests and
    /// examples.
    #[doc(hidden)]
    pub fn sample(ratio: f64, f_ad_bar: f64) -> SweepRow {
        SweepRow {
            ratio,
            f_ad_bar: Some(f_ad_bar),
            f_ad_bar_uncertainty: Some(0.01),
            estimate: Some("single-grid".into()),
            c_bar_at_min: Some(0.8),
            d_bar_at_min: Some(-0.2),
            jg_f_ad_bar: Some(0.5),
            n_d: Some(30.0),
            grid: 64,
            dx: 0.1,
            wall_s: 1.0,
            ny: 64,
            backend: "cpu-f64".into(),
            complete: true,
            min_reached: true,
            error: None,
        }
    }

    /// The row of one scene's finished (or stopped) request: its estimate and its finest run.
    pub fn from_summary(s: &Summary) -> SweepRow {
        let finest = s.runs.last();
        SweepRow {
            ratio: s.ratio,
            f_ad_bar: s.f_ad_bar,
            f_ad_bar_uncertainty: s.f_ad_bar_uncertainty,
            estimate: s.estimate.map(str::to_string),
            c_bar_at_min: s.c_bar_at_min,
            d_bar_at_min: s.d_bar_at_min,
            jg_f_ad_bar: s.jg_f_ad_bar,
            n_d: finest.and_then(|r| r.n_d),
            grid: finest.map_or(0, |r| r.nx),
            dx: finest.map_or(0.0, |r| r.dx),
            wall_s: s.wall_s,
            ny: finest.map_or(0, |r| r.ny),
            backend: finest.map_or(String::new(), |r| format!("{}-{}", r.backend, r.precision)),
            complete: s.complete,
            min_reached: s.min_reached,
            error: s.runs.iter().find_map(|r| r.error.clone()),
        }
    }

    /// The row of a pull-off that failed before it produced a summary (e.g. its backend did
    /// not open, or its states could not be written): incomplete, with the reason, and JG's
    /// |min F̄| for its ratio (`jg_f_ad_bar`, computed by the caller) as comparison.
    pub fn failed(
        ratio: f64,
        grid: (usize, usize),
        dx: f64,
        error: String,
        jg_f_ad_bar: Option<f64>,
    ) -> SweepRow {
        SweepRow {
            ratio,
            f_ad_bar: None,
            f_ad_bar_uncertainty: None,
            estimate: None,
            c_bar_at_min: None,
            d_bar_at_min: None,
            jg_f_ad_bar,
            n_d: None,
            grid: grid.0,
            dx,
            wall_s: 0.0,
            ny: grid.1,
            backend: String::new(),
            complete: false,
            min_reached: false,
            error: Some(error),
        }
    }

    /// Whether the row holds a usable adhesive force: complete, minimum reached, and every
    /// number finite.
    pub fn is_usable(&self) -> bool {
        let finite = |v: Option<f64>| v.is_some_and(f64::is_finite);
        self.complete
            && self.min_reached
            && finite(self.f_ad_bar)
            && finite(self.c_bar_at_min)
            && finite(self.d_bar_at_min)
            && self.dx.is_finite()
    }
}

/// The CSV header of a sweep's summary, one column per [`SweepRow`] field.
pub const HEADER: &str = "ratio,f_ad_bar,f_ad_bar_uncertainty,estimate,c_bar_at_min,\
d_bar_at_min,jg_f_ad_bar,n_d,grid,dx,wall_s,ny,backend,complete,min_reached,error";

use super::file::{read_regular, ReadError};
pub use super::names::{shard as shard_path, sweep_csv as sweep_csv_path};

/// Write rows (sorted by ratio) to `path` atomically, header first even without rows.
pub fn write_rows(path: &Path, rows: &[SweepRow]) -> Result<(), OutputError> {
    let mut rows = rows.to_vec();
    rows.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    file::write_csv(path, Some(HEADER), &rows)
}

/// Read the rows of a sweep CSV.
pub fn read_rows(path: &Path) -> Result<Vec<SweepRow>, csv::Error> {
    csv::Reader::from_path(path)?.deserialize().collect()
}

/// What makes one sweep: every shard of it records these, and [`collect`] merges only shards
/// that agree on them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepSettings {
    /// Every ratio R1/R2 of the sweep, in the order of `--ratios`.
    pub ratios: Vec<f64>,
    /// Elements along x, Nx (`--grid`), if every ratio had the same.
    pub grid: Option<usize>,
    /// The relative accuracy each ratio's grid was planned for (`--accuracy`), if it was.
    #[serde(default)]
    pub accuracy: Option<f64>,
    /// Load steps (`--steps`).
    pub steps: usize,
    /// Mean radius c̄0 of the first contact (`--start-radius`, dimensionless).
    pub start_radius: f64,
    /// Free margin around the first contact (`--margin`, dimensionless).
    pub margin: f64,
}

/// What a shard file says of its format.
pub const SHARD_FORMAT: &str = "jkrbem sweep shard 1";

/// One shard's file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Shard {
    /// [`SHARD_FORMAT`].
    pub format: String,
    /// The sweep it is part of.
    pub sweep: SweepSettings,
    /// Its position K (1-based).
    pub shard: usize,
    /// The number of shards N.
    pub of: usize,
    /// The ratios it was given ([`shard_ratios`]).
    pub ratios: Vec<f64>,
    /// One row per ratio it ran.
    pub rows: Vec<SweepRow>,
}

impl Shard {
    /// Shard `k` of `n` of `sweep`, with its rows.
    pub fn new(sweep: SweepSettings, (k, n): (usize, usize), rows: Vec<SweepRow>) -> Self {
        let ratios = shard_ratios(&sweep.ratios, Some((k, n)));
        Shard {
            format: SHARD_FORMAT.into(),
            sweep,
            shard: k,
            of: n,
            ratios,
            rows,
        }
    }

    /// Write it as JSON, atomically. Non-finite numbers are written as null.
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        let text = serde_json::to_string_pretty(self).expect("a shard always serialises");
        file::write_text(path, &(text + "\n"))
    }
}

/// What `collect` found in a folder of shard files.
#[derive(Debug, Clone, PartialEq)]
pub struct Collected {
    /// The sweep the shards belong to.
    pub sweep: SweepSettings,
    /// All rows found, sorted by ratio.
    pub rows: Vec<SweepRow>,
    /// The shard file of each row, in the order of `rows`.
    pub row_files: Vec<PathBuf>,
    /// Shard count N.
    pub shards: usize,
    /// Shards (1-based) whose file is missing.
    pub missing_shards: Vec<usize>,
    /// Ratios with no row (their shard is missing, or it did not record them).
    pub missing: Vec<f64>,
    /// Ratios whose row is not usable ([`SweepRow::is_usable`]): failed, no minimum reached,
    /// or not finite.
    pub incomplete: Vec<f64>,
}

/// Errors of [`collect`].
#[derive(Debug, thiserror::Error)]
pub enum CollectError {
    /// The folder could not be read.
    #[error("cannot read {0}: {1}")]
    Io(String, std::io::Error),
    /// No shard file was found.
    #[error("no sweep-shard-K-of-N.json files in {0} (a sweep run with {SHARD} K/N writes them)")]
    Empty(String),
    /// A file named as a shard is not a valid shard.
    #[error("{0} is not a valid shard file: {1}")]
    Corrupt(String, String),
    /// Shards of different sweeps were found.
    #[error("the shards in {0} are not of one sweep: {1}")]
    Mixed(String, String),
    /// A ratio was found more than once.
    #[error("R1/R2 = {ratio} appears more than once: {where_}")]
    Duplicate {
        /// The ratio.
        ratio: f64,
        /// The files (and how often) it appears in.
        where_: String,
    },
    /// A shard's row disagrees with the summary its ratio's run wrote.
    #[error(
        "R1/R2 = {ratio}: the row in {shard} does not match the ratio's own summary {summary}: \
         {why}; the shard file was edited or is of another run (run the shard again)"
    )]
    Mismatch {
        /// The ratio.
        ratio: f64,
        /// The shard file holding the row.
        shard: String,
        /// The per-ratio summary.
        summary: String,
        /// The fields that differ, with both values.
        why: String,
    },
}

/// The largest shard file [`collect`] reads (bytes). A shard records at most
/// [`MAX_SWEEP_RATIOS`] ratios and rows, well under a megabyte; a larger file is not a shard.
pub const MAX_SHARD_BYTES: u64 = 16 << 20;

/// The largest per-ratio summary [`check_row`] reads (bytes); a summary is a few kilobytes.
pub const MAX_SUMMARY_BYTES: u64 = 16 << 20;

/// The most ratios a sweep holds (`sweep --ratios` takes 1 to this many).
pub const MAX_SWEEP_RATIOS: usize = 1000;

/// (k, n) from "sweep-shard-K-of-N.json": `None` for a name of another form (a partial file,
/// say), `Some(Err)` for a shard's name with K outside 1..=N or N above [`MAX_SHARDS`] (the
/// shard counts `sweep --shard` accepts), so that such a file is refused before anything is
/// allocated for its N.
fn parse_shard_name(name: &str) -> Option<Result<(usize, usize), String>> {
    let rest = name.strip_prefix("sweep-shard-")?.strip_suffix(".json")?;
    let (k, n) = rest.split_once("-of-")?;
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    if !digits(k) || !digits(n) {
        return None;
    }
    let (k, n) = match (k.parse::<usize>(), n.parse::<usize>()) {
        (Ok(k), Ok(n)) if n <= MAX_SHARDS => (k, n),
        _ => {
            return Some(Err(format!(
                "it names N = {n} shards; a sweep is split into at most {MAX_SHARDS} \
                 ({SHARD} K/N)"
            )))
        }
    };
    if !(1..=n).contains(&k) {
        return Some(Err(format!(
            "it names shard {k} of {n}; K must be in 1..=N"
        )));
    }
    Some(Ok((k, n)))
}

/// The settings that differ between two sweeps, in words.
fn difference(a: &SweepSettings, b: &SweepSettings) -> String {
    let mut d = Vec::new();
    if a.ratios != b.ratios {
        d.push(format!("{RATIOS} {:?} against {:?}", a.ratios, b.ratios));
    }
    let grid = |s: &SweepSettings| match (s.grid, s.accuracy) {
        (Some(nx), _) => format!("{GRID} {nx}"),
        (None, Some(t)) => format!("{ACCURACY} {}%", crate::text::compact(100.0 * t)),
        (None, None) => "no grid".into(),
    };
    match (a.grid, b.grid) {
        (Some(x), Some(y)) if x != y => d.push(format!("{GRID} {x} against {y}")),
        _ if a.grid != b.grid || a.accuracy != b.accuracy => {
            d.push(format!("{} against {}", grid(a), grid(b)))
        }
        _ => {}
    }
    if a.steps != b.steps {
        d.push(format!("{STEPS} {} against {}", a.steps, b.steps));
    }
    if a.start_radius != b.start_radius {
        d.push(format!(
            "{START_RADIUS} {} against {}",
            a.start_radius, b.start_radius
        ));
    }
    if a.margin != b.margin {
        d.push(format!("{MARGIN} {} against {}", a.margin, b.margin));
    }
    d.join(", ")
}

/// Read and check one shard file named as shard `(k, n)`.
fn read_shard(path: &Path, (k, n): (usize, usize)) -> Result<Shard, CollectError> {
    let shown = path.display().to_string();
    let corrupt = |why: String| CollectError::Corrupt(shown.clone(), why);
    let bytes = read_regular(path, MAX_SHARD_BYTES).map_err(|e| match e {
        ReadError::Absent => corrupt("it was removed while being read".into()),
        ReadError::Refused(why) => corrupt(why),
    })?;
    let text =
        String::from_utf8(bytes).map_err(|_| corrupt("it is not UTF-8 text (JSON)".into()))?;
    if text.trim().is_empty() {
        return Err(corrupt(
            "the file is empty (a shard with no ratios still records its sweep); run the shard again"
                .into(),
        ));
    }
    let shard: Shard = serde_json::from_str(&text)
        .map_err(|e| corrupt(format!("{e} (truncated or edited?); run the shard again")))?;
    if shard.format != SHARD_FORMAT {
        return Err(corrupt(format!("unknown format {:?}", shard.format)));
    }
    let ratios = &shard.sweep.ratios;
    if ratios.is_empty() || ratios.len() > MAX_SWEEP_RATIOS {
        return Err(corrupt(format!(
            "its sweep has {} ratios; a sweep has 1 to {MAX_SWEEP_RATIOS} ({RATIOS})",
            ratios.len()
        )));
    }
    if let Some(r) = ratios.iter().find(|r| !(1.0..=MAX_RATIO).contains(*r)) {
        return Err(corrupt(format!(
            "its sweep has R1/R2 = {r}, outside [1, {MAX_RATIO}] (the range of {RATIOS})"
        )));
    }
    if let Some(r) = shard
        .rows
        .iter()
        .find(|r| !(1.0..=MAX_RATIO).contains(&r.ratio))
    {
        return Err(corrupt(format!(
            "it has a row for R1/R2 = {}, outside [1, {MAX_RATIO}] (the range of {RATIOS})",
            r.ratio
        )));
    }
    if (shard.shard, shard.of) != (k, n) {
        return Err(corrupt(format!(
            "named shard {k} of {n} but holds shard {} of {}",
            shard.shard, shard.of
        )));
    }
    if shard.ratios != shard_ratios(&shard.sweep.ratios, Some((k, n))) {
        return Err(corrupt(format!(
            "its ratios {:?} are not those of shard {k} of {n} of {RATIOS} {:?}",
            shard.ratios, shard.sweep.ratios
        )));
    }
    if let Some(r) = shard.rows.iter().find(|r| !shard.ratios.contains(&r.ratio)) {
        return Err(corrupt(format!(
            "it has a row for R1/R2 = {}, which is not one of its ratios {:?}",
            r.ratio, shard.ratios
        )));
    }
    if let Some(nx) = shard.sweep.grid {
        if let Some(r) = shard.rows.iter().find(|r| r.grid != nx) {
            return Err(corrupt(format!(
                "its row for R1/R2 = {} has grid {}, the sweep's is {nx}",
                r.ratio, r.grid
            )));
        }
    }
    Ok(shard)
}

/// Gather the shard files `sweep-shard-K-of-N.json` in `dir`, check that they are of one
/// sweep and that no ratio appears twice, and merge their rows.
pub fn collect(dir: &Path) -> Result<Collected, CollectError> {
    let shown = dir.display().to_string();
    let entries = std::fs::read_dir(dir).map_err(|e| CollectError::Io(shown.clone(), e))?;
    let mut found: Vec<((usize, usize), PathBuf)> = Vec::new();
    for entry in entries {
        let path = entry
            .map_err(|e| CollectError::Io(shown.clone(), e))?
            .path();
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
        match name.as_deref().and_then(parse_shard_name) {
            Some(Ok(kn)) => found.push((kn, path)),
            Some(Err(why)) => return Err(CollectError::Corrupt(path.display().to_string(), why)),
            None => {}
        }
    }
    if found.is_empty() {
        return Err(CollectError::Empty(shown));
    }
    found.sort();
    let mut counts: Vec<usize> = found.iter().map(|f| f.0 .1).collect();
    counts.dedup();
    if counts.len() > 1 {
        return Err(CollectError::Mixed(
            shown,
            format!("shard files of different shard counts N: {counts:?}"),
        ));
    }
    let n = counts[0];
    let mut shards = Vec::new();
    for (kn, path) in &found {
        shards.push((read_shard(path, *kn)?, path));
    }
    let (first, first_path) = (&shards[0].0, shards[0].1);
    for (s, path) in &shards[1..] {
        if s.sweep != first.sweep {
            return Err(CollectError::Mixed(
                shown,
                format!(
                    "{} and {} differ in {}",
                    first_path.display(),
                    path.display(),
                    difference(&first.sweep, &s.sweep)
                ),
            ));
        }
    }
    let sweep = first.sweep.clone();
    let mut listed = sweep.ratios.clone();
    listed.sort_by(f64::total_cmp);
    if let Some(w) = listed.windows(2).find(|w| w[0] == w[1]) {
        return Err(CollectError::Duplicate {
            ratio: w[0],
            where_: format!("twice in the sweep's {RATIOS} {:?}", sweep.ratios),
        });
    }
    for &ratio in &sweep.ratios {
        let holders: Vec<String> = shards
            .iter()
            .flat_map(|(s, p)| {
                s.rows
                    .iter()
                    .filter(move |r| r.ratio == ratio)
                    .map(move |_| p.display().to_string())
            })
            .collect();
        if holders.len() > 1 {
            return Err(CollectError::Duplicate {
                ratio,
                where_: holders.join(", "),
            });
        }
    }
    let mut sourced: Vec<(SweepRow, PathBuf)> = Vec::new();
    for (s, path) in &shards {
        sourced.extend(s.rows.iter().map(|r| (r.clone(), path.to_path_buf())));
    }
    sourced.sort_by(|a, b| a.0.ratio.total_cmp(&b.0.ratio));
    let (rows, row_files): (Vec<SweepRow>, Vec<PathBuf>) = sourced.into_iter().unzip();
    let missing_shards = (1..=n)
        .filter(|k| !shards.iter().any(|(s, _)| s.shard == *k))
        .collect();
    let missing = sweep
        .ratios
        .iter()
        .copied()
        .filter(|r| !rows.iter().any(|row| row.ratio == *r))
        .collect();
    let incomplete = rows
        .iter()
        .filter(|r| !r.is_usable())
        .map(|r| r.ratio)
        .collect();
    Ok(Collected {
        sweep,
        rows,
        row_files,
        shards: n,
        missing_shards,
        missing,
        incomplete,
    })
}

/// The fields of a per-ratio summary (see [`Summary`]) that a sweep row copies
/// ([`SweepRow::from_summary`]); the rest of the summary is not read.
#[derive(Debug, Deserialize)]
struct SummaryFields {
    ratio: f64,
    estimate: Option<String>,
    f_ad_bar: Option<f64>,
    f_ad_bar_uncertainty: Option<f64>,
    c_bar_at_min: Option<f64>,
    d_bar_at_min: Option<f64>,
    jg_f_ad_bar: Option<f64>,
    min_reached: bool,
    complete: bool,
    runs: Vec<RunFields>,
}

/// The fields of one run of a summary that a sweep row copies from its finest run.
#[derive(Debug, Deserialize)]
struct RunFields {
    nx: usize,
    ny: usize,
    dx: Option<f64>,
    n_d: Option<f64>,
}

/// What [`check_row`] found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowCheck {
    /// The row holds what its ratio's summary says.
    Agrees,
    /// There is no summary to check it against (the shard's files were not copied beside it).
    NoSummary,
}

/// Whether two numbers of a row and its summary are the same (to a relative 1e-9, so that a
/// tool that re-prints the JSON with fewer digits is not taken for an edit).
fn same(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => a == b || (a - b).abs() <= 1e-9 * a.abs().max(b.abs()),
        _ => false,
    }
}

/// A number for a message: "0.9" or "none".
fn shown(v: Option<f64>) -> String {
    v.map_or("none".into(), |v| v.to_string())
}

/// Check `row`, read from the shard file `shard`, against the summary its ratio's run wrote
/// (`summary`, the `.json` beside its states): every value the row copies from it (the
/// estimate of |min F̄| and its uncertainty, c̄ and d̄ at the minimum, JG's value, n_d, the
/// grid, Δx, and whether the run completed and reached the minimum) must be the summary's.
/// A summary that is absent is [`RowCheck::NoSummary`]; one that is not a regular file, is
/// larger than [`MAX_SUMMARY_BYTES`], is not a summary, or disagrees is an error naming the
/// ratio and both files.
pub fn check_row(row: &SweepRow, shard: &Path, summary: &Path) -> Result<RowCheck, CollectError> {
    let summary_shown = summary.display().to_string();
    let corrupt = |why: String| {
        CollectError::Corrupt(
            summary_shown.clone(),
            format!(
                "{why} (the summary of R1/R2 = {}, read to check {})",
                row.ratio,
                shard.display()
            ),
        )
    };
    let bytes = match read_regular(summary, MAX_SUMMARY_BYTES) {
        Ok(bytes) => bytes,
        Err(ReadError::Absent) => return Ok(RowCheck::NoSummary),
        Err(ReadError::Refused(why)) => return Err(corrupt(why)),
    };
    let s: SummaryFields = serde_json::from_slice(&bytes)
        .map_err(|e| corrupt(format!("not a jkrbem summary: {e}")))?;
    let finest = s.runs.last();
    let mut differ = Vec::new();
    let mut num = |name: &str, got: Option<f64>, want: Option<f64>| {
        if !same(got, want) {
            differ.push(format!("{name} = {} against {}", shown(got), shown(want)));
        }
    };
    num("ratio", Some(row.ratio), Some(s.ratio));
    num("f_ad_bar", row.f_ad_bar, s.f_ad_bar);
    num(
        "f_ad_bar_uncertainty",
        row.f_ad_bar_uncertainty,
        s.f_ad_bar_uncertainty,
    );
    num("c_bar_at_min", row.c_bar_at_min, s.c_bar_at_min);
    num("d_bar_at_min", row.d_bar_at_min, s.d_bar_at_min);
    num("jg_f_ad_bar", row.jg_f_ad_bar, s.jg_f_ad_bar);
    num("n_d", row.n_d, finest.and_then(|r| r.n_d));
    num("dx", Some(row.dx), finest.map_or(Some(0.0), |r| r.dx));
    let grid = finest.map_or((0, 0), |r| (r.nx, r.ny));
    if (row.grid, row.ny) != grid {
        differ.push(format!(
            "grid {}×{} against {}×{}",
            row.grid, row.ny, grid.0, grid.1
        ));
    }
    if row.estimate != s.estimate {
        differ.push(format!(
            "estimate = {:?} against {:?}",
            row.estimate, s.estimate
        ));
    }
    for (name, got, want) in [
        ("complete", row.complete, s.complete),
        ("min_reached", row.min_reached, s.min_reached),
    ] {
        if got != want {
            differ.push(format!("{name} = {got} against {want}"));
        }
    }
    if differ.is_empty() {
        Ok(RowCheck::Agrees)
    } else {
        Err(CollectError::Mismatch {
            ratio: row.ratio,
            shard: shard.display().to_string(),
            summary: summary_shown,
            why: differ.join(", "),
        })
    }
}

/// Parse a shard "K/N" (1 ≤ K ≤ N ≤ [`MAX_SHARDS`]).
pub fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let err = || format!("{SHARD} {text:?}: expected K/N with 1 ≤ K ≤ N ≤ {MAX_SHARDS}, e.g. 2/8");
    let (k, n) = text.split_once('/').ok_or_else(err)?;
    let (k, n): (usize, usize) = (
        k.trim().parse().map_err(|_| err())?,
        n.trim().parse().map_err(|_| err())?,
    );
    if k == 0 || k > n || n > MAX_SHARDS {
        return Err(err());
    }
    Ok((k, n))
}

pub use crate::params::limits::MAX_SHARDS;

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
            n_d: Some(60.0),
            grid: 128,
            dx: 0.05,
            ..SweepRow::sample(ratio, 0.5 / ratio.sqrt())
        }
    }

    fn settings(ratios: &[f64]) -> SweepSettings {
        SweepSettings {
            ratios: ratios.to_vec(),
            grid: Some(128),
            accuracy: None,
            steps: 200,
            start_radius: 1.5,
            margin: 0.08,
        }
    }

    fn write_shard(dir: &Path, sweep: &SweepSettings, kn: (usize, usize), rows: Vec<SweepRow>) {
        Shard::new(sweep.clone(), kn, rows)
            .write(&shard_path(dir, kn))
            .unwrap();
    }

    #[test]
    fn shards_partition_the_ratios_and_collect_merges_them() {
        let ratios = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0];
        let sweep = settings(&ratios);
        let dir = tempfile::tempdir().unwrap();
        let mut all = Vec::new();
        for k in 1..=4 {
            let mine = shard_ratios(&ratios, Some((k, 4)));
            all.extend(mine.clone());
            if k != 3 {
                write_shard(
                    dir.path(),
                    &sweep,
                    (k, 4),
                    mine.iter().map(|&r| row(r)).collect(),
                );
            }
        }
        all.sort_by(f64::total_cmp);
        assert_eq!(all, ratios);
        let c = collect(dir.path()).unwrap();
        assert_eq!(c.shards, 4);
        assert_eq!(c.missing_shards, vec![3]);
        assert_eq!(c.missing, vec![5.0]);
        assert!(c.incomplete.is_empty());
        let got: Vec<f64> = c.rows.iter().map(|r| r.ratio).collect();
        assert_eq!(got, vec![1.0, 2.0, 10.0, 25.0, 50.0]);
        assert_eq!(c.rows[0], row(1.0));
    }

    #[test]
    fn an_empty_shard_is_a_valid_file_and_an_empty_file_is_not() {
        let sweep = settings(&[1.0, 2.0]);
        let dir = tempfile::tempdir().unwrap();
        write_shard(dir.path(), &sweep, (1, 3), vec![row(1.0)]);
        write_shard(dir.path(), &sweep, (2, 3), vec![row(2.0)]);
        write_shard(dir.path(), &sweep, (3, 3), vec![]);
        let c = collect(dir.path()).unwrap();
        assert!(c.missing.is_empty() && c.missing_shards.is_empty());
        std::fs::write(shard_path(dir.path(), (3, 3)), "").unwrap();
        let e = collect(dir.path()).unwrap_err();
        assert!(matches!(e, CollectError::Corrupt(..)), "{e}");
        assert!(e.to_string().contains("empty"), "{e}");
    }

    #[test]
    fn shards_of_different_sweeps_and_repeated_ratios_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        write_shard(dir.path(), &settings(&[1.0, 2.0]), (1, 2), vec![row(1.0)]);
        let mut other = settings(&[1.0, 2.0]);
        other.grid = Some(64);
        let mut r2 = row(2.0);
        r2.grid = 64;
        write_shard(dir.path(), &other, (2, 2), vec![r2]);
        let e = collect(dir.path()).unwrap_err();
        assert!(
            crate::params::words::flags(&e.to_string()).contains("--grid 128 against 64"),
            "{e}"
        );

        let dir = tempfile::tempdir().unwrap();
        let sweep = settings(&[1.0, 2.0]);
        write_shard(dir.path(), &sweep, (1, 2), vec![row(1.0), row(1.0)]);
        write_shard(dir.path(), &sweep, (2, 2), vec![row(2.0)]);
        let e = collect(dir.path()).unwrap_err();
        assert!(
            matches!(e, CollectError::Duplicate { ratio, .. } if ratio == 1.0),
            "{e}"
        );
    }

    #[test]
    fn incomplete_and_non_finite_rows_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let sweep = settings(&[1.0, 2.0, 5.0]);
        let mut failed = row(2.0);
        failed.complete = false;
        let mut nan = row(5.0);
        nan.f_ad_bar = Some(f64::NAN);
        write_shard(dir.path(), &sweep, (1, 1), vec![row(1.0), failed, nan]);
        let c = collect(dir.path()).unwrap();
        assert_eq!(c.incomplete, vec![2.0, 5.0]);
    }

    #[test]
    fn shard_text_is_checked() {
        assert_eq!(parse_shard("2/8"), Ok((2, 8)));
        for bad in ["0/4", "5/4", "x/4", "3", "1/0", "1/100000"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
