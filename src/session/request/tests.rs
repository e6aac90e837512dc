use super::*;
use serde_json::json;

#[test]
fn the_default_request_names_every_parameter_and_round_trips() {
    let r = Request::from_values(Map::new()).unwrap();
    let v = r.to_json();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    let mut names: Vec<&str> = SPECS.iter().map(|s| s.name).collect();
    let mut sorted = keys.clone();
    sorted.sort();
    names.sort();
    assert_eq!(sorted, names);
    let back: Request = serde_json::from_value(v).unwrap();
    assert_eq!(back, r);
}

#[test]
fn text_and_json_requests_agree() {
    let a = Request::from_texts([("ratio", "2"), ("grid", "64"), ("onsets", "all")]).unwrap();
    let b = Request::from_json([
        ("ratio", &json!(2.0)),
        ("grid", &json!(64)),
        ("onsets", &json!("all")),
    ])
    .unwrap();
    assert_eq!(a, b);
    assert!(matches!(a.mode().unwrap(), Mode::Single));
}

#[test]
fn figure_formats_reach_the_session_and_old_requests_read_as_svg() {
    use crate::output::figure::{FigureFormat, FigureFormats};
    let r = Request::from_texts([("figure_format", "png,pdf")]).unwrap();
    assert_eq!(r.figure_format, [FigureFormat::Png, FigureFormat::Pdf]);
    let s = r.simulate_request(Sink::Memory, None).unwrap();
    assert_eq!(
        s.figures,
        FigureFormats::of(&[FigureFormat::Pdf, FigureFormat::Png])
    );
    let d = Request::from_values(Map::new()).unwrap();
    assert_eq!(d.figure_format, [FigureFormat::Svg]);
    // A request recorded before the parameter existed (a batch's summary that resume reads)
    // is the default's.
    let mut old = d.to_json();
    old.as_object_mut().unwrap().remove("figure_format");
    assert_eq!(serde_json::from_value::<Request>(old).unwrap(), d);
}

#[test]
fn a_bare_request_runs_to_two_per_cent() {
    let r = Request::from_values(Map::new()).unwrap();
    assert!(matches!(r.mode().unwrap(), Mode::Accuracy(a) if a == 0.02));
}

#[test]
fn conflicting_parameters_are_refused_naming_them() {
    for (given, named) in [
        (vec![("accuracy", "1%"), ("grid", "64")], "accuracy"),
        (vec![("extrapolate", "true"), ("grid", "64")], "extrapolate"),
        (vec![("time_limit", "1min"), ("grid", "64")], "time_limit"),
        (vec![("ratio", "2"), ("r1", "3")], "ratio"),
        (vec![("radius", "2")], "radius"),
    ] {
        let r = Request::from_texts(given.clone()).unwrap();
        let e = r
            .simulate_request(Sink::Memory, None)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with(&format!("⟨{named}⟩")), "{given:?}: {e}");
    }
}

#[test]
fn an_unknown_name_is_refused_with_the_closest() {
    let e = Request::from_texts([("mesh_angel", "3")])
        .unwrap_err()
        .to_string();
    assert!(e.contains("⟨mesh_angle⟩"), "{e}");
}

#[test]
fn the_schemas_defaults_are_the_models() {
    let r = Request::from_values(Map::new()).unwrap();
    let o = r.options();
    let d = ModelOptions::default();
    assert_eq!(
        (
            o.cg_tolerance,
            o.cg_max_iterations,
            o.cg_accept,
            o.max_sweeps
        ),
        (
            d.cg_tolerance,
            d.cg_max_iterations,
            d.cg_accept,
            d.max_sweeps
        )
    );
    assert_eq!(
        (o.mesh_angle_deg, o.apex_offset),
        (d.mesh_angle_deg, d.apex_offset)
    );
    assert_eq!(
        (o.start_radius_bar, o.preconditioner),
        (d.start_radius_bar, d.preconditioner)
    );
    assert_eq!(
        (o.onsets, o.measure, o.regrid),
        (d.onsets, d.measure, d.regrid)
    );
}

/// Every name a choice of the schema offers is one the request's enums take, so that the
/// schema's lists and the enums cannot drift apart.
#[test]
fn every_choice_the_schema_offers_is_a_value_of_the_request() {
    for spec in SPECS {
        if let params::Kind::Choice(names) | params::Kind::Choices(names) = spec.kind {
            for name in names {
                let r = Request::from_texts([(spec.name, *name)]);
                assert!(r.is_ok(), "{} = {name}: {:?}", spec.name, r.err());
            }
        }
    }
}
