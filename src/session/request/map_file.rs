//! A height map read from its file (`.npy` or text), refused before reading where it would not
//! fit in memory.

use super::super::{input, refuse, RunError};
use crate::output::digest::InputFile;
use crate::output::file::{read_regular, ReadError};
use crate::params::{Spec, SPACING};
use crate::scene::height_map::{HeightMap, HeightMapError};
use std::collections::HashMap;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

/// The largest height-map file read (bytes): the largest map, 16384², as text of up to 32
/// characters a value.
const MAX_MAP_BYTES: u64 = 16384 * 16384 * 32;

/// Memory reading a height map may take per byte of its file (dimensionless): the file's
/// bytes, the heights parsed from them (8 bytes for a text value of 2 characters or more, and
/// the list they grow in) and the map built from them.
const MAP_READ_BYTES_PER_BYTE: u64 = 6;

/// The bytes of a `.npy` header read before the data: NumPy writes headers of a few hundred.
const NPY_HEADER_PREFIX: u64 = 1 << 16;

/// Refuse a regular `.npy` file whose header states a shape outside the map limits, from its
/// first bytes alone (the data is not read).
fn refuse_npy_shape(path: &Path, name: &str, param: &'static Spec) -> Result<(), RunError> {
    use std::io::Read;
    if !std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        return Ok(()); // read_regular says why it cannot be read
    }
    let mut prefix = Vec::new();
    if let Ok(f) = std::fs::File::open(path) {
        let _ = f.take(NPY_HEADER_PREFIX).read_to_end(&mut prefix);
    }
    if !prefix.starts_with(b"\x93NUMPY") {
        return Ok(());
    }
    HeightMap::refuse_npy_shape(&prefix, name).map_err(|e| refuse(param, format!("{param}: {e}")))
}

/// Refuse, before reading it, a map file whose reading would need more memory than the machine
/// has ([`crate::plan::available_memory`]).
fn check_map_memory(path: &Path, name: &str, param: &'static Spec) -> Result<(), RunError> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(()); // read_regular says why it cannot be read
    };
    let available = crate::plan::available_memory().map_err(input)?;
    let need = meta.len().saturating_mul(MAP_READ_BYTES_PER_BYTE);
    match available {
        Some(a) if meta.is_file() && need > a => Err(refuse(
            param,
            format!(
                "{param} {name}: reading this {} file needs up to {} of memory, more than the \
             {} this machine has available (free memory, control group and process limits): \
             save it as a .npy of float32 (4 bytes a height), or crop or subsample it",
                crate::plan::bytes_text(meta.len()),
                crate::plan::bytes_text(need),
                crate::plan::bytes_text(a)
            ),
        )),
        _ => Ok(()),
    }
}

/// The map of the file at `path` (shown as `name`) given by `param` (the height map, or the
/// roughness added to a base shape), which errors name, with nodes `spacing` apart (length),
/// and the record of what was read. The file is noted as this run's input, so that no output
/// of the run may be it.
fn read_as(
    path: &Path,
    name: &str,
    spacing: f64,
    param: &'static Spec,
) -> Result<(HeightMap, InputFile), RunError> {
    crate::output::file::note_input(path, &param.to_string());
    refuse_npy_shape(path, name, param)?;
    check_map_memory(path, name, param)?;
    let bytes = read_regular(path, MAX_MAP_BYTES).map_err(|e| match e {
        ReadError::Absent => refuse(param, format!("{param} {name}: no such file")),
        ReadError::Refused(why) => refuse(param, format!("{param} {name}: {why}")),
    })?;
    let read = InputFile::read(param.name, path, &bytes);
    let map = HeightMap::from_file_bytes(path, &bytes, spacing).map_err(|e| match e {
        HeightMapError::Spacing { .. } => refuse(SPACING, format!("{SPACING}: {e}")),
        e => refuse(param, format!("{param}: {e}")),
    })?;
    Ok((map, read))
}

/// Height-map files read for many requests (a batch's rows): each file, by its resolved path,
/// read and checked once, its heights shared by every request that names it (whatever the
/// spacing each gives), so that 200 rows naming one 8 MB map hold it once, not 200 times.
#[derive(Debug, Default)]
pub struct MapReads {
    /// Each file read, by its resolved path and its name's extension (which chooses how its
    /// bytes are read): its map and the record of what was read.
    read: HashMap<(PathBuf, Option<OsString>), (HeightMap, InputFile)>,
}

impl MapReads {
    /// Like `read_as`, the file read only where no request before read it (the same file
    /// by its resolved path, under a name of the same extension): then its map is shared, with
    /// `spacing`, and its record names it as `path` gives it, with the content first read.
    pub fn read(
        &mut self,
        path: &Path,
        name: &str,
        spacing: f64,
        param: &'static Spec,
    ) -> Result<(HeightMap, InputFile), RunError> {
        let key = std::fs::canonicalize(path)
            .ok()
            .map(|p| (p, path.extension().map(|e| e.to_ascii_lowercase())));
        if let Some((map, file)) = key.as_ref().and_then(|k| self.read.get(k)) {
            crate::output::file::note_input(path, &param.to_string());
            let map = map
                .with_spacing(spacing, name)
                .map_err(|e| refuse(SPACING, format!("{SPACING}: {e}")))?;
            let record = InputFile {
                parameter: param.name.to_string(),
                path: path.display().to_string(),
                ..file.clone()
            };
            return Ok((map, record));
        }
        let (map, file) = read_as(path, name, spacing, param)?;
        if let Some(key) = key {
            self.read.insert(key, (map.clone(), file.clone()));
        }
        Ok((map, file))
    }
}
