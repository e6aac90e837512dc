//! Hardening, round three (issue 41): files. No file a run reads is ever one it writes (the
//! height map, `collect`'s shards, the program itself, a redirected standard stream), however
//! it is spelled or linked; two outputs that are one file are refused naming both flags, and
//! never blamed on another run; a link put at an output during the run is neither followed nor
//! replaced, the result kept and said where; a killed run's temporaries are removed by the
//! next; an output that could not be written is said in the summary.
//!
//! Every case failed before its fix: what it did then is in its first comment.

use crate::common;
use crate::common::SHORT;

use common::{names_in, stderr, wait_for};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::Duration;

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_jkrbem"));
    c.env_remove("JKRBEM_MEMORY_LIMIT");
    c
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    bin()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

/// Every file and folder under `dir`, hidden ones included, with each file's content (links
/// as their target), so that "nothing changed" is one comparison.
fn snapshot(dir: &Path) -> BTreeSet<(PathBuf, String)> {
    fn walk(root: &Path, dir: &Path, out: &mut BTreeSet<(PathBuf, String)>) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(root).unwrap().to_path_buf();
            let m = std::fs::symlink_metadata(&p).unwrap();
            if m.file_type().is_symlink() {
                let to = std::fs::read_link(&p).unwrap();
                out.insert((rel, format!("-> {}", to.display())));
            } else if m.is_dir() {
                out.insert((rel, "folder".into()));
                walk(root, &p, out);
            } else {
                let bytes = std::fs::read(&p).unwrap();
                out.insert((rel, String::from_utf8_lossy(&bytes).into_owned()));
            }
        }
    }
    let mut out = BTreeSet::new();
    walk(dir, dir, &mut out);
    out
}

/// The outcome must be a refusal before any work: exit status 2, every one of `words` in the
/// message, no "another jkrbem run", and nothing in `dir` created or changed.
fn assert_refused(o: &Output, words: &[&str], dir: &Path, before: &BTreeSet<(PathBuf, String)>) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not in: {err}");
    }
    assert!(!err.contains("another jkrbem run"), "{err}");
    assert_eq!(&snapshot(dir), before, "{err}");
}

/// A sampled sphere of radius 1 (161 × 161 nodes, spacing 0.05) as a text grid, for
/// `--indenter height-map`.
fn sphere_map() -> String {
    common::sphere_map_text(161, 0.05, 2.0)
}

/// `simulate` of the height map `map` (as given), with `extra` naming its outputs.
fn map_run(dir: &Path, map: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "simulate",
        "--indenter",
        "height-map",
        "--height-map",
        map,
        "--spacing",
        "0.05",
        "--grid",
        "32",
        "--measure",
        "adhesive-force",
        "--backend",
        "cpu",
    ];
    args.extend_from_slice(extra);
    run_in(dir, &args)
}

#[test]
fn the_height_map_is_never_an_output_however_it_is_named() {
    // Before: `--height-map surf.csv --out surf.csv` replaced the map with the states (exit
    // 0), as did --summary, a link or another spelling of it; a hard link was written over
    // without a word, and the map named as a lock file was truncated and removed.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("surf.csv"), sphere_map()).unwrap();
    std::fs::create_dir(d.join("sub")).unwrap();
    std::os::unix::fs::symlink("surf.csv", d.join("link.csv")).unwrap();
    std::fs::hard_link(d.join("surf.csv"), d.join("hard.json")).unwrap();
    std::fs::write(d.join(".s.csv.lock"), sphere_map()).unwrap();
    let abs = d.join("surf.csv").display().to_string();
    let before = snapshot(d);
    let cases: &[(&str, &[&str], &[&str])] = &[
        ("surf.csv", &["--out", "surf.csv"], &["--out surf.csv"]),
        (
            "surf.csv",
            &["--out", "s.csv", "--summary", "surf.csv"],
            &["--summary surf.csv"],
        ),
        ("./surf.csv", &["--out", &abs], &["--out"]),
        ("sub/../surf.csv", &["--out", "surf.csv"], &["--out"]),
        ("surf.csv", &["--out", "link.csv"], &["--out link.csv"]),
        (
            "surf.csv",
            &["--out", "s.csv", "--summary", "hard.json"],
            &["--summary hard.json"],
        ),
        (
            "surf.csv",
            &[
                "--out",
                "s.csv",
                "--fields",
                "minimum",
                "--summary",
                "hard.json",
            ],
            &["--summary hard.json"],
        ),
        (
            ".s.csv.lock",
            &["--out", "s.csv"],
            &["--out s.csv", "lock file"],
        ),
    ];
    for (map, extra, words) in cases {
        let o = map_run(d, map, extra);
        let mut all = vec!["--height-map", "which this run reads"];
        all.extend_from_slice(words);
        assert_refused(&o, &all, d, &before);
    }
}

/// Shards 1 and 2 of a sweep of R1/R2 = 1, 2, 5 in `dir/sw`.
fn two_shards(dir: &Path) {
    use jkrbem::output::sweep_csv::{shard_path, shard_ratios, Shard};
    let sweep = common::sweep_rows::settings(&[1.0, 2.0, 5.0], 32);
    for k in 1..=2 {
        let rows = shard_ratios(&sweep.ratios, Some((k, 2)))
            .into_iter()
            .map(|r| common::sweep_rows::row(r, 0.55))
            .collect();
        Shard::new(sweep.clone(), (k, 2), rows)
            .write(&shard_path(&dir.join("sw"), (k, 2)))
            .unwrap();
    }
}

#[test]
fn collect_never_writes_over_a_shard_it_reads() {
    // Before: sw/sweep.csv, a link to a shard, was written through (the shard replaced by the
    // merged CSV, exit 0); a chart hard-linked to a shard was written over without a word.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    two_shards(d);
    std::os::unix::fs::symlink("sweep-shard-1-of-2.json", d.join("sw/sweep.csv")).unwrap();
    let before = snapshot(d);
    let o = run_in(d, &["collect", "sw"]);
    assert_refused(
        &o,
        &[
            "DIR sw/sweep.csv",
            "sweep-shard-1-of-2.json",
            "which this run reads",
        ],
        d,
        &before,
    );
    std::fs::remove_file(d.join("sw/sweep.csv")).unwrap();
    std::fs::hard_link(
        d.join("sw/sweep-shard-2-of-2.json"),
        d.join("sw/pulloff_curves.svg"),
    )
    .unwrap();
    let before = snapshot(d);
    let o = run_in(d, &["collect", "sw"]);
    assert_refused(
        &o,
        &["pulloff_curves.svg", "sweep-shard-2-of-2.json"],
        d,
        &before,
    );
    // Without the link, the merge goes ahead.
    std::fs::remove_file(d.join("sw/pulloff_curves.svg")).unwrap();
    let o = run_in(d, &["collect", "sw"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn the_program_and_its_redirected_output_are_never_outputs() {
    // Before: `jkrbem theory --out <the jkrbem binary>` replaced the running program with a
    // CSV (exit 0), and `--out log.txt > log.txt` replaced the file the messages went to.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let program = d.join("jk");
    std::fs::copy(env!("CARGO_BIN_EXE_jkrbem"), &program).unwrap();
    let size = std::fs::metadata(&program).unwrap().len();
    let o = Command::new(&program)
        .args(["theory", "--model", "jkr", "--out"])
        .arg(&program)
        .current_dir(d)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--out") && err.contains("the jkrbem program itself"),
        "{err}"
    );
    assert_eq!(std::fs::metadata(&program).unwrap().len(), size);

    let log = d.join("log.txt");
    std::fs::write(&log, "").unwrap();
    for out in ["log.txt", "/dev/stdout"] {
        let o = bin()
            .args(["theory", "--model", "jkr", "--out", out])
            .current_dir(d)
            .stdout(Stdio::from(std::fs::File::create(&log).unwrap()))
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{out}: {err}");
        // (/dev/stdout is root's link: a user other than root is refused it as such.)
        let said = err.contains("standard output") || err.contains("owned by another user");
        assert!(err.contains("--out") && said, "{out}: {err}");
        assert_eq!(std::fs::read_to_string(&log).unwrap(), "", "{out}");
    }
    let left = names_in(d, |n| n != "jk" && n != "log.txt");
    assert!(left.is_empty(), "{left:?}");
}

#[test]
fn two_outputs_that_are_one_file_are_refused_naming_both_flags() {
    // Before: --out and --summary hard-linked to one file ran to the end, each written over
    // the other's name (exit 0).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("s.csv"), "KEEP\n").unwrap();
    std::fs::hard_link(d.join("s.csv"), d.join("t.json")).unwrap();
    let before = snapshot(d);
    let mut args = SHORT.to_vec();
    args.extend(["--out", "s.csv", "--summary", "t.json"]);
    let o = run_in(d, &args);
    assert_refused(
        &o,
        &["--summary t.json is the same file as --out s.csv"],
        d,
        &before,
    );
}

#[test]
fn a_clash_between_one_run_s_own_outputs_is_not_blamed_on_another_run() {
    // Before: --out link.csv (a link to real.csv) with --summary real.csv, or two spellings of
    // one file through a linked folder and `..`, were refused as "being written by another
    // jkrbem run (process N)", N being the run itself; and --summary on the pressure picture
    // of --fields was said to clash with --out.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("real.csv"), "KEEP\n").unwrap();
    std::os::unix::fs::symlink("real.csv", d.join("link.csv")).unwrap();
    std::fs::create_dir_all(d.join("y/z")).unwrap();
    std::fs::create_dir(d.join("x")).unwrap();
    std::os::unix::fs::symlink("../y/z", d.join("x/link")).unwrap();
    let before = snapshot(d);
    let cases: &[(&[&str], &[&str])] = &[
        (
            &["--out", "link.csv", "--summary", "real.csv"],
            &["--summary real.csv is the same file as --out link.csv"],
        ),
        (
            // x/link/.. is y (the link's folder's parent), not x.
            &["--out", "y/s.csv", "--summary", "x/link/../s.csv"],
            &["--summary x/link/../s.csv is the same file as --out y/s.csv"],
        ),
        (
            &[
                "--out",
                "a.csv",
                "--fields",
                "minimum",
                "--summary",
                "a.pressure.svg",
            ],
            &["--summary a.pressure.svg is the same file as --fields a.pressure.svg"],
        ),
    ];
    for (extra, words) in cases {
        let mut args = SHORT.to_vec();
        args.extend_from_slice(extra);
        let o = run_in(d, &args);
        assert_refused(&o, words, d, &before);
    }
}

#[test]
fn a_link_put_at_the_output_during_the_run_is_not_followed_and_the_result_is_kept() {
    // Before: the run was refused after all its work, with exit status 2 ("before any work"),
    // and the message did not say where the finished states were.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let child: Child = bin()
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
        ])
        .current_dir(d)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let partial = format!("s.incomplete-{}.csv", child.id());
    let started = wait_for(Duration::from_secs(120), || {
        std::fs::read_to_string(d.join(&partial)).is_ok_and(|t| t.lines().count() > 2)
    });
    assert!(started, "the run did not start writing states");
    std::os::unix::fs::symlink("elsewhere.csv", d.join("s.csv")).unwrap();
    let o = child.wait_with_output().unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("symbolic link") && err.contains("--out") && err.contains(&partial),
        "{err}"
    );
    assert!(err.contains("complete result is kept"), "{err}");
    // The link is untouched, nothing was written where it points, and the states are whole.
    assert_eq!(
        std::fs::read_link(d.join("s.csv")).unwrap(),
        PathBuf::from("elsewhere.csv")
    );
    assert!(!d.join("elsewhere.csv").exists());
    let text = std::fs::read_to_string(d.join(&partial)).unwrap();
    assert_eq!(
        text.lines().next(),
        Some(jkrbem::output::states_csv::HEADER)
    );
    assert!(text.ends_with('\n') && text.lines().count() > 20, "{text}");
    assert!(names_in(d, |n| n.starts_with('.')).is_empty());
}

#[test]
fn a_killed_run_s_temporary_is_removed_by_the_next_run_on_its_target() {
    // Before: the `.tmp` file a SIGKILL left during the fields' write (4 MB) stayed for good:
    // its name did not say whose it was, and no run removed it.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut gone = Command::new("true").spawn().unwrap();
    let dead = gone.id();
    gone.wait().unwrap();
    let stale = format!(".s.fields.npz.{dead}.Ab12Cd.tmp");
    std::fs::write(d.join(&stale), vec![0u8; 4 << 20]).unwrap();
    // A live process's temporary, and files of other names, are never removed.
    let keep = [
        format!(".s.fields.npz.{}.Ab12Cd.tmp", std::process::id()),
        ".s.fields.npz.Ab12Cd.tmp".to_string(),
        format!(".t.fields.npz.{dead}.Ab12Cd.tmp"),
    ];
    for k in &keep {
        std::fs::write(d.join(k), "x").unwrap();
    }
    let mut args = SHORT.to_vec();
    args.extend(["--out", "s.csv", "--fields", "minimum"]);
    let o = run_in(d, &args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(d.join("s.fields.npz").exists());
    assert!(
        !d.join(&stale).exists(),
        "the stale temporary is still there"
    );
    for k in &keep {
        assert!(d.join(k).exists(), "{k} was removed");
    }
}

#[test]
fn a_fields_file_that_cannot_be_written_is_said_in_the_summary() {
    // Before: the fields file failed (a file-size limit) and the summary said nothing of it:
    // `complete: true`, no warning, as if every output had been written.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut args = SHORT.to_vec();
    args.extend([
        "--out",
        "s.csv",
        "--summary",
        "s.json",
        "--fields",
        "every:1",
    ]);
    // 64 KiB (dash counts 512-byte blocks): the states and the summary fit, the fields do not.
    let o = Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 128; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_jkrbem"))
        .args(&args)
        .current_dir(d)
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("s.fields.npz") && err.contains("--fields"),
        "{err}"
    );
    assert!(!d.join("s.fields.npz").exists());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("s.json")).unwrap()).unwrap();
    let warnings = summary["warnings"].as_array().unwrap();
    assert!(
        warnings.iter().any(|w| w
            .as_str()
            .is_some_and(|w| w.contains("outputs incomplete") && w.contains("s.fields.npz"))),
        "{summary}"
    );
    assert!(names_in(d, |n| n.starts_with('.')).is_empty());
}

#[test]
fn names_with_control_characters_are_refused_before_any_work() {
    // Before: `--out $'a\nb.csv'` ran and wrote a file whose name broke every message that
    // named it ("states written to a", "b.csv" on two lines).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (flag, name) in [("--out", "a\nb.csv"), ("--summary", "s\u{1b}[2J.json")] {
        let mut args = SHORT.to_vec();
        if flag == "--summary" {
            args.extend(["--out", "s.csv"]);
        }
        args.extend([flag, name]);
        let o = run_in(d, &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(
            err.contains(flag) && err.contains("control character"),
            "{err}"
        );
        assert!(!err.contains(name), "the name is shown escaped: {err}");
        assert!(names_in(d, |_| true).is_empty());
    }
}

#[test]
fn an_output_in_a_folder_that_is_a_link_to_nothing_is_refused_saying_so() {
    // Before: refused with "cannot write dangling (--out): File exists (os error 17)", which
    // names neither the link nor what is wrong with it.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::os::unix::fs::symlink("nowhere", d.join("dangling")).unwrap();
    let before = snapshot(d);
    let mut args = SHORT.to_vec();
    args.extend(["--out", "dangling/s.csv"]);
    let o = run_in(d, &args);
    assert_refused(
        &o,
        &["--out", "dangling", "symbolic link to nothing (nowhere)"],
        d,
        &before,
    );
    // A folder reached through a link that exists is written through it.
    std::fs::create_dir(d.join("real")).unwrap();
    std::os::unix::fs::symlink("real", d.join("linked")).unwrap();
    let mut args = SHORT.to_vec();
    args.extend(["--out", "linked/s.csv"]);
    let o = run_in(d, &args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(d.join("real/s.csv").is_file());
}

#[test]
fn a_file_at_the_lock_name_that_is_no_lock_is_kept() {
    // Before: it was taken over as a killed run's lock: truncated to the run's process id and
    // removed at the end (exit 0).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join(".s.csv.lock"), "my notes\n").unwrap();
    let before = snapshot(d);
    let mut args = SHORT.to_vec();
    args.extend(["--out", "s.csv"]);
    let o = run_in(d, &args);
    assert_refused(&o, &["--out", "not a jkrbem lock file"], d, &before);
}
