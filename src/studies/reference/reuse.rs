//! Whether a run an earlier job left in a runs folder may stand for the run asked now. A run
//! records what it was asked to be ([`RunSettings`], beside its report in the summary JSON); it
//! is reused only where that matches the request, the backend that ran it is the one asked
//! for, its report agrees with the request, and its states reproduce its report (the force
//! minimum and where it lies). Anything else is run again, with the reason.

use crate::analysis::report::RunReport;
use crate::backend::select::BackendKind;
use crate::model::ModelOptions;
use crate::output::data::read_states;
use crate::params::BACKEND;
use crate::scene::Scene;
use crate::session::open::BackendRequest;
use crate::session::provenance::word;
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The key of the settings in a run's summary JSON.
pub const SETTINGS_KEY: &str = "settings";

/// Relative tolerance of a recorded number against the requested one (JSON round trips of
/// f64 may move the last digit).
const SAME: f64 = 1e-12;

/// Relative tolerance of a report's value against the state it comes from in the states CSV
/// (both written from the same f64; only the text round trip may move it).
const REPRODUCED: f64 = 1e-9;

/// Everything that decides a run's states, as asked: the scene, the model options and the
/// backend request. Written into each run's summary under [`SETTINGS_KEY`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSettings {
    /// The program that ran it ("jkrbem 0.1.0"); recorded, not compared.
    pub program: String,
    /// The ellipsoid's radius of curvature along x (length); null for another indenter.
    pub r1: Option<f64>,
    /// The ellipsoid's radius of curvature along y (length); null for another indenter.
    pub r2: Option<f64>,
    /// Any other indenter, in words (absent for an ellipsoid).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub indenter: Option<String>,
    /// E* (force/length²).
    pub e_star: f64,
    /// Δγ (force/length).
    pub work_of_adhesion: f64,
    /// The model options asked for (grid, domain, load path, CG, protocol), as
    /// [`ModelOptions`] serialises them.
    #[serde(flatten)]
    pub options: ModelOptions,
    /// The backend asked for ("auto", "cpu", "gpu"); the one that ran is in the report.
    pub backend: String,
    /// The convolution ("padded", "periodic").
    pub convolution: String,
    /// The requested CG check interval (`None`: the backend's own).
    pub check_every: Option<usize>,
}

impl RunSettings {
    /// The settings of a run of `options` on `scene` with `backend`.
    pub fn of(scene: &Scene, options: &ModelOptions, backend: &BackendRequest) -> Self {
        RunSettings {
            program: format!("jkrbem {}", env!("CARGO_PKG_VERSION")),
            r1: scene.indenter.radii().map(|r| r.0),
            r2: scene.indenter.radii().map(|r| r.1),
            indenter: (!scene.is_ellipsoid()).then(|| scene.indenter.describe()),
            e_star: scene.e_star,
            work_of_adhesion: scene.work_of_adhesion,
            options: options.clone(),
            backend: word(backend.kind),
            convolution: word(backend.convolution),
            check_every: backend.check_every,
        }
    }
}

/// Whether two recorded values are the same: numbers within [`SAME`] (relative), anything
/// else equal.
fn same_value(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    match (a, b) {
        (serde_json::Value::Number(x), serde_json::Value::Number(y)) => {
            match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) => (x - y).abs() <= SAME * x.abs().max(y.abs()),
                _ => x == y,
            }
        }
        (serde_json::Value::Array(x), serde_json::Value::Array(y)) => {
            x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same_value(a, b))
        }
        _ => a == b,
    }
}

/// The settings that differ between `recorded` and `asked` ("steps 20, asked 100"), the
/// program and the backend asked for left out (the backend that ran is checked on its own).
fn differences(recorded: &serde_json::Value, asked: &RunSettings) -> Vec<String> {
    let asked = serde_json::to_value(asked).unwrap_or_default();
    let Some(asked) = asked.as_object() else {
        return vec!["the settings cannot be compared".into()];
    };
    asked
        .iter()
        .filter(|(k, _)| !matches!(k.as_str(), "program" | "backend"))
        .filter_map(|(k, want)| {
            let got = recorded.get(k).unwrap_or(&serde_json::Value::Null);
            (!same_value(got, want)).then(|| format!("{k} {got}, asked {want}"))
        })
        .collect()
}

/// Whether a run on `backend` with `precision` ("cpu", "f64") is one `kind` asks for: `cpu`
/// the f64 CPU backend, `gpu` the f32 GPU backend, `auto` either.
fn backend_matches(kind: BackendKind, backend: &str, precision: &str) -> bool {
    match kind {
        BackendKind::Cpu => backend == "cpu" && precision == "f64",
        BackendKind::Gpu => backend == "gpu" && precision == "f32",
        BackendKind::Auto => {
            (backend == "cpu" && precision == "f64") || (backend == "gpu" && precision == "f32")
        }
    }
}

/// Whether `a` and `b` agree to `tolerance` (relative), both missing counting as agreeing.
fn close(a: Option<f64>, b: Option<f64>, tolerance: f64) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1e-300),
        (None, None) => true,
        _ => false,
    }
}

/// A text for an optional number.
fn text(v: Option<f64>) -> String {
    v.map_or("null".into(), |v| format!("{v}"))
}

/// Why the report `run` does not agree with the request `asked` (what the report records of
/// it: the grid, the margin, the ratio, the mesh, the onsets, the backend), if it does not.
fn report_differences(run: &RunReport, asked: &RunSettings, kind: BackendKind) -> Vec<String> {
    let mut why = Vec::new();
    if !backend_matches(kind, &run.backend, &run.precision) {
        why.push(format!(
            "it ran on {} ({}), asked {BACKEND} {}",
            run.backend,
            run.precision,
            word(kind)
        ));
    }
    if run.nx != asked.options.nx || asked.options.ny.is_some_and(|ny| ny != run.ny) {
        why.push(format!("its report's grid is {}", run.grid));
    }
    // A shape without radii (a power law, a punch, a map, a rough shape) reports the ratio 1;
    // which shape it is, the recorded settings say.
    let ratio = match (asked.r1, asked.r2) {
        (Some(r1), Some(r2)) => r1 / r2,
        _ => run.ratio,
    };
    for (what, got, want) in [
        ("ratio", run.ratio, ratio),
        ("margin", run.margin, asked.options.margin),
        (
            "mesh angle",
            run.mesh_angle_deg,
            asked.options.mesh_angle_deg,
        ),
        (
            "apex offset x",
            run.apex_offset[0],
            asked.options.apex_offset.0,
        ),
        (
            "apex offset y",
            run.apex_offset[1],
            asked.options.apex_offset.1,
        ),
    ] {
        if !close(Some(got), Some(want), SAME) && got != want {
            why.push(format!("its report's {what} is {got}, asked {want}"));
        }
    }
    if run.onsets.as_deref() != Some(asked.options.onsets.name()) {
        why.push(format!(
            "its report's onsets are {}, asked {}",
            run.onsets.as_deref().unwrap_or("not recorded"),
            asked.options.onsets.name()
        ));
    }
    why
}

/// Why the states CSV at `states` does not reproduce the report `run` (the number of states,
/// |min F̄| and the lowest F̄, c̄, d̄, Δx and n_d at the minimum), if it does not.
fn states_differences(run: &RunReport, states: &Path) -> Option<String> {
    let shown = states.display();
    let rows = match read_states(states) {
        Ok(read) if read.cut_short => {
            return Some(format!("its states {shown} end in a row cut short"))
        }
        Ok(read) => read.states,
        Err(e) => return Some(format!("its states {shown} cannot be read: {e}")),
    };
    if rows.len() != run.states {
        return Some(format!(
            "its states {shown} hold {} states, its report says {}",
            rows.len(),
            run.states
        ));
    }
    let Some(min) = rows.iter().min_by(|a, b| a.f_bar.total_cmp(&b.f_bar)) else {
        return Some(format!("its states {shown} are empty"));
    };
    let n_d = (2e6 * min.b_axis / min.dx).round() / 1e6;
    let checks = [
        ("|min F̄|", run.f_ad_bar, Some(-min.f_bar), REPRODUCED),
        ("lowest F̄", run.lowest_f_bar, Some(min.f_bar), REPRODUCED),
        (
            "c̄ at the minimum",
            run.c_bar_at_min,
            Some(min.c_bar),
            REPRODUCED,
        ),
        (
            "d̄ at the minimum",
            run.d_bar_at_min,
            Some(min.d_bar),
            REPRODUCED,
        ),
        ("Δx at the minimum", run.dx_at_min, Some(min.dx), REPRODUCED),
        ("n_d", run.n_d, Some(n_d), 1e-6),
    ];
    checks
        .iter()
        .find(|(_, report, states, tolerance)| !close(*report, *states, *tolerance))
        .map(|(what, report, from_states, _)| {
            format!(
                "its summary's {what} {} is not its states' {} ({shown})",
                text(*report),
                text(*from_states),
            )
        })
}

/// The run of the summary at `summary` (its states at `states`), if an earlier job finished it
/// with a force minimum for the request `asked` on `backend`; else why not (`Ok(None)`: there
/// is no summary, so nothing to say).
pub fn check(
    summary: &Path,
    states: &Path,
    asked: &RunSettings,
    backend: &BackendRequest,
) -> Result<Option<RunReport>, String> {
    let Ok(text) = std::fs::read_to_string(summary) else {
        return Ok(None);
    };
    let v: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("it is not JSON ({e})"))?;
    let run: RunReport = v
        .get("runs")
        .and_then(|r| r.get(0))
        .cloned()
        .ok_or_else(|| "it holds no run".to_string())
        .and_then(|r| {
            serde_json::from_value(r).map_err(|e| format!("its run cannot be read ({e})"))
        })?;
    if !(run.complete && run.min_reached && run.f_ad_bar.is_some()) {
        return Err("the run did not finish with a force minimum".into());
    }
    let Some(recorded) = v.get(SETTINGS_KEY) else {
        return Err("it records no settings (written by an older jkrbem)".into());
    };
    let mut why = report_differences(&run, asked, backend.kind);
    why.extend(differences(recorded, asked));
    if !why.is_empty() {
        return Err(format!("its settings differ: {}", why.join("; ")));
    }
    if let Some(why) = states_differences(&run, states) {
        return Err(why);
    }
    Ok(Some(run))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_differ_only_where_a_value_does() {
        let scene = Scene::from_ratio(2.0, 1.0, 1.0, 1.0).unwrap();
        let options = ModelOptions::default();
        let backend = BackendRequest::default();
        let asked = RunSettings::of(&scene, &options, &backend);
        let recorded = serde_json::to_value(&asked).unwrap();
        assert!(differences(&recorded, &asked).is_empty());
        let other = RunSettings::of(
            &scene,
            &ModelOptions {
                steps: 20,
                ..options
            },
            &backend,
        );
        let why = differences(&serde_json::to_value(&other).unwrap(), &asked);
        assert_eq!(why, vec!["steps 20, asked 200".to_string()]);
        assert!(backend_matches(BackendKind::Auto, "gpu", "f32"));
        assert!(!backend_matches(BackendKind::Cpu, "gpu", "f32"));
        assert!(!backend_matches(BackendKind::Cpu, "cpu", "f32"));
        assert!(!backend_matches(BackendKind::Gpu, "cpu", "f64"));
    }
}
