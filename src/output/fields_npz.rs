//! The fields of a run's picked states as a NumPy `.npz` archive that numpy (and any reader
//! of the format) opens without jkrbem: arrays stacked over the states, with the grid's
//! coordinates, and a `metadata` entry (JSON text as bytes) that names each array's unit and
//! says where the fields come from.

use super::OutputError;
use crate::analysis::fields::StateFields;
use ndarray::{Array1, Array2, Array3};
use ndarray_npy::NpzWriter;
use serde_json::{json, Value};
use std::io::Cursor;
use std::path::Path;

/// The archive's arrays, each with its unit: `pressure`, `gap`, `contact` (states, ny, nx),
/// `x` (states, nx) and `y` (states, ny), and one value per state for the rest.
pub const ARRAYS: &[(&str, &str)] = &[
    (
        "pressure",
        "force/length² (compressive positive), shape (states, ny, nx)",
    ),
    (
        "gap",
        "length (h − d + u; 0 on the contact), shape (states, ny, nx)",
    ),
    (
        "contact",
        "bool (true = in contact), shape (states, ny, nx)",
    ),
    (
        "x",
        "length (element centres from the apex along x), shape (states, nx)",
    ),
    (
        "y",
        "length (element centres from the apex along y), shape (states, ny)",
    ),
    (
        "state_index",
        "the state's row in the states CSV (0: the first press)",
    ),
    ("d", "length (the approach)"),
    ("force", "force (compressive positive)"),
    ("dx", "length (the element side)"),
    ("sigma_c", "force/length² (the detachment stress at dx)"),
    ("d_bar", "dimensionless (d·Re/c_r²)"),
    ("f_bar", "dimensionless (F/(3π Re Δγ))"),
    ("c_bar", "dimensionless (√(A/π)/c_r)"),
    (
        "metadata",
        "JSON text as uint8: json.loads(f['metadata'].tobytes())",
    ),
];

/// The archive's bytes for `fields` (all of one run: one grid size), with `about` (what
/// ran, e.g. the scene and the program's version) inside its metadata.
pub fn npz_bytes(fields: &[StateFields], about: Value) -> Result<Vec<u8>, String> {
    let first = fields.first().ok_or("no state's fields to write")?;
    let (nx, ny, k) = (first.nx, first.ny, fields.len());
    if fields.iter().any(|f| f.nx != nx || f.ny != ny) {
        return Err("the states' grids differ".into());
    }
    let stack = |get: &dyn Fn(&StateFields) -> &[f64]| {
        let flat: Vec<f64> = fields.iter().flat_map(|f| get(f).iter().copied()).collect();
        Array3::from_shape_vec((k, ny, nx), flat).map_err(|e| e.to_string())
    };
    let per_state = |get: &dyn Fn(&StateFields) -> f64| {
        Array1::from(fields.iter().map(get).collect::<Vec<f64>>())
    };
    let contact: Vec<bool> = fields
        .iter()
        .flat_map(|f| f.contact.iter().copied())
        .collect();
    let coords = |get: &dyn Fn(&StateFields) -> &[f64], n: usize| {
        let flat: Vec<f64> = fields.iter().flat_map(|f| get(f).iter().copied()).collect();
        Array2::from_shape_vec((k, n), flat).map_err(|e| e.to_string())
    };
    let metadata = json!({
        "format": "jkrbem fields",
        "units": ARRAYS.iter().map(|(n, u)| (n.to_string(), Value::from(*u))).collect::<serde_json::Map<_, _>>(),
        "labels": fields.iter().map(|f| f.label.clone()).collect::<Vec<_>>(),
        "layout": "row-major: array[j, i] is the element at x[i], y[j]",
        "rebuilt": "each state's contact set solved again on the CPU (f64) at its approach",
        "about": about,
    })
    .to_string();
    let mut npz = NpzWriter::new_compressed(Cursor::new(Vec::new()));
    let e = |e: ndarray_npy::WriteNpzError| e.to_string();
    npz.add_array("pressure", &stack(&|f| &f.pressure)?)
        .map_err(e)?;
    npz.add_array("gap", &stack(&|f| &f.gap)?).map_err(e)?;
    let contact = Array3::from_shape_vec((k, ny, nx), contact).map_err(|e| e.to_string())?;
    npz.add_array("contact", &contact).map_err(e)?;
    npz.add_array("x", &coords(&|f| &f.x, nx)?).map_err(e)?;
    npz.add_array("y", &coords(&|f| &f.y, ny)?).map_err(e)?;
    let index: Vec<u64> = fields.iter().map(|f| f.index as u64).collect();
    npz.add_array("state_index", &Array1::from(index))
        .map_err(e)?;
    npz.add_array("d", &per_state(&|f| f.state.d)).map_err(e)?;
    npz.add_array("force", &per_state(&|f| f.state.force))
        .map_err(e)?;
    npz.add_array("dx", &per_state(&|f| f.dx)).map_err(e)?;
    npz.add_array("sigma_c", &per_state(&|f| f.sigma_c))
        .map_err(e)?;
    npz.add_array("d_bar", &per_state(&|f| f.state.d_bar))
        .map_err(e)?;
    npz.add_array("f_bar", &per_state(&|f| f.state.f_bar))
        .map_err(e)?;
    npz.add_array("c_bar", &per_state(&|f| f.state.c_bar))
        .map_err(e)?;
    npz.add_array("metadata", &Array1::from(metadata.into_bytes()))
        .map_err(e)?;
    Ok(npz.finish().map_err(e)?.into_inner())
}

/// Write [`npz_bytes`] to `path` atomically.
pub fn write_npz(path: &Path, fields: &[StateFields], about: Value) -> Result<(), OutputError> {
    let bytes = npz_bytes(fields, about).map_err(|reason| OutputError::Encode {
        path: path.display().to_string(),
        param: None,
        reason,
    })?;
    super::file::write_bytes(path, &bytes)
}
