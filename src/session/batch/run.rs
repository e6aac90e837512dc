//! `jkrbem batch`: every scene of a table (or one shard of them) simulated to its own files,
//! `DIR/scene-<id>.csv` (states) and `DIR/scene-<id>.json` (summary, its provenance holding the
//! scene's request), with the batch's record beside them (`batch.json`, or
//! `batch-shard-K-of-N.json`: the run's own rows and the whole table's digest) for `collect`.
//! Every row is checked before any work; with
//! `resume`, a scene whose summary is complete, records the same request and read the same
//! files (size and CRC-32) is not run again.

use super::pool::{run_all, SceneEnded, SceneJob};
use super::table::{self, Row, Table};
use crate::model::Model;
use crate::output::batch_csv::{Manifest, ManifestScene, TableHasher, MANIFEST_FORMAT};
use crate::output::digest::InputFile;
use crate::output::file::{note_input, read_regular};
use crate::output::names;
use crate::output::NamedBy;
use crate::params::{words, OUT};
use crate::session::claim::{write_error, Outputs};
use crate::session::request::{MapReads, Request};
use crate::session::simulate::{planned_outputs, SimulateRequest, Sink};
use crate::session::{input, RunError, Watch};
use crate::solver::State;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A request for a batch.
#[derive(Debug, Clone)]
pub struct BatchRequest {
    /// The table of scenes (CSV).
    pub scenes: PathBuf,
    /// The folder every scene's files and the batch's record go to.
    pub out: PathBuf,
    /// Run only shard (K, N): the rows whose place j (from 0) has j mod N = K − 1.
    pub shard: Option<(usize, usize)>,
    /// Skip each scene whose summary is complete and records the same request.
    pub resume: bool,
    /// Scenes run at the same time (each on its own backend).
    pub jobs: usize,
}

/// What became of one scene this run took.
#[derive(Debug, Clone)]
pub struct SceneOutcome {
    /// Its id.
    pub id: String,
    /// Its summary JSON (written if it ran to an answer or fell short after starting).
    pub summary: PathBuf,
    /// Its estimate of |min F̄| (dimensionless), if it has one.
    pub f_ad_bar: Option<f64>,
    /// Its uncertainty (absolute), if stated.
    pub f_ad_bar_uncertainty: Option<f64>,
    /// Why it failed or fell short, if it did (named by the scene).
    pub failure: Option<String>,
}

/// What a batch run did.
#[derive(Debug, Clone)]
pub struct BatchDone {
    /// Scenes in the table.
    pub total: usize,
    /// Scenes of this shard (all of them, unsharded).
    pub in_shard: usize,
    /// The scenes run, in the table's order.
    pub ran: Vec<SceneOutcome>,
    /// The ids of the scenes skipped (`resume`: complete, with the same request).
    pub skipped: Vec<String>,
    /// The batch's record.
    pub manifest: PathBuf,
}

impl BatchDone {
    /// Why scenes failed or fell short, one line each.
    pub fn failures(&self) -> Vec<String> {
        self.ran.iter().filter_map(|s| s.failure.clone()).collect()
    }
}

/// A scene's simulation, to its own files in `dir`, its files read through `reads` (each file
/// once, however many rows name it).
fn scene_request(row: &Row, dir: &Path, reads: &mut MapReads) -> Result<SimulateRequest, RunError> {
    row.request.simulate_request_sharing(
        Sink::Files {
            out: Some(names::scene_states(dir, &row.id)),
            summary: Some(names::scene_summary(dir, &row.id)),
        },
        None,
        reads,
    )
}

/// The largest summary read to decide whether a scene is done (bytes).
const MAX_SUMMARY_BYTES: u64 = 16 << 20;

/// Whether the summary at `path` is complete, records `request` and read the files `read`
/// holds as they are now (the same size and CRC-32 of each): the scene need not run again.
/// Anything else (absent, unreadable, incomplete, of another request or another version's
/// schema, a file replaced since) says it must.
pub fn is_done(path: &Path, request: &Request, read: &[InputFile]) -> bool {
    let Ok(bytes) = read_regular(path, MAX_SUMMARY_BYTES) else {
        return false;
    };
    let Ok(summary) = serde_json::from_slice::<serde_json::Value>(&bytes) else {
        return false;
    };
    let provenance = summary.get("provenance");
    let recorded = provenance
        .and_then(|p| p.get("request"))
        .cloned()
        .and_then(|r| serde_json::from_value::<Request>(r).ok());
    let files = provenance
        .and_then(|p| p.get("input_files"))
        .cloned()
        .map_or(Some(Vec::new()), |f| {
            serde_json::from_value::<Vec<InputFile>>(f).ok()
        });
    let contents = |f: &[InputFile]| {
        f.iter()
            .map(|i| (i.parameter.clone(), i.digest.clone()))
            .collect::<Vec<_>>()
    };
    summary.get("complete") == Some(&serde_json::Value::Bool(true))
        && recorded.as_ref() == Some(request)
        && files.is_some_and(|f| contents(&f) == contents(read))
}

/// A batch's [`Watch`]: what its scenes say, in the table's words (each parameter as its
/// column's name, `cg_max_iterations`, where a scene's own run would name `simulate`'s flag),
/// passed on to `inner`.
struct TableWords<'a>(&'a dyn Watch);

impl Watch for TableWords<'_> {
    fn note(&self, line: &str) {
        self.0.note(&words::keywords(line))
    }
    fn pulloff_started(&self, model: &Model) {
        self.0.pulloff_started(model)
    }
    fn state(&self, model: &Model, state: &State) {
        self.0.state(model, state)
    }
    fn state_held(&self, model: &Model, state: &State) {
        self.0.state_held(model, state)
    }
    fn pulloff_ended(&self) {
        self.0.pulloff_ended()
    }
    fn warning(&self, line: &str) {
        self.0.warning(&words::keywords(line))
    }
    fn scene_ended(&self, scene: &SceneEnded) {
        let failure = scene.failure.map(words::keywords);
        self.0.scene_ended(&SceneEnded {
            failure: failure.as_deref(),
            ..scene.clone()
        })
    }
    fn keep_going(&self) -> bool {
        self.0.keep_going()
    }
}

/// A row's simulation, checked, and the files it writes (each with the flag that names it).
struct Checked {
    request: SimulateRequest,
    targets: Vec<(PathBuf, NamedBy)>,
}

/// Every row's simulation, checked as `simulate` checks it before any work, with the files
/// each writes; two rows that would write one file are refused, naming both. Each file the
/// rows read (a height map, a roughness) is read once, and its map shared by the rows naming
/// it.
fn checked_scenes(table: &Table, dir: &Path) -> Result<Vec<Checked>, RunError> {
    let mut writers: HashMap<PathBuf, usize> = HashMap::new();
    let mut out = Vec::with_capacity(table.rows.len());
    let mut reads = MapReads::default();
    for row in &table.rows {
        let refused = |e: RunError| table.refusal(row, &e.to_string());
        let sim = scene_request(row, dir, &mut reads).map_err(refused)?;
        // Every file of a scene is in the batch's folder, named by the batch's flag (the
        // scene's own, its states' and summary's, are no column of the table).
        let targets: Vec<(PathBuf, NamedBy)> = planned_outputs(&sim)
            .map_err(refused)?
            .into_iter()
            .map(|(path, _)| (path, OUT.into()))
            .collect();
        for (path, _) in &targets {
            if let Some(other) = writers.insert(path.clone(), row.index) {
                return Err(input(format!(
                    "{} and {} would both write {}: give them ids that differ more",
                    table.place(&table.rows[other]),
                    table.place(row),
                    path.display()
                )));
            }
        }
        out.push(Checked {
            request: sim,
            targets,
        });
    }
    Ok(out)
}

/// Run the batch: read and check every row (the other shards' too), check this shard's
/// files, write the batch's record, skip what `resume` finds done and run the rest.
pub fn batch(req: &BatchRequest, watch: &dyn Watch) -> Result<BatchDone, RunError> {
    note_input(&req.scenes, "SCENES");
    let table = table::read(&req.scenes)?;
    let scenes = checked_scenes(&table, &req.out)?;
    let mine: Vec<usize> = (0..table.rows.len())
        .filter(|j| req.shard.is_none_or(|(k, n)| j % n == k - 1))
        .collect();
    // What `resume` finds done is skipped, its files untouched (a write-protected one too);
    // the files of every other scene of the shard are checked before any work.
    let (done, to_run): (Vec<usize>, Vec<usize>) = mine.iter().partition(|&&j| {
        let row = &table.rows[j];
        req.resume
            && is_done(
                &names::scene_summary(&req.out, &row.id),
                &row.request,
                &scenes[j].request.input_files,
            )
    });
    for &j in &to_run {
        Outputs::check(&scenes[j].targets)?;
    }
    let manifest = names::batch_manifest(&req.out, req.shard);
    let _claimed = Outputs::claim(&[(manifest.clone(), OUT.into())])?;
    // The shard's own rows, and the digest of the whole table (so that `collect` tells the
    // shards of one table from another's without every record holding every row).
    let mut digest = TableHasher::default();
    let mut own = Vec::with_capacity(mine.len());
    for (j, row) in table.rows.iter().enumerate() {
        let request = row.request.to_json();
        digest.add(&row.id, &request);
        if req.shard.is_none_or(|(k, n)| j % n == k - 1) {
            own.push(ManifestScene {
                row: j + 1,
                id: row.id.clone(),
                request,
            });
        }
    }
    let record = Manifest {
        format: MANIFEST_FORMAT.to_string(),
        shard: req.shard,
        table: digest.finish(),
        scenes: own,
    };
    record.write(&manifest).map_err(write_error(OUT))?;
    let skipped: Vec<String> = done.iter().map(|&j| table.rows[j].id.clone()).collect();
    let mut jobs = Vec::new();
    let mut ran_rows = Vec::new();
    for &j in &to_run {
        let row = &table.rows[j];
        jobs.push(SceneJob {
            request: scenes[j].request.clone(),
            label: format!("scene {}", row.id),
        });
        ran_rows.push(row);
    }
    watch.note(&format!(
        "batch: {} scene(s){}, {} to run{}, {} at a time",
        table.rows.len(),
        req.shard.map_or(String::new(), |(k, n)| format!(
            ", shard {k} of {n} has {}",
            mine.len()
        )),
        jobs.len(),
        if skipped.is_empty() {
            String::new()
        } else {
            format!(
                ", {} skipped (complete, with the same request)",
                skipped.len()
            )
        },
        req.jobs
    ));
    let ran = run_all(jobs, req.jobs, &TableWords(watch), &|i, outcome| {
        let row = ran_rows[i];
        let summary = names::scene_summary(&req.out, &row.id);
        let label = format!("scene {}", row.id);
        match outcome {
            Ok(done) => SceneOutcome {
                id: row.id.clone(),
                summary,
                f_ad_bar: done.summary.f_ad_bar,
                f_ad_bar_uncertainty: done.summary.f_ad_bar_uncertainty,
                failure: done
                    .failure
                    .map(|f| format!("{label}: {}", words::keywords(&f))),
            },
            Err(e) => SceneOutcome {
                id: row.id.clone(),
                summary,
                f_ad_bar: None,
                f_ad_bar_uncertainty: None,
                failure: Some(format!("{label}: {}", words::keywords(&e.to_string()))),
            },
        }
    });
    Ok(BatchDone {
        total: table.rows.len(),
        in_shard: mine.len(),
        ran,
        skipped,
        manifest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Indenter;

    /// A sphere of unit radius sampled on `n`² nodes `spacing` apart, as text, its heights
    /// scaled by `scale`.
    fn sphere(n: usize, spacing: f64, scale: f64) -> String {
        let c = (n - 1) as f64 / 2.0;
        (0..n)
            .map(|j| {
                let y = (j as f64 - c) * spacing;
                let row: Vec<String> = (0..n)
                    .map(|i| {
                        let x = (i as f64 - c) * spacing;
                        format!("{:e}", scale * 0.5 * (x * x + y * y))
                    })
                    .collect();
                row.join(" ") + "\n"
            })
            .collect()
    }

    /// The heights of a checked scene's measured surface.
    fn heights(c: &Checked) -> &[f64] {
        match &c.request.scene.indenter {
            Indenter::HeightMap(s) => s.map.heights(),
            other => panic!("not a height map: {other:?}"),
        }
    }

    #[test]
    fn rows_naming_one_file_share_one_read_of_it_and_record_it_as_each_names_it() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        std::fs::create_dir(dir.join("sub")).unwrap();
        std::fs::write(dir.join("map.txt"), sphere(41, 0.05, 1.0)).unwrap();
        std::fs::write(dir.join("other.txt"), sphere(41, 0.05, 2.0)).unwrap();
        let d = dir.display();
        let table = format!(
            "id,indenter,height_map,spacing,grid,measure,backend\n\
             a,height-map,{d}/map.txt,0.05,32,adhesive-force,cpu\n\
             b,height-map,{d}/sub/../map.txt,0.05,32,adhesive-force,cpu\n\
             c,height-map,{d}/map.txt,0.05,32,adhesive-force,cpu\n\
             d,height-map,{d}/map.txt,0.06,32,adhesive-force,cpu\n\
             e,height-map,{d}/other.txt,0.05,32,adhesive-force,cpu\n"
        );
        let table = table::parse(&table, "t.csv").unwrap();
        let checked = checked_scenes(&table, &dir.join("runs")).unwrap();
        let at = |k: usize| heights(&checked[k]).as_ptr();
        for k in 1..4 {
            assert_eq!(
                at(k),
                at(0),
                "row {} holds a copy of the map of row 1",
                k + 1
            );
        }
        assert_ne!(at(4), at(0), "another file, another map");
        assert_eq!(heights(&checked[4])[0], 2.0 * heights(&checked[0])[0]);
        // Each row records the file as it names it, with what was read.
        let files: Vec<&InputFile> = checked.iter().map(|c| &c.request.input_files[0]).collect();
        assert_eq!(files[1].path, format!("{d}/sub/../map.txt"));
        assert_eq!(files[0].path, format!("{d}/map.txt"));
        for f in &files[1..4] {
            assert_eq!(f.parameter, "height_map");
            assert_eq!(f.resolved, files[0].resolved);
            assert_eq!(f.digest, files[0].digest);
        }
        assert_ne!(files[4].digest, files[0].digest);
        // The spacing of each row is its own.
        let spacing = |k: usize| match &checked[k].request.scene.indenter {
            Indenter::HeightMap(s) => s.map.spacing(),
            _ => unreachable!(),
        };
        assert_eq!((spacing(0), spacing(3)), (0.05, 0.06));
    }
}
