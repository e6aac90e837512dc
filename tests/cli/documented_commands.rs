//! Every fenced command of README.md and docs/*.md runs (issue 55, item 19): an example that
//! the program refuses (a roughness map smaller than its domain) or that reads a file nothing
//! makes fails this test instead of a reader.
//!
//! **What runs.** Each document's fenced shell blocks (```sh, ```bash, ```shell: a command a
//! line, `\` continuations joined, `#` comments dropped; in ```console blocks the lines after
//! `$ `) and its ```python blocks, in the order the document shows them, in one temporary folder
//! per document (a command may read what an earlier one of its document wrote), through `sh -c`
//! with the binary under test first on `PATH` as `jkrbem`. A command passes when it exits 0
//! within [`TIME_LIMIT`]; every failure is listed at the end, with its document and line.
//!
//! **How commands are shrunk** (so that the whole takes 105–150 s on 2 cores shared with other
//! builds; the documented sizes would take hours):
//! - `cargo run --release --` runs as `jkrbem`: the binary cargo builds is the one under test;
//! - a command in [`SHRUNK`] runs as the command beside it there: the same subcommand and kind
//!   of work on coarser grids, to a looser accuracy or over fewer cases (the documented ones
//!   take from tens of seconds to minutes); a Python block's fragments in [`SHRUNK_PYTHON`]
//!   likewise;
//! - a `--shard K/N` outside a job-array script is one of N jobs, as its text says: all N run,
//!   so that the `collect` after it (run "once all are done") finds every shard;
//! - a job-array script (`#SBATCH --array=A-B`) runs once per task, `SLURM_ARRAY_TASK_ID` set;
//!   `$SCRATCH` is a folder in the document's;
//! - a command in [`RUN_ONCE`] (seconds of work that nothing after it reads) that already ran,
//!   as run here, in an earlier document is not run again (the report says where it ran);
//! - a command in [`EXCLUDED`] is not run, for the reason given there;
//! - a command that asks for the GPU backend (`--backend gpu`, `gpu` in `--backends`) runs
//!   where a hardware adapter exists, or with `JKRBEM_REQUIRE_GPU=1` on any adapter (failing
//!   where there is none); otherwise it is reported as not run, with the reason (a software
//!   adapter takes 30–60× the CPU's time; `tests/gpu` covers the backend there);
//! - Python blocks run with `target/python-venv/bin/python`, the environment `./run-tests`
//!   builds (it runs `cargo test` first, so a fresh machine's first run has none yet), where
//!   it imports `jkrbem` and numpy; otherwise they are reported as not run, with the reason.
//!
//! **Files the text takes as given** ([`GIVEN`]): `scenes.csv` is the ```csv table of
//! docs/batch.md, for its own commands and for README.md's, which point to it.
//!
//! The report (each command as run, with its time; each not run, with why) goes to standard
//! error: `cargo test --release --test cli documented_commands -- --nocapture`.
//!
//! Every entry of [`SHRUNK`], [`SHRUNK_PYTHON`], [`RUN_ONCE`] and [`EXCLUDED`] must match a
//! documented command, so that none of the lists goes stale unnoticed.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest any one documented command may take here (shrunk), before it is stopped and
/// counted as failed.
const TIME_LIMIT: Duration = Duration::from_secs(300);

/// Documented commands that run shrunk: (the command as documented, comments dropped and
/// spaces collapsed; the command run instead).
const SHRUNK: &[(&str, &str)] = &[
    // README.md
    (
        // 25:1 and 50:1 take 15 s even at 5 %: they run in the 128² shards below.
        "jkrbem sweep --ratios 1,2,5,10,25,50 --accuracy 2% --backend auto --out jkrbem-out/sweep",
        "jkrbem sweep --ratios 1,2,5 --accuracy 5% --backend auto --out jkrbem-out/sweep",
    ),
    (
        "jkrbem sweep --ratios 1,2,5,10,25,50 --grid 512 --shard 3/6 --out $SCRATCH/sweep",
        "jkrbem sweep --ratios 1,2,5,10,25,50 --grid 128 --shard 3/6 --out $SCRATCH/sweep",
    ),
    (
        "jkrbem crossed --radius 0.01 --angles 90,70,50,30,16.1 --e 1e6 --nu 0.5 --work-of-adhesion 0.05 --accuracy 2%",
        "jkrbem crossed --radius 0.01 --angles 90,70,50,30,16.1 --e 1e6 --nu 0.5 --work-of-adhesion 0.05 --accuracy 5%",
    ),
    (
        "jkrbem accuracy --ratio 1 --grids 32,64,128 --backends cpu --out runs/accuracy",
        "jkrbem accuracy --ratio 1 --grids 32,64 --backends cpu --out runs/accuracy",
    ),
    (
        "jkrbem reference --ratios 1,2 --max-grid 256 --backend cpu --out runs/ref.csv",
        "jkrbem reference --ratios 1 --max-grid 128 --backend cpu --out runs/ref.csv",
    ),
    (
        "jkrbem bench --backends cpu --precisions f64,f32 --grids 128,256,512 --ratio 5 --measure adhesive-force --pulloff-max-grid 512 --out runs/bench-5",
        "jkrbem bench --backends cpu --precisions f64,f32 --grids 32,64 --ratio 5 --measure adhesive-force --pulloff-max-grid 64 --out runs/bench-5",
    ),
    // docs/accuracy.md
    (
        "jkrbem simulate --ratio 1 --extrapolate",
        "jkrbem simulate --ratio 1 --extrapolate --extrapolate-grids 32,64,128",
    ),
    (
        "jkrbem simulate --ratio 5 --extrapolate --extrapolate-grids 128,256,512 --summary x.json",
        "jkrbem simulate --ratio 5 --extrapolate --extrapolate-grids 32,64,128 --summary x.json",
    ),
    (
        "jkrbem accuracy --ratio 1 --grids 32,64,128,256 --backends cpu --out docs/accuracy-sphere",
        "jkrbem accuracy --ratio 1 --grids 32,64 --backends cpu --out docs/accuracy-sphere",
    ),
    (
        "jkrbem accuracy --ratio 5 --grids 64,128 --backends cpu,gpu --variants plain,regrid",
        "jkrbem accuracy --ratio 5 --grids 32,64 --backends cpu,gpu --variants plain,regrid",
    ),
    (
        "jkrbem coverage --ratios 1,2,3,5 --grids 64,128 --margins 0.08,0.18 --variants regrid --mesh-angles 0,45,90 --apex-offsets 0:0,0.25:0.25 --backend cpu",
        "jkrbem coverage --ratios 1 --grids 64 --margins 0.08 --variants regrid --mesh-angles 0,45,90 --apex-offsets 0:0,0.25:0.25 --backend cpu",
    ),
    // docs/commands.md
    (
        "jkrbem simulate --ratio 10 --grid 512 --out runs/r10.csv --summary runs/r10.json",
        "jkrbem simulate --ratio 10 --grid 128 --out runs/r10.csv --summary runs/r10.json",
    ),
    (
        "jkrbem simulate --ratio 5 --grid 256 --measure adhesive-force --regrid",
        "jkrbem simulate --ratio 5 --grid 64 --measure adhesive-force --regrid",
    ),
    (
        "jkrbem sweep --ratios 1,2,5 --grid 128 --out jkrbem-out/sweep128",
        "jkrbem sweep --ratios 1,2,5 --grid 64 --out jkrbem-out/sweep128",
    ),
    (
        "jkrbem sweep --ratios 1,2,5,10,25,50 --grid 512 --shard ${SLURM_ARRAY_TASK_ID}/6 --out $SCRATCH/sweep",
        "jkrbem sweep --ratios 1,2,5,10,25,50 --grid 128 --shard ${SLURM_ARRAY_TASK_ID}/6 --out $SCRATCH/sweep",
    ),
    (
        // Without `--backends` it takes the GPU too where one opens (lavapipe's 128² pull-off
        // alone takes minutes): the timings without the pull-off, on one grid.
        "jkrbem bench",
        "jkrbem bench --grids 32 --pulloff-max-grid 0",
    ),
    (
        "jkrbem bench --backends cpu,gpu --grids 64,128,256,512 --pulloff-max-grid 128 --repeats 9",
        "jkrbem bench --backends cpu,gpu --grids 32,64 --pulloff-max-grid 32 --repeats 9",
    ),
    // docs/gpu.md
    (
        "jkrbem simulate --ratio 5 --grid 2048 --backend gpu",
        "jkrbem simulate --ratio 5 --grid 64 --backend gpu",
    ),
    (
        "jkrbem bench --backends cpu,gpu --grids 256,512,1024,2048 --pulloff-max-grid 0 --profile",
        "jkrbem bench --backends cpu,gpu --grids 32,64 --pulloff-max-grid 0 --profile",
    ),
    // docs/indenters.md
    (
        "jkrbem simulate --indenter height-map --height-map flat.npy --spacing 0.02 --grid 256 --preload-area 0.2",
        "jkrbem simulate --indenter height-map --height-map flat.npy --spacing 0.02 --grid 64 --preload-area 0.2",
    ),
    (
        "jkrbem simulate --indenter ellipsoid --ratio 1 --roughness rough.npy --spacing 0.01 --preload-depth 0.5 --grid 256",
        "jkrbem simulate --indenter ellipsoid --ratio 1 --roughness rough.npy --spacing 0.01 --preload-depth 0.5 --grid 64",
    ),
    (
        "jkrbem simulate --indenter height-map --height-map ell5.txt --spacing 0.03",
        "jkrbem simulate --indenter height-map --height-map ell5.txt --spacing 0.03 --grid 64",
    ),
    (
        "jkrbem simulate --indenter ellipsoid --ratio 1 --roughness rough.npy --spacing 0.01 --work-of-adhesion 0.02 --margin 0.5 --grid 128 --measure adhesive-force --fields minimum --backend cpu --out rough-sphere.csv",
        "jkrbem simulate --indenter ellipsoid --ratio 1 --roughness rough.npy --spacing 0.01 --work-of-adhesion 0.02 --margin 0.5 --grid 64 --measure adhesive-force --fields minimum --backend cpu --out rough-sphere.csv",
    ),
];

/// Fragments of Python blocks replaced before they run: (fragment, replacement).
const SHRUNK_PYTHON: &[(&str, &str)] = &[
    // docs/indenters.md: the rough sphere's grid (the roughness map's own `grid=` is its size,
    // which the domain needs, and stays).
    (
        "preload_depth=0.5, grid=256)",
        "preload_depth=0.5, grid=64)",
    ),
];

/// Commands (as run, after [`SHRUNK`]) that several documents show and nothing after them
/// reads: they run in the first document that shows them only.
const RUN_ONCE: &[&str] = &[
    "jkrbem sweep --ratios 1,2,5 --accuracy 5% --backend auto --out jkrbem-out/sweep",
    "jkrbem crossed --radius 0.01 --angles 90,70,50,30,16.1 --e 1e6 --nu 0.5 --work-of-adhesion 0.05 --accuracy 5%",
    "jkrbem reproduce --quick --out jkrbem-out/reproduce",
    "jkrbem reference --ratios 1 --max-grid 128 --backend cpu --out runs/ref.csv",
    "jkrbem coverage --ratios 1,5 --grids 64 --margins 0.08,0.13 --variants regrid",
];

/// Documented commands that are not run: (the command as documented, why).
const EXCLUDED: &[(&str, &str)] = &[
    (
        "./run-tests",
        "the whole test suite, this test included (about 15 minutes on 2 cores)",
    ),
    (
        "jkrbem reproduce --jobs 2 --out jkrbem-out/reproduce",
        "the whole study at three grids per ratio (6 minutes on 2 cores) and without a grid \
         flag to shrink; `reproduce --quick`, shown beside it, runs the same steps on one \
         coarse grid per ratio",
    ),
    (
        "jkrbem reference",
        "twelve ratios to 0.3 % on grids up to 2048 (hours on a CPU); `reference --ratios 1,2` \
         runs the same ladder, shrunk",
    ),
    (
        "jkrbem reference --ratios 50 --first-grid 256 --max-grid 1024 --backend cpu",
        "grids up to 1024 (minutes); a 50:1 ladder cannot start below 128, and 128–512 still \
         take 20 s: `--first-grid` is tested in tests/cli/hardening_reference.rs and \
         tests/physics/reference.rs",
    ),
    (
        "jkrbem reference --ratios 35 --first-grid 256 --max-grid 1024 --phases 3 --backend cpu",
        "three phases of grids up to 1024 (minutes; 128–512 still take 35 s): `--phases` is \
         tested in tests/physics/reference.rs",
    ),
    (
        "jkrbem coverage --backend cpu --out runs/coverage",
        "the coverage study: 180 runs, 46 minutes on 2 cores (the slow tier's \
         tests/physics/coverage.rs runs its cases); the `coverage --ratios 1,5 …` command \
         shown with it runs the same code on 4 cases",
    ),
    (
        "jkrbem coverage --backend cpu --runs-per-case 2 --out runs/coverage",
        "the coverage study in pairs: 360 runs, more than an hour on 2 cores",
    ),
];

/// Files a document's commands take as given: (document, file, the document whose ```csv
/// block is the file).
const GIVEN: &[(&str, &str, &str)] = &[
    ("README.md", "scenes.csv", "docs/batch.md"),
    ("docs/batch.md", "scenes.csv", "docs/batch.md"),
];

/// What a fenced block holds.
#[derive(Debug, Clone, PartialEq)]
enum Block {
    /// Shell commands (each with its line in the document); `array` is a job-array script's
    /// task ids.
    Shell {
        commands: Vec<(usize, String)>,
        array: Option<(u32, u32)>,
    },
    /// A Python program, with the line of its opening fence.
    Python { line: usize, code: String },
    /// A table (```csv).
    Csv(String),
}

/// `text` with a shell comment (a `#` at the start or after white space, outside quotes) cut
/// off, and trimmed.
fn strip_comment(text: &str) -> String {
    let (mut single, mut double) = (false, false);
    let mut prev = ' ';
    for (i, c) in text.char_indices() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            '#' if !single && !double && prev.is_whitespace() => {
                return text[..i].trim().to_string();
            }
            _ => {}
        }
        prev = c;
    }
    text.trim().to_string()
}

/// `text` with each run of white space outside quotes made one space: the form [`SHRUNK`],
/// [`RUN_ONCE`] and [`EXCLUDED`] name commands in.
fn collapse(text: &str) -> String {
    let (mut single, mut double) = (false, false);
    let mut out = String::new();
    for c in text.trim().chars() {
        match c {
            '\'' if !double => single = !single,
            '"' if !single => double = !double,
            _ => {}
        }
        if c.is_whitespace() && !single && !double {
            if !out.ends_with(' ') {
                out.push(' ');
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// The fenced blocks of a Markdown document that this test reads, in order.
fn blocks(doc: &str) -> Vec<Block> {
    let lines: Vec<&str> = doc.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let open = lines[i].trim_start();
        let Some(lang) = open.strip_prefix("```") else {
            i += 1;
            continue;
        };
        let lang = lang.trim().to_string();
        let indent = lines[i].len() - open.len();
        let start = i + 1; // the block's first line, counted from 0
        let mut end = start;
        while end < lines.len() && lines[end].trim() != "```" {
            end += 1;
        }
        let body: Vec<&str> = lines[start..end.min(lines.len())]
            .iter()
            .map(|l| l.get(indent..).unwrap_or(l.trim_start()))
            .collect();
        i = end + 1;
        match lang.as_str() {
            "sh" | "bash" | "shell" | "console" => {
                let console = lang == "console";
                let mut commands = Vec::new();
                let mut array = None;
                let mut k = 0;
                while k < body.len() {
                    let first = k;
                    let mut text = body[k].to_string();
                    while text.trim_end().ends_with('\\') && k + 1 < body.len() {
                        let t = text.trim_end();
                        text = format!("{} {}", t[..t.len() - 1].trim_end(), body[k + 1].trim());
                        k += 1;
                    }
                    k += 1;
                    let text = text.trim();
                    if let Some(spec) = text.strip_prefix("#SBATCH --array=") {
                        let (a, b) = spec.trim().split_once('-').expect("an array A-B");
                        array = Some((a.parse().unwrap(), b.parse().unwrap()));
                        continue;
                    }
                    let text = if console {
                        match text.strip_prefix("$ ") {
                            Some(c) => c,
                            None => continue,
                        }
                    } else {
                        text
                    };
                    let command = strip_comment(text);
                    if !command.is_empty() {
                        // Lines counted from 1: the fence is line `start`.
                        commands.push((start + first + 1, command));
                    }
                }
                out.push(Block::Shell { commands, array });
            }
            "python" => out.push(Block::Python {
                line: start,
                code: body.join("\n") + "\n",
            }),
            "csv" => out.push(Block::Csv(body.join("\n") + "\n")),
            _ => {}
        }
    }
    out
}

/// The repository's root.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and docs/*.md, by their paths from the root, in order.
fn documents() -> Vec<String> {
    let mut docs: Vec<String> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    docs.sort();
    docs.insert(0, "README.md".to_string());
    docs
}

/// Whether the command asks for the GPU backend.
fn asks_for_gpu(command: &str) -> bool {
    let words: Vec<&str> = command.split_whitespace().collect();
    words.windows(2).any(|w| {
        (w[0] == "--backend" && w[1] == "gpu")
            || (w[0] == "--backends" && w[1].split(',').any(|b| b == "gpu"))
    }) || words
        .iter()
        .any(|w| *w == "--backend=gpu" || w.starts_with("--backends=") && w.contains("gpu"))
}

/// Why the commands that ask for the GPU backend are not run here, or `None` where they are.
fn gpu_skip_reason() -> Option<String> {
    #[cfg(feature = "gpu")]
    {
        if crate::common::gpu_required() {
            return None;
        }
        match jkrbem::backend::gpu::list_adapters().first() {
            None => Some("no GPU adapter".to_string()),
            Some(a) if a.device_type == "Cpu" => Some(format!(
                "the only GPU adapter is a software one ({}), at 30–60× the CPU's time; \
                 JKRBEM_REQUIRE_GPU=1 runs them on it",
                a.name
            )),
            Some(_) => None,
        }
    }
    #[cfg(not(feature = "gpu"))]
    {
        Some("built without the `gpu` feature".to_string())
    }
}

/// The Python that runs the Python blocks, or why there is none.
fn python() -> Result<PathBuf, String> {
    let python = root().join("target/python-venv/bin/python");
    if !python.exists() {
        return Err(format!(
            "no {} (./run-tests makes it, after the Rust tests)",
            python.display()
        ));
    }
    let o = Command::new(&python)
        .args(["-c", "import jkrbem, numpy"])
        .output()
        .map_err(|e| format!("{} does not start: {e}", python.display()))?;
    if o.status.success() {
        Ok(python)
    } else {
        Err(format!(
            "{} cannot import jkrbem and numpy: {}",
            python.display(),
            String::from_utf8_lossy(&o.stderr).trim()
        ))
    }
}

/// How one run of a command ended.
struct Ended {
    /// `None` where it was stopped at [`TIME_LIMIT`] (or by a signal).
    code: Option<i32>,
    seconds: f64,
    /// The end of its standard output and error.
    tail: String,
}

/// Run `program` with `args` in `dir` with `env`, its output to files in `logs`, stopping its
/// whole process group at [`TIME_LIMIT`].
fn run_one(
    program: &Path,
    args: &[&str],
    dir: &Path,
    env: &[(&str, String)],
    logs: &Path,
    n: usize,
) -> Ended {
    let out_path = logs.join(format!("{n}.out"));
    let err_path = logs.join(format!("{n}.err"));
    let mut c = Command::new(program);
    c.args(args)
        .current_dir(dir)
        .env_remove("JKRBEM_MEMORY_LIMIT")
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap())
        .process_group(0);
    for (k, v) in env {
        c.env(k, v);
    }
    let start = Instant::now();
    let mut child = c.spawn().expect("the command starts");
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break Some(s);
        }
        if start.elapsed() > TIME_LIMIT {
            // The whole group: `sh` and what it started.
            unsafe { libc::kill(-(child.id() as i32), libc::SIGKILL) };
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let read = |p: &Path| String::from_utf8_lossy(&std::fs::read(p).unwrap()).into_owned();
    let text = read(&out_path) + &read(&err_path);
    let tail: String = {
        let lines: Vec<&str> = text.lines().collect();
        lines[lines.len().saturating_sub(12)..].join("\n")
    };
    Ended {
        code: status.and_then(|s| s.code()),
        seconds: start.elapsed().as_secs_f64(),
        tail,
    }
}

/// The `csv` block of `doc`.
fn csv_of(doc: &str) -> String {
    let text = std::fs::read_to_string(root().join(doc)).unwrap();
    let tables: Vec<String> = blocks(&text)
        .into_iter()
        .filter_map(|b| match b {
            Block::Csv(t) => Some(t),
            _ => None,
        })
        .collect();
    assert_eq!(tables.len(), 1, "{doc} should show one ```csv table");
    tables.into_iter().next().unwrap()
}

/// Every command the documents show, each where it is shown: (document, line, command as
/// documented).
fn documented() -> Vec<(String, usize, String)> {
    let mut all = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(root().join(&doc)).unwrap();
        for b in blocks(&text) {
            if let Block::Shell { commands, .. } = b {
                for (line, c) in commands {
                    all.push((doc.clone(), line, collapse(&c)));
                }
            }
        }
    }
    all
}

#[test]
fn the_lists_name_documented_commands_only() {
    let all: Vec<String> = documented().into_iter().map(|(_, _, c)| c).collect();
    assert!(all.len() > 40, "{} commands found", all.len());
    let run: Vec<String> = all
        .iter()
        .map(|c| {
            SHRUNK
                .iter()
                .find(|(d, _)| d == c)
                .map_or(c.clone(), |(_, r)| r.to_string())
        })
        .collect();
    for (d, r) in SHRUNK {
        assert!(
            all.iter().any(|c| c == d),
            "SHRUNK names `{d}`, no document shows it"
        );
        assert_ne!(d, r, "SHRUNK runs `{d}` as itself");
    }
    for (d, _) in EXCLUDED {
        assert!(
            all.iter().any(|c| c == d),
            "EXCLUDED names `{d}`, no document shows it"
        );
    }
    for r in RUN_ONCE {
        assert!(
            run.iter().filter(|c| c == r).count() >= 2,
            "RUN_ONCE names `{r}`, which fewer than two places show"
        );
    }
    let pythons: Vec<String> = documents()
        .iter()
        .flat_map(|doc| blocks(&std::fs::read_to_string(root().join(doc)).unwrap()))
        .filter_map(|b| match b {
            Block::Python { code, .. } => Some(code),
            _ => None,
        })
        .collect();
    for (from, _) in SHRUNK_PYTHON {
        assert!(
            pythons.iter().any(|p| p.contains(from)),
            "SHRUNK_PYTHON names `{from}`, no Python block holds it"
        );
    }
}

#[test]
fn blocks_are_read_as_a_shell_reads_them() {
    let doc = "text\n```sh\njkrbem a --x 1   # note\n# a comment\njkrbem b \\\n  --y 2\n```\n\
               ```console\n$ jkrbem c\noutput\n```\n  ```bash\n  #!/bin/bash\n  #SBATCH \
               --array=1-3\n  echo '#kept' \"a  b\" # cut\n  ```\n```python\nprint(1)\n```\n";
    let b = blocks(doc);
    assert_eq!(
        b[0],
        Block::Shell {
            commands: vec![(3, "jkrbem a --x 1".into()), (5, "jkrbem b --y 2".into())],
            array: None
        }
    );
    assert_eq!(
        b[1],
        Block::Shell {
            commands: vec![(9, "jkrbem c".into())],
            array: None
        }
    );
    assert_eq!(
        b[2],
        Block::Shell {
            commands: vec![(15, "echo '#kept' \"a  b\"".into())],
            array: Some((1, 3))
        }
    );
    assert_eq!(
        b[3],
        Block::Python {
            line: 17,
            code: "print(1)\n".into()
        }
    );
    assert_eq!(collapse("a   'b  c'  d"), "a 'b  c' d");
    assert!(asks_for_gpu("jkrbem x --backends cpu,gpu"));
    assert!(asks_for_gpu("jkrbem x --backend gpu"));
    assert!(!asks_for_gpu("jkrbem x --backend auto"));
}

/// What runs the documents' commands, and what it has seen.
struct Runner {
    /// `PATH` with the binary under test first.
    path: String,
    /// Why the GPU commands are not run, if they are not.
    gpu_skip: Option<String>,
    /// The Python for the Python blocks, or why there is none.
    python: Result<PathBuf, String>,
    /// Where each run's output and each Python block go.
    logs: tempfile::TempDir,
    /// Runs so far (each names its files in `logs`).
    n: usize,
    ran: usize,
    not_run: usize,
    /// The commands of [`RUN_ONCE`] that have run, and where.
    ran_once: HashMap<String, String>,
    report: String,
    failures: Vec<String>,
}

impl Runner {
    fn new() -> Runner {
        let bin = PathBuf::from(env!("CARGO_BIN_EXE_jkrbem"));
        Runner {
            path: format!(
                "{}:{}",
                bin.parent().unwrap().display(),
                std::env::var("PATH").unwrap_or_default()
            ),
            gpu_skip: gpu_skip_reason(),
            python: python(),
            logs: tempfile::tempdir().unwrap(),
            n: 0,
            ran: 0,
            not_run: 0,
            ran_once: HashMap::new(),
            report: String::new(),
            failures: Vec::new(),
        }
    }

    /// Run `program` with `args` in `dir`, and record how it ended as `shown`, at `at`.
    fn run(
        &mut self,
        program: &Path,
        args: &[&str],
        dir: &Path,
        env: &[(&str, String)],
        at: &str,
        shown: &str,
    ) {
        self.n += 1;
        let end = run_one(program, args, dir, env, self.logs.path(), self.n);
        self.ran += 1;
        let _ = writeln!(self.report, "  {:6.1} s  {at}  {shown}", end.seconds);
        if end.code != Some(0) {
            let how = match end.code {
                Some(c) => format!("exited {c}"),
                None => format!("did not finish within {} s", TIME_LIMIT.as_secs()),
            };
            self.failures
                .push(format!("{at}: `{shown}` {how}:\n{}", end.tail));
        }
    }

    /// Record a command that is not run, and why.
    fn not_run(&mut self, at: &str, what: &str, why: &str) {
        self.not_run += 1;
        let _ = writeln!(self.report, "  not run  {at}  {what}\n           ({why})");
    }

    /// Run a Python block in `dir`.
    fn python_block(&mut self, dir: &Path, at: &str, code: &str) {
        let python = match &self.python {
            Ok(p) => p.clone(),
            Err(why) => {
                let why = why.clone();
                return self.not_run(at, "(Python block)", &why);
            }
        };
        let mut code = code.to_string();
        for (from, to) in SHRUNK_PYTHON {
            code = code.replace(from, to);
        }
        let file = self.logs.path().join(format!("block-{}.py", self.n + 1));
        std::fs::write(&file, &code).unwrap();
        self.run(
            &python,
            &[file.to_str().unwrap()],
            dir,
            &[],
            at,
            "(Python block)",
        );
    }

    /// Run a documented shell command in `dir` (as task `task` of a job array, if given).
    fn shell_command(&mut self, dir: &Path, at: &str, documented: &str, task: Option<u32>) {
        let key = collapse(documented);
        if let Some((_, why)) = EXCLUDED.iter().find(|(d, _)| *d == key) {
            return self.not_run(at, &key, why);
        }
        let command = SHRUNK
            .iter()
            .find(|(d, _)| *d == key)
            .map_or(key.clone(), |(_, r)| r.to_string())
            .replace("cargo run --release --", "jkrbem");
        if asks_for_gpu(&command) {
            if let Some(why) = self.gpu_skip.clone() {
                return self.not_run(at, &command, &format!("GPU: {why}"));
            }
        }
        if RUN_ONCE.contains(&command.as_str()) {
            if let Some(there) = self.ran_once.get(&command) {
                let _ = writeln!(self.report, "  (ran at {there})  {at}  {command}");
                return;
            }
            self.ran_once.insert(command.clone(), at.to_string());
        }
        // A shard outside a job array stands for all N of its jobs.
        let runs: Vec<String> = match shard_of(&command) {
            Some((flag, total)) if task.is_none() => (1..=total)
                .map(|k| command.replace(&flag, &format!("--shard {k}/{total}")))
                .collect(),
            _ => vec![command],
        };
        let mut env = vec![
            ("PATH", self.path.clone()),
            ("SCRATCH", dir.join("scratch").display().to_string()),
        ];
        if let Some(t) = task {
            env.push(("SLURM_ARRAY_TASK_ID", t.to_string()));
        }
        for run in runs {
            let shown = match task {
                Some(t) => format!("{run}  [SLURM_ARRAY_TASK_ID={t}]"),
                None => run.clone(),
            };
            self.run(Path::new("sh"), &["-c", &run], dir, &env, at, &shown);
        }
    }

    /// Run a document's blocks in order, in a folder of its own.
    fn document(&mut self, doc: &str) {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        let blocks = blocks(&text);
        if blocks.iter().all(|b| matches!(b, Block::Csv(_))) {
            return;
        }
        let folder = tempfile::tempdir().unwrap();
        let dir = folder.path();
        for (d, file, source) in GIVEN {
            if *d == doc {
                std::fs::write(dir.join(file), csv_of(source)).unwrap();
            }
        }
        std::fs::create_dir(dir.join("scratch")).unwrap();
        let start = Instant::now();
        for block in blocks {
            match block {
                Block::Csv(_) => {}
                Block::Python { line, code } => {
                    self.python_block(dir, &format!("{doc}:{line}"), &code)
                }
                Block::Shell { commands, array } => {
                    let tasks: Vec<Option<u32>> = match array {
                        Some((a, b)) => (a..=b).map(Some).collect(),
                        None => vec![None],
                    };
                    for task in tasks {
                        for (line, documented) in &commands {
                            self.shell_command(dir, &format!("{doc}:{line}"), documented, task);
                        }
                    }
                }
            }
        }
        let _ = writeln!(self.report, "{doc}: {:.1} s", start.elapsed().as_secs_f64());
    }
}

#[test]
fn slow_every_documented_command_runs() {
    let started = Instant::now();
    let mut runner = Runner::new();
    for doc in documents() {
        runner.document(&doc);
    }
    eprintln!(
        "documented commands: {} run, {} not run, {:.0} s\n{}",
        runner.ran,
        runner.not_run,
        started.elapsed().as_secs_f64(),
        runner.report
    );
    assert!(
        runner.failures.is_empty(),
        "{} documented command(s) failed:\n\n{}",
        runner.failures.len(),
        runner.failures.join("\n\n")
    );
}

/// A command's `--shard K/N`: (the flag and its value as written, N), where K and N are numbers.
fn shard_of(command: &str) -> Option<(String, u32)> {
    let words: Vec<&str> = command.split_whitespace().collect();
    words.windows(2).find_map(|w| {
        let (k, n) = w[1].split_once('/')?;
        (w[0] == "--shard" && k.parse::<u32>().is_ok())
            .then(|| n.parse().ok().map(|n| (format!("--shard {}", w[1]), n)))
            .flatten()
    })
}
