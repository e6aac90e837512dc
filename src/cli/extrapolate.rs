//! `jkrbem simulate --extrapolate`: one scene on several grids, its adhesive force (and c̄, d̄
//! at the minimum) extrapolated to Δx → 0.

use super::outputs::{write_error, Outputs};
use super::simulate::{check_precision, open_backend, pulloff_to_file, Args, GPU_CHECK_EVERY};
use super::{count_in, failed, input, CliError};
use jkrbem::analysis::extrapolate::{extrapolate_first_order, Extrapolated};
use jkrbem::backend::cpu::GridSetup;
use jkrbem::backend::select::AnyBackend;
use jkrbem::model::{Model, ModelOptions};
use jkrbem::output::summary::Summary;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// The extrapolation report (also written as JSON with --summary).
#[derive(Debug, Serialize)]
struct Report {
    ratio: f64,
    grids: Vec<usize>,
    dx_bar: Vec<f64>,
    f_ad_bar: Vec<f64>,
    f_ad_bar_extrapolated: Extrapolated,
    c_bar_at_min_extrapolated: Option<Extrapolated>,
    d_bar_at_min_extrapolated: Option<Extrapolated>,
    reference_model: &'static str,
    reference_f_ad_bar: Option<f64>,
    relative_error: Option<f64>,
    wall_s: f64,
}

/// Run the extrapolation.
pub fn run(args: &Args) -> Result<(), CliError> {
    let grids = &args.extrapolate_grids;
    count_in("--extrapolate-grids", grids.len(), 2, 8)?;
    if grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(input(
            "--extrapolate-grids: give 2 to 8 increasing grids, e.g. 64,128,256",
        ));
    }
    let scene = args.scene()?;
    let mut models = Vec::new();
    for &nx in grids {
        let opts = ModelOptions {
            nx,
            ny: None,
            ..args.options()
        };
        let m = Model::build(&scene, &opts)
            .map_err(|e| input(format!("--extrapolate-grids {nx}: {e}")))?;
        models.push(m);
    }
    // The grids run one after another: the largest must fit.
    let refs: Vec<&Model> = models.iter().collect();
    jkrbem::plan::check_memory(&refs, 1, "--extrapolate-grids").map_err(input)?;
    let stem = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("jkrbem-out/extrapolate-r{}.csv", scene.ratio())));
    let name = stem
        .file_stem()
        .map_or("states".into(), |s| s.to_string_lossy().into_owned());
    let outs: Vec<PathBuf> = models
        .iter()
        .map(|m| stem.with_file_name(format!("{name}-n{}.csv", m.nx)))
        .collect();
    let mut targets: Vec<(PathBuf, String)> = outs
        .iter()
        .map(|p| (p.clone(), "--out".to_string()))
        .collect();
    if let Some(p) = &args.summary {
        targets.push((p.clone(), "--summary".to_string()));
    }
    let _claimed = Outputs::claim(&targets)?;
    let start = Instant::now();
    let mut summaries: Vec<Summary> = Vec::new();
    for (mut model, out) in models.into_iter().zip(outs) {
        let opened = open_backend(args, &GridSetup::for_model(&model))?;
        check_precision(&opened.backend, &model)?;
        eprintln!(
            "jkrbem: R1/R2 = {}, grid {}×{}{}, backend {}",
            scene.ratio(),
            model.nx,
            model.ny,
            super::simulate::angle_note(&model),
            opened.note
        );
        let mut any = opened.backend;
        if matches!(any, AnyBackend::Gpu(_)) {
            model.cg.check_every = args.cg_check_every.unwrap_or(GPU_CHECK_EVERY);
        }
        let (summary, outcome, path) = jkrbem::with_backend!(
            &mut any,
            backend => pulloff_to_file(backend, &model, &out, "--out", None)
        )?;
        if let Some(e) = outcome.error {
            return Err(failed(format!(
                "the {}×{} run stopped early: {e} (states so far in {})",
                model.nx,
                model.ny,
                path.display()
            )));
        }
        if !summary.min_reached {
            return Err(failed(format!(
                "the {}×{} run did not reach the force minimum (lowest F̄ {}), so there is no \
                 adhesive force to extrapolate; lower --final-d or leave it out",
                model.nx,
                model.ny,
                summary
                    .lowest_f_bar
                    .map_or("—".into(), |f| jkrbem::text::fixed(f, 4))
            )));
        }
        println!(
            "grid {}×{}: |min F̄| = {:.5}, n_d = {:.0}, {:.1} s",
            model.nx,
            model.ny,
            summary.f_ad_bar.unwrap_or(f64::NAN),
            summary.n_d.unwrap_or(f64::NAN),
            summary.wall_s
        );
        summaries.push(summary);
    }
    let length = scene.scales().length;
    let dx: Vec<f64> = summaries
        .iter()
        .map(|s| s.dx_at_min.unwrap_or(s.dx) / length)
        .collect();
    let column = |get: fn(&Summary) -> Option<f64>| -> Option<Vec<f64>> {
        summaries.iter().map(get).collect()
    };
    let f = column(|s| s.f_ad_bar).ok_or_else(|| failed("a run recorded no force minimum"))?;
    let fx = extrapolate_first_order(&dx, &f).ok_or_else(|| failed("cannot extrapolate"))?;
    let cx = column(|s| s.c_bar_at_min).and_then(|v| extrapolate_first_order(&dx, &v));
    let dxx = column(|s| s.d_bar_at_min).and_then(|v| extrapolate_first_order(&dx, &v));
    let reference = summaries[0].reference_f_ad_bar;
    let report = Report {
        ratio: scene.ratio(),
        grids: grids.clone(),
        dx_bar: dx,
        f_ad_bar: f,
        f_ad_bar_extrapolated: fx,
        c_bar_at_min_extrapolated: cx,
        d_bar_at_min_extrapolated: dxx,
        reference_model: summaries[0].reference_model,
        reference_f_ad_bar: reference,
        relative_error: reference.map(|r| fx.value / r - 1.0),
        wall_s: start.elapsed().as_secs_f64(),
    };
    println!(
        "extrapolated to Δx → 0: |min F̄| = {:.4} ± {:.4} (finest grid {:.4}; observed order {})",
        fx.value,
        fx.error_bar,
        fx.finest,
        fx.observed_order
            .map_or("—".to_string(), |p| format!("{p:.2}"))
    );
    if let Some(r) = reference {
        println!(
            "  {} value {:.4}: extrapolated error {:+.2} %, finest grid {:+.2} %",
            report.reference_model,
            r,
            100.0 * (fx.value / r - 1.0),
            100.0 * (fx.finest / r - 1.0)
        );
    }
    if let (Some(c), Some(d)) = (cx, dxx) {
        println!(
            "  at the minimum: c̄ = {:.4} ± {:.4}, d̄ = {:.4} ± {:.4}",
            c.value, c.error_bar, d.value, d.error_bar
        );
    }
    println!("{:.1} s in all", report.wall_s);
    if let Some(p) = &args.summary {
        let text = serde_json::to_string_pretty(&report).map_err(failed)? + "\n";
        jkrbem::output::file::write_bytes(p, text.as_bytes()).map_err(write_error("--summary"))?;
    }
    Ok(())
}
