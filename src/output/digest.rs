//! What a run read from each input file, recorded beside its results: the file's size and a
//! CRC-32 of its bytes, enough to tell that a height map was replaced by another surface since
//! (a batch's `resume` reruns such a scene; `collect` refuses to merge its summary).

use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::io::Read;
use std::path::Path;

/// A file's content, as a size and a fast hash.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct FileDigest {
    /// Its length (bytes).
    pub bytes: u64,
    /// The CRC-32 (IEEE) of its bytes, as 8 hexadecimal digits.
    pub crc32: String,
}

impl FileDigest {
    /// The digest of `bytes`, a file's whole content.
    pub fn of_bytes(bytes: &[u8]) -> Self {
        FileDigest {
            bytes: bytes.len() as u64,
            crc32: format!("{:08x}", crc32fast::hash(bytes)),
        }
    }

    /// The digest of the regular file at `path`, read in pieces (its content is not held).
    pub fn of_file(path: &Path) -> std::io::Result<Self> {
        let meta = std::fs::metadata(path)?;
        if !meta.is_file() {
            return Err(std::io::Error::other("not a regular file"));
        }
        let mut file = std::fs::File::open(path)?;
        let mut hasher = crc32fast::Hasher::new();
        let mut buf = vec![0u8; 1 << 20];
        let mut bytes = 0u64;
        loop {
            let n = file.read(&mut buf)?;
            if n == 0 {
                break;
            }
            hasher.update(&buf[..n]);
            bytes += n as u64;
        }
        Ok(FileDigest {
            bytes,
            crc32: format!("{:08x}", hasher.finalize()),
        })
    }
}

/// One file a scene read: the parameter that named it, its path as given and as resolved
/// (absolute, so that a check from another folder finds it), and its content's digest.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct InputFile {
    /// The parameter that named it ("height_map", "roughness").
    pub parameter: String,
    /// Its path as the request gave it.
    pub path: String,
    /// Its absolute path when it was read.
    pub resolved: String,
    /// What was read.
    #[serde(flatten)]
    pub digest: FileDigest,
}

impl InputFile {
    /// The record of `bytes`, read from `path` for `parameter`.
    pub fn read(parameter: &str, path: &Path, bytes: &[u8]) -> Self {
        let resolved = std::fs::canonicalize(path)
            .or_else(|_| std::path::absolute(path))
            .unwrap_or_else(|_| path.to_path_buf());
        InputFile {
            parameter: parameter.to_string(),
            path: path.display().to_string(),
            resolved: resolved.display().to_string(),
            digest: FileDigest::of_bytes(bytes),
        }
    }

    /// Why the file no longer holds what was read (replaced, changed, gone), or `None` where
    /// it still does.
    pub fn changed(&self) -> Option<String> {
        self.changed_from(FileDigest::of_file(Path::new(&self.resolved)).map_err(|e| e.to_string()))
    }

    /// Like [`InputFile::changed`], against `now`, the file's digest as it is now (or why it
    /// cannot be read).
    fn changed_from(&self, now: Result<FileDigest, String>) -> Option<String> {
        let what = format!("its {} {}", self.parameter.replace('_', " "), self.path);
        match now {
            Ok(now) if now == self.digest => None,
            Ok(now) if now.bytes != self.digest.bytes => Some(format!(
                "{what} changed since it ran ({} bytes, against {} when read)",
                now.bytes, self.digest.bytes
            )),
            Ok(_) => Some(format!(
                "{what} changed since it ran (same size, other content)"
            )),
            Err(e) => Some(format!(
                "{what} cannot be read to check it ({}: {e})",
                self.resolved
            )),
        }
    }
}

/// The digests of files as they are now, each file read once however many records name it.
#[derive(Debug, Default)]
pub struct CurrentDigests(HashMap<String, Result<FileDigest, String>>);

impl CurrentDigests {
    /// Why `file` no longer holds what was read, or `None` where it still does.
    pub fn changed(&mut self, file: &InputFile) -> Option<String> {
        let now = self
            .0
            .entry(file.resolved.clone())
            .or_insert_with(|| {
                FileDigest::of_file(Path::new(&file.resolved)).map_err(|e| e.to_string())
            })
            .clone();
        file.changed_from(now)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_replaced_file_is_told_apart_and_an_unchanged_one_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.txt");
        std::fs::write(&path, b"1 2\n3 4\n").unwrap();
        let read = InputFile::read("height_map", &path, b"1 2\n3 4\n");
        assert_eq!(read.digest, FileDigest::of_file(&path).unwrap());
        assert_eq!(read.changed(), None);
        std::fs::write(&path, b"1 2\n3 5\n").unwrap();
        assert!(read.changed().unwrap().contains("same size, other content"));
        std::fs::write(&path, b"1 2\n").unwrap();
        assert!(read.changed().unwrap().contains("4 bytes, against 8"));
        std::fs::remove_file(&path).unwrap();
        assert!(read.changed().unwrap().contains("cannot be read"));
    }

    #[test]
    fn the_digest_of_a_file_read_in_pieces_is_that_of_its_bytes() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("big.bin");
        let bytes: Vec<u8> = (0..3_000_000u32).map(|i| (i * 7 % 251) as u8).collect();
        std::fs::write(&path, &bytes).unwrap();
        assert_eq!(
            FileDigest::of_file(&path).unwrap(),
            FileDigest::of_bytes(&bytes)
        );
        let read = InputFile::read("roughness", &path, &bytes);
        let mut now = CurrentDigests::default();
        assert_eq!(now.changed(&read), None);
        std::fs::write(&path, b"other").unwrap();
        assert_eq!(now.changed(&read), None, "read once, as it was first");
        assert!(CurrentDigests::default().changed(&read).is_some());
    }
}
