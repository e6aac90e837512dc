//! A generated surface on disk: its heights as a NumPy `.npy` (float64, shape (ny, nx),
//! C order: `a[j, i]` is node `(i, j)`, as [`HeightMap::read`] takes it back) and a JSON
//! sidecar `<name>.json` beside it with the parameters (defaults filled in), the achieved
//! statistics and the generator's version. Both are written atomically
//! ([`super::file`]): an existing file is replaced whole or not at all.

use super::file::write_bytes;
use super::OutputError;
use crate::scene::height_map::HeightMap;
use crate::scene::roughness::{statistics, RoughnessParams, GENERATOR_VERSION};
use ndarray::Array2;
use ndarray_npy::WriteNpyExt;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};

/// The map's heights as the bytes of a `.npy` file: float64, little-endian, shape
/// `(ny, nx)`, C order.
///
/// # Errors
///
/// The encoder's message (none is expected for a valid map).
pub fn npy_bytes(map: &HeightMap) -> Result<Vec<u8>, String> {
    let array = Array2::from_shape_vec((map.ny(), map.nx()), map.heights().to_vec())
        .map_err(|e| e.to_string())?;
    let mut bytes = Vec::new();
    array.write_npy(&mut bytes).map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// The sidecar beside the surface `npy`: its name with the extension `.json`.
pub fn sidecar_path(npy: &Path) -> PathBuf {
    npy.with_extension("json")
}

/// The sidecar's content for `map` generated from `params` and saved as `data` (a file
/// name): the generator's version, the parameters with their defaults filled in, the
/// statistics the map achieves, the layout and the units.
///
/// # Errors
///
/// Those of [`RoughnessParams::resolved`].
pub fn sidecar(
    map: &HeightMap,
    params: &RoughnessParams,
    data: &str,
) -> Result<Value, crate::scene::SceneError> {
    let resolved = params.resolved()?;
    Ok(json!({
        "generator": GENERATOR_VERSION,
        "jkrbem": env!("CARGO_PKG_VERSION"),
        "data": data,
        "layout": "float64, shape (ny, nx), row-major: array[j, i] is node (i, j) at \
                   x = i·spacing, y = j·spacing; periodic over nx·spacing × ny·spacing",
        "units": {
            "heights": "length (the spacing's unit)",
            "spacing": "length",
            "rms_height": "length",
            "rms_slope": "dimensionless (rms of |∇h|, spectral)",
            "rms_curvature": "1/length (rms of ½∇²h, spectral)",
            "rolloff": "length", "cutoff": "length", "largest_wavelength": "length",
        },
        "params": resolved,
        "statistics": statistics(map),
    }))
}

/// Writes `map`, generated from `params`, to `path` as `.npy` and its sidecar to
/// [`sidecar_path`]`(path)`, each atomically, and returns the sidecar's path. The heights
/// are written first: a sidecar never describes a file that was not written.
///
/// # Errors
///
/// [`OutputError`] naming the file that could not be written (or encoded).
pub fn save(
    map: &HeightMap,
    params: &RoughnessParams,
    path: &Path,
) -> Result<PathBuf, OutputError> {
    let encode = |path: &Path, reason: String| OutputError::Encode {
        path: path.display().to_string(),
        param: None,
        reason,
    };
    let json_path = sidecar_path(path);
    let data = path
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let meta = sidecar(map, params, &data).map_err(|e| encode(&json_path, e.to_string()))?;
    let bytes = npy_bytes(map).map_err(|e| encode(path, e))?;
    write_bytes(path, &bytes)?;
    let text =
        serde_json::to_string_pretty(&meta).map_err(|e| encode(&json_path, e.to_string()))?;
    write_bytes(&json_path, format!("{text}\n").as_bytes())?;
    Ok(json_path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::roughness::{generate, Statistics};

    #[test]
    fn the_surface_round_trips_through_npy_and_its_sidecar_says_what_it_is() {
        let params = RoughnessParams {
            grid_y: Some(24),
            seed: 9,
            ..RoughnessParams::with_rms_slope(32, 0.1, 0.6, 0.05)
        };
        let map = generate(&params).unwrap();
        let back = HeightMap::from_npy_bytes(&npy_bytes(&map).unwrap(), 0.1, "surface").unwrap();
        assert_eq!(back, map);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("surface.npy");
        std::fs::write(&path, b"old").unwrap();
        let json_path = save(&map, &params, &path).unwrap();
        assert_eq!(json_path, dir.path().join("surface.json"));
        assert_eq!(HeightMap::read(&path, 0.1).unwrap(), map);
        let meta: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&json_path).unwrap()).unwrap();
        assert_eq!(meta["generator"], GENERATOR_VERSION);
        assert_eq!(meta["data"], "surface.npy");
        let stored: RoughnessParams = serde_json::from_value(meta["params"].clone()).unwrap();
        assert_eq!(stored, params.resolved().unwrap());
        assert_eq!(stored.cutoff, Some(0.4));
        assert_eq!(stored.largest_wavelength, Some(3.2));
        // The stored parameters make the same surface again.
        assert_eq!(generate(&stored).unwrap(), map);
        let achieved: Statistics = serde_json::from_value(meta["statistics"].clone()).unwrap();
        assert!((achieved.rms_slope / 0.05 - 1.0).abs() < 1e-9);
    }
}
