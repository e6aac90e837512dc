//! The one way jkrbem writes a file.
//!
//! - [`write_atomic`]: the content goes to a unique temporary file in the target's folder
//!   (`.<name>.<random>.tmp`), is flushed and synced, and only then renamed over the target.
//!   An existing target is never deleted or truncated before that, so it is either the old
//!   file or the whole new one, whatever happens on the way (an error, a full disk, a signal).
//! - [`PartialFile`]: a file written while a run goes on (the states CSV). It is written under
//!   a name that says it is partial and is unique per run, `<stem>.incomplete-<pid>.<ext>`, and
//!   renamed to the target only when the run completes; otherwise it stays, marked.
//! - [`OutputLock`]: a lock file `.<name>.lock` beside a target, holding the process id, so that
//!   a second run aimed at the same output is refused while the first one holds it. The lock is
//!   an advisory OS lock on that file, so it is released when its process dies, however it
//!   dies; a lock file left by a killed run is taken over.
//! - [`check_target`]: a target that exists and is not a regular file (a device, a FIFO, a
//!   folder) is refused.
//! - [`read_regular`]: the one way jkrbem reads a file a user may have put in its way (a shard,
//!   a summary): regular files only, opened without blocking, read to a bound.
//!
//! Temporary files and lock files are registered while they exist, so that a signal handler
//! can remove them ([`remove_registered`]) before the process exits.

use super::OutputError;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Read, Write};
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
        flag: None,
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
/// only fail after the work; and a file name too long for the names written beside it.
fn check_file_name(path: &Path) -> Result<(), OutputError> {
    let text = path.to_string_lossy();
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
                "it exists and is write-protected: make it writable (chmod u+w), choose \
                 another name, or pass --force to replace it",
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

/// Create the folder of `path` if needed.
pub fn create_folder(path: &Path) -> Result<(), OutputError> {
    let dir = folder(path);
    fs::create_dir_all(&dir).map_err(|e| OutputError::io(&dir, e))
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
    check_target(path)?;
    let target = resolved(path);
    create_folder(&target)?;
    let dir = folder(&target);
    let mut builder = tempfile::Builder::new();
    let prefix = format!(".{}.", file_name(&target));
    builder.prefix(&prefix).suffix(".tmp");
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
        check_target(path)?;
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

/// Write `bytes` to `path` atomically (see [`write_atomic`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomic(path, |w| w.write_all(bytes))
}

/// Write rows as CSV to `path` atomically (see [`write_atomic`]); `header` is written first
/// when given (so that a file without rows still says what it holds), otherwise the rows'
/// own field names are.
pub fn write_csv<T: serde::Serialize>(
    path: &Path,
    header: Option<&str>,
    rows: impl IntoIterator<Item = T>,
) -> Result<(), OutputError> {
    write_atomic(path, |w| {
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
    })
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
    pub fn create(target: &Path) -> Result<Self, OutputError> {
        check_target(target)?;
        let target = resolved(target);
        create_folder(&target)?;
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
        check_target(&self.target)?;
        fs::rename(&self.partial, &self.target).map_err(|e| OutputError::io(&self.target, e))?;
        Ok(self.target)
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
                    register(&path);
                    let written = file
                        .set_len(0)
                        .and_then(|_| writeln!(file, "{}", std::process::id()))
                        .and_then(|_| file.flush());
                    if let Err(e) = written {
                        // Still holding the lock: remove the empty file it would leave.
                        let _ = fs::remove_file(&path);
                        unregister(&path);
                        return Err(OutputError::io(&path, e));
                    }
                    return Ok(OutputLock {
                        path,
                        file: Some(file),
                    });
                }
                Err(fs::TryLockError::WouldBlock) => {
                    let mut text = String::new();
                    let _ = file.read_to_string(&mut text);
                    return Err(OutputError::Locked {
                        path: target.display().to_string(),
                        flag: None,
                        lock: path.display().to_string(),
                        pid: text.trim().parse().ok(),
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
