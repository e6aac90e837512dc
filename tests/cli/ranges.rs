//! Every numeric flag of every command has a range in the schema, and a value just past
//! either end of it (and NaN and ±inf) is refused before any work: exit 2, the flag and the
//! end it passed named, nothing created (issue 55, item 22). The commands and their flags are
//! read from the program's own `--help`, and each flag's range from the schema
//! ([`of_command`]), so a flag added without a parameter in the schema fails here, as does one
//! whose range the command does not hold.

use crate::common::bin;
use jkrbem::params::{of_command, Kind, Range, Spec, APEX_OFFSETS, SHARD};
use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

/// The commands `jkrbem --help` lists (but `help`).
fn commands() -> Vec<String> {
    let o = bin().arg("--help").output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    text.lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(str::to_string)
        .collect()
}

/// The flags `command --help` lists that take a value (not switches, not positionals).
fn value_flags(command: &str) -> Vec<String> {
    let o = bin().args([command, "--help"]).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    let mut flags = Vec::new();
    for line in text.lines() {
        let body = line.trim_start();
        // An option's line starts indented by at most 6 (`  -h, --help`, `      --grid <N>`).
        if line.len() - body.len() > 6 || !body.starts_with('-') {
            continue;
        }
        let words: Vec<&str> = body.split_whitespace().collect();
        let Some(at) = words.iter().position(|w| w.starts_with("--")) else {
            continue;
        };
        if words.get(at + 1).is_some_and(|w| w.starts_with('<')) {
            flags.push(words[at].trim_end_matches(',').to_string());
        }
    }
    flags
}

/// What a command is given besides the flag under test, as (flag, value) pairs (a positional
/// with no flag), so that the flag's own check is the one that refuses; all valid.
fn fixed(command: &str) -> Vec<(&'static str, &'static str)> {
    match command {
        "simulate" => vec![("--backend", "cpu"), ("--out", "o.csv")],
        "sweep" | "crossed" | "reproduce" | "coverage" => {
            vec![("--backend", "cpu"), ("--out", "o")]
        }
        "reference" => vec![("--backend", "cpu"), ("--out", "o/t.csv")],
        "bench" => vec![("--backends", "cpu"), ("--out", "o")],
        "accuracy" => vec![("--out", "o")],
        "batch" => vec![("", "scenes.csv"), ("--out", "o")],
        "collect" => vec![("", ".")],
        "theory" => vec![("--model", "jg"), ("--out", "t.csv")],
        "roughness" => vec![
            ("--out", "r.npy"),
            ("--grid", "64"),
            ("--spacing", "1"),
            ("--hurst", "0.8"),
            ("--rms-height", "1"),
        ],
        _ => Vec::new(),
    }
}

/// The flag that may not be given beside `flag` (the other of a pair of which one is given).
fn excludes(flag: &str) -> Option<&'static str> {
    match flag {
        "--rms-slope" => Some("--rms-height"),
        _ => None,
    }
}

/// A number written so that it reads back as itself.
fn text(v: f64) -> String {
    format!("{v:e}")
}

/// The number just below `v` (f64's next down).
fn below(v: f64) -> f64 {
    v.next_down()
}

/// The number just above `v`.
fn above(v: f64) -> f64 {
    v.next_up()
}

/// The values past either end of `r`: (value, the end it passes).
fn past_range(r: Range) -> [(f64, f64); 2] {
    [
        (if r.lo_open { r.lo } else { below(r.lo) }, r.lo),
        (if r.hi_open { r.hi } else { above(r.hi) }, r.hi),
    ]
}

/// The values of `spec` past its range, as the command line writes them: (text, the end it
/// passes as the message writes it, where it has one). NaN and ±inf for real numbers.
fn past(spec: &Spec) -> Vec<(String, Option<String>)> {
    let c = jkrbem::text::compact;
    let not_numbers = |unit: &str| -> Vec<(String, Option<String>)> {
        ["NaN", "inf", "-inf"]
            .iter()
            .map(|v| (format!("{v}{unit}"), None))
            .collect()
    };
    match spec.kind {
        Kind::Count(lo, hi) if spec == SHARD => vec![
            (format!("{}/{}", lo - 1, hi), Some(lo.to_string())),
            (format!("1/{}", hi as u128 + 1), Some(hi.to_string())),
            ("NaN/2".into(), None),
        ],
        Kind::Count(lo, hi) => vec![
            (
                if lo == 0 {
                    "-1".to_string()
                } else {
                    (lo - 1).to_string()
                },
                Some(lo.to_string()),
            ),
            ((hi as u128 + 1).to_string(), Some(hi.to_string())),
            ("NaN".into(), None),
        ],
        Kind::PowerOfTwo(lo, hi) => vec![
            ((lo / 2).to_string(), Some(lo.to_string())),
            ((hi * 2).to_string(), Some(hi.to_string())),
            ("NaN".into(), None),
        ],
        Kind::Real(r) => {
            let mut v: Vec<_> = past_range(r)
                .iter()
                .map(|&(v, end)| (text(v), Some(c(end))))
                .collect();
            v.extend(not_numbers(""));
            v
        }
        Kind::Fraction(lo, hi) => {
            // A percentage a relative 1e-9 past each end.
            let mut v = vec![
                (
                    format!("{}%", text(lo * 100.0 * (1.0 - 1e-9))),
                    Some(c(lo * 100.0)),
                ),
                (
                    format!("{}%", text(hi * 100.0 * (1.0 + 1e-9))),
                    Some(c(hi * 100.0)),
                ),
            ];
            v.extend(not_numbers("%"));
            v
        }
        Kind::Seconds(lo, hi) => {
            let mut v = vec![
                (format!("{}s", text(lo * (1.0 - 1e-9))), None),
                (format!("{}s", text(hi * (1.0 + 1e-9))), None),
            ];
            v.extend(not_numbers("s"));
            v
        }
        Kind::Pair(r) => {
            // One number past an end, the other inside.
            let inside = 0f64.clamp(r.lo, r.hi);
            let join = if spec == APEX_OFFSETS { ':' } else { ',' };
            let [(lo, lo_end), (hi, hi_end)] = past_range(r);
            vec![
                (
                    format!("{}{join}{}", text(lo), text(inside)),
                    Some(c(lo_end)),
                ),
                (
                    format!("{}{join}{}", text(inside), text(hi)),
                    Some(c(hi_end)),
                ),
                (format!("NaN{join}{}", text(inside)), None),
                (format!("{}{join}inf", text(inside)), None),
            ]
        }
        Kind::Grids(lo, hi) => vec![
            (format!("{},{lo}", lo / 2), Some(lo.to_string())),
            (format!("{hi},{}", hi * 2), Some(hi.to_string())),
            (format!("NaN,{lo}"), None),
        ],
        Kind::States => vec![("every:0".into(), Some("1".into()))],
        Kind::Switch | Kind::Choice(_) | Kind::Choices(_) | Kind::File => Vec::new(),
    }
}

/// Whether `text` names `flag` as a whole word (not `--grid` inside `--grid-y`).
fn names(text: &str, flag: &str) -> bool {
    text.match_indices(flag).any(|(at, _)| {
        !text[at + flag.len()..].starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
    })
}

/// The names in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Run `args` in `dir` (the memory limit of the caller's environment removed) for at most
/// `limit`: its exit code (`None` if it was still running and was killed) and standard error.
fn run(dir: &Path, args: &[String], limit: Duration) -> (Option<i32>, String) {
    let log = tempfile::NamedTempFile::new().unwrap();
    let mut child = bin()
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::from(log.reopen().unwrap()))
        .spawn()
        .unwrap();
    let start = Instant::now();
    let code = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status.code();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    (
        code,
        std::fs::read_to_string(log.path()).unwrap_or_default(),
    )
}

#[test]
fn every_numeric_flag_of_every_command_refuses_a_value_past_its_range_naming_it() {
    let commands = commands();
    assert!(commands.len() >= 13, "{commands:?}");
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("scenes.csv"), "ratio\n1\n").unwrap();
    let before = listing(dir.path());
    let (mut flags, mut cases) = (0, 0);
    let mut wrong = Vec::new();
    for command in &commands {
        for flag in value_flags(command) {
            let Some(spec) = of_command(command, &flag) else {
                wrong.push(format!(
                    "{command} {flag}: no parameter in the schema (no range)"
                ));
                continue;
            };
            let values = past(spec);
            if values.is_empty() {
                continue;
            }
            flags += 1;
            let fixed: Vec<_> = fixed(command)
                .into_iter()
                .filter(|(f, _)| *f != flag && Some(*f) != excludes(&flag))
                .collect();
            for (value, end) in values {
                cases += 1;
                let mut args = vec![command.clone()];
                for (f, v) in &fixed {
                    args.extend((!f.is_empty()).then(|| f.to_string()));
                    args.push(v.to_string());
                }
                args.extend([flag.clone(), value.clone()]);
                let (code, err) = run(dir.path(), &args, Duration::from_secs(30));
                let err = err.replace('−', "-");
                let mut why = Vec::new();
                if code != Some(2) {
                    why.push(format!("exit {code:?}"));
                }
                if !names(&err, &flag) {
                    why.push(format!("{flag} not named"));
                }
                if let Some(end) = end.filter(|e| !err.contains(e.as_str())) {
                    why.push(format!("the end {end} not said"));
                }
                if listing(dir.path()) != before {
                    why.push(format!("created {:?}", listing(dir.path())));
                    for name in listing(dir.path()) {
                        if !before.contains(&name) {
                            let p = dir.path().join(&name);
                            let _ =
                                std::fs::remove_dir_all(&p).or_else(|_| std::fs::remove_file(&p));
                        }
                    }
                }
                if !why.is_empty() {
                    let first = err.lines().next().unwrap_or("");
                    wrong.push(format!("{}: {}: {first}", args.join(" "), why.join(", ")));
                }
            }
        }
    }
    println!(
        "{flags} numeric flags of {} commands, {cases} values past their ranges",
        commands.len()
    );
    assert!(flags >= 80 && cases >= 250, "{flags} flags, {cases} cases");
    assert!(
        wrong.is_empty(),
        "{} wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
}
