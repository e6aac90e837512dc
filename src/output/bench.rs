//! The timings of `jkrbem bench`: a CSV with one row per backend and grid, and a log–log
//! chart of time against grid size.

use super::chart::{LogLogChart, Series};
use super::OutputError;
use crate::bench::Measurement;
use serde::Serialize;
use std::path::Path;

/// The CSV header, one column per [`BenchRow`] field.
pub const HEADER: &str = "backend,precision,adapter,grid,nx,ny,convolution_ms,cg_iteration_ms,\
dispatches_per_iteration,readbacks_per_iteration,pulloff_s,pulloff_cg_iterations,f_ad_bar";

/// One backend on one grid. Times are medians of the run's repeats and include one scalar
/// readback each (see [`crate::bench`]); cells left empty were not measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BenchRow {
    /// Backend name ("cpu", "gpu").
    pub backend: String,
    /// Precision of its fields ("f64", "f32").
    pub precision: String,
    /// The device: the CPU model and threads, or the GPU adapter.
    pub adapter: String,
    /// The grid asked for (`--grids`), Nx.
    pub grid: usize,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// One convolution u = K ∗ p (ms).
    pub convolution_ms: f64,
    /// One preconditioned CG iteration, CG's start excluded (ms).
    pub cg_iteration_ms: f64,
    /// Compute dispatches per CG iteration (0 on the CPU).
    pub dispatches_per_iteration: f64,
    /// Blocking readbacks per CG iteration (the residual is read once per timed solve).
    pub readbacks_per_iteration: f64,
    /// Wall time of one whole pull-off (s); empty if not run or if it failed.
    pub pulloff_s: Option<f64>,
    /// CG iterations of that pull-off.
    pub pulloff_cg_iterations: Option<usize>,
    /// Its adhesive force |min F̄| (dimensionless).
    pub f_ad_bar: Option<f64>,
}

impl BenchRow {
    /// The row of measurement `m` made for grid `grid` on `adapter`.
    pub fn new(m: &Measurement, adapter: &str, grid: usize) -> Self {
        let pulloff = m.pulloff.as_ref().filter(|p| p.error.is_none());
        BenchRow {
            backend: m.backend.to_string(),
            precision: m.precision.to_string(),
            adapter: adapter.to_string(),
            grid,
            nx: m.nx,
            ny: m.ny,
            convolution_ms: m.convolution_ms,
            cg_iteration_ms: m.cg_iteration_ms,
            dispatches_per_iteration: m.work_per_iteration.dispatches,
            readbacks_per_iteration: m.work_per_iteration.readbacks,
            pulloff_s: pulloff.map(|p| p.wall_s),
            pulloff_cg_iterations: pulloff.map(|p| p.cg_iterations),
            f_ad_bar: pulloff.and_then(|p| p.f_ad_bar),
        }
    }
}

/// Write `rows` as CSV to `path` (creating its folder), atomically ([`super::file`]).
pub fn write_csv(path: &Path, rows: &[BenchRow]) -> Result<(), OutputError> {
    super::file::write_csv(path, Some(HEADER), rows)
}

/// Time (ms) against grid size Nx on log–log axes: per backend one colour, a solid line for
/// the CG iteration and a dashed one for the convolution.
pub fn timing_chart(rows: &[BenchRow], title: &str) -> LogLogChart {
    let mut chart = LogLogChart::new(title, "grid size Nx (elements along x)", "median time (ms)");
    let mut backends: Vec<(&str, &str)> = Vec::new();
    for r in rows {
        if !backends.contains(&(&r.backend, &r.precision)) {
            backends.push((&r.backend, &r.precision));
        }
    }
    for (color, &(backend, precision)) in backends.iter().enumerate() {
        let of = |f: fn(&BenchRow) -> f64| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|r| r.backend == backend && r.precision == precision)
                .map(|r| (r.nx as f64, f(r)))
                .collect()
        };
        chart.push(Series {
            label: format!("{backend} ({precision}): one CG iteration"),
            points: of(|r| r.cg_iteration_ms),
            color,
            dashed: false,
        });
        chart.push(Series {
            label: format!("{backend} ({precision}): one convolution"),
            points: of(|r| r.convolution_ms),
            color,
            dashed: true,
        });
    }
    chart
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    fn row(backend: &str, nx: usize, pulloff: Option<f64>) -> BenchRow {
        BenchRow {
            backend: backend.into(),
            precision: "f64".into(),
            adapter: "a, with a comma".into(),
            grid: nx,
            nx,
            ny: nx,
            convolution_ms: 0.1,
            cg_iteration_ms: 0.2,
            dispatches_per_iteration: 0.0,
            readbacks_per_iteration: 0.0,
            pulloff_s: pulloff,
            pulloff_cg_iterations: pulloff.map(|_| 10),
            f_ad_bar: pulloff.map(|_| 0.5),
        }
    }

    #[test]
    fn csv_has_the_documented_header_and_empty_cells() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub/bench.csv");
        write_csv(&path, &[row("cpu", 16, Some(1.5)), row("cpu", 32, None)]).unwrap();
        let text = fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], HEADER);
        assert!(lines[1].ends_with(",1.5,10,0.5"), "{}", lines[1]);
        assert!(lines[2].ends_with(",,,"), "{}", lines[2]);
        write_csv(&path, &[]).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap().trim_end(), HEADER);
    }

    #[test]
    fn chart_has_two_series_per_backend() {
        let rows = [
            row("cpu", 16, None),
            row("gpu", 16, None),
            row("cpu", 32, None),
        ];
        let c = timing_chart(&rows, "t");
        assert_eq!(c.series.len(), 4);
        assert_eq!(c.series[0].points, vec![(16.0, 0.2), (32.0, 0.2)]);
        assert_eq!(c.series[3].color, 1);
    }
}
