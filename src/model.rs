//! What a scene needs numerically: the domain and grid, the detachment stress, the load
//! steps and the CG settings. Knows nothing of backends.

use crate::backend::Preconditioner;
use crate::scene::Scene;
use crate::theory::{self, hertz::HertzContact, TheoryModel};
use std::f64::consts::PI;
use thiserror::Error;

/// Smallest grid side accepted (elements).
pub const MIN_GRID: usize = 16;

/// An invalid model choice, named as the flag that sets it.
#[derive(Debug, Error, PartialEq)]
pub enum ModelError {
    /// A grid side that is not a power of two ≥ [`MIN_GRID`].
    #[error("{flag} = {value} is invalid: the grid must be a power of two ≥ {MIN_GRID} (e.g. 64, 128, 256, 512)")]
    Grid {
        /// The flag.
        flag: &'static str,
        /// The value given.
        value: usize,
    },
    /// Any other out-of-range value.
    #[error("{flag} = {value} is invalid: {expected}")]
    Invalid {
        /// The flag.
        flag: &'static str,
        /// The value given, as text.
        value: String,
        /// What is accepted, and what to change.
        expected: String,
    },
}

/// κ = (2/π)·(ln(1+√2) − (√2−1)/3) (dimensionless): the mean displacement of a uniformly
/// loaded square is 2κ p Δx / E* (SPEC §5).
pub fn kappa() -> f64 {
    let s2 = 2f64.sqrt();
    2.0 / PI * ((1.0 + s2).ln() - (s2 - 1.0) / 3.0)
}

/// The Pohrt–Popov critical tensile stress σ_c = √(E* Δγ / (κ Δx)) (force/length²) for
/// elements of side `dx` (length).
pub fn critical_stress(scene: &Scene, dx: f64) -> f64 {
    (scene.e_star * scene.work_of_adhesion / (kappa() * dx)).sqrt()
}

/// How the approach is decreased from one recorded state to the next.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stepping {
    /// Fixed steps, each refined to the exact approach of every detachment onset inside it
    /// (the sawtooth's local minima), so the force minimum does not depend on the step size.
    #[default]
    Adaptive,
    /// Fixed steps only: the detachment cascade of a whole step is resolved at its end. Kept
    /// to show what too large a step costs.
    Fixed,
}

/// What a run is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Measure {
    /// The whole pull-off curve, to the end of contact.
    #[default]
    Curve,
    /// Only the adhesive force |min F̄|: fixed steps while the force falls, onsets refined
    /// from three steps before the minimum, and a stop once the minimum is confirmed.
    AdhesiveForce,
}

/// The user's choices that shape a model; `None` means "choose for the scene".
#[derive(Debug, Clone, PartialEq)]
pub struct ModelOptions {
    /// Elements along x (power of two).
    pub nx: usize,
    /// Elements along y (power of two), or fit to the contact's aspect.
    pub ny: Option<usize>,
    /// Mean radius of the initial non-adhesive contact, c̄0 (dimensionless, in c_r).
    pub start_radius_bar: f64,
    /// Number of load steps from d0 to the expected end of contact.
    pub steps: usize,
    /// Final approach d̄ at which to stop if the contact is still there (dimensionless).
    pub final_d_bar: Option<f64>,
    /// Relative free margin around the initial contact on each side (dimensionless).
    pub margin: f64,
    /// Relative residual at which CG stops (dimensionless).
    pub cg_tolerance: f64,
    /// CG iteration limit per solve.
    pub cg_max_iterations: usize,
    /// Relative residual up to which a solve that missed the tolerance even in CG's safer
    /// retry is accepted, and its state marked (dimensionless).
    pub cg_accept: f64,
    /// Read the residual back every this many CG iterations.
    pub cg_check_every: usize,
    /// Preconditioner.
    pub preconditioner: Preconditioner,
    /// Limit on detachment/attachment sweeps per load step.
    pub max_sweeps: usize,
    /// How load steps are taken.
    pub stepping: Stepping,
    /// What the run is for.
    pub measure: Measure,
    /// Re-grid as the contact shrinks: the same Nx × Ny on a smaller domain (finer Δx).
    pub regrid: bool,
    /// Angle θ between the ellipsoid's major axis and the grid's x axis (degrees); 0 aligns
    /// them. A rotated mesh checks results where crack fronts run along grid lines (SPEC §7).
    pub mesh_angle_deg: f64,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions {
            nx: 256,
            ny: None,
            start_radius_bar: 1.5,
            steps: 200,
            final_d_bar: None,
            margin: 0.08,
            cg_tolerance: 1e-8,
            cg_max_iterations: 5000,
            cg_accept: 1e-5,
            cg_check_every: 1,
            preconditioner: Preconditioner::Stiffness,
            max_sweeps: 2000,
            stepping: Stepping::Adaptive,
            measure: Measure::Curve,
            regrid: false,
            mesh_angle_deg: 0.0,
        }
    }
}

/// Conjugate-gradient settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CgSettings {
    /// Stop when ‖r‖ ≤ tolerance · ‖d − h‖ on C (dimensionless).
    pub tolerance: f64,
    /// Iteration limit per solve (and again for its safer retry).
    pub max_iterations: usize,
    /// Read the residual every this many iterations.
    pub check_every: usize,
    /// A solve that misses the tolerance even in the safer retry is still accepted, and its
    /// state marked, if ‖r‖ ≤ accept · ‖d − h‖ on C (dimensionless).
    pub accept: f64,
}

impl CgSettings {
    /// The relative residual up to which a solve is accepted: `accept`, or the tolerance
    /// if that is looser.
    pub fn acceptable(&self) -> f64 {
        self.accept.max(self.tolerance)
    }
}

/// The numerical model of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The scene modelled.
    pub scene: Scene,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side Δx (length).
    pub dx: f64,
    /// Detachment stress σ_c (force/length²).
    pub sigma_c: f64,
    /// The initial non-adhesive (Hertz) contact the approach aims at.
    pub initial: HertzContact,
    /// Approach of the first, non-adhesive press, d0 (length).
    pub d0: f64,
    /// Decrement of d per load step (length).
    pub d_step: f64,
    /// Stop once d falls below this (length).
    pub d_final: f64,
    /// CG settings.
    pub cg: CgSettings,
    /// Preconditioner.
    pub preconditioner: Preconditioner,
    /// Limit on detachment sweeps per step.
    pub max_sweeps: usize,
    /// Relative free margin around the contact on each side (dimensionless).
    pub margin: f64,
    /// How load steps are taken.
    pub stepping: Stepping,
    /// What the run is for.
    pub measure: Measure,
    /// Whether to re-grid as the contact shrinks.
    pub regrid: bool,
    /// The rotation of the ellipsoid against the grid.
    pub mesh: MeshAngle,
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

fn check_grid(flag: &'static str, n: usize) -> Result<(), ModelError> {
    if n >= MIN_GRID && n.is_power_of_two() {
        Ok(())
    } else {
        Err(ModelError::Grid { flag, value: n })
    }
}

fn invalid(flag: &'static str, value: impl ToString, expected: impl ToString) -> ModelError {
    ModelError::Invalid {
        flag,
        value: value.to_string(),
        expected: expected.to_string(),
    }
}

impl Model {
    /// Build the model: the initial Hertz contact of mean radius c̄0 sets the domain (plus
    /// the margin), nx sets Δx, and ny is fitted to the contact's aspect unless given.
    pub fn build(scene: &Scene, opt: &ModelOptions) -> Result<Self, ModelError> {
        check_grid("--grid", opt.nx)?;
        if let Some(ny) = opt.ny {
            check_grid("--grid-y", ny)?;
        }
        let c0 = opt.start_radius_bar;
        if !(c0.is_finite() && c0 > 0.0) {
            return Err(invalid(
                "--start-radius",
                c0,
                "a positive finite c̄0 (default 1.5)",
            ));
        }
        if opt.steps == 0 {
            return Err(invalid("--steps", 0, "at least 1 load step"));
        }
        if !(opt.margin.is_finite() && opt.margin >= 0.0) {
            return Err(invalid("--margin", opt.margin, "a finite margin ≥ 0"));
        }
        if !(opt.cg_tolerance > 0.0 && opt.cg_tolerance < 1.0) {
            return Err(invalid(
                "--cg-tolerance",
                opt.cg_tolerance,
                "a value in (0, 1)",
            ));
        }
        if !(opt.cg_accept > 0.0 && opt.cg_accept < 1.0) {
            return Err(invalid(
                "--cg-accept",
                opt.cg_accept,
                "a value in (0, 1) (default 1e-5)",
            ));
        }
        if !opt.mesh_angle_deg.is_finite() {
            return Err(invalid(
                "--mesh-angle",
                opt.mesh_angle_deg,
                "a finite angle in degrees (e.g. 0 or 45)",
            ));
        }
        let mesh = MeshAngle::from_degrees(opt.mesh_angle_deg);
        let scales = scene.scales();
        let c0_len = c0 * scales.length;
        let initial =
            theory::hertz::hertz_for_mean_radius(scene.r1, scene.r2, scene.e_star, c0_len)
                .map_err(|e| invalid("--ratio", scene.ratio(), e.to_string()))?;
        // The box around the (rotated) initial contact, plus the margin.
        let (box_x, box_y) = mesh.bounding_half_widths(initial.a, initial.b);
        let half_x = box_x * (1.0 + opt.margin);
        let dx = 2.0 * half_x / opt.nx as f64;
        // Elements the initial contact and its margin span along y (the 1e-9 absorbs round-off
        // when the box is square and this equals nx).
        let need_y = (2.0 * box_y * (1.0 + opt.margin) / dx - 1e-9).ceil() as usize;
        let ny = match opt.ny {
            Some(ny) if ny < need_y => {
                return Err(invalid(
                    "--grid-y",
                    ny,
                    format!(
                    "the initial contact (c̄0 = {c0}) spans {need_y} elements along y at this Δx: \
                         use --grid-y {} or more, or a smaller --start-radius",
                    need_y.next_power_of_two()
                ),
                ))
            }
            Some(ny) => ny,
            None => need_y.next_power_of_two().max(MIN_GRID),
        };
        let end = theory::pull_off(
            TheoryModel::adhesive_reference(scene.ratio()),
            scene.ratio(),
        )
        .map(|p| p.end_of_contact.d_bar)
        .unwrap_or(-0.5);
        let d0 = initial.d;
        let d0_bar = d0 / scales.approach;
        if let Some(f) = opt.final_d_bar {
            if !(f.is_finite() && f < d0_bar) {
                return Err(invalid(
                    "--final-d",
                    f,
                    format!("a finite d̄ below the initial approach d̄0 = {d0_bar:.4}"),
                ));
            }
        }
        let d_step = (d0_bar - end) / opt.steps as f64 * scales.approach;
        let d_final = opt.final_d_bar.unwrap_or(end - 2.0 * (d0_bar - end)) * scales.approach;
        Ok(Model {
            scene: *scene,
            nx: opt.nx,
            ny,
            dx,
            sigma_c: critical_stress(scene, dx),
            initial,
            d0,
            d_step,
            d_final,
            cg: CgSettings {
                tolerance: opt.cg_tolerance,
                max_iterations: opt.cg_max_iterations,
                check_every: opt.cg_check_every.max(1),
                accept: opt.cg_accept,
            },
            preconditioner: opt.preconditioner,
            max_sweeps: opt.max_sweeps,
            margin: opt.margin,
            stepping: opt.stepping,
            measure: opt.measure,
            regrid: opt.regrid,
            mesh,
        })
    }

    /// The same model on a domain scaled by `factor` (< 1 refines): Δx scales with it, the
    /// grid stays Nx × Ny, and σ_c is recomputed for the new Δx.
    pub fn regridded(&self, factor: f64) -> Model {
        let dx = self.dx * factor;
        Model {
            dx,
            sigma_c: critical_stress(&self.scene, dx),
            ..self.clone()
        }
    }

    /// Half-extents (length) of the contact in `mask` along x and y: the largest |x| (|y|)
    /// reached by a contact element's outer side; (0, 0) without contact.
    pub fn contact_extent(&self, mask: &[bool]) -> (f64, f64) {
        let (mut ex, mut ey) = (0f64, 0f64);
        for j in 0..self.ny {
            for i in 0..self.nx {
                if mask[j * self.nx + i] {
                    ex = ex.max(self.x(i).abs() + 0.5 * self.dx);
                    ey = ey.max(self.y(j).abs() + 0.5 * self.dx);
                }
            }
        }
        (ex, ey)
    }

    /// Carry a field (row-major, on this model's grid) over to `fine`, a re-gridded model:
    /// each element of the new grid takes the value of the element of this grid that holds
    /// its centre (`outside` where none does).
    pub fn resample<T: Copy>(&self, fine: &Model, values: &[T], outside: T) -> Vec<T> {
        let index = |x: f64, n: usize| {
            let k = (x / self.dx + n as f64 / 2.0).floor();
            (k >= 0.0 && k < n as f64).then_some(k as usize)
        };
        let mut out = Vec::with_capacity(fine.nx * fine.ny);
        for j in 0..fine.ny {
            for i in 0..fine.nx {
                out.push(
                    match (index(fine.x(i), self.nx), index(fine.y(j), self.ny)) {
                        (Some(ic), Some(jc)) => values[jc * self.nx + ic],
                        _ => outside,
                    },
                );
            }
        }
        out
    }

    /// x coordinate (length) of the centre of column `i`; the apex lies between the two
    /// middle columns.
    pub fn x(&self, i: usize) -> f64 {
        (i as f64 + 0.5 - self.nx as f64 / 2.0) * self.dx
    }

    /// y coordinate (length) of the centre of row `j`.
    pub fn y(&self, j: usize) -> f64 {
        (j as f64 + 0.5 - self.ny as f64 / 2.0) * self.dx
    }

    /// The indenter profile h at element centres (length), row-major nx × ny.
    pub fn profile(&self) -> Vec<f64> {
        let mut h = Vec::with_capacity(self.nx * self.ny);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let (xi, eta) = self.mesh.to_ellipsoid(self.x(i), self.y(j));
                h.push(self.scene.profile(xi, eta));
            }
        }
        h
    }

    /// The initial guess of the contact set: the Hertz ellipse of the first press (rotated
    /// with the ellipsoid).
    pub fn initial_contact(&self) -> Vec<bool> {
        let (a, b) = (self.initial.a, self.initial.b);
        let mut m = Vec::with_capacity(self.nx * self.ny);
        for j in 0..self.ny {
            for i in 0..self.nx {
                let (xi, eta) = self.mesh.to_ellipsoid(self.x(i), self.y(j));
                let (x, y) = (xi / a, eta / b);
                m.push(x * x + y * y < 1.0);
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kappa_matches_spec_value() {
        assert!((kappa() - 0.473201).abs() < 1e-6);
    }

    #[test]
    fn critical_stress_balances_energy() {
        // ½ σ_c² Δx³ · 2κ/E* = Δγ Δx²  (SPEC §5).
        let s = Scene::new(1.0, 1.0, 2.0, 0.3).unwrap();
        let dx = 0.01;
        let sc = critical_stress(&s, dx);
        let released = 0.5 * sc * sc * dx.powi(3) * 2.0 * kappa() / s.e_star;
        assert!((released / (s.work_of_adhesion * dx * dx) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn grid_must_be_power_of_two() {
        let s = Scene::new(1.0, 1.0, 1.0, 1.0).unwrap();
        for bad in [0, 8, 100, 255] {
            let opt = ModelOptions {
                nx: bad,
                ..Default::default()
            };
            let e = Model::build(&s, &opt).unwrap_err();
            assert!(e.to_string().contains("--grid"), "{e}");
        }
    }

    fn rotated(ratio: f64, nx: usize, degrees: f64) -> Model {
        let s = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).unwrap();
        let opt = ModelOptions {
            nx,
            mesh_angle_deg: degrees,
            ..Default::default()
        };
        Model::build(&s, &opt).unwrap()
    }

    #[test]
    fn mesh_angle_must_be_finite() {
        let s = Scene::from_ratio(5.0, 1.0, 1.0, 1.0).unwrap();
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let opt = ModelOptions {
                nx: 64,
                mesh_angle_deg: bad,
                ..Default::default()
            };
            let e = Model::build(&s, &opt).unwrap_err();
            assert!(e.to_string().contains("--mesh-angle"), "{e}");
        }
    }

    #[test]
    fn rotated_profile_is_the_rotated_quadratic_form() {
        // h = ½ xᵀ M x with M = Rᵀ diag(1/R1, 1/R2) R, written out element by element.
        let m = rotated(5.0, 64, 30.0);
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (k1, k2) = (1.0 / m.scene.r1, 1.0 / m.scene.r2);
        let (mxx, mxy, myy) = (
            c * c * k1 + s * s * k2,
            c * s * (k1 - k2),
            s * s * k1 + c * c * k2,
        );
        let h = m.profile();
        for j in 0..m.ny {
            for i in 0..m.nx {
                let (x, y) = (m.x(i), m.y(j));
                let want = 0.5 * (mxx * x * x + 2.0 * mxy * x * y + myy * y * y);
                let got = h[j * m.nx + i];
                assert!(
                    (got - want).abs() <= 1e-12 * (1.0 + want),
                    "({i}, {j}): {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn rotated_initial_contact_lies_along_the_rotated_major_axis() {
        // At θ = 30° the element 0.9 a along (cos θ, sin θ) is in the Hertz ellipse, the one
        // 0.9 a along the grid's x axis is not (R1/R2 = 5: b/a ≈ 0.3), and the box holds it.
        let m = rotated(5.0, 128, 30.0);
        let mask = m.initial_contact();
        let at = |x: f64, y: f64| {
            let i = (x / m.dx + m.nx as f64 / 2.0).floor() as usize;
            let j = (y / m.dx + m.ny as f64 / 2.0).floor() as usize;
            mask[j * m.nx + i]
        };
        let (a, t) = (m.initial.a, 30f64.to_radians());
        assert!(at(0.9 * a * t.cos(), 0.9 * a * t.sin()));
        assert!(at(-0.9 * a * t.cos(), -0.9 * a * t.sin()));
        assert!(!at(0.9 * a, 0.0));
        let ring = (0..m.nx * m.ny).filter(|&k| {
            let (i, j) = (k % m.nx, k / m.nx);
            mask[k] && (i == 0 || j == 0 || i == m.nx - 1 || j == m.ny - 1)
        });
        assert_eq!(ring.count(), 0);
        let n = mask.iter().filter(|&&v| v).count() as f64;
        let area = PI * m.initial.a * m.initial.b / (m.dx * m.dx);
        assert!(
            (n / area - 1.0).abs() < 0.02,
            "{n} elements vs ellipse area {area}"
        );
    }

    #[test]
    fn a_quarter_turn_swaps_the_axes() {
        // The aligned model's grid, transposed and turned by 90°: profile and initial
        // contact are the aligned ones transposed, exactly.
        let m0 = rotated(5.0, 64, 0.0);
        let mut m90 = m0.clone();
        (m90.nx, m90.ny) = (m0.ny, m0.nx);
        m90.mesh = MeshAngle::from_degrees(90.0);
        let (h0, h90) = (m0.profile(), m90.profile());
        let (c0, c90) = (m0.initial_contact(), m90.initial_contact());
        for j in 0..m90.ny {
            for i in 0..m90.nx {
                // (x, y) at 90° is (ξ, η) = (y, −x): column j, row ny0 − 1 − i of the aligned grid.
                let k0 = (m0.ny - 1 - i) * m0.nx + j;
                assert_eq!(h90[j * m90.nx + i], h0[k0]);
                assert_eq!(c90[j * m90.nx + i], c0[k0]);
            }
        }
        // Built from options, the box turns too: Δx follows the minor axis.
        let b = rotated(5.0, 64, 90.0);
        let (ha, hb) = (m0.initial.a * 1.08, m0.initial.b * 1.08);
        assert!((b.dx * 32.0 / hb - 1.0).abs() < 1e-12);
        assert!(b.ny as f64 * b.dx >= 2.0 * ha);
    }

    #[test]
    fn at_45_degrees_the_grid_is_square_and_mirror_symmetric_in_its_diagonal() {
        let m = rotated(25.0, 64, 45.0);
        assert_eq!((m.nx, m.ny), (64, 64));
        let (h, c) = (m.profile(), m.initial_contact());
        let n = m.nx;
        for j in 0..n {
            for i in 0..n {
                assert_eq!(h[j * n + i], h[i * n + j]);
                assert_eq!(c[j * n + i], c[i * n + j]);
                // Point symmetry about the apex.
                assert_eq!(c[j * n + i], c[(n - 1 - j) * n + (n - 1 - i)]);
            }
        }
        // The contact runs along the diagonal, not the anti-diagonal.
        assert!(c[(n / 2 + 10) * n + n / 2 + 10]);
        assert!(!c[(n / 2 + 10) * n + n / 2 - 11]);
    }

    #[test]
    fn aligned_angle_leaves_the_model_unchanged() {
        let s = Scene::from_ratio(25.0, 1.0, 1.0, 1.0).unwrap();
        let m = Model::build(&s, &ModelOptions::default()).unwrap();
        let a = MeshAngle::from_degrees(0.0);
        assert_eq!(m.mesh, a);
        assert_eq!(a.to_ellipsoid(0.3, -0.7), (0.3, -0.7));
        assert_eq!(a.bounding_half_widths(2.0, 0.5), (2.0, 0.5));
        assert_eq!(MeshAngle::from_degrees(-270.0).cos, 0.0);
        assert_eq!(
            MeshAngle::from_degrees(405.0).sin,
            std::f64::consts::FRAC_1_SQRT_2
        );
    }
}
