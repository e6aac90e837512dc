//! The rigid indenter's shape: its height h(x, y), the first (non-adhesive) contact the
//! approach aims at, the scales that normalise its results and, where a closed form exists,
//! where its pull-off lies (the hints the model sizes its domain and load path from).

use super::measured::MeasuredSurface;
use super::rough::RoughShape;
use super::{check, input_range, Scales, SceneError};
use crate::params::{EXPONENT, RADIUS, SCALE};
use crate::text::compact;
use crate::theory::hertz::HertzContact;
use crate::theory::power_law::{kendall_approach, kendall_force, PowerLawContact};
use crate::theory::{self, TheoryModel};
use std::f64::consts::PI;
use std::sync::Arc;

pub use crate::params::limits::MAX_EXPONENT;

/// The power law's factor s of h = s·rⁿ where none is given (length^(1−n)): with n = 2,
/// s = 1/(2R) = 0.5 is the sphere of radius 1.
pub const DEFAULT_POWER_LAW_SCALE: f64 = 0.5;

pub use crate::params::limits::MIN_EXPONENT;

/// Height of the flat punch's walls above its face, in the larger of its radius and Kendall's
/// approach at pull-off (dimensionless): far beyond any gap the half-space can close (the
/// surface outside the face never rises above the approach, and no run presses beyond a few
/// Kendall approaches), so that nothing outside the face ever touches. In radii alone it was
/// not: a punch of radius 1e-7 with E* = Δγ = 1 is pressed 4000 radii deep.
const PUNCH_WALL: f64 = 1e3;

/// A rigid indenter; lengths in the user's unit L.
#[derive(Debug, Clone, PartialEq)]
pub enum Indenter {
    /// h = x²/(2 R1) + y²/(2 R2), R1 ≥ R2 (length): x is the contact's major axis.
    Ellipsoid {
        /// Radius of curvature along x (length).
        r1: f64,
        /// Radius of curvature along y (length).
        r2: f64,
    },
    /// Axisymmetric h = scale·rⁿ, r = √(x² + y²) (length); n = 2 is the sphere of radius
    /// 1/(2·scale).
    PowerLaw {
        /// The exponent n (dimensionless), in [[`MIN_EXPONENT`], [`MAX_EXPONENT`]].
        n: f64,
        /// The factor s (length^(1−n)).
        scale: f64,
    },
    /// A flat cylindrical punch: h = 0 on the face r < radius, walls outside (length).
    FlatPunch {
        /// The face's radius a (length).
        radius: f64,
    },
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
    /// Peak pressure (force per length²; at the centre).
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
    /// Check the shape's parameters; errors name the parameter that sets each.
    pub fn checked(self) -> Result<Self, SceneError> {
        match self {
            Indenter::Ellipsoid { .. } | Indenter::HeightMap(_) | Indenter::Rough(_) => Ok(self),
            Indenter::PowerLaw { n, scale } => {
                check(
                    EXPONENT,
                    n,
                    (MIN_EXPONENT..=MAX_EXPONENT).contains(&n),
                    &format!("an exponent n in [{MIN_EXPONENT}, {MAX_EXPONENT}] (2 is the sphere)"),
                )?;
                check(
                    SCALE,
                    scale,
                    super::input_in_range(scale),
                    &input_range("the factor s of h = s·rⁿ (length^(1−n))"),
                )?;
                // Every scale of the problem must stay finite: the length scale c_n.
                let probe =
                    PowerLawContact::new(n, scale, 1.0, 1.0).map_err(|e| SceneError::Invalid {
                        param: SCALE,
                        value: scale,
                        expected: e,
                    })?;
                let (length, _, _) = probe.scales();
                check(
                    SCALE,
                    scale,
                    length.is_finite() && length > 0.0,
                    "a factor whose contact length scale is finite; rescale the units",
                )?;
                Ok(self)
            }
            Indenter::FlatPunch { radius } => {
                check(
                    RADIUS,
                    radius,
                    super::input_in_range(radius),
                    &input_range("a punch radius"),
                )?;
                Ok(self)
            }
        }
    }

    /// The shape's name as `--indenter` takes it.
    pub fn name(&self) -> &'static str {
        match self {
            Indenter::Ellipsoid { .. } => "ellipsoid",
            Indenter::PowerLaw { .. } => "power-law",
            Indenter::FlatPunch { .. } => "flat-punch",
            Indenter::HeightMap(_) => "height-map",
            Indenter::Rough(_) => "rough",
        }
    }

    /// The shape and its parameters, in words (for reports).
    pub fn describe(&self) -> String {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => {
                format!(
                    "ellipsoid R1 = {}, R2 = {} (R1/R2 = {})",
                    compact(r1),
                    compact(r2),
                    compact(r1 / r2)
                )
            }
            Indenter::PowerLaw { n, scale } => {
                format!(
                    "power law h = s·rⁿ, n = {}, s = {}",
                    compact(n),
                    compact(scale)
                )
            }
            Indenter::FlatPunch { radius } => {
                format!("flat punch of radius {}", compact(radius))
            }
            Indenter::HeightMap(ref m) => m.describe(),
            Indenter::Rough(ref r) => r.describe(),
        }
    }

    /// The radii (R1, R2) of an ellipsoid (length); `None` for the other shapes.
    pub fn radii(&self) -> Option<(f64, f64)> {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => Some((r1, r2)),
            _ => None,
        }
    }

    /// The axis ratio R1/R2 of an ellipsoid; 1 for the axisymmetric shapes (dimensionless).
    pub fn ratio(&self) -> f64 {
        match self.ellipsoid_like() {
            Some((r1, r2)) => r1 / r2,
            None => 1.0,
        }
    }

    /// The radii that size and normalise the shape like an ellipsoid: an ellipsoid's own, a
    /// height map's apex radii (length); `None` for the other shapes.
    fn ellipsoid_like(&self) -> Option<(f64, f64)> {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => Some((r1, r2)),
            Indenter::HeightMap(ref m) => m.radii,
            Indenter::Rough(ref r) => r.base.ellipsoid_like(),
            _ => None,
        }
    }

    /// The node spacing of a height map (length); `None` for the other shapes.
    pub fn map_spacing(&self) -> Option<f64> {
        match *self {
            Indenter::HeightMap(ref m) => Some(m.map.spacing()),
            Indenter::Rough(ref r) => Some(r.map.spacing()),
            _ => None,
        }
    }

    /// The shortest wavelength a height map or a rough shape's roughness holds (length,
    /// [`crate::scene::height_map::HeightMap::shortest_wavelength`]); `None` for the other shapes.
    pub fn shortest_wavelength(&self) -> Option<f64> {
        match *self {
            Indenter::HeightMap(ref m) => Some(m.map.shortest_wavelength()),
            Indenter::Rough(ref r) => Some(r.map.shortest_wavelength()),
            _ => None,
        }
    }

    /// The shortest wavelength that carries a share of a height map's surface less its smooth
    /// shape, or of a rough shape's roughness (length,
    /// [`crate::scene::height_map::HeightMap::carrying_wavelength`]); `None` for the other
    /// shapes and for a map that is its quadratic.
    pub fn carrying_wavelength(&self) -> Option<f64> {
        match *self {
            Indenter::HeightMap(ref m) => m.map.carrying_wavelength(),
            Indenter::Rough(ref r) => r.map.carrying_wavelength(),
            _ => None,
        }
    }

    /// Whether the shape's height is known over the rectangle |x| ≤ `half_x`, |y| ≤ `half_y`
    /// (length) about the apex, in its own axes: everywhere but for a height map.
    pub fn covers(&self, half_x: f64, half_y: f64) -> bool {
        match *self {
            Indenter::HeightMap(ref m) => m.covers(half_x, half_y),
            Indenter::Rough(ref r) => r.covers(half_x, half_y) && r.base.covers(half_x, half_y),
            _ => true,
        }
    }

    /// Height h (length) at (x, y) (length) from the apex, in the shape's own axes (+∞
    /// outside a height map: [`Indenter::covers`] keeps a model inside it), pressed into a
    /// half-space of E* (force/length²) with Δγ (force/length), which set how high the flat
    /// punch's walls must stand.
    pub fn height(&self, x: f64, y: f64, e_star: f64, work_of_adhesion: f64) -> f64 {
        match *self {
            Indenter::HeightMap(ref m) => m.height(x, y).unwrap_or(f64::INFINITY),
            Indenter::Rough(ref r) => {
                r.base.height(x, y, e_star, work_of_adhesion)
                    + r.roughness(x, y).unwrap_or(f64::INFINITY)
            }
            Indenter::Ellipsoid { r1, r2 } => x * x / (2.0 * r1) + y * y / (2.0 * r2),
            Indenter::PowerLaw { n, scale } => scale * (x * x + y * y).sqrt().powf(n),
            Indenter::FlatPunch { radius } => {
                if x * x + y * y < radius * radius {
                    0.0
                } else {
                    PUNCH_WALL * radius.max(kendall_approach(radius, e_star, work_of_adhesion))
                }
            }
        }
    }

    /// The normalisation scales (physics §2 for the ellipsoid; for a power law the same
    /// forms with its length c_n and radius R_n, equal to the sphere's at n = 2; for a flat
    /// punch its radius a, Kendall's pull-off force √(8π E* Δγ a³) and the approach at
    /// pull-off F/(2E* a)), for E* (stress) and Δγ (force/length).
    pub fn scales(&self, e_star: f64, work_of_adhesion: f64) -> Scales {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => ellipsoid_scales(r1, r2, e_star, work_of_adhesion),
            Indenter::HeightMap(ref m) => match m.radii {
                Some((r1, r2)) => ellipsoid_scales(r1, r2, e_star, work_of_adhesion),
                None => Scales::UNITS,
            },
            Indenter::Rough(ref r) => r.base.scales(e_star, work_of_adhesion),
            Indenter::PowerLaw { n, scale } => {
                let (length, force, approach) =
                    power_law(n, scale, e_star, work_of_adhesion).scales();
                Scales {
                    length,
                    force,
                    approach,
                }
            }
            Indenter::FlatPunch { radius } => Scales {
                length: radius,
                force: kendall_force(radius, e_star, work_of_adhesion),
                approach: kendall_approach(radius, e_star, work_of_adhesion),
            },
        }
    }

    /// The first, non-adhesive contact the approach aims at, of mean radius `c` (length):
    /// Hertz's ellipse for the ellipsoid, the power law's circle, the whole face of a flat
    /// punch pressed to half Kendall's pull-off approach (its first contact does not depend
    /// on `c`).
    pub fn first_contact(
        &self,
        c: f64,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Result<FirstContact, String> {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => {
                theory::hertz::hertz_for_mean_radius(r1, r2, e_star, c)
                    .map(FirstContact::from)
                    .map_err(|e| e.to_string())
            }
            Indenter::Rough(ref r) => r.base.first_contact(c, e_star, work_of_adhesion),
            Indenter::HeightMap(ref m) => {
                // The apex ellipsoid's Hertz contact, as a circle of its major half-axis: the
                // map's principal axes need not lie along the grid's.
                let Some((r1, r2)) = m.radii else {
                    return Err(
                        "a map that is not convex about its lowest node has no first \
                                contact to build: it is pressed on"
                            .to_string(),
                    );
                };
                let h = theory::hertz::hertz_for_mean_radius(r1, r2, e_star, c)
                    .map_err(|e| e.to_string())?;
                Ok(FirstContact { b: h.a, ..h.into() })
            }
            Indenter::PowerLaw { n, scale } => {
                let p = power_law(n, scale, e_star, work_of_adhesion);
                Ok(FirstContact {
                    a: c,
                    b: c,
                    d: p.hertz_approach(c),
                    force: p.hertz_force(c),
                    p0: p.hertz_peak_pressure(c),
                })
            }
            Indenter::FlatPunch { radius } => {
                let d = 0.5 * kendall_approach(radius, e_star, work_of_adhesion);
                Ok(FirstContact {
                    a: radius,
                    b: radius,
                    d,
                    force: 2.0 * e_star * radius * d,
                    // The pressure at the face's centre (it is singular at the edge).
                    p0: e_star * d / (PI * radius),
                })
            }
        }
    }

    /// Where the closed form of this shape puts the pull-off (JKR or JG for the ellipsoid,
    /// JKR by the method of dimensionality reduction for a power law, Kendall for the flat
    /// punch); `None` where none is computed.
    pub fn pull_off_hint(&self, e_star: f64, work_of_adhesion: f64) -> Option<PullOffHint> {
        match *self {
            Indenter::Rough(ref r) => r.base.pull_off_hint(e_star, work_of_adhesion),
            Indenter::HeightMap(ref m) if m.radii.is_none() => None,
            Indenter::Ellipsoid { .. } | Indenter::HeightMap(_) => {
                let ratio = self.ratio();
                let p = theory::pull_off(TheoryModel::adhesive_reference(ratio), ratio).ok()?;
                Some(PullOffHint {
                    end_d_bar: p.end_of_contact.d_bar,
                    b_bar_at_min: p.force_min.b_bar,
                })
            }
            Indenter::PowerLaw { n, scale } => {
                let p = power_law(n, scale, e_star, work_of_adhesion);
                let s = self.scales(e_star, work_of_adhesion);
                Some(PullOffHint {
                    end_d_bar: p.end_of_contact().d / s.approach,
                    b_bar_at_min: p.force_minimum().a / s.length,
                })
            }
            Indenter::FlatPunch { .. } => Some(PullOffHint {
                end_d_bar: -1.0,
                b_bar_at_min: 1.0,
            }),
        }
    }

    /// The exact Δx → 0 limit of the adhesive force |min F̄| that this shape's closed form
    /// gives, with its name: JKR's 1/2 for the sphere (and the power law n = 2), the power
    /// law's JKR solution, Kendall's 1 for the flat punch; `None` for an ellipsoid with
    /// R1 ≠ R2 (where only approximations exist).
    pub fn exact_adhesive_force(
        &self,
        e_star: f64,
        work_of_adhesion: f64,
    ) -> Option<(&'static str, f64)> {
        match *self {
            Indenter::Ellipsoid { r1, r2 } => (r1 == r2).then_some(("JKR", 0.5)),
            Indenter::HeightMap(_) | Indenter::Rough(_) => None,
            Indenter::PowerLaw { n, scale } => {
                let p = power_law(n, scale, e_star, work_of_adhesion);
                let s = self.scales(e_star, work_of_adhesion);
                Some(("JKR (power law)", -p.force_minimum().force / s.force))
            }
            Indenter::FlatPunch { .. } => Some(("Kendall", 1.0)),
        }
    }
}

/// The power law h = `scale`·rⁿ's closed forms for E* (stress) and Δγ (force/length).
fn power_law(n: f64, scale: f64, e_star: f64, work_of_adhesion: f64) -> PowerLawContact {
    PowerLawContact {
        n,
        scale,
        e_star,
        work_of_adhesion,
    }
}

/// Physics §2's scales of an ellipsoid of radii R1, R2 (length).
fn ellipsoid_scales(r1: f64, r2: f64, e_star: f64, work_of_adhesion: f64) -> Scales {
    let re = (r1 * r2).sqrt();
    let c_r = (9.0 * PI * re * re * work_of_adhesion / (4.0 * e_star)).cbrt();
    Scales {
        length: c_r,
        force: 3.0 * PI * re * work_of_adhesion,
        approach: c_r * c_r / re,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_of_exponent_two_is_the_sphere() {
        let r = 3.0;
        let sphere = Indenter::Ellipsoid { r1: r, r2: r };
        let law = Indenter::PowerLaw {
            n: 2.0,
            scale: 1.0 / (2.0 * r),
        };
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
        let p = Indenter::FlatPunch { radius: 2.0 };
        let s = p.scales(3.0, 0.5);
        assert_eq!(s.length, 2.0);
        assert!((s.force - (8.0 * PI * 3.0 * 0.5 * 8.0f64).sqrt()).abs() < 1e-12);
        assert!((s.approach - s.force / (2.0 * 3.0 * 2.0)).abs() < 1e-12);
        assert_eq!(p.height(1.9, 0.0, 3.0, 0.5), 0.0);
        assert!(p.height(2.1, 0.0, 3.0, 0.5) > 100.0);
        // A tiny punch is pressed far deeper than its radius: its wall clears the approach.
        let tiny = Indenter::FlatPunch { radius: 1e-7 };
        let d = tiny.scales(1.0, 1.0).approach;
        assert!(d > 1e3 * 1e-7, "{d}");
        assert!(tiny.height(2e-7, 0.0, 1.0, 1.0) >= 1e3 * d);
    }

    #[test]
    fn bad_shapes_name_their_parameter() {
        use crate::params::{EXPONENT, RADIUS, SCALE};
        for (shape, param) in [
            (Indenter::PowerLaw { n: 0.5, scale: 1.0 }, EXPONENT),
            (
                Indenter::PowerLaw {
                    n: f64::NAN,
                    scale: 1.0,
                },
                EXPONENT,
            ),
            (
                Indenter::PowerLaw {
                    n: 3.0,
                    scale: -1.0,
                },
                SCALE,
            ),
            (Indenter::FlatPunch { radius: 0.0 }, RADIUS),
            (
                Indenter::FlatPunch {
                    radius: f64::INFINITY,
                },
                RADIUS,
            ),
        ] {
            assert_eq!(shape.checked().unwrap_err().param(), param);
        }
    }
}
