//! The summary of a run: the adhesive force and where it occurred, beside the closed-form
//! value, with what the run cost. Printed for people, written as JSON for scripts.

use super::OutputError;
use crate::analysis::convergence;
use crate::model::{Model, Stepping};
use crate::solver::{protocol::RegridEvent, Outcome};
use crate::text::fixed;
use crate::theory::{self, TheoryModel};
use serde::Serialize;
use std::path::Path;

/// Summary of one pull-off run.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// R1/R2 (dimensionless).
    pub ratio: f64,
    /// Adhesive force |min F̄| (dimensionless); null if the run did not reach the force
    /// minimum (`min_reached` false).
    pub f_ad_bar: Option<f64>,
    /// Whether the run reached the force minimum: after it the contact jumped off, or the
    /// approach went 0.1 past it with the force 2 % above it (`Outcome::min_reached`). When
    /// false, no adhesive force is reported and `lowest_f_bar` is only the lowest force seen.
    pub min_reached: bool,
    /// The lowest F̄ recorded (dimensionless; on the last grid after re-grids), whether or not
    /// it is the minimum; null if no state was recorded.
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
    /// Elements across the contact's minor axis at the force minimum (2 b / Δx; the diameter
    /// for a sphere).
    pub n_d: Option<f64>,
    /// Name of the closed form compared with ("jkr" or "jg").
    pub reference_model: &'static str,
    /// Its adhesive force |min F̄| (dimensionless).
    pub reference_f_ad_bar: Option<f64>,
    /// Relative error of f_ad_bar against the reference (dimensionless, signed).
    pub relative_error: Option<f64>,
    /// Elements along x.
    pub nx: usize,
    /// Elements along y.
    pub ny: usize,
    /// Element side Δx (length).
    pub dx: f64,
    /// Angle between the ellipsoid's major axis and the grid's x axis (degrees).
    pub mesh_angle_deg: f64,
    /// Detachment stress σ_c (force/length²).
    pub sigma_c: f64,
    /// Backend that ran the solver.
    pub backend: String,
    /// Arithmetic precision of the backend.
    pub precision: String,
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
    /// Where the states were written.
    pub states_csv: String,
    /// Element side Δx at the force minimum (length; differs from `dx` after re-grids).
    pub dx_at_min: Option<f64>,
    /// The grid changes made during the run.
    pub regrids: Vec<RegridEvent>,
    /// Whether the run stopped once the force minimum was confirmed (--measure adhesive-force).
    pub stopped_after_minimum: bool,
    /// Warnings about the result (CG retries and states accepted above the CG tolerance, too
    /// coarse a grid, too large load steps); empty for a healthy run.
    pub warnings: Vec<String>,
}

/// `v` with `decimals` decimals and its sign ("+2.05", "-0.31"), never "-0.00".
fn signed(v: f64, decimals: usize) -> String {
    let s = fixed(v, decimals);
    if s.starts_with('-') {
        s
    } else {
        format!("+{s}")
    }
}

/// With [`Stepping::Fixed`], a warning if the steps around the force minimum detached
/// elements: the minimum then lies at an onset inside a step, which whole steps do not see.
fn step_warning(model: &Model, outcome: &Outcome) -> Option<String> {
    if model.stepping != Stepping::Fixed {
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
            "load steps too large to resolve the force minimum: with --stepping fixed, one step \
             (Δd̄ = {:.4}) around it detached {lost} elements and changed F̄ by {:.1} % of |min F̄|, \
             so the minimum lies at an onset inside a step; use --stepping adaptive (the \
             default), which refines every step to its onsets",
            model.d_step / model.scene.scales().approach,
            100.0 * jump / f_min
        )
    })
}

impl Summary {
    /// Summarise an outcome.
    pub fn new(
        model: &Model,
        outcome: &Outcome,
        backend: (&str, &str),
        wall_s: f64,
        states_csv: &Path,
    ) -> Self {
        let ratio = model.scene.ratio();
        let which = TheoryModel::adhesive_reference(ratio);
        let name = which.name();
        let reference = theory::pull_off(which, ratio)
            .ok()
            .map(|p| -p.force_min.f_bar);
        let lowest = outcome.force_minimum();
        let min_reached = outcome.min_reached();
        let min = lowest.filter(|_| min_reached);
        let f_ad = min.map(|s| -s.f_bar);
        // 2b/Δx is a count of elements (half-integers on an aligned mesh): rounded to 1e-6 so
        // that it does not read 25.999999999999996.
        let n_d = min.map(|s| (2e6 * s.b_axis / s.dx).round() / 1e6);
        let warnings = n_d
            .and_then(|n| convergence::coarse_grid_warning(ratio, n))
            .into_iter()
            .chain(step_warning(model, outcome))
            .chain(outcome.warnings.iter().cloned())
            .collect();
        Summary {
            ratio,
            f_ad_bar: f_ad,
            min_reached,
            lowest_f_bar: lowest.map(|s| s.f_bar),
            d_bar_at_lowest: lowest.map(|s| s.d_bar),
            c_bar_at_min: min.map(|s| s.c_bar),
            d_bar_at_min: min.map(|s| s.d_bar),
            a_bar_at_min: min.map(|s| s.a_bar),
            b_bar_at_min: min.map(|s| s.b_bar),
            n_d,
            reference_model: name,
            reference_f_ad_bar: reference,
            relative_error: f_ad.zip(reference).map(|(f, r)| f / r - 1.0),
            nx: model.nx,
            ny: model.ny,
            dx: model.dx,
            mesh_angle_deg: model.mesh.degrees,
            sigma_c: model.sigma_c,
            backend: backend.0.to_string(),
            precision: backend.1.to_string(),
            cg_iterations: outcome.cg_iterations(),
            cg_residual_max: outcome.worst_cg_residual(),
            cg_retries: outcome.cg_retries.len(),
            states: outcome.states.len(),
            wall_s,
            complete: outcome.complete(),
            error: outcome.error.as_ref().map(|e| e.to_string()),
            states_csv: states_csv.display().to_string(),
            dx_at_min: min.map(|s| s.dx),
            regrids: outcome.regrids.clone(),
            stopped_after_minimum: outcome.stopped_after_minimum,
            warnings,
        }
    }

    /// Write as pretty JSON.
    pub fn write_json(&self, path: &Path) -> Result<(), OutputError> {
        let text = serde_json::to_string_pretty(self).expect("a summary always serialises");
        super::file::write_bytes(path, (text + "\n").as_bytes())
    }

    /// Human-readable lines.
    pub fn to_text(&self) -> String {
        let opt = |v: Option<f64>, p: usize| v.map_or("—".into(), |x| fixed(x, p));
        let mut s = String::new();
        if self.min_reached {
            s += &format!(
                "adhesive force |min F̄| = {}  ({} value {}, error {})\n",
                opt(self.f_ad_bar, 4),
                self.reference_model.to_uppercase(),
                opt(self.reference_f_ad_bar, 4),
                self.relative_error
                    .map_or("—".into(), |e| format!("{} %", signed(100.0 * e, 2)))
            );
            s += &format!(
                "  at c̄ = {}, d̄ = {}, ā = {}, b̄ = {}\n",
                opt(self.c_bar_at_min, 4),
                opt(self.d_bar_at_min, 4),
                opt(self.a_bar_at_min, 4),
                opt(self.b_bar_at_min, 4)
            );
        } else {
            let seen = match (self.lowest_f_bar, self.d_bar_at_lowest) {
                (Some(f), Some(d)) => format!(
                    "the lowest F̄ recorded is {} at d̄ = {}, and the force had not turned after it",
                    fixed(f, 4),
                    fixed(d, 4)
                ),
                _ => "no state was recorded".to_string(),
            };
            let why = if self.complete {
                "the run stopped at its final approach: lower --final-d (or leave it out) to \
                 pass the minimum"
            } else {
                "the run stopped early (see INCOMPLETE below)"
            };
            s += &format!(
                "NO ADHESIVE FORCE: the run did not reach the force minimum; {seen}; {why}\n"
            );
        }
        let angle = if self.mesh_angle_deg == 0.0 {
            String::new()
        } else {
            format!(" turned by {}°", self.mesh_angle_deg)
        };
        s += &format!(
            "grid {}×{}{angle}, Δx = {:.5e}, σ_c = {:.5e}, {} elements across the minor axis at pull-off\n",
            self.nx,
            self.ny,
            self.dx,
            self.sigma_c,
            opt(self.n_d, 0)
        );
        if !self.regrids.is_empty() {
            s += &format!(
                "Δx at the force minimum {} after {} re-grid(s)\n",
                self.dx_at_min.map_or("—".into(), |v| format!("{v:.5e}")),
                self.regrids.len()
            );
        }
        s += &format!(
            "{} backend ({}), {} states, {} CG iterations, {:.2} s\n",
            self.backend, self.precision, self.states, self.cg_iterations, self.wall_s
        );
        if self.cg_retries > 0 {
            s += &format!(
                "CG: {} solve(s) retried in the safer mode, worst relative residual {} \
                 (warnings on stderr)\n",
                self.cg_retries,
                self.cg_residual_max
                    .map_or("—".into(), |r| format!("{r:.2e}"))
            );
        }
        for r in &self.regrids {
            s += &format!(
                "re-gridded at d̄ = {:.4}: Δx {:.4e} → {:.4e}\n",
                r.d_bar, r.dx_from, r.dx_to
            );
        }
        if self.stopped_after_minimum {
            s += "stopped once the force minimum was confirmed (--measure adhesive-force)\n";
        }
        for w in &self.warnings {
            s += &format!("WARNING: {w}\n");
        }
        if let Some(e) = &self.error {
            s += &format!("INCOMPLETE: {e}\n");
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::ModelOptions;
    use crate::scene::Scene;
    use crate::solver::{Phase, State};

    fn state(model: &Model, force: f64, b_elements: f64, n_contact: usize) -> State {
        let dx = model.dx;
        State {
            step: 1,
            phase: Phase::Pulloff,
            d: 0.0,
            force,
            area: 1.0,
            mean_radius: 1.0,
            a_axis: b_elements * dx,
            b_axis: b_elements * dx,
            n_contact,
            cg_iterations: 1,
            detach_sweeps: 0,
            d_bar: 0.0,
            f_bar: force,
            c_bar: 0.8,
            a_bar: 0.8,
            b_bar: 0.8,
            cg_residual: 1e-9,
            dx,
        }
    }

    fn outcome(states: Vec<State>) -> Outcome {
        Outcome {
            states,
            error: None,
            regrids: Vec::new(),
            stopped_after_minimum: false,
            cg_retries: Vec::new(),
            warnings: Vec::new(),
        }
    }

    #[test]
    fn n_d_is_a_count_of_elements_without_round_off() {
        // Before: n_d = 2 b / Δx came out as 25.999999999999996.
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        let k = (1..200)
            .map(f64::from)
            .find(|k| 2.0 * (k * model.dx) / model.dx != 2.0 * k)
            .expect("some count has round-off in 2 k Δx / Δx");
        let min = state(&model, -1.0, k, 100);
        let gone = state(&model, -0.3, 0.0, 0);
        let s = Summary::new(
            &model,
            &outcome(vec![min, gone]),
            ("cpu", "f64"),
            0.0,
            Path::new("s.csv"),
        );
        assert!(s.min_reached);
        assert_eq!(s.n_d, Some(2.0 * k));
    }

    #[test]
    fn without_a_minimum_there_is_no_adhesive_force_line() {
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: 32,
                ..ModelOptions::default()
            },
        )
        .unwrap();
        // The force still falls at the last state.
        let states = vec![state(&model, -0.2, 10.0, 80), state(&model, -0.49, 9.0, 70)];
        let s = Summary::new(
            &model,
            &outcome(states),
            ("cpu", "f64"),
            0.0,
            Path::new("s.csv"),
        );
        assert!(!s.min_reached);
        assert_eq!(s.f_ad_bar, None);
        assert_eq!(s.lowest_f_bar, Some(-0.49));
        let text = s.to_text();
        assert!(!text.contains("adhesive force |min F̄|"), "{text}");
        assert!(text.contains("NO ADHESIVE FORCE"), "{text}");
        assert!(!text.contains("-0.0000"), "{text}");
    }
}
