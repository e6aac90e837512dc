//! The shared table of bad inputs (tests/data/bad_inputs.txt), through the command line: each
//! case is refused (exit 2) before any work, naming its parameter by its flag. The Python
//! package's tests run the same table through its keywords (python/tests/test_schema.py).

use crate::common::run_in;

/// The table's cases: the parameter to be named, and (name, text) given.
pub fn cases() -> Vec<(String, Vec<(String, String)>)> {
    include_str!("../data/bad_inputs.txt")
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let mut words = l.split_whitespace();
            let named = words.next().unwrap().to_string();
            let given = words
                .map(|w| {
                    let (n, v) = w.split_once('=').expect("name=value");
                    (n.to_string(), v.to_string())
                })
                .collect();
            (named, given)
        })
        .collect()
}

/// Whether `text` names `flag` as a whole word (not `--grid` inside `--grid-y`).
fn names(text: &str, flag: &str) -> bool {
    text.match_indices(flag).any(|(at, _)| {
        !text[at + flag.len()..].starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
    })
}

#[test]
fn every_bad_input_of_the_shared_table_is_refused_naming_its_flag() {
    let cases = cases();
    assert!(cases.len() >= 60, "{} cases", cases.len());
    let dir = tempfile::tempdir().unwrap();
    let mut wrong = Vec::new();
    for (named, given) in &cases {
        let mut args: Vec<String> = vec!["simulate".into()];
        for (name, value) in given {
            let spec = jkrbem::params::by_name(name).expect("a parameter of the schema");
            args.push(spec.flag.to_string());
            if !matches!(spec.kind, jkrbem::params::Kind::Switch) {
                args.push(value.clone());
            }
        }
        if !given.iter().any(|(n, _)| n == "backend") {
            args.extend(["--backend".into(), "cpu".into()]);
        }
        args.extend(["--out".into(), "bad.csv".into()]);
        let refs: Vec<&str> = args.iter().map(|s| s.as_str()).collect();
        let o = run_in(dir.path(), &refs, &[]);
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        let flag = jkrbem::params::by_name(named).unwrap().flag;
        if o.status.code() != Some(2) || !names(&err, flag) {
            wrong.push(format!("{args:?}: exit {:?}, {err}", o.status.code()));
        }
    }
    assert!(
        wrong.is_empty(),
        "{} wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    assert!(!dir.path().join("bad.csv").exists());
}

/// The GPU computes in f32 only: `--backend gpu --precision f64` is refused (exit 2) before
/// any adapter is sought, so the refusal is the same on a machine with a GPU, without one and
/// in a build without the `gpu` feature, and it says what to use instead.
#[test]
fn f64_on_the_gpu_is_refused_before_any_adapter_is_sought() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_in(
        dir.path(),
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "16",
            "--backend",
            "gpu",
            "--precision",
            "f64",
            "--out",
            "s.csv",
        ],
        &[],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--precision f64 is not offered by --backend gpu")
            && err.contains("f32 only")
            && err.contains("--backend cpu"),
        "{err}"
    );
    assert!(!err.contains("adapter"), "{err}");
    assert!(!dir.path().join("s.csv").exists());
}

/// The studies take the precision too, and refuse f64 on the GPU the same way, before any
/// output is claimed.
#[test]
fn the_studies_refuse_f64_on_the_gpu_too() {
    for args in [
        &["sweep", "--ratios", "1", "--grid", "16", "--out", "o"][..],
        &["crossed", "--angles", "90", "--out", "o"][..],
        &["reproduce", "--quick", "--out", "o"][..],
    ] {
        let dir = tempfile::tempdir().unwrap();
        let mut all = args.to_vec();
        all.extend(["--backend", "gpu", "--precision", "f64"]);
        let o = run_in(dir.path(), &all, &[]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("f64") && err.contains("gpu"),
            "{args:?}: {err}"
        );
        assert!(!dir.path().join("o").exists(), "{args:?}");
    }
}
