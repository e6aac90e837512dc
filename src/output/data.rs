//! The one seam for a run's data files: its states, streamed as they come, and the fields of
//! its picked states. The session hands its data here and never names a format; the formats
//! (the states' CSV, [`super::states_csv`]; the fields' NumPy `.npz`, [`super::fields_npz`])
//! sit behind it, and a new one is a writer behind [`StateStream`] or [`write_fields`]. Every
//! place that reads states back (a reference's reuse, a sweep's curves, the tests) reads them
//! through [`read_states`].

use super::states_csv::{self, StateWriter};
use super::{fields_npz, names, OutputError};
use crate::analysis::fields::StateFields;
use crate::solver::State;
use serde_json::Value;
use std::path::{Path, PathBuf};

/// A run's states being written as they come: under a partial name until the run ends, so a
/// file under the name asked for always holds a complete run.
pub trait StateStream {
    /// Append one state and flush it to disk.
    fn write(&mut self, state: &State) -> Result<(), OutputError>;

    /// Where the states are being written now (the partial name).
    fn partial_path(&self) -> &Path;

    /// Close the stream; a `complete` run takes the final name. Returns where the states are.
    fn finish(self: Box<Self>, complete: bool) -> Result<PathBuf, OutputError>;
}

impl StateStream for StateWriter {
    fn write(&mut self, state: &State) -> Result<(), OutputError> {
        StateWriter::write(self, state)
    }

    fn partial_path(&self) -> &Path {
        StateWriter::partial_path(self)
    }

    fn finish(self: Box<Self>, complete: bool) -> Result<PathBuf, OutputError> {
        StateWriter::finish(*self, complete)
    }
}

/// Start streaming a run's states to `path` (CSV), for a run that locates `onsets`
/// ("near-minimum", "all", "none"). An existing file at `path` is not touched until the run
/// completes; a `path` that exists and is not a regular file is refused.
pub fn state_stream(
    path: &Path,
    onsets: &'static str,
) -> Result<Box<dyn StateStream>, OutputError> {
    Ok(Box::new(StateWriter::create(path, onsets)?))
}

/// The states file's bytes for `states` as a stream would leave it, for an output that is
/// not a file (standard output).
pub fn states_bytes(states: &[State], onsets: &str) -> Vec<u8> {
    states_csv::states_csv_bytes(states, onsets)
}

/// Where the fields of the run whose states go to `states` are written.
pub fn fields_path(states: &Path) -> PathBuf {
    names::fields_npz(states)
}

/// Write the fields of one run's picked states (one grid) beside its states file `states`,
/// atomically, with `about` (what ran) inside; returns the file written.
pub fn write_fields(
    states: &Path,
    fields: &[StateFields],
    about: Value,
) -> Result<PathBuf, OutputError> {
    let path = fields_path(states);
    fields_npz::write_npz(&path, fields, about)?;
    Ok(path)
}

/// The states read back from a states file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ReadStates {
    /// The whole rows, in order.
    pub states: Vec<State>,
    /// Whether the file ends in a row cut short (fewer fields than its header: a run's partial
    /// file that a write error stopped mid-row); the rows before it are in `states`.
    pub cut_short: bool,
}

/// Read a states file back: every whole row as a [`State`], up to a last row cut short (a
/// partial file's), which is left out and said. A column of the header missing, or a value
/// that is not a number, is an error naming the file.
pub fn read_states(path: &Path) -> Result<ReadStates, OutputError> {
    let csv_err = |e| OutputError::csv(path, e);
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .from_path(path)
        .map_err(csv_err)?;
    let header = reader.headers().cloned().map_err(csv_err)?;
    let mut read = ReadStates::default();
    for record in reader.records() {
        let record = match record {
            Ok(r) if r.len() == header.len() => r,
            // A row cut short (or torn by a write error): the rows before it are whole.
            _ => {
                read.cut_short = true;
                break;
            }
        };
        read.states
            .push(record.deserialize(Some(&header)).map_err(csv_err)?);
    }
    Ok(read)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_states_read_back_are_the_states_written_and_a_cut_row_is_said() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.csv");
        let states: Vec<State> = (0..3)
            .map(|i| State {
                step: i,
                phase: crate::solver::Phase::Pulloff,
                f_bar: -0.1 * i as f64,
                d_bar: 0.25 * i as f64,
                ..State::default()
            })
            .collect();
        let mut w = state_stream(&path, "near-minimum").unwrap();
        for s in &states {
            w.write(s).unwrap();
        }
        assert_eq!(w.finish(true).unwrap(), path);
        let read = read_states(&path).unwrap();
        assert_eq!(read.states, states);
        assert!(!read.cut_short);
        // The same file, its last row cut off mid-way.
        let text = std::fs::read_to_string(&path).unwrap();
        let cut = &text[..text.trim_end().rfind(',').unwrap()];
        std::fs::write(&path, cut).unwrap();
        let read = read_states(&path).unwrap();
        assert_eq!(read.states, states[..2]);
        assert!(read.cut_short);
    }

    #[test]
    fn a_file_written_before_the_cg_residual_column_still_reads() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("old.csv");
        let old_header = super::states_csv::HEADER
            .strip_suffix(",cg_residual,dx,onsets")
            .unwrap();
        std::fs::write(
            &path,
            format!("{old_header}\n0,approach,1,2,3,4,5,6,7,8,9,10,11,12,13,14\n"),
        )
        .unwrap();
        let states = read_states(&path).unwrap().states;
        assert_eq!(states.len(), 1);
        assert_eq!(states[0].b_bar, 14.0);
        assert!(states[0].cg_residual.is_nan(), "not recorded reads as NaN");
    }
}
