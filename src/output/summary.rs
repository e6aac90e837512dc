//! The summary of a run: the adhesive force and where it occurred, beside the closed-form
//! value, with what the run cost. Printed for people, written as JSON for scripts.

use super::OutputError;
use crate::model::Model;
use crate::solver::Outcome;
use crate::theory::{self, TheoryModel};
use serde::Serialize;
use std::path::Path;

/// Summary of one pull-off run.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// R1/R2 (dimensionless).
    pub ratio: f64,
    /// Adhesive force |min F̄| (dimensionless); null if no state was recorded.
    pub f_ad_bar: Option<f64>,
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
        let min = outcome.force_minimum();
        let f_ad = min.map(|s| -s.f_bar);
        Summary {
            ratio,
            f_ad_bar: f_ad,
            c_bar_at_min: min.map(|s| s.c_bar),
            d_bar_at_min: min.map(|s| s.d_bar),
            a_bar_at_min: min.map(|s| s.a_bar),
            b_bar_at_min: min.map(|s| s.b_bar),
            n_d: min.map(|s| 2.0 * s.b_axis / model.dx),
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
            states: outcome.states.len(),
            wall_s,
            complete: outcome.complete(),
            error: outcome.error.as_ref().map(|e| e.to_string()),
            states_csv: states_csv.display().to_string(),
        }
    }

    /// Write as pretty JSON.
    pub fn write_json(&self, path: &Path) -> Result<(), OutputError> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| OutputError::io(dir, e))?;
        }
        let text = serde_json::to_string_pretty(self).expect("a summary always serialises");
        std::fs::write(path, text + "\n").map_err(|e| OutputError::io(path, e))
    }

    /// Human-readable lines.
    pub fn to_text(&self) -> String {
        let opt = |v: Option<f64>, p: usize| v.map_or("—".into(), |x| format!("{x:.p$}"));
        let mut s = String::new();
        s += &format!(
            "adhesive force |min F̄| = {}  ({} value {}, error {})\n",
            opt(self.f_ad_bar, 4),
            self.reference_model.to_uppercase(),
            opt(self.reference_f_ad_bar, 4),
            self.relative_error
                .map_or("—".into(), |e| format!("{:+.2} %", 100.0 * e))
        );
        s += &format!(
            "  at c̄ = {}, d̄ = {}, ā = {}, b̄ = {}\n",
            opt(self.c_bar_at_min, 4),
            opt(self.d_bar_at_min, 4),
            opt(self.a_bar_at_min, 4),
            opt(self.b_bar_at_min, 4)
        );
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
        s += &format!(
            "{} backend ({}), {} states, {} CG iterations, {:.2} s\n",
            self.backend, self.precision, self.states, self.cg_iterations, self.wall_s
        );
        if let Some(e) = &self.error {
            s += &format!("INCOMPLETE: {e}\n");
        }
        s
    }
}
