//! A batch's own files besides its scenes' (see [`super::names`]): the record of the batch
//! that every run of it writes (`batch.json`, or `batch-shard-K-of-N.json` for a shard: every
//! scene's id and request, in the table's order), read back by `collect`; and the merged table
//! `batch.csv` (one row per scene: its id, its parameters, its results) with the wall times
//! kept apart in `batch-timings.csv`, so that the table is the same however the batch was
//! split. Serialisation only: what goes in them is decided in `run::scenes`.

use super::file::{self, read_regular, ReadError};
use super::OutputError;
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::Path;

/// The `format` a batch's record states.
pub const MANIFEST_FORMAT: &str = "jkrbem batch 1";

/// The largest record [`Manifest::read`] reads (bytes): a scene's request is about a
/// kilobyte, and a batch has at most `run::scenes::table::MAX_SCENES` of them.
pub const MAX_MANIFEST_BYTES: u64 = 64 << 20;

/// The record of a batch: which scenes it has, in order, and the request of each.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// [`MANIFEST_FORMAT`].
    pub format: String,
    /// The shard (K, N) of the run that wrote it, or `None` for a whole batch.
    pub shard: Option<(usize, usize)>,
    /// Every scene of the batch (not only the shard's), in the table's order.
    pub scenes: Vec<ManifestScene>,
}

/// One scene of a batch's record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestScene {
    /// Its id (its files are `scene-<id>.*`).
    pub id: String,
    /// Its request as the schema completed it (`run::request::Request::to_json`).
    pub request: Value,
}

impl Manifest {
    /// Write it as JSON, atomically (one scene a line, so that it stays readable).
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        let mut text = format!(
            "{{\n  \"format\": {},\n  \"shard\": {},\n  \"scenes\": [",
            Value::from(self.format.as_str()),
            serde_json::to_string(&self.shard).expect("a shard always serialises")
        );
        for (i, s) in self.scenes.iter().enumerate() {
            text.push_str(if i == 0 { "\n    " } else { ",\n    " });
            text.push_str(&serde_json::to_string(s).expect("a scene always serialises"));
        }
        text.push_str("\n  ]\n}\n");
        file::write_bytes(path, text.as_bytes())
    }

    /// Read and parse a record, or say why it is not one (in words, without the path).
    pub fn read(path: &Path) -> Result<Manifest, String> {
        let bytes = read_regular(path, MAX_MANIFEST_BYTES).map_err(|e| match e {
            ReadError::Absent => "it was removed while being read".to_string(),
            ReadError::Refused(why) => why,
        })?;
        let m: Manifest = serde_json::from_slice(&bytes)
            .map_err(|e| format!("{e} (truncated or edited?); run the batch again"))?;
        if m.format != MANIFEST_FORMAT {
            return Err(format!("unknown format {:?}", m.format));
        }
        Ok(m)
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
        let m = Manifest {
            format: MANIFEST_FORMAT.into(),
            shard: Some((2, 4)),
            scenes: vec![
                ManifestScene {
                    id: "a".into(),
                    request: serde_json::json!({"ratio": 2.5, "grid": 32}),
                },
                ManifestScene {
                    id: "b".into(),
                    request: serde_json::json!({"ratio": null, "apex_offset": [0.25, -0.5]}),
                },
            ],
        };
        m.write(&path).unwrap();
        assert_eq!(Manifest::read(&path).unwrap(), m);
        std::fs::write(&path, "{\"format\": \"jkrbem batch 1\", \"shard\"").unwrap();
        assert!(Manifest::read(&path).unwrap_err().contains("truncated"));
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
