//! The one way jkrbem writes a file.
//!
//! - [`write_atomic`]: the content goes to a unique temporary file in the target's folder
//!   (`.<name>.<pid>.<random>.tmp`), is flushed and synced, and only then renamed over the
//!   target. An existing target is never deleted or truncated before that, so it is either the
//!   old file or the whole new one, whatever happens on the way (an error, a full disk, a
//!   signal). Temporaries a killed run left are removed by the next run that locks the target
//!   (see the `temporary` submodule).
//! - [`PartialFile`]: a file written while a run goes on (the states CSV). It is written under
//!   a name that says it is partial and is unique per run, `<stem>.incomplete-<pid>.<ext>`, and
//!   renamed to the target only when the run completes; otherwise it stays, marked.
//! - [`OutputLock`]: a lock file `.<name>.lock` beside a target, holding the process id, so that
//!   a second run aimed at the same output is refused while the first one holds it. The lock is
//!   an advisory OS lock on that file, so it is released when its process dies, however it
//!   dies; a lock file left by a killed run is taken over (a file there that holds anything
//!   but a process id is refused, not taken). While it is held, the target is *claimed*:
//!   what it resolved to then is kept, and a write that finds it changed since (a symbolic
//!   link put there during the run) fails instead of following it, after the work, with exit
//!   status 1 and the result kept where it is said to be.
//! - [`file_id`] and [`note_input`]: which file a path names, however spelled or linked, and the
//!   files this run reads; an output that is one of them is refused (see
//!   the session's claim of its outputs), and never written.
//! - [`check_target`]: a target that exists and is not a regular file (a device, a FIFO, a
//!   folder) is refused.
//! - [`read_regular`]: the one way jkrbem reads a file a user may have put in its way (a shard,
//!   a summary): regular files only, opened without blocking, read to a bound.
//!
//! Temporary files and lock files are registered while they exist, so that a signal handler
//! can remove them ([`remove_registered`]) before the process exits.

mod identity;
mod temporary;

pub use identity::{
    canonical, file_id, input_at, note_input, stream_is_input, stream_on_input, FileId, Input,
    InputKind,
};

use super::OutputError;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary and lock files to remove if the process is stopped by a signal.
static REGISTERED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn register(path: &Path) {
    if let Ok(mut r) = REGISTERED.lock() {
        r.push(path.to_path_buf());
    }
}

fn unregister(path: &Path) {
    if let Ok(mut r) = REGISTERED.lock() {
        if let Some(k) = r.iter().rposition(|p| p == path) {
            r.swap_remove(k);
        }
    }
}

/// Remove every temporary and lock file that is registered now (for a signal handler, just
/// before the process exits). Returns how many were removed.
pub fn remove_registered() -> usize {
    REGISTERED
        .lock()
        .map_or(0, |mut r| remove_all(std::mem::take(&mut *r)))
}

/// [`remove_registered`] where the list may be held by this very thread (an allocation that
/// failed while registering): removes nothing then, rather than wait for itself.
pub fn try_remove_registered() -> usize {
    REGISTERED
        .try_lock()
        .map_or(0, |mut r| remove_all(std::mem::take(&mut *r)))
}

fn remove_all(paths: Vec<PathBuf>) -> usize {
    paths.iter().filter(|p| fs::remove_file(p).is_ok()).count()
}

/// The file name of `path` as text ("output" if it has none).
fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned())
}

/// The folder of `path` ("." for a bare file name).
fn folder(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Whether an existing write-protected target may be replaced (`--force`); set once by the
/// command line.
static FORCE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Let writes replace write-protected targets (the command line's `--force`).
pub fn set_force(force: bool) {
    FORCE.store(force, std::sync::atomic::Ordering::Relaxed);
}

fn refused(path: &Path, reason: impl Into<String>) -> OutputError {
    OutputError::Refused {
        path: path.display().to_string(),
        param: None,
        reason: reason.into(),
    }
}

/// The user id this process acts as (files it creates are owned by it).
#[cfg(unix)]
fn effective_uid() -> u32 {
    // SAFETY: geteuid has no preconditions and cannot fail.
    unsafe { libc::geteuid() }
}

/// Refuse a symbolic link at `path` that another user owns: following it would let that user
/// redirect this run's write to any file the runner may write (the rule of Linux's
/// `protected_symlinks`). The runner's own links are followed.
#[cfg(unix)]
fn check_link_owner(path: &Path, uid: u32) -> Result<(), OutputError> {
    use std::os::unix::fs::MetadataExt;
    match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() && m.uid() != uid => Err(refused(
            path,
            format!(
                "it is a symbolic link owned by another user (uid {}, this run's is {uid}): a \
                 link planted by someone else could redirect the write to any file; remove it \
                 or name the file it points to",
                m.uid()
            ),
        )),
        _ => Ok(()),
    }
}

/// The longest output file name (bytes): the lock, temporary and partial names beside it add
/// up to 30 bytes to it, and a file name may have 255.
pub const MAX_NAME_BYTES: usize = 225;

/// Refuse a name that ends in `/` (or `/.`, `/..`): it names a folder, and the write would
/// only fail after the work; a file name too long for the names written beside it; and a
/// name with a control character (a newline, a tab, an escape), which would break every
/// message and listing that names it (the message shows it escaped).
fn check_file_name(path: &Path) -> Result<(), OutputError> {
    let text = path.to_string_lossy();
    if let Some(c) = text.chars().find(|c| c.is_control()) {
        return Err(OutputError::Refused {
            path: format!("{text:?}"),
            param: None,
            reason: format!(
                "the name holds a control character ({c:?}), which would break the messages \
                 and listings that name the file: choose a name without one"
            ),
        });
    }
    let folder_like = text.ends_with('/')
        || text.ends_with("/.")
        || text.ends_with("/..")
        || matches!(&*text, "." | "..")
        || path.file_name().is_none();
    if folder_like {
        return Err(refused(
            path,
            "the name ends in a folder, not a file: give a file name (e.g. out/states.csv)",
        ));
    }
    let name_bytes = path.file_name().map_or(0, |n| n.len());
    if name_bytes > MAX_NAME_BYTES {
        return Err(refused(
            path,
            format!(
                "the file name is {name_bytes} bytes long; at most {MAX_NAME_BYTES} (the \
                 files written beside it, `.<name>.lock` and `<stem>.incomplete-<pid>.<ext>`, \
                 need the rest of the system's 255)"
            ),
        ));
    }
    Ok(())
}

/// Refuse an existing target without write permission for its owner (as the shell's `>`
/// would for a non-root user), unless forced.
fn check_writable(path: &Path, meta: &fs::Metadata) -> Result<(), OutputError> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        if meta.permissions().mode() & 0o200 == 0
            && !FORCE.load(std::sync::atomic::Ordering::Relaxed)
        {
            return Err(refused(
                path,
                format!(
                    "it exists and is write-protected: make it writable (chmod u+w), choose \
                     another name, or pass {} to replace it",
                    crate::params::FORCE
                ),
            ));
        }
    }
    #[cfg(not(unix))]
    let _ = (path, meta);
    Ok(())
}

/// Refuse `path` if its name ends in a folder, if it is a symbolic link owned by another user,
/// if it exists and is not a regular file (after following a symbolic link: writing there
/// would replace a device, a FIFO or a folder with a file), or if it is write-protected
/// (unless forced).
pub fn check_target(path: &Path) -> Result<(), OutputError> {
    check_file_name(path)?;
    #[cfg(unix)]
    check_link_owner(path, effective_uid())?;
    match fs::metadata(path) {
        Ok(m) if m.is_file() => check_writable(path, &m),
        Ok(m) => Err(refused(
            path,
            format!(
                "it exists and is {}, not a regular file",
                if m.is_dir() {
                    "a folder"
                } else {
                    "a device, FIFO or socket"
                }
            ),
        )),
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            // A dangling symbolic link: refuse rather than replace the link.
            match fs::symlink_metadata(path) {
                Ok(_) => Err(refused(path, "it is a symbolic link to nothing")),
                Err(_) => Ok(()),
            }
        }
        // A file where a folder should be, a name too long, a folder that may not be read:
        // the path cannot be written, whatever the run computes.
        Err(e) => Err(refused(path, e.to_string())),
    }
}

/// The path a write to `path` replaces: `path` itself, or the file a symbolic link there
/// points to (so that the link is kept).
fn resolved(path: &Path) -> PathBuf {
    match fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => fs::canonicalize(path).unwrap_or(path.into()),
        _ => path.to_path_buf(),
    }
}

/// The lock file a claim of `target` takes: beside the file a write to `target` replaces
/// (through a symbolic link there).
pub fn lock_of(target: &Path) -> PathBuf {
    lock_path(&resolved(target))
}

/// `path` as one name, not followed through a symbolic link at its end: its folder
/// [`canonical`], and its file name.
fn name_id(path: &Path) -> PathBuf {
    match path.file_name() {
        Some(name) => canonical(&folder(path)).join(name),
        None => canonical(path),
    }
}

/// The outputs this process holds the lock of: each name (see [`name_id`]) and the file it
/// resolved to when its lock was taken.
static CLAIMED: Mutex<Vec<(PathBuf, PathBuf)>> = Mutex::new(Vec::new());

/// What `path` resolved to when this process locked it, if it holds its lock.
fn claimed(path: &Path) -> Option<PathBuf> {
    let name = name_id(path);
    CLAIMED
        .lock()
        .ok()?
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, resolved)| resolved.clone())
}

/// A refusal found while writing, after the run's work: a failure (exit status 1), since
/// the work was done, that says nothing was written under the name.
fn after_work(e: OutputError, kept: Option<&Path>) -> OutputError {
    let kept = kept.map_or_else(String::new, |p| {
        format!("; the complete result is kept in {}", p.display())
    });
    match e {
        OutputError::Refused {
            path,
            param,
            reason,
        } => OutputError::Io {
            path,
            param,
            source: io::Error::other(format!(
                "{reason} (found when writing, after the run's work: it changed during the \
                 run), so nothing was written under this name{kept}"
            )),
        },
        OutputError::Io {
            path,
            param,
            source,
        } if !kept.is_empty() => OutputError::Io {
            path,
            param,
            source: io::Error::new(source.kind(), format!("{source}{kept}")),
        },
        other => other,
    }
}

/// Refuse to write `target` (the file a write to `path` replaces) where it changed since
/// the claim: now a symbolic link, or resolving elsewhere than it did then (a link put there
/// or changed during the run); or where it is a file this run reads.
fn check_unchanged(path: &Path, target: &Path) -> Result<(), OutputError> {
    if let Some(at_claim) = claimed(path) {
        let now_link = fs::symlink_metadata(&at_claim).is_ok_and(|m| m.file_type().is_symlink());
        if now_link || name_id(&at_claim) != name_id(target) {
            return Err(refused(
                path,
                "a symbolic link was put at it (or changed) during the run; a link that was \
                 not there when the run claimed the file is neither followed nor replaced",
            ));
        }
    }
    if let Some(input) = input_at(&file_id(target)) {
        return Err(refused(
            path,
            format!("it is now the same file as {}", input.describe()),
        ));
    }
    Ok(())
}

/// Create the folder of `path` if needed. A folder on the way that is a symbolic link to
/// nothing is refused, naming it (the system says only "File exists").
pub fn create_folder(path: &Path) -> Result<(), OutputError> {
    let dir = folder(path);
    fs::create_dir_all(&dir).map_err(|e| {
        let dangling = dir.ancestors().find(|a| {
            fs::symlink_metadata(a).is_ok_and(|m| m.file_type().is_symlink())
                && fs::metadata(a).is_err()
        });
        match dangling {
            Some(link) => refused(
                link,
                format!(
                    "its folder is a symbolic link to nothing ({}), so nothing can be written \
                     in it: create the folder it points to, or remove the link",
                    fs::read_link(link).unwrap_or_default().display()
                ),
            ),
            None => OutputError::io(&dir, e),
        }
    })
}

/// Open a new file with the usual permissions (0666 less the umask), or the target's if it
/// exists.
fn permissions_like(file: &File, target: &Path) {
    if let Ok(m) = fs::metadata(target) {
        let _ = file.set_permissions(m.permissions());
    }
}

/// Write `path` atomically: `write` fills a unique temporary file in the same folder, which is
/// synced and renamed over `path` only if `write` succeeds. On any error the temporary file is
/// removed and `path` is untouched. The folder is created if needed; a `path` that exists and
/// is not a regular file is refused.
pub fn write_atomic<F>(path: &Path, write: F) -> Result<(), OutputError>
where
    F: FnOnce(&mut BufWriter<&File>) -> io::Result<()>,
{
    // After the claim (this process holds the lock), a refusal is a failure of the work.
    let late = claimed(path).is_some();
    let checked = || -> Result<PathBuf, OutputError> {
        check_target(path)?;
        let target = resolved(path);
        check_unchanged(path, &target)?;
        Ok(target)
    };
    let target = checked().map_err(|e| if late { after_work(e, None) } else { e })?;
    create_folder(&target)?;
    let dir = folder(&target);
    let mut builder = tempfile::Builder::new();
    let prefix = temporary::prefix(&file_name(&target));
    builder
        .prefix(&prefix)
        .rand_bytes(temporary::RANDOM_CHARS)
        .suffix(temporary::SUFFIX);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    let tmp = builder
        .tempfile_in(&dir)
        .map_err(|e| OutputError::io(&dir, e))?;
    let tmp_path = tmp.path().to_path_buf();
    register(&tmp_path);
    let result = (|| -> Result<(), OutputError> {
        let err = |e| OutputError::io(path, e);
        {
            let mut w = BufWriter::new(tmp.as_file());
            write(&mut w).map_err(err)?;
            w.flush().map_err(err)?;
        }
        tmp.as_file().sync_all().map_err(err)?;
        permissions_like(tmp.as_file(), &target);
        check_target(path).map_err(|e| after_work(e, None))?;
        if resolved(path) != target {
            return Err(after_work(
                refused(path, "a symbolic link was put at it while it was written"),
                None,
            ));
        }
        check_unchanged(path, &target).map_err(|e| after_work(e, None))?;
        Ok(())
    })();
    let outcome = match result {
        Ok(()) => tmp
            .persist(&target)
            .map(|_| ())
            .map_err(|e| OutputError::io(path, e.error)),
        Err(e) => Err(e),
    };
    unregister(&tmp_path);
    outcome
}

/// Write `bytes` to `path` atomically (see [`write_atomic`]), as they are (a binary file).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomic(path, |w| w.write_all(bytes))
}

/// Write `text` to `path` atomically (see [`write_atomic`]), in the command line's words.
///
/// The rule for text files: the messages a file carries (a summary's warnings, a row's error,
/// a chart's legend, the study's captions) name their parameters by marker in memory, so that
/// each front end words them; every text file the library writes (JSON, CSV, SVG, HTML) is the
/// command line's, and is worded as it is written, each marker as its flag
/// ([`words::flags`](crate::params::words::flags)). A file read back (a summary a later
/// run reuses, a shard) therefore names flags.
pub fn write_text(path: &Path, text: &str) -> Result<(), OutputError> {
    write_bytes(path, crate::params::words::flags(text).as_bytes())
}

/// Write rows as CSV to `path` atomically (see [`write_atomic`]); `header` is written first
/// when given (so that a file without rows still says what it holds), otherwise the rows'
/// own field names are. Text in the rows is worded for the command line, as by
/// [`write_text`].
pub fn write_csv<T: serde::Serialize>(
    path: &Path,
    header: Option<&str>,
    rows: impl IntoIterator<Item = T>,
) -> Result<(), OutputError> {
    let mut bytes = Vec::new();
    csv_to(&mut bytes, header, rows).map_err(|e| OutputError::io(path, e))?;
    let text = String::from_utf8(bytes).map_err(|e| OutputError::io(path, io::Error::other(e)))?;
    write_text(path, &text)
}

/// Write rows as CSV to `w`, as [`write_csv`] writes them to a file (for a stream that is not
/// a file, such as standard output, given a `Vec<u8>`).
pub fn csv_to<T: serde::Serialize>(
    w: impl Write,
    header: Option<&str>,
    rows: impl IntoIterator<Item = T>,
) -> io::Result<()> {
    let mut c = csv::WriterBuilder::new()
        .has_headers(header.is_none())
        .from_writer(w);
    if let Some(h) = header {
        c.write_record(h.split(',')).map_err(io::Error::other)?;
    }
    for r in rows {
        c.serialize(r).map_err(io::Error::other)?;
    }
    c.flush()
}

/// Open `path` for reading without blocking on a FIFO.
#[cfg(unix)]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

/// Open `path` for reading.
#[cfg(not(unix))]
fn open_nonblocking(path: &Path) -> io::Result<File> {
    File::open(path)
}

/// Why [`read_regular`] read nothing.
#[derive(Debug)]
pub enum ReadError {
    /// No file of that name.
    Absent,
    /// Not a regular file, too large, or unreadable: the reason in words.
    Refused(String),
}

/// The bytes of the regular file `path`, at most `limit` of them. Anything else (a FIFO, a
/// device such as /dev/zero, a folder) is refused before it is opened and again, by the open
/// file's own metadata, after (so that one swapped in between cannot block or fill memory);
/// the file is opened non-blocking and read no further than `limit` + 1 bytes.
pub fn read_regular(path: &Path, limit: u64) -> Result<Vec<u8>, ReadError> {
    let not_regular = || {
        ReadError::Refused(
            "not a regular file (a FIFO, a device or a folder); only regular files are read".into(),
        )
    };
    let io = |e: std::io::Error| match e.kind() {
        std::io::ErrorKind::NotFound => ReadError::Absent,
        _ => ReadError::Refused(e.to_string()),
    };
    if !std::fs::metadata(path).map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let file = open_nonblocking(path).map_err(io)?;
    if !file.metadata().map_err(io)?.is_file() {
        return Err(not_regular());
    }
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| ReadError::Refused(e.to_string()))?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::Refused(format!(
            "larger than {} MiB, more than any file of its kind holds",
            limit >> 20
        )));
    }
    Ok(bytes)
}

/// The name of a run's partial file for `target`: `<stem>.incomplete-<pid>.<ext>` beside it,
/// with `-2`, `-3`, … added if that exists.
fn partial_candidates(target: &Path) -> impl Iterator<Item = PathBuf> + '_ {
    let stem = target
        .file_stem()
        .map_or_else(|| "output".into(), |s| s.to_string_lossy().into_owned());
    let ext = target
        .extension()
        .map_or_else(String::new, |e| format!(".{}", e.to_string_lossy()));
    let pid = std::process::id();
    (1..).map(move |k| {
        let n = if k == 1 {
            String::new()
        } else {
            format!("-{k}")
        };
        target.with_file_name(format!("{stem}.incomplete-{pid}{n}{ext}"))
    })
}

/// Whether `name` is the file name of a partial file of `target_name` (see [`PartialFile`]).
pub fn is_partial_of(name: &str, target_name: &str) -> bool {
    let (stem, ext) = match target_name.rsplit_once('.') {
        Some((s, e)) => (s, format!(".{e}")),
        None => (target_name, String::new()),
    };
    name.strip_prefix(&format!("{stem}.incomplete-"))
        .and_then(|rest| rest.strip_suffix(&ext))
        .is_some_and(|id| !id.is_empty() && id.chars().all(|c| c.is_ascii_digit() || c == '-'))
}

/// A file written while a run goes on: under a partial name unique to this run until
/// [`PartialFile::finish`] renames it to its target (see the module's description).
pub struct PartialFile {
    target: PathBuf,
    partial: PathBuf,
    writer: BufWriter<File>,
}

impl PartialFile {
    /// Start writing the partial file of `target` (creating its folder). A `target` that
    /// exists and is not a regular file is refused; an existing regular one is left as it is.
    /// The partial files of `target` that runs no longer alive left holding nothing past
    /// their first line are removed first (see the `temporary` module).
    pub fn create(target: &Path) -> Result<Self, OutputError> {
        check_target(target)?;
        let target = resolved(target);
        create_folder(&target)?;
        temporary::remove_empty_partials(&folder(&target), &file_name(&target));
        let candidates: Vec<PathBuf> = partial_candidates(&target).take(1000).collect();
        for partial in candidates {
            let mut open = OpenOptions::new();
            open.write(true).create_new(true);
            match open.open(&partial) {
                Ok(file) => {
                    return Ok(PartialFile {
                        target,
                        partial,
                        writer: BufWriter::new(file),
                    })
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
                Err(e) => return Err(OutputError::io(&partial, e)),
            }
        }
        Err(OutputError::io(
            &target,
            io::Error::other("no free name for the partial file"),
        ))
    }

    /// Where the content is being written now.
    pub fn partial_path(&self) -> &Path {
        &self.partial
    }

    /// Flush what was written to the file, so that a reader (or a killed run) sees it.
    pub fn flush(&mut self) -> Result<(), OutputError> {
        self.writer
            .flush()
            .map_err(|e| OutputError::io(&self.partial, e))
    }

    /// Close the file. If `complete`, it is synced and renamed to the target; otherwise it
    /// keeps its partial name. Returns where the content is.
    pub fn finish(mut self, complete: bool) -> Result<PathBuf, OutputError> {
        self.flush()?;
        if !complete {
            return Ok(self.partial);
        }
        let file = self
            .writer
            .into_inner()
            .map_err(|e| OutputError::io(&self.partial, e.into_error()))?;
        file.sync_all()
            .map_err(|e| OutputError::io(&self.partial, e))?;
        permissions_like(&file, &self.target);
        drop(file);
        // The work is done: whatever is found now is a failure, and the result stays under
        // its partial name, said in the message.
        let kept = Some(self.partial.as_path());
        check_no_link_put_at(&self.target)
            .and_then(|()| check_target(&self.target))
            .and_then(|()| check_unchanged(&self.target, &self.target))
            .map_err(|e| after_work(e, kept))?;
        fs::rename(&self.partial, &self.target)
            .map_err(|e| after_work(OutputError::io(&self.target, e), kept))?;
        Ok(self.target)
    }
}

/// Refuse a symbolic link at a partial file's target: [`PartialFile::create`] resolved any
/// link there, so a link there now was put there during the run (it is not followed, which
/// would write where nothing was checked, nor replaced).
fn check_no_link_put_at(target: &Path) -> Result<(), OutputError> {
    match fs::symlink_metadata(target) {
        Ok(m) if m.file_type().is_symlink() => Err(refused(
            target,
            "a symbolic link was put at it during the run; it is neither followed nor replaced",
        )),
        _ => Ok(()),
    }
}

impl Write for PartialFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.writer.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer.flush()
    }
}

/// The lock file of a target: `.<name>.lock` in its folder.
pub fn lock_path(target: &Path) -> PathBuf {
    target.with_file_name(format!(".{}.lock", file_name(target)))
}

/// A held lock on an output (see the module's description). Dropping it removes the lock
/// file and releases the lock.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
    file: Option<File>,
    /// The claimed name (see [`name_id`]), in [`CLAIMED`] while the lock is held.
    name: PathBuf,
}

#[cfg(unix)]
fn same_file(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

#[cfg(not(unix))]
fn same_file(_file: &File, path: &Path) -> bool {
    path.exists()
}

/// Open (or create) the lock file at `path` without following a symbolic link there and
/// without blocking on a FIFO, and refuse anything but a regular file with one name that this
/// user owns: a lock file is truncated and written, so one planted by someone else (a link
/// or a hard link to a file of the runner's) must never be opened for writing.
fn open_lock_file(path: &Path) -> Result<File, OutputError> {
    let mut open = OpenOptions::new();
    open.read(true).write(true).create(true).truncate(false);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        open.custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK);
    }
    let file = match open.open(path) {
        Ok(f) => f,
        Err(e) if is_link_error(&e, path) => {
            return Err(refused(
                path,
                "the lock file's name is a symbolic link: a lock is never opened through a \
                 link (it could point at any file); remove the link",
            ))
        }
        Err(e) => return Err(OutputError::io(path, e)),
    };
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let m = file.metadata().map_err(|e| OutputError::io(path, e))?;
        if !m.is_file() {
            return Err(refused(
                path,
                "the lock file's name is taken by something that is not a regular file",
            ));
        }
        if m.uid() != effective_uid() || m.nlink() != 1 {
            return Err(refused(
                path,
                format!(
                    "the lock file exists and belongs to another user (uid {}) or has other \
                     names ({} links): it is not this user's lock; remove it",
                    m.uid(),
                    m.nlink()
                ),
            ));
        }
    }
    Ok(file)
}

/// The most bytes a lock file holds: a process id and a newline.
const MAX_LOCK_BYTES: u64 = 24;

/// Refuse to take over a file at a lock's name that holds anything but a process id (or
/// nothing): it is some other file that happens to have that name, and taking the lock would
/// truncate it and remove it at the end.
fn check_lock_content(file: &mut File, path: &Path) -> Result<(), OutputError> {
    let mut text = String::new();
    let read = file.take(MAX_LOCK_BYTES + 1).read_to_string(&mut text);
    let is_pid = |t: &str| t.trim().bytes().all(|b| b.is_ascii_digit());
    let lock_like = read.is_ok() && text.len() as u64 <= MAX_LOCK_BYTES && is_pid(&text);
    if lock_like {
        return Ok(());
    }
    Err(refused(
        path,
        "a file of that name exists and is not a jkrbem lock file (it holds something other \
         than a process id): it is never truncated or removed; rename it or remove it",
    ))
}

/// Whether opening `path` failed because it is a symbolic link (`O_NOFOLLOW`).
fn is_link_error(e: &io::Error, path: &Path) -> bool {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::ELOOP) {
        return true;
    }
    let _ = e;
    fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink())
}

impl OutputLock {
    /// Lock `target` for this process (creating its folder). Refused, naming the process that
    /// holds it, while another process holds it.
    pub fn acquire(target: &Path) -> Result<Self, OutputError> {
        let name = name_id(target);
        let target = resolved(target);
        create_folder(&target)?;
        let path = lock_path(&target);
        for _ in 0..100 {
            let mut file = open_lock_file(&path)?;
            match file.try_lock() {
                Ok(()) => {
                    // A holder that finished removes its lock file before it unlocks: if
                    // ours is no longer the file at `path`, start again.
                    if !same_file(&file, &path) {
                        continue;
                    }
                    check_lock_content(&mut file, &path)?;
                    register(&path);
                    let written = file
                        .set_len(0)
                        .and_then(|_| file.rewind())
                        .and_then(|_| writeln!(file, "{}", std::process::id()))
                        .and_then(|_| file.flush());
                    if let Err(e) = written {
                        // Still holding the lock: remove the empty file it would leave.
                        let _ = fs::remove_file(&path);
                        unregister(&path);
                        return Err(OutputError::io(&path, e));
                    }
                    if let Ok(mut claimed) = CLAIMED.lock() {
                        claimed.push((name.clone(), target.clone()));
                    }
                    // No other live process writes the target now: its temporaries whose
                    // writer is gone were left by a killed run.
                    temporary::remove_stale(&folder(&target), &file_name(&target));
                    return Ok(OutputLock {
                        path,
                        file: Some(file),
                        name,
                    });
                }
                Err(fs::TryLockError::WouldBlock) => {
                    let mut text = String::new();
                    let _ = (&mut file).take(64).read_to_string(&mut text);
                    let pid: Option<u32> = text.trim().parse().ok();
                    if pid == Some(std::process::id()) {
                        return Err(refused(
                            &target,
                            format!(
                                "its lock file {} is held by this same run: another of its \
                                 outputs is this file (under another name or through a link); \
                                 give the outputs different files",
                                path.display()
                            ),
                        ));
                    }
                    return Err(OutputError::Locked {
                        path: target.display().to_string(),
                        param: None,
                        lock: path.display().to_string(),
                        pid,
                    });
                }
                Err(fs::TryLockError::Error(e)) => return Err(OutputError::io(&path, e)),
            }
        }
        Err(OutputError::io(
            &path,
            io::Error::other("the lock file kept changing"),
        ))
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for OutputLock {
    fn drop(&mut self) {
        // Remove the file while still holding the lock, then release it.
        let _ = fs::remove_file(&self.path);
        unregister(&self.path);
        if let Ok(mut claimed) = CLAIMED.lock() {
            if let Some(k) = claimed.iter().rposition(|(n, _)| *n == self.name) {
                claimed.swap_remove(k);
            }
        }
        drop(self.file.take());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_atomic_write_that_fails_leaves_the_old_file_and_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("keep.csv");
        fs::write(&path, "old\n").unwrap();
        let e = write_atomic(&path, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("disk full"))
        })
        .unwrap_err();
        assert!(e.to_string().contains("keep.csv"), "{e}");
        assert_eq!(fs::read_to_string(&path).unwrap(), "old\n");
        let names: Vec<_> = fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "a temporary file was left: {names:?}");
        write_bytes(&path, b"new\n").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "new\n");
    }

    #[test]
    fn non_regular_targets_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let e = write_bytes(dir.path(), b"x").unwrap_err();
        assert!(matches!(e, OutputError::Refused { .. }), "{e}");
        assert!(e.to_string().contains("folder"), "{e}");
        #[cfg(unix)]
        {
            let e = write_bytes(Path::new("/dev/null"), b"x").unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
            let link = dir.path().join("dangling");
            std::os::unix::fs::symlink(dir.path().join("nowhere"), &link).unwrap();
            assert!(write_bytes(&link, b"x").is_err());
        }
    }

    #[test]
    fn a_link_to_a_file_is_kept_and_the_file_replaced() {
        #[cfg(unix)]
        {
            let dir = tempfile::tempdir().unwrap();
            let real = dir.path().join("real.json");
            fs::write(&real, "old").unwrap();
            let link = dir.path().join("link.json");
            std::os::unix::fs::symlink(&real, &link).unwrap();
            write_bytes(&link, b"new").unwrap();
            assert!(fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink());
            assert_eq!(fs::read_to_string(&real).unwrap(), "new");
        }
    }

    #[test]
    fn partial_files_have_unique_names_and_only_a_complete_one_takes_the_target() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("s.csv");
        fs::write(&target, "previous run\n").unwrap();
        let mut a = PartialFile::create(&target).unwrap();
        let mut b = PartialFile::create(&target).unwrap();
        assert_ne!(a.partial_path(), b.partial_path());
        let name = |p: &Path| p.file_name().unwrap().to_string_lossy().into_owned();
        assert!(is_partial_of(&name(a.partial_path()), "s.csv"));
        assert!(!is_partial_of("s.csv", "s.csv"));
        a.write_all(b"a\n").unwrap();
        b.write_all(b"b\n").unwrap();
        let kept = a.finish(false).unwrap();
        assert_eq!(fs::read_to_string(&target).unwrap(), "previous run\n");
        assert_eq!(fs::read_to_string(&kept).unwrap(), "a\n");
        assert_eq!(b.finish(true).unwrap(), target);
        assert_eq!(fs::read_to_string(&target).unwrap(), "b\n");
    }

    #[test]
    fn a_temporary_is_named_with_its_process_id() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("t.csv");
        let mut seen = Vec::new();
        write_atomic(&target, |w| {
            seen = fs::read_dir(dir.path())
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            w.write_all(b"x")
        })
        .unwrap();
        assert_eq!(seen.len(), 1, "{seen:?}");
        assert_eq!(
            temporary::writer_of(&seen[0], "t.csv"),
            Some(std::process::id())
        );
    }

    #[test]
    fn a_file_at_a_lock_name_that_is_no_lock_is_never_taken() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.csv");
        fs::write(lock_path(&target), "precious\n").unwrap();
        let e = OutputLock::acquire(&target).unwrap_err();
        assert!(
            e.is_refusal() && e.to_string().contains("not a jkrbem lock"),
            "{e}"
        );
        assert_eq!(
            fs::read_to_string(lock_path(&target)).unwrap(),
            "precious\n"
        );
        // A killed run's lock (its process id) is taken over.
        fs::write(lock_path(&target), "4194303\n").unwrap();
        drop(OutputLock::acquire(&target).unwrap());
        assert!(!lock_path(&target).exists());
    }

    #[test]
    fn one_process_claiming_one_file_twice_is_not_told_of_another_run() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("twice.csv");
        let held = OutputLock::acquire(&target).unwrap();
        let e = OutputLock::acquire(&dir.path().join("./twice.csv")).unwrap_err();
        assert!(matches!(e, OutputError::Refused { .. }), "{e}");
        assert!(e.to_string().contains("this same run"), "{e}");
        drop(held);
    }

    #[cfg(unix)]
    #[test]
    fn a_link_put_at_a_partial_file_s_target_is_neither_followed_nor_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("s.csv");
        let held = OutputLock::acquire(&target).unwrap();
        let mut p = PartialFile::create(&target).unwrap();
        p.write_all(b"all of it\n").unwrap();
        let partial = p.partial_path().to_path_buf();
        std::os::unix::fs::symlink("victim.csv", &target).unwrap();
        let e = p.finish(true).unwrap_err();
        assert!(!e.is_refusal(), "{e}");
        let text = e.to_string();
        assert!(text.contains("symbolic link"), "{text}");
        assert!(text.contains(&partial.display().to_string()), "{text}");
        assert_eq!(fs::read_to_string(&partial).unwrap(), "all of it\n");
        assert!(fs::symlink_metadata(&target).unwrap().is_symlink());
        assert!(!dir.path().join("victim.csv").exists());
        // A summary written after the claim is not written through a link put there since.
        let summary = dir.path().join("s.json");
        let claim = OutputLock::acquire(&summary).unwrap();
        fs::write(dir.path().join("victim.json"), "KEEP").unwrap();
        std::os::unix::fs::symlink("victim.json", &summary).unwrap();
        let e = write_bytes(&summary, b"{}").unwrap_err();
        assert!(
            !e.is_refusal() && e.to_string().contains("symbolic link"),
            "{e}"
        );
        assert_eq!(
            fs::read_to_string(dir.path().join("victim.json")).unwrap(),
            "KEEP"
        );
        drop((held, claim));
    }

    #[test]
    fn a_lock_is_exclusive_and_released_on_drop() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.csv");
        let held = OutputLock::acquire(&target).unwrap();
        let text = fs::read_to_string(held.path()).unwrap();
        assert_eq!(text.trim(), std::process::id().to_string());
        // A second open file description (as another process has) cannot take it.
        let lock = lock_path(&target);
        let other = OpenOptions::new().write(true).open(&lock).unwrap();
        assert!(other.try_lock().is_err());
        drop(other);
        drop(held);
        assert!(!lock.exists());
        let again = OutputLock::acquire(&target).unwrap();
        drop(again);
    }
}
