//! Which file a path names, however it is spelled, and the files this run reads.
//!
//! - [`file_id`]: an existing file is its (device, inode), so that a hard link, a symbolic link
//!   to it, `./`, `..` and an absolute spelling all give one identity; a path where nothing
//!   exists is its [`canonical`] path.
//! - [`note_input`]: a file the run reads (a height map, a shard), with the parameter (or
//!   argument) that named it. [`input_at`] says whether a file is one of them, or one that every run reads or
//!   writes besides its outputs: the program itself and its standard input, output and
//!   error where they are regular files. No file a run reads is ever one it writes.

use std::fs;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;

/// What file a path names: see [`file_id`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FileId {
    /// An existing file: its device and inode numbers (through symbolic links).
    Inode {
        /// The device number.
        dev: u64,
        /// The inode number.
        ino: u64,
    },
    /// A path where nothing exists (yet): see [`canonical`].
    Path(PathBuf),
}

/// The (device, inode) of an existing file's metadata.
#[cfg(unix)]
fn inode(m: &fs::Metadata) -> Option<FileId> {
    use std::os::unix::fs::MetadataExt;
    Some(FileId::Inode {
        dev: m.dev(),
        ino: m.ino(),
    })
}

#[cfg(not(unix))]
fn inode(_m: &fs::Metadata) -> Option<FileId> {
    None
}

/// The identity of the file `path` names: its (device, inode) where it exists (following
/// symbolic links), else its [`canonical`] path.
pub fn file_id(path: &Path) -> FileId {
    fs::metadata(path)
        .ok()
        .and_then(|m| inode(&m))
        .unwrap_or_else(|| FileId::Path(canonical(path)))
}

/// `path` made absolute, with its longest existing part resolved by the system (symbolic
/// links, `.` and `..` as the file system has them) and the rest, which does not exist yet,
/// cleaned as text (`.` dropped, `..` removing the name before it).
pub fn canonical(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let parts: Vec<Component> = abs.components().collect();
    let (mut out, rest) = (0..=parts.len())
        .rev()
        .find_map(|k| {
            let head: PathBuf = parts[..k].iter().collect();
            fs::canonicalize(&head).ok().map(|c| (c, &parts[k..]))
        })
        .unwrap_or((PathBuf::new(), &parts[..]));
    for part in rest {
        match part {
            Component::ParentDir => {
                out.pop();
            }
            Component::CurDir => {}
            other => out.push(other),
        }
    }
    out
}

/// What kind of file an [`Input`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InputKind {
    /// A file the run reads, named by a parameter or argument ([`note_input`]).
    Noted,
    /// The program file this process runs from.
    Program,
    /// A standard stream (input, output or error) that is a regular file.
    Stream,
}

/// A file this run reads (or, for a standard stream, writes other than as an output).
#[derive(Debug, Clone)]
pub struct Input {
    /// The path as the user gave it (or as the system names it).
    pub path: PathBuf,
    /// The parameter that named it (its marker, `⟨height_map⟩`, which the front end words;
    /// or a front end's own word), the argument (`DIR`), or what it is ("this run's standard
    /// output").
    pub flag: String,
    /// Its identity when it was noted.
    pub id: FileId,
    /// What kind of file it is.
    pub kind: InputKind,
}

impl Input {
    /// The input in words: "--height-map surf.csv, which this run reads", or what it is.
    pub fn describe(&self) -> String {
        let path = self.path.display();
        match self.kind {
            InputKind::Noted => format!("{} {path}, which this run reads", self.flag),
            InputKind::Program => format!("{} ({path}), which is running", self.flag),
            InputKind::Stream => format!("{} ({path}), where it was redirected", self.flag),
        }
    }
}

/// The files noted by [`note_input`].
static INPUTS: Mutex<Vec<Input>> = Mutex::new(Vec::new());

/// Note that this run reads `path`, named by `flag` (a parameter's marker, e.g.
/// `&HEIGHT_MAP.to_string()`, or an argument's name): an output that is the same file (or whose
/// lock file is) is refused by the claim before any work, and never written.
pub fn note_input(path: &Path, flag: &str) {
    let input = Input {
        path: path.to_path_buf(),
        flag: flag.to_string(),
        id: file_id(path),
        kind: InputKind::Noted,
    };
    if let Ok(mut inputs) = INPUTS.lock() {
        inputs.push(input);
    }
}

/// The files every run reads or writes besides its outputs: the program itself (an output
/// there would replace it while it runs) and its standard input, output and error where they
/// are regular files (`> log.txt`: an output there would replace the file the messages go to).
fn implicit_inputs() -> Vec<Input> {
    let mut found = Vec::new();
    if let Ok(exe) = std::env::current_exe() {
        if let Some(id) = fs::metadata(&exe).ok().and_then(|m| inode(&m)) {
            found.push(Input {
                path: exe,
                flag: "the jkrbem program itself".into(),
                id,
                kind: InputKind::Program,
            });
        }
    }
    for (fd, what) in [
        (0, "this run's standard input"),
        (1, "this run's standard output"),
        (2, "this run's standard error"),
    ] {
        if let Some(id) = regular_stream(fd) {
            let path = PathBuf::from(format!("/dev/fd/{fd}"));
            let shown = fs::read_link(&path).unwrap_or(path);
            found.push(Input {
                path: shown,
                flag: what.into(),
                id,
                kind: InputKind::Stream,
            });
        }
    }
    found
}

/// A standard stream (output or error) redirected to a regular file that this run reads
/// (`--out - >> map.npy`, `2>> map.npy`, a hard link of it): what it is, in words ("this
/// run's standard output is --height-map map.npy, which this run reads"); `None` where
/// neither is. Results or messages written there would change the input.
pub fn stream_on_input() -> Option<String> {
    [(1, "standard output"), (2, "standard error")]
        .into_iter()
        .find_map(|(fd, what)| {
            input_behind(fd).map(|read| format!("this run's {what} is {}", read.describe()))
        })
}

/// Whether the standard stream `fd` (1: output, 2: error) is a regular file this run reads:
/// nothing may then be written to it.
pub fn stream_is_input(fd: i32) -> bool {
    input_behind(fd).is_some()
}

/// The identity of the file the standard stream `fd` is redirected to, where it is a regular
/// file.
fn regular_stream(fd: i32) -> Option<FileId> {
    let m = fs::metadata(format!("/dev/fd/{fd}")).ok()?;
    m.is_file().then(|| inode(&m)).flatten()
}

/// The noted input that the standard stream `fd` is redirected to, if any.
fn input_behind(fd: i32) -> Option<Input> {
    let id = regular_stream(fd)?;
    let inputs = INPUTS.lock().ok()?;
    inputs
        .iter()
        .find(|i| i.id == id && file_id(&i.path) == id)
        .cloned()
}

/// The input that is the file `id`, if any: one noted, or one every run has (the program
/// itself, a standard stream redirected to a regular file). A noted input counts only while
/// its name still names the file that was read: one removed since (whose inode the system
/// may give to a new file) or replaced is no longer it.
pub fn input_at(id: &FileId) -> Option<Input> {
    let noted = INPUTS.lock().ok().and_then(|inputs| {
        inputs
            .iter()
            .find(|i| i.id == *id && file_id(&i.path) == *id)
            .cloned()
    });
    noted.or_else(|| implicit_inputs().into_iter().find(|i| i.id == *id))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_file_has_one_identity_however_it_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let a = dir.path().join("a.csv");
        fs::write(&a, "x").unwrap();
        let sub = dir.path().join("sub");
        fs::create_dir(&sub).unwrap();
        let id = file_id(&a);
        assert!(matches!(id, FileId::Inode { .. }));
        assert_eq!(file_id(&sub.join("../a.csv")), id);
        assert_eq!(file_id(&dir.path().join("./a.csv")), id);
        #[cfg(unix)]
        {
            fs::hard_link(&a, dir.path().join("hard.csv")).unwrap();
            assert_eq!(file_id(&dir.path().join("hard.csv")), id);
            std::os::unix::fs::symlink("a.csv", dir.path().join("soft.csv")).unwrap();
            assert_eq!(file_id(&dir.path().join("soft.csv")), id);
            // A folder reached through a link: a file not yet there has one path.
            std::os::unix::fs::symlink(&sub, dir.path().join("linked")).unwrap();
            assert_eq!(
                file_id(&dir.path().join("linked/new.csv")),
                file_id(&sub.join("new.csv"))
            );
            assert_eq!(
                canonical(&dir.path().join("linked/x/../y/new.csv")),
                canonical(&sub.join("y/new.csv"))
            );
        }
        assert_ne!(file_id(&dir.path().join("b.csv")), id);
    }

    #[test]
    fn a_noted_input_is_found_by_any_of_its_names() {
        let dir = tempfile::tempdir().unwrap();
        let map = dir.path().join("surface-for-note.txt");
        fs::write(&map, "1 2\n3 4\n").unwrap();
        assert!(input_at(&file_id(&map)).is_none());
        note_input(&map, "--height-map");
        let again = dir.path().join("./surface-for-note.txt");
        let found = input_at(&file_id(&again)).unwrap();
        assert_eq!(found.flag, "--height-map");
        assert!(found.describe().starts_with("--height-map "));
        assert!(found.describe().ends_with("which this run reads"));
        // Once removed, its inode may name a new file, which is not the input.
        let id = file_id(&map);
        fs::remove_file(&map).unwrap();
        assert!(input_at(&id).is_none());
        // The program itself is always an input.
        let exe = std::env::current_exe().unwrap();
        assert!(input_at(&file_id(&exe)).is_some());
    }
}
