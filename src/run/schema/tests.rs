use super::values::{from_json, from_text};
use super::words::{flags, keywords, named};
use super::*;
use serde_json::json;

#[test]
fn names_and_flags_are_unique_and_spelt_alike() {
    for (i, a) in SPECS.iter().enumerate() {
        assert_eq!(a.name, a.flag[2..].replace('-', "_"), "{a:?}");
        assert!(!a.help.is_empty(), "{}", a.name);
        for b in &SPECS[i + 1..] {
            assert_ne!(a.name, b.name);
        }
    }
}

#[test]
fn every_default_value_is_valid() {
    for s in SPECS {
        if let Fallback::Value(text) = s.fallback {
            assert!(from_text(s, text).is_ok(), "{}: {text}", s.name);
        }
    }
}

#[test]
fn markers_are_worded_by_each_front_end() {
    let m = format!("{MESH_ANGLE} = 95 is invalid: use {GRID_Y} 128, or a smaller {GRID}");
    assert_eq!(
        flags(&m),
        "--mesh-angle = 95 is invalid: use --grid-y 128, or a smaller --grid"
    );
    assert_eq!(
        keywords(&m),
        "mesh_angle = 95 is invalid: use grid_y 128, or a smaller grid"
    );
    let names: Vec<&str> = named(&m).iter().map(|s| s.name).collect();
    assert_eq!(names, ["mesh_angle", "grid_y", "grid"]);
    assert_eq!(flags("no parameter: σ_c"), "no parameter: σ_c");
}

#[test]
fn text_and_json_give_the_same_canonical_values() {
    let cases: &[(&Spec, &str, serde_json::Value)] = &[
        (GRID, "64", json!(64)),
        (MESH_ANGLE, "45", json!(45.0)),
        (ACCURACY, "2%", json!(0.02)),
        (TIME_LIMIT, "2min", json!(120.0)),
        (APEX_OFFSET, "0.25,-0.5", json!([0.25, -0.5])),
        (EXTRAPOLATE_GRIDS, "64,128,256", json!([64, 128, 256])),
        (INDENTER, "flat-punch", json!("flat_punch")),
        (REGRID, "true", json!(true)),
    ];
    for (spec, text, value) in cases {
        let a = from_text(spec, text).unwrap();
        let b = from_json(spec, value).unwrap();
        assert_eq!(a, b, "{}", spec.name);
    }
}

#[test]
fn values_out_of_kind_or_range_are_refused_naming_the_parameter() {
    let bad: &[(&Spec, &str)] = &[
        (GRID, "100"),
        (GRID, "8"),
        (GRID, "64.5"),
        (MESH_ANGLE, "NaN"),
        (MESH_ANGLE, "400"),
        (CG_TOLERANCE, "0"),
        (CG_TOLERANCE, "1"),
        (ACCURACY, "2"),
        (ACCURACY, "60%"),
        (TIME_LIMIT, "90"),
        (APEX_OFFSET, "0.25"),
        (EXTRAPOLATE_GRIDS, "128,64"),
        (EXTRAPOLATE_GRIDS, "64"),
        (INDENTER, "cone"),
        (FIELDS, "every:0"),
    ];
    for (spec, text) in bad {
        let e = from_text(spec, text).unwrap_err();
        assert!(e.starts_with(&spec.to_string()), "{e}");
        assert!(e.len() < 300, "{e}");
    }
}

#[test]
fn a_value_written_as_text_reads_back_as_itself() {
    use super::values::to_text;
    let samples: [(&Spec, &str); 12] = [
        (RATIO, "2.5"),
        (E_STAR, "1.5e-25"),
        (E_STAR, "123456789012345678901234"),
        (GRID, "64"),
        (ACCURACY, "0.5%"),
        (TIME_LIMIT, "90s"),
        (TIME_LIMIT, "2h"),
        (APEX_OFFSET, "0.25,-0.5"),
        (EXTRAPOLATE_GRIDS, "64,128,256"),
        (REGRID, "true"),
        (ONSETS, "near_minimum"),
        (FIELDS, "every:3"),
    ];
    let defaults = SPECS.iter().filter_map(|s| match s.fallback {
        Fallback::Value(text) => Some((*s, text)),
        Fallback::Chosen(_) => None,
    });
    for (spec, text) in samples.into_iter().chain(defaults) {
        let v = from_text(spec, text).unwrap();
        let written = to_text(spec, &v);
        assert_eq!(
            from_text(spec, &written).unwrap(),
            v,
            "{}: {text} → {written}",
            spec.name
        );
    }
    assert_eq!(to_text(ACCURACY, &json!(0.02)), "2%");
    assert_eq!(to_text(TIME_LIMIT, &json!(90.0)), "90s");
    assert_eq!(to_text(GRID, &serde_json::Value::Null), "");
}

#[test]
fn a_column_names_a_parameter_by_its_name_or_its_flag() {
    for header in ["mesh_angle", "--mesh-angle", "mesh-angle", " mesh_angle "] {
        assert_eq!(by_column(header), Some(MESH_ANGLE), "{header}");
    }
    assert_eq!(by_column("mesh angle"), None);
    assert_eq!(by_column("-mesh-angle"), None);
}
