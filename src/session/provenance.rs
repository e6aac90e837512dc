//! The provenance a session states beside its results ([`Provenance`]): the scene in the
//! user's units, the options that shaped the runs, the backend asked for and the device each
//! run used, and the command line of the `jkrbem` process (set once by the CLI; a library
//! caller such as the Python package has none).

use super::open::BackendRequest;
use crate::analysis::report::RunReport;
use crate::model::{Model, ModelOptions};
use crate::output::provenance::Provenance;
use crate::scene::{Indenter, Scene};
use serde_json::{json, Value};
use std::sync::OnceLock;

static COMMAND_LINE: OnceLock<String> = OnceLock::new();

/// Record this process's command line (the CLI calls it once, first).
pub fn set_command_line(line: String) {
    let _ = COMMAND_LINE.set(line);
}

/// An option's value as the CLI spells it (e.g. "adhesive-force", "cpu"): its serialised name,
/// kebab-case as the parser's (checked against clap's in the tests, where the `cli` feature
/// builds it).
pub(crate) fn word<T: serde::Serialize>(value: T) -> String {
    match serde_json::to_value(value) {
        Ok(Value::String(name)) => name,
        _ => String::new(),
    }
}

/// The scene in the user's units.
pub fn scene_json(scene: &Scene) -> Value {
    let shape = match &scene.indenter {
        Indenter::HeightMap(m) => json!({"indenter": "height-map", "source": m.source,
                                         "spacing": m.map.spacing(),
                                         "fitted_radii": m.radii.map(|r| [r.0, r.1]),
                                         "placement": m.describe()}),
        Indenter::Rough(r) => {
            let mut base = scene_json(&Scene {
                indenter: r.base.clone(),
                ..scene.clone()
            });
            base["roughness"] = json!({"source": r.source, "spacing": r.map.spacing(),
                                       "rms_height": r.rms_height()});
            base
        }
        smooth => {
            let mut v = json!({"indenter": smooth.name()});
            for (name, value) in smooth.shape().parameters() {
                v[name] = json!(value);
            }
            v
        }
    };
    let mut v = shape;
    v["e_star"] = json!(scene.e_star);
    v["work_of_adhesion"] = json!(scene.work_of_adhesion);
    v["units"] = json!("lengths in the user's unit L, e_star in F/L², work_of_adhesion in F/L");
    let sc = scene.scales();
    v["normalisation"] = if scene.is_normalised() {
        json!({"length": sc.length, "force": sc.force, "approach": sc.approach,
               "by": scene.normalised_by()})
    } else {
        json!({"by": "none: the normalised values are in the user's units"})
    };
    v
}

/// The options that shaped a run, with `mode` (what was run: one grid, several, an accuracy):
/// every field of [`ModelOptions`] as it serialises itself, a field that a parameter of the
/// request schema sets under that parameter's name (`grid`, not `nx`).
pub fn options_json(opt: &ModelOptions, mode: Value) -> Value {
    /// The fields whose name is not the parameter's.
    const RENAMED: [(&str, &str); 5] = [
        ("nx", "grid"),
        ("ny", "grid_y"),
        ("start_radius_bar", "start_radius"),
        ("final_d_bar", "final_d"),
        ("mesh_angle_deg", "mesh_angle"),
    ];
    let mut v = serde_json::to_value(opt).unwrap_or(Value::Null);
    if let Value::Object(map) = &mut v {
        for (field, name) in RENAMED {
            if let Some(x) = map.remove(field) {
                map.insert(name.to_string(), x);
            }
        }
        map.insert("mode".to_string(), mode);
    }
    v
}

/// The options a built model carries (what a batch job ran), with `mode`.
pub fn model_json(model: &Model, mode: Value) -> Value {
    json!({
        "mode": mode,
        "grid": model.nx,
        "grid_y": model.ny,
        "dx": model.dx,
        "margin": model.margin,
        "mesh_angle": model.mesh.degrees,
        "apex_offset": [model.apex_offset.0, model.apex_offset.1],
        "load_step": model.load.d_step,
        "final_d": model.load.d_final,
        "cg_tolerance": model.cg.tolerance,
        "cg_max_iterations": model.cg.max_iterations,
        "cg_accept": model.cg.accept,
        "preconditioner": word(model.preconditioner),
        "onsets": model.onsets.name(),
        "loose_rounds": model.loose_rounds,
        "measure": word(model.measure),
        "regrid": model.regrid,
    })
}

/// The backend asked for and, per run, what ran.
pub fn backend_json(request: &BackendRequest, runs: &[RunReport]) -> Value {
    json!({
        "requested": word(request.kind),
        "precision": word(request.precision),
        "convolution": word(request.convolution),
        "check_every": request.check_every,
        "runs": runs.iter().map(|r| json!({"grid": r.grid, "backend": r.backend,
                                           "precision": r.precision, "device": r.device}))
                    .collect::<Vec<_>>(),
    })
}

/// The provenance of a result made now.
pub fn provenance(scene: &Scene, options: Value, backend: Value) -> Provenance {
    Provenance::now(
        scene_json(scene),
        options,
        backend,
        COMMAND_LINE.get().cloned(),
    )
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::word;
    use crate::backend::select::{BackendKind, Precision};
    use crate::model::Measure;
    use crate::session::open::Convolution;
    use crate::setup::Preconditioner;
    use clap::ValueEnum;

    /// Every value of `T` as the parser names it.
    fn parser_names<T: ValueEnum + serde::Serialize + Clone>() -> Vec<(String, String)> {
        T::value_variants()
            .iter()
            .map(|v| {
                let parsed = v.to_possible_value().unwrap().get_name().to_string();
                (word(v.clone()), parsed)
            })
            .collect()
    }

    #[test]
    fn a_word_is_the_name_the_parser_takes() {
        let all = [
            parser_names::<Preconditioner>(),
            parser_names::<Measure>(),
            parser_names::<BackendKind>(),
            parser_names::<Precision>(),
            parser_names::<Convolution>(),
        ];
        for (word, parsed) in all.iter().flatten() {
            assert_eq!(word, parsed);
        }
        assert_eq!(word(Measure::AdhesiveForce), "adhesive-force");
        assert_eq!(word(Precision::F64), "f64");
    }
}
