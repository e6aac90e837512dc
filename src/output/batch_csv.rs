//! A batch's own files besides its scenes' (see [`super::names`]): the record that every run
//! of it writes (`batch.json`, or `batch-shard-K-of-N.json` for a shard: the scenes that run
//! holds, each with its row, id and request, and the digest of the whole table, so that a
//! shard's record grows with its own rows, not with the table), read back by `collect`; and
//! the merged table `batch.csv` (one row per scene: its id, its parameters, its results) with
//! the wall times kept apart in `batch-timings.csv`, so that the table is the same however the
//! batch was split. Serialisation only: what goes in them is decided in `session::batch`.

use super::file::{self, read_regular, ReadError};
use super::OutputError;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::Path;

/// The `format` a batch's record states.
pub const MANIFEST_FORMAT: &str = "jkrbem batch 2";

/// The `format` of the records earlier versions wrote (each held every scene of the table, and
/// no digest): still read, as the record of the scenes of its shard.
pub const MANIFEST_FORMAT_1: &str = "jkrbem batch 1";

/// The largest record [`Manifest::read`] reads (bytes): a scene's request is about a
/// kilobyte, and a batch (a whole batch's record) has at most
/// `session::batch::table::MAX_SCENES` of them.
pub const MAX_MANIFEST_BYTES: u64 = 64 << 20;

/// What tells a batch's table from another: how many scenes it has, and a digest of every
/// scene's id and request in order.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableDigest {
    /// Scenes in the table.
    pub scenes: usize,
    /// The CRC-32 (IEEE) of the scenes, each as the line `{"id":…,"request":…}` (compact
    /// JSON, then a newline), in the table's order: 8 hexadecimal digits.
    pub crc32: String,
}

/// A [`TableDigest`] being computed, one scene after another.
#[derive(Debug, Default)]
pub struct TableHasher {
    hasher: crc32fast::Hasher,
    scenes: usize,
}

/// A scene as its table's digest reads it.
#[derive(Serialize)]
struct DigestLine<'a> {
    id: &'a str,
    request: &'a Value,
}

impl TableHasher {
    /// Add the next scene of the table: its id and request.
    pub fn add(&mut self, id: &str, request: &Value) {
        let line =
            serde_json::to_string(&DigestLine { id, request }).expect("a scene always serialises");
        self.hasher.update(line.as_bytes());
        self.hasher.update(b"\n");
        self.scenes += 1;
    }

    /// The digest of the scenes added.
    pub fn finish(self) -> TableDigest {
        TableDigest {
            scenes: self.scenes,
            crc32: format!("{:08x}", self.hasher.finalize()),
        }
    }
}

impl TableDigest {
    /// The digest of a table's scenes, each its id and request, in order.
    pub fn of<'a>(scenes: impl IntoIterator<Item = (&'a str, &'a Value)>) -> Self {
        let mut h = TableHasher::default();
        for (id, request) in scenes {
            h.add(id, request);
        }
        h.finish()
    }
}

/// The record of a run of a batch: which table it is of, and the scenes of that table it
/// holds (its shard's, or all of them).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// [`MANIFEST_FORMAT`].
    pub format: String,
    /// The shard (K, N) of the run that wrote it, or `None` for a whole batch.
    pub shard: Option<(usize, usize)>,
    /// The whole table's (not only the shard's).
    pub table: TableDigest,
    /// The scenes of the shard (of the table, for a whole batch), in the table's order.
    pub scenes: Vec<ManifestScene>,
}

/// One scene of a batch's record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestScene {
    /// Its row in the table, from 1.
    pub row: usize,
    /// Its id (its files are `scene-<id>.*`).
    pub id: String,
    /// Its request as the schema completed it (`session::request::Request::to_json`).
    pub request: Value,
}

/// A record as [`MANIFEST_FORMAT_1`] wrote it: every scene of the table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestV1 {
    shard: Option<(usize, usize)>,
    scenes: Vec<SceneV1>,
    #[serde(rename = "format")]
    _format: String,
}

/// A scene of a [`ManifestV1`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SceneV1 {
    id: String,
    request: Value,
}

/// A record's format, read alone.
#[derive(Deserialize)]
struct Format {
    format: Option<String>,
}

impl Manifest {
    /// Write it as JSON, atomically (one scene a line, so that it stays readable).
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        let mut text = format!(
            "{{\n  \"format\": {},\n  \"shard\": {},\n  \"table\": {},\n  \"scenes\": [",
            Value::from(self.format.as_str()),
            serde_json::to_string(&self.shard).expect("a shard always serialises"),
            serde_json::to_string(&self.table).expect("a digest always serialises")
        );
        for (i, s) in self.scenes.iter().enumerate() {
            text.push_str(if i == 0 { "\n    " } else { ",\n    " });
            text.push_str(&serde_json::to_string(s).expect("a scene always serialises"));
        }
        text.push_str("\n  ]\n}\n");
        file::write_bytes(path, text.as_bytes())
    }

    /// Read and parse a record, or say why it is not one (in words, without the path). A
    /// record of [`MANIFEST_FORMAT_1`] is read as the record of its shard's scenes, with the
    /// digest of the table it holds.
    pub fn read(path: &Path) -> Result<Manifest, String> {
        let bytes = read_regular(path, MAX_MANIFEST_BYTES).map_err(|e| match e {
            ReadError::Absent => "it was removed while being read".to_string(),
            ReadError::Refused(why) => why,
        })?;
        let damaged =
            |e: serde_json::Error| format!("{e} (truncated or edited?); run the batch again");
        let format = serde_json::from_slice::<Format>(&bytes)
            .map_err(damaged)?
            .format;
        match format.as_deref() {
            Some(MANIFEST_FORMAT) => serde_json::from_slice(&bytes).map_err(damaged),
            Some(MANIFEST_FORMAT_1) => {
                let old: ManifestV1 = serde_json::from_slice(&bytes).map_err(damaged)?;
                Ok(Manifest::from_v1(old))
            }
            Some(other) => Err(format!("unknown format {other:?}")),
            None => Err("no format stated (truncated or edited?); run the batch again".into()),
        }
    }

    /// A [`MANIFEST_FORMAT_1`] record as a record of its shard's scenes.
    fn from_v1(old: ManifestV1) -> Manifest {
        let table = TableDigest::of(old.scenes.iter().map(|s| (s.id.as_str(), &s.request)));
        let scenes = old
            .scenes
            .into_iter()
            .enumerate()
            .filter(|(j, _)| old.shard.is_none_or(|(k, n)| n > 0 && j % n + 1 == k))
            .map(|(j, s)| ManifestScene {
                row: j + 1,
                id: s.id,
                request: s.request,
            })
            .collect();
        Manifest {
            format: MANIFEST_FORMAT.to_string(),
            shard: old.shard,
            table,
            scenes,
        }
    }
}

/// One scene's row of `batch.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct BatchRow {
    /// The scene's id.
    pub id: String,
    /// Its parameters as text (as a table gives them; empty: chosen for the scene), in the
    /// order of the table's parameter columns.
    pub parameters: Vec<String>,
    /// The estimate of the adhesive force |min F̄| at Δx → 0 (dimensionless).
    pub f_ad_bar: Option<f64>,
    /// Its stated half-width (absolute, dimensionless).
    pub f_ad_bar_uncertainty: Option<f64>,
    /// The estimate's kind ("single-grid", "extrapolated").
    pub estimate: Option<String>,
    /// c̄ at the force minimum (dimensionless).
    pub c_bar_at_min: Option<f64>,
    /// d̄ at the force minimum (dimensionless).
    pub d_bar_at_min: Option<f64>,
    /// The finest grid's own |min F̄| (dimensionless, uncorrected).
    pub grid_f_ad_bar: Option<f64>,
    /// Whether every run reached the force minimum.
    pub min_reached: bool,
    /// Whether every run ran to its end.
    pub complete: bool,
    /// CG iterations over all runs.
    pub cg_iterations: u64,
    /// How many warnings its summary holds.
    pub warnings: usize,
    /// Wall time of all its runs (s): written to `batch-timings.csv` only.
    pub wall_s: f64,
}

/// The result columns of `batch.csv`, after `id` and the parameters.
pub const RESULT_COLUMNS: [&str; 10] = [
    "f_ad_bar",
    "f_ad_bar_uncertainty",
    "estimate",
    "c_bar_at_min",
    "d_bar_at_min",
    "grid_f_ad_bar",
    "min_reached",
    "complete",
    "cg_iterations",
    "warnings",
];

/// A number as the table writes it: Rust's shortest form that reads back as the same number;
/// empty where there is none.
fn number(v: Option<f64>) -> String {
    v.map_or_else(String::new, |v| format!("{v}"))
}

impl BatchRow {
    /// Its cells, in the order of the header [`write_table`] writes.
    fn cells(&self) -> Vec<String> {
        let mut cells = vec![self.id.clone()];
        cells.extend(self.parameters.iter().cloned());
        cells.extend([
            number(self.f_ad_bar),
            number(self.f_ad_bar_uncertainty),
            self.estimate.clone().unwrap_or_default(),
            number(self.c_bar_at_min),
            number(self.d_bar_at_min),
            number(self.grid_f_ad_bar),
            self.min_reached.to_string(),
            self.complete.to_string(),
            self.cg_iterations.to_string(),
            self.warnings.to_string(),
        ]);
        cells
    }
}

/// Write `batch.csv`: the columns `id`, `parameters` (their names) and [`RESULT_COLUMNS`],
/// one row per scene, atomically.
pub fn write_table(path: &Path, parameters: &[&str], rows: &[BatchRow]) -> Result<(), OutputError> {
    let mut header = vec!["id"];
    header.extend(parameters);
    header.extend(RESULT_COLUMNS);
    let header = header.join(",");
    file::write_csv(path, Some(header.as_str()), rows.iter().map(|r| r.cells()))
}

/// Write `batch-timings.csv`: each scene's id and wall time (s), atomically.
pub fn write_timings(path: &Path, rows: &[BatchRow]) -> Result<(), OutputError> {
    file::write_csv(
        path,
        Some("id,wall_s"),
        rows.iter().map(|r| [r.id.clone(), format!("{}", r.wall_s)]),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_reads_back_as_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("batch.json");
        let a = serde_json::json!({"ratio": 2.5, "grid": 32});
        let b = serde_json::json!({"ratio": null, "apex_offset": [0.25, -0.5]});
        let m = Manifest {
            format: MANIFEST_FORMAT.into(),
            shard: Some((2, 4)),
            table: TableDigest::of([("a", &a), ("b", &b), ("c", &a), ("d", &a), ("e", &b)]),
            scenes: vec![
                ManifestScene {
                    row: 2,
                    id: "b".into(),
                    request: b.clone(),
                },
                ManifestScene {
                    row: 6,
                    id: "f".into(),
                    request: a.clone(),
                },
            ],
        };
        m.write(&path).unwrap();
        assert_eq!(Manifest::read(&path).unwrap(), m);
        assert_eq!(m.table.scenes, 5);
        std::fs::write(&path, "{\"format\": \"jkrbem batch 2\", \"shard\"").unwrap();
        assert!(Manifest::read(&path).unwrap_err().contains("truncated"));
        std::fs::write(&path, "{\"format\": \"jkrbem batch 9\"}").unwrap();
        assert!(Manifest::read(&path)
            .unwrap_err()
            .contains("unknown format"));
    }

    #[test]
    fn a_record_of_the_first_format_is_read_as_its_shard_s() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("batch-shard-2-of-2.json");
        let r = |x: f64| serde_json::json!({"ratio": x});
        let scenes: Vec<Value> = (1..=5)
            .map(|k| serde_json::json!({"id": format!("s{k}"), "request": r(k as f64)}))
            .collect();
        let old =
            serde_json::json!({"format": MANIFEST_FORMAT_1, "shard": [2, 2], "scenes": scenes});
        std::fs::write(&path, old.to_string()).unwrap();
        let m = Manifest::read(&path).unwrap();
        assert_eq!(m.shard, Some((2, 2)));
        let rows: Vec<(usize, &str)> = m.scenes.iter().map(|s| (s.row, s.id.as_str())).collect();
        assert_eq!(rows, [(2, "s2"), (4, "s4")]);
        let requests: Vec<Value> = (1..=5).map(|k| r(k as f64)).collect();
        let ids: Vec<String> = (1..=5).map(|k| format!("s{k}")).collect();
        assert_eq!(
            m.table,
            TableDigest::of(ids.iter().map(String::as_str).zip(&requests))
        );
        // The digest tells tables apart: another request, another order.
        assert_ne!(
            m.table,
            TableDigest::of(ids.iter().map(String::as_str).zip(requests.iter().rev()))
        );
    }

    #[test]
    fn the_table_has_no_wall_time() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("batch.csv");
        let row = BatchRow {
            id: "s1".into(),
            parameters: vec!["ellipsoid".into(), "".into()],
            f_ad_bar: Some(0.5),
            f_ad_bar_uncertainty: None,
            estimate: Some("single-grid".into()),
            c_bar_at_min: Some(1.0),
            d_bar_at_min: Some(-0.25),
            grid_f_ad_bar: Some(0.51),
            min_reached: true,
            complete: true,
            cg_iterations: 12,
            warnings: 0,
            wall_s: 3.5,
        };
        write_table(&path, &["indenter", "ratio"], &[row]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            text,
            "id,indenter,ratio,f_ad_bar,f_ad_bar_uncertainty,estimate,c_bar_at_min,\
             d_bar_at_min,grid_f_ad_bar,min_reached,complete,cg_iterations,warnings\n\
             s1,ellipsoid,,0.5,,single-grid,1,-0.25,0.51,true,true,12,0\n"
        );
    }
}
