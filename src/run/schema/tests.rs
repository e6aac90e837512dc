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
        assert!(from_json(spec, &json!({"a": 1})).unwrap_err().wrong_type);
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
