//! The load path of a height map on a window, which has no closed form to size it: the
//! press's depth from the bearing area of the geometry, the pull-off's range from that depth
//! and from the adhesion of the contact the press makes.

use super::limits::{DEFAULT_PRELOAD_AREA, WINDOW_FINAL_BELOW, WINDOW_PULL_BELOW};
use super::options::Preload;
use super::steps::LoadPath;
use std::f64::consts::PI;

/// How far the pull-off runs past its expected end before it stops, in that expected range
/// below the first touch (dimensionless): as far again as [`LoadPath::new`] goes, and more.
const WINDOW_FINAL_PAST_END: f64 = 3.0;

/// What sizes a window's load path: the heights of the grid's element centres, sorted
/// (length), the window's area in elements, the element side Δx (length), E* (force/length²)
/// and Δγ (force/length).
pub struct WindowGeometry<'a> {
    /// The element centres' heights, ascending (length); at least one.
    pub heights: &'a [f64],
    /// The window's area in elements.
    pub window: usize,
    /// The element side Δx (length).
    pub dx: f64,
    /// The half-space's modulus E* (force/length²).
    pub e_star: f64,
    /// The work of adhesion Δγ (force/length).
    pub work_of_adhesion: f64,
}

/// A window's load path and its loading step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WindowPath {
    /// The pull-off's path: from the default preload's depth d0, in `steps` equal steps to
    /// its expected end (lengths).
    pub load: LoadPath,
    /// The default preload's depth above the first touch (length).
    pub depth: f64,
    /// The loading phase's step (length): the depth's share of the pull-off's steps, so that
    /// the press follows the geometry whatever the adhesion.
    pub loading_step: f64,
}

impl WindowGeometry<'_> {
    /// The approach at which the indenter's height falls below the approach over twice
    /// `area` (elements; the bearing area: an elastic contact covers about half of it),
    /// above the first touch (length; at least the least positive number).
    fn depth_for_area(&self, area: f64) -> f64 {
        let h = self.heights;
        let k = ((2.0 * area) as usize).min(h.len() - 1);
        (h[k] - h[0]).max(f64::MIN_POSITIVE)
    }

    /// The contact area the press to `preload` is expected to make (elements): the fraction
    /// asked for, or half the bearing area at the depth asked for; by force or by default,
    /// [`DEFAULT_PRELOAD_AREA`] of the window.
    fn preload_area(&self, preload: Option<Preload>) -> f64 {
        let window = self.window as f64;
        match preload {
            Some(Preload::AreaFraction(a)) if a > 0.0 && a < 1.0 => a * window,
            Some(Preload::Depth(d)) if d.is_finite() => {
                let bearing = self.heights.partition_point(|&h| h < d) as f64;
                (0.5 * bearing).clamp(1.0, window)
            }
            _ => DEFAULT_PRELOAD_AREA * window,
        }
    }

    /// The approach by which a flat punch of the preload contact's area must be pulled to
    /// come off (length): Kendall's δ = √(2π Δγ a / E*) at the radius a of that area. No
    /// patch of the contact holds on longer than the whole contact pulled as a punch, so
    /// this bounds the adhesive part of the pull-off's range.
    fn adhesive_range(&self, preload: Option<Preload>) -> f64 {
        let radius = (self.preload_area(preload) * self.dx * self.dx / PI).sqrt();
        (2.0 * PI * self.work_of_adhesion * radius / self.e_star).sqrt()
    }

    /// The load path of `steps` steps: pressed to the depth of [`DEFAULT_PRELOAD_AREA`]'s
    /// bearing area, pulled off to [`WINDOW_PULL_BELOW`] of that depth or the adhesive range
    /// below the first touch, whichever is further, and stopped [`WINDOW_FINAL_PAST_END`]
    /// times as far down (at least [`WINDOW_FINAL_BELOW`] depths).
    pub fn path(&self, steps: usize, preload: Option<Preload>) -> WindowPath {
        let d_touch = self.heights[0];
        let depth = self.depth_for_area(DEFAULT_PRELOAD_AREA * self.window as f64);
        let below = (WINDOW_PULL_BELOW * depth).max(self.adhesive_range(preload));
        let steps = steps as f64;
        let load = LoadPath {
            d0: d_touch + depth,
            d_step: (depth + below) / steps,
            d_final: d_touch - (WINDOW_FINAL_PAST_END * below).max(WINDOW_FINAL_BELOW * depth),
            d_end: d_touch - below,
        };
        WindowPath {
            load,
            depth,
            loading_step: depth * (1.0 + WINDOW_PULL_BELOW) / steps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cone-like surface: the heights of `n` elements rising linearly from 0 to 1.
    fn ramp(n: usize) -> Vec<f64> {
        (0..n).map(|i| i as f64 / (n - 1) as f64).collect()
    }

    fn geometry(heights: &[f64], dgamma: f64) -> WindowGeometry<'_> {
        WindowGeometry {
            heights,
            window: heights.len(),
            dx: 0.1,
            e_star: 1.0,
            work_of_adhesion: dgamma,
        }
    }

    #[test]
    fn a_weak_adhesion_keeps_the_geometric_path() {
        let h = ramp(1000);
        let p = geometry(&h, 1e-12).path(100, None);
        // Twice 10 % of 1000 elements: the 200th height.
        assert!((p.depth - 200.0 / 999.0).abs() < 1e-12);
        assert!((p.load.d_end + WINDOW_PULL_BELOW * p.depth).abs() < 1e-12);
        assert!((p.load.d_step - p.loading_step).abs() < 1e-15);
        assert!((p.load.d_final + WINDOW_FINAL_BELOW * p.depth).abs() < 1e-12);
    }

    #[test]
    fn a_strong_adhesion_reaches_kendalls_approach_of_the_preload_contact() {
        let h = ramp(1000);
        let g = geometry(&h, 1.0);
        let p = g.path(100, Some(Preload::AreaFraction(0.2)));
        // 200 elements of 0.01: a = √(2/π); δ = √(2π a).
        let a = (2.0 / PI).sqrt();
        let delta = (2.0 * PI * a).sqrt();
        assert!((p.load.d_end + delta).abs() < 1e-12);
        assert!((p.load.d_step - (p.depth + delta) / 100.0).abs() < 1e-15);
        assert!((p.load.d_final + WINDOW_FINAL_PAST_END * delta).abs() < 1e-12);
        // The press still follows the geometry.
        assert!((p.loading_step - p.depth * 1.5 / 100.0).abs() < 1e-15);
        // A deeper preload makes a larger contact, which holds on longer.
        let deep = g.path(100, Some(Preload::Depth(0.8)));
        assert!(deep.load.d_end < p.load.d_end);
    }
}
