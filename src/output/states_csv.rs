//! Streams states to CSV. While a run is going the file is named `<stem>.incomplete.csv`;
//! only a complete run renames it to the path asked for, so a file under that name always
//! holds a complete run.

use super::OutputError;
use crate::solver::State;
use std::fs::{self, File};
use std::path::{Path, PathBuf};

/// The CSV header, one column per [`State`] field.
pub const HEADER: &str = "step,phase,d,force,area,mean_radius,a_axis,b_axis,n_contact,\
cg_iterations,detach_sweeps,d_bar,f_bar,c_bar,a_bar,b_bar,cg_residual,dx";

/// The name a run's states carry until it completes: `dir/stem.incomplete.csv`.
pub fn incomplete_path(path: &Path) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "states".into());
    path.with_file_name(format!("{stem}.incomplete.csv"))
}

/// A CSV of states being written.
pub struct StateWriter {
    path: PathBuf,
    partial: PathBuf,
    writer: csv::Writer<File>,
}

impl StateWriter {
    /// Create the folder, remove any stale file of a previous run under `path`, and start
    /// writing to the incomplete name.
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            fs::create_dir_all(dir).map_err(|e| OutputError::io(dir, e))?;
        }
        let partial = incomplete_path(path);
        for stale in [path, partial.as_path()] {
            if stale.exists() {
                fs::remove_file(stale).map_err(|e| OutputError::io(stale, e))?;
            }
        }
        let file = File::create(&partial).map_err(|e| OutputError::io(&partial, e))?;
        let writer = csv::WriterBuilder::new()
            .has_headers(true)
            .from_writer(file);
        Ok(StateWriter {
            path: path.to_path_buf(),
            partial,
            writer,
        })
    }

    /// Append one state and flush it to disk.
    pub fn write(&mut self, state: &State) -> Result<(), OutputError> {
        let err = |source| OutputError::Csv {
            path: self.partial.display().to_string(),
            source,
        };
        self.writer.serialize(state).map_err(err)?;
        self.writer
            .flush()
            .map_err(|e| OutputError::io(&self.partial, e))
    }

    /// Close the file; a complete run takes the final name. Returns where the states are.
    pub fn finish(mut self, complete: bool) -> Result<PathBuf, OutputError> {
        self.writer
            .flush()
            .map_err(|e| OutputError::io(&self.partial, e))?;
        drop(self.writer);
        if complete {
            fs::rename(&self.partial, &self.path).map_err(|e| OutputError::io(&self.path, e))?;
            Ok(self.path)
        } else {
            Ok(self.partial)
        }
    }
}

/// Read the states of a CSV written by [`StateWriter`] (for tests and post-processing).
pub fn read_states(path: &Path) -> Result<Vec<csv::StringRecord>, OutputError> {
    let mut r = csv::Reader::from_path(path).map_err(|source| OutputError::Csv {
        path: path.display().to_string(),
        source,
    })?;
    r.records()
        .collect::<Result<_, _>>()
        .map_err(|source| OutputError::Csv {
            path: path.display().to_string(),
            source,
        })
}

/// Read a states CSV back into [`State`]s (the columns of [`HEADER`]).
pub fn read_state_rows(path: &Path) -> Result<Vec<State>, OutputError> {
    let csv_err = |source| OutputError::Csv {
        path: path.display().to_string(),
        source,
    };
    csv::Reader::from_path(path)
        .map_err(csv_err)?
        .deserialize()
        .collect::<Result<_, _>>()
        .map_err(csv_err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_written_before_the_cg_residual_column_still_reads() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("old.csv");
        let old_header = HEADER.strip_suffix(",cg_residual,dx").unwrap();
        fs::write(
            &path,
            format!("{old_header}\n0,approach,1,2,3,4,5,6,7,8,9,10,11,12,13,14\n"),
        )
        .unwrap();
        let states = read_state_rows(&path).unwrap();
        assert_eq!(states.len(), 1);
        assert_eq!(states[0].b_bar, 14.0);
        assert!(states[0].cg_residual.is_nan(), "not recorded reads as NaN");
    }
}
