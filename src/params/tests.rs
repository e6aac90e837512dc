use super::values::{from_json, from_text};
use super::words::{flags, keywords, named};
use super::*;
use serde_json::json;

#[test]
fn names_and_flags_are_unique_and_spelt_alike() {
    let every: Vec<&Spec> = all().collect();
    assert_eq!(
        every.len(),
        SPECS.len() + STUDY_SPECS.len() + ROUGHNESS_SPECS.len()
    );
    for (i, a) in every.iter().enumerate() {
        assert_eq!(a.name, a.flag[2..].replace('-', "_"), "{a:?}");
        assert!(!a.help.is_empty(), "{}", a.name);
        for b in &every[i + 1..] {
            assert_ne!(a.name, b.name);
        }
    }
    for s in STUDY_SPECS {
        assert_eq!(by_name(s.name), Some(*s));
        assert_eq!(by_flag(s.flag), Some(*s));
    }
    assert_eq!(
        flags(&format!("{MARGINS} and {MARGIN}")),
        "--margins and --margin"
    );
}

#[test]
fn every_default_value_is_valid() {
    for s in all() {
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
        (FIGURE_FORMAT, "svg,pdf,png", json!(["svg", "pdf", "png"])),
        (FIGURE_FORMAT, " png ", json!("png")),
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
        (INDENTER, "sphere"),
        (FIELDS, "every:0"),
        (FIGURE_FORMAT, "jpeg"),
        (FIGURE_FORMAT, "svg,svg"),
        (FIGURE_FORMAT, ""),
        (FIGURE_FORMAT, "svg,"),
    ];
    for (spec, text) in bad {
        let e = from_text(spec, text).unwrap_err();
        assert!(e.starts_with(&spec.to_string()), "{e}");
        assert!(e.len() < 300, "{e}");
    }
}

/// The library names every parameter by its [`Spec`], never by a flag: no string literal of a
/// library source (all of `src` but the command line's `src/cli` and `src/main.rs`, and the
/// schema that declares the flags) holds a `--flag`. Comments and tests may.
#[test]
fn no_library_message_names_a_flag() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    let mut dirs = vec![root.clone()];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                dirs.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    let skipped = ["cli", "main.rs", "params"];
    let mut found = Vec::new();
    for path in files {
        let relative = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if skipped.iter().any(|s| relative.starts_with(s)) {
            continue;
        }
        let source = std::fs::read_to_string(&path).unwrap();
        let code = source.split("#[cfg(test)]").next().unwrap();
        for literal in string_literals(code) {
            if let Some(flag) = flag_in(&literal) {
                found.push(format!("{relative}: {flag} in {literal:?}"));
            }
        }
    }
    assert!(
        found.is_empty(),
        "flags in library messages:\n{}",
        found.join("\n")
    );
    // The scan itself finds a flag, and only in code.
    let sample = "// --grid in a comment\nlet m = format!(\"use --grid {n}\"); let c = '\"';";
    let literals = string_literals(sample);
    assert_eq!(literals, ["use --grid {n}"]);
    assert_eq!(flag_in(&literals[0]), Some("--grid".to_string()));
}

/// The text of every string literal in Rust `code` (plain and raw), comments skipped.
fn string_literals(code: &str) -> Vec<String> {
    let chars: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let rest = |k: usize| chars.get(i + k).copied();
        match chars[i] {
            '/' if rest(1) == Some('/') => {
                while i < chars.len() && chars[i] != '\n' {
                    i += 1;
                }
            }
            '/' if rest(1) == Some('*') => {
                i += 2;
                while i + 1 < chars.len() && !(chars[i] == '*' && chars[i + 1] == '/') {
                    i += 1;
                }
                i += 2;
            }
            // A character literal ('"', '\'', 'x'), not a lifetime ('a).
            '\'' if rest(1) == Some('\\') => {
                i += 2;
                while i < chars.len() && chars[i] != '\'' {
                    i += 1;
                }
                i += 1;
            }
            '\'' if rest(2) == Some('\'') => i += 3,
            'r' if matches!(rest(1), Some('"') | Some('#'))
                && !(i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_')) =>
            {
                let mut j = i + 1;
                let mut hashes = 0;
                while chars.get(j) == Some(&'#') {
                    hashes += 1;
                    j += 1;
                }
                if chars.get(j) != Some(&'"') {
                    i += 1;
                    continue;
                }
                let start = j + 1;
                let mut k = start;
                loop {
                    if k >= chars.len() {
                        break;
                    }
                    if chars[k] == '"' && (0..hashes).all(|h| chars.get(k + 1 + h) == Some(&'#')) {
                        break;
                    }
                    k += 1;
                }
                out.push(chars[start..k.min(chars.len())].iter().collect());
                i = k + 1 + hashes;
            }
            '"' => {
                let mut text = String::new();
                i += 1;
                while i < chars.len() && chars[i] != '"' {
                    if chars[i] == '\\' {
                        i += 1;
                    }
                    if let Some(&c) = chars.get(i) {
                        text.push(c);
                    }
                    i += 1;
                }
                out.push(text);
                i += 1;
            }
            _ => i += 1,
        }
    }
    out
}

/// The first `--flag` token of `text` ("--" and a lower-case letter, then letters, digits
/// and hyphens), if any.
fn flag_in(text: &str) -> Option<String> {
    let mut rest = text;
    while let Some(at) = rest.find("--") {
        let tail = &rest[at + 2..];
        if tail.starts_with(|c: char| c.is_ascii_lowercase()) {
            let len = tail
                .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
                .unwrap_or(tail.len());
            return Some(format!("--{}", &tail[..len]));
        }
        rest = tail;
    }
    None
}

#[test]
fn a_value_written_as_text_reads_back_as_itself() {
    use super::values::to_text;
    let samples: [(&Spec, &str); 13] = [
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
        (FIGURE_FORMAT, "png,svg"),
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

/// A command's own range for a flag ([`COMMAND_SPECS`]) is a parameter a message names as any
/// other (its name is one of [`all`]'s, with the same flag); every other flag's is its own.
#[test]
fn a_command_s_own_ranges_name_the_same_parameter() {
    for (command, spec) in COMMAND_SPECS {
        let named = by_name(spec.name).expect("a parameter of the schema");
        assert_eq!(named.flag, spec.flag, "{command}");
        assert_ne!(
            named.kind, spec.kind,
            "{command} {}: the same range",
            spec.flag
        );
        assert_eq!(of_command(command, spec.flag), Some(*spec));
    }
    assert_eq!(of_command("simulate", "--grid"), Some(GRID));
    assert_eq!(of_command("roughness", "--grid"), Some(ROUGHNESS_GRID));
    assert_eq!(of_command("bench", "--repeats"), Some(REPEATS));
    assert_eq!(of_command("bench", "--no-such-flag"), None);
}
