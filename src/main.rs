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

#[derive(Subcommand)]
enum Command {
    /// Simulate the adhesive pull-off of one scene and write its states as CSV.
    Simulate(cli::simulate::Args),
    /// Run one pull-off per axis ratio R1/R2 (optionally one shard of them) and write a
    /// summary CSV beside each ratio's states.
    Sweep(cli::sweep::Args),
    /// Crossed identical elastic cylinders at several angles: adhesive force in newtons
    /// beside Johnson–Greenwood.
    Crossed(cli::crossed::Args),
    /// Run the whole study (sweep, fits, crossed cylinders) and write every chart and an
    /// index.html.
    Reproduce(cli::reproduce::Args),
    /// One scene on several grids and backends: the error of the adhesive force against its
    /// wall time, as CSV and a log–log chart.
    Accuracy(cli::accuracy::Args),
    /// Merge the shard summaries of a split sweep into DIR/sweep.csv.
    Collect(cli::collect::Args),
    /// Write a closed-form curve (Hertz, JKR or Johnson–Greenwood) as CSV.
    Theory(cli::theory::Args),
    /// List the GPU adapters wgpu sees, with their limits and the largest grid each holds.
    Devices(cli::devices::Args),
    /// Time the convolution, one CG iteration and whole pull-offs per backend and grid; write
    /// a CSV and an SVG chart.
    Bench(cli::bench::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Simulate(a) => cli::simulate::run(a),
        Command::Theory(a) => cli::theory::run(a),
        Command::Sweep(a) => cli::sweep::run(a),
        Command::Collect(a) => cli::collect::run(a),
        Command::Accuracy(a) => cli::accuracy::run(a),
        Command::Reproduce(a) => cli::reproduce::run(a),
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
