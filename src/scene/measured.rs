//! A measured topography as an indenter: a [`HeightMap`] placed so that its apex (the
//! stationary point of a quadratic fitted around its lowest node) lies at the origin, with
//! heights measured from the apex, and the principal radii of that fit as the ellipsoid that
//! sizes the domain and normalises the results.

use super::height_map::HeightMap;
use super::SceneError;
use crate::run::schema::HEIGHT_MAP;
use crate::text::compact;

/// The fit around the lowest node takes the nodes within this fraction of the map's smaller
/// half-width (dimensionless), and at least [`MIN_FIT_NODES`] spacings.
pub const FIT_FRACTION: f64 = 0.25;

/// The smallest fit radius, in map spacings (dimensionless).
pub const MIN_FIT_NODES: f64 = 3.0;

/// A height map placed as an indenter.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredSurface {
    /// The map (heights in the user's length unit).
    pub map: HeightMap,
    /// Where it was read from, for reports.
    pub source: String,
    /// The apex in the map's coordinates (length): the indenter's origin.
    pub apex: (f64, f64),
    /// The fitted height at the apex, measured from the map's minimum (length).
    pub apex_height: f64,
    /// The principal radii of curvature (R1 ≥ R2, length) of the fit at the apex.
    pub radii: (f64, f64),
}

impl MeasuredSurface {
    /// Place `map` (read from `source`): fit h ≈ c0 + g·x + ½ xᵀ K x around its lowest node,
    /// take the fit's stationary point as the apex (the lowest node if that point lies
    /// outside the fit's disc). Refused (naming the height map's parameter) where the map is not convex
    /// around its lowest node.
    pub fn new(map: HeightMap, source: &str) -> Result<Self, SceneError> {
        let (ex, ey) = map.extent();
        let radius = (FIT_FRACTION * ex.min(ey)).max(MIN_FIT_NODES * map.spacing());
        let refuse = |why: String| SceneError::Refused {
            param: HEIGHT_MAP,
            why: format!("{source}: {why}"),
        };
        let fit = map.curvature_fit(radius).ok_or_else(|| {
            refuse(format!(
                "no quadratic could be fitted within {} of its lowest node (too few nodes)",
                compact(radius)
            ))
        })?;
        let radii = fit.principal_radii().ok_or_else(|| {
            refuse(format!(
                "the surface is not convex within {} of its lowest node (curvatures {}, {}, {}): \
                 a contact there has no single apex",
                compact(radius),
                compact(fit.kxx),
                compact(fit.kxy),
                compact(fit.kyy)
            ))
        })?;
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
        Ok(MeasuredSurface {
            apex: (lx + sx, ly + sy),
            apex_height: fitted - map.min_height(),
            radii,
            source: source.to_string(),
            map,
        })
    }

    /// Height (length) at (x, y) (length) from the apex; `None` outside the map.
    pub fn height(&self, x: f64, y: f64) -> Option<f64> {
        self.map
            .sample(self.apex.0 + x, self.apex.1 + y)
            .map(|h| h - self.apex_height)
    }

    /// Whether the map covers the rectangle |x| ≤ `half_x`, |y| ≤ `half_y` (length) about
    /// the apex.
    pub fn covers(&self, half_x: f64, half_y: f64) -> bool {
        let (ex, ey) = self.map.extent();
        self.apex.0.abs() + half_x <= ex && self.apex.1.abs() + half_y <= ey
    }

    /// The map in words.
    pub fn describe(&self) -> String {
        format!(
            "height map {} ({}×{}, spacing {}; apex radii {}, {})",
            self.source,
            self.map.nx(),
            self.map.ny(),
            compact(self.map.spacing()),
            compact(self.radii.0),
            compact(self.radii.1)
        )
    }
}
