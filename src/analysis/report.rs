//! What one pull-off found, as numbers: its force minimum and where it lies, its grid, what it
//! cost and what to warn about. Built from a model and its outcome; `output` only writes it.

use super::convergence;
use crate::model::{Model, Onsets, MIN_MAP_SPACINGS_AT_MINIMUM};
use crate::params::{ONSETS, SPACING};
use crate::solver::cost::CostAccount;
use crate::solver::protocol::Confirmation;
use crate::solver::window::Refinement;
use crate::solver::State;
use crate::solver::{state::RegridEvent, Outcome};
use crate::text::compact;
use serde::Serialize;
use std::path::Path;

/// One run's report (normalised quantities per physics §2).
#[derive(Debug, Clone, PartialEq, Serialize, serde::Deserialize)]
pub struct RunReport {
    /// The indenter's shape ("ellipsoid", "power-law", "flat-punch"); "ellipsoid" in reports
    /// written before it was recorded.
    #[serde(default = "ellipsoid")]
    pub indenter: String,
    /// R1/R2 (dimensionless; 1 for the axisymmetric indenters).
    pub ratio: f64,
    /// The grid, "Nx×Ny".
    pub grid: String,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side Δx at the start (length).
    pub dx: f64,
    /// The domain's free margin around the initial contact (relative to its half-axes); 0.08,
    /// the default, in reports written before it was recorded.
    #[serde(default = "default_margin")]
    pub margin: f64,
    /// Element side Δx at the force minimum (length; smaller than `dx` after re-grids).
    pub dx_at_min: Option<f64>,
    /// Angle between the ellipsoid's major axis and the grid's x axis (degrees).
    pub mesh_angle_deg: f64,
    /// The apex's position within the element grid (fractions of an element along x, y).
    pub apex_offset: [f64; 2],
    /// Detachment stress σ_c at the start (force/length²).
    pub sigma_c: f64,
    /// |min F̄| on this grid (dimensionless); null if the run did not reach the minimum.
    pub f_ad_bar: Option<f64>,
    /// Whether the run reached the force minimum: after it the contact jumped off, or the
    /// approach went 0.1 past it with the force 2 % above it. When false, `f_ad_bar` is null
    /// and `lowest_f_bar` is only the lowest force seen.
    pub min_reached: bool,
    /// Whether the force minimum is resolved: false where whole load steps (`--onsets none`)
    /// detached elements around it, so that the minimum lies at an onset inside a step and
    /// the lowest state seen is not it. No adhesive force is estimated from such a run.
    #[serde(default = "resolved")]
    pub min_resolved: bool,
    /// Why the adhesive force is withheld although the run reached the force minimum: a
    /// contact front straight along the grid (see `straight_front_share`), a height map too
    /// coarse for the contact there (fewer than [`crate::model::MIN_MAP_SPACINGS_AT_MINIMUM`]
    /// map spacings across it), or a minimum that is not tensile (the indenter never pulled);
    /// several joined by "; and ". `f_ad_bar` is then null.
    /// Absent where nothing is withheld.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub withheld: Option<String>,
    /// Whether the force minimum lies at the first onsets of a pinned contact: the contact
    /// the pull-off began with (a small preload's) was narrower than the receding branch's
    /// contact at its minimum (the closed form's), so the minimum is where that contact starts
    /// to come off, not one a receding front reached. The ellipsoid's convergence law, fitted to the latter, does not
    /// apply to it, nor do the closed forms of that branch (JKR's). Never set for a flat
    /// punch, whose edge pins every contact.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub min_pinned: bool,
    /// For a measured surface: the share of the contact's edge at the force minimum that runs
    /// straight along a grid axis or diagonal ([`super::fronts`]; dimensionless, 0–1). From
    /// [`super::fronts::STRAIGHT_SHARE_LIMIT`] on, the answer is withheld: the criterion pins
    /// such fronts. Absent for the smooth shapes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub straight_front_share: Option<f64>,
    /// The lowest F̄ recorded (dimensionless), minimum or not; null if no state was recorded.
    pub lowest_f_bar: Option<f64>,
    /// d̄ of that state.
    pub d_bar_at_lowest: Option<f64>,
    /// c̄ at the force minimum.
    pub c_bar_at_min: Option<f64>,
    /// d̄ at the force minimum.
    pub d_bar_at_min: Option<f64>,
    /// ā at the force minimum.
    pub a_bar_at_min: Option<f64>,
    /// b̄ at the force minimum.
    pub b_bar_at_min: Option<f64>,
    /// Elements across the contact's minor axis at the force minimum (2b/Δx; the diameter for
    /// a sphere).
    pub n_d: Option<f64>,
    /// Backend that ran the solver ("cpu", "gpu").
    pub backend: String,
    /// Its arithmetic ("f64", "f32").
    pub precision: String,
    /// The device it ran on (the CPU model and threads, or the GPU adapter), where recorded.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub device: Option<String>,
    /// CG iterations over the run.
    pub cg_iterations: usize,
    /// The largest relative CG residual of any state, recomputed from p (dimensionless).
    pub cg_residual_max: Option<f64>,
    /// CG solves that needed the safer retry.
    pub cg_retries: usize,
    /// States recorded.
    pub states: usize,
    /// Wall time of the solve (s).
    pub wall_s: f64,
    /// Whether the protocol ran to its end.
    pub complete: bool,
    /// Why it did not, if it did not.
    pub error: Option<String>,
    /// Where the states were written; null for a run kept in memory only.
    #[serde(default)]
    pub states_csv: Option<String>,
    /// The grid changes made during the run.
    pub regrids: Vec<RegridEvent>,
    /// Whether the run stopped once the force minimum was confirmed (adhesive-force measure).
    pub stopped_after_minimum: bool,
    /// How the force minimum was confirmed; null where it was not reached, and in reports
    /// written before it was recorded.
    #[serde(default)]
    pub confirmation: Option<Confirmation>,
    /// Warnings about this run (CG retries and states accepted above the CG tolerance, too
    /// coarse a grid, too large load steps); empty for a healthy run.
    pub warnings: Vec<String>,
    /// Which detachment onsets the run located ("near-minimum", "all", "none"); null in
    /// reports written before it was recorded.
    #[serde(default)]
    pub onsets: Option<String>,
    /// Where the run spent its work: states, steps, onsets, cascade rounds, solves, CG
    /// iterations and convolutions outside CG, in all and per c̄ band; null in reports
    /// written before it was recorded.
    #[serde(default)]
    pub cost: Option<CostAccount>,
    /// Which load steps had their onsets located and the check that they hold the force
    /// minimum (`--onsets near-minimum`); null otherwise.
    #[serde(default)]
    pub refinement: Option<Refinement>,
}

/// The indenter of a report written before [`RunReport::indenter`] existed.
fn ellipsoid() -> String {
    "ellipsoid".to_string()
}

/// Whether a report's indenter is the ellipsoid (the shape the convergence law is for).
pub fn is_ellipsoid(run: &RunReport) -> bool {
    run.indenter == "ellipsoid"
}

/// A report written before [`RunReport::min_resolved`] existed had its minimum resolved.
fn resolved() -> bool {
    true
}

/// The margin of a report written before [`RunReport::margin`] existed: the default.
fn default_margin() -> f64 {
    crate::model::ModelOptions::default().margin
}

impl RunReport {
    /// The report of `outcome`, a run of `model` on `backend` (name, precision) that took
    /// `wall_s` seconds and wrote its states to `states_csv` (`None`: kept in memory only).
    pub fn new(
        model: &Model,
        outcome: &Outcome,
        backend: (&str, &str),
        wall_s: f64,
        states_csv: Option<&Path>,
    ) -> Self {
        let ratio = model.scene.ratio();
        let lowest = outcome.force_minimum();
        let min_reached = outcome.min_reached();
        let min = lowest.filter(|_| min_reached);
        // 2b/Δx is a count of elements (half-integers on an aligned mesh): rounded to 1e-6 so
        // that it does not read 25.999999999999996.
        let n_d = min.map(|s| (2e6 * s.b_axis / s.dx).round() / 1e6);
        // A re-grid keeps the element counts: the minimum's mask is nx × ny.
        let (nx, ny) = (model.nx, model.ny);
        let fronts = outcome
            .contact_at_minimum()
            .filter(|mask| mask.len() == nx * ny)
            .and_then(|mask| super::fronts::straight_fronts(mask, nx, ny));
        // Every reason to withhold, the one refining cannot mend first.
        let withheld = min.and_then(|s| {
            let why: Vec<String> = [
                fronts.filter(|f| f.decide()).map(straight_fronts_withheld),
                map_too_coarse(model, s),
                compressive_minimum(s),
            ]
            .into_iter()
            .flatten()
            .collect();
            (!why.is_empty()).then(|| why.join("; and "))
        });
        // A flat punch's contact is pinned by its edge: its minimum is always that onset.
        let punch = matches!(model.scene.indenter, crate::scene::Indenter::FlatPunch(_));
        let min_pinned = !punch && min.is_some_and(|m| pinned_at(model, outcome, m));
        let unresolved = step_warning(model, outcome);
        let min_resolved = unresolved.is_none();
        let warnings = n_d
            .filter(|_| model.scene.is_ellipsoid() && !min_pinned)
            .and_then(|n| convergence::coarse_grid_warning(ratio, n))
            .into_iter()
            .chain(unresolved)
            .chain(withheld.clone())
            .chain(
                (min_pinned && model.scene.is_ellipsoid() && withheld.is_none())
                    .then(pinned_warning),
            )
            .chain(outcome.warnings.iter().cloned())
            .collect();
        RunReport {
            indenter: model.scene.indenter.name().to_string(),
            ratio,
            grid: format!("{}×{}", model.nx, model.ny),
            nx: model.nx,
            ny: model.ny,
            dx: model.dx,
            margin: model.margin,
            dx_at_min: min.map(|s| s.dx),
            mesh_angle_deg: model.mesh.degrees,
            apex_offset: [model.apex_offset.0, model.apex_offset.1],
            sigma_c: model.sigma_c,
            f_ad_bar: min.filter(|_| withheld.is_none()).map(|s| -s.f_bar),
            min_reached,
            min_resolved,
            withheld,
            straight_front_share: fronts.map(|f| f.share),
            min_pinned,
            lowest_f_bar: lowest.map(|s| s.f_bar),
            d_bar_at_lowest: lowest.map(|s| s.d_bar),
            c_bar_at_min: min.map(|s| s.c_bar),
            d_bar_at_min: min.map(|s| s.d_bar),
            a_bar_at_min: min.map(|s| s.a_bar),
            b_bar_at_min: min.map(|s| s.b_bar),
            n_d,
            backend: backend.0.to_string(),
            precision: backend.1.to_string(),
            device: None,
            cg_iterations: outcome.cg_iterations(),
            cg_residual_max: outcome.worst_cg_residual(),
            cg_retries: outcome.cg_retries.len(),
            states: outcome.states.len(),
            wall_s,
            complete: outcome.complete(),
            error: outcome.error.as_ref().map(|e| e.to_string()),
            states_csv: states_csv.map(|p| p.display().to_string()),
            regrids: outcome.regrids.clone(),
            stopped_after_minimum: outcome.stopped_after_minimum,
            confirmation: outcome.confirmation(),
            warnings,
            onsets: Some(model.onsets.name().to_string()),
            cost: Some(outcome.cost.clone()),
            refinement: outcome.refinement.clone(),
        }
    }

    /// Δx at the force minimum in units of c_r (dimensionless): the variable the adhesive
    /// force converges in.
    pub fn dx_bar_at_min(&self, length_scale: f64) -> Option<f64> {
        self.dx_at_min.map(|dx| dx / length_scale)
    }
}

/// For a height map, why its force minimum `at_min` cannot be trusted: the contact there spans
/// fewer than [`MIN_MAP_SPACINGS_AT_MINIMUM`] map spacings, so the solver worked on the map's
/// facets (the checks before the run predict this, from the closed form at the apex and from
/// the window's size on a window; this one measures it). At the apex the width is the
/// contact's minor axis 2b; on a window, where the contact may lie anywhere and in patches,
/// its mean diameter 2√(A/π). `None` where the map resolves it, and for the other shapes.
fn map_too_coarse(model: &Model, at_min: &State) -> Option<String> {
    // A rough shape's map is roughness on a smooth base, the shape the contact resolves.
    if matches!(model.scene.indenter, crate::scene::Indenter::Rough(_)) {
        return None;
    }
    let spacing = model.scene.indenter.map_spacing()?;
    let (width, measure) = if model.scene.window_half().is_some() {
        (2.0 * at_min.mean_radius, "its mean diameter 2√(A/π)")
    } else {
        (2.0 * at_min.b_axis, "its minor axis, 2b")
    };
    let across = width / spacing;
    (across < MIN_MAP_SPACINGS_AT_MINIMUM).then(|| {
        format!(
            "height map too coarse for its contact: at the force minimum the contact spans \
             {across:.1} map spacings across ({measure} = {}; at least \
             {MIN_MAP_SPACINGS_AT_MINIMUM} are needed), so the solver worked on the map's flat \
             facets instead of the surface's shape: the adhesive force is withheld; give a map \
             of {SPACING} {} or finer over the same area",
            compact(width),
            compact(width / MIN_MAP_SPACINGS_AT_MINIMUM)
        )
    })
}

/// Whether the force minimum `at_min` of `outcome` lies at the first onsets of the contact
/// the pull-off began with, not on the receding branch: that contact (the pull-off's first
/// state on the minimum's grid) is narrower than the receding branch's contact at its
/// minimum (the closed form's b̄ there), which a front that only recedes cannot reach. `None`
/// of the closed form (a height map): not known, so not pinned.
fn pinned_at(model: &Model, outcome: &Outcome, at_min: &State) -> bool {
    let scene = &model.scene;
    let Some(hint) = scene
        .indenter
        .pull_off_hint(scene.e_star, scene.work_of_adhesion)
    else {
        return false;
    };
    outcome
        .states
        .iter()
        .find(|s| s.dx == at_min.dx && !s.phase.is_loading())
        .is_some_and(|start| start.b_bar < hint.b_bar_at_min)
}

/// What a pinned force minimum of the ellipsoid means for its answer.
fn pinned_warning() -> String {
    "the force minimum lies at the first onset of a pinned contact (the contact the pull-off \
     began with, after a small preload, is narrower than the receding branch's contact at its \
     minimum, so no front recedes to that minimum): the convergence law, fitted to minima a \
     receding front reaches, does not apply, so no estimate with an uncertainty is made from \
     this run; its discretisation error is of first order in Δx (refine the grid to see it \
     converge), and JKR's 1/2 and Johnson–Greenwood are of the other branch"
        .to_string()
}

/// Why an answer decided by straight fronts along the grid is withheld.
fn straight_fronts_withheld(f: super::fronts::StraightFronts) -> String {
    format!(
        "the contact's front at the force minimum runs straight along the grid: {:.0} % of its \
         edge ({} element faces) lies in straight runs of {} elements or more along a grid axis \
         or diagonal; the detachment criterion pins such fronts (along an axis its energy \
         release rate converges to 1.82 Δγ, not Δγ: Johnson's wave comes out +50 %, turned by \
         45° +21 %, and refining the grid does not help; docs/failures.md), so the answer is \
         biased high by far more than any uncertainty it could state: the adhesive force is \
         withheld (the grid's lowest F̄ is in the states)",
        100.0 * f.share,
        f.edge,
        f.min_run
    )
}

/// Why a force minimum that is not tensile gives no adhesive force: the indenter never pulled
/// on the surface (F̄ > 0 at the lowest force), so |min F̄| would be negative. A healthy
/// adhesive run always pulls; this guards the answer against a broken one. `None` for a
/// tensile minimum.
fn compressive_minimum(at_min: &State) -> Option<String> {
    (at_min.f_bar > 0.0).then(|| {
        format!(
            "the lowest force reached is compressive (F̄ = {}): the indenter never pulled on \
             the surface, so there is no adhesive force to state: it is withheld",
            compact(at_min.f_bar)
        )
    })
}

/// With [`Onsets::None`], a warning if the steps around the force minimum detached
/// elements: the minimum then lies at an onset inside a step, which whole steps do not see.
fn step_warning(model: &Model, outcome: &Outcome) -> Option<String> {
    if model.onsets != Onsets::None {
        return None;
    }
    let states = &outcome.states;
    let k = states
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.force.total_cmp(&b.1.force))?
        .0;
    let around = &states[k.saturating_sub(1)..(k + 2).min(states.len())];
    let lost = around
        .windows(2)
        .map(|w| w[0].n_contact.saturating_sub(w[1].n_contact))
        .max()
        .unwrap_or(0);
    let jump = around
        .windows(2)
        .map(|w| (w[1].f_bar - w[0].f_bar).abs())
        .fold(0.0, f64::max);
    let f_min = states[k].f_bar.abs();
    (lost > 0).then(|| {
        format!(
            "load steps too large to resolve the force minimum: with {ONSETS} none, one step \
             (Δd̄ = {:.4}) around it detached {lost} elements and changed F̄ by {:.1} % of |min F̄|, \
             so the minimum lies at an onset inside a step; use {ONSETS} near-minimum (the \
             default), which locates the onsets of every step that can hold the minimum",
            model.load.d_step / model.scene.scales().approach,
            100.0 * jump / f_min
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ModelOptions;
    use crate::scene::height_map::HeightMap;
    use crate::scene::{Indenter, MeasuredSurface, Scene};
    use std::sync::Arc;

    /// A model of the sphere (x² + y²)/2 given as a 161 × 161 map of spacing 0.05 (length),
    /// E* = Δγ = 1: the contact at the force minimum is predicted about 61 spacings wide.
    fn sphere_map_model() -> Model {
        let (n, s) = (161usize, 0.05);
        let c = (n - 1) as f64 / 2.0;
        let heights = (0..n * n)
            .map(|k| {
                let (x, y) = (((k % n) as f64 - c) * s, ((k / n) as f64 - c) * s);
                0.5 * (x * x + y * y)
            })
            .collect();
        let map = HeightMap::new(n, n, s, heights).unwrap();
        let surface = MeasuredSurface::new(map, "sphere").unwrap();
        let scene = Scene::with_indenter(Indenter::HeightMap(Arc::new(surface)), 1.0, 1.0).unwrap();
        Model::build(&scene, &ModelOptions::default()).unwrap()
    }

    #[test]
    fn a_height_map_too_coarse_for_the_measured_contact_withholds_the_answer() {
        let model = sphere_map_model();
        // A contact 2b = 0.5 wide spans 10 map spacings: withheld, saying why and what helps.
        let narrow = State {
            b_axis: 0.25,
            ..State::default()
        };
        let why = map_too_coarse(&model, &narrow).expect("10 spacings are too few");
        assert!(
            why.contains("10.0 map spacings") && why.contains("withheld"),
            "{why}"
        );
        assert!(
            why.contains(&format!("{SPACING} 0.03125 or finer")),
            "{why}"
        );
        // 2b = 1 spans 20: the answer stands.
        let wide = State {
            b_axis: 0.5,
            ..State::default()
        };
        assert_eq!(map_too_coarse(&model, &wide), None);
    }

    #[test]
    fn a_compressive_minimum_is_no_adhesive_force() {
        let pushing = State {
            f_bar: 0.25,
            ..State::default()
        };
        let why = compressive_minimum(&pushing).expect("a compressive minimum is withheld");
        assert!(
            why.contains("compressive") && why.contains("withheld"),
            "{why}"
        );
        let pulling = State {
            f_bar: -0.5,
            ..State::default()
        };
        assert_eq!(compressive_minimum(&pulling), None);
    }

    #[test]
    fn other_shapes_are_not_judged_as_maps() {
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(&scene, &ModelOptions::default()).unwrap();
        let tiny = State {
            b_axis: 1e-9,
            ..State::default()
        };
        assert_eq!(map_too_coarse(&model, &tiny), None);
    }
}
