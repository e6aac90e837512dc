//! A sweep's pull-off curves for its chart: from the states its runs recorded, or (for shards
//! merged later) read back from their states files (complete, or a failed run's partial
//! file). The session layer gathers the points; the chart only draws them.

use crate::output::data::read_states;
use crate::output::file::is_partial_of;
use crate::output::names;
use crate::output::sweep_csv::SweepRow;
use crate::output::OutputError;
use crate::session::pulloffs::JobResult;
use std::path::{Path, PathBuf};

/// The (d̄, F̄) points of each row's states in `dir`, or why there are none (a missing or
/// unreadable states file), in the rows' order.
pub fn sweep_curves(dir: &Path, rows: &[SweepRow]) -> Vec<Result<Vec<(f64, f64)>, String>> {
    rows.iter()
        .map(|row| {
            let path = states_file(dir, row)?;
            pulloff_points(&path).map_err(|e| format!("its states cannot be read: {e}"))
        })
        .collect()
}

/// The run of `results` behind a sweep row (its ratio and finest grid).
pub fn run_of<'a>(results: &'a [JobResult], row: &SweepRow) -> Option<&'a JobResult> {
    results
        .iter()
        .find(|r| r.ratio == row.ratio && r.grid.0 == row.grid)
}

/// The (d̄, F̄) points of the pull-off and onset states that the runs behind each row
/// recorded, or why there are none, in the rows' order.
pub fn row_curves(
    results: &[JobResult],
    rows: &[SweepRow],
) -> Vec<Result<Vec<(f64, f64)>, String>> {
    rows.iter()
        .map(|row| match run_of(results, row) {
            Some(r) if !r.states.is_empty() => Ok(state_points(&r.states)),
            _ => Err("it recorded no states".to_string()),
        })
        .collect()
}

/// (d̄, F̄) of the pull-off and onset states among `states` (the same points as
/// [`pulloff_points`] reads from their CSV).
pub fn state_points(states: &[crate::solver::State]) -> Vec<(f64, f64)> {
    states
        .iter()
        .filter(|s| s.phase != crate::solver::Phase::Approach)
        .map(|s| (s.d_bar, s.f_bar))
        .collect()
}

/// (d̄, F̄) of the pull-off and onset states in a states file.
///
/// The file may be a run's partial states, cut off mid-row by a write error: the rows up to the
/// first one that is not whole (fewer fields than the header) are read, and the rest ignored.
pub fn pulloff_points(states_csv: &Path) -> Result<Vec<(f64, f64)>, OutputError> {
    Ok(state_points(&read_states(states_csv)?.states))
}

/// The newest partial states file of `target_name` in `dir` (see
/// [`crate::output::file::PartialFile`]), if any.
fn newest_partial(dir: &Path, target_name: &str) -> Option<PathBuf> {
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(Result::ok)
        .filter(|e| is_partial_of(&e.file_name().to_string_lossy(), target_name))
        .max_by_key(|e| e.metadata().and_then(|m| m.modified()).ok())
        .map(|e| e.path())
}

/// The states file of `row` in `dir`: its complete file if that is a regular file, else its
/// newest partial file; or why there is none, in words.
fn states_file(dir: &Path, row: &SweepRow) -> Result<PathBuf, String> {
    let complete = names::sweep_states(dir, row.ratio, row.grid);
    let name = complete
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    match std::fs::metadata(&complete) {
        Ok(m) if m.is_file() => return Ok(complete),
        Ok(_) => {
            return Err(format!(
                "{} is not a regular file (a FIFO, a device or a folder)",
                complete.display()
            ))
        }
        Err(_) => {}
    }
    newest_partial(dir, &name)
        .filter(|p| p.metadata().is_ok_and(|m| m.is_file()))
        .ok_or_else(|| format!("its states file {} is missing", complete.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_states_file_cut_off_mid_row_gives_its_whole_rows() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r1-n32.incomplete-7.csv");
        let header = crate::output::states_csv::HEADER;
        let row = |d: f64, f: f64| {
            format!("1,pulloff,0,0,0,0,0,0,0,0,0,{d},{f},0,0,0,0,0,near-minimum\n")
        };
        // The third row was cut off by a write error.
        let text = format!(
            "{header}\n{}{}1,pulloff,0,0,0,0,0,0,0,0,0,0.5,-0.4",
            row(1.0, -0.1),
            row(0.9, -0.2)
        );
        std::fs::write(&path, text).unwrap();
        assert_eq!(
            pulloff_points(&path).unwrap(),
            vec![(1.0, -0.1), (0.9, -0.2)]
        );
    }
}
