//! `jkrbem crossed`: two identical elastic cylinders crossed at angles θ, each mapped to an
//! ellipsoid (SPEC §1), one pull-off per angle; the adhesive force in newtons (in the units of
//! the inputs) beside Johnson–Greenwood's.

use super::outputs::{named, write_error, Outputs};
use super::simulate::BackendChoice;
use super::sweep::{run_all, run_files};
use super::{count_in, failed, input, no_repeats, CliError, MAX_JOBS};
use jkrbem::analysis::CrossedCylinders;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::output::line_chart::{LineChart, Style};
use jkrbem::theory;
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `jkrbem crossed`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Radius R of both cylinders (length, e.g. m; in [1e-30, 1e30]).
    #[arg(long, default_value_t = 0.01)]
    pub radius: f64,
    /// Crossing angles θ in degrees, comma-separated: 1 to 100 values, none repeated, each in
    /// [3.63, 90] (90 is sphere-like; 16.1 gives R1/R2 ≈ 50; below 3.63° R1/R2 would exceed
    /// 1000).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "90,70,50,30,16.1",
        allow_hyphen_values = true
    )]
    pub angles: Vec<f64>,
    /// Young's modulus E of both cylinders (force/length², e.g. Pa; in [1e-30, 1e30]).
    #[arg(long = "e", default_value_t = 1.0e6)]
    pub young: f64,
    /// Poisson's ratio ν of both cylinders, in [−0.99, 0.5].
    #[arg(long = "nu", default_value_t = 0.5)]
    pub poisson: f64,
    /// Work of adhesion Δγ (energy/area, e.g. J/m²; in [1e-30, 1e30]).
    #[arg(long, default_value_t = 0.05)]
    pub work_of_adhesion: f64,
    /// Elements along x, Nx, for every angle (a power of two from 16 to 65536).
    #[arg(long, default_value_t = 128)]
    pub grid: usize,
    /// Load steps from the initial approach to the expected end of contact (1 to 100000).
    #[arg(long, default_value_t = 200)]
    pub steps: usize,
    /// Free margin around the initial contact, relative to its half-axes (in [0, 10]).
    #[arg(long, default_value_t = 0.08)]
    pub margin: f64,
    /// Backend: `cpu`, `gpu` or `auto`.
    #[arg(long, value_enum, default_value_t = BackendChoice::Auto)]
    pub backend: BackendChoice,
    /// Pull-offs run at the same time (1 to 256).
    #[arg(long, default_value_t = 1, value_parser = clap::builder::RangedU64ValueParser::<usize>::new().range(1..=MAX_JOBS as u64))]
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
    count_in("--angles", args.angles.len(), 1, 100)?;
    no_repeats("--angles", &args.angles)?;
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
        .map_err(|e| input(format!("--angles {}: {e}", jkrbem::text::compact(angle))))?;
        scales.push((angle, scene.ratio(), c.force_scale().map_err(input)?));
        work.push((
            model,
            args.out.join(format!("theta{angle}-n{}.csv", args.grid)),
        ));
    }
    let refs: Vec<&Model> = work.iter().map(|(m, _)| m).collect();
    jkrbem::plan::check_memory(&refs, args.jobs, "--grid").map_err(input)?;
    let csv_path = args.out.join("crossed.csv");
    let svg_path = args.out.join("crossed.svg");
    let mut targets: Vec<PathBuf> = work.iter().flat_map(|(_, out)| run_files(out)).collect();
    targets.extend([csv_path.clone(), svg_path.clone()]);
    let _claimed = Outputs::claim(&named("--out", &targets))?;
    let results = run_all(work, args.jobs, args.backend);
    let failures: Vec<String> = results.iter().filter_map(|r| r.error.clone()).collect();
    let mut rows: Vec<CrossedRow> = scales
        .iter()
        .zip(&results)
        .map(|(&(angle, ratio, scale), r)| {
            let s = r.summary.as_ref();
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
    jkrbem::output::file::write_csv(&csv_path, None, &rows).map_err(write_error("--out"))?;
    chart(&args, &rows)
        .write_svg(&svg_path)
        .map_err(write_error("--out"))?;
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
    println!("written {} and {}", csv_path.display(), svg_path.display());
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

/// Adhesive force against crossing angle: the runs beside JG over (θ_min, 90°]. The title
/// gives the inputs in SI units (the documented use: m, Pa, J/m², so forces in N); other
/// consistent units work the same, as the y label says.
fn chart(args: &Args, rows: &[CrossedRow]) -> LineChart {
    use jkrbem::text::compact;
    let mut chart = LineChart::new(
        &format!(
            "Crossed cylinders: R = {} m, E = {} Pa, ν = {}, Δγ = {} J/m²",
            compact(args.radius),
            compact(args.young),
            compact(args.poisson),
            compact(args.work_of_adhesion)
        ),
        "crossing angle θ (degrees)",
        "adhesive force |F_min| (N; in the unit of E·R² for non-SI inputs)",
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
