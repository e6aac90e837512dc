//! `jkrbem accuracy`: one scene on several grids, backends and ways of running; the error of
//! the adhesive force against the wall time it cost, as CSV and a log–log chart.

use super::parse::value;
use super::progress::Progress;
use super::{count_in, failures, no_repeats, run_error, CliError};
use jkrbem::backend::select::BackendKind;
use jkrbem::params::{GRIDS, RATIO};
use jkrbem::studies::accuracy::{accuracy, AccuracyRequest, Variant};
use std::path::PathBuf;

/// Arguments of `jkrbem accuracy`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratio R1/R2, in [1, 1000] (1 is the sphere, whose exact answer is JKR's 1/2;
    /// otherwise the reference is the first backend's own extrapolation to Δx → 0).
    #[arg(long, default_value_t = 1.0, value_parser = value::<f64>(RATIO))]
    pub ratio: f64,
    /// Grids Nx, coarse to fine: 2 to 12 increasing powers of two from 16 to 65536.
    #[arg(long, value_delimiter = ',', default_value = "32,64,128", value_parser = value::<usize>(GRIDS))]
    pub grids: Vec<usize>,
    /// Backends, comma-separated, none repeated: `cpu` (f64), `gpu` (f32), `auto`. The
    /// precision follows the backend.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "cpu")]
    pub backends: Vec<BackendKind>,
    /// Ways of running each grid, comma-separated, none repeated: `plain` (the whole curve on
    /// a fixed grid), `measure` (--measure adhesive-force: stop once the minimum is confirmed)
    /// and `regrid` (--measure adhesive-force --regrid: also refine Δx as the contact
    /// shrinks).
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "plain,measure,regrid"
    )]
    pub variants: Vec<Variant>,
    /// Output folder: states per run, accuracy.csv and accuracy.svg.
    #[arg(long, default_value = "jkrbem-out/accuracy")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// Run `jkrbem accuracy`.
pub fn run(args: Args) -> Result<(), CliError> {
    count_in("--grids", args.grids.len(), 2, 12)?;
    super::stdout::not_stdout("--out", &args.out, "accuracy")?;
    let names: Vec<String> = args
        .backends
        .iter()
        .map(|b| format!("{b:?}").to_lowercase())
        .collect();
    no_repeats("--backends", &names)?;
    no_repeats("--variants", &args.variants)?;
    let req = AccuracyRequest {
        ratio: args.ratio,
        grids: args.grids,
        backends: args.backends,
        variants: args.variants,
        out: args.out,
        figures: args.figures.figure_format,
    };
    let done = accuracy(&req, &Progress::new()).map_err(run_error)?;
    outln!("reference: {}", done.reference);
    outln!(
        "variant  backend  grid                                  raw |min F̄| (error)   \
         stated |min F̄| ± uncertainty (error)   CG its   wall (s)"
    );
    let percent = |e: Option<f64>| e.map_or("—".into(), |v| format!("{:+.2} %", 100.0 * v));
    for r in &done.rows {
        let raw = match r.f_ad_bar {
            Some(v) => format!("{v:.4} ({})", percent(r.error)),
            None => "—".into(),
        };
        let stated = match (r.stated, r.stated_uncertainty) {
            (Some(v), Some(u)) => format!("{v:.4} ± {u:.4} ({})", percent(r.stated_error)),
            _ => "—".into(),
        };
        outln!(
            "{:<8} {:<8} {:<37} {:<21} {:<38} {:<8} {:.2}",
            r.variant,
            r.backend,
            r.grid,
            raw,
            stated,
            r.cg_iterations,
            r.wall_s
        );
    }
    outln!(
        "written {}, {} and {}",
        done.csv.display(),
        args.figures.figure_format.shown(&done.svg),
        args.figures.figure_format.shown(&done.iterations_svg)
    );
    failures("runs", &done.failures, "")
}
