//! `jkrbem collect DIR` for a batch: the records its runs left (`batch.json`,
//! `batch-shard-K-of-N.json`, each holding its own rows and the table's digest) checked to be
//! of one table and to hold its shard's rows, the scenes of the shards that left no record
//! named, and every recorded scene's summary merged, in
//! the table's order, into `DIR/batch.csv` (its id, every parameter as its request recorded
//! it, its results) and `DIR/batch-timings.csv` (the wall times, kept apart so that a batch
//! collects to the same table however it was split). Missing, stale and incomplete scenes
//! are named.

use super::table::MAX_SCENES;
use crate::output::batch_csv::{self, BatchRow, Manifest, ManifestScene, TableDigest};
use crate::output::digest::{CurrentDigests, InputFile};
use crate::output::file::{note_input, read_regular, ReadError};
use crate::output::names;
use crate::output::sweep_csv::MAX_SHARDS;
use crate::params::{values, Fronts, SPECS};
use crate::params::{ALLOW_MISSING, HEIGHT_MAP, RESUME, ROUGHNESS};
use crate::session::claim::{named, write_error, Outputs};
use crate::session::request::Request;
use crate::session::{failed, input, RunError};
use crate::text::listed;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The folder `collect` merges, as the command names it.
const DIR: crate::output::NamedBy = crate::output::NamedBy::Argument("DIR");

/// What merging a batch produced.
#[derive(Debug, Clone)]
pub struct BatchMerged {
    /// Scenes of the batch.
    pub scenes: usize,
    /// Rows written (scenes with a summary of their request).
    pub rows: usize,
    /// The records found.
    pub records: Vec<PathBuf>,
    /// `batch.csv`.
    pub path: PathBuf,
    /// `batch-timings.csv`.
    pub timings: PathBuf,
    /// What is missing, stale or incomplete (merged anyway with `allow_missing`).
    pub problems: Vec<String>,
}

/// The records of batches in `dir`, with the shard each names (`None`: a whole batch).
pub fn records_in(dir: &Path) -> Vec<(PathBuf, Option<(usize, usize)>)> {
    let mut found: Vec<(PathBuf, Option<(usize, usize)>)> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            names::parse_batch_manifest(&name).map(|shard| (e.path(), shard))
        })
        .collect();
    found.sort_by(|a, b| a.1.cmp(&b.1).then_with(|| a.0.cmp(&b.0)));
    found
}

/// Whether row `j` (from 0) of a table is of `shard` (every row is of a whole batch).
fn of_shard(j: usize, shard: Option<(usize, usize)>) -> bool {
    shard.is_none_or(|(k, n)| j % n + 1 == k)
}

/// "shard 2 of 4", or "the whole batch".
fn shard_text(shard: Option<(usize, usize)>) -> String {
    shard.map_or_else(
        || "the whole batch".into(),
        |(k, n)| format!("shard {k} of {n}"),
    )
}

/// The scenes of the batch whose records are in `dir`, by their place in its table: each
/// that a record holds (`None` where none does: its shard left no record). Every record is
/// checked to be of one table (its number of scenes and digest), to hold exactly its shard's
/// rows, and to agree with the others on a row they both hold; where together they hold every
/// row, those rows must make the table their digest names.
fn batch_scenes(
    dir: &Path,
    records: &[(PathBuf, Option<(usize, usize)>)],
) -> Result<Vec<Option<ManifestScene>>, RunError> {
    let mut first: Option<(&Path, TableDigest)> = None;
    let mut scenes: Vec<Option<(ManifestScene, &Path)>> = Vec::new();
    for (path, shard) in records {
        let invalid = |why: String| {
            failed(format!(
                "{} is not a valid batch record: {why}",
                path.display()
            ))
        };
        let m = Manifest::read(path).map_err(invalid)?;
        let valid = |(k, n): (usize, usize)| (1..=n).contains(&k) && n <= MAX_SHARDS;
        if m.shard != *shard || !shard.is_none_or(valid) {
            return Err(invalid(format!(
                "its name and its content name different shards, or a shard K of N outside \
                 1 ≤ K ≤ N ≤ {MAX_SHARDS}"
            )));
        }
        if m.table.scenes == 0 || m.table.scenes > MAX_SCENES {
            return Err(invalid(format!(
                "a table of {} scenes, outside 1 to {MAX_SCENES} (edited?)",
                m.table.scenes
            )));
        }
        match &first {
            None => {
                scenes = vec![None; m.table.scenes];
                first = Some((path, m.table.clone()));
            }
            Some((p, t)) if *t != m.table => {
                return Err(failed(format!(
                    "{} and {} record different batches (a table of {} scenes, CRC-32 {}, \
                     against {}, CRC-32 {}: the table changed between runs): run every shard \
                     of the same table again with {RESUME} (it skips the scenes already done), \
                     or remove the older record from {}",
                    p.display(),
                    path.display(),
                    t.scenes,
                    t.crc32,
                    m.table.scenes,
                    m.table.crc32,
                    dir.display()
                )));
            }
            Some(_) => {}
        }
        let total = m.table.scenes;
        let expected: Vec<usize> = (0..total).filter(|&j| of_shard(j, *shard)).collect();
        let held: Vec<usize> = m.scenes.iter().map(|s| s.row.wrapping_sub(1)).collect();
        if held != expected {
            return Err(invalid(format!(
                "it holds {} row(s), not the {} of {} in the table's order (truncated or \
                 edited?); run the batch again",
                held.len(),
                expected.len(),
                shard_text(*shard)
            )));
        }
        for scene in m.scenes {
            let j = scene.row - 1;
            match &scenes[j] {
                Some((other, p)) if *other != scene => {
                    return Err(failed(format!(
                        "{} and {} hold different scenes at row {} ({} against {}): one of \
                         them was edited; run the batch again",
                        p.display(),
                        path.display(),
                        scene.row,
                        other.id,
                        scene.id
                    )))
                }
                Some(_) => {}
                None => scenes[j] = Some((scene, path)),
            }
        }
    }
    if let (Some((_, table)), true) = (&first, scenes.iter().all(Option::is_some)) {
        let made = TableDigest::of(
            scenes
                .iter()
                .flatten()
                .map(|(s, _)| (s.id.as_str(), &s.request)),
        );
        if made != *table {
            return Err(failed(format!(
                "the records in {} hold rows that do not make the table their digest names \
                 (CRC-32 {} against {}): a record was edited; run the batch again",
                dir.display(),
                made.crc32,
                table.crc32
            )));
        }
    }
    Ok(scenes.into_iter().map(|s| s.map(|(s, _)| s)).collect())
}

/// What a scene's summary says, or why it is no row.
enum Scene {
    /// Its row.
    Row(Box<BatchRow>),
    /// It has no summary.
    Missing,
    /// Its summary is unreadable or of another request: why, in words.
    Stale(String),
}

/// A summary's number field.
fn number(v: &Value, key: &str) -> Option<f64> {
    v.get(key).and_then(Value::as_f64)
}

/// Why the files a summary's scene read no longer hold what it read (a height map replaced
/// since), or `None` where they still do. A request that names a file whose summary records
/// no digest of it (an older version's) cannot be vouched for.
fn files_changed(summary: &Value, request: &Value, now: &mut CurrentDigests) -> Option<String> {
    let files = match summary.pointer("/provenance/input_files") {
        None => Vec::new(),
        Some(f) => match serde_json::from_value::<Vec<InputFile>>(f.clone()) {
            Ok(f) => f,
            Err(_) => return Some("its record of the files it read is unreadable".into()),
        },
    };
    for param in [HEIGHT_MAP, ROUGHNESS] {
        let named = request.get(param.name).is_some_and(|v| !v.is_null());
        if named && !files.iter().any(|f| f.parameter == param.name) {
            return Some(format!(
                "it records no digest of its {param} file (written by an older version), so \
                 it cannot be checked against the file as it is now"
            ));
        }
    }
    files.iter().find_map(|f| now.changed(f))
}

/// The row of `scene` from its summary in `dir`, the files it read checked against `now`.
fn scene_row(dir: &Path, scene: &ManifestScene, now: &mut CurrentDigests) -> Scene {
    let path = names::scene_summary(dir, &scene.id);
    let bytes = match read_regular(&path, 16 << 20) {
        Ok(b) => b,
        Err(ReadError::Absent) => return Scene::Missing,
        Err(ReadError::Refused(why)) => return Scene::Stale(format!("{}: {why}", path.display())),
    };
    note_input(&path, "DIR");
    let Ok(s) = serde_json::from_slice::<Value>(&bytes) else {
        return Scene::Stale(format!("{} is not a summary (edited?)", path.display()));
    };
    let recorded = s.pointer("/provenance/request").cloned();
    let same = match (
        recorded,
        serde_json::from_value::<Request>(scene.request.clone()),
    ) {
        (Some(r), Ok(want)) => serde_json::from_value::<Request>(r).ok() == Some(want),
        _ => false,
    };
    if !same {
        return Scene::Stale(format!(
            "{} is of another request (the table changed since it ran)",
            path.display()
        ));
    }
    if let Some(why) = files_changed(&s, &scene.request, now) {
        return Scene::Stale(format!("{}: {why}", path.display()));
    }
    let parameters = SPECS
        .iter()
        .filter(|spec| spec.fronts != Fronts::Cli)
        .map(|spec| values::to_text(spec, scene.request.get(spec.name).unwrap_or(&Value::Null)))
        .collect();
    let runs = s.get("runs").and_then(Value::as_array);
    let flag = |key: &str| s.get(key).and_then(Value::as_bool).unwrap_or(false);
    Scene::Row(Box::new(BatchRow {
        id: scene.id.clone(),
        parameters,
        f_ad_bar: number(&s, "f_ad_bar"),
        f_ad_bar_uncertainty: number(&s, "f_ad_bar_uncertainty"),
        estimate: s.get("estimate").and_then(Value::as_str).map(String::from),
        c_bar_at_min: number(&s, "c_bar_at_min"),
        d_bar_at_min: number(&s, "d_bar_at_min"),
        grid_f_ad_bar: runs
            .and_then(|r| r.last())
            .and_then(|r| number(r, "f_ad_bar")),
        min_reached: flag("min_reached"),
        complete: flag("complete"),
        cg_iterations: s.get("cg_iterations").and_then(Value::as_u64).unwrap_or(0),
        warnings: s
            .get("warnings")
            .and_then(Value::as_array)
            .map_or(0, Vec::len),
        wall_s: number(&s, "wall_s").unwrap_or(f64::NAN),
    }))
}

/// The shards of an N-way split that left no record, where every record found is of one
/// split; else none.
fn shards_not_started(
    records: &[(PathBuf, Option<(usize, usize)>)],
) -> Option<(Vec<usize>, usize)> {
    let n = records.first()?.1?.1;
    if records.iter().any(|(_, s)| s.is_none_or(|(_, m)| m != n)) {
        return None;
    }
    let missing: Vec<usize> = (1..=n)
        .filter(|k| !records.iter().any(|(_, s)| s.is_some_and(|(j, _)| j == *k)))
        .collect();
    (!missing.is_empty()).then_some((missing, n))
}

/// Merge the batch in `dir` into `batch.csv` and `batch-timings.csv`, after checking that its
/// records are of one batch. Missing, stale or incomplete scenes stop the merge (naming them)
/// unless `allow_missing`.
pub fn collect_batch(dir: &Path, allow_missing: bool) -> Result<BatchMerged, RunError> {
    let records = records_in(dir);
    if records.is_empty() {
        return Err(input(format!(
            "no batch records (batch.json, batch-shard-K-of-N.json) in {}",
            dir.display()
        )));
    }
    for (path, _) in &records {
        note_input(path, "DIR");
    }
    let scenes = batch_scenes(dir, &records)?;
    let unrecorded: Vec<usize> = (1..=scenes.len())
        .filter(|&row| scenes[row - 1].is_none())
        .collect();
    let mut rows = Vec::new();
    let mut missing = Vec::new();
    let mut stale = Vec::new();
    let mut incomplete = Vec::new();
    let mut now = CurrentDigests::default();
    for scene in scenes.iter().flatten() {
        match scene_row(dir, scene, &mut now) {
            Scene::Row(row) => {
                if !row.complete {
                    incomplete.push(row.id.clone());
                }
                rows.push(*row);
            }
            Scene::Missing => missing.push(scene.id.clone()),
            Scene::Stale(why) => stale.push(format!("scene {}: {why}", scene.id)),
        }
    }
    let mut problems = Vec::new();
    if !unrecorded.is_empty() {
        let which = shards_not_started(&records).map_or_else(
            || {
                format!(
                    "rows [{}] of the table: run the shards that hold them",
                    listed(&unrecorded)
                )
            },
            |(ks, n)| {
                format!(
                    "shards [{}] of {n} have left no record: run them",
                    listed(&ks)
                )
            },
        );
        problems.push(format!(
            "{} of the {} scene(s) are in no record ({which})",
            unrecorded.len(),
            scenes.len()
        ));
    }
    if !missing.is_empty() {
        problems.push(format!(
            "{} scene(s) missing, with no summary: {}",
            missing.len(),
            listed(&missing)
        ));
    }
    if !stale.is_empty() {
        problems.push(format!(
            "{} scene(s) without a summary of their request and files as they are now (run \
             the batch again with {RESUME}): {}",
            stale.len(),
            stale.join("; ")
        ));
    }
    if !incomplete.is_empty() {
        problems.push(format!(
            "{} scene(s) incomplete (a run failed or stopped early: see their summaries' \
             warnings and runs): {}",
            incomplete.len(),
            listed(&incomplete)
        ));
    }
    if !problems.is_empty() && !allow_missing {
        return Err(failed(format!(
            "{}; nothing was written (pass {ALLOW_MISSING} to merge what there is)",
            problems.join("; ")
        )));
    }
    let path = names::batch_csv(dir);
    let timings = names::batch_timings(dir);
    let _claimed = Outputs::claim(&named(DIR, [&path, &timings]))?;
    let parameters: Vec<&str> = SPECS
        .iter()
        .filter(|spec| spec.fronts != Fronts::Cli)
        .map(|spec| spec.name)
        .collect();
    batch_csv::write_table(&path, &parameters, &rows).map_err(write_error(DIR))?;
    batch_csv::write_timings(&timings, &rows).map_err(write_error(DIR))?;
    Ok(BatchMerged {
        scenes: scenes.len(),
        rows: rows.len(),
        records: records.into_iter().map(|(p, _)| p).collect(),
        path,
        timings,
        problems,
    })
}
