//! Hardening, round three (issue 41), the inputs: a height map is judged against the contact
//! it must resolve (refused before any work where the closed form predicts too few map
//! spacings across the contact at the force minimum); `--fields` counts in the memory check;
//! the flat punch's walls clear any approach; fields of a run that never reached the force
//! minimum are not called its; and the small cases: control characters, decimal commas and
//! `.npz` archives in maps, long numbers echoed, states that do not exist, another indenter's
//! flags, the smallest grid, and a memory limit that is not a number.

use crate::common;

use common::{run_in, stderr};
use std::path::Path;
use std::process::Output;

/// The sphere h = (x² + y²)/2 on `n` × `n` nodes `spacing` apart (heights in the same unit),
/// written as a text grid to `dir/name`.
fn sphere_map(dir: &Path, name: &str, n: usize, spacing: f64) {
    std::fs::write(dir.join(name), common::sphere_map_text(n, spacing, 0.0)).unwrap();
}

/// `simulate` on the height map `dir/map` of node spacing `spacing`, on the CPU, into
/// `r.csv`, with `extra` flags.
fn map_run(dir: &Path, map: &str, spacing: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "simulate",
        "--indenter",
        "height-map",
        "--height-map",
        map,
        "--spacing",
        spacing,
        "--backend",
        "cpu",
        "--out",
        "r.csv",
    ];
    args.extend(extra);
    run_in(dir, &args, &[])
}

/// Names in `dir` other than the inputs given.
fn outputs(dir: &Path, inputs: &[&str]) -> Vec<String> {
    common::names_in(dir, |n| !inputs.contains(&n))
}

fn summary(dir: &Path, name: &str) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join(name)).unwrap()).unwrap()
}

/// E* = 1e3 and Δγ = 1e-3 on a 64 grid: the sphere's contact a hundred times smaller than
/// with E* = Δγ = 1.
const TINY_CONTACT: &[&str] = &[
    "--e-star",
    "1e3",
    "--work-of-adhesion",
    "1e-3",
    "--grid",
    "64",
];

fn refused_naming(o: &Output, flag: &str) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(flag), "{flag} not named: {err}");
    err
}

#[test]
fn a_map_too_coarse_for_its_contact_is_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "m.txt", 129, 0.06);
    // E* = 1e3, Δγ = 1e-3: the contact at the minimum is half a map spacing wide.
    let o = map_run(d, "m.txt", "0.06", TINY_CONTACT);
    let err = refused_naming(&o, "--height-map");
    assert!(
        err.contains("too coarse for the contact") && err.contains("0.5 map spacings"),
        "{err}"
    );
    assert!(
        err.contains("--spacing 0.0019"),
        "the spacing that would do: {err}"
    );
    // The same map at --spacing 1e-6 (a contact of 1.3 spacings), and an 8 × 8-node map.
    let o = map_run(d, "m.txt", "1e-6", &["--grid", "64"]);
    refused_naming(&o, "--height-map");
    sphere_map(d, "m8.txt", 8, 1.2);
    let o = map_run(d, "m8.txt", "1.2", &["--grid", "32"]);
    let err = refused_naming(&o, "--height-map");
    assert!(err.contains("too coarse for the contact"), "{err}");
    assert_eq!(outputs(d, &["m.txt", "m8.txt"]), Vec::<String>::new());
}

#[test]
fn a_map_on_a_window_too_coarse_for_its_contact_is_refused_or_withheld() {
    // The sphere of radius 1 with E* = 1e3, Δγ = 1e-3 (c_r ≈ 0.019): a map 0.014 wide is too
    // small for the first contact, so it is placed on a window; the contact at the force
    // minimum is about 0.0049 wide.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "m8.txt", 8, 0.002);
    let o = map_run(d, "m8.txt", "0.002", &TINY_CONTACT[..4]);
    let err = refused_naming(&o, "--height-map");
    assert!(
        err.contains("too coarse for any contact it can hold") && err.contains("7.9 map spacings"),
        "{err}"
    );
    assert_eq!(outputs(d, &["m8.txt"]), Vec::<String>::new());

    // 16 × 16 nodes over the same area: the window passes, but the contact at the minimum
    // spans about 5 map spacings: the answer is withheld, saying why.
    let spacing = format!("{}", 0.014 / 15.0);
    sphere_map(d, "m16.txt", 16, 0.014 / 15.0);
    let mut extra = TINY_CONTACT[..4].to_vec();
    extra.extend(["--grid", "64", "--summary", "r.json"]);
    let o = map_run(d, "m16.txt", &spacing, &extra);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("r.json")).unwrap()).unwrap();
    let run = &summary["runs"][0];
    assert!(run["f_ad_bar"].is_null(), "{run}");
    assert!(summary["f_ad_bar"].is_null());
    let why = run["withheld"].as_str().unwrap();
    assert!(
        why.contains("too coarse for its contact") && why.contains("mean diameter"),
        "{why}"
    );
}

#[test]
fn a_map_whose_contact_falls_inside_one_cell_is_refused_and_blames_no_flag_not_given() {
    // 128 × 128 nodes (an even count: the apex between nodes) at 0.06, E* = 1e3, Δγ = 1e-3.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "m.txt", 128, 0.06);
    let o = map_run(d, "m.txt", "0.06", TINY_CONTACT);
    let err = refused_naming(&o, "--height-map");
    assert!(!err.contains("--final-d"), "{err}");
    assert_eq!(outputs(d, &["m.txt"]), Vec::<String>::new());
}

#[test]
fn a_resolved_map_gives_the_same_normalised_answer_at_any_scale() {
    // (x² + y²)/2 with E* = Δγ = 1 at spacing 0.06, and the same problem scaled: E* = 1e3,
    // Δγ = 1e-3 shrink c_r a hundredfold, so the map's lengths shrink by 100 (heights by 1e4).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "a.txt", 129, 0.06);
    sphere_map(d, "b.txt", 129, 0.0006);
    let common = [
        "--indenter",
        "height-map",
        "--grid",
        "32",
        "--measure",
        "adhesive-force",
        "--backend",
        "cpu",
    ];
    let run = |map: &str, spacing: &str, scale: &[&str], out: &str| {
        let mut args = vec!["simulate", "--height-map", map, "--spacing", spacing];
        args.extend(common);
        args.extend(scale);
        let json = format!("{out}.json");
        args.extend(["--out", out, "--summary", &json]);
        let o = run_in(d, &args, &[]);
        assert!(o.status.success(), "{}", stderr(&o));
        summary(d, &format!("{out}.json"))["runs"][0]["f_ad_bar"]
            .as_f64()
            .expect("an answer")
    };
    let unit = run("a.txt", "0.06", &[], "a.csv");
    let scaled = run(
        "b.txt",
        "0.0006",
        &["--e-star", "1e3", "--work-of-adhesion", "1e-3"],
        "b.csv",
    );
    assert!((unit / scaled - 1.0).abs() < 1e-6, "{unit} vs {scaled}");
    assert!((unit - 0.55).abs() < 0.1, "a 32² sphere: {unit}");
}

#[test]
fn the_memory_of_the_fields_kept_is_checked_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = run_in(
        d,
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "128",
            "--steps",
            "100000",
            "--fields",
            "every:1",
            "--backend",
            "cpu",
            "--out",
            "r.csv",
        ],
        &[("JKRBEM_MEMORY_LIMIT", "1e8")],
    );
    let err = refused_naming(&o, "--fields");
    assert!(err.contains("GB") && err.contains("every:"), "{err}");
    // A grid that fits alone but not with the fields of every state.
    let o = run_in(
        d,
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "2048",
            "--fields",
            "every:1",
            "--backend",
            "cpu",
            "--out",
            "r.csv",
        ],
        &[("JKRBEM_MEMORY_LIMIT", "2e10")],
    );
    refused_naming(&o, "--fields");
    assert_eq!(outputs(d, &[]), Vec::<String>::new());
}

#[test]
fn the_memory_limit_must_be_a_number_of_bytes() {
    let dir = tempfile::tempdir().unwrap();
    for bad in ["garbage", "nan", "-1", "inf", ""] {
        let o = run_in(
            dir.path(),
            &[
                "simulate",
                "--ratio",
                "1",
                "--grid",
                "32",
                "--backend",
                "cpu",
                "--out",
                "r.csv",
            ],
            &[("JKRBEM_MEMORY_LIMIT", bad)],
        );
        refused_naming(&o, "JKRBEM_MEMORY_LIMIT");
    }
    assert_eq!(outputs(dir.path(), &[]), Vec::<String>::new());
}

#[test]
fn a_map_file_too_large_for_memory_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "m.txt", 257, 0.03);
    let size = std::fs::metadata(d.join("m.txt")).unwrap().len();
    let limit = (3 * size).to_string();
    let o = run_in(
        d,
        &[
            "simulate",
            "--indenter",
            "height-map",
            "--height-map",
            "m.txt",
            "--spacing",
            "0.03",
            "--grid",
            "32",
            "--backend",
            "cpu",
            "--out",
            "r.csv",
        ],
        &[("JKRBEM_MEMORY_LIMIT", &limit)],
    );
    let err = refused_naming(&o, "--height-map");
    assert!(err.contains("memory") && !err.contains("--grid"), "{err}");
    // One line longer than any map may be is refused at its 16385th value.
    let line: Vec<&str> = vec!["1"; 20_000];
    std::fs::write(d.join("line.txt"), line.join(" ")).unwrap();
    let o = run_in(
        d,
        &[
            "simulate",
            "--indenter",
            "height-map",
            "--height-map",
            "line.txt",
            "--spacing",
            "1",
            "--backend",
            "cpu",
            "--out",
            "r.csv",
        ],
        &[],
    );
    let err = refused_naming(&o, "--height-map");
    assert!(err.contains("16385"), "{err}");
}

#[test]
fn a_tiny_flat_punch_runs_like_any_other() {
    // Radius 1e-7 with E* = Δγ = 1 is pressed 4000 radii deep: its walls must clear that.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut answers = Vec::new();
    for (radius, out) in [("1e-7", "tiny.csv"), ("1", "unit.csv")] {
        let o = run_in(
            d,
            &[
                "simulate",
                "--indenter",
                "flat-punch",
                "--radius",
                radius,
                "--grid",
                "64",
                "--backend",
                "cpu",
                "--out",
                out,
                "--summary",
                &format!("{out}.json"),
            ],
            &[],
        );
        assert!(o.status.success(), "radius {radius}: {}", stderr(&o));
        answers.push(
            summary(d, &format!("{out}.json"))["runs"][0]["f_ad_bar"]
                .as_f64()
                .unwrap(),
        );
    }
    assert!((answers[0] / answers[1] - 1.0).abs() < 1e-6, "{answers:?}");
}

#[test]
fn fields_of_a_run_that_never_reached_the_minimum_are_not_called_its() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let o = run_in(
        d,
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--final-d",
            "0",
            "--fields",
            "minimum",
            "--backend",
            "cpu",
            "--out",
            "f.csv",
            "--summary",
            "f.json",
        ],
        &[],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(summary(d, "f.json")["min_reached"], false);
    let file = std::fs::File::open(d.join("f.fields.npz")).unwrap();
    let mut npz = ndarray_npy::NpzReader::new(file).unwrap();
    let bytes: ndarray::Array1<u8> = npz.by_name("metadata").unwrap();
    let meta: serde_json::Value = serde_json::from_slice(bytes.as_slice().unwrap()).unwrap();
    let labels = meta["labels"].to_string();
    assert!(labels.contains("lowest force recorded"), "{labels}");
    assert!(!labels.contains("force minimum"), "{labels}");
    let svg = std::fs::read_to_string(d.join("f.pressure.svg")).unwrap();
    assert!(svg.contains("lowest force recorded") && !svg.contains("at the force minimum"));
}

#[test]
fn map_files_are_echoed_safely_and_their_format_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let map = |name: &str, spacing: &str| map_run(d, name, spacing, &[]);
    // Control characters from the file reach the terminal escaped, never raw.
    std::fs::write(
        d.join("ctl.txt"),
        "1 2 3 4\n1 2 \x1b]0;title\x07\x1b[2J\0 4\n",
    )
    .unwrap();
    let o = map("ctl.txt", "1");
    let err = refused_naming(&o, "--height-map");
    assert!(
        !o.stderr.iter().any(|&b| b == 0x1b || b == 0x07 || b == 0),
        "{err:?}"
    );
    assert!(err.contains("\\u{1b}]0;title"), "{err}");
    // Decimal commas are named as such, not read as twice the columns.
    std::fs::write(d.join("comma.txt"), "1,5 2,5 3,5 4,5\n".repeat(8)).unwrap();
    let err = refused_naming(&map("comma.txt", "1"), "--height-map");
    assert!(
        err.contains("decimal comma") && err.contains("'1,5'"),
        "{err}"
    );
    // Comma-separated values are a list, as before.
    std::fs::write(d.join("csv.txt"), "1,2,3,4\n".repeat(4)).unwrap();
    let err = stderr(&map("csv.txt", "1"));
    assert!(!err.contains("decimal comma"), "{err}");
    // A NumPy .npz (a zip archive) is named, not read as text.
    std::fs::write(d.join("m.npz"), b"PK\x03\x04rest of a zip").unwrap();
    let err = refused_naming(&map("m.npz", "1"), "--height-map");
    assert!(
        err.contains(".npz") && !err.contains("not a number"),
        "{err}"
    );
    // A long number is echoed short, and the spacing's error names --spacing.
    sphere_map(d, "m.txt", 33, 0.2);
    let err = refused_naming(&map("m.txt", "1e300"), "--spacing");
    assert!(
        err.contains("1e300") && !err.contains("0000000000"),
        "{err}"
    );
}

#[test]
fn states_that_the_run_never_recorded_are_named() {
    let dir = tempfile::tempdir().unwrap();
    // The sphere at 32² keeping the fields of `states`, its states in `out`.
    let run = |states: &str, out: &str| {
        let fields = format!("states:{states}");
        let args = [
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "32",
            "--fields",
            &fields,
            "--backend",
            "cpu",
            "--out",
            out,
        ];
        run_in(dir.path(), &args, &[])
    };
    let o = run("3,999999", "f.csv");
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("no fields for state(s) 999999"),
        "{}",
        stderr(&o)
    );
    // A long list of them is named in a line, not a screenful: the first twenty and a count.
    let many: Vec<String> = (100_000..105_000).map(|i| i.to_string()).collect();
    let o = run(&many.join(","), "g.csv");
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    let line = err
        .lines()
        .find(|l| l.contains("no fields for state(s)"))
        .unwrap_or_else(|| panic!("{err}"));
    assert!(
        line.contains("100019 and 4980 more") && line.len() < 400,
        "{line}"
    );
}

#[test]
fn another_indenter_s_flags_are_refused_not_ignored() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    sphere_map(d, "m.txt", 129, 0.06);
    let cases: [(&[&str], &str); 6] = [
        (
            &[
                "--indenter",
                "height-map",
                "--height-map",
                "m.txt",
                "--spacing",
                "0.06",
                "--ratio",
                "7",
            ],
            "--ratio",
        ),
        (&["--spacing", "-1"], "--spacing"),
        (&["--height-map", "m.txt"], "--height-map"),
        (
            &["--indenter", "flat-punch", "--start-radius", "2"],
            "--start-radius",
        ),
        (&["--indenter", "power-law", "--radius", "2"], "--radius"),
        (&["--ratio", "2", "--r1", "3"], "--r1"),
    ];
    for (flags, flag) in cases {
        let mut args = vec!["simulate", "--backend", "cpu", "--out", "r.csv"];
        args.extend(flags);
        let err = refused_naming(&run_in(d, &args, &[]), flag);
        assert!(!err.contains("panicked"), "{err}");
    }
    assert_eq!(outputs(d, &["m.txt"]), Vec::<String>::new());
}

#[test]
fn the_smallest_grid_runs() {
    let dir = tempfile::tempdir().unwrap();
    for shape in [
        &["--ratio", "1"][..],
        &["--indenter", "flat-punch"][..],
        &["--indenter", "power-law"][..],
    ] {
        let mut args = vec![
            "simulate",
            "--grid",
            "16",
            "--backend",
            "cpu",
            "--out",
            "g.csv",
        ];
        args.extend(shape);
        let o = run_in(dir.path(), &args, &[]);
        assert!(o.status.success(), "{shape:?}: {}", stderr(&o));
        std::fs::remove_file(dir.path().join("g.csv")).unwrap();
    }
}

/// A `.npy` map too large for the limits is refused from its header (issue 55), before its
/// data is read: a 20000² float64 map (3.2 GB, sparse here) was read in full first, or refused
/// by the memory check for the wrong cause.
#[test]
fn an_npy_map_of_too_many_nodes_is_refused_from_its_header() {
    let dir = tempfile::tempdir().unwrap();
    let header = "{'descr': '<f8', 'fortran_order': False, 'shape': (20000, 20000), }";
    let pad = (64 - (10 + header.len() + 1) % 64) % 64;
    let header = format!("{header}{}\n", " ".repeat(pad));
    let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
    bytes.extend_from_slice(&(header.len() as u16).to_le_bytes());
    bytes.extend_from_slice(header.as_bytes());
    let path = dir.path().join("big.npy");
    let file = std::fs::File::create(&path).unwrap();
    use std::io::Write;
    (&file).write_all(&bytes).unwrap();
    file.set_len(bytes.len() as u64 + 20000 * 20000 * 8)
        .unwrap();
    let o = map_run(dir.path(), "big.npy", "0.01", &[]);
    let err = refused_naming(&o, "--height-map");
    assert!(
        err.contains("20000 columns") && err.contains("16384"),
        "{err}"
    );
}

#[test]
fn a_sphere_pulled_from_a_small_preload_states_no_law_corrected_answer() {
    // Pressed to d = 0.5 (E* = Δγ = R = 1), the contact is Hertz's, a = √(R d): narrower than
    // the receding branch's at its minimum, so the force minimum is where that pinned contact
    // starts to come off, JKR's F(a) = 4E*a³/(3R) − √(8πΔγE*a³) at a = √0.5. The sphere's law
    // (for a minimum a receding front reaches) corrected it to 0.2553 ± 0.0039 at 128², which
    // excludes that value.
    let a: f64 = 0.5f64.sqrt();
    let pinned = -(4.0 * a.powi(3) / 3.0 - (8.0 * std::f64::consts::PI * a.powi(3)).sqrt())
        / (3.0 * std::f64::consts::PI);
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for grid in ["64", "128"] {
        let args = [
            "simulate",
            "--ratio",
            "1",
            "--preload-depth",
            "0.5",
            "--grid",
            grid,
            "--backend",
            "cpu",
            "--out",
            "p.csv",
            "--summary",
            "p.json",
        ];
        let o = run_in(d, &args, &[]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let s = summary(d, "p.json");
        let run = &s["runs"][0];
        assert_eq!(run["min_pinned"], true, "{run}");
        assert!(s["f_ad_bar"].is_null() && s["f_ad_bar_uncertainty"].is_null());
        assert!(s.get("exact_limit").is_none_or(|e| e.is_null()), "{s}");
        let own = run["f_ad_bar"].as_f64().unwrap();
        assert!(
            own > pinned && own < 1.08 * pinned,
            "{grid}: {own} against the pinned branch's {pinned}"
        );
        let text = common::stdout(&o);
        assert!(text.contains("first onset of a pinned contact"), "{text}");
        assert!(!text.contains("against JKR's exact 1/2"), "{text}");
        let warnings = s["warnings"].to_string();
        assert!(warnings.contains("does not apply"), "{warnings}");
    }
    // Pressed deeper (d = 3), the contact recedes to the branch's minimum: the law applies.
    let args = [
        "simulate",
        "--ratio",
        "1",
        "--preload-depth",
        "3",
        "--grid",
        "64",
        "--backend",
        "cpu",
        "--out",
        "q.csv",
        "--summary",
        "q.json",
    ];
    let o = run_in(d, &args, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let s = summary(d, "q.json");
    assert!(s["runs"][0].get("min_pinned").is_none());
    let f = s["f_ad_bar"].as_f64().unwrap();
    let u = s["f_ad_bar_uncertainty"].as_f64().unwrap();
    assert!((f - 0.5).abs() <= u, "{f} ± {u} against JKR's 1/2");
}
