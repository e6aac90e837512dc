//! `jkrbem crossed`: two identical elastic cylinders crossed at angles θ, each mapped to an
//! ellipsoid (physics §1), one pull-off per angle; the adhesive force in newtons (in the units
//! of the inputs) beside Johnson–Greenwood's. The work is [`jkrbem::studies::crossed`].

use super::parse::value;
use super::progress::Progress;
use super::stdout::not_stdout;
use super::{count_in, no_repeats, run_error, CliError};
use jkrbem::params::{
    Spec, ACCURACY, ANGLE, ANGLES, E, GRID, JOBS, MARGIN, NU, POISSON, RADIUS, STEPS,
    WORK_OF_ADHESION, YOUNG,
};
use jkrbem::studies::crossed::{crossed, CrossedRequest};
use std::path::PathBuf;

/// Arguments of `jkrbem crossed`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Radius R of both cylinders (length, e.g. m; in [1e-30, 1e30]).
    #[arg(long, default_value_t = 0.01, value_parser = value::<f64>(RADIUS))]
    pub radius: f64,
    /// Crossing angles θ in degrees, comma-separated: 1 to 100 values, none repeated, each in
    /// [3.63, 90] (90 is sphere-like; 16.1 gives R1/R2 ≈ 50; below 3.63° R1/R2 would exceed
    /// 1000).
    #[arg(long, value_delimiter = ',', default_value = "90,70,50,30,16.1", value_parser = value::<f64>(ANGLES))]
    pub angles: Vec<f64>,
    /// Young's modulus E of both cylinders (force/length², e.g. Pa; in [1e-30, 1e30]).
    #[arg(long = "e", default_value_t = 1.0e6, value_parser = value::<f64>(E))]
    pub young: f64,
    /// Poisson's ratio ν of both cylinders, in [−0.99, 0.5].
    #[arg(long = "nu", default_value_t = 0.5, value_parser = value::<f64>(NU))]
    pub poisson: f64,
    /// Work of adhesion Δγ (energy/area, e.g. J/m²; in [1e-30, 1e30]).
    #[arg(long, default_value_t = 0.05, value_parser = value::<f64>(WORK_OF_ADHESION))]
    pub work_of_adhesion: f64,
    /// Elements along x, Nx, for every angle (a power of two from 16 to 65536); each estimate
    /// then states its expected bias [default: the grid --accuracy chooses].
    #[arg(long, value_parser = value::<usize>(GRID))]
    pub grid: Option<usize>,
    /// The relative accuracy of each adhesive force |min F̄| at Δx → 0 (a percentage such as
    /// `2%`, the unit required): each angle gets the one grid, re-gridded, whose estimate is
    /// predicted to state an uncertainty within it [default: 2% unless --grid is given].
    #[arg(long, value_parser = value::<f64>(ACCURACY), conflicts_with = "grid")]
    pub accuracy: Option<f64>,

    /// Load steps from the initial approach to the expected end of contact (1 to 100000).
    #[arg(long, default_value_t = 200, value_parser = value::<usize>(STEPS))]
    pub steps: usize,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10]).
    #[arg(long, default_value_t = 0.08, value_parser = value::<f64>(MARGIN))]
    pub margin: f64,
    // The backend of every run, and its arithmetic.
    #[command(flatten)]
    pub backend: super::study_backend::StudyBackendArgs,
    /// Pull-offs run at the same time (1 to 256).
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(JOBS))]
    pub jobs: usize,
    /// Output folder: per angle states and summary, crossed.csv and crossed.svg.
    #[arg(long, default_value = "jkrbem-out/crossed")]
    pub out: PathBuf,
    #[command(flatten)]
    pub figures: super::figures::FigureArgs,
}

/// The parameter of this command that sets each of the analysis layer's (its flag is the one
/// a message names).
pub(crate) fn flag(parameter: &'static Spec) -> &'static Spec {
    if parameter == ANGLE {
        ANGLES
    } else if parameter == YOUNG {
        E
    } else if parameter == POISSON {
        NU
    } else {
        parameter
    }
}

/// Run `jkrbem crossed`.
pub fn run(args: Args) -> Result<(), CliError> {
    count_in("--angles", args.angles.len(), 1, 100)?;
    no_repeats("--angles", &args.angles)?;
    not_stdout("--out", &args.out, "crossed")?;
    let request = CrossedRequest {
        radius: args.radius,
        angles: args.angles.clone(),
        young: args.young,
        poisson: args.poisson,
        work_of_adhesion: args.work_of_adhesion,
        grid: super::grid_choice(args.grid, args.accuracy),
        steps: args.steps,
        margin: args.margin,
        backend: args.backend.request(),
        jobs: args.jobs,
        out: args.out.clone(),
        figures: args.figures.figure_format,
    };
    let done = crossed(&request, &flag, &Progress::new()).map_err(run_error)?;
    outln!("θ (deg)  R1/R2    F_ad                    JG F_ad    n_d");
    for r in &done.rows {
        let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4e}"));
        let u = r
            .f_ad_uncertainty
            .map_or(String::new(), |u| format!(" ± {u:.2e}"));
        outln!(
            "{:<8} {:<8.3} {:<23} {:<10} {}",
            r.angle_deg,
            r.ratio,
            format!("{}{u}", f(r.f_ad)),
            f(r.jg_f_ad),
            r.n_d.map_or("—".into(), |v| format!("{v:.0}"))
        );
    }
    for w in &done.warnings {
        errln!("WARNING: {w}");
    }
    outln!(
        "written {} and {}",
        done.files[0].display(),
        args.figures.figure_format.shown(&done.files[1])
    );
    super::failures("pull-offs", &done.failures, "")
}
