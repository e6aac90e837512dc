//! The command line: its commands and their output, bad invocations (fuzzed and listed), files
//! that are missing, damaged, linked or locked, interrupted runs, `batch` and `collect`,
//! `reference`'s reuse rules, `bench`, what goes to stdout and what to stderr, and every command
//! the documentation shows. One test binary; each former file is a module.

#[path = "../common/mod.rs"]
mod common;

mod bad_inputs;
mod batch;
mod bench;
mod cli;
mod cli_fuzz;
mod documented_commands;
mod figures;
mod hardening_collect;
mod hardening_files;
mod hardening_inputs;
mod hardening_reference;
mod layout;
mod periodic_map;
mod print_quality;
mod ranges;
mod robustness;
mod roughness;
mod streams;
