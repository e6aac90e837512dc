//! What a scene needs numerically: the domain and grid, the detachment stress, the load
//! steps and the CG settings, in modules: `limits` (ranges and sizes), `error`, `options` (what
//! a caller chooses), `grid` (the grid against the scene) and `steps` (the load path); this
//! module builds the model.

use crate::params::{
    APEX_OFFSET, BACKEND, CG_ACCEPT, CG_MAX_ITERATIONS, CG_TOLERANCE, CONVOLUTION, E_STAR, GRID,
    GRID_Y, HEIGHT_MAP, INDENTER, MARGIN, MESH_ANGLE, PRECISION, PRELOAD_AREA, PRELOAD_DEPTH,
    PRELOAD_FORCE, ROUGHNESS, START_RADIUS, STEPS, WORK_OF_ADHESION,
};
use crate::scene::{FirstContact, Indenter, PullOffHint, Scene};
use crate::setup::Preconditioner;
use crate::text::compact;

mod error;
mod grid;
mod limits;
mod options;
pub mod steps;
mod window_path;

pub use error::ModelError;
use grid::{check_grid, check_resolution, invalid};
pub use grid::{critical_stress, kappa, memory_estimate, MeshAngle};
pub use limits::*;
pub use options::{CgSettings, Measure, ModelOptions, Onsets, Preload};
pub use steps::{LoadPath, LoadTarget, Loading};
use window_path::WindowGeometry;

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
    pub initial: FirstContact,
    /// The load path: the first approach d0, the load step and where to stop (lengths).
    pub load: LoadPath,
    /// CG settings.
    pub cg: CgSettings,
    /// Preconditioner.
    pub preconditioner: Preconditioner,
    /// Limit on detachment sweeps per step.
    pub max_sweeps: usize,
    /// Relative free margin around the contact on each side (dimensionless).
    pub margin: f64,
    /// Which detachment onsets are located.
    pub onsets: Onsets,
    /// Whether a cascade's intermediate rounds are solved loosely (see the solver's
    /// equilibrium module).
    pub loose_rounds: bool,
    /// Whether a cascade round's solve starts from the detached elements' load handed to
    /// their neighbours ([`crate::backend::shares`]); on with [`Model::loose_rounds`].
    pub spread_detached: bool,
    /// Whether a cascade detaches, without a solve, the elements certain to go once the
    /// detached load is handed on ([`crate::backend::certify`]); on with
    /// [`Model::loose_rounds`].
    pub certify_detached: bool,
    /// Whether a loose round that detaches nothing is solved once more, to
    /// the solver's tight tolerance, before the exact solve; on with
    /// [`Model::loose_rounds`].
    pub tighten_stalls: bool,
    /// What the run is for.
    pub measure: Measure,
    /// Whether to re-grid as the contact shrinks.
    pub regrid: bool,
    /// The rotation of the ellipsoid against the grid.
    pub mesh: MeshAngle,
    /// The apex's position within the element grid (elements along x and y, in [−0.5, 0.5]):
    /// element centres lie at x = (i + ½ − nx/2 − offset.0)·Δx from the apex.
    pub apex_offset: (f64, f64),
    /// The loading phase before the pull-off, if the contact is pressed on rather than built
    /// in one piece as the first contact's non-adhesive solution.
    pub loading: Option<Loading>,
    /// Whether a measure of the adhesive force may stop once the force minimum is confirmed
    /// (the solver's confirming d̄ past it): only where the results are
    /// normalised, so that the test's d̄ has its meaning; a surface in the user's units runs
    /// to the end of contact.
    pub confirm_minimum: bool,
}

impl Model {
    /// Build the model: the initial Hertz contact of mean radius c̄0 sets the domain (plus
    /// the margin), nx sets Δx, and ny is fitted to the contact's aspect unless given.
    pub fn build(scene: &Scene, opt: &ModelOptions) -> Result<Self, ModelError> {
        check_grid(GRID, opt.nx)?;
        if let Some(ny) = opt.ny {
            check_grid(GRID_Y, ny)?;
        }
        let c0 = opt.start_radius_bar;
        let (c_lo, c_hi) = START_RADIUS_RANGE;
        if !(c_lo..=c_hi).contains(&c0) {
            return Err(invalid(
                START_RADIUS,
                compact(c0),
                format!(
                    "c̄0 must be in [{c_lo}, {c_hi}] (default 1.5): above the contact radius \
                     at the force minimum (about 0.8), so that the pull-off passes through it"
                ),
            ));
        }
        if !(1..=MAX_STEPS).contains(&opt.steps) {
            return Err(invalid(
                STEPS,
                opt.steps,
                format!("from 1 to {MAX_STEPS} load steps (default 200)"),
            ));
        }
        if !(0.0..=MAX_MARGIN).contains(&opt.margin) {
            return Err(invalid(
                MARGIN,
                compact(opt.margin),
                format!("a relative margin in [0, {MAX_MARGIN}] (default 0.08)"),
            ));
        }
        if !(opt.cg_tolerance > 0.0 && opt.cg_tolerance < 1.0) {
            return Err(invalid(
                CG_TOLERANCE,
                compact(opt.cg_tolerance),
                "a value in (0, 1) (default 1e-8)",
            ));
        }
        if !(opt.cg_accept > 0.0 && opt.cg_accept < 1.0) {
            return Err(invalid(
                CG_ACCEPT,
                compact(opt.cg_accept),
                "a value in (0, 1) (default 1e-5)",
            ));
        }
        if !(1..=MAX_CG_ITERATIONS).contains(&opt.cg_max_iterations) {
            return Err(invalid(
                CG_MAX_ITERATIONS,
                opt.cg_max_iterations,
                format!("from 1 to {MAX_CG_ITERATIONS} (default 5000)"),
            ));
        }
        if !(-MAX_MESH_ANGLE..=MAX_MESH_ANGLE).contains(&opt.mesh_angle_deg) {
            return Err(invalid(
                MESH_ANGLE,
                compact(opt.mesh_angle_deg),
                format!(
                    "an angle in degrees in [−{MAX_MESH_ANGLE}, {MAX_MESH_ANGLE}] (e.g. 0 or 45)"
                ),
            ));
        }
        let mesh = MeshAngle::from_degrees(opt.mesh_angle_deg);
        let (ox, oy) = opt.apex_offset;
        if !((-0.5..=0.5).contains(&ox) && (-0.5..=0.5).contains(&oy)) {
            return Err(invalid(
                APEX_OFFSET,
                format!("{},{}", compact(ox), compact(oy)),
                "two fractions of an element in [−0.5, 0.5], e.g. 0.25,-0.5".to_string(),
            ));
        }
        let placed = placed_on_map(scene, opt, &mesh)?;
        let scene = &placed;
        if let Some(half) = scene.window_half() {
            return Model::on_window(scene, opt, mesh, half);
        }
        let scales = scene.scales();
        let c0_len = c0 * scales.length;
        let initial = scene
            .indenter
            .first_contact(c0_len, scene.e_star, scene.work_of_adhesion)
            .map_err(|e| invalid(INDENTER, scene.indenter.describe(), e))?;
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
                    GRID_Y,
                    ny,
                    format!(
                    "the initial contact (c̄0 = {c0}) spans {need_y} elements along y at this Δx: \
                         use {GRID_Y} {} or more, or a smaller {START_RADIUS}",
                    need_y.next_power_of_two()
                ),
                ))
            }
            Some(ny) => ny,
            None => need_y.next_power_of_two().max(MIN_GRID),
        };
        let hint = steps::hint_for(scene, opt.hint);
        let load = LoadPath::new(initial.d, scales.approach, opt.steps, opt.final_d_bar, hint)?;
        check_resolution(scene, opt, hint, initial.b, dx)?;
        check_map_resolution(scene, hint)?;
        check_covered(scene, &mesh, opt, (opt.nx, ny), dx)?;
        let model = Model::assemble(scene, opt, mesh, (ny, dx), initial, load);
        let preload = opt
            .preload
            .or_else(|| scene.presses_on().then_some(Preload::StartRadius));
        let model = Model {
            loading: preload.map(|p| model.loading_to(p)).transpose()?,
            ..model
        };
        model.check_scales("f64", F64_SAFE_RANGE)?;
        Ok(model)
    }

    /// The model of `scene` on an Nx × `ny` grid of element side `dx` (length) with its
    /// first contact and load path, every other setting as `opt` chooses; no loading phase.
    fn assemble(
        scene: &Scene,
        opt: &ModelOptions,
        mesh: MeshAngle,
        (ny, dx): (usize, f64),
        initial: FirstContact,
        load: LoadPath,
    ) -> Model {
        Model {
            scene: scene.clone(),
            nx: opt.nx,
            ny,
            dx,
            sigma_c: critical_stress(scene, dx),
            initial,
            load,
            cg: CgSettings {
                tolerance: opt.cg_tolerance,
                max_iterations: opt.cg_max_iterations,
                check_every: opt.cg_check_every.max(1),
                accept: opt.cg_accept,
            },
            preconditioner: opt.preconditioner,
            max_sweeps: opt.max_sweeps,
            margin: opt.margin,
            onsets: opt.onsets,
            loose_rounds: opt.loose_rounds,
            spread_detached: opt.loose_rounds,
            certify_detached: opt.loose_rounds,
            tighten_stalls: opt.loose_rounds,
            measure: opt.measure,
            regrid: opt.regrid,
            mesh,
            apex_offset: opt.apex_offset,
            loading: None,
            confirm_minimum: true,
        }
    }

    /// The model of a height map placed on a window of half-widths `half` (length): the
    /// window is the domain (Δx = its width / Nx, Ny fitted to its aspect unless given; on a
    /// periodic map's period, Ny spans the period exactly: [`periodic_rows`]), the
    /// surface is pressed on from its first touch (to [`DEFAULT_PRELOAD_AREA`] of the domain
    /// unless a preload is given), and the load steps are sized from the geometry and the
    /// adhesion (see `window_path`).
    fn on_window(
        scene: &Scene,
        opt: &ModelOptions,
        mesh: MeshAngle,
        (half_x, half_y): (f64, f64),
    ) -> Result<Self, ModelError> {
        check_window_map_resolution(scene, (half_x, half_y))?;
        let dx = 2.0 * half_x / opt.nx as f64;
        let ny = match periodic_map(scene) {
            Some(m) => periodic_rows(m, opt, &mesh, dx)?,
            None => {
                let need_y = ((2.0 * half_y / dx - 1e-9).ceil() as usize).max(1);
                opt.ny.unwrap_or(need_y.next_power_of_two().max(MIN_GRID))
            }
        };
        let unknown = FirstContact {
            a: 0.0,
            b: 0.0,
            d: 0.0,
            force: 0.0,
            p0: 0.0,
        };
        let unsized_path = LoadPath {
            d0: 0.0,
            d_step: 0.0,
            d_final: 0.0,
            d_end: 0.0,
        };
        let mut model = Model {
            regrid: false,
            confirm_minimum: scene.is_normalised(),
            ..Model::assemble(scene, opt, mesh, (ny, dx), unknown, unsized_path)
        };
        let mut heights: Vec<f64> = model
            .profile()
            .into_iter()
            .filter(|h| h.is_finite())
            .collect();
        heights.sort_by(f64::total_cmp);
        if heights.is_empty() {
            return Err(invalid(
                INDENTER,
                scene.indenter.describe(),
                "a surface that the half-space can touch somewhere in the domain",
            ));
        }
        let geometry = WindowGeometry {
            heights: &heights,
            window: (half_x * half_y * 4.0 / (dx * dx)).round().max(1.0) as usize,
            dx,
            e_star: scene.e_star,
            work_of_adhesion: scene.work_of_adhesion,
        };
        let path = geometry.path(opt.steps, opt.preload);
        model.load = path.load;
        model.initial = FirstContact {
            a: 0.0,
            b: 0.0,
            d: path.load.d0,
            force: 0.0,
            // The pressure a contact of the domain's size pressed by the depth carries.
            p0: scene.e_star * path.depth / (2.0 * half_x),
        };
        let preload = opt
            .preload
            .unwrap_or(Preload::AreaFraction(DEFAULT_PRELOAD_AREA));
        model.loading = Some(Loading {
            d_step: path.loading_step,
            ..model.loading_to(preload)?
        });
        model.check_scales("f64", F64_SAFE_RANGE)?;
        Ok(model)
    }

    /// The loading phase to `preload`: from the least height of the grid's element centres,
    /// in steps of the pull-off's load step. Refuses a preload that is not finite and
    /// positive (a depth: above the first touch; an area: a fraction below 1).
    fn loading_to(&self, preload: Preload) -> Result<Loading, ModelError> {
        let d_touch = self.profile().into_iter().fold(f64::INFINITY, f64::min);
        let target = match preload {
            Preload::StartRadius => LoadTarget::Depth(self.load.d0),
            Preload::Depth(d) => LoadTarget::Depth(d),
            Preload::Force(f) => LoadTarget::Force(f),
            Preload::AreaFraction(a) => LoadTarget::AreaFraction(a),
        };
        let refuse = |spec: &'static crate::params::Spec, value: f64, expected: String| {
            Err(invalid(spec, compact(value), expected))
        };
        match target {
            LoadTarget::Depth(d) if !(d.is_finite() && d > d_touch) => {
                return refuse(
                    PRELOAD_DEPTH,
                    d,
                    format!(
                        "an approach beyond the first touch at d = {} (length)",
                        compact(d_touch)
                    ),
                )
            }
            LoadTarget::Force(f) if !(f.is_finite() && f > 0.0) => {
                return refuse(PRELOAD_FORCE, f, "a compressive force > 0".to_string())
            }
            LoadTarget::AreaFraction(a) if !(a > 0.0 && a < 1.0) => {
                return refuse(PRELOAD_AREA, a, "a fraction of the domain in (0, 1)".into())
            }
            _ => {}
        }
        if !d_touch.is_finite() {
            return Err(invalid(
                INDENTER,
                self.scene.indenter.describe(),
                "a surface that the half-space can touch somewhere in the domain",
            ));
        }
        let loading = Loading {
            d_touch,
            d_step: self.load.d_step,
            target,
        };
        if let LoadTarget::Depth(d) = target {
            // A depth further than the loading's steps can go is refused before any work.
            let deepest = d_touch + MAX_LOADING_STEPS as f64 * loading.d_step;
            if (d - d_touch) / loading.d_step > MAX_LOADING_STEPS as f64 {
                return refuse(
                    PRELOAD_DEPTH,
                    d,
                    format!(
                        "at most {MAX_LOADING_STEPS} loading steps of Δd = {} (length): a depth \
                         up to {}",
                        compact(loading.d_step),
                        compact(deepest)
                    ),
                );
            }
        }
        Ok(loading)
    }

    /// The characteristic numbers a backend holds, with their names and units: σ_c, the
    /// element side, the first approach, the load step and the first contact's pressure scale.
    pub fn scales(&self) -> [(&'static str, f64); 5] {
        let p0 = self.initial.p0;
        [
            ("σ_c, the detachment stress (force/length²)", self.sigma_c),
            ("Δx, the element side (length)", self.dx),
            ("d0, the first approach (length)", self.load.d0),
            ("the load step (length)", self.load.d_step),
            ("the first contact's pressure scale (force/length²)", p0),
        ]
    }

    /// Check that every scale of [`Model::scales`] is finite and within `range`, as the
    /// arithmetic `precision` ("f64" or "f32") needs. The error names the quantity (e.g.
    /// "σ_c … = inf") rather than a symptom further down (a contact at the domain's edge, a
    /// non-finite CG value).
    pub fn check_scales(
        &self,
        precision: &'static str,
        range: (f64, f64),
    ) -> Result<(), ModelError> {
        for (quantity, value) in self.scales() {
            let magnitude = value.abs();
            if !(magnitude.is_finite() && magnitude >= range.0 && magnitude <= range.1) {
                return Err(ModelError::Scale {
                    quantity,
                    value,
                    precision,
                    range,
                    advice: format!(
                        "it follows from E* = {}, Δγ = {}, the {} and the grid; \
                         rescale {E_STAR}, {WORK_OF_ADHESION} and the indenter's lengths to \
                         units nearer 1 (the normalised results do not depend on the units){}",
                        compact(self.scene.e_star),
                        compact(self.scene.work_of_adhesion),
                        self.scene.indenter.describe(),
                        if precision == "f32" {
                            format!(", or use {BACKEND} cpu with {PRECISION} f64")
                        } else {
                            String::new()
                        }
                    ),
                });
            }
        }
        Ok(())
    }

    /// Load steps the pull-off is expected to take (see [`LoadPath::expected_steps`]).
    pub fn expected_steps(&self) -> usize {
        self.load.expected_steps()
    }

    /// States the run is expected to record: a state per load step, and the detachment
    /// onsets it locates (about 150 near the minimum in the study's runs up to 2048×1024; with
    /// `--onsets all`, every ring of the front, up to about 5 per element along the grid).
    pub fn expected_states(&self) -> usize {
        let onsets = match self.onsets {
            Onsets::None => 0,
            Onsets::NearMinimum => 200,
            Onsets::All => 5 * self.nx.max(self.ny),
        };
        self.expected_steps().saturating_add(onsets)
    }

    /// The memory this model's run needs (bytes): [`BYTES_FIXED`] plus
    /// [`BYTES_PER_ELEMENT`] per element.
    pub fn memory_estimate(&self) -> u64 {
        memory_estimate(self.nx, self.ny)
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

    /// Half-extents (length) of a contact whose elements' index box is `[i_min, i_max, j_min,
    /// j_max]` (as [`crate::backend::ContactMeasure::bounds`]) along x and y: the largest |x|
    /// (|y|) reached by a contact element's outer side.
    pub fn extent_of_bounds(&self, [i0, i1, j0, j1]: [usize; 4]) -> (f64, f64) {
        let half = 0.5 * self.dx;
        (
            self.x(i0).abs().max(self.x(i1).abs()) + half,
            self.y(j0).abs().max(self.y(j1).abs()) + half,
        )
    }

    /// Carry a field (row-major, on this model's grid) over to `fine`, a re-gridded model:
    /// each element of the new grid takes the value of the element of this grid that holds
    /// its centre (`outside` where none does).
    pub fn resample<T: Copy>(&self, fine: &Model, values: &[T], outside: T) -> Vec<T> {
        let index = |x: f64, n: usize, offset: f64| {
            let k = (x / self.dx + n as f64 / 2.0 + offset).floor();
            (k >= 0.0 && k < n as f64).then_some(k as usize)
        };
        let (ox, oy) = self.apex_offset;
        let mut out = Vec::with_capacity(fine.nx * fine.ny);
        for j in 0..fine.ny {
            for i in 0..fine.nx {
                out.push(
                    match (index(fine.x(i), self.nx, ox), index(fine.y(j), self.ny, oy)) {
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
        (i as f64 + 0.5 - self.nx as f64 / 2.0 - self.apex_offset.0) * self.dx
    }

    /// y coordinate (length) of the centre of row `j`.
    pub fn y(&self, j: usize) -> f64 {
        (j as f64 + 0.5 - self.ny as f64 / 2.0 - self.apex_offset.1) * self.dx
    }

    /// What a backend for this model is built from: its grid, element size, material,
    /// profile and preconditioner.
    pub fn grid_setup(&self) -> crate::setup::GridSetup {
        crate::setup::GridSetup {
            nx: self.nx,
            ny: self.ny,
            dx: self.dx,
            e_star: self.scene.e_star,
            profile: self.profile(),
            preconditioner: self.preconditioner,
        }
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

/// The map of `scene` where it is one period of a periodic surface
/// ([`crate::scene::MeasuredSurface::on_period`]).
fn periodic_map(scene: &Scene) -> Option<&crate::scene::MeasuredSurface> {
    match scene.indenter {
        Indenter::HeightMap(ref m) if m.is_periodic() => Some(m),
        _ => None,
    }
}

/// The rows of a periodic map's domain at the element side `dx` (length, the period along x
/// over Nx): the period along y in elements, which must be a whole power of two in
/// [[`MIN_GRID`], [`MAX_GRID`]] (the periodic convolution's domain is the period along both
/// axes, with square elements), and ⟨grid_y⟩, if given, that number. The mesh must not be
/// turned: a turned grid does not repeat with the map.
fn periodic_rows(
    map: &crate::scene::MeasuredSurface,
    opt: &ModelOptions,
    mesh: &MeshAngle,
    dx: f64,
) -> Result<usize, ModelError> {
    if !mesh.is_aligned() {
        return Err(invalid(
            MESH_ANGLE,
            compact(opt.mesh_angle_deg),
            format!(
                "0 under {CONVOLUTION} periodic: the domain is the map's period, which a grid \
                 turned against the map does not repeat"
            ),
        ));
    }
    let (px, py) = map.period();
    let rows = py / dx;
    let whole = rows.round();
    let fits = (rows - whole).abs() <= 1e-6 * rows.max(1.0) && {
        let n = whole as usize;
        (MIN_GRID..=MAX_GRID).contains(&n) && n.is_power_of_two()
    };
    if !fits {
        return Err(invalid(
            GRID,
            opt.nx,
            format!(
                "under {CONVOLUTION} periodic the domain is the map's period along both axes \
                 ({} × {}), in square elements: Δx = {}/{} leaves {} elements along y, which \
                 must be a power of two from {MIN_GRID} to {MAX_GRID}; give a grid that does \
                 (the map's sides' ratio must be a power of two, and its shorter side at least \
                 {MIN_GRID} elements)",
                compact(px),
                compact(py),
                compact(px),
                opt.nx,
                crate::text::compact_digits(rows, 4),
            ),
        ));
    }
    let rows = whole as usize;
    match opt.ny {
        Some(ny) if ny != rows => Err(invalid(
            GRID_Y,
            ny,
            format!(
                "{rows} under {CONVOLUTION} periodic at {GRID} {}: the domain is the map's \
                 period along y, {} long, in elements of Δx = {} (leave it out to take that)",
                opt.nx,
                compact(py),
                compact(dx)
            ),
        )),
        _ => Ok(rows),
    }
}

/// The scene as the model places it: a height map at its apex whose first contact of c̄0
/// (with its margin, on this grid) does not fit in the map is placed on the whole map.
fn placed_on_map(scene: &Scene, opt: &ModelOptions, mesh: &MeshAngle) -> Result<Scene, ModelError> {
    let Indenter::HeightMap(ref m) = scene.indenter else {
        return Ok(scene.clone());
    };
    if m.on_window_placed() {
        return Ok(scene.clone());
    }
    let scales = scene.scales();
    let fits = scene
        .indenter
        .first_contact(
            opt.start_radius_bar * scales.length,
            scene.e_star,
            scene.work_of_adhesion,
        )
        .map(|first| {
            let (bx, by) = mesh.bounding_half_widths(first.a, first.b);
            let (ox, oy) = opt.apex_offset;
            let hx = bx * (1.0 + opt.margin);
            let dx = 2.0 * hx / opt.nx as f64;
            let hy = by * (1.0 + opt.margin) + (oy.abs() + 1.0) * dx;
            let hx = hx + ox.abs() * dx;
            (0..4).all(|k| {
                let (sx, sy) = ([1.0, -1.0][k % 2], [1.0, -1.0][k / 2]);
                let (xi, eta) = mesh.to_ellipsoid(sx * hx, sy * hy);
                scene.indenter.covers(xi.abs(), eta.abs())
            })
        })
        .unwrap_or(false);
    if fits {
        return Ok(scene.clone());
    }
    Ok(Scene {
        indenter: Indenter::HeightMap(std::sync::Arc::new(m.on_whole_map())),
        ..scene.clone()
    })
}

/// Refuse a height map whose spacing is too coarse for the contact at the force minimum
/// (fewer than [`MIN_MAP_SPACINGS_AT_MINIMUM`] spacings across its minor axis, from the
/// closed form's b̄ there); other shapes pass.
fn check_map_resolution(scene: &Scene, hint: PullOffHint) -> Result<(), ModelError> {
    let Some(spacing) = scene.indenter.map_spacing() else {
        return Ok(());
    };
    let c_r = scene.scales().length;
    let width = 2.0 * hint.b_bar_at_min * c_r;
    let at_minimum = width / spacing;
    if at_minimum >= MIN_MAP_SPACINGS_AT_MINIMUM {
        return Ok(());
    }
    Err(ModelError::MapTooCoarse {
        map: scene.indenter.describe(),
        at_minimum,
        width,
        needed_spacing: width / MIN_MAP_SPACINGS_AT_MINIMUM,
        c_r,
    })
}

/// Refuse a height map on a window of half-widths `half` (length) too small, in map
/// spacings, for any contact it could hold to be resolved: no contact is larger than the
/// window, so where even the window's mean diameter 2√(A/π) spans fewer than
/// [`MIN_MAP_SPACINGS_AT_MINIMUM`] map spacings, so does the contact at the force minimum
/// (the run's report measures that contact too). Roughness on a smooth
/// base passes (its base is the shape the contact resolves).
fn check_window_map_resolution(
    scene: &Scene,
    (half_x, half_y): (f64, f64),
) -> Result<(), ModelError> {
    let Indenter::HeightMap(ref m) = scene.indenter else {
        return Ok(());
    };
    let spacing = m.map.spacing();
    let width = 2.0 * (4.0 * half_x * half_y / std::f64::consts::PI).sqrt();
    let across = width / spacing;
    if across >= MIN_MAP_SPACINGS_AT_MINIMUM {
        return Ok(());
    }
    Err(ModelError::WindowMapTooCoarse {
        map: scene.indenter.describe(),
        across,
        width,
        needed_spacing: width / MIN_MAP_SPACINGS_AT_MINIMUM,
    })
}

/// Refuse a domain that reaches beyond the indenter's known heights (a height map's edge),
/// naming `--height-map` and what would fit.
fn check_covered(
    scene: &Scene,
    mesh: &MeshAngle,
    opt: &ModelOptions,
    (nx, ny): (usize, usize),
    dx: f64,
) -> Result<(), ModelError> {
    let (ox, oy) = opt.apex_offset;
    let hx = (0.5 * nx as f64 + ox.abs()) * dx;
    let hy = (0.5 * ny as f64 + oy.abs()) * dx;
    let (mut ex, mut ey) = (0.0f64, 0.0f64);
    for (x, y) in [(hx, hy), (hx, -hy), (-hx, hy), (-hx, -hy)] {
        let (xi, eta) = mesh.to_ellipsoid(x, y);
        ex = ex.max(xi.abs());
        ey = ey.max(eta.abs());
    }
    if scene.indenter.covers(ex, ey) {
        return Ok(());
    }
    let param = match scene.indenter {
        Indenter::Rough(_) => ROUGHNESS,
        _ => HEIGHT_MAP,
    };
    Err(invalid(
        param,
        scene.indenter.describe(),
        format!(
            "the domain (±{} × ±{} about the apex, the first contact of c̄0 = {} and its margin) \
             reaches beyond the map: use a larger map, or a smaller {START_RADIUS} or {MARGIN}",
            compact(ex),
            compact(ey),
            compact(opt.start_radius_bar)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn kappa_matches_spec_value() {
        assert!((kappa() - 0.473201).abs() < 1e-6);
    }

    #[test]
    fn critical_stress_balances_energy() {
        // ½ σ_c² Δx³ · 2κ/E* = Δγ Δx²  (physics §5).
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
            assert!(
                matches!(e, ModelError::Grid { param, .. } if param == GRID),
                "{e}"
            );
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
            assert!(
                matches!(e, ModelError::Invalid { param, .. } if param == MESH_ANGLE),
                "{e}"
            );
        }
    }

    #[test]
    fn rotated_profile_is_the_rotated_quadratic_form() {
        // h = ½ xᵀ M x with M = Rᵀ diag(1/R1, 1/R2) R, written out element by element.
        let m = rotated(5.0, 64, 30.0);
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let (r1, r2) = m.scene.indenter.radii().unwrap();
        let (k1, k2) = (1.0 / r1, 1.0 / r2);
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

    #[test]
    fn scales_out_of_range_are_diagnosed_by_their_cause() {
        // Before: E* = 1e300 (σ_c = ∞) failed later as "the contact reached the edge of the
        // domain", and E* = 1e-300 as "CG produced a non-finite value". The CLI's input ranges
        // refuse those values; a scene built past them is refused here, naming σ_c.
        let s = Scene {
            indenter: crate::scene::Indenter::ellipsoid(1.0, 1.0),
            e_star: 1e300,
            work_of_adhesion: 1.0,
        };
        let e = Model::build(
            &s,
            &ModelOptions {
                nx: 64,
                ..Default::default()
            },
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("σ_c") && e.contains("inf"), "{e}");
        // Inputs within their ranges whose scales f32 cannot hold: refused for the GPU only.
        let s = Scene::new(1e-20, 1e-20, 1e25, 1e-25).unwrap();
        let m = Model::build(
            &s,
            &ModelOptions {
                nx: 64,
                ..Default::default()
            },
        )
        .unwrap();
        assert!(m.check_scales("f64", F64_SAFE_RANGE).is_ok());
        let e = m
            .check_scales("f32", F32_SAFE_RANGE)
            .unwrap_err()
            .to_string();
        let e = crate::params::words::flags(&e);
        assert!(e.contains("f32") && e.contains("--backend cpu"), "{e}");
    }

    #[test]
    fn too_coarse_grids_are_refused_with_the_grid_that_resolves_them() {
        // Before: R1/R2 = 1000 on 64 columns ran with 2 elements across the contact, and
        // c̄0 = 1e12 with none at all.
        let s = Scene::from_ratio(1000.0, 1.0, 1.0, 1.0).unwrap();
        let e = Model::build(
            &s,
            &ModelOptions {
                nx: 64,
                ..Default::default()
            },
        )
        .unwrap_err();
        assert!(matches!(e, ModelError::TooCoarse { .. }), "{e}");
        let text = crate::params::words::flags(&e.to_string());
        let suggested: usize = text
            .split("use --grid ")
            .nth(1)
            .and_then(|r| r.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .expect("a suggested grid");
        assert!(Model::build(
            &s,
            &ModelOptions {
                nx: suggested,
                ..Default::default()
            }
        )
        .is_ok());
        assert!(Model::build(
            &s,
            &ModelOptions {
                nx: suggested / 2,
                ..Default::default()
            }
        )
        .is_err());
    }
}
