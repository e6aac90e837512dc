//! The summary of an adhesive-force request, one shape for every run (one grid or several):
//! the best estimate of |min F̄| with its uncertainty, where the minimum lies, the requested
//! accuracy, the closed forms as comparisons, and every run. Printed for people, written as
//! JSON for scripts. Every number comes from `analysis`; this module only lays it out.
//!
//! Its messages (warnings, a run's error, what was withheld) and its text name parameters by
//! their marker (`⟨steps⟩`): in memory, a [`Summary`] is every front end's, and each words it
//! (the command line as flags, Python as keywords); the JSON file ([`Summary::write_json`]) is
//! the command line's, worded as flags as it is written, as is every text file the library
//! writes ([`write_text`](super::file::write_text)). A summary read back from its file (a run
//! that `reference` or `coverage` reuses) names flags.

use super::OutputError;
use crate::analysis::estimate::AdhesiveResult;
use crate::analysis::generic_limit::GenericLimit;
use crate::analysis::report::RunReport;
use crate::params::{FINAL_D, MEASURE, ONSETS, STEPS};
use crate::text::fixed;
use serde::Serialize;
use std::path::Path;

/// The summary (see "The summary" in docs/commands.md for every field).
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// R1/R2 (dimensionless).
    pub ratio: f64,
    /// "single-grid" or "extrapolated"; null if no run reached the force minimum.
    pub estimate: Option<&'static str>,
    /// The best estimate of the adhesive force |min F̄| at Δx → 0 (dimensionless).
    pub f_ad_bar: Option<f64>,
    /// Half-width of the interval stated to hold the Δx → 0 limit (absolute).
    pub f_ad_bar_uncertainty: Option<f64>,
    /// One grid: how much its own |min F̄| exceeds the estimate (positive: it over-predicts).
    pub f_ad_bar_bias: Option<f64>,
    /// c̄ at the force minimum (best estimate).
    pub c_bar_at_min: Option<f64>,
    /// Its uncertainty (absolute).
    pub c_bar_at_min_uncertainty: Option<f64>,
    /// d̄ at the force minimum (best estimate).
    pub d_bar_at_min: Option<f64>,
    /// Its uncertainty (absolute).
    pub d_bar_at_min_uncertainty: Option<f64>,
    /// How the estimate was made, in words.
    pub method: Option<String>,
    /// The requested relative accuracy (`--accuracy`), if any.
    pub target: Option<f64>,
    /// Whether the estimate's relative uncertainty is within the target.
    pub target_met: Option<bool>,
    /// Johnson–Greenwood's |min F̄| (a comparison, not a reference).
    pub jg_f_ad_bar: Option<f64>,
    /// f_ad_bar / jg_f_ad_bar − 1: the deviation from JG (dimensionless, signed).
    pub jg_deviation: Option<f64>,
    /// For the sphere: f_ad_bar / 0.5 − 1, the error against JKR's exact value.
    pub jkr_error: Option<f64>,
    /// For an indenter other than the ellipsoid ("power-law", "flat-punch"): its name
    /// (absent for an ellipsoid).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indenter: Option<String>,
    /// For such an indenter: the closed form of the Δx → 0 limit of |min F̄| ("Kendall",
    /// "JKR (power law)") and its value (absent where none exists).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub exact_limit: Option<ExactLimit>,
    /// The force scale of the scene's normalisation (the user's force unit): F = F̄ × it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_scale: Option<f64>,
    /// The adhesive force in the user's force unit, force_scale × f_ad_bar.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adhesive_force: Option<f64>,
    /// Its half-width (the user's force unit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adhesive_force_uncertainty: Option<f64>,
    /// For a shape without a convergence law extrapolated over grids and grid phases: the
    /// extrapolation's order, its parts of the half-width and the grids
    /// ([`GenericLimit`]); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<GenericLimit>,
    /// Whether every run reached the force minimum.
    pub min_reached: bool,
    /// Whether every run ran to its end.
    pub complete: bool,
    /// CG iterations over all runs.
    pub cg_iterations: usize,
    /// Wall time of all runs (s).
    pub wall_s: f64,
    /// Warnings of every run.
    pub warnings: Vec<String>,
    /// Every run, coarse to fine.
    pub runs: Vec<RunReport>,
    /// Where the result comes from: version, date, scene in the user's units, options,
    /// backend and device, command line (absent in summaries made without a session).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub provenance: Option<super::provenance::Provenance>,
}

/// The closed form of the Δx → 0 limit of |min F̄| for an indenter other than the ellipsoid,
/// and the grid's distance to it.
#[derive(Debug, Clone, Serialize)]
pub struct ExactLimit {
    /// Whose closed form it is.
    pub name: &'static str,
    /// Its |min F̄| (dimensionless, in the indenter's normalisation).
    pub f_ad_bar: f64,
    /// The grid's own |min F̄| against it, f/limit − 1 (its discretisation error; null if
    /// the run did not reach the minimum). Several grids: the finest grid's mean over its
    /// phases.
    pub grid_error: Option<f64>,
    /// The estimate against it, f_ad_bar/limit − 1 (a comparison: the estimate's reference
    /// is the Δx → 0 limit of the model, of which the closed form is one account); absent
    /// without an estimate.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub deviation: Option<f64>,
}

impl Summary {
    /// The summary of `result`.
    pub fn new(result: &AdhesiveResult) -> Self {
        let e = result.estimate.as_ref();
        let c = result.comparison;
        Summary {
            ratio: result.ratio,
            estimate: e.map(|e| e.kind.name()),
            f_ad_bar: e.map(|e| e.f_ad_bar.value),
            f_ad_bar_uncertainty: e.map(|e| e.f_ad_bar.uncertainty),
            f_ad_bar_bias: e.and_then(|e| e.f_ad_bar_bias),
            c_bar_at_min: e.and_then(|e| e.c_bar_at_min).map(|v| v.value),
            c_bar_at_min_uncertainty: e.and_then(|e| e.c_bar_at_min).map(|v| v.uncertainty),
            d_bar_at_min: e.and_then(|e| e.d_bar_at_min).map(|v| v.value),
            d_bar_at_min_uncertainty: e.and_then(|e| e.d_bar_at_min).map(|v| v.uncertainty),
            method: e.map(|e| e.method.clone()),
            target: result.target.map(|t| t.target),
            target_met: result.target.map(|t| t.met),
            jg_f_ad_bar: c.jg_f_ad_bar,
            jg_deviation: c.jg_deviation,
            jkr_error: c.jkr_error,
            indenter: result
                .runs
                .first()
                .filter(|r| !crate::analysis::report::is_ellipsoid(r) || r.min_pinned)
                .map(|r| r.indenter.clone()),
            exact_limit: c.exact.map(|(name, f_ad_bar)| ExactLimit {
                name,
                f_ad_bar,
                grid_error: c.grid_error,
                deviation: e.map(|e| e.f_ad_bar.value / f_ad_bar - 1.0),
            }),
            force_scale: None,
            adhesive_force: None,
            adhesive_force_uncertainty: None,
            limit: e.and_then(|e| e.generic.clone()),
            min_reached: result.runs.iter().all(|r| r.min_reached),
            complete: result.runs.iter().all(|r| r.complete),
            cg_iterations: result.runs.iter().map(|r| r.cg_iterations).sum(),
            wall_s: result.runs.iter().map(|r| r.wall_s).sum(),
            warnings: result.warnings(),
            runs: result.runs.clone(),
            provenance: None,
        }
    }

    /// Set the scene's force scale (the user's force unit per unit F̄) and, where there is an
    /// estimate, the adhesive force in that unit with its half-width.
    pub fn set_force_scale(&mut self, scale: f64) {
        self.force_scale = Some(scale);
        self.adhesive_force = self.f_ad_bar.map(|f| f * scale);
        self.adhesive_force_uncertainty = self.f_ad_bar_uncertainty.map(|u| u * scale);
    }

    /// Write as pretty JSON ([`Summary::to_json`]), in the command line's words (see the
    /// module's rule).
    pub fn write_json(&self, path: &Path) -> Result<(), OutputError> {
        super::file::write_text(path, &self.to_json())
    }

    /// The pretty JSON [`Summary::write_json`] writes, newline-terminated (for a stream).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a summary always serialises") + "\n"
    }

    /// Human-readable lines of the result: the answer, every run and what stopped early (the
    /// warnings are apart, in [`Summary::warning_lines`], for a front end to show where it
    /// shows warnings).
    pub fn to_text(&self) -> String {
        let opt = |v: Option<f64>, p: usize| v.map_or("—".into(), |x| fixed(x, p));
        let pct =
            |v: Option<f64>| v.map_or("—".into(), |e| format!("{} %", signed(100.0 * e, 2)));
        let mut s = String::new();
        match (self.f_ad_bar, self.f_ad_bar_uncertainty) {
            (Some(f), Some(u)) => {
                s += &format!(
                    "adhesive force |min F̄| = {} ± {} ({}, ± {:.2} %)\n",
                    fixed(f, 4),
                    fixed(u, 4),
                    self.estimate.unwrap_or("—"),
                    100.0 * u / f
                );
                if let Some(b) = self.f_ad_bar_bias {
                    let own = self.runs.first().and_then(|r| r.f_ad_bar);
                    s += &format!(
                        "  the grid's own |min F̄| = {} over-predicts it by {} % (first order in Δx: \
                         refine the grid or extrapolate to shrink the uncertainty)\n",
                        opt(own, 4),
                        signed(100.0 * b / f, 2)
                    );
                }
                if let (Some(t), Some(met)) = (self.target, self.target_met) {
                    s += &format!(
                        "  target ± {:.2} %: {}\n",
                        100.0 * t,
                        if met {
                            "met"
                        } else {
                            "NOT MET (the best answer within the limits is shown)"
                        }
                    );
                }
                if let (Some(a), Some(au)) = (self.adhesive_force, self.adhesive_force_uncertainty)
                {
                    s += &format!(
                        "  adhesive force F = {} ± {} (your force unit: F̄ × {})\n",
                        sig(a),
                        sig(au),
                        sig(self.force_scale.unwrap_or(f64::NAN))
                    );
                }
                if let Some(l) = &self.limit {
                    s += &self.limit_text(l);
                } else {
                    s += &format!(
                        "  at c̄ = {} ± {}, d̄ = {} ± {}\n",
                        opt(self.c_bar_at_min, 4),
                        opt(self.c_bar_at_min_uncertainty, 4),
                        opt(self.d_bar_at_min, 4),
                        opt(self.d_bar_at_min_uncertainty, 4)
                    );
                }
                if self.indenter.is_some() {
                    if let Some(l) = &self.exact_limit {
                        s += &format!(
                            "  beside {}'s exact limit {} (deviation from {} {}, a comparison)\n",
                            l.name,
                            fixed(l.f_ad_bar, 4),
                            l.name,
                            pct(l.deviation)
                        );
                    }
                } else {
                    s += &format!(
                        "  beside Johnson–Greenwood {} (deviation from JG {})",
                        opt(self.jg_f_ad_bar, 4),
                        pct(self.jg_deviation)
                    );
                    if self.jkr_error.is_some() {
                        s += &format!("; against JKR's exact 1/2: {}", pct(self.jkr_error));
                    }
                    s += "\n";
                }
            }
            _ if self.min_reached && self.runs.iter().any(|r| r.withheld.is_some()) => {
                let grids: Vec<&str> = self
                    .runs
                    .iter()
                    .filter(|r| r.withheld.is_some())
                    .map(|r| r.grid.as_str())
                    .collect();
                s += &format!(
                    "NO ADHESIVE FORCE: the {} run reached the force minimum, but the answer is \
                     withheld (its WARNING says why)\n",
                    grids.join(", ")
                );
            }
            _ if self.indenter.is_some() && self.min_reached => {
                s += &self.indenter_text();
            }
            _ if self.min_reached && self.runs.iter().any(|r| !r.min_resolved) => {
                let grids: Vec<&str> = self
                    .runs
                    .iter()
                    .filter(|r| !r.min_resolved)
                    .map(|r| r.grid.as_str())
                    .collect();
                s += &format!(
                    "NO ADHESIVE FORCE: the load steps of the {} run were too large to resolve \
                     the force minimum (see its WARNING): its lowest state is not the \
                     minimum, so no answer with an uncertainty is given; leave out {ONSETS} none \
                     or use more {STEPS}\n",
                    grids.join(", ")
                );
            }
            _ => {
                let lowest = self.runs.iter().find(|r| !r.min_reached);
                let seen = match lowest.and_then(|r| r.lowest_f_bar.zip(r.d_bar_at_lowest)) {
                    Some((f, d)) => format!(
                        "the lowest F̄ recorded is {} at d̄ = {}, and the force had not turned \
                         after it",
                        fixed(f, 4),
                        fixed(d, 4)
                    ),
                    None => "no state was recorded".to_string(),
                };
                let why = if self.complete {
                    format!(
                        "the run ran to its final approach without the force turning (given by \
                         {FINAL_D}, or by default where the closed form puts the end of \
                         contact): a lower {FINAL_D} passes the minimum"
                    )
                } else {
                    "the run stopped early (see INCOMPLETE below)".to_string()
                };
                s += &format!(
                    "NO ADHESIVE FORCE: the run did not reach the force minimum; {seen}; {why}\n"
                );
            }
        }
        for r in &self.runs {
            s += &run_text(r);
        }
        for r in &self.runs {
            if let Some(e) = &r.error {
                s += &format!("INCOMPLETE ({}): {e}\n", r.grid);
            }
        }
        s
    }

    /// The warnings, one human-readable line each ("WARNING: …", without a newline).
    pub fn warning_lines(&self) -> Vec<String> {
        self.warnings
            .iter()
            .map(|w| format!("WARNING: {w}"))
            .collect()
    }
}

impl Summary {
    /// How a shape without a convergence law was extrapolated: its grids and phases, the
    /// order, and the parts of the half-width.
    fn limit_text(&self, l: &GenericLimit) -> String {
        let order = if l.order_estimated {
            format!(
                "order p = {:.2} ± {:.2}, estimated from the grids",
                l.order, l.order_sd
            )
        } else {
            format!(
                "order assumed first order (p = {:.2} ± {:.2}; the grids cannot fix it)",
                l.order, l.order_sd
            )
        };
        format!(
            "  grids {} at {} grid phases each, Richardson-extrapolated: {order}\n\
             \x20 ± {} the grid phases, {} the extrapolation's own error, {} the order (in \
             quadrature); the finest grid's phases {} ± {}\n",
            l.grids.join(", "),
            l.phases.iter().max().copied().unwrap_or(0),
            fixed(l.phase_part, 4),
            fixed(l.extrapolation_part, 4),
            fixed(l.order_part, 4),
            fixed(l.finest_mean, 4),
            fixed(l.finest_spread, 4),
        )
    }

    /// The answer for an indenter other than the ellipsoid: the grid's own |min F̄| (no
    /// convergence law, so no estimate with an uncertainty) and its distance to the closed
    /// form of the limit, where one exists.
    fn indenter_text(&self) -> String {
        let own = self.runs.first().and_then(|r| r.f_ad_bar);
        let ellipsoid = self.indenter.as_deref() == Some("ellipsoid");
        let mut s = if ellipsoid && self.runs.iter().any(|r| r.min_pinned) {
            format!(
                "the grid's |min F̄| = {} ({}, at the first onset of a pinned contact)\n\
                 \x20 the convergence law is for a minimum a receding front reaches, so no \
                 estimate with an uncertainty: its discretisation error is of first order in \
                 Δx (refine the grid to see it converge)\n",
                own.map_or("—".into(), |f| fixed(f, 4)),
                self.indenter.as_deref().unwrap_or("—"),
            )
        } else {
            format!(
                "the grid's |min F̄| = {} ({}; F̄ in its own normalisation, see \
                 docs/indenters.md)\n\
                 \x20 no convergence law for this indenter yet, so no estimate with an \
                 uncertainty: its discretisation error is of first order in Δx (refine the grid \
                 to see it converge)\n",
                own.map_or("—".into(), |f| fixed(f, 4)),
                self.indenter.as_deref().unwrap_or("—"),
            )
        };
        if let Some(l) = &self.exact_limit {
            s += &format!(
                "  beside {}'s exact limit {}: the grid is off by {}\n",
                l.name,
                fixed(l.f_ad_bar, 4),
                l.grid_error
                    .map_or("—".into(), |e| format!("{} %", signed(100.0 * e, 2)))
            );
        }
        s
    }
}

/// One run's lines: grid, Δx, its own |min F̄|, cost.
fn run_text(r: &RunReport) -> String {
    let opt = |v: Option<f64>, p: usize| v.map_or("—".into(), |x| fixed(x, p));
    let mut s = String::new();
    let mut angle = if r.mesh_angle_deg == 0.0 {
        String::new()
    } else {
        format!(" turned by {}°", r.mesh_angle_deg)
    };
    if r.apex_offset != [0.0, 0.0] {
        angle += &format!(
            ", apex offset {}:{}",
            crate::text::compact(r.apex_offset[0]),
            crate::text::compact(r.apex_offset[1])
        );
    }
    // A contact that does not cross the centre lines at pull-off (the patches of a nominally
    // flat rough surface) has no width across them to state: the clause is left out.
    let across = match r.n_d {
        Some(n) if n > 0.0 => format!(
            ", {} elements across the minor axis at pull-off",
            fixed(n, 0)
        ),
        Some(_) => String::new(),
        None => ", — elements across the minor axis at pull-off".to_string(),
    };
    s += &format!(
        "grid {}{angle}: |min F̄| = {}, Δx = {:.5e}, σ_c = {:.5e}{across}\n",
        r.grid,
        opt(r.f_ad_bar, 5),
        r.dx,
        r.sigma_c,
    );
    if !r.regrids.is_empty() {
        s += &format!(
            "  Δx at the force minimum {} after {} re-grid(s)\n",
            r.dx_at_min.map_or("—".into(), |v| format!("{v:.5e}")),
            r.regrids.len()
        );
    }
    s += &format!(
        "  {} backend ({}), {} states, {} CG iterations, {:.2} s\n",
        r.backend, r.precision, r.states, r.cg_iterations, r.wall_s
    );
    if let Some(cost) = &r.cost {
        s += &format!("  cost: {}\n", cost.line());
        for line in cost.band_lines() {
            s += &format!("    {line}\n");
        }
        if let Some(line) = cost.activity_line() {
            s += &format!("    {line}\n");
        }
    }
    if let Some(w) = &r.refinement {
        s += &format!("  {}\n", refinement_line(w));
    }
    if r.cg_retries > 0 {
        s += &format!(
            "  CG: {} solve(s) retried in the safer mode, worst relative residual {} (warnings \
             below)\n",
            r.cg_retries,
            r.cg_residual_max.map_or("—".into(), |v| format!("{v:.2e}"))
        );
    }
    for g in &r.regrids {
        s += &format!(
            "  re-gridded at d̄ = {:.4}: Δx {:.4e} → {:.4e}\n",
            g.d_bar, g.dx_from, g.dx_to
        );
    }
    if let Some(c) = &r.confirmation {
        s += &format!("  {}\n", confirmation_line(c));
    }
    if r.stopped_after_minimum {
        s +=
            &format!("  stopped once the force minimum was confirmed ({MEASURE} adhesive-force)\n");
    }
    s
}

/// How the force minimum was confirmed, in words.
fn confirmation_line(c: &crate::solver::protocol::Confirmation) -> String {
    use crate::solver::protocol::{CONFIRM_D_BAR, CONFIRM_RISE};
    if c.vanished {
        return format!(
            "force minimum confirmed by the contact's end at d̄ = {:.4}, {:.4} past it",
            c.d_bar, c.past_d_bar
        );
    }
    format!(
        "force minimum confirmed by the state at d̄ = {:.4}: {:.4} past it in d̄ and {:.2} % \
         above it (the test asks ≥ {CONFIRM_D_BAR} and ≥ {} %); every onset between was located \
         or bounded above it",
        c.d_bar,
        c.past_d_bar,
        100.0 * c.rise,
        100.0 * CONFIRM_RISE
    )
}

/// Which steps had their onsets located, in words.
fn refinement_line(w: &crate::solver::window::Refinement) -> String {
    let span = match (w.d_bar_from, w.d_bar_to) {
        (Some(a), Some(b)) => format!(" (d̄ {a:.4} to {b:.4})"),
        _ => String::new(),
    };
    let margin = w.margin_f_bar.map_or(String::new(), |m| {
        format!(
            "; every step left whole has its bound ≥ the minimum (margin {m:.2e} in F̄{})",
            if w.bound_violation_f_bar > 0.0 {
                format!(
                    ", but a located onset fell {:.2e} below its bound: window widened",
                    w.bound_violation_f_bar
                )
            } else {
                String::new()
            }
        )
    });
    format!(
        "onsets located in {} of {} steps{span}: {} candidate steps, {} parts pruned, {} split, \
         {} walked ({} cut short), {} starts recomputed{margin}",
        w.steps.len(),
        w.steps.len() + w.whole_steps,
        w.candidates,
        w.pruned,
        w.splits,
        w.walks,
        w.cut_short,
        w.recomputed
    )
}

/// `v` to five significant digits ("1.2346e-3", "0.51018").
fn sig(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e5) {
        format!("{v:.4e}")
    } else {
        format!("{v:.5}")
    }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Model, ModelOptions};
    use crate::scene::Scene;
    use crate::solver::{Outcome, Phase, State};

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
            cost: Default::default(),
            refinement: None,
            min_contact: None,
        }
    }

    fn sphere(nx: usize) -> Model {
        let scene = Scene::from_ratio(1.0, 1.0, 1.0, 1.0).unwrap();
        Model::build(
            &scene,
            &ModelOptions {
                nx,
                ..ModelOptions::default()
            },
        )
        .unwrap()
    }

    fn summary_of(model: &Model, states: Vec<State>) -> Summary {
        let run = RunReport::new(
            model,
            &outcome(states),
            ("cpu", "f64"),
            0.0,
            Some(Path::new("s.csv")),
        );
        Summary::new(&AdhesiveResult::single(run, None))
    }

    #[test]
    fn a_contact_off_the_centre_lines_states_no_width_across_it() {
        // The patches of a nominally flat rough surface read "0 elements across the minor axis".
        let model = sphere(32);
        let patches = state(&model, -1.0, 0.0, 40);
        let gone = state(&model, -0.3, 0.0, 0);
        let text = run_text(&summary_of(&model, vec![patches, gone]).runs[0]);
        assert!(!text.contains("elements across"), "{text}");
        let round = state(&model, -1.0, 13.0, 500);
        let gone = state(&model, -0.3, 0.0, 0);
        let text = run_text(&summary_of(&model, vec![round, gone]).runs[0]);
        assert!(
            text.contains("26 elements across the minor axis at pull-off"),
            "{text}"
        );
    }

    #[test]
    fn n_d_is_a_count_of_elements_without_round_off() {
        // Before: n_d = 2 b / Δx came out as 25.999999999999996.
        let model = sphere(32);
        let k = (1..200)
            .map(f64::from)
            .find(|k| 2.0 * (k * model.dx) / model.dx != 2.0 * k)
            .expect("some count has round-off in 2 k Δx / Δx");
        let min = state(&model, -1.0, k, 100);
        let gone = state(&model, -0.3, 0.0, 0);
        let s = summary_of(&model, vec![min, gone]);
        assert!(s.min_reached);
        assert_eq!(s.runs[0].n_d, Some(2.0 * k));
    }

    #[test]
    fn one_shape_with_the_estimate_its_uncertainty_and_the_comparisons() {
        let model = sphere(32);
        let min = state(&model, -0.55, 16.0, 100);
        let gone = state(&model, -0.3, 0.0, 0);
        let s = summary_of(&model, vec![min, gone]);
        assert_eq!(s.estimate, Some("single-grid"));
        let (f, u) = (s.f_ad_bar.unwrap(), s.f_ad_bar_uncertainty.unwrap());
        // The grid's 0.55 over-predicts: the estimate lies below it, and its interval is
        // wide enough to hold JKR's 1/2 (k = 3.2 at n_d = 32: +10 %).
        assert!(f < 0.55 && (f - 0.5).abs() <= u, "{f} ± {u}");
        assert_eq!(s.runs[0].f_ad_bar, Some(0.55));
        assert!((s.f_ad_bar_bias.unwrap() - (0.55 - f)).abs() < 1e-12);
        // JG reduces to JKR for the sphere (to round-off).
        assert!((s.jg_f_ad_bar.unwrap() - 0.5).abs() < 1e-12);
        assert!((s.jkr_error.unwrap() - (f / 0.5 - 1.0)).abs() < 1e-12);
        assert!((s.jg_deviation.unwrap() - s.jkr_error.unwrap()).abs() < 1e-12);
        let json = serde_json::to_value(&s).unwrap();
        for key in [
            "f_ad_bar",
            "f_ad_bar_uncertainty",
            "estimate",
            "target",
            "target_met",
            "jg_f_ad_bar",
            "jg_deviation",
            "jkr_error",
            "c_bar_at_min",
            "c_bar_at_min_uncertainty",
            "d_bar_at_min",
            "d_bar_at_min_uncertainty",
            "runs",
        ] {
            assert!(json.get(key).is_some(), "{key} missing from {json}");
        }
        assert!(json["f_ad_bar"].is_number());
        assert!(!json.to_string().contains("relative_error"));
        let text = s.to_text();
        assert!(text.contains("deviation from JG"), "{text}");
        assert!(!text.contains("error +"), "{text}");
    }

    #[test]
    fn the_warnings_are_apart_from_the_text_of_the_result() {
        // 16 elements across the minor axis: too coarse a grid, warned of.
        let model = sphere(32);
        let min = state(&model, -0.55, 8.0, 100);
        let gone = state(&model, -0.3, 0.0, 0);
        let s = summary_of(&model, vec![min, gone]);
        assert!(!s.warnings.is_empty());
        let text = s.to_text();
        assert!(
            text.contains("adhesive force") && !text.contains("WARNING"),
            "{text}"
        );
        let lines = s.warning_lines();
        assert_eq!(lines.len(), s.warnings.len());
        assert!(lines
            .iter()
            .all(|l| l.starts_with("WARNING: ") && !l.contains('\n')));
        assert!(s.to_json().ends_with("}\n"));
    }

    #[test]
    fn without_a_minimum_there_is_no_adhesive_force_line() {
        let model = sphere(32);
        // The force still falls at the last state.
        let states = vec![state(&model, -0.2, 10.0, 80), state(&model, -0.49, 9.0, 70)];
        let s = summary_of(&model, states);
        assert!(!s.min_reached);
        assert_eq!(s.f_ad_bar, None);
        assert_eq!(s.runs[0].lowest_f_bar, Some(-0.49));
        let text = s.to_text();
        assert!(!text.contains("adhesive force |min F̄|"), "{text}");
        assert!(text.contains("NO ADHESIVE FORCE"), "{text}");
        assert!(!text.contains("-0.0000"), "{text}");
    }
}
