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
//!
//! Heights are measured from the map's lowest node (so a height map's approach d is too)
//! and interpolated bilinearly between nodes: the surface the solver sees is the same
//! continuous one on every grid, so its grids converge to the limit of that surface, and a
//! grid finer than the map's spacing resolves every facet of it.

use super::height_map::HeightMap;
use super::SceneError;
use crate::run::schema::{WINDOW_X, WINDOW_Y};
use crate::text::compact;

/// The fit around the lowest node takes the nodes within this fraction of the map's smaller
/// half-width (dimensionless), and at least [`MIN_FIT_NODES`] spacings.
pub const FIT_FRACTION: f64 = 0.25;

/// The smallest fit radius, in map spacings (dimensionless).
pub const MIN_FIT_NODES: f64 = 3.0;

/// Height of the domain's part outside a window, above the map's highest node, in the
/// window's size plus the map's height range (dimensionless): far beyond any gap the
/// half-space can close there, so that nothing outside the window ever touches.
pub const OUTSIDE_WALL: f64 = 1e3;

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
        if !explains(map, &fit, radius) {
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
    /// nothing there touches.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
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
                "domain x {}…{}, y {}…{}; {}",
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
