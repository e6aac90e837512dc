//! The files a request will write, claimed once every input has been checked and before any
//! work: two outputs that are the same file (`--out o.csv --summary o.csv`, or two names of
//! one file) are refused, as is a target that is not a regular file and one that is a file
//! the run reads, and each target is locked against other runs ([`OutputLock`]) until the
//! claim is dropped. The writing itself goes through [`crate::output::file`].

use super::{failed, input, RunError};
use crate::output::file::{
    canonical, check_target, file_id, input_at, lock_of, FileId, OutputLock,
};
use crate::output::{NamedBy, OutputError};
use std::path::{Path, PathBuf};

/// An output error as the request's error: a refusal (not a regular file, held by another
/// run) is bad input, anything else a failure. The message names the path and `param`, the
/// parameter that named it.
pub fn write_error(param: impl Into<NamedBy>) -> impl Fn(OutputError) -> RunError {
    let param = param.into();
    move |e| {
        let e = e.with_param(param);
        if e.is_refusal() {
            input(e)
        } else {
            failed(e)
        }
    }
}

/// The outputs claimed by one request, locked until it is dropped.
#[derive(Default)]
pub struct Outputs {
    locks: Vec<OutputLock>,
}

impl Outputs {
    /// Claim every `(path, parameter)` for this command: refuse two that name the same file, a
    /// target that exists and is not a regular file, and one that another run holds. Nothing
    /// is created unless all pass the first two checks; the folders are then created and the
    /// locks taken. Every failure here comes before any work and is bad input (exit code 2).
    pub fn claim(targets: &[(PathBuf, NamedBy)]) -> Result<Outputs, RunError> {
        Self::check(targets)?;
        let mut outputs = Outputs::default();
        let mut taken: Vec<(PathBuf, &Path, NamedBy)> = Vec::new();
        for &(ref path, param) in targets {
            // Two of this run's own outputs on one lock (a link changed since the check) are
            // said to be so, not blamed on another run.
            let lock = canonical(&lock_of(path));
            if let Some((_, other, other_param)) = taken.iter().find(|(l, _, _)| *l == lock) {
                return Err(input(format!(
                    "{param} {} is the same file as {other_param} {} (they share the lock file \
                     {}): give them different names",
                    path.display(),
                    other.display(),
                    lock_of(path).display()
                ))
                .blaming(param.spec()));
            }
            // Nothing has been computed yet: a lock that cannot be taken (held by another
            // run, a read-only or full folder, a name too long, a file where a folder should
            // be) is a refusal of the request, exit code 2.
            let held = OutputLock::acquire(path).map_err(|e| input(e.with_param(param)))?;
            outputs.locks.push(held);
            taken.push((lock, path, param));
        }
        Ok(outputs)
    }

    /// The checks of [`Outputs::claim`] that create nothing: no output that exists and is not
    /// a regular file; no two outputs that are one file, however spelled or linked (hard
    /// links and symbolic links included: see [`file_id`]) or that share a lock file; none
    /// named as another's lock file; and none that is, or whose lock file is, a file this run
    /// reads ([`note_input`](crate::output::file::note_input): `--height-map`, the shards of
    /// `collect`), the program itself or a standard stream redirected to a file.
    pub fn check(targets: &[(PathBuf, NamedBy)]) -> Result<(), RunError> {
        // A standard stream appended to a file this run reads would write into it.
        if let Some(what) = crate::output::file::stream_on_input() {
            return Err(input(format!(
                "{what}: the run's results or messages would be written into a file it \
                 reads; send the stream elsewhere"
            )));
        }
        let mut seen: Vec<Claimed> = Vec::new();
        for &(ref path, param) in targets {
            check_target(path).map_err(write_error(param))?;
            let claimed = Claimed {
                id: file_id(path),
                lock: file_id(&lock_of(path)),
                path,
                param,
            };
            if let Some(other) = seen
                .iter()
                .find(|o| o.id == claimed.id || o.lock == claimed.lock)
            {
                return Err(input(if other.param == param {
                    format!(
                        "{param}: two outputs of this command would be the same file {} \
                         (check for repeated values)",
                        path.display()
                    )
                } else {
                    format!(
                        "{param} {} is the same file as {} {}: give them different names",
                        path.display(),
                        other.param,
                        other.path.display()
                    )
                }));
            }
            if let Some(read) = input_at(&claimed.id) {
                return Err(input(format!(
                    "{param} {} is the same file as {}: an output never replaces it; give \
                     another name",
                    path.display(),
                    read.describe()
                ))
                .blaming(param.spec()));
            }
            if let Some(read) = input_at(&claimed.lock) {
                return Err(input(format!(
                    "{param} {}: its lock file {} is the same file as {}: the lock would \
                     overwrite it; give another name",
                    path.display(),
                    lock_of(path).display(),
                    read.describe()
                ))
                .blaming(param.spec()));
            }
            seen.push(claimed);
        }
        // An output named as another's lock file would be removed with the lock at the end.
        for s in &seen {
            if let Some(other) = seen.iter().find(|o| o.lock == s.id) {
                return Err(input(format!(
                    "{} {} is the lock file of {} {}: give it another name",
                    s.param,
                    s.path.display(),
                    other.param,
                    other.path.display()
                )));
            }
        }
        Ok(())
    }
}

/// An output being checked: its identity, its lock file's, and the parameter that named it.
struct Claimed<'a> {
    id: FileId,
    lock: FileId,
    path: &'a Path,
    param: NamedBy,
}

/// `(path, parameter)` pairs for [`Outputs::claim`], every path named by `param`.
pub fn named<'a>(
    param: impl Into<NamedBy>,
    paths: impl IntoIterator<Item = &'a PathBuf>,
) -> Vec<(PathBuf, NamedBy)> {
    let param = param.into();
    paths.into_iter().map(|p| (p.clone(), param)).collect()
}
