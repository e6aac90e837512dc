//! Robustness of the command line (issue 12): bad invocations of every subcommand are refused
//! before any work (exit code 2, the flag named, nothing created); a file under a name asked
//! for is never lost or half-written (failures, SIGTERM, SIGKILL, a file-size limit, a second
//! run on the same output); a run that did not reach the force minimum says so; and no input
//! makes the parser panic.
//!
//! Every case is listed, with its outcome, in docs/errors.md.

use crate::common;
use crate::common::SHORT;

use common::{bin, names_in, output_in as run_in, stderr, wait_for};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

/// Every file and folder under `dir`, hidden ones included, as relative paths.
fn listing(dir: &Path) -> BTreeSet<PathBuf> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeSet<PathBuf>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            out.insert(p.strip_prefix(root).unwrap().to_path_buf());
            if p.is_dir() && !p.is_symlink() {
                walk(root, &p, out);
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(dir, dir, &mut out);
    out
}

/// (subcommand and its fixed arguments, the bad arguments, the flag the message must name,
/// environment). A case's outcome must be: exit code 2, the flag named, no panic, nothing
/// created or changed in the folder it runs in.
type Case = (
    &'static [&'static str],
    &'static [&'static str],
    &'static str,
    &'static [(&'static str, &'static str)],
);

const SIM: &[&str] = &["simulate", "--out", "out/s.csv"];
const SWEEP: &[&str] = &["sweep", "--out", "sw", "--backend", "cpu"];
const CROSSED: &[&str] = &["crossed", "--out", "cr", "--backend", "cpu"];
const REPRODUCE: &[&str] = &["reproduce", "--out", "rp", "--backend", "cpu"];
const ACCURACY: &[&str] = &["accuracy", "--out", "acc"];
const THEORY: &[&str] = &["theory", "--out", "th/t.csv"];
const BENCH: &[&str] = &["bench", "--out", "bn", "--backends", "cpu"];
const REFERENCE: &[&str] = &["reference", "--out", "ref/table.csv", "--backend", "cpu"];
const COVERAGE: &[&str] = &["coverage", "--out", "cov", "--backend", "cpu"];
const NONE: &[(&str, &str)] = &[];
const SMALL_MEMORY: &[(&str, &str)] = &[("JKRBEM_MEMORY_LIMIT", "1e9")];

/// The bad invocations (listed in docs/errors.md).
pub const CASES: &[Case] = &[
    // simulate: the scene
    (SIM, &["--ratio", "-5"], "--ratio", NONE),
    (SIM, &["--ratio=-5"], "--ratio", NONE),
    (SIM, &["--ratio", "0.5"], "--ratio", NONE),
    (SIM, &["--ratio", "NaN"], "--ratio", NONE),
    (SIM, &["--ratio", "inf"], "--ratio", NONE),
    (SIM, &["--ratio", "1e8"], "--ratio", NONE),
    (SIM, &["--r1", "0.5", "--r2", "1"], "--r1", NONE),
    (SIM, &["--r1", "2000", "--r2", "1"], "--r1", NONE),
    (SIM, &["--r2", "0"], "--r2", NONE),
    (SIM, &["--r2", "-1"], "--r2", NONE),
    (SIM, &["--e-star", "-1"], "--e-star", NONE),
    (SIM, &["--e-star", "0"], "--e-star", NONE),
    (SIM, &["--e-star", "1e300"], "--e-star", NONE),
    (SIM, &["--e-star", "1e-300"], "--e-star", NONE),
    (
        SIM,
        &["--work-of-adhesion", "0"],
        "--work-of-adhesion",
        NONE,
    ),
    (
        SIM,
        &["--work-of-adhesion", "1e-300"],
        "--work-of-adhesion",
        NONE,
    ),
    // simulate: the grid
    (SIM, &["--grid", "100"], "--grid", NONE),
    (SIM, &["--grid", "8"], "--grid", NONE),
    (SIM, &["--grid", "-64"], "--grid", NONE),
    (SIM, &["--grid", "abc"], "--grid", NONE),
    (SIM, &["--grid", "1048576"], "--grid", NONE),
    (SIM, &["--grid", "1073741824"], "--grid", NONE),
    (SIM, &["--grid", "4096"], "--grid", SMALL_MEMORY),
    (
        SIM,
        &["--ratio", "1", "--grid", "64", "--grid-y", "16"],
        "--grid-y",
        NONE,
    ),
    (SIM, &["--grid-y", "100"], "--grid-y", NONE),
    (
        SIM,
        &["--ratio", "1000", "--grid", "64"],
        "--grid 1024",
        NONE,
    ),
    (
        SIM,
        &["--ratio", "1", "--grid", "32", "--start-radius", "20"],
        "--grid",
        NONE,
    ),
    // simulate: the protocol
    (SIM, &["--start-radius", "0"], "--start-radius", NONE),
    (SIM, &["--start-radius", "NaN"], "--start-radius", NONE),
    (SIM, &["--start-radius", "-1"], "--start-radius", NONE),
    (SIM, &["--start-radius", "1e-12"], "--start-radius", NONE),
    (SIM, &["--start-radius", "1e12"], "--start-radius", NONE),
    (SIM, &["--steps", "0"], "--steps", NONE),
    (SIM, &["--steps", "-5"], "--steps", NONE),
    (SIM, &["--steps", "1000000000"], "--steps", NONE),
    (SIM, &["--margin", "-0.1"], "--margin", NONE),
    (SIM, &["--margin", "1e300"], "--margin", NONE),
    (SIM, &["--final-d", "5"], "--final-d", NONE),
    (SIM, &["--final-d", "NaN"], "--final-d", NONE),
    (SIM, &["--final-d", "-1e9"], "--final-d", NONE),
    (SIM, &["--mesh-angle", "NaN"], "--mesh-angle", NONE),
    (SIM, &["--mesh-angle", "1e9"], "--mesh-angle", NONE),
    (SIM, &["--cg-tolerance", "0"], "--cg-tolerance", NONE),
    (SIM, &["--cg-tolerance", "2"], "--cg-tolerance", NONE),
    // Looser than the stated uncertainty can take (0.1 stated 0.4623 ± 0.0066 for 0.4993).
    (SIM, &["--cg-tolerance", "0.1"], "--cg-tolerance", NONE),
    (SIM, &["--cg-tolerance", "1e-4"], "--cg-tolerance", NONE),
    // A depth further than the loading's step limit (it loaded for ever).
    (
        SIM,
        &["--ratio", "1", "--preload-depth", "1e30"],
        "--preload-depth",
        NONE,
    ),
    (
        SIM,
        &["--cg-max-iterations", "0"],
        "--cg-max-iterations",
        NONE,
    ),
    (
        SIM,
        &["--cg-max-iterations", "-1"],
        "--cg-max-iterations",
        NONE,
    ),
    (SIM, &["--cg-accept", "0"], "--cg-accept", NONE),
    (SIM, &["--cg-accept", "1"], "--cg-accept", NONE),
    (SIM, &["--cg-check-every", "0"], "--cg-check-every", NONE),
    (SIM, &["--backend", "quantum"], "--backend", NONE),
    (SIM, &["--accuracy", "0%"], "--accuracy", NONE),
    (SIM, &["--accuracy", "200%"], "--accuracy", NONE),
    (SIM, &["--accuracy", "abc"], "--accuracy", NONE),
    (
        SIM,
        &["--extrapolate", "--extrapolate-grids", "128,64"],
        "--extrapolate-grids",
        NONE,
    ),
    (
        SIM,
        &["--extrapolate", "--extrapolate-grids", "64"],
        "--extrapolate-grids",
        NONE,
    ),
    (
        SIM,
        &["--extrapolate", "--extrapolate-grids", "32,1048576"],
        "--extrapolate-grids",
        NONE,
    ),
    // signed values that are not plain numbers reach the flag's own check
    (SIM, &["--ratio", "-NaN"], "--ratio", NONE),
    (SIM, &["--ratio", "-inf"], "--ratio", NONE),
    (SIM, &["--r2", "-inf"], "--r2", NONE),
    (SIM, &["--accuracy", "-1%"], "--accuracy", NONE),
    (SIM, &["--time-limit", "-1s"], "--time-limit", NONE),
    (SIM, &["--steps", "-NaN"], "--steps", NONE),
    // simulate: names that end in a folder are refused before the work
    (&["simulate"], &["--out", "newdir/"], "--out", NONE),
    (&["simulate"], &["--out", "newdir/."], "--out", NONE),
    (
        &["simulate"],
        &["--out", "s.csv", "--summary", "newdir/"],
        "--summary",
        NONE,
    ),
    (
        THEORY,
        &["--model", "jg", "--ratio", "-NaN"],
        "--ratio",
        NONE,
    ),
    (
        &["theory", "--model", "jkr"],
        &["--out", "th/"],
        "--out",
        NONE,
    ),
    // simulate: clashing outputs
    (
        &["simulate"],
        &["--out", "o.csv", "--summary", "o.csv"],
        "--summary",
        NONE,
    ),
    (
        &["simulate"],
        &["--out", "o.csv", "--summary", "./sub/../o.csv"],
        "--summary",
        NONE,
    ),
    (&["simulate"], &["--out", "."], "--out", NONE),
    // sweep
    (SWEEP, &["--ratios", "1,1,1.0"], "--ratios", NONE),
    (SWEEP, &["--ratios", "-1,2"], "--ratios", NONE),
    (SWEEP, &["--ratios", "1,0.5"], "--ratios", NONE),
    (SWEEP, &["--ratios", ""], "--ratios", NONE),
    (SWEEP, &["--ratios", "1,1e8"], "--ratios", NONE),
    (SWEEP, &["--ratios", "1000", "--grid", "32"], "--grid", NONE),
    (SWEEP, &["--shard", "3/2"], "--shard", NONE),
    (SWEEP, &["--shard", "x"], "--shard", NONE),
    (SWEEP, &["--shard", "0/2"], "--shard", NONE),
    (SWEEP, &["--jobs", "0"], "--jobs", NONE),
    (SWEEP, &["--jobs", "-2"], "--jobs", NONE),
    (SWEEP, &["--jobs", "1000"], "--jobs", NONE),
    (SWEEP, &["--grid", "100"], "--grid", NONE),
    (
        SWEEP,
        &["--grid", "8192", "--ratios", "1"],
        "--grid",
        SMALL_MEMORY,
    ),
    (SWEEP, &["--steps", "0"], "--steps", NONE),
    (SWEEP, &["--start-radius", "0.5"], "--start-radius", NONE),
    (SWEEP, &["--margin", "-1"], "--margin", NONE),
    // crossed
    (CROSSED, &["--angles", "1e-10"], "--angles", NONE),
    (CROSSED, &["--angles", "0"], "--angles", NONE),
    (CROSSED, &["--angles", "120"], "--angles", NONE),
    (CROSSED, &["--angles", "-30"], "--angles", NONE),
    (CROSSED, &["--angles", "90,90"], "--angles", NONE),
    (CROSSED, &["--nu", "0.7"], "--nu", NONE),
    (CROSSED, &["--nu", "-1"], "--nu", NONE),
    (CROSSED, &["--e", "0"], "--e ", NONE),
    (CROSSED, &["--radius", "-1"], "--radius", NONE),
    (CROSSED, &["--radius", "1e300"], "--radius", NONE),
    (
        CROSSED,
        &["--work-of-adhesion", "0"],
        "--work-of-adhesion",
        NONE,
    ),
    (CROSSED, &["--jobs", "0"], "--jobs", NONE),
    (CROSSED, &["--grid", "12"], "--grid", NONE),
    (SWEEP, &["--accuracy", "-1%"], "--accuracy", NONE),
    (SWEEP, &["--ratios", "-NaN"], "--ratios", NONE),
    (SWEEP, &["--margin", "-inf"], "--margin", NONE),
    (CROSSED, &["--angles", "-NaN"], "--angles", NONE),
    // reference
    (REFERENCE, &["--ratios", "-5"], "--ratios", NONE),
    (REFERENCE, &["--ratios", "-NaN"], "--ratios", NONE),
    (REFERENCE, &["--phases", "-1"], "--phases", NONE),
    (REFERENCE, &["--target", "-1%"], "--target", NONE),
    (REFERENCE, &["--max-grid", "-64"], "--max-grid", NONE),
    (
        &["reference", "--out", "ref/table.csv"],
        &["--backend", "tpu"],
        "--backend",
        NONE,
    ),
    // coverage
    (COVERAGE, &["--ratios", "-1"], "--ratio", NONE),
    (COVERAGE, &["--margins", "-0.1"], "--margins", NONE),
    (COVERAGE, &["--margins", "-NaN"], "--margins", NONE),
    (COVERAGE, &["--grids", "-64"], "--grids", NONE),
    (
        COVERAGE,
        &["--runs-per-case", "-1"],
        "--runs-per-case",
        NONE,
    ),
    // reproduce
    (REPRODUCE, &["--jobs", "0"], "--jobs", NONE),
    (REPRODUCE, &["--jobs", "-1"], "--jobs", NONE),
    (REPRODUCE, &["--jobs", "abc"], "--jobs", NONE),
    (REPRODUCE, &[], "--quick", &[("JKRBEM_MEMORY_LIMIT", "1e8")]),
    // accuracy
    (ACCURACY, &["--backends", "cpu,cpu"], "--backends", NONE),
    (ACCURACY, &["--backends", "tpu"], "--backends", NONE),
    (ACCURACY, &["--variants", "plain,plain"], "--variants", NONE),
    (ACCURACY, &["--variants", "fancy"], "--variants", NONE),
    (ACCURACY, &["--grids", "64,32"], "--grids", NONE),
    (ACCURACY, &["--grids", "32"], "--grids", NONE),
    (ACCURACY, &["--grids", "32,100"], "--grids", NONE),
    (ACCURACY, &["--ratio", "-2"], "--ratio", NONE),
    (ACCURACY, &["--ratio", "2000"], "--ratio", NONE),
    (ACCURACY, &["--ratio", "-inf"], "--ratio", NONE),
    (ACCURACY, &["--grids", "-32,64"], "--grids", NONE),
    // theory
    (
        THEORY,
        &["--model", "jg", "--points", "1e11"],
        "--points",
        NONE,
    ),
    (
        THEORY,
        &["--model", "jg", "--points", "100000000000"],
        "--points",
        NONE,
    ),
    (
        THEORY,
        &["--model", "jg", "--points", "1"],
        "--points",
        NONE,
    ),
    (
        THEORY,
        &["--model", "jg", "--points", "-5"],
        "--points",
        NONE,
    ),
    (THEORY, &["--model", "jkr", "--ratio", "2"], "--ratio", NONE),
    (THEORY, &["--model", "jg", "--ratio", "-1"], "--ratio", NONE),
    (
        THEORY,
        &["--model", "jg", "--ratio", "1e8"],
        "--ratio",
        NONE,
    ),
    (THEORY, &["--model", "quantum"], "--model", NONE),
    (THEORY, &[], "--model", NONE),
    // collect, bench, devices, and no subcommand
    (&["collect", "nowhere"], &[], "nowhere", NONE),
    (
        &["collect", "."],
        &["--allow-missing=maybe"],
        "--allow-missing",
        NONE,
    ),
    (BENCH, &["--grids", "30"], "--grids", NONE),
    (BENCH, &["--grids", "-64"], "--grids", NONE),
    (BENCH, &["--repeats", "0"], "--repeats", NONE),
    (BENCH, &["--cg-iterations", "0"], "--cg-iterations", NONE),
    (BENCH, &["--ratio", "-5"], "--ratio", NONE),
    (BENCH, &["--margin", "1e300"], "--margin", NONE),
    (BENCH, &["--start-radius", "0"], "--start-radius", NONE),
    (BENCH, &["--ratio", "-NaN"], "--ratio", NONE),
    (BENCH, &["--repeats", "-1"], "--repeats", NONE),
    (&["collect", "."], &["--allow-missing", "-1"], "-1", NONE),
    (&["devices"], &["--foo"], "--foo", NONE),
    (&["frobnicate"], &[], "frobnicate", NONE),
];

#[test]
fn bad_invocations_of_every_subcommand_are_refused_naming_the_flag_and_creating_nothing() {
    assert!(CASES.len() >= 60, "{} cases", CASES.len());
    let mut failures = Vec::new();
    let dir = tempfile::tempdir().unwrap();
    for (base, bad, flag, env) in CASES {
        let before = listing(dir.path());
        let args: Vec<&str> = base.iter().chain(bad.iter()).copied().collect();
        let o = run_in(dir.path(), &args, env);
        let err = stderr(&o);
        let after = listing(dir.path());
        let mut why = Vec::new();
        if o.status.code() != Some(2) {
            why.push(format!("exit {:?}", o.status.code()));
        }
        if !err.contains(flag) {
            why.push(format!("{flag} not named"));
        }
        if err.contains("panicked") {
            why.push("panicked".into());
        }
        if after != before {
            why.push(format!(
                "created {:?}",
                after.difference(&before).collect::<Vec<_>>()
            ));
        }
        // Values are echoed short: no 300-digit numbers.
        if err
            .lines()
            .any(|l| l.split_whitespace().any(|w| w.len() > 60))
        {
            why.push("a very long word in the message".into());
        }
        if !why.is_empty() {
            failures.push(format!("{args:?}: {}\n    {}", why.join(", "), err.trim()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    println!("{} bad invocations refused", CASES.len());
}

fn signal(child: &Child, name: &str) {
    let ok = Command::new("kill")
        .args([&format!("-{name}"), &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill -{name} failed");
}

/// A run of a few seconds (sphere, 128²) writing `out` in `dir`.
fn long_run(dir: &Path, out: &str) -> Child {
    bin()
        .args([
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "128",
            "--backend",
            "cpu",
            "--out",
            out,
        ])
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap()
}

#[test]
fn an_existing_output_survives_a_run_that_fails_and_the_partial_file_has_a_header() {
    // Before: --out deleted the file at that path before any work, and a run that failed at
    // its first state left a 0-byte partial file without a header.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("s.csv"), "KEEP\n").unwrap();
    let mut args = SHORT.to_vec();
    args.extend(["--cg-max-iterations", "1", "--out", "s.csv"]);
    let o = run_in(dir.path(), &args, &[]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("s.csv")).unwrap(),
        "KEEP\n"
    );
    let partial = names_in(dir.path(), |n| n.starts_with("s.incomplete-"));
    assert_eq!(partial.len(), 1, "{partial:?}");
    let text = std::fs::read_to_string(dir.path().join(&partial[0])).unwrap();
    assert_eq!(
        text.lines().next(),
        Some(jkrbem::output::states_csv::HEADER)
    );
    assert!(names_in(dir.path(), |n| n.starts_with('.')).is_empty());
}

#[test]
fn sigterm_leaves_the_existing_output_untouched_and_removes_temporary_files() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("keep.csv"), "KEEP\n").unwrap();
    let mut child = long_run(dir.path(), "keep.csv");
    let started = wait_for(Duration::from_secs(20), || {
        names_in(dir.path(), |n| n.starts_with("keep.incomplete-"))
            .first()
            .and_then(|n| std::fs::read_to_string(dir.path().join(n)).ok())
            .is_some_and(|t| t.lines().count() > 2)
    });
    assert!(started, "the run did not start writing states");
    signal(&child, "TERM");
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(128 + 15), "{status:?}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("keep.csv")).unwrap(),
        "KEEP\n"
    );
    let hidden = names_in(dir.path(), |n| n.starts_with('.'));
    assert!(
        hidden.is_empty(),
        "lock or temporary files left: {hidden:?}"
    );
    assert_eq!(
        names_in(dir.path(), |n| n.starts_with("keep.incomplete-")).len(),
        1
    );
}

#[test]
fn a_second_run_on_the_same_output_is_refused_and_a_killed_runs_lock_is_taken_over() {
    // Before: two runs on one --out shared one partial name and deleted each other's files;
    // one reported "complete" over the other's rows.
    let dir = tempfile::tempdir().unwrap();
    let mut first = long_run(dir.path(), "s.csv");
    let lock = dir.path().join(".s.csv.lock");
    // Both the lock and the run's partial states, a state in them (written once its backend
    // is open: under load that comes well after the lock; a partial file that holds nothing
    // past its header is removed by the next run on s.csv).
    let started = || {
        lock.exists()
            && names_in(dir.path(), |n| n.starts_with("s.incomplete-"))
                .first()
                .and_then(|n| std::fs::read_to_string(dir.path().join(n)).ok())
                .is_some_and(|t| t.lines().count() > 1)
    };
    assert!(wait_for(Duration::from_secs(60), started));
    let mut args = SHORT.to_vec();
    args.extend(["--out", "s.csv"]);
    let second = run_in(dir.path(), &args, &[]);
    let err = stderr(&second);
    assert_eq!(second.status.code(), Some(2), "{err}");
    assert!(
        err.contains("s.csv") && err.contains("another jkrbem run"),
        "{err}"
    );
    assert!(err.contains(&first.id().to_string()), "{err}");
    assert!(!dir.path().join("s.csv").exists());
    // SIGKILL runs no handler: the lock file stays, but its lock died with the process.
    signal(&first, "KILL");
    first.wait().unwrap();
    assert!(lock.exists());
    let third = run_in(dir.path(), &args, &[]);
    assert_eq!(third.status.code(), Some(0), "{}", stderr(&third));
    let text = std::fs::read_to_string(dir.path().join("s.csv")).unwrap();
    assert_eq!(
        text.lines().next(),
        Some(jkrbem::output::states_csv::HEADER)
    );
    assert!(text.lines().count() > 20);
    assert!(!lock.exists());
    // The killed run's partial states keep their own name.
    let partial = names_in(dir.path(), |n| n.starts_with("s.incomplete-"));
    assert_eq!(partial, vec![format!("s.incomplete-{}.csv", first.id())]);
}

/// Run `args` under a file-size limit of `blocks` (of the shell's unit) in `dir`.
fn limited(dir: &Path, blocks: u32, args: &[&str]) -> Output {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -f {blocks}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_jkrbem"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

#[test]
fn a_write_error_leaves_no_file_under_the_requested_name_and_names_the_path() {
    // Before: a full disk left 0-byte or truncated files under the requested names, and some
    // errors did not say which file.
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("jg.csv"), "KEEP\n").unwrap();
    let o = limited(
        dir.path(),
        8,
        &[
            "theory", "--model", "jg", "--ratio", "2", "--points", "20000", "--out", "jg.csv",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("jg.csv") && err.contains("--out"), "{err}");
    assert_eq!(
        std::fs::read_to_string(dir.path().join("jg.csv")).unwrap(),
        "KEEP\n"
    );
    assert!(names_in(dir.path(), |n| n.starts_with('.')).is_empty());

    let mut args = SHORT.to_vec();
    args.extend(["--out", "s.csv", "--summary", "s.json"]);
    let o = limited(dir.path(), 8, &args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("s.incomplete-") && err.contains("--out"),
        "{err}"
    );
    assert!(err.contains("nothing was written to s.csv"), "{err}");
    assert!(!dir.path().join("s.csv").exists());
    assert!(!dir.path().join("s.json").exists());
}

#[test]
fn a_sweep_whose_runs_cannot_be_written_lists_every_ratio_as_incomplete() {
    // Before: ratios whose files failed were missing from sweep.csv instead of marked.
    let dir = tempfile::tempdir().unwrap();
    let o = limited(
        dir.path(),
        24,
        &[
            "sweep",
            "--ratios",
            "1,2",
            "--grid",
            "32",
            // Enough states (one per step) that each run's CSV outgrows the 24 KB limit.
            "--steps",
            "200",
            "--margin",
            "0.2",
            "--backend",
            "cpu",
            "--out",
            "sw",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let rows = jkrbem::output::sweep_csv::read_rows(&dir.path().join("sw/sweep.csv")).unwrap();
    assert_eq!(rows.len(), 2, "{rows:?}");
    for r in &rows {
        assert!(!r.complete && r.f_ad_bar.is_none(), "{r:?}");
        assert!(
            r.error
                .as_deref()
                .is_some_and(|e| e.contains("os error 27")),
            "{r:?}"
        );
    }
    assert!(!dir.path().join("sw/r1-n32.csv").exists());
    // Before: the error was a CSV parse error of the sweep's own cut-off partial file (read
    // back for the curves chart), hiding the write errors.
    assert!(
        !err.contains("CSV error") && !err.contains("found record"),
        "{err}"
    );
    for ratio in ["R1/R2 = 1:", "R1/R2 = 2:"] {
        assert!(
            err.lines()
                .any(|l| l.contains(ratio) && l.contains("File too large")),
            "{err}"
        );
    }
}

#[test]
fn non_regular_targets_are_refused() {
    // Before: as root, --out /dev/full replaced the device node with a CSV.
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.csv");
    assert!(Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap()
        .success());
    let mut args = SHORT.to_vec();
    args.extend(["--out", "pipe.csv"]);
    let o = run_in(dir.path(), &args, &[]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("pipe.csv") && err.contains("not a regular file"),
        "{err}"
    );
    use std::os::unix::fs::FileTypeExt;
    assert!(std::fs::symlink_metadata(&fifo)
        .unwrap()
        .file_type()
        .is_fifo());
}

#[test]
fn a_run_stopped_before_the_force_minimum_reports_no_adhesive_force() {
    // Before: --final-d 0 exited "complete" with "|min F̄| = 0.4898 (error −2.05 %)", the
    // last state and not a minimum.
    let dir = tempfile::tempdir().unwrap();
    let mut args = SHORT.to_vec();
    args.extend(["--final-d", "0", "--out", "s.csv", "--summary", "s.json"]);
    let o = run_in(dir.path(), &args, &[]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(!stdout.contains("adhesive force |min F̄|"), "{stdout}");
    assert!(stdout.contains("NO ADHESIVE FORCE"), "{stdout}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("s.json")).unwrap()).unwrap();
    assert_eq!(s["min_reached"], false);
    assert!(
        s["f_ad_bar"].is_null() && s["jkr_error"].is_null() && s["f_ad_bar_uncertainty"].is_null(),
        "{s}"
    );
    assert!(s["runs"][0]["lowest_f_bar"].as_f64().unwrap() < 0.0);
    // The whole pull-off passes the minimum.
    let mut args = SHORT.to_vec();
    args.extend(["--out", "t.csv", "--summary", "t.json"]);
    let o = run_in(dir.path(), &args, &[]);
    assert_eq!(o.status.code(), Some(0));
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("t.json")).unwrap()).unwrap();
    assert_eq!(s["min_reached"], true);
    // The grid over-predicts JKR's 1/2, and its estimate corrects down towards it.
    let grid_f = s["runs"][0]["f_ad_bar"].as_f64().unwrap();
    assert!(
        grid_f > 0.5 && s["f_ad_bar"].as_f64().unwrap() < grid_f,
        "{s}"
    );
    // n_d is a count of elements, not 25.999999999999996.
    let n_d = s["runs"][0]["n_d"].as_f64().unwrap();
    assert_eq!((2.0 * n_d).fract(), 0.0, "{n_d}");
}

mod collect {
    use super::*;
    use jkrbem::output::sweep_csv::{shard_path, shard_ratios, Shard, SweepRow, SweepSettings};

    fn row(ratio: f64) -> SweepRow {
        common::sweep_rows::row(ratio, 0.55)
    }

    fn sweep(grid: usize) -> SweepSettings {
        common::sweep_rows::settings(&[1.0, 2.0, 5.0], grid)
    }

    /// Shards 1..=n of the 3-ratio sweep in `dir`, each with its rows (changed by `edit`).
    fn shards(dir: &Path, n: usize, edit: impl Fn(usize, &mut Vec<SweepRow>)) {
        for k in 1..=n {
            let mut rows: Vec<SweepRow> = shard_ratios(&sweep(32).ratios, Some((k, n)))
                .into_iter()
                .map(row)
                .collect();
            edit(k, &mut rows);
            Shard::new(sweep(32), (k, n), rows)
                .write(&shard_path(&dir.join("sw"), (k, n)))
                .unwrap();
        }
    }

    fn collect(dir: &Path, extra: &[&str]) -> Output {
        let mut args = vec!["collect", "sw"];
        args.extend_from_slice(extra);
        run_in(dir, &args, &[])
    }

    /// `collect` exits 1 naming `words`, and writes no sweep.csv.
    fn refused(dir: &Path, words: &[&str]) {
        let o = collect(dir, &[]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        for w in words {
            assert!(err.contains(w), "{w:?} not in: {err}");
        }
        assert!(!dir.join("sw/sweep.csv").exists());
    }

    #[test]
    fn good_shards_merge() {
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |_, _| {});
        let o = collect(dir.path(), &[]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let rows = jkrbem::output::sweep_csv::read_rows(&dir.path().join("sw/sweep.csv")).unwrap();
        assert_eq!(rows, vec![row(1.0), row(2.0), row(5.0)]);
    }

    #[test]
    fn a_corrupt_shard_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |_, _| {});
        let path = shard_path(&dir.path().join("sw"), (2, 2));
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, &text[..text.len() / 2]).unwrap();
        refused(
            dir.path(),
            &["sweep-shard-2-of-2.json", "not a valid shard"],
        );
    }

    #[test]
    fn an_empty_file_is_refused_but_an_empty_shard_is_valid() {
        // Before: a 0-byte shard merged silently and its ratio disappeared.
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |_, _| {});
        std::fs::write(shard_path(&dir.path().join("sw"), (2, 2)), "").unwrap();
        refused(dir.path(), &["sweep-shard-2-of-2.json", "empty"]);
        // A shard given no ratio (4 shards of 3 ratios) writes a recognisable file.
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 4, |_, _| {});
        let empty: Shard = serde_json::from_str(
            &std::fs::read_to_string(shard_path(&dir.path().join("sw"), (4, 4))).unwrap(),
        )
        .unwrap();
        assert!(empty.ratios.is_empty() && empty.rows.is_empty());
        assert_eq!(collect(dir.path(), &[]).status.code(), Some(0));
    }

    #[test]
    fn duplicate_rows_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |k, rows| {
            if k == 1 {
                rows.push(row(1.0));
            }
        });
        refused(dir.path(), &["R1/R2 = 1 appears more than once"]);
    }

    #[test]
    fn a_ratio_claimed_by_the_wrong_shard_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |k, rows| {
            if k == 2 {
                rows.push(row(1.0));
            }
        });
        refused(dir.path(), &["sweep-shard-2-of-2.json", "R1/R2 = 1"]);
    }

    #[test]
    fn shards_of_different_sweeps_are_refused() {
        // Before: shards of different grids merged silently.
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |_, _| {});
        let mut other = row(2.0);
        other.grid = 64;
        Shard::new(sweep(64), (2, 2), vec![other])
            .write(&shard_path(&dir.path().join("sw"), (2, 2)))
            .unwrap();
        refused(dir.path(), &["not of one sweep", "--grid 32 against 64"]);
        // Shard files of different counts N.
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 2, |_, _| {});
        Shard::new(sweep(32), (1, 3), vec![row(1.0), row(5.0)][..1].to_vec())
            .write(&shard_path(&dir.path().join("sw"), (1, 3)))
            .unwrap();
        refused(dir.path(), &["different shard counts"]);
    }

    #[test]
    fn missing_and_incomplete_ratios_are_named_by_value() {
        // Before: complete = false and NaN rows merged with exit 0.
        let dir = tempfile::tempdir().unwrap();
        shards(dir.path(), 3, |k, rows| match k {
            2 => rows[0].complete = false,
            3 => rows[0].f_ad_bar = Some(f64::NAN),
            _ => {}
        });
        refused(dir.path(), &["R1/R2 = 2, 5 incomplete"]);
        std::fs::remove_file(shard_path(&dir.path().join("sw"), (3, 3))).unwrap();
        refused(
            dir.path(),
            &[
                "R1/R2 = 5 missing",
                "shards [3] of 3",
                "R1/R2 = 2 incomplete",
            ],
        );
        let o = collect(dir.path(), &["--allow-missing"]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let rows = jkrbem::output::sweep_csv::read_rows(&dir.path().join("sw/sweep.csv")).unwrap();
        assert_eq!(rows.len(), 2);
        assert!(!rows[1].complete);
    }

    #[test]
    fn the_missing_ratios_and_shards_are_named_at_most_twenty() {
        // Before: every missing ratio and shard was listed (9999 shards of a 10000-way split).
        let dir = tempfile::tempdir().unwrap();
        let ratios: Vec<f64> = (0..30).map(|k| 1.0 + 0.5 * k as f64).collect();
        let settings = common::sweep_rows::settings(&ratios, 32);
        Shard::new(settings, (1, 30), vec![row(1.0)])
            .write(&shard_path(&dir.path().join("sw"), (1, 30)))
            .unwrap();
        refused(
            dir.path(),
            &[
                "R1/R2 = 1.5, 2, 2.5, ",
                ", 11 and 9 more missing",
                "(shards [2, 3, 4, ",
                ", 21 and 9 more] of 30",
            ],
        );
        let err = stderr(&collect(dir.path(), &[]));
        assert!(!err.contains("11.5") && !err.contains(" 22,"), "{err}");
    }

    #[test]
    fn a_real_shard_with_no_ratio_writes_a_valid_empty_file() {
        // Before: `sweep --shard 3/3` with 2 ratios wrote a 0-byte file.
        let dir = tempfile::tempdir().unwrap();
        let o = run_in(
            dir.path(),
            &[
                "sweep",
                "--ratios",
                "1,2",
                "--shard",
                "3/3",
                "--grid",
                "32",
                "--backend",
                "cpu",
                "--out",
                "sw",
            ],
            &[],
        );
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        let shard: Shard = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join("sw/sweep-shard-3-of-3.json")).unwrap(),
        )
        .unwrap();
        assert_eq!(shard.sweep.ratios, vec![1.0, 2.0]);
        assert_eq!((shard.shard, shard.of), (3, 3));
        assert!(shard.rows.is_empty());
    }
}

/// Hardening, round two (issue 23): links, pipes, process limits, write-protected files, and
/// refusals before any work.
mod round_two {
    use super::*;
    use std::os::unix::fs::{symlink, PermissionsExt};

    fn is_root() -> bool {
        // SAFETY: geteuid has no preconditions.
        unsafe { libc::geteuid() == 0 }
    }

    #[test]
    fn a_link_at_the_lock_name_is_never_followed() {
        // Before: the lock file was opened through the link and the victim truncated to a pid.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("victim.txt"), "DATA\n").unwrap();
        symlink("victim.txt", dir.path().join(".s.csv.lock")).unwrap();
        let mut args = SHORT.to_vec();
        args.extend(["--out", "s.csv"]);
        let o = run_in(dir.path(), &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains("symbolic link") && err.contains(".s.csv.lock"),
            "{err}"
        );
        assert_eq!(
            std::fs::read_to_string(dir.path().join("victim.txt")).unwrap(),
            "DATA\n"
        );
        assert!(!dir.path().join("s.csv").exists());
        // A dangling link there is not followed either (it would create the file it names).
        std::fs::remove_file(dir.path().join(".s.csv.lock")).unwrap();
        symlink("created.txt", dir.path().join(".s.csv.lock")).unwrap();
        let o = run_in(dir.path(), &args, NONE);
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        assert!(!dir.path().join("created.txt").exists());
    }

    #[test]
    fn a_lock_file_with_a_second_name_is_refused() {
        // A hard link at the lock name to a file of the runner's would be truncated.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("victim.txt"), "DATA\n").unwrap();
        std::fs::hard_link(
            dir.path().join("victim.txt"),
            dir.path().join(".s.csv.lock"),
        )
        .unwrap();
        let mut args = SHORT.to_vec();
        args.extend(["--out", "s.csv"]);
        let o = run_in(dir.path(), &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("lock file"), "{err}");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("victim.txt")).unwrap(),
            "DATA\n"
        );
    }

    #[test]
    fn a_link_at_the_output_owned_by_another_user_is_refused() {
        // Before: a link planted by another user redirected the write to the runner's file.
        if !is_root() {
            println!("skipped: giving a link another owner needs root (CI runs as root)");
            return;
        }
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("private")).unwrap();
        std::fs::create_dir_all(dir.path().join("shared")).unwrap();
        std::fs::write(dir.path().join("private/secret.conf"), "SECRET\n").unwrap();
        let link = dir.path().join("shared/s.csv");
        symlink("../private/secret.conf", &link).unwrap();
        std::os::unix::fs::lchown(&link, Some(65534), None).unwrap();
        let mut args = SHORT.to_vec();
        args.extend(["--out", "shared/s.csv"]);
        let o = run_in(dir.path(), &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("owned by another user"), "{err}");
        assert_eq!(
            std::fs::read_to_string(dir.path().join("private/secret.conf")).unwrap(),
            "SECRET\n"
        );
        // The runner's own link is still followed (and kept).
        std::os::unix::fs::lchown(&link, Some(0), None).unwrap();
        let o = run_in(dir.path(), &args, NONE);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(
            std::fs::read_to_string(dir.path().join("private/secret.conf"))
                .unwrap()
                .starts_with("step,")
        );
        assert!(std::fs::symlink_metadata(&link).unwrap().is_symlink());
    }

    #[test]
    fn a_closed_or_full_standard_output_never_panics() {
        // Before: "failed printing to stdout", exit 101.
        let dir = tempfile::tempdir().unwrap();
        let cases: [&[&str]; 4] = [
            &[
                "simulate",
                "--ratio",
                "1",
                "--grid",
                "32",
                "--steps",
                "20",
                "--backend",
                "cpu",
                "--out",
                "s.csv",
            ],
            &["theory", "--model", "jg", "--ratio", "3", "--out", "t.csv"],
            &[
                "sweep",
                "--ratios",
                "1",
                "--grid",
                "32",
                "--steps",
                "20",
                "--backend",
                "cpu",
                "--out",
                "sw",
            ],
            &["devices"],
        ];
        for args in cases {
            // A reader that has gone away: the run ends quietly, its files written.
            let mut child = bin()
                .args(args)
                .current_dir(dir.path())
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap();
            drop(child.stdout.take());
            let o = child.wait_with_output().unwrap();
            let err = stderr(&o);
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert_eq!(o.status.code(), Some(0), "{args:?}: {err}");
            // A full device: an error naming standard output, exit code 1.
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let o = bin()
                .args(args)
                .current_dir(dir.path())
                .stdout(full)
                .output()
                .unwrap();
            let err = stderr(&o);
            assert!(!err.contains("panicked"), "{args:?}: {err}");
            assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
            assert!(err.contains("standard output"), "{args:?}: {err}");
            // Standard error full: its messages are dropped, the run is not affected.
            let full = std::fs::OpenOptions::new()
                .write(true)
                .open("/dev/full")
                .unwrap();
            let o = bin()
                .args(args)
                .current_dir(dir.path())
                .stdout(Stdio::null())
                .stderr(full)
                .output()
                .unwrap();
            assert_eq!(o.status.code(), Some(0), "{args:?} with stderr full");
        }
        assert!(dir.path().join("s.csv").exists() && dir.path().join("t.csv").exists());
    }

    /// `args` under `ulimit -v <kb>` in `dir`, with `env`.
    fn address_limited(dir: &Path, kb: u64, args: &[&str], env: &[(&str, &str)]) -> Output {
        let mut c = Command::new("sh");
        c.arg("-c")
            .arg(format!("ulimit -v {kb}; exec \"$0\" \"$@\""))
            .arg(env!("CARGO_BIN_EXE_jkrbem"))
            .args(args)
            .current_dir(dir)
            .env_remove("JKRBEM_MEMORY_LIMIT");
        for (k, v) in env {
            c.env(k, v);
        }
        c.output().unwrap()
    }

    #[test]
    fn the_memory_check_counts_the_process_limits_and_a_failed_allocation_is_an_error() {
        // Before: `ulimit -v` passed the check, the allocation aborted (exit 134) and left a
        // stale lock.
        let dir = tempfile::tempdir().unwrap();
        let args = [
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "4096",
            "--backend",
            "cpu",
            "--out",
            "big.csv",
        ];
        let o = address_limited(dir.path(), 2_000_000, &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("--grid") && err.contains("GB"), "{err}");
        assert!(listing(dir.path()).is_empty(), "{:?}", listing(dir.path()));
        // With the check told there is plenty, the allocation itself fails: exit 1, a
        // message, and no lock or temporary file left.
        let o = address_limited(
            dir.path(),
            2_000_000,
            &args,
            &[("JKRBEM_MEMORY_LIMIT", "1e12")],
        );
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains("out of memory"), "{err}");
        let left: Vec<_> = listing(dir.path())
            .into_iter()
            .filter(|p| !p.to_string_lossy().contains(".incomplete-"))
            .collect();
        assert!(left.is_empty(), "{left:?}");
    }

    #[test]
    fn refusals_before_any_work_exit_with_2() {
        // Before: a name too long or a file where a folder should be exited with 1.
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("afile"), "x").unwrap();
        let long = format!("{}.csv", "n".repeat(300));
        // Fits the system's 255 bytes, but its partial-states name would not.
        let longish = format!("{}.csv", "n".repeat(236));
        for out in ["afile/s.csv", long.as_str(), longish.as_str()] {
            let mut args = SHORT.to_vec();
            args.extend(["--out", out]);
            let o = run_in(dir.path(), &args, NONE);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{out}: {err}");
            assert!(err.contains("--out"), "{err}");
        }
        assert_eq!(listing(dir.path()).len(), 1, "{:?}", listing(dir.path()));
        // An output named as another's lock file (before: the summary was deleted with the
        // lock at the end of the run, exit 0).
        let mut args = SHORT.to_vec();
        args.extend(["--out", "s.csv", "--summary", ".s.csv.lock"]);
        let o = run_in(dir.path(), &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains("lock file of --out"), "{err}");
    }

    #[test]
    fn a_write_protected_output_is_refused_unless_forced() {
        // Before: a 0444 file was replaced silently.
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("s.csv");
        std::fs::write(&target, "KEEP\n").unwrap();
        std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o444)).unwrap();
        let mut args = SHORT.to_vec();
        args.extend(["--out", "s.csv"]);
        let o = run_in(dir.path(), &args, NONE);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains("write-protected") && err.contains("--force"),
            "{err}"
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "KEEP\n");
        args.push("--force");
        let o = run_in(dir.path(), &args, NONE);
        assert!(o.status.success(), "{}", stderr(&o));
        assert!(std::fs::read_to_string(&target)
            .unwrap()
            .starts_with("step,"));
        let mode = std::fs::metadata(&target).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o444, "the file keeps its permissions");
    }

    #[test]
    fn a_summary_that_fails_after_the_states_names_them_and_still_gives_the_answer() {
        // Before: the answer was lost and the message did not say the states were written.
        let dir = tempfile::tempdir().unwrap();
        let child = bin()
            .args([
                "simulate",
                "--ratio",
                "1",
                "--grid",
                "128",
                "--backend",
                "cpu",
                "--out",
                "s.csv",
                "--summary",
                "s.json",
            ])
            .current_dir(dir.path())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // Once the run is under way, a folder takes the summary's name.
        assert!(wait_for(Duration::from_secs(60), || !names_in(
            dir.path(),
            |n| n.starts_with("s.incomplete-")
        )
        .is_empty()));
        std::fs::create_dir(dir.path().join("s.json")).unwrap();
        let o = child.wait_with_output().unwrap();
        let err = stderr(&o);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert!(err.contains("--summary") && err.contains("s.csv"), "{err}");
        assert!(out.contains("adhesive force |min F̄| ="), "{out}");
        assert!(std::fs::read_to_string(dir.path().join("s.csv"))
            .unwrap()
            .starts_with("step,"));
    }
}

/// A preload the domain cannot hold (issue 55): a force the window of a nominally flat map
/// cannot carry is out of reach once the contact covers the window, and the run stops saying
/// so (exit 1) instead of loading for ever.
#[test]
fn a_preload_the_window_cannot_hold_stops_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    wavy_map(&dir.path().join("m.txt"));
    let args = [WAVY_MAP_RUN, &["--preload-force", "1e6", "--out", "s.csv"]].concat();
    let o = common::jkrbem(&args, dir.path());
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("the preload cannot be reached") && err.contains("covers the whole domain"),
        "{err}"
    );
    assert!(
        !dir.path().join("s.csv").exists(),
        "no complete result is claimed"
    );
}

/// A standard stream appended onto an input (issue 55): `--out - >> map`, `2>> map` and
/// `--out - >> a hard link of the map` are refused before any work (exit 2), the map left as
/// it was; the refusal is said on the other stream.
#[test]
fn a_standard_stream_appended_onto_an_input_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let map = dir.path().join("m.txt");
    let text = wavy_map(&map);
    std::fs::hard_link(&map, dir.path().join("hl.txt")).unwrap();
    for (fd, target, out) in [(1, "m.txt", "-"), (2, "m.txt", "o.csv"), (1, "hl.txt", "-")] {
        let append = std::fs::OpenOptions::new()
            .append(true)
            .open(dir.path().join(target))
            .unwrap();
        let mut cmd = bin();
        cmd.current_dir(dir.path())
            .args(WAVY_MAP_RUN)
            .args(["--out", out]);
        let said = if fd == 1 {
            let o = cmd.stdout(Stdio::from(append)).output().unwrap();
            assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
            stderr(&o)
        } else {
            let o = cmd.stderr(Stdio::from(append)).output().unwrap();
            assert_eq!(o.status.code(), Some(2));
            String::from_utf8_lossy(&o.stdout).into_owned()
        };
        assert!(
            said.contains("which this run reads"),
            "fd {fd} onto {target}: {said}"
        );
        assert_eq!(
            std::fs::read_to_string(&map).unwrap(),
            text,
            "fd {fd} onto {target}"
        );
        assert!(!dir.path().join("o.csv").exists());
    }
}

/// `simulate` of the map [`wavy_map`] writes to `m.txt`, on the CPU at 32².
const WAVY_MAP_RUN: &[&str] = &[
    "simulate",
    "--indenter",
    "height-map",
    "--height-map",
    "m.txt",
    "--spacing",
    "0.02",
    "--grid",
    "32",
    "--backend",
    "cpu",
];

/// A gently wavy surface on a window (no apex) as a text map of 48 × 48 nodes (for a spacing
/// of 0.02), written to `path`; returns its text.
fn wavy_map(path: &Path) -> String {
    let n = 48;
    let text: String = (0..n)
        .map(|j| {
            let row: Vec<String> = (0..n)
                .map(|i| {
                    let (x, y) = (i as f64 * 0.3, j as f64 * 0.2);
                    format!("{:.9e}", 0.01 * (x.sin() + y.cos()))
                })
                .collect();
            row.join(" ") + "\n"
        })
        .collect();
    std::fs::write(path, &text).unwrap();
    text
}
