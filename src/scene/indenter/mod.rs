//! The rigid indenter's shape: its height h(x, y), the first (non-adhesive) contact the
//! approach aims at, the scales that normalise its results and, where a closed form exists,
//! where its pull-off lies (the hints the model sizes its domain and load path from).
//!
//! One file per shape (as an FFT library keeps one per algorithm), each behind
//! [`IndenterShape`]: the ellipsoid, the power law, the flat punch and the cone here, the
//! height map ([`MeasuredSurface`]) and the rough shape ([`RoughShape`]) in their own modules.
//! [`Indenter`] names which shape a scene holds and hands every question to it.

mod cone;
mod ellipsoid;
mod flat_punch;
mod power_law;

pub use cone::{Cone, DEFAULT_HALF_ANGLE};
pub use ellipsoid::Ellipsoid;
pub(crate) use ellipsoid::{ellipsoid_hint, ellipsoid_scales};
pub use flat_punch::FlatPunch;
pub use power_law::{PowerLaw, DEFAULT_POWER_LAW_SCALE};

use super::height_map::HeightMap;
use super::measured::MeasuredSurface;
use super::rough::RoughShape;
use super::{Scales, SceneError};
use crate::theory::hertz::HertzContact;
use std::fmt::Debug;
use std::sync::Arc;

pub use crate::params::limits::{MAX_EXPONENT, MIN_EXPONENT};

/// What a shape answers: everything the scene, the model and the reports ask of an indenter.
/// Lengths are in the user's unit L, E* (`e_star`) in force/length², Δγ (`work_of_adhesion`)
/// in force/length.
pub trait IndenterShape: Debug + Send + Sync {
    /// The shape's name as the indenter parameter takes it ("ellipsoid", "cone", …).
    fn name(&self) -> &'static str;

    /// The shape and its parameters, in words (for reports).
    fn describe(&self) -> String;

    /// A short tag for file names ("r5", "power-law-n3", "cone-a70").
    fn tag(&self) -> String;

    /// What normalises the results, in words.
    fn normalised_by(&self) -> String;

    /// The shape's numbers by name, in the user's units, for provenance (empty for the shapes
    /// that record themselves otherwise: maps).
    fn parameters(&self) -> Vec<(&'static str, f64)> {
        Vec::new()
    }

    /// Check the shape's parameters; errors name the parameter that sets each.
    fn check(&self) -> Result<(), SceneError> {
        Ok(())
    }

    /// Height h (length) at (x, y) (length) from the apex, in the shape's own axes (+∞ where
    /// the shape is unknown: [`IndenterShape::covers`] keeps a model inside it).
    fn height(&self, x: f64, y: f64, e_star: f64, work_of_adhesion: f64) -> f64;

    /// The normalisation scales (physics §2 for the ellipsoid; each shape's own otherwise).
    fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales;

    /// The first, non-adhesive contact the approach aims at, of mean radius `c` (length).
    fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String>;

    /// Where the shape's closed form puts the pull-off; `None` where none is computed.
    fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint>;

    /// The exact Δx → 0 limit of the adhesive force |min F̄| that the shape's closed form
    /// gives, with its name; `None` where only approximations exist.
    fn exact_adhesive_force(
        &self,
        _e_star: f64,
        _work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        None
    }

    /// The radii (length) that size and normalise the shape like an ellipsoid (an
    /// ellipsoid's own, a height map's apex radii, a rough shape's base's); `None` otherwise.
    fn ellipsoid_like(&self) -> Option<(f64, f64)> {
        None
    }

    /// The height map the shape samples (a measured surface's, a rough shape's roughness);
    /// `None` for a shape given by a formula.
    fn map(&self) -> Option<&HeightMap> {
        None
    }

    /// Whether the shape's height is known over the rectangle |x| ≤ `half_x`, |y| ≤ `half_y`
    /// (length) about the apex, in its own axes: everywhere but for a map.
    fn covers(&self, _half_x: f64, _half_y: f64) -> bool {
        true
    }

    /// The radius (length) of the sphere the shape is, where it is one (JKR's closed form
    /// applies to it); `None` otherwise.
    fn sphere_radius(&self) -> Option<f64> {
        None
    }
}

/// A rigid indenter: which shape a scene holds; lengths in the user's unit L.
#[derive(Debug, Clone, PartialEq)]
pub enum Indenter {
    /// h = x²/(2 R1) + y²/(2 R2) ([`Ellipsoid`]).
    Ellipsoid(Ellipsoid),
    /// Axisymmetric h = s·rⁿ ([`PowerLaw`]).
    PowerLaw(PowerLaw),
    /// A flat cylindrical punch ([`FlatPunch`]).
    FlatPunch(FlatPunch),
    /// A cone h = r·cot α ([`Cone`]).
    Cone(Cone),
    /// A measured topography ([`MeasuredSurface`]): its apex at the origin, sized and
    /// normalised as the ellipsoid of its apex's principal radii.
    HeightMap(Arc<MeasuredSurface>),
    /// A base shape with roughness added ([`RoughShape`]): sized, normalised and hinted as
    /// its base.
    Rough(Arc<RoughShape>),
}

/// The first, non-adhesive contact the approach aims at (Hertz's for the ellipsoid): what the
/// model sizes the domain and first press from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstContact {
    /// Half-axis along x (length).
    pub a: f64,
    /// Half-axis along y (length).
    pub b: f64,
    /// Approach, pressing in positive (length).
    pub d: f64,
    /// Normal force, compressive positive (force).
    pub force: f64,
    /// Its pressure scale (force per length²): the peak, at the centre; the mean F/(πa²) where
    /// the peak is infinite (under a cone's tip).
    pub p0: f64,
}

impl From<HertzContact> for FirstContact {
    fn from(h: HertzContact) -> Self {
        FirstContact {
            a: h.a,
            b: h.b,
            d: h.d,
            force: h.force,
            p0: h.p0,
        }
    }
}

/// Where a closed form puts the pull-off, normalised by the indenter's scales: what the model
/// sizes the load path and checks the grid's resolution with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOffHint {
    /// d̄ where the contact ends (jumps off) under displacement control.
    pub end_d_bar: f64,
    /// The contact's minor half-axis at the force minimum, b̄ (for a circle its radius).
    pub b_bar_at_min: f64,
}

impl Indenter {
    /// The ellipsoid of radii `r1` ≥ `r2` (length); checked by [`super::Scene::new`].
    pub fn ellipsoid(r1: f64, r2: f64) -> Indenter {
        Indenter::Ellipsoid(Ellipsoid { r1, r2 })
    }

    /// The power law h = `scale`·rⁿ (n = `exponent`, scale in length^(1−n)).
    pub fn power_law(exponent: f64, scale: f64) -> Indenter {
        Indenter::PowerLaw(PowerLaw { n: exponent, scale })
    }

    /// The flat punch of face radius `radius` (length).
    pub fn flat_punch(radius: f64) -> Indenter {
        Indenter::FlatPunch(FlatPunch { radius })
    }

    /// The cone of half-angle `half_angle` (degrees, between its axis and its flank).
    pub fn cone(half_angle: f64) -> Indenter {
        Indenter::Cone(Cone::new(half_angle))
    }

    /// The shape behind the name, which answers every question below.
    pub fn shape(&self) -> &dyn IndenterShape {
        match self {
            Indenter::Ellipsoid(s) => s,
            Indenter::PowerLaw(s) => s,
            Indenter::FlatPunch(s) => s,
            Indenter::Cone(s) => s,
            Indenter::HeightMap(s) => s.as_ref(),
            Indenter::Rough(s) => s.as_ref(),
        }
    }

    /// Check the shape's parameters; errors name the parameter that sets each.
    pub fn checked(self) -> Result<Self, SceneError> {
        self.shape().check()?;
        Ok(self)
    }

    /// The shape's name as the indenter parameter takes it.
    pub fn name(&self) -> &'static str {
        self.shape().name()
    }

    /// The shape and its parameters, in words (for reports).
    pub fn describe(&self) -> String {
        self.shape().describe()
    }

    /// The radii (R1, R2) of an ellipsoid (length); `None` for the other shapes.
    pub fn radii(&self) -> Option<(f64, f64)> {
        match *self {
            Indenter::Ellipsoid(Ellipsoid { r1, r2 }) => Some((r1, r2)),
            _ => None,
        }
    }

    /// The axis ratio R1/R2 of an ellipsoid (or of the radii that normalise a map like one);
    /// 1 for the axisymmetric shapes (dimensionless).
    pub fn ratio(&self) -> f64 {
        match self.shape().ellipsoid_like() {
            Some((r1, r2)) => r1 / r2,
            None => 1.0,
        }
    }

    /// The node spacing of a height map (length); `None` for the other shapes.
    pub fn map_spacing(&self) -> Option<f64> {
        self.shape().map().map(HeightMap::spacing)
    }

    /// The shortest wavelength a height map or a rough shape's roughness holds (length,
    /// [`HeightMap::shortest_wavelength`]); `None` for the other shapes.
    pub fn shortest_wavelength(&self) -> Option<f64> {
        self.shape().map().map(HeightMap::shortest_wavelength)
    }

    /// The shortest wavelength that carries a share of a height map's surface less its smooth
    /// shape, or of a rough shape's roughness (length, [`HeightMap::carrying_wavelength`]);
    /// `None` for the other shapes and for a map that is its quadratic.
    pub fn carrying_wavelength(&self) -> Option<f64> {
        self.shape().map().and_then(HeightMap::carrying_wavelength)
    }

    /// Whether the shape's height is known over the rectangle |x| ≤ `half_x`, |y| ≤ `half_y`
    /// (length) about the apex, in its own axes: everywhere but for a height map.
    pub fn covers(&self, half_x: f64, half_y: f64) -> bool {
        self.shape().covers(half_x, half_y)
    }

    /// Height h (length) at (x, y) (length) from the apex, in the shape's own axes (+∞
    /// outside a height map: [`Indenter::covers`] keeps a model inside it), pressed into a
    /// half-space of E* (force/length²) with Δγ (force/length), which set how high the flat
    /// punch's walls must stand.
    pub fn height(&self, x: f64, y: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
        self.shape().height(x, y, e_star, work_of_adhesion)
    }

    /// The normalisation scales (see each shape's [`IndenterShape::scales`]), for E* (stress)
    /// and Δγ (force/length).
    pub fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        self.shape().scales(e_star, work_of_adhesion)
    }

    /// The first, non-adhesive contact the approach aims at, of mean radius `c` (length).
    pub fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        self.shape().first_contact(c, e_star, work_of_adhesion)
    }

    /// Where the closed form of this shape puts the pull-off (JKR or JG for the ellipsoid,
    /// JKR by the method of dimensionality reduction for a power law and a cone, Kendall for
    /// the flat punch); `None` where none is computed.
    pub fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint> {
        self.shape().pull_off_hint(e_star, work_of_adhesion)
    }

    /// The exact Δx → 0 limit of the adhesive force |min F̄| that this shape's closed form
    /// gives, with its name: JKR's 1/2 for the sphere (and the power law n = 2), the power
    /// law's and the cone's JKR solutions, Kendall's 1 for the flat punch; `None` for an
    /// ellipsoid with R1 ≠ R2 (where only approximations exist) and for maps.
    pub fn exact_adhesive_force(
        &self,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        self.shape().exact_adhesive_force(e_star, work_of_adhesion)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_power_law_of_exponent_two_is_the_sphere() {
        let r = 3.0;
        let sphere = Indenter::ellipsoid(r, r);
        let law = Indenter::power_law(2.0, 1.0 / (2.0 * r));
        for (x, y) in [(0.3, -0.2), (1.0, 2.0), (0.0, 0.0)] {
            let (a, b) = (sphere.height(x, y, 2.0, 0.1), law.height(x, y, 2.0, 0.1));
            assert!((a - b).abs() <= 1e-14 * (1.0 + a), "{a} vs {b}");
        }
        let (s, l) = (sphere.scales(2.0, 0.1), law.scales(2.0, 0.1));
        for (a, b) in [
            (s.length, l.length),
            (s.force, l.force),
            (s.approach, l.approach),
        ] {
            assert!((a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
        }
        let (hs, hl) = (
            sphere.pull_off_hint(2.0, 0.1).unwrap(),
            law.pull_off_hint(2.0, 0.1).unwrap(),
        );
        assert!((hs.end_d_bar - hl.end_d_bar).abs() < 1e-9, "{hs:?} {hl:?}");
        assert!((hs.b_bar_at_min - hl.b_bar_at_min).abs() < 1e-9);
        let (fs, fl) = (
            sphere.first_contact(1.2, 2.0, 0.1).unwrap(),
            law.first_contact(1.2, 2.0, 0.1).unwrap(),
        );
        for (a, b) in [
            (fs.a, fl.a),
            (fs.d, fl.d),
            (fs.force, fl.force),
            (fs.p0, fl.p0),
        ] {
            assert!((a / b - 1.0).abs() < 1e-9, "{fs:?} vs {fl:?}");
        }
        assert_eq!(
            law.exact_adhesive_force(2.0, 0.1).map(|e| e.0),
            Some("JKR (power law)")
        );
        assert!((law.exact_adhesive_force(2.0, 0.1).unwrap().1 - 0.5).abs() < 1e-12);
    }

    #[test]
    fn the_flat_punch_is_normalised_by_kendall() {
        let p = Indenter::flat_punch(2.0);
        let s = p.scales(3.0, 0.5);
        assert_eq!(s.length, 2.0);
        assert!((s.force - (8.0 * PI * 3.0 * 0.5 * 8.0f64).sqrt()).abs() < 1e-12);
        assert!((s.approach - s.force / (2.0 * 3.0 * 2.0)).abs() < 1e-12);
        assert_eq!(p.height(1.9, 0.0, 3.0, 0.5), 0.0);
        assert!(p.height(2.1, 0.0, 3.0, 0.5) > 100.0);
        // A tiny punch is pressed far deeper than its radius: its wall clears the approach.
        let tiny = Indenter::flat_punch(1e-7);
        let d = tiny.scales(1.0, 1.0).approach;
        assert!(d > 1e3 * 1e-7, "{d}");
        assert!(tiny.height(2e-7, 0.0, 1.0, 1.0) >= 1e3 * d);
    }

    #[test]
    fn bad_shapes_name_their_parameter() {
        use crate::params::{EXPONENT, RADIUS, SCALE};
        for (shape, param) in [
            (Indenter::power_law(0.5, 1.0), EXPONENT),
            (Indenter::power_law(f64::NAN, 1.0), EXPONENT),
            (Indenter::power_law(3.0, -1.0), SCALE),
            (Indenter::flat_punch(0.0), RADIUS),
            (Indenter::flat_punch(f64::INFINITY), RADIUS),
        ] {
            assert_eq!(shape.checked().unwrap_err().param(), param);
        }
    }
}
