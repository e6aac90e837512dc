//! The names of [`super::write_atomic`]'s temporary files, and the removal of those that a
//! killed run left; and the removal of the partial files (see [`super::PartialFile`]) that
//! a run which ended without its result left holding nothing.
//!
//! A temporary file of a target `<name>` is `.<name>.<pid>.<random>.tmp` beside it: the
//! process id says whose it is. A run that is killed (SIGKILL runs no handler) leaves it; a
//! later run that holds the target's lock removes those of its temporaries whose process is
//! no longer alive, and nothing else: only regular files of this user with one name, whose
//! name is exactly of that pattern for that target.
//!
//! A partial file `<stem>.incomplete-<pid>[-k].<ext>` is kept when its run ends short (it
//! holds the states computed); one that holds nothing past its first line (the header, or not
//! even that: a run killed or failed before its first state) is removed, under the same
//! conditions, by the next run that writes the target, so that a scene run again and again
//! (`batch --resume`) leaves no pile of them.

use std::fs;
use std::path::Path;

/// The random characters of a temporary file's name.
pub const RANDOM_CHARS: usize = 6;

/// The start of the temporary files' names of `target_name` written by this process:
/// `.<name>.<pid>.`.
pub fn prefix(target_name: &str) -> String {
    format!(".{target_name}.{}.", std::process::id())
}

/// The end of a temporary file's name.
pub const SUFFIX: &str = ".tmp";

/// The process that wrote `name` if it is the name of a temporary file of `target_name`
/// (`.<target_name>.<pid>.<random>.tmp`).
pub fn writer_of(name: &str, target_name: &str) -> Option<u32> {
    let middle = name
        .strip_prefix('.')?
        .strip_prefix(target_name)?
        .strip_prefix('.')?
        .strip_suffix(SUFFIX)?;
    let (pid, random) = middle.split_once('.')?;
    let digits = !pid.is_empty() && pid.len() <= 10 && pid.bytes().all(|b| b.is_ascii_digit());
    let random_ok =
        random.len() == RANDOM_CHARS && random.bytes().all(|b| b.is_ascii_alphanumeric());
    match (digits, random_ok) {
        (true, true) => pid.parse().ok().filter(|&p| p > 0),
        _ => None,
    }
}

/// Whether process `pid` may exist (a process of another user, or a zombie, counts; so does
/// an id that is no process id, so that nothing is removed for it).
#[cfg(unix)]
pub fn alive(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return true;
    };
    if pid <= 0 {
        // 0 and negative ids name process groups, not a process.
        return true;
    }
    // SAFETY: signal 0 only checks that the process exists; nothing is sent.
    if unsafe { libc::kill(pid, 0) } == 0 {
        return true;
    }
    std::io::Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
}

#[cfg(not(unix))]
pub fn alive(_pid: u32) -> bool {
    true
}

/// Whether the file with metadata `m` (not followed through a link) is this user's regular
/// file with one name.
#[cfg(unix)]
fn ours(m: &fs::Metadata) -> bool {
    use std::os::unix::fs::MetadataExt;
    m.file_type().is_file() && m.uid() == super::effective_uid() && m.nlink() == 1
}

#[cfg(not(unix))]
fn ours(m: &fs::Metadata) -> bool {
    m.file_type().is_file()
}

/// Remove the temporary files of `target` (a file name in `dir`) left by processes that
/// no longer exist (see the module's description). The caller holds the target's lock.
/// Returns how many were removed.
pub fn remove_stale(dir: &Path, target_name: &str) -> usize {
    remove_left_by_dead(dir, |n| writer_of(n, target_name), |_, m| ours(m))
}

/// Remove the files in `dir` whose name `writer` gives the process of, where that process
/// is another and no longer exists and the file is `removable`. Returns how many were
/// removed.
fn remove_left_by_dead(
    dir: &Path,
    writer: impl Fn(&str) -> Option<u32>,
    removable: impl Fn(&Path, &fs::Metadata) -> bool,
) -> usize {
    let Ok(entries) = fs::read_dir(dir) else {
        return 0;
    };
    let own = std::process::id();
    entries
        .filter_map(Result::ok)
        .filter(|e| {
            let Some(pid) = e.file_name().to_str().and_then(&writer) else {
                return false;
            };
            let path = e.path();
            pid != own
                && !alive(pid)
                && fs::symlink_metadata(&path).is_ok_and(|m| removable(&path, &m))
                && fs::remove_file(&path).is_ok()
        })
        .count()
}

/// The process that wrote `name` if it is the name of a partial file of `target_name`
/// (`<stem>.incomplete-<pid>[-k]<ext>`).
pub fn partial_writer_of(name: &str, target_name: &str) -> Option<u32> {
    let (stem, ext) = match target_name.rsplit_once('.') {
        Some((s, e)) => (s, format!(".{e}")),
        None => (target_name, String::new()),
    };
    let id = name
        .strip_prefix(stem)?
        .strip_prefix(".incomplete-")?
        .strip_suffix(ext.as_str())?;
    let (pid, k) = id.split_once('-').unwrap_or((id, "1"));
    let digits = |t: &str| !t.is_empty() && t.len() <= 10 && t.bytes().all(|b| b.is_ascii_digit());
    (digits(pid) && digits(k))
        .then(|| pid.parse().ok())
        .flatten()
        .filter(|&p| p > 0)
}

/// The longest partial file read to tell whether it holds anything past its first line
/// (bytes): a longer one does.
const EMPTY_PARTIAL_BYTES: u64 = 1 << 16;

/// Whether the file at `path` holds nothing past its first line.
fn holds_nothing(path: &Path, m: &fs::Metadata) -> bool {
    if m.len() == 0 {
        return true;
    }
    if m.len() > EMPTY_PARTIAL_BYTES {
        return false;
    }
    fs::read(path).is_ok_and(|b| match b.iter().position(|&c| c == b'\n') {
        Some(end) => end + 1 == b.len(),
        None => true,
    })
}

/// Remove the partial files of `target` (a file name in `dir`) left by processes that no
/// longer exist and holding nothing past their first line (see the module's description).
/// The caller is about to write the target. Returns how many were removed.
pub fn remove_empty_partials(dir: &Path, target_name: &str) -> usize {
    remove_left_by_dead(
        dir,
        |n| partial_writer_of(n, target_name),
        |p, m| ours(m) && holds_nothing(p, m),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_names_of_the_pattern_are_temporaries() {
        assert_eq!(
            writer_of(".s.fields.npz.123.aB3dE9.tmp", "s.fields.npz"),
            Some(123)
        );
        for other in [
            ".s.fields.npz.lock",
            ".s.fields.npz.aB3dE9.tmp",
            ".s.fields.npz.123.aB3dE.tmp",
            ".s.fields.npz.123.aB3dE9.tmp.x",
            ".t.fields.npz.123.aB3dE9.tmp",
            "s.fields.npz.123.aB3dE9.tmp",
            ".s.fields.npz.0.aB3dE9.tmp",
            ".s.fields.npz.-1.aB3dE9.tmp",
            ".s.fields.npz.12.a/3dE9.tmp",
        ] {
            assert_eq!(writer_of(other, "s.fields.npz"), None, "{other}");
        }
    }

    #[test]
    fn only_names_of_the_pattern_are_partial_files() {
        assert_eq!(partial_writer_of("s.incomplete-12.csv", "s.csv"), Some(12));
        assert_eq!(
            partial_writer_of("s.incomplete-12-3.csv", "s.csv"),
            Some(12)
        );
        assert_eq!(partial_writer_of("s.incomplete-12", "s"), Some(12));
        for other in [
            "s.incomplete-.csv",
            "s.incomplete-12-.csv",
            "s.incomplete-12-3-4.csv",
            "s.incomplete-0.csv",
            "s.incomplete-x.csv",
            "t.incomplete-12.csv",
            "s.incomplete-12.json",
            "s.csv",
        ] {
            assert_eq!(partial_writer_of(other, "s.csv"), None, "{other}");
        }
    }

    #[test]
    fn only_a_dead_process_s_temporaries_are_removed() {
        let dir = tempfile::tempdir().unwrap();
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let dead = child.id();
        child.wait().unwrap();
        let live = std::process::id();
        let names = [
            format!(".s.csv.{dead}.aaaaaa.tmp"),
            format!(".s.csv.{live}.bbbbbb.tmp"),
            format!(".t.csv.{dead}.cccccc.tmp"),
            ".s.csv.dddddd.tmp".to_string(),
        ];
        for n in &names {
            fs::write(dir.path().join(n), "x").unwrap();
        }
        assert_eq!(remove_stale(dir.path(), "s.csv"), 1);
        assert!(!dir.path().join(&names[0]).exists());
        for n in &names[1..] {
            assert!(dir.path().join(n).exists(), "{n}");
        }
    }
}
