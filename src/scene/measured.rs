//! A measured topography as an indenter: a [`HeightMap`] of any shape, placed in one of two
//! ways ([`Placement`]).
//!
//! - **At its apex**, where the map is convex about its lowest node (a quadratic fitted
//!   there has a minimum): the fit's stationary point is the origin and its principal radii
//!   size the domain (the first contact of c̄0 and its margin) and normalise the results as
//!   an ellipsoid's.
//! - **On a window**: the domain is a rectangle of the map (the user's, else the whole map),
//!   its centre the origin. Any surface runs so: several patches, no apex, non-convex. It is
//!   pressed on from its first touch. The results are normalised by the apex fit's radii
//!   where the map is convex about its lowest node, else not at all (the user's units).
//! - **On its period** ([`MeasuredSurface::on_period`], for the periodic convolution): the map
//!   is one period of a surface periodic along both axes, n × m nodes at spacing s: its
//!   period is n·s × m·s (node n wraps onto node 0), not the nodes' hull (n − 1)·s × (m − 1)·s,
//!   and the heights between the last node and the first are interpolated across that seam.
//!   The domain is the whole period (a window given must be one). A map whose seam jumps by
//!   far more than its steps between neighbouring nodes (`SEAM_STEP_LIMIT`) is not periodic
//!   and is refused.
//!
//! Heights are measured from the map's lowest node (so a height map's approach d is too)
//! and interpolated bilinearly between nodes: the surface the solver sees is the same
//! continuous one on every grid, so its grids converge to the limit of that surface, and a
//! grid finer than the map's spacing resolves every facet of it.

use super::height_map::HeightMap;
use super::indenter::{ellipsoid_hint, ellipsoid_scales, FirstContact, IndenterShape, PullOffHint};
use super::{Scales, SceneError};
use crate::params::{Spec, CONVOLUTION, HEIGHT_MAP, WINDOW_X, WINDOW_Y};
use crate::text::compact;
use crate::theory::hertz::hertz_for_mean_radius;

/// The fit around the lowest node takes the nodes within this fraction of the map's smaller
/// half-width (dimensionless), and at least [`MIN_FIT_NODES`] spacings.
pub const FIT_FRACTION: f64 = 0.25;

/// The smallest fit radius, in map spacings (dimensionless).
pub const MIN_FIT_NODES: f64 = 3.0;

/// Height of the domain's part outside a window, above the map's highest node, in the
/// window's size plus the map's height range (dimensionless): far beyond any gap the
/// half-space can close there, so that nothing outside the window ever touches.
pub const OUTSIDE_WALL: f64 = 1e3;

/// A map given for the periodic convolution is taken as periodic where, along each axis, the
/// rms jump across its seam (from its last node back to its first, one per row or column) is
/// at most this many times the rms of its steps between neighbouring nodes along that axis
/// (dimensionless). For one period of a stationary surface the seam's steps are drawn from
/// the same distribution as the others (their rms ratio is about 1): a sampled sinusoid of a
/// whole number of wavelengths has at most √2 (its seam at the steepest slope); for a Gaussian
/// random surface the rms of the m ≥ 4 seam steps exceeds 3 times the steps' with
/// probability below 3e-7 (χ²₄ > 36). A map cut from a surface that is not periodic there
/// (a tilt, a cap, a wave of a fractional number of wavelengths) jumps by about its height
/// range, many of its steps.
pub const SEAM_STEP_LIMIT: f64 = 3.0;

/// Relative slack (of the period, dimensionless) within which a window given under the
/// periodic convolution is the map's period.
const PERIOD_SLACK: f64 = 1e-9;

/// A map's apex: its position in the map's coordinates (length), its fitted height from the
/// map's minimum (length) and the fit's principal radii (length).
type Apex = ((f64, f64), f64, (f64, f64));

/// How a map is placed against the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Placement {
    /// The apex (the fit's stationary point) at the origin; the domain is sized from the
    /// first contact about it.
    Apex,
    /// The domain is this rectangle of the map, its centre the origin.
    Window {
        /// The window's centre in the map's coordinates (length).
        centre: (f64, f64),
        /// The window's half-widths along x and y (length).
        half: (f64, f64),
    },
}

/// A height map placed as an indenter.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSurface {
    /// The map (heights in the user's length unit; coordinates centred on the map).
    pub map: HeightMap,
    /// Where it was read from, for reports.
    pub source: String,
    /// The origin in the map's coordinates (length): the apex, or the window's centre.
    pub apex: (f64, f64),
    /// The height at the origin, measured from the map's lowest node (length): the fitted
    /// height at an apex, 0 on a window (whose heights are the map's own, from its lowest
    /// node).
    pub apex_height: f64,
    /// The principal radii of curvature (R1 ≥ R2, length) of the quadratic fitted about the
    /// lowest node, where the map is convex there: they normalise the results. `None`: the
    /// results are in the user's units.
    pub radii: Option<(f64, f64)>,
    /// How the map is placed.
    pub placement: Placement,
    /// The height of the domain outside a window (length: a thousand times the map's height range and size).
    wall: f64,
    /// Whether the map is one period of a periodic surface, its window that period
    /// ([`MeasuredSurface::on_period`]): heights wrap across its seam, and no wall stands.
    periodic: bool,
}

impl MeasuredSurface {
    /// Place `map` (read from `source`) at its apex where it is convex about its lowest
    /// node, else on the whole map.
    pub fn new(map: HeightMap, source: &str) -> Result<Self, SceneError> {
        match Self::apex_of(&map) {
            Some((apex, apex_height, radii)) => Ok(MeasuredSurface {
                apex,
                apex_height,
                radii: Some(radii),
                source: source.to_string(),
                placement: Placement::Apex,
                wall: wall_of(&map),
                periodic: false,
                map,
            }),
            None => Ok(Self::whole(map, source, None)),
        }
    }

    /// Place `map` on the window `x`, `y` (x0,x1 and y0,y1 in the map's coordinates,
    /// length; `None`: the map's whole extent along that axis). Refused (naming the window's
    /// parameter) where the window is empty or reaches beyond the map.
    pub fn on_window(
        map: HeightMap,
        source: &str,
        x: Option<[f64; 2]>,
        y: Option<[f64; 2]>,
    ) -> Result<Self, SceneError> {
        let (ex, ey) = map.extent();
        let side = |given: Option<[f64; 2]>, e: f64, param| match given {
            None => Ok((0.0, e)),
            Some([a, b]) if a < b && a >= -e * (1.0 + 1e-12) && b <= e * (1.0 + 1e-12) => {
                Ok((0.5 * (a + b), 0.5 * (b - a)))
            }
            Some([a, b]) => Err(SceneError::Refused {
                param,
                why: format!(
                    "{}, {} is not a window of {source}: give x0 < x1 within ±{} (the map's \
                     coordinates are centred on it)",
                    compact(a),
                    compact(b),
                    compact(e)
                ),
            }),
        };
        let (cx, hx) = side(x, ex, WINDOW_X)?;
        let (cy, hy) = side(y, ey, WINDOW_Y)?;
        let radii = Self::apex_of(&map).map(|a| a.2);
        let mut s = Self::whole(map, source, radii);
        s.apex = (cx, cy);
        s.placement = Placement::Window {
            centre: (cx, cy),
            half: (hx, hy),
        };
        Ok(s)
    }

    /// Place `map` (read from `source`) as one period of a surface periodic along both axes,
    /// for the periodic convolution: n × m nodes at spacing s are a period of n·s × m·s (the
    /// node beyond the last wraps onto the first, and the heights between them are
    /// interpolated across the seam), the domain is that whole period. `x`, `y` (x0,x1 and
    /// y0,y1 in the map's centred coordinates, length; `None`: the period centred on the map)
    /// may move the period's origin but must span the period. Refused, naming the map's
    /// parameter, where the map is not periodic (`SEAM_STEP_LIMIT`), and naming the
    /// window's where a window given is not one period long.
    pub fn on_period(
        map: HeightMap,
        source: &str,
        x: Option<[f64; 2]>,
        y: Option<[f64; 2]>,
    ) -> Result<Self, SceneError> {
        check_periodic(&map, source)?;
        let s = map.spacing();
        let side = |given: Option<[f64; 2]>, n: usize, param: &'static Spec, axis: &str| {
            let period = n as f64 * s;
            match given {
                None => Ok((0.0, 0.5 * period)),
                Some([a, b]) if a < b && ((b - a) - period).abs() <= PERIOD_SLACK * period => {
                    Ok((0.5 * (a + b), 0.5 * period))
                }
                Some([a, b]) => Err(SceneError::Refused {
                    param,
                    why: format!(
                        "{}, {} is not a period of {source}: under {CONVOLUTION} periodic the \
                         domain is the map's whole period, its {n} nodes along {axis} at \
                         spacing {} spanning {} (the node after the last wraps onto the \
                         first): give a window {} long, e.g. {},{}, or leave it out (a part of \
                         a map runs with {CONVOLUTION} padded)",
                        compact(a),
                        compact(b),
                        compact(s),
                        compact(period),
                        compact(period),
                        compact(-0.5 * period),
                        compact(0.5 * period),
                    ),
                }),
            }
        };
        let (cx, hx) = side(x, map.nx(), WINDOW_X, "x")?;
        let (cy, hy) = side(y, map.ny(), WINDOW_Y, "y")?;
        let radii = Self::apex_of(&map).map(|a| a.2);
        let mut surface = Self::whole(map, source, radii);
        surface.apex = (cx, cy);
        surface.placement = Placement::Window {
            centre: (cx, cy),
            half: (hx, hy),
        };
        surface.periodic = true;
        Ok(surface)
    }

    /// Whether the map is one period of a periodic surface ([`MeasuredSurface::on_period`]).
    pub fn is_periodic(&self) -> bool {
        self.periodic
    }

    /// The map's period along x and y (length): its nodes times its spacing.
    pub fn period(&self) -> (f64, f64) {
        let s = self.map.spacing();
        (self.map.nx() as f64 * s, self.map.ny() as f64 * s)
    }

    /// The same map on its whole extent (the placement a map at its apex falls back on when
    /// the first contact does not fit in it), keeping its normalisation.
    pub fn on_whole_map(&self) -> Self {
        Self::whole(self.map.clone(), &self.source, self.radii)
    }

    fn whole(map: HeightMap, source: &str, radii: Option<(f64, f64)>) -> Self {
        let half = map.extent();
        MeasuredSurface {
            apex: (0.0, 0.0),
            apex_height: 0.0,
            radii,
            source: source.to_string(),
            placement: Placement::Window {
                centre: (0.0, 0.0),
                half,
            },
            wall: wall_of(&map),
            periodic: false,
            map,
        }
    }

    /// The apex of a map convex about its lowest node: fit h ≈ c0 + g·x + ½ xᵀ K x around
    /// it, take the fit's stationary point (the lowest node if that point lies outside the
    /// fit's disc); with the fitted height there (from the map's minimum) and the principal
    /// radii. `None` where no convex quadratic fits.
    fn apex_of(map: &HeightMap) -> Option<Apex> {
        let (ex, ey) = map.extent();
        let radius = (FIT_FRACTION * ex.min(ey)).max(MIN_FIT_NODES * map.spacing());
        let fit = map.curvature_fit(radius)?;
        let radii = fit.principal_radii()?;
        // A valley or a ridge (a wave extruded along one axis: one radius round-off large)
        // has no apex; past the ellipsoid's largest ratio no contact of its normalisation is
        // meant.
        if !explains(map, &fit, radius) || radii.0 / radii.1 > super::MAX_RATIO {
            return None;
        }
        // Stationary point of the fit: K s = −g, relative to the lowest node.
        let det = fit.kxx * fit.kyy - fit.kxy * fit.kxy;
        let sx = (-fit.gx * fit.kyy + fit.gy * fit.kxy) / det;
        let sy = (-fit.gy * fit.kxx + fit.gx * fit.kxy) / det;
        let (lx, ly) = map.lowest_point();
        let (sx, sy) = if sx.hypot(sy) <= radius {
            (sx, sy)
        } else {
            (0.0, 0.0)
        };
        let fitted = fit.c0
            + fit.gx * sx
            + fit.gy * sy
            + 0.5 * (fit.kxx * sx * sx + fit.kyy * sy * sy)
            + fit.kxy * sx * sy;
        Some(((lx + sx, ly + sy), fitted - map.min_height(), radii))
    }

    /// Whether the map sits on a window (not at its apex).
    pub fn on_window_placed(&self) -> bool {
        matches!(self.placement, Placement::Window { .. })
    }

    /// The window's half-widths (length), if the map sits on one.
    pub fn window_half(&self) -> Option<(f64, f64)> {
        match self.placement {
            Placement::Window { half, .. } => Some(half),
            Placement::Apex => None,
        }
    }

    /// Height (length) at (x, y) (length) from the origin; `None` outside the map. On a
    /// window, the domain's part outside it stands a wall far above the map:
    /// nothing there touches. On its period, the map repeats: every (x, y) has a height.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        if self.periodic {
            return sample_periodic(&self.map, self.apex.0 + x, self.apex.1 + y);
        }
        if let Placement::Window { half, .. } = self.placement {
            let slack = 1e-9 * self.map.spacing();
            if x.abs() > half.0 + slack || y.abs() > half.1 + slack {
                return Some(self.wall);
            }
        }
        self.map
            .sample(self.apex.0 + x, self.apex.1 + y)
            .map(|h| h - self.apex_height)
    }

    /// Whether the map covers the rectangle |x| ≤ `half_x`, |y| ≤ `half_y` (length) about
    /// the origin (a window covers all of it: beyond the window stands its wall).
    pub fn covers(&self, half_x: f64, half_y: f64) -> bool {
        if self.on_window_placed() {
            return true;
        }
        let (ex, ey) = self.map.extent();
        self.apex.0.abs() + half_x <= ex && self.apex.1.abs() + half_y <= ey
    }

    /// The map in words.
    pub fn describe(&self) -> String {
        let placed = match (self.placement, self.radii) {
            (Placement::Apex, Some((r1, r2))) => {
                format!("apex radii {}, {}", compact(r1), compact(r2))
            }
            (Placement::Window { centre, half }, radii) => format!(
                "{}domain x {}…{}, y {}…{}; {}",
                if self.periodic {
                    "periodic, one period the "
                } else {
                    ""
                },
                compact(centre.0 - half.0),
                compact(centre.0 + half.0),
                compact(centre.1 - half.1),
                compact(centre.1 + half.1),
                match radii {
                    Some((r1, r2)) => format!(
                        "normalised by the apex radii {}, {}",
                        compact(r1),
                        compact(r2)
                    ),
                    None => "not normalised: values in the user's units".to_string(),
                }
            ),
            (Placement::Apex, None) => "at its lowest node".to_string(),
        };
        format!(
            "height map {} ({}×{}, spacing {}; {placed})",
            self.source,
            self.map.nx(),
            self.map.ny(),
            compact(self.map.spacing()),
        )
    }
}

/// The share of the heights' variance about their mean within `radius` of the lowest node
/// that a quadratic fit must explain for the map to have an apex (dimensionless): a smooth
/// tip with roughness on it passes, a nominally flat rough surface (whose lowest node is one
/// asperity among many) does not.
const APEX_FIT_EXPLAINS: f64 = 0.9;

/// Whether `fit` explains [`APEX_FIT_EXPLAINS`] of the variance of the map's heights within
/// `radius` (length) of its lowest node.
fn explains(map: &HeightMap, fit: &super::height_map::QuadraticFit, radius: f64) -> bool {
    let (lx, ly) = map.lowest_point();
    let (nx, ny, s) = (map.nx(), map.ny(), map.spacing());
    let (mut n, mut sum, mut sum2, mut resid) = (0.0, 0.0, 0.0, 0.0);
    for j in 0..ny {
        let y = (j as f64 - 0.5 * (ny - 1) as f64) * s - ly;
        for i in 0..nx {
            let x = (i as f64 - 0.5 * (nx - 1) as f64) * s - lx;
            if x.hypot(y) > radius {
                continue;
            }
            let h = map.heights()[j * nx + i];
            let q = fit.c0
                + fit.gx * x
                + fit.gy * y
                + 0.5 * (fit.kxx * x * x + fit.kyy * y * y)
                + fit.kxy * x * y;
            n += 1.0;
            sum += h;
            sum2 += h * h;
            resid += (h - q) * (h - q);
        }
    }
    let variance = sum2 / n - (sum / n) * (sum / n);
    n > 0.0 && resid / n <= (1.0 - APEX_FIT_EXPLAINS) * variance
}

/// The wall beyond a window of `map` (length): [`OUTSIDE_WALL`] times its height range and
/// its size.
fn wall_of(map: &HeightMap) -> f64 {
    let span = map
        .heights()
        .iter()
        .fold(0.0f64, |m, &h| m.max(h - map.min_height()));
    let (ex, ey) = map.extent();
    OUTSIDE_WALL * (span + 2.0 * ex.max(ey))
}

/// Bilinear interpolation of `map`'s height (length, from its lowest node) at (x, y) (length,
/// in its centred coordinates), the map repeating with its period n·s × m·s: between its
/// last node and its first the heights are interpolated across the seam. `None` for
/// coordinates that are not finite.
fn sample_periodic(map: &HeightMap, x: f64, y: f64) -> Option<f64> {
    let s = map.spacing();
    // The fractional node index, wrapped into [0, n), the nodes beside it and the fraction.
    let wrap = |c: f64, n: usize| {
        let u = (c / s + 0.5 * (n as f64 - 1.0)).rem_euclid(n as f64);
        if !u.is_finite() {
            return None;
        }
        let i0 = (u.floor() as usize).min(n - 1);
        Some((i0, (i0 + 1) % n, u - i0 as f64))
    };
    let (i0, i1, t) = wrap(x, map.nx())?;
    let (j0, j1, v) = wrap(y, map.ny())?;
    let h = map.heights();
    let node = |i: usize, j: usize| h[j * map.nx() + i] - map.min_height();
    let bottom = (1.0 - t) * node(i0, j0) + t * node(i1, j0);
    let top = (1.0 - t) * node(i0, j1) + t * node(i1, j1);
    Some((1.0 - v) * bottom + v * top)
}

/// The rms jump across `map`'s seam along x (its first column less its last, one per row) and
/// the rms of its steps between neighbouring nodes along x (length); `transpose` takes y.
fn seam_and_steps(map: &HeightMap, transpose: bool) -> (f64, f64) {
    let (nx, ny) = (map.nx(), map.ny());
    let h = map.heights();
    let (n, m) = if transpose { (ny, nx) } else { (nx, ny) };
    let at = |i: usize, j: usize| {
        if transpose {
            h[i * nx + j]
        } else {
            h[j * nx + i]
        }
    };
    let (mut seam, mut steps) = (0.0, 0.0);
    for j in 0..m {
        seam += (at(0, j) - at(n - 1, j)).powi(2);
        for i in 0..n - 1 {
            steps += (at(i + 1, j) - at(i, j)).powi(2);
        }
    }
    (
        (seam / m as f64).sqrt(),
        (steps / (m * (n - 1)) as f64).sqrt(),
    )
}

/// Refuse (naming the map's parameter) a map that is not periodic: along x or y, the rms jump
/// across its seam exceeds [`SEAM_STEP_LIMIT`] times the rms of its steps (plus 1e-9 of its
/// height range, for a map constant along that axis).
fn check_periodic(map: &HeightMap, source: &str) -> Result<(), SceneError> {
    let range = map
        .heights()
        .iter()
        .fold(0.0f64, |m, &h| m.max(h - map.min_height()));
    for (transpose, axis, across) in [(false, "x", "column"), (true, "y", "row")] {
        let (seam, steps) = seam_and_steps(map, transpose);
        if seam <= SEAM_STEP_LIMIT * steps + 1e-9 * range {
            continue;
        }
        return Err(SceneError::Refused {
            param: HEIGHT_MAP,
            why: format!(
                "{source} is not periodic along {axis}, and {CONVOLUTION} periodic repeats it: \
                 from its last {across} back to its first it jumps by {} rms, {} times its \
                 typical step between neighbouring nodes ({} rms; a periodic map's seam is \
                 one more such step, and more than {} times is refused). Give one period of \
                 the surface (its last {across} followed by its first, not repeating it), or \
                 run the map with {CONVOLUTION} padded, as an isolated contact",
                compact(seam),
                crate::text::compact_digits(seam / steps, 3),
                compact(steps),
                compact(SEAM_STEP_LIMIT),
            ),
        });
    }
    Ok(())
}

/// A measured surface as an indenter: its apex at the origin, sized and normalised as the
/// ellipsoid of its apex's principal radii (in the user's units where it has none).
impl IndenterShape for MeasuredSurface {
    fn name(&self) -> &'static str {
        "height-map"
    }

    fn describe(&self) -> String {
        MeasuredSurface::describe(self)
    }

    fn tag(&self) -> String {
        "height-map".to_string()
    }

    fn normalised_by(&self) -> String {
        match self.radii {
            Some(_) => "the apex fit's radii, as an ellipsoid's".to_string(),
            None => "none: the user's units".to_string(),
        }
    }

    fn height(&self, x: f64, y: f64, _e_star: f64, _work_of_adhesion: f64) -> f64 {
        MeasuredSurface::height(self, x, y).unwrap_or(f64::INFINITY)
    }

    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        match self.radii {
            Some((r1, r2)) => ellipsoid_scales(r1, r2, e_star, work_of_adhesion),
            None => Scales::UNITS,
        }
    }

    /// The apex ellipsoid's Hertz contact, as a circle of its major half-axis: the map's
    /// principal axes need not lie along the grid's.
    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        _work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        let Some((r1, r2)) = self.radii else {
            return Err(
                "a map that is not convex about its lowest node has no first \
                        contact to build: it is pressed on"
                    .to_string(),
            );
        };
        let h = hertz_for_mean_radius(r1, r2, e_star, c).map_err(|e| e.to_string())?;
        Ok(FirstContact { b: h.a, ..h.into() })
    }

    fn pull_off_hint(&self, _e_star: f64, _work_of_adhesion: f64) -> Option<PullOffHint> {
        let (r1, r2) = self.radii?;
        ellipsoid_hint(r1 / r2)
    }

    fn ellipsoid_like(&self) -> Option<(f64, f64)> {
        self.radii
    }

    fn map(&self) -> Option<&HeightMap> {
        Some(&self.map)
    }

    fn covers(&self, half_x: f64, half_y: f64) -> bool {
        MeasuredSurface::covers(self, half_x, half_y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::roughness::{generate, RoughnessParams};
    use std::f64::consts::PI;

    /// `f(i, j)` on n × m nodes at spacing `s`.
    fn map(n: usize, m: usize, s: f64, f: impl Fn(usize, usize) -> f64) -> HeightMap {
        let h = (0..n * m).map(|k| f(k % n, k / n)).collect();
        HeightMap::new(n, m, s, h).unwrap()
    }

    /// A wave of `waves` wavelengths along x over n nodes, uniform along y.
    fn wave(n: usize, waves: f64) -> HeightMap {
        map(n, 6, 0.5, |i, _| {
            1.0 - (2.0 * PI * waves * i as f64 / n as f64).cos()
        })
    }

    #[test]
    fn a_period_is_the_nodes_times_the_spacing_not_their_hull() {
        let s = MeasuredSurface::on_period(wave(32, 2.0), "w", None, None).unwrap();
        assert!(s.is_periodic());
        assert_eq!(s.period(), (16.0, 3.0));
        assert_eq!(s.window_half(), Some((8.0, 1.5)));
        // Without the periodic convolution the default window is the hull, as before.
        let w = MeasuredSurface::on_window(wave(32, 2.0), "w", None, None).unwrap();
        assert!(!w.is_periodic());
        assert_eq!(w.window_half(), Some((7.75, 1.25)));
    }

    #[test]
    fn heights_wrap_across_the_seam() {
        // Node i at x = (i − (n − 1)/2)·s: the last node at +3.75 (s = 0.5, n = 16), the
        // first at −3.75, and between them, at +4.0 ≡ −4.0, the mean of the two.
        let m = map(16, 4, 0.5, |i, j| (i * i + 3 * j) as f64);
        let (last, first) = (225.0, 0.0);
        let s = MeasuredSurface::on_period(m.clone(), "m", None, None);
        // The map is far from periodic: refused (see below); check the sampler itself.
        assert!(s.is_err());
        let at = |x: f64, y: f64| sample_periodic(&m, x, y).unwrap();
        let y0 = -0.75; // row 0
        assert!((at(3.75, y0) - last).abs() < 1e-12);
        assert!((at(-3.75, y0) - first).abs() < 1e-12);
        assert!((at(4.0, y0) - 0.5 * (last + first)).abs() < 1e-12);
        assert!((at(-4.0, y0) - 0.5 * (last + first)).abs() < 1e-12);
        // A whole period away is the same point; the seam along y too (rows 3 and 0).
        assert!((at(3.9 + 8.0, 0.3) - at(3.9, 0.3)).abs() < 1e-9);
        assert!((at(0.25, 1.0) - 0.5 * (at(0.25, 0.75) + at(0.25, -0.75))).abs() < 1e-12);
        // The height between nodes is bilinear within the map too, as `HeightMap::sample`.
        for (x, y) in [(0.3, 0.1), (-2.2, 0.7), (3.7, -0.74)] {
            assert!(
                (at(x, y) - m.sample(x, y).unwrap()).abs() < 1e-9,
                "{x}, {y}"
            );
        }
    }

    #[test]
    fn a_periodic_surface_samples_its_period_without_a_wall() {
        let s = MeasuredSurface::on_period(wave(32, 2.0), "w", None, None).unwrap();
        // h = 1 − cos(2π·2·i/32) from the lowest node; node 0 at x = −7.75, node 31 at 7.75.
        let node = |i: usize| 1.0 - (2.0 * PI * 2.0 * i as f64 / 32.0).cos();
        assert!((s.height(-7.75, 0.0).unwrap() - node(0)).abs() < 1e-12);
        let seam = s.height(8.0, 0.0).unwrap();
        assert!((seam - 0.5 * (node(31) + node(0))).abs() < 1e-12);
        // Beyond the period the surface repeats, far beyond too.
        assert!((s.height(8.0 + 16.0 * 7.0, 1.0).unwrap() - seam).abs() < 1e-9);
    }

    #[test]
    fn periodic_maps_pass_and_others_are_refused_naming_the_map() {
        // Whole numbers of wavelengths pass, at any phase.
        for waves in [1.0, 2.0, 5.0] {
            assert!(MeasuredSurface::on_period(wave(64, waves), "w", None, None).is_ok());
        }
        let shifted = map(64, 8, 1.0, |i, j| {
            (2.0 * PI * (i as f64 + 0.37) / 64.0).sin() + (2.0 * PI * 3.0 * j as f64 / 8.0).cos()
        });
        assert!(MeasuredSurface::on_period(shifted, "w", None, None).is_ok());
        // A generated rough surface is periodic by construction, whatever its seed.
        for seed in 0..8 {
            let mut p = RoughnessParams::with_rms_height(64, 0.1, 0.8, 0.01);
            p.grid_y = Some(16);
            p.seed = seed;
            let m = generate(&p).unwrap();
            assert!(
                MeasuredSurface::on_period(m, "rough", None, None).is_ok(),
                "seed {seed}"
            );
        }
        // A cap centred on the map is continuous across its seam (its repeats meet in a
        // ridge): a periodic surface, which passes. Off centre, a fractional number of
        // wavelengths, a tilt: refused, naming the map, why and what to do.
        let cap = |cx: f64| {
            map(32, 32, 1.0, move |i, j| {
                let (x, y) = (i as f64 - cx, j as f64 - 15.5);
                (x * x + y * y) / 200.0
            })
        };
        assert!(MeasuredSurface::on_period(cap(15.5), "cap", None, None).is_ok());
        let cap = cap(10.0);
        let tilt = map(32, 8, 1.0, |i, j| {
            0.1 * i as f64 + 0.02 * ((i * 7 + j * 3) % 5) as f64
        });
        for (m, axis) in [(wave(64, 2.5), "x"), (cap, "x"), (tilt, "x")] {
            let e = MeasuredSurface::on_period(m, "m.npy", None, None).unwrap_err();
            assert_eq!(e.param(), HEIGHT_MAP);
            let text = e.to_string();
            assert!(
                text.contains(&format!("m.npy is not periodic along {axis}"))
                    && text.contains("one period")
                    && text.contains(&format!("{CONVOLUTION} padded")),
                "{text}"
            );
        }
        let along_y = map(8, 32, 1.0, |i, j| {
            (j as f64).powi(2) + (PI * i as f64 / 4.0).sin()
        });
        let e = MeasuredSurface::on_period(along_y, "m", None, None).unwrap_err();
        assert!(e.to_string().contains("not periodic along y"), "{e}");
    }

    #[test]
    fn a_window_under_the_periodic_convolution_must_be_the_period() {
        let m = wave(32, 2.0);
        // The period, centred or moved: its centre is the origin.
        for ([x0, x1], centre) in [([-8.0, 8.0], 0.0), ([0.0, 16.0], 8.0)] {
            let s = MeasuredSurface::on_period(m.clone(), "w", Some([x0, x1]), None).unwrap();
            assert_eq!(s.window_half(), Some((8.0, 1.5)));
            assert_eq!(s.apex, (centre, 0.0));
        }
        // The hull, a part, an empty window: refused naming the window's parameter.
        for (x, y, param) in [
            (Some([-7.75, 7.75]), None, WINDOW_X),
            (Some([-4.0, 4.0]), None, WINDOW_X),
            (Some([8.0, -8.0]), None, WINDOW_X),
            (None, Some([-1.0, 1.0]), WINDOW_Y),
        ] {
            let e = MeasuredSurface::on_period(m.clone(), "w", x, y).unwrap_err();
            assert_eq!(e.param(), param);
            let text = e.to_string();
            assert!(
                text.contains("is not a period of w") && text.contains("leave it out"),
                "{text}"
            );
        }
        let e = MeasuredSurface::on_period(m, "w", Some([-4.0, 4.0]), None).unwrap_err();
        assert!(
            e.to_string().contains("give a window 16 long, e.g. -8,8"),
            "{e}"
        );
    }
}
