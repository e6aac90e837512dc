//! `jkrbem accuracy`: one scene on several grids and backends; the error of the adhesive force
//! against the wall time it cost, as CSV and a log–log chart.

use super::simulate::BackendChoice;
use super::sweep::run_all;
use super::{failed, input, CliError};
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
    /// Axis ratio R1/R2 (≥ 1; 1 is the sphere, whose exact answer is JKR's 1/2).
    #[arg(long, default_value_t = 1.0)]
    pub ratio: f64,
    /// Grids Nx, coarse to fine (powers of two ≥ 16).
    #[arg(long, value_delimiter = ',', default_value = "32,64,128")]
    pub grids: Vec<usize>,
    /// Backends, comma-separated: `cpu` (f64) and/or `gpu` (f32). The precision follows the
    /// backend.
    #[arg(long, value_delimiter = ',', default_value = "cpu")]
    pub backends: Vec<String>,
    /// Ways of running each grid, comma-separated: `plain` (the whole curve on a fixed grid),
    /// `measure` (--measure adhesive-force: stop once the minimum is confirmed) and `regrid`
    /// (--measure adhesive-force --regrid: also refine Δx as the contact shrinks).
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
    if args.grids.len() < 2 || args.grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(input(
            "--grids: give at least two increasing grids, e.g. 32,64,128",
        ));
    }
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
    let mut per_backend: Vec<(String, Variant, Vec<Summary>)> = Vec::new();
    let mut failures = Vec::new();
    for (name, choice) in args.backends.iter().zip(&choices) {
        for &variant in &variants {
            let mut work = Vec::new();
            for &nx in &args.grids {
                let model = Model::build(&scene, &variant.options(nx))
                    .map_err(|e| input(format!("--grids {nx}: {e}")))?;
                let file = format!("{}-{}-n{nx}.csv", name.trim(), variant.name());
                work.push((model, args.out.join(file)));
            }
            let (mut summaries, f) = run_all(work, 1, *choice);
            summaries.sort_by_key(|s| s.nx);
            failures.extend(f);
            per_backend.push((name.trim().to_string(), variant, summaries));
        }
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
    chart.legend = plotters::prelude::SeriesLabelPosition::UpperRight;
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
    std::fs::create_dir_all(&args.out).map_err(failed)?;
    let csv_path = args.out.join("accuracy.csv");
    let mut w = csv::Writer::from_path(&csv_path).map_err(failed)?;
    for r in &rows {
        w.serialize(r).map_err(failed)?;
    }
    w.flush().map_err(failed)?;
    chart
        .write_svg(&args.out.join("accuracy.svg"))
        .map_err(failed)?;
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
    println!(
        "written {} and {}",
        csv_path.display(),
        args.out.join("accuracy.svg").display()
    );
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
