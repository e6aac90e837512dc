//! A fuzz test of the command line (issue 12): random flags and values, good and bad, for every
//! subcommand never make `jkrbem` panic or die by a signal, and it exits with 0, 1 or 2 only.
//!
//! `JKRBEM_MEMORY_LIMIT=1` makes every pull-off that passes its checks stop at the memory check
//! (exit 2) instead of running, so that the test stays fast (`reference`, `coverage` and
//! `bench` too); `theory` and `collect` run for real. `devices` is left out: it has no flags.

use proptest::prelude::*;
use std::process::Command;

/// Values that have broken parsers: signs, huge and tiny numbers, non-numbers, lists, empty.
const VALUES: &[&str] = &[
    "-5",
    "0",
    "1",
    "2",
    "5",
    "16",
    "32",
    "64",
    "100",
    "1e300",
    "-1e300",
    "1e-300",
    "NaN",
    "inf",
    "-inf",
    "abc",
    "",
    " ",
    "1,1",
    "1,2,5",
    "-1,2",
    "3/2",
    "0/0",
    "1/3",
    "18446744073709551616",
    "-0",
    "0.5",
    "1.5",
    "4096",
    "1048576",
    "5%",
    "200%",
    "%",
    "cpu",
    "gpu",
    "auto",
    "jg",
    "jkr",
    "hertz",
    "plain",
    "regrid",
    "--",
    "-",
    "é",
    "1e",
    "0x10",
    "9999999999",
    "-NaN",
    "-1%",
    "-1s",
    "90s",
    "newdir/",
    "-64",
];

const SUBCOMMANDS: &[(&str, &[&str])] = &[
    (
        "simulate",
        &[
            "--ratio",
            "--r1",
            "--r2",
            "--e-star",
            "--work-of-adhesion",
            "--grid",
            "--grid-y",
            "--start-radius",
            "--steps",
            "--onsets",
            "--measure",
            "--final-d",
            "--margin",
            "--mesh-angle",
            "--cg-tolerance",
            "--cg-max-iterations",
            "--cg-accept",
            "--cg-check-every",
            "--preconditioner",
            "--backend",
            "--convolution",
            "--out",
            "--summary",
            "--extrapolate-grids",
            "--accuracy",
        ],
    ),
    (
        "sweep",
        &[
            "--ratios",
            "--grid",
            "--steps",
            "--start-radius",
            "--margin",
            "--backend",
            "--shard",
            "--jobs",
            "--out",
        ],
    ),
    (
        "crossed",
        &[
            "--radius",
            "--angles",
            "--e",
            "--nu",
            "--work-of-adhesion",
            "--grid",
            "--steps",
            "--margin",
            "--backend",
            "--jobs",
            "--out",
        ],
    ),
    ("reproduce", &["--out", "--backend", "--jobs"]),
    (
        "accuracy",
        &["--ratio", "--grids", "--backends", "--variants", "--out"],
    ),
    ("theory", &["--model", "--ratio", "--points", "--out"]),
    (
        "reference",
        &[
            "--ratios",
            "--target",
            "--max-grid",
            "--first-grid",
            "--phases",
            "--backend",
            "--out",
        ],
    ),
    (
        "coverage",
        &[
            "--ratios",
            "--grids",
            "--margins",
            "--runs-per-case",
            "--backend",
            "--out",
        ],
    ),
    (
        "bench",
        &[
            "--backends",
            "--grids",
            "--pulloff-max-grid",
            "--repeats",
            "--cg-iterations",
            "--ratio",
            "--start-radius",
            "--margin",
            "--out",
        ],
    ),
    ("collect", &[]),
];

/// Flags without a value.
const SWITCHES: &[&str] = &[
    "--regrid",
    "--extrapolate",
    "--quick",
    "--allow-missing",
    "--help",
];

fn invocation() -> impl Strategy<Value = Vec<String>> {
    let pairs = prop::collection::vec(
        (any::<prop::sample::Index>(), prop::sample::select(VALUES)),
        0..6,
    );
    let switches = prop::collection::vec(prop::sample::select(SWITCHES), 0..2);
    (
        prop::sample::select(SUBCOMMANDS),
        pairs,
        switches,
        any::<bool>(),
    )
        .prop_map(|((name, flags), pairs, switches, equals)| {
            let mut args = vec![name.to_string()];
            if name == "collect" {
                args.push(pairs.first().map_or("sw", |p| p.1).to_string());
            }
            for (i, value) in pairs {
                if flags.is_empty() {
                    break;
                }
                let flag = flags[i.index(flags.len())];
                if equals {
                    args.push(format!("{flag}={value}"));
                } else {
                    args.push(flag.to_string());
                    args.push(value.to_string());
                }
            }
            args.extend(switches.iter().map(|s| s.to_string()));
            args
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn the_parser_never_panics_and_exits_with_0_1_or_2(args in invocation()) {
        let dir = tempfile::tempdir().unwrap();
        let o = Command::new(env!("CARGO_BIN_EXE_jkrbem"))
            .args(&args)
            .current_dir(dir.path())
            .env("JKRBEM_MEMORY_LIMIT", "1")
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        prop_assert!(!err.contains("panicked"), "{args:?}: {err}");
        let code = o.status.code();
        prop_assert!(matches!(code, Some(0..=2)), "{args:?}: exit {:?}: {err}", o.status);
    }
}
