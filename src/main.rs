//! The `jkrbem` command: parses arguments, builds a scene, calls the library, writes outputs.

mod cli;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// FFT-based BEM solver for JKR-type adhesive contact of a rigid ellipsoid
/// h = x²/(2R1) + y²/(2R2) with an elastic half-space (Pohrt–Popov detachment criterion).
///
/// Units: give lengths in any unit L, E* in F/L² and the work of adhesion Δγ in F/L (energy per
/// area); dimensional outputs come out in L and F. Normalised outputs (suffix _bar) use
/// Re = √(R1 R2), c_r = (9π Re² Δγ / (4E*))^(1/3): c̄ = c/c_r, F̄ = F/(3π Re Δγ),
/// d̄ = d·Re/c_r². For a sphere JKR gives the adhesive force |min F̄| = 1/2.
#[derive(Parser)]
#[command(name = "jkrbem", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

// Every subcommand lets negative numbers through to its range checks (`--ratio -5` is
// refused as "--ratio = -5 is invalid: …", not as an unknown argument "-5").
#[derive(Subcommand)]
enum Command {
    /// Simulate the adhesive pull-off of one scene and write its states as CSV.
    #[command(allow_negative_numbers = true)]
    Simulate(cli::simulate::Args),
    /// Run one pull-off per axis ratio R1/R2 (optionally one shard of them) and write a
    /// summary CSV beside each ratio's states.
    #[command(allow_negative_numbers = true)]
    Sweep(cli::sweep::Args),
    /// Crossed identical elastic cylinders at several angles: adhesive force in newtons
    /// beside Johnson–Greenwood.
    #[command(allow_negative_numbers = true)]
    Crossed(cli::crossed::Args),
    /// Run the whole study (sweep, fits, crossed cylinders) and write every chart and an
    /// index.html.
    #[command(allow_negative_numbers = true)]
    Reproduce(cli::reproduce::Args),
    /// The reference table of converged adhesive forces per R1/R2 (|min F̄|, c̄ and d̄ at the
    /// minimum at Δx → 0, with uncertainties), from ladders of grids.
    Reference(cli::reference::Args),
    /// How honest the stated uncertainties are: single-grid runs of the tabled ratios at many
    /// grid phases, each estimate against its reference (1/2, or the table's Δx → 0 value).
    Coverage(cli::coverage::Args),
    /// One scene on several grids and backends: the error of the adhesive force against its
    /// wall time, as CSV and a log–log chart.
    #[command(allow_negative_numbers = true)]
    Accuracy(cli::accuracy::Args),
    /// Merge the shard files of a split sweep into DIR/sweep.csv, checking that they are of
    /// one sweep and naming missing or incomplete ratios.
    Collect(cli::collect::Args),
    /// Write a closed-form curve (Hertz, JKR or Johnson–Greenwood) as CSV.
    #[command(allow_negative_numbers = true)]
    Theory(cli::theory::Args),
    /// List the GPU adapters wgpu sees, with their limits and the largest grid each holds.
    Devices(cli::devices::Args),
    /// Time the convolution, one CG iteration and whole pull-offs per backend and grid; write
    /// a CSV and an SVG chart.
    #[command(allow_negative_numbers = true)]
    Bench(cli::bench::Args),
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
            eprintln!(
                "\njkrbem: stopped by {name}: outputs already finished are complete, unfinished \
                 ones were not written under their names (partial states keep their \
                 .incomplete-{} names)",
                std::process::id()
            );
            std::process::exit(128 + signal);
        }
    });
}

fn main() -> ExitCode {
    install_signal_handlers();
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Simulate(a) => cli::simulate::run(a),
        Command::Theory(a) => cli::theory::run(a),
        Command::Sweep(a) => cli::sweep::run(a),
        Command::Collect(a) => cli::collect::run(a),
        Command::Accuracy(a) => cli::accuracy::run(a),
        Command::Reproduce(a) => cli::reproduce::run(a),
        Command::Reference(a) => cli::reference::run(a),
        Command::Coverage(a) => cli::coverage::run(a),
        Command::Crossed(a) => cli::crossed::run(a),
        Command::Devices(a) => cli::devices::run(a),
        Command::Bench(a) => cli::bench::run(a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}
