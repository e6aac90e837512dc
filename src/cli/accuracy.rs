//! `jkrbem accuracy`: one scene on several grids and backends; the error of the adhesive force
//! against the wall time it cost, as CSV and a log–log chart.

use super::outputs::{named, write_error, Outputs};
use super::simulate::BackendChoice;
use super::sweep::{run_all, run_files};
use super::{count_in, failed, input, no_repeats, CliError};
use jkrbem::analysis::extrapolate::extrapolate_first_order;
use jkrbem::model::{Measure, Model, ModelOptions};
use jkrbem::output::chart::{LogLogChart, Series};
use jkrbem::output::summary::Summary;
use jkrbem::scene::Scene;
use serde::Serialize;
use std::path::PathBuf;

/// Arguments of `jkrbem accuracy`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Axis ratio R1/R2, in [1, 1000] (1 is the sphere, whose exact answer is JKR's 1/2).
    #[arg(long, default_value_t = 1.0)]
    pub ratio: f64,
    /// Grids Nx, coarse to fine: 2 to 12 increasing powers of two from 16 to 65536.
    #[arg(long, value_delimiter = ',', default_value = "32,64,128")]
    pub grids: Vec<usize>,
    /// Backends, comma-separated, none repeated: `cpu` (f64) and/or `gpu` (f32). The
    /// precision follows the backend.
    #[arg(long, value_delimiter = ',', default_value = "cpu")]
    pub backends: Vec<String>,
    /// Ways of running each grid, comma-separated: `plain` (the whole curve on a fixed grid),
    /// `measure` (--measure adhesive-force: stop once the minimum is confirmed) and `regrid`
    /// (--measure adhesive-force --regrid: also refine Δx as the contact shrinks). None
    /// repeated.
    #[arg(long, value_delimiter = ',', default_value = "plain,measure,regrid")]
    pub variants: Vec<String>,
    /// Output folder: states per run, accuracy.csv and accuracy.svg.
    #[arg(long, default_value = "jkrbem-out/accuracy")]
    pub out: PathBuf,
}

/// A way of running each grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Variant {
    Plain,
    Measure,
    Regrid,
}

impl Variant {
    fn parse(text: &str) -> Result<Self, CliError> {
        match text.trim() {
            "plain" => Ok(Variant::Plain),
            "measure" => Ok(Variant::Measure),
            "regrid" => Ok(Variant::Regrid),
            other => Err(input(format!(
                "--variants: unknown variant {other:?} (use plain, measure, regrid)"
            ))),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Variant::Plain => "plain",
            Variant::Measure => "measure",
            Variant::Regrid => "regrid",
        }
    }

    /// The flags this variant adds, for labels.
    fn flags(self) -> &'static str {
        match self {
            Variant::Plain => "whole curve",
            Variant::Measure => "--measure adhesive-force",
            Variant::Regrid => "--measure adhesive-force --regrid",
        }
    }

    fn options(self, nx: usize) -> ModelOptions {
        ModelOptions {
            nx,
            measure: if self == Variant::Plain {
                Measure::Curve
            } else {
                Measure::AdhesiveForce
            },
            regrid: self == Variant::Regrid,
            ..ModelOptions::default()
        }
    }
}

/// The header of accuracy.csv, one column per [`Row`] field.
const ROW_HEADER: &str = "variant,backend,precision,grid,n_d,f_ad_bar,error,wall_s,cg_iterations";

/// One run of the chart.
#[derive(Debug, Clone, Serialize)]
struct Row {
    variant: &'static str,
    backend: String,
    precision: String,
    grid: String,
    n_d: Option<f64>,
    f_ad_bar: Option<f64>,
    /// Relative error of |min F̄| against the reference.
    error: Option<f64>,
    wall_s: f64,
    cg_iterations: usize,
}

/// Run `jkrbem accuracy`.
pub fn run(args: Args) -> Result<(), CliError> {
    count_in("--grids", args.grids.len(), 2, 12)?;
    if args.grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(input(
            "--grids: give 2 to 12 increasing grids, e.g. 32,64,128",
        ));
    }
    let names: Vec<String> = args.backends.iter().map(|b| b.trim().to_string()).collect();
    no_repeats("--backends", &names)?;
    let variant_names: Vec<String> = args.variants.iter().map(|v| v.trim().to_string()).collect();
    no_repeats("--variants", &variant_names)?;
    let mut choices = Vec::new();
    for b in &args.backends {
        choices.push(match b.trim() {
            "cpu" => BackendChoice::Cpu,
            "gpu" => BackendChoice::Gpu,
            other => {
                return Err(input(format!(
                    "--backends: unknown backend {other:?} (use cpu and/or gpu)"
                )))
            }
        });
    }
    let variants: Vec<Variant> = args
        .variants
        .iter()
        .map(|v| Variant::parse(v))
        .collect::<Result<_, _>>()?;
    if variants.is_empty() {
        return Err(input(
            "--variants: give at least one of plain, measure, regrid",
        ));
    }
    let scene = Scene::from_ratio(args.ratio, 1.0, 1.0, 1.0).map_err(input)?;
    // Every model is built, and every output claimed, before any work.
    let mut plan = Vec::new();
    for (name, choice) in names.iter().zip(&choices) {
        for &variant in &variants {
            let mut work = Vec::new();
            for &nx in &args.grids {
                let model = Model::build(&scene, &variant.options(nx))
                    .map_err(|e| input(format!("--grids {nx}: {e}")))?;
                let file = format!("{name}-{}-n{nx}.csv", variant.name());
                work.push((model, args.out.join(file)));
            }
            plan.push((name.clone(), *choice, variant, work));
        }
    }
    let refs: Vec<&Model> = plan
        .iter()
        .flat_map(|p| p.3.iter().map(|(m, _)| m))
        .collect();
    jkrbem::plan::check_memory(&refs, 1, "--grids").map_err(input)?;
    let csv_path = args.out.join("accuracy.csv");
    let svg_path = args.out.join("accuracy.svg");
    let mut targets: Vec<PathBuf> = plan
        .iter()
        .flat_map(|p| p.3.iter().flat_map(|(_, out)| run_files(out)))
        .collect();
    targets.extend([csv_path.clone(), svg_path.clone()]);
    let _claimed = Outputs::claim(&named("--out", &targets))?;
    let mut per_backend: Vec<(String, Variant, Vec<Summary>)> = Vec::new();
    let mut failures = Vec::new();
    for (name, choice, variant, work) in plan {
        let results = run_all(work, 1, choice);
        failures.extend(results.iter().filter_map(|r| r.error.clone()));
        let mut summaries: Vec<Summary> = results.into_iter().filter_map(|r| r.summary).collect();
        summaries.sort_by_key(|s| s.nx);
        per_backend.push((name, variant, summaries));
    }
    // The reference: JKR's exact 1/2 for the sphere, else the first backend extrapolated.
    let (reference, reference_text) = if args.ratio == 1.0 {
        (Some(0.5), "exact JKR value 1/2".to_string())
    } else {
        let s = &per_backend[0].2;
        let dx: Vec<f64> = s.iter().map(|s| s.dx_at_min.unwrap_or(s.dx)).collect();
        let f: Option<Vec<f64>> = s.iter().map(|s| s.f_ad_bar).collect();
        let x = f.and_then(|f| extrapolate_first_order(&dx, &f));
        (
            x.map(|x| x.value),
            x.map_or("no reference".into(), |x| {
                format!(
                    "{} extrapolated to Δx → 0: {:.4} ± {:.4}",
                    per_backend[0].0, x.value, x.error_bar
                )
            }),
        )
    };
    let error = |f: Option<f64>| Some(f? / reference? - 1.0);
    let mut rows = Vec::new();
    let mut chart = LogLogChart::new(
        format!(
            "R1/R2 = {}: error of |min F̄| against cost ({reference_text})",
            args.ratio
        ),
        "wall time (s)",
        "|relative error of |min F̄||",
    );
    chart.x_data_ticks = false;
    for (i, (name, variant, summaries)) in per_backend.iter().enumerate() {
        let mut points = Vec::new();
        for s in summaries {
            let e = error(s.f_ad_bar);
            rows.push(Row {
                variant: variant.name(),
                backend: name.clone(),
                precision: s.precision.clone(),
                grid: format!("{}x{}", s.nx, s.ny),
                n_d: s.n_d,
                f_ad_bar: s.f_ad_bar,
                error: e,
                wall_s: s.wall_s,
                cg_iterations: s.cg_iterations,
            });
            if let Some(e) = e {
                points.push((s.wall_s, e.abs()));
            }
        }
        chart.push(Series {
            label: format!(
                "{name} ({}), {}: one grid per point",
                summaries.first().map_or("", |s| s.precision.as_str()),
                variant.flags()
            ),
            points,
            color: i,
            dashed: false,
        });
        // Extrapolation from each pair of consecutive grids costs their wall times together.
        let Some(reference) = reference else { continue };
        let mut points = Vec::new();
        for pair in summaries.windows(2) {
            let dx: Vec<f64> = pair.iter().map(|s| s.dx_at_min.unwrap_or(s.dx)).collect();
            let f: Option<Vec<f64>> = pair.iter().map(|s| s.f_ad_bar).collect();
            let Some(x) = f.and_then(|f| extrapolate_first_order(&dx, &f)) else {
                continue;
            };
            let cost = pair[0].wall_s + pair[1].wall_s;
            let e = x.value / reference - 1.0;
            rows.push(Row {
                variant: variant.name(),
                backend: name.clone(),
                precision: pair[0].precision.clone(),
                grid: format!("extrapolated from {} and {}", pair[0].nx, pair[1].nx),
                n_d: None,
                f_ad_bar: Some(x.value),
                error: Some(e),
                wall_s: cost,
                cg_iterations: pair[0].cg_iterations + pair[1].cg_iterations,
            });
            // The reference itself (non-sphere) has no error to chart.
            if e.abs() > 0.0 {
                points.push((cost, e.abs()));
            }
        }
        if !points.is_empty() {
            chart.push(Series {
                label: format!(
                    "{name}, {}: extrapolated from two consecutive grids",
                    variant.name()
                ),
                points,
                color: i,
                dashed: true,
            });
        }
    }
    jkrbem::output::file::write_csv(&csv_path, Some(ROW_HEADER), &rows)
        .map_err(write_error("--out"))?;
    chart.write_svg(&svg_path).map_err(write_error("--out"))?;
    println!("reference: {reference_text}");
    println!("variant  backend  grid                         |min F̄|   error      wall (s)");
    for r in &rows {
        println!(
            "{:<8} {:<8} {:<28} {:<9} {:<10} {:.2}",
            r.variant,
            r.backend,
            r.grid,
            r.f_ad_bar.map_or("—".into(), |v| format!("{v:.4}")),
            r.error
                .map_or("—".into(), |v| format!("{:+.2} %", 100.0 * v)),
            r.wall_s
        );
    }
    println!("written {} and {}", csv_path.display(), svg_path.display());
    if failures.is_empty() {
        Ok(())
    } else {
        Err(failed(format!(
            "{} run(s) failed:\n  {}",
            failures.len(),
            failures.join("\n  ")
        )))
    }
}
