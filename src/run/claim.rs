//! The files a request will write, claimed once every input has been checked and before any
//! work: two outputs that are the same file (`--out o.csv --summary o.csv`) are refused, as is
//! a target that is not a regular file, and each target is locked against other runs
//! ([`OutputLock`]) until the claim is dropped. The writing itself goes through
//! [`crate::output::file`].

use super::{failed, input, RunError};
use crate::output::file::{check_target, lock_path, OutputLock};
use crate::output::OutputError;
use std::path::{Path, PathBuf};

/// An output error as the request's error: a refusal (not a regular file, held by another
/// run) is bad input, anything else a failure. The message names the path and `flag`.
pub fn write_error(flag: &str) -> impl Fn(OutputError) -> RunError + '_ {
    move |e| {
        let e = e.with_flag(flag);
        if e.is_refusal() {
            input(e)
        } else {
            failed(e)
        }
    }
}

/// A path as one file, whatever way it was written: absolute, `.` and `..` resolved, and the
/// folder's symbolic links followed where it exists.
fn identity(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut clean = PathBuf::new();
    for c in abs.components() {
        match c {
            std::path::Component::ParentDir => {
                clean.pop();
            }
            std::path::Component::CurDir => {}
            other => clean.push(other),
        }
    }
    match (clean.parent(), clean.file_name()) {
        (Some(dir), Some(name)) => match std::fs::canonicalize(dir) {
            Ok(dir) => dir.join(name),
            Err(_) => clean,
        },
        _ => clean,
    }
}

/// The outputs claimed by one request, locked until it is dropped.
#[derive(Default)]
pub struct Outputs {
    locks: Vec<OutputLock>,
}

impl Outputs {
    /// Claim every `(path, flag)` for this command: refuse two that name the same file, a
    /// target that exists and is not a regular file, and one that another run holds. Nothing
    /// is created unless all pass the first two checks; the folders are then created and the
    /// locks taken. Every failure here comes before any work and is bad input (exit code 2).
    pub fn claim(targets: &[(PathBuf, String)]) -> Result<Outputs, RunError> {
        Self::check(targets)?;
        let mut outputs = Outputs::default();
        for (path, flag) in targets {
            // Nothing has been computed yet: a lock that cannot be taken (held by another
            // run, a read-only or full folder, a name too long, a file where a folder should
            // be) is a refusal of the request, exit code 2.
            let lock = OutputLock::acquire(path).map_err(|e| input(e.with_flag(flag)))?;
            outputs.locks.push(lock);
        }
        Ok(outputs)
    }

    /// The checks of [`Outputs::claim`] that create nothing: no two outputs the same file,
    /// none that exists and is not a regular file.
    pub fn check(targets: &[(PathBuf, String)]) -> Result<(), RunError> {
        let mut seen: Vec<(PathBuf, &Path, &str)> = Vec::new();
        for (path, flag) in targets {
            let id = identity(path);
            if let Some((_, other, other_flag)) = seen.iter().find(|(i, _, _)| *i == id) {
                return Err(input(if other_flag == flag {
                    format!(
                        "{flag}: two outputs of this command would be the same file {} \
                         (check for repeated values)",
                        path.display()
                    )
                } else {
                    format!(
                        "{flag} {} is the same file as {other_flag} {}: give them different names",
                        path.display(),
                        other.display()
                    )
                }));
            }
            check_target(path).map_err(write_error(flag))?;
            seen.push((id, path, flag));
        }
        // An output named as another's lock file would be removed with the lock at the end.
        let locks: std::collections::HashMap<PathBuf, (&Path, &str)> = seen
            .iter()
            .map(|(_, other, other_flag)| (identity(&lock_path(other)), (*other, *other_flag)))
            .collect();
        for (id, path, flag) in &seen {
            if let Some((other, other_flag)) = locks.get(id) {
                return Err(input(format!(
                    "{flag} {} is the lock file of {other_flag} {}: give it another name",
                    path.display(),
                    other.display()
                )));
            }
        }
        Ok(())
    }
}

/// `(path, flag)` pairs for [`Outputs::claim`].
pub fn named<'a>(
    flag: &str,
    paths: impl IntoIterator<Item = &'a PathBuf>,
) -> Vec<(PathBuf, String)> {
    paths
        .into_iter()
        .map(|p| (p.clone(), flag.to_string()))
        .collect()
}
