//! The `jkrbem` command: parses arguments, builds a scene, calls the library, writes outputs.

/// `print!` that never panics: see [`cli::write_stdout`].
macro_rules! out {
    ($($arg:tt)*) => {
        $crate::cli::write_stdout(format_args!($($arg)*))
    };
}

/// `println!` that never panics: see [`cli::write_stdout`].
macro_rules! outln {
    () => {
        $crate::cli::write_stdout(format_args!("\n"))
    };
    ($($arg:tt)*) => {
        $crate::cli::write_stdout(format_args!("{}\n", format_args!($($arg)*)))
    };
}

/// `eprintln!` that never panics: a message standard error cannot take (a closed pipe, a full
/// disk) is dropped, as there is nowhere else to say it. Where standard error is a file this
/// run reads (`2>> map.npy`), the message goes to standard output instead, or nowhere if that
/// is one too: an input is never written.
macro_rules! errln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let text = jkrbem::params::words::flags(&format!($($arg)*));
        if !jkrbem::output::file::stream_is_input(2) {
            let _ = writeln!(std::io::stderr(), "{text}");
        } else if !jkrbem::output::file::stream_is_input(1) {
            let _ = writeln!(std::io::stdout(), "{text}");
        }
    }};
}

mod cli;

use clap::{CommandFactory, FromArgMatches, Parser, Subcommand};
use std::process::ExitCode;

/// FFT-based BEM solver for JKR-type adhesive contact of a rigid indenter with an elastic
/// half-space (Pohrt–Popov detachment criterion): an ellipsoid h = x²/(2R1) + y²/(2R2) by
/// default, or a flat punch, a power law h = s·rⁿ, a cone h = r·cot α or a measured height map
/// (`simulate --indenter`).
///
/// Units: give lengths in any unit L, E* in F/L² and the work of adhesion Δγ in F/L (energy per
/// area); dimensional outputs come out in L and F. Normalised outputs (suffix _bar) of an
/// ellipsoid use Re = √(R1 R2), c_r = (9π Re² Δγ / (4E*))^(1/3): c̄ = c/c_r, F̄ = F/(3π Re Δγ),
/// d̄ = d·Re/c_r² (the other indenters have their own scales: docs/indenters.md). For a sphere
/// JKR gives the adhesive force |min F̄| = 1/2.
#[derive(Parser)]
#[command(name = "jkrbem", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Replace output files that are write-protected (without it they are refused, as the
    /// shell's `>` refuses them).
    #[arg(long, global = true)]
    force: bool,
}

// Every flag's value may start with '-' (see `values_may_start_with_a_hyphen`): `--ratio -5` is
// refused as "--ratio = -5 is invalid: …", not as an unknown argument "-5".
#[derive(Subcommand)]
enum Command {
    /// Simulate the adhesive pull-off of one scene and write its states as CSV.
    Simulate(Box<cli::simulate::Args>),
    /// Run one pull-off per axis ratio R1/R2 (optionally one shard of them) and write a
    /// summary CSV beside each ratio's states.
    Sweep(cli::sweep::Args),
    /// Simulate every scene of a table (one per row, any parameter of `simulate` as a column),
    /// each to its own files; optionally one shard of the rows, resuming what is done.
    Batch(cli::batch::Args),
    /// Crossed identical elastic cylinders at several angles: adhesive force in newtons
    /// beside Johnson–Greenwood.
    Crossed(cli::crossed::Args),
    /// Run the whole study (sweep, fits, crossed cylinders) and write every chart and an
    /// index.html.
    Reproduce(cli::reproduce::Args),
    /// The reference table of converged adhesive forces per R1/R2 (|min F̄|, c̄ and d̄ at the
    /// minimum at Δx → 0, with uncertainties), from ladders of grids.
    Reference(cli::reference::Args),
    /// How honest the stated uncertainties are: single-grid runs of the tabled ratios at many
    /// grid phases, each estimate against its reference (1/2, or the table's Δx → 0 value).
    Coverage(cli::coverage::Args),
    /// One scene on several grids and backends: the error of the adhesive force against its
    /// wall time, as CSV and a log–log chart.
    Accuracy(cli::accuracy::Args),
    /// Merge a split sweep's shard files into DIR/sweep.csv, or a batch's scenes into
    /// DIR/batch.csv, checking that they are of one run and naming what is missing.
    Collect(cli::collect::Args),
    /// Write a closed-form curve (Hertz, JKR or Johnson–Greenwood) as CSV.
    Theory(cli::theory::Args),
    /// List the GPU adapters wgpu sees, with their limits and the largest grid each holds.
    Devices(cli::devices::Args),
    /// Time the convolution, one CG iteration and whole pull-offs per backend and grid; write
    /// a CSV and an SVG chart.
    Bench(cli::bench::Args),
    /// Generate a random self-affine rough surface (periodic, isotropic power spectrum with a
    /// roll-off and a cut-off, scaled exactly to an rms height or slope) and write it as a .npy
    /// height map with a .json sidecar of its parameters and statistics. Lengths in any unit L.
    Roughness(cli::roughness::Args),
}

/// The system allocator, except that an allocation the system refuses (a process limit such
/// as `ulimit -v`, or memory that ran out after the planner's check) ends the run as an error
/// with exit code 1, its lock and temporary files removed, instead of an abort.
struct ExitOnOutOfMemory;

// SAFETY: every call is passed to the system allocator unchanged; only a null result is
// handled, by exiting the process.
unsafe impl std::alloc::GlobalAlloc for ExitOnOutOfMemory {
    unsafe fn alloc(&self, layout: std::alloc::Layout) -> *mut u8 {
        checked(std::alloc::System.alloc(layout), layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: std::alloc::Layout) -> *mut u8 {
        checked(std::alloc::System.alloc_zeroed(layout), layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: std::alloc::Layout) {
        std::alloc::System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: std::alloc::Layout, size: usize) -> *mut u8 {
        checked(std::alloc::System.realloc(ptr, layout, size), size)
    }
}

#[global_allocator]
static ALLOCATOR: ExitOnOutOfMemory = ExitOnOutOfMemory;

/// `ptr` if the allocation of `bytes` succeeded; otherwise remove this run's lock and
/// temporary files, say so and exit with code 1 (without allocating for the message).
fn checked(ptr: *mut u8, bytes: usize) -> *mut u8 {
    if !ptr.is_null() {
        return ptr;
    }
    use std::io::Write;
    let mut message = [0u8; 400];
    let mut w = &mut message[..];
    let _ = write!(
        w,
        "\nerror: out of memory: an allocation of {bytes} bytes failed (the machine, its \
         control group or this process's limits, e.g. `ulimit -v`, allow less than the run \
         needs); choose a smaller --grid\n"
    );
    let left = w.len();
    let _ = std::io::stderr().write_all(&message[..message.len() - left]);
    jkrbem::output::file::try_remove_registered();
    std::process::exit(1)
}

/// This process's command line, each argument quoted where the shell would need it.
fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if !a.is_empty()
                && a.chars()
                    .all(|c| c.is_alphanumeric() || "-_./,=:%+@".contains(c))
            {
                a
            } else {
                format!("'{}'", a.replace('\'', "'\\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Flags that name files: a value starting with `-` there is more likely a forgotten value
/// followed by the next flag, and stays refused as an unknown argument.
const PATH_FLAGS: &[&str] = &["out", "summary"];

/// Let every other flag of every subcommand take a value that starts with `-` (`-5`, `-NaN`,
/// `-inf`, `-1%`, `-1s`), so that the flag's own check refuses it and names the flag, rather
/// than the parser saying "unexpected argument '-5'".
fn values_may_start_with_a_hyphen(command: clap::Command) -> clap::Command {
    let names: Vec<String> = command
        .get_subcommands()
        .map(|s| s.get_name().to_string())
        .collect();
    names.iter().fold(command, |command, name| {
        command.mut_subcommand(name, |sub| {
            let ids: Vec<clap::Id> = sub
                .get_arguments()
                .filter(|a| {
                    !a.is_positional()
                        && a.get_action().takes_values()
                        && !PATH_FLAGS.contains(&a.get_id().as_str())
                })
                .map(|a| a.get_id().clone())
                .collect();
            ids.into_iter().fold(sub, |sub, id| {
                sub.mut_arg(id, |a| a.allow_hyphen_values(true))
            })
        })
    })
}

/// On SIGINT, SIGTERM or SIGHUP: remove the temporary and lock files of this run (the files
/// under the names asked for are untouched, partial states keep their `.incomplete-<pid>`
/// names) and exit with 128 + the signal. SIGXFSZ (a file-size limit reached) is caught so
/// that the write fails with an error naming the file instead of killing the process.
fn install_signal_handlers() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM, SIGXFSZ};
    let _ = signal_hook::flag::register(
        SIGXFSZ,
        std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false)),
    );
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            jkrbem::output::file::remove_registered();
            let name = match signal {
                SIGINT => "SIGINT",
                SIGTERM => "SIGTERM",
                _ => "SIGHUP",
            };
            errln!(
                "\njkrbem: stopped by {name}: outputs already finished are complete, unfinished \
                 ones were not written under their names (partial states keep their \
                 .incomplete-{} names)",
                std::process::id()
            );
            std::process::exit(128 + signal);
        }
    });
}

/// Stack size of the pool thread that runs a command (bytes): the main thread's usual 8 MiB.
const MAIN_STACK_BYTES: usize = 8 << 20;

fn main() -> ExitCode {
    // First, while this is the only thread: the environment may be changed only now.
    #[cfg(feature = "gpu")]
    jkrbem::backend::gpu::headless::quiet_display_probe();
    install_signal_handlers();
    jkrbem::session::provenance::set_command_line(command_line());
    let command = values_may_start_with_a_hyphen(Cli::command());
    let cli = Cli::from_arg_matches(&command.get_matches()).unwrap_or_else(|e| e.exit());
    jkrbem::output::file::set_force(cli.force);
    // The command runs on a thread of rayon's pool (with the main thread's stack size): the
    // CPU backend's parallel passes then start from a worker, not by handing each call over
    // from outside the pool (a cost that dominated small grids).
    let _ = rayon::ThreadPoolBuilder::new()
        .stack_size(MAIN_STACK_BYTES)
        .build_global();
    let result = rayon::scope(move |_| match cli.command {
        Command::Simulate(a) => cli::simulate::run(*a),
        Command::Theory(a) => cli::theory::run(a),
        Command::Sweep(a) => cli::sweep::run(a),
        Command::Batch(a) => cli::batch::run(a),
        Command::Collect(a) => cli::collect::run(a),
        Command::Accuracy(a) => cli::accuracy::run(a),
        Command::Reproduce(a) => cli::reproduce::run(a),
        Command::Reference(a) => cli::reference::run(a),
        Command::Coverage(a) => cli::coverage::run(a),
        Command::Crossed(a) => cli::crossed::run(a),
        Command::Devices(a) => cli::devices::run(a),
        Command::Bench(a) => cli::bench::run(a),
        Command::Roughness(a) => cli::roughness::run(a),
    });
    // What standard output could not take (a closed pipe ends quietly; a full disk or
    // another error is a failure of the run, after its other messages).
    let stdout_error = cli::finish_stdout();
    match (result, stdout_error) {
        (Ok(()), None) => ExitCode::SUCCESS,
        (Ok(()), Some(e)) => {
            errln!("error: {e}");
            ExitCode::from(1)
        }
        (Err(e), stdout_error) => {
            errln!("error: {e}");
            if let Some(s) = stdout_error {
                errln!("error: {s}");
            }
            e.exit_code()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every parameter the library's messages can name is a flag of some subcommand, or the
    /// global `--force` (`crossed` renames its cylinders' parameters to its own flags).
    #[test]
    fn every_parameter_the_library_names_is_a_flag() {
        let command = Cli::command();
        let flags: Vec<String> = command
            .get_subcommands()
            .flat_map(|s| s.get_arguments())
            .chain(command.get_arguments())
            .filter_map(|a| a.get_long().map(|l| format!("--{l}")))
            .collect();
        for p in jkrbem::params::all() {
            let flag = cli::crossed::flag(p).flag;
            assert!(flags.iter().any(|f| f == flag), "{} is no flag", p.flag);
        }
    }
}
