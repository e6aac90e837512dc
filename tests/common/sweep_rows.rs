//! Sweep rows and settings for tests that craft shard files.

use jkrbem::output::sweep_csv::{SweepRow, SweepSettings};

/// A complete row of R1/R2 = `ratio` on grid 32 with |min F̄| = `f_ad_bar`.
pub fn row(ratio: f64, f_ad_bar: f64) -> SweepRow {
    SweepRow {
        grid: 32,
        dx: 0.2,
        wall_s: 0.1,
        ny: 32,
        ..SweepRow::sample(ratio, f_ad_bar)
    }
}

/// The settings of a sweep of `ratios` on grid `grid` (20 steps, c̄0 1.5, margin 0.2).
pub fn settings(ratios: &[f64], grid: usize) -> SweepSettings {
    SweepSettings {
        ratios: ratios.to_vec(),
        grid: Some(grid),
        accuracy: None,
        steps: 20,
        start_radius: 1.5,
        margin: 0.2,
    }
}
