//! The grid against the scene: the detachment stress per element size, the mesh angle, the
//! memory a grid needs and the checks that it resolves the contact.

use super::error::ModelError;
use super::limits::*;
use super::options::ModelOptions;
use crate::params::{Spec, GRID, GRID_Y, MARGIN, RATIO, START_RADIUS};
use crate::scene::{PullOffHint, Scene};
use crate::setup::ChordAxes;
use std::f64::consts::PI;

/// κ = (2/π)·(ln(1+√2) − (√2−1)/3) (dimensionless): the mean displacement of a uniformly
/// loaded square is 2κ p Δx / E* (physics §5).
pub fn kappa() -> f64 {
    let s2 = 2f64.sqrt();
    2.0 / PI * ((1.0 + s2).ln() - (s2 - 1.0) / 3.0)
}

/// The Pohrt–Popov critical tensile stress σ_c = √(E* Δγ / (κ Δx)) (force/length²) for
/// elements of side `dx` (length).
pub fn critical_stress(scene: &Scene, dx: f64) -> f64 {
    (scene.e_star * scene.work_of_adhesion / (kappa() * dx)).sqrt()
}

/// The angle θ between the ellipsoid's major axis and the grid's x axis, with its cosine and
/// sine. A grid point (x, y) lies at ξ = x cos θ + y sin θ along the major axis and at
/// η = −x sin θ + y cos θ along the minor one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshAngle {
    /// θ (degrees).
    pub degrees: f64,
    /// cos θ (dimensionless).
    pub cos: f64,
    /// sin θ (dimensionless).
    pub sin: f64,
}

impl MeshAngle {
    /// The angle of `degrees`. Multiples of 45° get exact values (0, ±1, ±1/√2 with
    /// cos = ±sin), so that 90° is an exact swap of the axes and 45° an exact mirror in the
    /// grid's diagonal.
    pub fn from_degrees(degrees: f64) -> Self {
        let r = degrees.rem_euclid(360.0);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let table = [
            (1.0, 0.0),
            (h, h),
            (0.0, 1.0),
            (-h, h),
            (-1.0, 0.0),
            (-h, -h),
            (0.0, -1.0),
            (h, -h),
        ];
        let k = r / 45.0;
        let (cos, sin) = if k.fract() == 0.0 && k < 8.0 {
            table[k as usize]
        } else {
            let (s, c) = r.to_radians().sin_cos();
            (c, s)
        };
        MeshAngle { degrees, cos, sin }
    }

    /// Whether the ellipsoid's axes lie along the grid's (θ = 0 exactly).
    pub fn is_aligned(&self) -> bool {
        self.degrees == 0.0
    }

    /// The directions of the contact's chords (the ellipsoid's axes) in the grid's frame:
    /// exactly the grid's own axes when aligned.
    pub fn chord_axes(&self) -> ChordAxes {
        if self.is_aligned() {
            ChordAxes::ALIGNED
        } else {
            ChordAxes {
                cos: self.cos,
                sin: self.sin,
            }
        }
    }

    /// (ξ, η): the point (x, y) of the grid (length) in the ellipsoid's frame (length).
    pub fn to_ellipsoid(&self, x: f64, y: f64) -> (f64, f64) {
        if self.is_aligned() {
            (x, y)
        } else {
            (x * self.cos + y * self.sin, -x * self.sin + y * self.cos)
        }
    }

    /// Half-widths along the grid's x and y (length) of the box around an ellipse of
    /// half-axes `a` along ξ and `b` along η (length).
    pub fn bounding_half_widths(&self, a: f64, b: f64) -> (f64, f64) {
        if self.is_aligned() {
            (a, b)
        } else {
            let (c, s) = (self.cos, self.sin);
            (
                (a * a * c * c + b * b * s * s).sqrt(),
                (a * a * s * s + b * b * c * c).sqrt(),
            )
        }
    }
}

/// The memory a run on an nx × ny grid needs (bytes), see [`BYTES_PER_ELEMENT`], with the
/// states kept to go back to ([`snapshot_slots`]).
pub fn memory_estimate(nx: usize, ny: usize) -> u64 {
    let n = (nx as u64).saturating_mul(ny as u64);
    let kept = (snapshot_slots(nx.saturating_mul(ny)) as u64)
        .saturating_mul(SNAPSHOT_BYTES_PER_ELEMENT)
        .saturating_mul(n);
    BYTES_FIXED
        .saturating_add(BYTES_PER_ELEMENT.saturating_mul(n))
        .saturating_add(kept)
}

/// Refuse a grid that resolves the contact by too few elements: fewer than
/// [`MIN_ELEMENTS_FIRST_CONTACT`] across the first contact's minor axis (half-axis `b0`,
/// length), or an expected fewer than [`MIN_ELEMENTS_AT_MINIMUM`] at the force minimum (the
/// closed form's b̄ there). The error names the grid that would resolve it.
pub(super) fn check_resolution(
    scene: &Scene,
    opt: &ModelOptions,
    hint: PullOffHint,
    b0: f64,
    dx: f64,
) -> Result<(), ModelError> {
    let b_min_bar = hint.b_bar_at_min;
    let first = 2.0 * b0 / dx;
    let at_minimum = 2.0 * b_min_bar * scene.scales().length / dx;
    if first >= MIN_ELEMENTS_FIRST_CONTACT && at_minimum >= MIN_ELEMENTS_AT_MINIMUM {
        return Ok(());
    }
    let factor = (MIN_ELEMENTS_FIRST_CONTACT / first).max(MIN_ELEMENTS_AT_MINIMUM / at_minimum);
    let needed = (opt.nx as f64 * factor).ceil();
    let mut others = Vec::new();
    if opt.start_radius_bar > 1.5 {
        others.push(format!("a smaller {START_RADIUS} (default 1.5)"));
    }
    if opt.margin > 0.5 {
        others.push(format!("a smaller {MARGIN} (default 0.08)"));
    }
    let others = if others.is_empty() {
        String::new()
    } else {
        format!(", or {}", others.join(", or "))
    };
    let advice = if needed <= MAX_GRID as f64 {
        let nx = (needed as usize).next_power_of_two().max(MIN_GRID);
        let ny = opt
            .ny
            .map(|ny| {
                format!(
                    " (and {GRID_Y} {})",
                    ((ny as f64 * factor).ceil() as usize).next_power_of_two()
                )
            })
            .unwrap_or_default();
        format!("use {GRID} {nx}{ny} or finer{others}")
    } else {
        format!("no grid up to {GRID} {MAX_GRID} resolves it: use a smaller {RATIO}{others}")
    };
    Err(ModelError::TooCoarse {
        scene: scene.headline(),
        nx: opt.nx,
        first,
        at_minimum,
        advice,
    })
}

pub(super) fn check_grid(param: &'static Spec, n: usize) -> Result<(), ModelError> {
    if (MIN_GRID..=MAX_GRID).contains(&n) && n.is_power_of_two() {
        Ok(())
    } else {
        Err(ModelError::Grid { param, value: n })
    }
}

pub(super) fn invalid(
    param: &'static Spec,
    value: impl ToString,
    expected: impl ToString,
) -> ModelError {
    ModelError::Invalid {
        param,
        value: value.to_string(),
        expected: expected.to_string(),
    }
}
