//! The per-kernel profile of `jkrbem bench --profile`: one CSV row per grid and kernel.

use super::OutputError;
use crate::bench::{KernelProfile, PulloffProfile};
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

/// The CSV header of a whole pull-off's profile, one column per [`PulloffProfileRow`] field.
pub const PULLOFF_HEADER: &str = "label,kernel,dispatches,gpu_s,bytes,gb_per_s,share_of_kernels";

/// One kernel over a whole pull-off; the rows "(wall)", "(readback wait)", "(submit)" and
/// "(profiled wall)" hold the run's host times in `gpu_s` (s) and their counts in
/// `dispatches`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PulloffProfileRow {
    /// "--backends gpu 2048×1024".
    pub label: String,
    /// The kernel (WGSL entry point), or a host time in parentheses.
    pub kernel: String,
    /// Its dispatches (readbacks, submissions for the host rows).
    pub dispatches: u64,
    /// Its GPU time over the pull-off (s); the host time for the host rows.
    pub gpu_s: f64,
    /// Bytes it read and wrote, counted from its code.
    pub bytes: u64,
    /// Achieved bandwidth (1e9 bytes/s).
    pub gb_per_s: f64,
    /// Its share of the kernels' summed time (0…1; empty meaning 0 for host rows).
    pub share_of_kernels: f64,
}

/// The rows of one pull-off's profile: the host's times first, then each kernel.
pub fn pulloff_rows(p: &PulloffProfile) -> Vec<PulloffProfileRow> {
    let total = p.kernel_s();
    let host = |kernel: &str, count: u64, s: f64| PulloffProfileRow {
        label: p.label.clone(),
        kernel: kernel.to_string(),
        dispatches: count,
        gpu_s: s,
        bytes: 0,
        gb_per_s: 0.0,
        share_of_kernels: 0.0,
    };
    let mut rows = vec![
        host("(wall)", p.host.dispatches, p.wall_s),
        host(
            "(readback wait)",
            p.host.readbacks,
            p.host.wait_ns as f64 * 1e-9,
        ),
        host("(submit)", p.host.submits, p.host.submit_ns as f64 * 1e-9),
        host("(profiled wall)", 0, p.profiled_wall_s),
    ];
    rows.extend(p.kernels.iter().map(|k| PulloffProfileRow {
        label: p.label.clone(),
        kernel: k.kernel.to_string(),
        dispatches: k.dispatches,
        gpu_s: k.seconds,
        bytes: k.bytes,
        gb_per_s: if k.seconds > 0.0 {
            k.bytes as f64 / k.seconds / 1e9
        } else {
            0.0
        },
        share_of_kernels: if total > 0.0 { k.seconds / total } else { 0.0 },
    }));
    rows
}

/// Write a whole pull-off's profile rows as CSV to `path`, atomically.
pub fn write_pulloff_csv(path: &Path, rows: &[PulloffProfileRow]) -> Result<(), OutputError> {
    super::file::write_csv(path, Some(PULLOFF_HEADER), rows)
}
