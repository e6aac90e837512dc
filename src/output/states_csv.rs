//! Streams states to CSV. While a run is going the file has a partial name unique to the run,
//! `<stem>.incomplete-<pid>.csv` ([`PartialFile`]); only a complete run renames it to the path
//! asked for, so a file under that name always holds a complete run, and an existing file
//! there is left untouched until then. The header is written at once, so that even a run that
//! fails before its first state leaves a file that says what it would have held. Written and
//! read back through [`super::data`], the seam of every data file.

use super::file::PartialFile;
use super::OutputError;
use crate::solver::State;
use std::path::{Path, PathBuf};

/// The CSV header: one column per [`State`] field, then `onsets`, which onsets the file
/// holds (the run's `--onsets`, the same on every row): `near-minimum` (every step's end
/// state, and the onsets of the steps that could hold the force minimum), `all` (the whole
/// sawtooth) or `none` (step ends only).
pub const HEADER: &str = "step,phase,d,force,area,mean_radius,a_axis,b_axis,n_contact,\
cg_iterations,detach_sweeps,d_bar,f_bar,c_bar,a_bar,b_bar,cg_residual,dx,onsets";

/// A CSV of states being written.
pub struct StateWriter {
    partial: PathBuf,
    writer: csv::Writer<PartialFile>,
    /// The `onsets` column's value.
    onsets: &'static str,
}

impl StateWriter {
    /// Create the folder and start writing, header first, under this run's partial name
    /// beside `path`, for a run that locates `onsets` ("near-minimum", "all", "none"). An
    /// existing file at `path` is not touched; a `path` that exists and is not a regular file
    /// is refused.
    pub fn create(path: &Path, onsets: &'static str) -> Result<Self, OutputError> {
        let file = PartialFile::create(path)?;
        let partial = file.partial_path().to_path_buf();
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(file);
        writer
            .write_record(HEADER.split(','))
            .map_err(|e| OutputError::csv(&partial, e))?;
        writer.flush().map_err(|e| OutputError::io(&partial, e))?;
        Ok(StateWriter {
            partial,
            writer,
            onsets,
        })
    }

    /// Where the states are being written now (the partial name).
    pub fn partial_path(&self) -> &Path {
        &self.partial
    }

    /// Append one state and flush it to disk.
    pub fn write(&mut self, state: &State) -> Result<(), OutputError> {
        self.writer
            .serialize((state, self.onsets))
            .map_err(|e| OutputError::csv(&self.partial, e))?;
        self.writer
            .flush()
            .map_err(|e| OutputError::io(&self.partial, e))
    }

    /// Close the file; a complete run takes the final name. Returns where the states are.
    pub fn finish(self, complete: bool) -> Result<PathBuf, OutputError> {
        let partial = self.partial;
        let file = self
            .writer
            .into_inner()
            .map_err(|e| OutputError::io(&partial, e.into_error()))?;
        file.finish(complete)
    }
}

/// The CSV of `states` as [`StateWriter`] writes it to a file (header first, then each state
/// with `onsets`), as bytes for a stream that is not a file (standard output).
pub fn states_csv_bytes(states: &[State], onsets: &str) -> Vec<u8> {
    let mut writer = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new());
    // Writing to memory fails only if a state cannot be serialised, which none can.
    let _ = writer.write_record(HEADER.split(','));
    for s in states {
        let _ = writer.serialize((s, onsets));
    }
    writer.into_inner().unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn the_states_as_bytes_are_the_file_a_complete_run_leaves() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.csv");
        let states: Vec<State> = [(0usize, -0.1), (1, -0.52), (2, -0.3)]
            .into_iter()
            .map(|(step, f_bar)| State {
                step,
                phase: crate::solver::Phase::Pulloff,
                f_bar,
                d_bar: 0.1 * step as f64,
                cg_residual: 1e-9,
                ..State::default()
            })
            .collect();
        let mut w = StateWriter::create(&path, "near-minimum").unwrap();
        for s in &states {
            w.write(s).unwrap();
        }
        w.finish(true).unwrap();
        assert_eq!(
            fs::read(&path).unwrap(),
            states_csv_bytes(&states, "near-minimum")
        );
        assert_eq!(
            states_csv_bytes(&[], "all"),
            format!("{HEADER}\n").into_bytes()
        );
    }
}
