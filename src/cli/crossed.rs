//! `jkrbem crossed`: two identical elastic cylinders crossed at angles θ, each mapped to an
//! ellipsoid (SPEC §1), one pull-off per angle; the adhesive force in newtons (in the units of
//! the inputs) beside Johnson–Greenwood's.

use super::simulate::BackendChoice;
use super::sweep::run_all;
use super::{failed, input, CliError};
use jkrbem::analysis::CrossedCylinders;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::output::line_chart::{LineChart, Style};
use jkrbem::theory;
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `jkrbem crossed`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Radius R of both cylinders (length, e.g. m).
    #[arg(long, default_value_t = 0.01)]
    pub radius: f64,
    /// Crossing angles θ in degrees, in (0, 90] (90 is sphere-like; 16.1 gives R1/R2 ≈ 50).
    #[arg(long, value_delimiter = ',', default_value = "90,70,50,30,16.1")]
    pub angles: Vec<f64>,
    /// Young's modulus E of both cylinders (force/length², e.g. Pa).
    #[arg(long = "e", default_value_t = 1.0e6)]
    pub young: f64,
    /// Poisson's ratio ν of both cylinders, in (−1, 0.5].
    #[arg(long = "nu", default_value_t = 0.5)]
    pub poisson: f64,
    /// Work of adhesion Δγ (energy/area, e.g. J/m²).
    #[arg(long, default_value_t = 0.05)]
    pub work_of_adhesion: f64,
    /// Elements along x, Nx, for every angle (a power of two ≥ 16).
    #[arg(long, default_value_t = 128)]
    pub grid: usize,
    /// Load steps from the initial approach to the expected end of contact.
    #[arg(long, default_value_t = 200)]
    pub steps: usize,
    /// Free margin around the initial contact, relative to its half-axes.
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Backend: `cpu`, `gpu` or `auto`.
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Pull-offs run at the same time.
    #[arg(long, default_value_t = 1)]
    pub jobs: usize,
    /// Output folder: per angle states and summary, crossed.csv and crossed.svg.
    #[arg(long, default_value = "jkrbem-out/crossed")]
    pub out: PathBuf,
}

/// One angle's result (forces in the inputs' force unit, e.g. N).
#[derive(Debug, Clone, Serialize)]
struct CrossedRow {
    angle_deg: f64,
    ratio: f64,
    f_ad: Option<f64>,
    jg_f_ad: Option<f64>,
    f_ad_bar: Option<f64>,
    jg_f_ad_bar: Option<f64>,
    n_d: Option<f64>,
    grid: usize,
    wall_s: f64,
    complete: bool,
}

/// JG's (JKR's at 90°) adhesive force |min F̄| at a ratio.
fn jg_force_bar(ratio: f64) -> Option<f64> {
    theory::reference_adhesive_force(ratio).ok()
}

/// The analysis layer names its parameters `--angle`, `--young` and `--poisson`; this
/// command's flags are `--angles`, `--e` and `--nu`.
fn with_cli_flags(message: &str) -> String {
    message
        .replace("--angle", "--angles")
        .replace("--young", "--e")
        .replace("--poisson", "--nu")
}

/// Run `jkrbem crossed`.
pub fn run(args: Args) -> Result<(), CliError> {
    if args.angles.is_empty() || args.jobs == 0 {
        return Err(input(
            "--angles needs at least one angle and --jobs at least 1",
        ));
    }
    let pair = |angle_deg: f64| CrossedCylinders {
        radius: args.radius,
        angle_deg,
        young: args.young,
        poisson: args.poisson,
        work_of_adhesion: args.work_of_adhesion,
    };
    let mut work = Vec::new();
    let mut scales = Vec::new();
    for &angle in &args.angles {
        let c = pair(angle);
        let scene = c
            .scene()
            .map_err(|e| input(with_cli_flags(&e.to_string())))?;
        let model = Model::build(
            &scene,
            &ModelOptions {
                nx: args.grid,
                steps: args.steps,
                margin: args.margin,
                ..ModelOptions::default()
            },
        )
        .map_err(|e| input(format!("--angles {angle}: {e}")))?;
        scales.push((angle, scene.ratio(), c.force_scale().map_err(input)?));
        work.push((
            model,
            args.out.join(format!("theta{angle}-n{}.csv", args.grid)),
        ));
    }
    let (summaries, failures) = run_all(work, args.jobs, args.backend);
    let mut rows: Vec<CrossedRow> = scales
        .iter()
        .map(|&(angle, ratio, scale)| {
            let s = summaries.iter().find(|s| s.ratio == ratio);
            let f_ad_bar = s.and_then(|s| s.f_ad_bar);
            let jg = jg_force_bar(ratio);
            CrossedRow {
                angle_deg: angle,
                ratio,
                f_ad: f_ad_bar.map(|f| f * scale),
                jg_f_ad: jg.map(|f| f * scale),
                f_ad_bar,
                jg_f_ad_bar: jg,
                n_d: s.and_then(|s| s.n_d),
                grid: args.grid,
                wall_s: s.map_or(0.0, |s| s.wall_s),
                complete: s.is_some_and(|s| s.complete),
            }
        })
        .collect();
    rows.sort_by(|a, b| b.angle_deg.total_cmp(&a.angle_deg));
    let csv_path = args.out.join("crossed.csv");
    let mut w = csv::Writer::from_path(&csv_path).map_err(failed)?;
    for r in &rows {
        w.serialize(r).map_err(failed)?;
    }
    w.flush().map_err(failed)?;
    chart(&args, &rows)
        .write_svg(&args.out.join("crossed.svg"))
        .map_err(failed)?;
    println!("θ (deg)  R1/R2    F_ad       JG F_ad    n_d");
    for r in &rows {
        let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.4e}"));
        println!(
            "{:<8} {:<8.3} {:<10} {:<10} {}",
            r.angle_deg,
            r.ratio,
            f(r.f_ad),
            f(r.jg_f_ad),
            r.n_d.map_or("—".into(), |v| format!("{v:.0}"))
        );
    }
    println!(
        "written {} and {}",
        csv_path.display(),
        args.out.join("crossed.svg").display()
    );
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} of the pull-offs failed:\n  {}",
            failures.len(),
            failures.join("\n  ")
        )))
    }
}

/// Adhesive force against crossing angle: the runs beside JG over (θ_min, 90°].
fn chart(args: &Args, rows: &[CrossedRow]) -> LineChart {
    let mut chart = LineChart::new(
        &format!(
            "Crossed cylinders: R = {}, E = {}, ν = {}, Δγ = {}",
            args.radius, args.young, args.poisson, args.work_of_adhesion
        ),
        "crossing angle θ (degrees)",
        "adhesive force |F_min| (force unit of E·R²)",
    );
    let lo = rows.iter().map(|r| r.angle_deg).fold(90.0, f64::min);
    let jg: Vec<(f64, f64)> = (0..=200)
        .map(|i| lo + (90.0 - lo) * i as f64 / 200.0)
        .filter_map(|a| {
            let c = CrossedCylinders {
                radius: args.radius,
                angle_deg: a,
                young: args.young,
                poisson: args.poisson,
                work_of_adhesion: args.work_of_adhesion,
            };
            let ratio = c.scene().ok()?.ratio();
            Some((a, jg_force_bar(ratio)? * c.force_scale().ok()?))
        })
        .collect();
    chart.push("Johnson–Greenwood", jg, 1, Style::Line);
    let sim = rows
        .iter()
        .filter_map(|r| Some((r.angle_deg, r.f_ad?)))
        .collect();
    chart.push(
        &format!("jkrbem (Nx = {})", args.grid),
        sim,
        0,
        Style::Markers,
    );
    chart
}
