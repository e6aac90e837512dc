//! Hardening of `jkrbem collect` and of the sweep charts (issue items 13 and 16): a shard row
//! that disagrees with its ratio's own summary, or a sweep with a ratio outside [1, 1000], is
//! refused naming the ratio and the file; a ratio whose states are missing from the pull-off
//! chart is warned of; a shard count N above what `sweep --shard` accepts is refused before
//! anything is allocated for it; a FIFO, a device or an oversized file named as a shard is
//! refused without blocking or filling memory; and the legend of a 30-ratio sweep's chart stays
//! inside its picture.

use crate::common;
use crate::common::stdout;
use jkrbem::output::sweep_csv::{shard_path, shard_ratios, Shard, SweepRow, SweepSettings};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_jkrbem"));
    c.env_remove("JKRBEM_MEMORY_LIMIT");
    c
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Run the binary in `dir` with `args`, under an address-space limit of 2 GiB (so that a run
/// that tries to fill memory fails at once instead of swapping), killed after `limit`; `None`
/// if it had to be killed.
fn run_limited(dir: &Path, args: &[&str], limit: Duration) -> Option<Output> {
    let mut script = String::from("ulimit -v 2097152; exec \"$0\"");
    for k in 1..=args.len() {
        script += &format!(" \"${{{k}}}\"");
    }
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_jkrbem"))
        .args(args)
        .env_remove("JKRBEM_MEMORY_LIMIT")
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    let start = Instant::now();
    while start.elapsed() < limit {
        if child
            .try_wait()
            .expect("the child can be waited on")
            .is_some()
        {
            return Some(child.wait_with_output().expect("its output"));
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// `jkrbem collect sw` in `dir` (limited as [`run_limited`], 30 s).
fn collect(dir: &Path) -> Output {
    run_limited(dir, &["collect", "sw"], Duration::from_secs(30))
        .expect("collect finished within 30 s (it blocked or read without end)")
}

/// `collect` exits 1 naming every one of `words` on stderr, without a panic, and writes no
/// sweep.csv.
fn refused(dir: &Path, words: &[&str]) {
    let o = collect(dir);
    let err = stderr(&o);
    assert_eq!(
        o.status.code(),
        Some(1),
        "stdout: {}\nstderr: {err}",
        stdout(&o)
    );
    assert!(!err.contains("panicked"), "{err}");
    for w in words {
        assert!(err.contains(w), "{w:?} not in: {err}");
    }
    assert!(!dir.join("sw/sweep.csv").exists());
}

/// A real sweep of R1/R2 = 1, 2 on a 32 grid, split into two shards, run into `dir/sw`.
fn real_shards(dir: &Path) {
    for k in ["1/2", "2/2"] {
        let o = bin()
            .args([
                "sweep",
                "--ratios",
                "1,2",
                "--grid",
                "32",
                "--steps",
                "20",
                "--backend",
                "cpu",
                "--shard",
                k,
                "--out",
                "sw",
            ])
            .current_dir(dir)
            .output()
            .expect("the binary runs");
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
}

fn row(ratio: f64) -> SweepRow {
    common::sweep_rows::row(ratio, 0.5 / ratio.powf(0.3))
}

fn settings(ratios: &[f64]) -> SweepSettings {
    common::sweep_rows::settings(ratios, 32)
}

/// Shards 1..=n of a sweep of `ratios` in `dir/sw`, every row written (no per-ratio files).
fn crafted_shards(dir: &Path, ratios: &[f64], n: usize) {
    for k in 1..=n {
        let rows = shard_ratios(ratios, Some((k, n)))
            .into_iter()
            .map(row)
            .collect();
        Shard::new(settings(ratios), (k, n), rows)
            .write(&shard_path(&dir.join("sw"), (k, n)))
            .unwrap();
    }
}

/// Replace the value of `"key": …` (first occurrence) in the JSON file `path` by `value`.
fn edit_json(path: &Path, key: &str, value: &str) {
    let text = std::fs::read_to_string(path).unwrap();
    let at = text.find(&format!("\"{key}\": ")).expect("the key") + key.len() + 4;
    let end = at + text[at..].find([',', '\n']).unwrap();
    std::fs::write(path, format!("{}{value}{}", &text[..at], &text[end..])).unwrap();
}

#[test]
fn an_edited_shard_row_is_refused_against_its_ratios_summary() {
    // Before: a row's f_ad_bar edited to 0.9 merged with exit 0.
    let dir = tempfile::tempdir().unwrap();
    real_shards(dir.path());
    let o = collect(dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    std::fs::remove_file(dir.path().join("sw/sweep.csv")).unwrap();
    edit_json(
        &dir.path().join("sw/sweep-shard-1-of-2.json"),
        "f_ad_bar",
        "0.9",
    );
    refused(
        dir.path(),
        &[
            "R1/R2 = 1",
            "sweep-shard-1-of-2.json",
            "r1-n32.json",
            "f_ad_bar = 0.9",
        ],
    );
    // An edit to whether it completed is caught the same way.
    let dir = tempfile::tempdir().unwrap();
    real_shards(dir.path());
    edit_json(
        &dir.path().join("sw/sweep-shard-2-of-2.json"),
        "c_bar_at_min",
        "0.5",
    );
    refused(dir.path(), &["R1/R2 = 2", "r2-n32.json", "c_bar_at_min"]);
}

#[test]
fn a_row_without_its_summary_is_merged_with_a_warning() {
    // Before: nothing said that the row could not be checked.
    let dir = tempfile::tempdir().unwrap();
    real_shards(dir.path());
    std::fs::remove_file(dir.path().join("sw/r2-n32.json")).unwrap();
    let o = collect(dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // Warnings go to standard error; stdout keeps only what was merged.
    let out = stderr(&o);
    assert!(
        out.contains("warning") && out.contains("R1/R2 = 2") && out.contains("r2-n32.json"),
        "{out}"
    );
    assert!(!stdout(&o).contains("warning"), "{}", stdout(&o));
}

#[test]
fn a_summary_that_is_not_a_regular_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    real_shards(dir.path());
    let summary = dir.path().join("sw/r1-n32.json");
    std::fs::remove_file(&summary).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &summary).unwrap();
    refused(dir.path(), &["r1-n32.json", "not a regular file"]);
}

#[test]
fn ratios_outside_the_range_of_sweep_are_refused() {
    // Before: a sweep of R1/R2 = 0.5 and 2000 merged with exit 0.
    for (bad, shown) in [
        (0.5, "R1/R2 = 0.5"),
        (2000.0, "R1/R2 = 2000"),
        (-3.0, "R1/R2 = -3"),
    ] {
        let dir = tempfile::tempdir().unwrap();
        crafted_shards(dir.path(), &[1.0, bad], 2);
        refused(dir.path(), &[shown, "[1, 1000]", "sweep-shard-"]);
    }
}

#[test]
fn a_missing_states_file_is_named_and_shown_in_the_curves_chart() {
    // Before: pulloff_curves.svg was drawn without R1/R2 = 2's curve and nothing was said.
    let dir = tempfile::tempdir().unwrap();
    real_shards(dir.path());
    std::fs::remove_file(dir.path().join("sw/r2-n32.csv")).unwrap();
    let o = collect(dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stderr(&o);
    assert!(
        out.contains("warning")
            && out.contains("R1/R2 = 2")
            && out.contains("r2-n32.csv")
            && out.contains("pulloff_curves.svg"),
        "{out}"
    );
    assert!(!out.contains("R1/R2 = 1:"), "{out}");
    let svg = std::fs::read_to_string(dir.path().join("sw/pulloff_curves.svg")).unwrap();
    assert!(svg.contains("no states file"), "the legend says so");
}

#[test]
fn a_shard_count_above_what_sweep_accepts_is_refused_before_allocating() {
    // Before: sweep-shard-1-of-1000000000.json allocated gigabytes (and ran out of memory
    // under the 2 GiB limit).
    let dir = tempfile::tempdir().unwrap();
    let n = 1_000_000_000;
    Shard::new(settings(&[1.0, 2.0]), (1, n), vec![row(1.0)])
        .write(&shard_path(&dir.path().join("sw"), (1, n)))
        .unwrap();
    refused(
        dir.path(),
        &["sweep-shard-1-of-1000000000.json", "at most 10000"],
    );
    // A count too large for any integer is refused the same way, not ignored.
    let dir = tempfile::tempdir().unwrap();
    crafted_shards(dir.path(), &[1.0, 2.0], 1);
    std::fs::write(
        dir.path()
            .join("sw/sweep-shard-1-of-99999999999999999999999999.json"),
        "{}",
    )
    .unwrap();
    refused(dir.path(), &["99999999999999999999999999", "at most 10000"]);
}

#[test]
fn a_fifo_named_as_a_shard_does_not_block() {
    // Before: collect waited for a writer forever.
    let dir = tempfile::tempdir().unwrap();
    crafted_shards(dir.path(), &[1.0, 2.0], 2);
    let fifo = shard_path(&dir.path().join("sw"), (2, 2));
    std::fs::remove_file(&fifo).unwrap();
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    refused(
        dir.path(),
        &["sweep-shard-2-of-2.json", "not a regular file"],
    );
}

#[test]
fn a_device_named_as_a_shard_is_not_read() {
    // Before: a link to /dev/zero was read until memory ran out.
    let dir = tempfile::tempdir().unwrap();
    crafted_shards(dir.path(), &[1.0, 2.0], 2);
    let shard = shard_path(&dir.path().join("sw"), (2, 2));
    std::fs::remove_file(&shard).unwrap();
    std::os::unix::fs::symlink("/dev/zero", &shard).unwrap();
    refused(
        dir.path(),
        &["sweep-shard-2-of-2.json", "not a regular file"],
    );
}

#[test]
fn a_shard_file_larger_than_any_shard_is_refused() {
    // Before: a valid shard padded to 17 MiB was read whole and merged.
    let dir = tempfile::tempdir().unwrap();
    crafted_shards(dir.path(), &[1.0, 2.0], 2);
    let shard = shard_path(&dir.path().join("sw"), (2, 2));
    let mut text = std::fs::read_to_string(&shard).unwrap();
    text += &" ".repeat(17 << 20);
    std::fs::write(&shard, text).unwrap();
    refused(
        dir.path(),
        &["sweep-shard-2-of-2.json", "larger than 16 MiB"],
    );
}

/// The picture's (width, height) and every text element's (x, text) of an SVG from plotters.
fn svg_texts(svg: &str) -> ((f64, f64), Vec<(f64, String)>) {
    let attr = |part: &str, name: &str| -> f64 {
        let key = format!(" {name}=\"");
        part.split_once(&key)
            .and_then(|(_, r)| r.split_once('"'))
            .and_then(|(v, _)| v.parse().ok())
            .unwrap_or(f64::NAN)
    };
    let head = svg.split_once('>').unwrap().0;
    let size = (attr(head, "width"), attr(head, "height"));
    let texts = svg
        .split("<text")
        .skip(1)
        .map(|part| {
            let body = part
                .split_once('>')
                .map(|(_, r)| r.split("</text>").next().unwrap_or("").trim().to_string())
                .unwrap_or_default();
            (attr(part, "x"), body)
        })
        .collect();
    (size, texts)
}

#[test]
fn the_legend_of_a_30_ratio_sweep_stays_inside_its_chart() {
    // Before: force_vs_ratio.svg's legend listed all 30 grids on one line, running past the
    // right edge of the picture.
    let dir = tempfile::tempdir().unwrap();
    let ratios: Vec<f64> = (1..=30).map(|k| k as f64).collect();
    crafted_shards(dir.path(), &ratios, 3);
    let o = collect(dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for chart in ["force_vs_ratio.svg", "pulloff_curves.svg"] {
        let svg = std::fs::read_to_string(dir.path().join("sw").join(chart)).unwrap();
        let ((width, _), texts) = svg_texts(&svg);
        assert!(width.is_finite() && !texts.is_empty(), "{chart}");
        let view = format!("viewBox=\"0 0 {width} ");
        assert!(svg.contains(&view), "{chart}: no {view}");
        // Every text's glyphs, rendered with the embedded font, end inside the picture.
        let tree = jkrbem::output::render::svg_tree(&svg).unwrap();
        for (text, [_, _, right, _]) in jkrbem::output::render::text_boxes(&tree) {
            assert!(
                right as f64 <= width + 0.5,
                "{chart}: {text:?} ends at x = {right}, past the width {width}"
            );
        }
    }
}
