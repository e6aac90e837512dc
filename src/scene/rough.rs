//! A rough shape: a smooth base indenter (ellipsoid, power law or flat punch) with a height
//! map added to it, the map's centre on the base's apex and its mean taken off. The base
//! sizes the domain and normalises the results (its scales, first contact and closed-form
//! hints); the roughness is interpolated bilinearly between its nodes, so the surface is the
//! same continuous one on every grid.

use super::height_map::HeightMap;
use super::indenter::{FirstContact, Indenter, IndenterShape, PullOffHint};
use super::{Scales, SceneError};
use crate::params::ROUGHNESS;
use crate::text::compact;

/// A base shape with roughness added.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughShape {
    /// The smooth base (never a height map or another rough shape).
    pub base: Indenter,
    /// The roughness (heights in the user's length unit, coordinates centred on the map).
    pub map: HeightMap,
    /// Where the roughness was read from, for reports.
    pub source: String,
    /// The roughness's mean over its nodes, from its lowest node (length): taken off, so that
    /// the rough surface lies about the base.
    mean: f64,
}

impl RoughShape {
    /// `base` with `map` (read from `source`) added. Refused (naming the roughness
    /// parameter) for a base that is itself a map.
    pub fn new(base: Indenter, map: HeightMap, source: &str) -> Result<Self, SceneError> {
        if matches!(base, Indenter::HeightMap(_) | Indenter::Rough(_)) {
            return Err(SceneError::Refused {
                param: ROUGHNESS,
                why: format!(
                    "{source}: roughness is added to an ellipsoid, a power law or a flat punch"
                ),
            });
        }
        let n = map.heights().len() as f64;
        let mean = map
            .heights()
            .iter()
            .map(|h| h - map.min_height())
            .sum::<f64>()
            / n;
        Ok(RoughShape {
            base,
            map,
            source: source.to_string(),
            mean,
        })
    }

    /// The roughness (length) at (x, y) (length) from the base's apex; `None` outside the map.
    pub fn roughness(&self, x: f64, y: f64) -> Option<f64> {
        self.map.sample(x, y).map(|h| h - self.mean)
    }

    /// The roughness's rms height about its mean (length).
    pub fn rms_height(&self) -> f64 {
        let h = self.map.heights();
        let m = self.mean + self.map.min_height();
        (h.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / h.len() as f64).sqrt()
    }

    /// Whether the roughness covers the rectangle |x| ≤ `half_x`, |y| ≤ `half_y` (length).
    pub fn covers(&self, half_x: f64, half_y: f64) -> bool {
        let (ex, ey) = self.map.extent();
        half_x <= ex && half_y <= ey
    }

    /// The shape in words.
    pub fn describe(&self) -> String {
        format!(
            "{} with roughness {} ({}×{}, spacing {}, rms {})",
            self.base.describe(),
            self.source,
            self.map.nx(),
            self.map.ny(),
            compact(self.map.spacing()),
            compact(self.rms_height())
        )
    }
}

impl IndenterShape for RoughShape {
    fn name(&self) -> &'static str {
        "rough"
    }

    fn describe(&self) -> String {
        RoughShape::describe(self)
    }

    fn tag(&self) -> String {
        format!("rough-{}", self.base.shape().tag())
    }

    fn normalised_by(&self) -> String {
        format!("the base shape's: {}", self.base.shape().normalised_by())
    }

    fn height(&self, x: f64, y: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
        self.base.height(x, y, e_star, work_of_adhesion)
            + self.roughness(x, y).unwrap_or(f64::INFINITY)
    }

    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        self.base.scales(e_star, work_of_adhesion)
    }

    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        self.base.first_contact(c, e_star, work_of_adhesion)
    }

    fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint> {
        self.base.pull_off_hint(e_star, work_of_adhesion)
    }

    fn ellipsoid_like(&self) -> Option<(f64, f64)> {
        self.base.shape().ellipsoid_like()
    }

    fn map(&self) -> Option<&HeightMap> {
        Some(&self.map)
    }

    fn covers(&self, half_x: f64, half_y: f64) -> bool {
        RoughShape::covers(self, half_x, half_y) && self.base.covers(half_x, half_y)
    }
}
