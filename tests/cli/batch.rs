//! `jkrbem batch` and `jkrbem collect` of a batch: a table of 200 tiny scenes (ellipsoids of
//! several ratios, materials, mesh angles and apex offsets, flat punches, power laws) run
//! whole, and split four ways with one shard killed mid-run and resumed, collect to
//! byte-identical tables; bad cells are refused naming their row and column before anything is
//! written; `--resume` skips the scenes done and runs a changed row again.

use crate::common::{names_in, run_in, stderr, stdout, wait_for};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant, SystemTime};

/// A table of `n` tiny scenes (each a fraction of a second), every 50th without an id (so
/// named by its row number).
fn scenes(n: usize) -> String {
    let mut text = String::from(
        "id,indenter,ratio,e_star,work_of_adhesion,mesh_angle,apex_offset,exponent,grid,\
         measure,backend\n",
    );
    for i in 0..n {
        let id = if i % 50 == 49 {
            String::new()
        } else {
            format!("s{:03}", i + 1)
        };
        let e = [1.0, 2.0, 0.5][i % 3];
        let w = [1.0, 0.5, 2.0][(i / 3) % 3];
        let row = match i % 10 {
            7 => format!("{id},flat-punch,,{e},{w},,,,16"),
            8 => format!("{id},power-law,,{e},{w},,,{},32", [2, 4][(i / 10) % 2]),
            _ => format!(
                "{id},,{},{e},{w},{},{},,32",
                [1.0, 1.5, 2.0, 2.5][(i / 2) % 4],
                [0, 15, 30, 45][(i / 5) % 4],
                ["", "\"0.25,-0.5\"", "\"-0.25,0.25\""][(i / 7) % 3]
            ),
        };
        text += &format!("{row},adhesive-force,cpu\n");
    }
    text
}

/// Run `jkrbem` in `dir` and require exit code `code`.
fn run_ok(dir: &Path, args: &[&str], code: i32) -> Output {
    let o = run_in(dir, args, &[]);
    assert_eq!(
        o.status.code(),
        Some(code),
        "jkrbem {args:?}\nstdout: {}\nstderr: {}",
        stdout(&o),
        stderr(&o)
    );
    o
}

/// The scene summaries in `dir`.
fn summaries(dir: &Path) -> Vec<String> {
    if !dir.exists() {
        return Vec::new();
    }
    names_in(dir, |n| n.starts_with("scene-") && n.ends_with(".json"))
}

#[test]
fn a_batch_split_four_ways_with_a_shard_killed_and_resumed_collects_to_the_same_table() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("scenes.csv"), scenes(200)).unwrap();

    let start = Instant::now();
    let o = run_ok(
        dir,
        &["batch", "scenes.csv", "--out", "whole", "--jobs", "2"],
        0,
    );
    let whole_s = start.elapsed().as_secs_f64();
    assert!(stdout(&o).contains("200 ran (0 failed)"), "{}", stdout(&o));
    assert_eq!(summaries(&dir.join("whole")).len(), 200);

    // Shard 1 of 4 (50 scenes), killed once some but not all of its summaries exist.
    let start = Instant::now();
    let split = dir.join("split");
    let mut child = Command::new(env!("CARGO_BIN_EXE_jkrbem"))
        .args([
            "batch",
            "scenes.csv",
            "--out",
            "split",
            "--shard",
            "1/4",
            "--jobs",
            "2",
        ])
        .current_dir(dir)
        .env_remove("JKRBEM_MEMORY_LIMIT")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("the binary starts");
    let some = wait_for(Duration::from_secs(120), || summaries(&split).len() >= 3);
    child.kill().expect("SIGKILL");
    child.wait().unwrap();
    assert!(some, "shard 1 wrote fewer than 3 summaries in 120 s");
    let done_at_kill = summaries(&split);
    assert!(
        done_at_kill.len() < 50,
        "shard 1 finished all its 50 scenes before it was killed: the kill tested nothing"
    );
    // What the killed run left is whole: every summary a complete JSON document.
    for name in &done_at_kill {
        let text = std::fs::read_to_string(split.join(name)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text)
            .unwrap_or_else(|e| panic!("{name} is not whole after the kill: {e}"));
        assert_eq!(v["complete"], true, "{name}");
    }
    for k in 2..=4 {
        let shard = format!("{k}/4");
        let o = run_ok(
            dir,
            &[
                "batch",
                "scenes.csv",
                "--out",
                "split",
                "--shard",
                &shard,
                "--jobs",
                "2",
            ],
            0,
        );
        assert!(stdout(&o).contains("50 ran (0 failed)"), "{}", stdout(&o));
    }
    // Before shard 1 is resumed, collect names what is missing and writes nothing.
    let o = run_ok(dir, &["collect", "split"], 1);
    assert!(stderr(&o).contains("missing"), "{}", stderr(&o));
    assert!(!split.join("batch.csv").exists());
    let o = run_ok(
        dir,
        &[
            "batch",
            "scenes.csv",
            "--out",
            "split",
            "--shard",
            "1/4",
            "--resume",
            "--jobs",
            "2",
        ],
        0,
    );
    let ran = 50 - done_at_kill.len();
    let expected = format!("{ran} ran (0 failed), {} skipped", done_at_kill.len());
    assert!(stdout(&o).contains(&expected), "{}", stdout(&o));
    let split_s = start.elapsed().as_secs_f64();

    run_ok(dir, &["collect", "whole"], 0);
    let o = run_ok(dir, &["collect", "split"], 0);
    assert!(
        stdout(&o).contains("merged 200 of 200 scene(s) from 4 record(s)"),
        "{}",
        stdout(&o)
    );
    let whole = std::fs::read(dir.join("whole/batch.csv")).unwrap();
    let parts = std::fs::read(split.join("batch.csv")).unwrap();
    assert!(
        whole == parts,
        "the split batch's table differs from the whole one's"
    );
    let text = String::from_utf8(whole).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 201);
    assert!(lines[0].starts_with("id,indenter,ratio,"), "{}", lines[0]);
    assert!(!lines[0].contains("wall"), "{}", lines[0]);
    assert!(lines[1].starts_with("s001,ellipsoid,1,"), "{}", lines[1]);
    assert!(lines[50].starts_with("50,"), "{}", lines[50]);
    assert!(split.join("batch-timings.csv").exists());
    eprintln!(
        "200 scenes: whole (--jobs 2) {whole_s:.1} s; split four ways, one shard killed after \
         {} scenes and resumed, {split_s:.1} s",
        done_at_kill.len()
    );
}

#[test]
fn bad_cells_and_columns_are_refused_naming_their_row_and_column_before_any_work() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let table = scenes(20).replacen("s013,,2,", "s013,,0.5,", 1);
    assert!(table.contains("s013,,0.5,"));
    std::fs::write(dir.join("bad.csv"), &table).unwrap();
    let o = run_ok(dir, &["batch", "bad.csv", "--out", "runs"], 2);
    let err = stderr(&o);
    assert!(
        err.contains("bad.csv row 13 (line 14, id s013), column ratio: ratio = \"0.5\" is invalid"),
        "{err}"
    );
    assert!(
        !dir.join("runs").exists(),
        "a refused batch wrote {:?}",
        dir.join("runs")
    );

    for (table, words) in [
        ("id,ratoi\na,2\n", vec!["column 2", "did you mean ratio"]),
        (
            "id,ratio,out\na,2,x.csv\n",
            vec!["column 3", "leave the column out"],
        ),
        (
            "id,ratio,grid\na,2,32\na,3,32\n",
            vec!["rows 1 and 2 have the same id"],
        ),
        (
            "id,ratio,grid,accuracy\na,2,32,\nb,2,32,2%\n",
            vec![
                "row 2 (line 3, id b), column accuracy",
                "cannot be given together",
            ],
        ),
        (
            "id,--mesh-angle\na,400\n",
            vec!["row 1 (line 2, id a), column --mesh-angle"],
        ),
    ] {
        std::fs::write(dir.join("bad.csv"), table).unwrap();
        let o = run_ok(dir, &["batch", "bad.csv", "--out", "runs"], 2);
        for w in words {
            assert!(
                stderr(&o).contains(w),
                "{table:?}: {w:?} not in {}",
                stderr(&o)
            );
        }
        assert!(!dir.join("runs").exists());
    }
}

/// The modification time of `dir/scene-<id>.json`.
fn modified(dir: &Path, id: &str) -> SystemTime {
    std::fs::metadata(dir.join(format!("scene-{id}.json")))
        .unwrap()
        .modified()
        .unwrap()
}

#[test]
fn resume_skips_the_scenes_done_and_runs_a_changed_row_again() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let runs = dir.join("runs");
    let table = "id,ratio,grid,measure,backend\na,1,32,adhesive-force,cpu\n\
                 b,2,32,adhesive-force,cpu\nc,1.5,32,adhesive-force,cpu\n";
    std::fs::write(dir.join("scenes.csv"), table).unwrap();
    let args = ["batch", "scenes.csv", "--out", "runs", "--resume"];
    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("3 ran (0 failed), 0 skipped"),
        "{}",
        stdout(&o)
    );
    let before: Vec<SystemTime> = ["a", "b", "c"].map(|id| modified(&runs, id)).to_vec();

    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("0 ran (0 failed), 3 skipped"),
        "{}",
        stdout(&o)
    );
    let after: Vec<SystemTime> = ["a", "b", "c"].map(|id| modified(&runs, id)).to_vec();
    assert_eq!(before, after, "a complete scene was run again");

    std::fs::write(dir.join("scenes.csv"), table.replace("b,2,", "b,2.5,")).unwrap();
    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("1 ran (0 failed), 2 skipped"),
        "{}",
        stdout(&o)
    );
    assert_eq!(modified(&runs, "a"), before[0]);
    assert_ne!(modified(&runs, "b"), before[1]);
    let b: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(runs.join("scene-b.json")).unwrap()).unwrap();
    assert_eq!(b["provenance"]["request"]["ratio"], 2.5);

    // Without --resume every scene runs again, replacing its files.
    let o = run_ok(dir, &["batch", "scenes.csv", "--out", "runs"], 0);
    assert!(
        stdout(&o).contains("3 ran (0 failed), 0 skipped"),
        "{}",
        stdout(&o)
    );
    assert_ne!(modified(&runs, "a"), before[0]);

    // collect merges in the table's order; a folder that also holds a sweep's shard is refused.
    let o = run_ok(dir, &["collect", "runs"], 0);
    assert!(stdout(&o).contains("merged 3 of 3"), "{}", stdout(&o));
    let csv = std::fs::read_to_string(runs.join("batch.csv")).unwrap();
    let ids: Vec<&str> = csv.lines().skip(1).map(|l| &l[..1]).collect();
    assert_eq!(ids, ["a", "b", "c"]);
    std::fs::write(runs.join("sweep-shard-1-of-1.json"), "{}").unwrap();
    let o = run_ok(dir, &["collect", "runs"], 2);
    assert!(stderr(&o).contains("holds both"), "{}", stderr(&o));
}

#[test]
fn resume_runs_a_scene_whose_height_map_was_replaced_and_collect_refuses_its_old_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let sphere = crate::common::sphere_map_text(41, 0.05, 0.0);
    std::fs::write(dir.join("map.txt"), &sphere).unwrap();
    let table = "id,indenter,height_map,spacing,grid,measure,backend\n\
                 m,height-map,map.txt,0.05,32,adhesive-force,cpu\n\
                 e,ellipsoid,,,32,adhesive-force,cpu\n";
    std::fs::write(dir.join("scenes.csv"), table).unwrap();
    let args = ["batch", "scenes.csv", "--out", "runs", "--resume"];
    let o = run_ok(dir, &args, 0);
    assert!(stdout(&o).contains("2 ran (0 failed)"), "{}", stdout(&o));
    let recorded = |id: &str| -> serde_json::Value {
        let path = dir.join(format!("runs/scene-{id}.json"));
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    };
    let first = recorded("m");
    let files = &first["provenance"]["input_files"];
    assert_eq!(files[0]["parameter"], "height_map");
    assert_eq!(files[0]["path"], "map.txt");
    assert_eq!(files[0]["bytes"], sphere.len() as u64);
    assert!(recorded("e")["provenance"].get("input_files").is_none());
    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("0 ran (0 failed), 2 skipped"),
        "{}",
        stdout(&o)
    );

    // Another surface under the same name: the sphere of half the radius.
    let steeper: String = sphere
        .lines()
        .map(|l| {
            let row: Vec<String> = l
                .split_whitespace()
                .map(|h| format!("{:e}", 2.0 * h.parse::<f64>().unwrap()))
                .collect();
            row.join(" ") + "\n"
        })
        .collect();
    std::fs::write(dir.join("map.txt"), &steeper).unwrap();
    let o = run_ok(dir, &["collect", "runs"], 1);
    assert!(
        stderr(&o).contains("scene m:") && stderr(&o).contains("map.txt changed since it ran"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("runs/batch.csv").exists());

    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("1 ran (0 failed), 1 skipped"),
        "{}",
        stdout(&o)
    );
    let second = recorded("m");
    assert_ne!(
        second["provenance"]["input_files"],
        first["provenance"]["input_files"]
    );
    let radius = |v: &serde_json::Value| v["provenance"]["scene"]["fitted_radii"][0].as_f64();
    assert!((radius(&first).unwrap() - 1.0).abs() < 1e-6);
    assert!(
        (radius(&second).unwrap() - 0.5).abs() < 1e-6,
        "the new surface ran"
    );
    let o = run_ok(dir, &["collect", "runs"], 0);
    assert!(stdout(&o).contains("merged 2 of 2"), "{}", stdout(&o));
    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("0 ran (0 failed), 2 skipped"),
        "{}",
        stdout(&o)
    );
}

/// The text of a run's standard output and error together.
fn said(o: &Output) -> String {
    format!("{}{}", stdout(o), stderr(o))
}

#[test]
fn a_batch_speaks_of_its_table_s_columns_not_of_simulate_s_flags() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // A scene whose run fails: CG stops at its 3rd iteration.
    std::fs::write(
        dir.join("scenes.csv"),
        "id,ratio,grid,measure,backend,cg_max_iterations\na,1,64,adhesive-force,cpu,3\n\
         b,1,32,adhesive-force,cpu,\n",
    )
    .unwrap();
    let o = run_ok(dir, &["batch", "scenes.csv", "--out", "runs"], 1);
    let text = said(&o);
    assert!(text.contains("raise cg_max_iterations"), "{text}");
    assert!(
        !text.contains("--cg-") && !text.contains("--preconditioner"),
        "{text}"
    );
    // A scene's file the batch may not replace is named by the batch's own flag.
    let b = dir.join("runs/scene-b.json");
    let mut perms = std::fs::metadata(&b).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&b, perms).unwrap();
    let o = run_ok(dir, &["batch", "scenes.csv", "--out", "runs"], 2);
    let text = stderr(&o);
    assert!(
        text.contains("runs/scene-b.json (--out)") && text.contains("write-protected"),
        "{text}"
    );
    assert!(!text.contains("--summary"), "{text}");
}

#[test]
fn standard_output_is_no_batch_or_sweep_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("scenes.csv"), "id,ratio,grid\na,1,32\n").unwrap();
    for args in [
        &["batch", "scenes.csv", "--out", "-"][..],
        &["sweep", "--ratios", "1", "--grid", "32", "--out", "-"][..],
    ] {
        let o = run_ok(dir, args, 2);
        assert!(
            stderr(&o).contains("--out -: standard output holds a single file"),
            "{args:?}: {}",
            stderr(&o)
        );
        assert!(!dir.join("-").exists(), "{args:?} wrote a folder named -");
    }
}

#[test]
fn the_scene_limit_is_told_and_ids_that_differ_only_in_case_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let o = run_ok(dir, &["batch", "--help"], 0);
    assert!(stdout(&o).contains("10000 scenes"), "{}", stdout(&o));
    let docs =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/batch.md")).unwrap();
    assert!(
        docs.contains("10000 scenes"),
        "docs/batch.md says nothing of the limit"
    );
    // "A" and "a" name one file on a case-insensitive file system.
    std::fs::write(
        dir.join("scenes.csv"),
        "id,ratio,grid\nx,1,32\nScene-A,1,32\nscene-a,2,32\n",
    )
    .unwrap();
    let o = run_ok(dir, &["batch", "scenes.csv", "--out", "runs"], 2);
    let err = stderr(&o);
    assert!(
        err.contains("rows 2 and 3")
            && err.contains("\"Scene-A\" and \"scene-a\"")
            && err.contains("differ only in case"),
        "{err}"
    );
    assert!(!dir.join("runs").exists());
}

#[test]
fn collect_names_the_shards_that_left_no_record_at_most_twenty() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("scenes.csv"), scenes(30)).unwrap();
    run_ok(
        dir,
        &["batch", "scenes.csv", "--out", "runs", "--shard", "1/30"],
        0,
    );
    let o = run_ok(dir, &["collect", "runs"], 1);
    let err = stderr(&o);
    assert!(
        err.contains("(shards [2, 3, 4, ") && err.contains(", 21 and 9 more] of 30"),
        "{err}"
    );
    assert!(!err.contains("30 of 30") && !err.contains(" 22,"), "{err}");
}

#[test]
fn resume_skips_a_finished_scene_whose_files_are_write_protected() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(
        dir.join("scenes.csv"),
        "id,ratio,grid,measure,backend\na,1,32,adhesive-force,cpu\nb,2,32,adhesive-force,cpu\n",
    )
    .unwrap();
    let args = ["batch", "scenes.csv", "--out", "runs", "--resume"];
    run_ok(dir, &args, 0);
    for name in ["scene-a.json", "scene-a.csv"] {
        let path = dir.join("runs").join(name);
        let mut perms = std::fs::metadata(&path).unwrap().permissions();
        perms.set_readonly(true);
        std::fs::set_permissions(&path, perms).unwrap();
    }
    let o = run_ok(dir, &args, 0);
    assert!(
        stdout(&o).contains("0 ran (0 failed), 2 skipped"),
        "{}",
        said(&o)
    );
}

#[test]
fn a_scene_rerun_under_resume_leaves_no_pile_of_empty_partial_states() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let runs = dir.join("runs");
    // Scene a fails at its first state (CG stops at its 3rd iteration): each run of it leaves
    // its partial states, the header alone.
    std::fs::write(
        dir.join("scenes.csv"),
        "id,ratio,grid,measure,backend,cg_max_iterations\na,1,64,adhesive-force,cpu,3\n",
    )
    .unwrap();
    let partials = || names_in(&runs, |n| n.starts_with("scene-a.incomplete-"));
    let args = ["batch", "scenes.csv", "--out", "runs", "--resume"];
    for _ in 0..3 {
        run_ok(dir, &args, 1);
    }
    assert_eq!(partials().len(), 1, "{:?}", partials());
    // A killed run's partial that holds states is kept, as is a live run's, whatever it holds.
    let dead = {
        let mut child = Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        pid
    };
    let kept = [
        (format!("scene-a.incomplete-{dead}-2.csv"), "h\n1\n"),
        (format!("scene-a.incomplete-{}.csv", std::process::id()), ""),
    ];
    let gone = [
        (format!("scene-a.incomplete-{dead}.csv"), ""),
        (format!("scene-a.incomplete-{dead}-3.csv"), "header only\n"),
    ];
    for (name, text) in kept.iter().chain(&gone) {
        std::fs::write(runs.join(name), text).unwrap();
    }
    run_ok(dir, &args, 1);
    let now = partials();
    assert_eq!(now.len(), 3, "{now:?}");
    for (name, _) in &kept {
        assert!(now.contains(name), "{name} removed: {now:?}");
    }
}

/// The JSON document at `path`.
fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn a_shard_s_record_holds_its_own_rows_and_collect_checks_the_table_s_digest() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let runs = dir.join("runs");
    std::fs::write(dir.join("scenes.csv"), scenes(12)).unwrap();
    let shard = |k: usize| {
        let kn = format!("{k}/4");
        run_ok(
            dir,
            &[
                "batch",
                "scenes.csv",
                "--out",
                "runs",
                "--shard",
                &kn,
                "--jobs",
                "2",
            ],
            0,
        );
    };
    shard(1);
    shard(2);
    let record = json(&runs.join("batch-shard-1-of-4.json"));
    let rows: Vec<(u64, &str)> = record["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (s["row"].as_u64().unwrap(), s["id"].as_str().unwrap()))
        .collect();
    assert_eq!(rows, [(1, "s001"), (5, "s005"), (9, "s009")]);
    assert_eq!(record["table"]["scenes"], 12);
    let digest = record["table"]["crc32"].as_str().unwrap().to_string();
    assert_eq!(digest.len(), 8);
    assert_eq!(
        json(&runs.join("batch-shard-2-of-4.json"))["table"]["crc32"],
        digest
    );
    // Two shards of four: collect names the two that left no record, and the scenes they hold.
    let o = run_ok(dir, &["collect", "runs"], 1);
    assert!(
        stderr(&o).contains("6 of the 12 scene(s) are in no record (shards [3, 4] of 4"),
        "{}",
        stderr(&o)
    );
    let o = run_ok(dir, &["collect", "runs", "--allow-missing"], 0);
    assert!(
        stdout(&o).contains("merged 6 of 12 scene(s) from 2 record(s)"),
        "{}",
        stdout(&o)
    );
    // A shard of another table (one row changed) is refused by the digest.
    std::fs::write(
        dir.join("scenes.csv"),
        scenes(12).replacen("s002,,1,", "s002,,1.25,", 1),
    )
    .unwrap();
    shard(3);
    let o = run_ok(dir, &["collect", "runs"], 1);
    assert!(
        stderr(&o).contains("record different batches") && stderr(&o).contains(&digest),
        "{}",
        stderr(&o)
    );
    std::fs::write(dir.join("scenes.csv"), scenes(12)).unwrap();
    shard(3);
    shard(4);
    let o = run_ok(dir, &["collect", "runs"], 0);
    assert!(
        stdout(&o).contains("merged 12 of 12 scene(s) from 4 record(s)"),
        "{}",
        stdout(&o)
    );

    // A record of the earlier format (every scene of the table, no digest) is still read, and
    // must be of the same table.
    let mut every = Vec::new();
    for k in 1..=4 {
        let r = json(&runs.join(format!("batch-shard-{k}-of-4.json")));
        every.extend(r["scenes"].as_array().unwrap().iter().cloned());
    }
    every.sort_by_key(|s| s["row"].as_u64());
    let old = |scenes: &[serde_json::Value]| {
        let scenes: Vec<serde_json::Value> = scenes
            .iter()
            .map(|s| serde_json::json!({"id": s["id"], "request": s["request"]}))
            .collect();
        serde_json::json!({"format": "jkrbem batch 1", "shard": null, "scenes": scenes}).to_string()
    };
    std::fs::write(runs.join("batch.json"), old(&every)).unwrap();
    let o = run_ok(dir, &["collect", "runs"], 0);
    assert!(
        stdout(&o).contains("merged 12 of 12 scene(s) from 5 record(s)"),
        "{}",
        stdout(&o)
    );
    every[4]["request"]["ratio"] = serde_json::json!(2.25);
    std::fs::write(runs.join("batch.json"), old(&every)).unwrap();
    let o = run_ok(dir, &["collect", "runs"], 1);
    assert!(
        stderr(&o).contains("record different batches"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn collect_refuses_a_record_that_was_edited() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let runs = dir.join("runs");
    std::fs::write(dir.join("scenes.csv"), scenes(4)).unwrap();
    for kn in ["1/2", "2/2"] {
        run_ok(
            dir,
            &["batch", "scenes.csv", "--out", "runs", "--shard", kn],
            0,
        );
    }
    run_ok(dir, &["collect", "runs"], 0);
    let path = runs.join("batch-shard-1-of-2.json");
    let text = std::fs::read_to_string(&path).unwrap();
    let refused = |edited: String, words: &[&str]| {
        std::fs::write(&path, edited).unwrap();
        let o = run_ok(dir, &["collect", "runs"], 1);
        for w in words {
            assert!(stderr(&o).contains(w), "{w:?} not in {}", stderr(&o));
        }
    };
    // A request changed, the digest left as it was.
    refused(
        text.replacen("\"ratio\":1.0", "\"ratio\":1.5", 1),
        &["do not make the table their digest names"],
    );
    // A row taken out; a row of the other shard put in.
    let lines: Vec<&str> = text.lines().collect();
    let row3 = lines.iter().position(|l| l.contains("\"row\":3")).unwrap();
    let mut cut = lines.clone();
    cut.remove(row3);
    cut[row3 - 1] = cut[row3 - 1].trim_end_matches(',');
    refused(
        cut.join("\n"),
        &[
            "not a valid batch record",
            "holds 1 row(s), not the 2 of shard 1 of 2",
        ],
    );
    refused(
        text.replacen("\"row\":3", "\"row\":4", 1),
        &["not a valid batch record", "not the 2 of shard 1 of 2"],
    );
    std::fs::write(&path, &text).unwrap();
    run_ok(dir, &["collect", "runs"], 0);
}
