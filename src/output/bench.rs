//! The timings of `jkrbem bench`: a CSV with one row per backend and grid, and a log–log
//! chart of time against grid size.

use super::chart::{LogLogChart, Series};
use super::OutputError;
use crate::bench::{GridProfile, Measurement, PulloffProfile};
use crate::params::ONSETS;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The CSV header, one column per [`BenchRow`] field.
pub const HEADER: &str = "backend,precision,adapter,grid,nx,ny,convolution_ms,cg_iteration_ms,\
dispatches_per_iteration,readbacks_per_iteration,pulloff_s,pulloff_cg_iterations,f_ad_bar,\
pulloff_states,pulloff_steps,pulloff_onsets,pulloff_rounds,pulloff_solves,\
pulloff_convolutions,pulloff_readbacks,pulloff_cg_c_below_070,pulloff_cg_c_070_090,\
pulloff_cg_c_090_110,pulloff_cg_c_above_110,pulloff_cg_whole_steps_to_minimum,\
pulloff_cg_whole_steps_past_minimum,pulloff_cg_search_to_minimum,pulloff_cg_search_past_minimum,\
pulloff_dispatches,pulloff_submits,pulloff_wait_s,pulloff_submit_s";

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
    /// States it recorded.
    pub pulloff_states: Option<usize>,
    /// Load steps it took.
    pub pulloff_steps: Option<usize>,
    /// Detachment onsets it located.
    pub pulloff_onsets: Option<usize>,
    /// Cascade rounds (sweeps that changed the contact set).
    pub pulloff_rounds: Option<usize>,
    /// CG solves.
    pub pulloff_solves: Option<usize>,
    /// Convolutions made outside CG's iterations.
    pub pulloff_convolutions: Option<usize>,
    /// Blocking readbacks (0 on the CPU).
    pub pulloff_readbacks: Option<u64>,
    /// CG iterations done at contacts of c̄ < 0.7 (the c̄ bands of
    /// [`crate::solver::cost::C_BAR_BAND_EDGES`]).
    pub pulloff_cg_c_below_070: Option<usize>,
    /// CG iterations at 0.7 ≤ c̄ < 0.9.
    pub pulloff_cg_c_070_090: Option<usize>,
    /// CG iterations at 0.9 ≤ c̄ < 1.1.
    pub pulloff_cg_c_090_110: Option<usize>,
    /// CG iterations at c̄ ≥ 1.1.
    pub pulloff_cg_c_above_110: Option<usize>,
    /// CG iterations of the load steps taken whole, down to the force minimum.
    pub pulloff_cg_whole_steps_to_minimum: Option<usize>,
    /// The same past the minimum.
    pub pulloff_cg_whole_steps_past_minimum: Option<usize>,
    /// CG iterations of the search near the minimum, down to it.
    pub pulloff_cg_search_to_minimum: Option<usize>,
    /// The same past the minimum.
    pub pulloff_cg_search_past_minimum: Option<usize>,
    /// Compute dispatches of the pull-off (0 on the CPU).
    pub pulloff_dispatches: Option<u64>,
    /// Queue submissions of the pull-off (0 on the CPU).
    pub pulloff_submits: Option<u64>,
    /// Host wall time blocked on the pull-off's readbacks (s; 0 on the CPU).
    pub pulloff_wait_s: Option<f64>,
    /// Host wall time finishing and submitting its command buffers (s; 0 on the CPU).
    pub pulloff_submit_s: Option<f64>,
}

impl BenchRow {
    /// The row of measurement `m` made for grid `grid` on `adapter`.
    pub fn new(m: &Measurement, adapter: &str, grid: usize) -> Self {
        let pulloff = m.pulloff.as_ref().filter(|p| p.error.is_none());
        let band =
            |k: usize| pulloff.and_then(|p| p.cost.bands.get(k).map(|b| b.work.cg_iterations));
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
            pulloff_states: pulloff.map(|p| p.cost.states),
            pulloff_steps: pulloff.map(|p| p.cost.steps),
            pulloff_onsets: pulloff.map(|p| p.cost.onsets),
            pulloff_rounds: pulloff.map(|p| p.cost.work.rounds),
            pulloff_solves: pulloff.map(|p| p.cost.work.solves),
            pulloff_convolutions: pulloff.map(|p| p.cost.work.convolutions),
            pulloff_readbacks: pulloff.map(|p| p.cost.readbacks),
            pulloff_cg_c_below_070: band(0),
            pulloff_cg_c_070_090: band(1),
            pulloff_cg_c_090_110: band(2),
            pulloff_cg_c_above_110: band(3),
            pulloff_cg_whole_steps_to_minimum: pulloff
                .map(|p| p.cost.to_minimum.whole_steps.cg_iterations),
            pulloff_cg_whole_steps_past_minimum: pulloff
                .map(|p| p.cost.past_minimum.whole_steps.cg_iterations),
            pulloff_cg_search_to_minimum: pulloff.map(|p| p.cost.to_minimum.search.cg_iterations),
            pulloff_cg_search_past_minimum: pulloff
                .map(|p| p.cost.past_minimum.search.cg_iterations),
            pulloff_dispatches: pulloff.map(|p| p.host.dispatches),
            pulloff_submits: pulloff.map(|p| p.host.submits),
            pulloff_wait_s: pulloff.map(|p| p.host.wait_ns as f64 * 1e-9),
            pulloff_submit_s: pulloff.map(|p| p.host.submit_ns as f64 * 1e-9),
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
            errors: Vec::new(),
        });
        chart.push(Series {
            label: format!("{backend} ({precision}): one convolution"),
            points: of(|r| r.convolution_ms),
            color,
            dashed: true,
            errors: Vec::new(),
        });
    }
    chart
}

/// An optional value printed with `digits` decimals, or "—".
fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or_else(|| "—".into(), |v| format!("{v:.digits$}"))
}

/// The timings as a table for people: the devices, then one line per backend and grid.
pub fn table_text(rows: &[BenchRow], measured: &[Measurement]) -> String {
    let mut out = String::new();
    let mut devices: Vec<(&str, &str)> = Vec::new();
    for r in rows {
        if !devices.iter().any(|(b, _)| *b == r.backend) {
            devices.push((&r.backend, &r.adapter));
        }
    }
    for (b, a) in devices {
        let _ = writeln!(out, "{b}: {a}");
    }
    if let Some(m) = measured.first() {
        let _ = writeln!(
        out,
            "medians of {} samples (each the mean over ≥ 20 ms of calls); every call ends with one \
             scalar readback; CG: {} iterations per solve, its start excluded",
            m.repeats, m.cg_iterations
        );
    }
    let _ = writeln!(
        out,
        "{:<8} {:>9} {:>10} {:>10} {:>8} {:>8} {:>8} {:>11} {:>8} {:>8}",
        "backend",
        "grid",
        "conv (ms)",
        "CG it (ms)",
        "disp/it",
        "read/it",
        "subm/it",
        "pull-off(s)",
        "CG its",
        "f_ad_bar"
    );
    for (r, m) in rows.iter().zip(measured) {
        let w = m.work_per_iteration;
        let _ = writeln!(
            out,
            "{:<8} {:>9} {:>10.4} {:>10.4} {:>8.2} {:>8.3} {:>8.2} {:>11} {:>8} {:>8}",
            format!("{} {}", r.backend, r.precision),
            format!("{}×{}", r.nx, r.ny),
            r.convolution_ms,
            r.cg_iteration_ms,
            w.dispatches,
            w.readbacks,
            w.submits,
            opt(r.pulloff_s, 2),
            r.pulloff_cg_iterations
                .map_or_else(|| "—".into(), |n| n.to_string()),
            opt(r.f_ad_bar, 4),
        );
    }
    out
}

/// The pull-offs' cost accounts as a table: per backend and grid, the states, steps,
/// onsets, cascade rounds, solves, CG iterations and convolutions outside CG, and the growth
/// of the solves and CG iterations from the grid before (×, per doubling of Nx). Empty if no
/// pull-off was timed.
pub fn cost_text(rows: &[BenchRow]) -> String {
    let mut out = String::new();
    let timed: Vec<&BenchRow> = rows.iter().filter(|r| r.pulloff_steps.is_some()).collect();
    if timed.is_empty() {
        return out;
    }
    let _ = writeln!(
        out,
        "pull-off cost account ({ONSETS} near-minimum):\n{:<8} {:>9} {:>7} {:>6} \
         {:>7} {:>7} {:>7} {:>8} {:>7} {:>9} {:>9}",
        "backend",
        "grid",
        "states",
        "steps",
        "onsets",
        "rounds",
        "solves",
        "CG its",
        "conv",
        "×solves",
        "×CG its"
    );
    let n = |v: Option<usize>| v.map_or_else(|| "—".into(), |n| n.to_string());
    for (i, r) in timed.iter().enumerate() {
        let before = timed[..i]
            .iter()
            .rev()
            .find(|b| b.backend == r.backend && b.precision == r.precision && b.nx * 2 == r.nx);
        let growth = |f: fn(&BenchRow) -> Option<usize>| match (before.and_then(|b| f(b)), f(r)) {
            (Some(a), Some(b)) if a > 0 => format!("{:.2}", b as f64 / a as f64),
            _ => "—".into(),
        };
        let _ = writeln!(
            out,
            "{:<8} {:>9} {:>7} {:>6} {:>7} {:>7} {:>7} {:>8} {:>7} {:>9} {:>9}",
            format!("{} {}", r.backend, r.precision),
            format!("{}×{}", r.nx, r.ny),
            n(r.pulloff_states),
            n(r.pulloff_steps),
            n(r.pulloff_onsets),
            n(r.pulloff_rounds),
            n(r.pulloff_solves),
            n(r.pulloff_cg_iterations),
            n(r.pulloff_convolutions),
            growth(|r| r.pulloff_solves),
            growth(|r| r.pulloff_cg_iterations),
        );
    }
    out.push_str(&band_text(&timed));
    out
}

/// The pull-offs' CG iterations per c̄ band and by activity on either side of the force
/// minimum (whole steps, the search near the minimum), each with its growth from the grid
/// before (× per doubling of Nx).
fn band_text(timed: &[&BenchRow]) -> String {
    type Column = (&'static str, fn(&BenchRow) -> Option<usize>);
    let columns: [Column; 8] = [
        ("c̄<0.7", |r| r.pulloff_cg_c_below_070),
        ("0.7–0.9", |r| r.pulloff_cg_c_070_090),
        ("0.9–1.1", |r| r.pulloff_cg_c_090_110),
        ("c̄≥1.1", |r| r.pulloff_cg_c_above_110),
        ("steps≤min", |r| r.pulloff_cg_whole_steps_to_minimum),
        ("steps>min", |r| r.pulloff_cg_whole_steps_past_minimum),
        ("search≤min", |r| r.pulloff_cg_search_to_minimum),
        ("search>min", |r| r.pulloff_cg_search_past_minimum),
    ];
    let mut out = String::from(
        "CG iterations per c̄ band (where the work was done) and by activity (≤min: down to the \
         force minimum, >min: past it), ×: growth from the grid before:\n",
    );
    let _ = write!(out, "{:<8} {:>9}", "backend", "grid");
    for (name, _) in &columns {
        let _ = write!(out, " {name:>15}");
    }
    out.push('\n');
    for (i, r) in timed.iter().enumerate() {
        let before = timed[..i]
            .iter()
            .rev()
            .find(|b| b.backend == r.backend && b.precision == r.precision && b.nx * 2 == r.nx);
        let _ = write!(
            out,
            "{:<8} {:>9}",
            format!("{} {}", r.backend, r.precision),
            format!("{}×{}", r.nx, r.ny)
        );
        for (_, f) in &columns {
            let cell = match (f(r), before.and_then(|b| f(b))) {
                (Some(n), Some(a)) if a > 0 => format!("{n} ×{:.2}", n as f64 / a as f64),
                (Some(n), _) => n.to_string(),
                (None, _) => "—".into(),
            };
            let _ = write!(out, " {cell:>15}");
        }
        out.push('\n');
    }
    out
}

/// One grid's kernel profile: time, bytes and bandwidth per CG iteration, and the kernels'
/// bytes against the iteration's floor.
pub fn profile_text(p: &GridProfile) -> String {
    let mut out = String::new();
    let (label, profile, floor) = (&p.label, &p.kernels, p.floor_bytes);
    let time: f64 = profile.iter().map(|k| k.ms_per_iteration).sum();
    let bytes: f64 = profile.iter().map(|k| k.bytes_per_iteration).sum();
    let _ = writeln!(
        out,
        "profile {label}, per CG iteration (GPU timestamps around each dispatch):"
    );
    let _ = writeln!(
        out,
        "  {:<18} {:>8} {:>10} {:>10} {:>9} {:>7}",
        "kernel", "disp/it", "ms/it", "MB/it", "GB/s", "share"
    );
    for k in profile {
        let _ = writeln!(
            out,
            "  {:<18} {:>8.2} {:>10.4} {:>10.2} {:>9.0} {:>6.1}%",
            k.kernel,
            k.dispatches_per_iteration,
            k.ms_per_iteration,
            k.bytes_per_iteration / 1e6,
            k.gb_per_s(),
            100.0 * k.ms_per_iteration / time.max(f64::MIN_POSITIVE)
        );
    }
    let _ = writeln!(
        out,
        "  kernels: {time:.4} ms, {:.1} MB ({:.2}× the floor of {:.1} MB), {:.0} GB/s overall",
        bytes / 1e6,
        bytes / floor,
        floor / 1e6,
        bytes / (time * 1e-3).max(f64::MIN_POSITIVE) / 1e9
    );
    out
}

/// A whole pull-off's profile: where its wall time went (the host blocked on readbacks, the
/// host submitting, the rest of the host's work) and the GPU's time per kernel.
pub fn pulloff_profile_text(p: &PulloffProfile) -> String {
    let mut out = String::new();
    let h = &p.host;
    let wait = h.wait_ns as f64 * 1e-9;
    let submit = h.submit_ns as f64 * 1e-9;
    let kernels = p.kernel_s();
    let per = |n: u64| if n > 0 { 1e6 * wait / n as f64 } else { 0.0 };
    let pct = |x: f64| 100.0 * x / p.wall_s.max(f64::MIN_POSITIVE);
    let _ = writeln!(
        out,
        "whole pull-off profile {}: {:.2} s wall, {} CG iterations, {} cascade rounds, \
         {} dispatches, {} submissions, {} readbacks ({:.1} per round)",
        p.label,
        p.wall_s,
        p.cg_iterations,
        p.rounds,
        h.dispatches,
        h.submits,
        h.readbacks,
        h.readbacks as f64 / (p.rounds.max(1)) as f64
    );
    let _ = writeln!(
        out,
        "  host blocked on readbacks {wait:.2} s ({:.0} %, {:.0} µs each); submitting {submit:.2} s \
         ({:.0} %); the rest of the host's work {:.2} s ({:.0} %)",
        pct(wait),
        per(h.readbacks),
        pct(submit),
        (p.wall_s - wait - submit).max(0.0),
        pct((p.wall_s - wait - submit).max(0.0))
    );
    let _ = writeln!(
        out,
        "  GPU kernels {kernels:.2} s ({:.0} % of the unprofiled wall; profiled run {:.2} s): \
         the GPU idles {:.2} s",
        pct(kernels),
        p.profiled_wall_s,
        (p.wall_s - kernels).max(0.0)
    );
    let _ = writeln!(
        out,
        "  {:<22} {:>10} {:>10} {:>9} {:>9} {:>7}",
        "kernel", "dispatches", "GPU s", "µs each", "GB/s", "share"
    );
    for k in &p.kernels {
        let _ = writeln!(
            out,
            "  {:<22} {:>10} {:>10.4} {:>9.2} {:>9.0} {:>6.1}%",
            k.kernel,
            k.dispatches,
            k.seconds,
            1e6 * k.seconds / k.dispatches.max(1) as f64,
            if k.seconds > 0.0 {
                k.bytes as f64 / k.seconds / 1e9
            } else {
                0.0
            },
            100.0 * k.seconds / kernels.max(f64::MIN_POSITIVE)
        );
    }
    out
}

/// GPU/CPU time ratios per grid, when both ran in this invocation (empty otherwise).
pub fn ratios_text(rows: &[BenchRow]) -> String {
    let mut out = String::new();
    let find = |b: &str, g: usize| rows.iter().find(|r| r.backend == b && r.grid == g);
    let mut header = false;
    for r in rows.iter().filter(|r| r.backend == "cpu") {
        let Some(gpu) = find("gpu", r.grid) else {
            continue;
        };
        if !header {
            let _ = writeln!(
                out,
                "GPU/CPU time ratios (below 1: the GPU is faster), measured in this run:"
            );
            let _ = writeln!(
                out,
                "{:>9} {:>12} {:>13} {:>9}",
                "grid", "convolution", "CG iteration", "pull-off"
            );
            header = true;
        }
        let pulloff = gpu.pulloff_s.zip(r.pulloff_s).map(|(g, c)| g / c);
        let _ = writeln!(
            out,
            "{:>9} {:>12.3} {:>13.3} {:>9}",
            format!("{}×{}", r.nx, r.ny),
            gpu.convolution_ms / r.convolution_ms,
            gpu.cg_iteration_ms / r.cg_iteration_ms,
            opt(pulloff, 3),
        );
    }
    out
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
            pulloff_states: pulloff.map(|_| 5),
            pulloff_steps: pulloff.map(|_| 4),
            pulloff_onsets: pulloff.map(|_| 1),
            pulloff_rounds: pulloff.map(|_| 2),
            pulloff_solves: pulloff.map(|_| 6),
            pulloff_convolutions: pulloff.map(|_| 7),
            pulloff_readbacks: pulloff.map(|_| 0),
            pulloff_cg_c_below_070: pulloff.map(|_| 1),
            pulloff_cg_c_070_090: pulloff.map(|_| 5),
            pulloff_cg_c_090_110: pulloff.map(|_| 2),
            pulloff_cg_c_above_110: pulloff.map(|_| 2),
            pulloff_cg_whole_steps_to_minimum: pulloff.map(|_| 4),
            pulloff_cg_whole_steps_past_minimum: pulloff.map(|_| 1),
            pulloff_cg_search_to_minimum: pulloff.map(|_| 3),
            pulloff_cg_search_past_minimum: pulloff.map(|_| 2),
            pulloff_dispatches: pulloff.map(|_| 0),
            pulloff_submits: pulloff.map(|_| 0),
            pulloff_wait_s: pulloff.map(|_| 0.0),
            pulloff_submit_s: pulloff.map(|_| 0.0),
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
        assert!(
            lines[1].ends_with(",1.5,10,0.5,5,4,1,2,6,7,0,1,5,2,2,4,1,3,2,0,0,0.0,0.0"),
            "{}",
            lines[1]
        );
        assert!(lines[2].ends_with(",,,,,,,,,,,,,,,,,,,,,,"), "{}", lines[2]);
        write_csv(&path, &[]).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap().trim_end(), HEADER);
    }

    #[test]
    fn the_band_columns_are_named_by_the_accounts_band_edges() {
        // pulloff_cg_c_below_070 … pulloff_cg_c_above_110: one column per band of the account.
        assert_eq!(crate::solver::cost::C_BAR_BAND_EDGES, [0.7, 0.9, 1.1]);
        let bands: Vec<&str> = HEADER
            .split(',')
            .filter(|c| c.starts_with("pulloff_cg_c_"))
            .collect();
        assert_eq!(bands.len(), crate::solver::cost::C_BAR_BAND_EDGES.len() + 1);
    }

    #[test]
    fn cost_table_gives_the_growth_per_doubling() {
        let mut a = row("cpu", 16, Some(1.0));
        let mut b = row("cpu", 32, Some(2.0));
        a.pulloff_cg_iterations = Some(100);
        b.pulloff_cg_iterations = Some(250);
        b.pulloff_cg_search_past_minimum = Some(8);
        let t = cost_text(&[a, b, row("cpu", 64, None)]);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines.len(), 8, "{t}");
        assert!(lines[2].ends_with("—         —"), "{t}");
        assert!(lines[3].ends_with("1.00      2.50"), "{t}");
        // Per band and activity: the growth of each from the grid before.
        assert!(lines[4].starts_with("CG iterations per c̄ band"), "{t}");
        assert!(lines[6].trim_end().ends_with(" 2"), "{t}");
        assert!(lines[7].trim_end().ends_with("8 ×4.00"), "{t}");
        assert!(cost_text(&[row("cpu", 16, None)]).is_empty());
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
