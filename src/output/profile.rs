//! The per-kernel profile of `jkrbem bench --profile`: one CSV row per grid and kernel.

use super::OutputError;
use crate::bench::KernelProfile;
use serde::Serialize;
use std::path::Path;

/// The CSV header, one column per [`ProfileRow`] field.
pub const HEADER: &str = "grid,nx,ny,kernel,dispatches_per_iteration,ms_per_iteration,\
bytes_per_iteration,gb_per_s,share_of_iteration";

/// One kernel on one grid, per preconditioned CG iteration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileRow {
    /// The grid asked for (`--grids`), Nx.
    pub grid: usize,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// The kernel (WGSL entry point).
    pub kernel: String,
    /// Its dispatches per CG iteration.
    pub dispatches_per_iteration: f64,
    /// Its GPU time per CG iteration, between its dispatches' timestamps (ms).
    pub ms_per_iteration: f64,
    /// Bytes it reads and writes per CG iteration, counted from its code.
    pub bytes_per_iteration: f64,
    /// Achieved bandwidth (1e9 bytes/s).
    pub gb_per_s: f64,
    /// Its share of the kernels' summed time per iteration (0…1).
    pub share_of_iteration: f64,
}

/// The rows of one grid's profile.
pub fn rows(grid: usize, nx: usize, ny: usize, profile: &[KernelProfile]) -> Vec<ProfileRow> {
    let total: f64 = profile.iter().map(|k| k.ms_per_iteration).sum();
    profile
        .iter()
        .map(|k| ProfileRow {
            grid,
            nx,
            ny,
            kernel: k.kernel.to_string(),
            dispatches_per_iteration: k.dispatches_per_iteration,
            ms_per_iteration: k.ms_per_iteration,
            bytes_per_iteration: k.bytes_per_iteration,
            gb_per_s: k.gb_per_s(),
            share_of_iteration: if total > 0.0 {
                k.ms_per_iteration / total
            } else {
                0.0
            },
        })
        .collect()
}

/// Write `rows` as CSV to `path` (creating its folder), atomically.
pub fn write_csv(path: &Path, rows: &[ProfileRow]) -> Result<(), OutputError> {
    super::file::write_csv(path, Some(HEADER), rows)
}
