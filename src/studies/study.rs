//! The whole study of physics §8 from one request: the sweep over R1/R2, the branch fits and
//! their laws, the crossed cylinders, every chart as SVG and an index.html that shows them.

use super::chart_data;
use super::crossed::{crossed, CrossedRequest};
use super::curves::{row_curves, run_of};
use crate::analysis::capture::ContourRow;
use crate::analysis::estimate::{self, AdhesiveResult};
use crate::analysis::study_fits::{
    branch_fits, coefficient_laws, limit_fits, BranchFits, CoefficientLaw, RatioRun,
};
use crate::model::{Model, ModelOptions};
use crate::output::figure::{FigureFormat, FigureFormats, WriteFigure};
use crate::output::names::sweep_states as states_path;
use crate::output::study_charts::{
    axis_ratio_chart, branch_chart, coefficients_chart, contour_chart, BranchLaw,
};
use crate::output::study_index::{self, Figure, StudyPage};
use crate::output::summary::Summary;
use crate::output::sweep_charts::{force_vs_ratio_chart, pulloff_curves_chart};
use crate::output::sweep_csv::{self, SweepRow};
use crate::params::{ACCURACY, OUT, QUICK};
use crate::scene::Scene;
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::pulloffs::{jg_of, run_files, run_jobs, Job, JobResult};
use crate::session::Watch;
use crate::session::{failed, input, RunError};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// The ratios of the study and the grid Nx of each: quick (one grid per ratio, minutes on 2
/// CPU cores), and the finest of the full study's three (halving, so that every adhesive
/// force and every branch law is extrapolated to Δx → 0 with an uncertainty; under 45
/// minutes on 2 CPU cores). Slender contacts need more elements along x for the same count
/// across the minor axis.
const RATIOS: [f64; 6] = [1.0, 2.0, 5.0, 10.0, 25.0, 50.0];
const QUICK_GRIDS: [usize; 6] = [64, 64, 128, 128, 256, 256];
const FULL_GRIDS: [usize; 6] = [256, 256, 512, 512, 1024, 1024];

/// Grids per ratio in the full study, each half the next.
const FULL_LEVELS: usize = 3;

/// The grids Nx of one ratio whose finest is `finest`: one (quick) or [`FULL_LEVELS`].
fn ladder(finest: usize, quick: bool) -> Vec<usize> {
    let levels = if quick { 1 } else { FULL_LEVELS };
    (0..levels).rev().map(|k| finest >> k).collect()
}

/// A request for the whole study.
#[derive(Debug, Clone)]
pub struct StudyRequest {
    /// Output folder: sweep/, crossed/, the charts and index.html.
    pub out: PathBuf,
    /// One coarse grid per ratio (Nx 64 … 256, a minute on 2 CPU cores) instead of the full
    /// study's three (up to Nx 1024), extrapolated to Δx → 0.
    pub quick: bool,
    /// The backend.
    pub backend: BackendRequest,
    /// Pull-offs at the same time.
    pub jobs: usize,
    /// The formats of the charts besides SVG, which the index shows and is always written;
    /// each chart's data goes to `<stem>.plot.csv`.
    pub figures: FigureFormats,
}

/// What the study produced.
pub struct StudyDone {
    /// index.html.
    pub index: PathBuf,
    /// Charts written.
    pub charts: usize,
    /// Wall time of the whole study (s).
    pub wall_s: f64,
    /// The parts that failed, one line each (the report shows the rest).
    pub failures: Vec<String>,
}

/// The files `reproduce` writes in its --out folder itself (beside sweep/ and crossed/),
/// besides its charts ([`CHARTS`]).
const FILES: [&str; 3] = ["fits.csv", "coefficient_laws.csv", "index.html"];

/// The charts `reproduce` writes in its --out folder, by their SVG names (each also in the
/// other formats asked for, with its `.plot.csv`: [`FigureFormats::files`]).
const CHARTS: [&str; 14] = [
    "accuracy_cost.svg",
    "accuracy_cost_iterations.svg",
    "pulloff_curves.svg",
    "pulloff_shapes_r5.svg",
    "axis_ratio.svg",
    "d_of_c.svg",
    "f_of_c.svg",
    "f_of_d.svg",
    "coefficients.svg",
    "force_vs_ratio.svg",
    "contours_r1.svg",
    "contours_r5.svg",
    "contours_r25.svg",
    "crossed.svg",
];

/// The formats of the study's charts: those asked for, and SVG, which index.html shows.
fn chart_formats(args: &StudyRequest) -> FigureFormats {
    args.figures.with(FigureFormat::Svg)
}

/// Run the study: the sweep, the fits, the crossed cylinders, the charts and the index.
/// `watch` receives progress notes.
pub fn study(args: &StudyRequest, watch: &dyn Watch) -> Result<StudyDone, RunError> {
    let start = Instant::now();
    args.backend.check()?;
    let sweep_dir = args.out.join("sweep");
    let work = study_jobs(args, &sweep_dir)?;
    check_study_memory(&work, args)?;
    // The files of this command (crossed/ claims its own when it runs).
    let mut targets: Vec<PathBuf> = work.iter().flat_map(|j| run_files(&j.out)).collect();
    targets.push(sweep_csv::sweep_csv_path(&sweep_dir));
    targets.extend(FILES.iter().map(|file| args.out.join(file)));
    targets.extend(
        CHARTS
            .iter()
            .flat_map(|chart| chart_formats(args).files(&args.out.join(chart))),
    );
    let _claimed = Outputs::claim(&named(OUT, &targets))?;
    announce(args, watch);
    let results = run_study_jobs(work, args, watch);
    let mut failures: Vec<String> = results.iter().filter_map(|r| r.error.clone()).collect();
    let mut warnings = study_warnings(&results, args.quick);
    let rows = write_sweep_rows(&sweep_dir, &results)?;
    let ratio_runs = ratio_runs(&results);
    let fits = fit_branches(&ratio_runs, &mut warnings);
    // The charts draw each ratio's finest run beside its laws.
    let runs: Vec<RatioRun> = ratio_runs
        .into_iter()
        .filter_map(|(_, mut r)| r.pop())
        .collect();
    // Ratios whose answer rests on a grid too coarse for its estimate: drawn apart, not fitted.
    let coarse: Vec<f64> = rows
        .iter()
        .filter(|r| crate::output::sweep_charts::too_coarse(r))
        .map(|r| r.ratio)
        .collect();
    let laws = coefficient_laws(&fits, &coarse);
    write_fit_tables(&args.out, &fits, &laws, &coarse)?;
    let what = caption_tail(args, &rows);
    let backend = rows.first().map_or("?".to_string(), |r| r.backend.clone());
    let mut figures = Figures::new(&args.out, chart_formats(args));
    let study = StudyData {
        results: &results,
        rows: &rows,
        runs: &runs,
        fits: &fits,
        laws: &laws,
        coarse: &coarse,
    };
    draw_study_charts(&mut figures, &study, &what)?;
    draw_marked_states(&mut figures, &results, &rows, &backend)?;
    draw_accuracy_cost(&mut figures, &results, &backend, args.quick)?;
    draw_contours(&mut figures, &results, &rows, &backend)?;
    crossed_step(
        args,
        &backend,
        &mut figures,
        &mut failures,
        &mut warnings,
        watch,
    )?;
    for w in &warnings {
        watch.note(&format!("warning: {w}"));
    }
    write_index(
        &args.out,
        &StudyPage {
            figures: &figures.figures,
            rows: &rows,
            fits: &fits,
            warnings: &warnings,
            wall_s: start.elapsed().as_secs_f64(),
            quick: args.quick,
        },
    )?;
    Ok(StudyDone {
        index: args.out.join("index.html"),
        charts: figures.figures.len(),
        wall_s: start.elapsed().as_secs_f64(),
        failures,
    })
}

/// The study's grids: [`QUICK_GRIDS`] or [`FULL_GRIDS`].
fn study_grids(args: &StudyRequest) -> [usize; 6] {
    if args.quick {
        QUICK_GRIDS
    } else {
        FULL_GRIDS
    }
}

/// One pull-off per ratio and grid of its ladder, its states under `sweep_dir`.
fn study_jobs(args: &StudyRequest, sweep_dir: &Path) -> Result<Vec<Job>, RunError> {
    let mut work = Vec::new();
    for (&ratio, &finest) in RATIOS.iter().zip(&study_grids(args)) {
        let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(input)?;
        for grid in ladder(finest, args.quick) {
            let model = Model::build(
                &scene,
                &ModelOptions {
                    nx: grid,
                    ..ModelOptions::default()
                },
            )
            .map_err(input)?;
            let out = states_path(sweep_dir, ratio, grid);
            work.push(Job {
                model,
                out,
                target: None,
            });
        }
    }
    Ok(work)
}

/// Refuse a study whose `--jobs` largest pull-offs do not fit in memory.
fn check_study_memory(work: &[Job], args: &StudyRequest) -> Result<(), RunError> {
    let refs: Vec<&Model> = work.iter().map(|j| &j.model).collect();
    crate::plan::check_memory(&refs, args.jobs, QUICK).map_err(|e| {
        let why = match e {
            crate::model::ModelError::Invalid { expected, .. } => expected,
            other => other.to_string(),
        };
        input(format!(
            "the study's grids do not fit in this machine's memory{}: {why}",
            if args.quick {
                String::new()
            } else {
                format!(
                    " (use {QUICK} for one grid of 64 to 256 per ratio, or a machine with more \
                     memory)"
                )
            }
        ))
    })
}

/// Say which ratios and grids the study runs.
fn announce(args: &StudyRequest, watch: &dyn Watch) {
    watch.note(&format!(
        "reproduce: {} ratios on grids {}{}",
        RATIOS.len(),
        study_grids(args)
            .iter()
            .map(|&g| format!("{:?}", ladder(g, args.quick)))
            .collect::<Vec<_>>()
            .join(", "),
        if args.quick { " (quick)" } else { "" }
    ));
}

/// Run every pull-off (the largest first, so that parallel jobs end together); the results
/// sorted by ratio, then grid.
fn run_study_jobs(mut work: Vec<Job>, args: &StudyRequest, watch: &dyn Watch) -> Vec<JobResult> {
    work.sort_by_key(|j| std::cmp::Reverse(j.model.nx * j.model.ny));
    let mut results = run_jobs(work, args.jobs, args.backend, watch);
    results.sort_by(|a, b| a.ratio.total_cmp(&b.ratio).then(a.grid.0.cmp(&b.grid.0)));
    results
}

/// One row per ratio (its grids' estimate), written as the study's sweep.csv.
fn write_sweep_rows(sweep_dir: &Path, results: &[JobResult]) -> Result<Vec<SweepRow>, RunError> {
    let mut rows: Vec<SweepRow> = RATIOS
        .iter()
        .map(|&ratio| {
            let group: Vec<&JobResult> = results.iter().filter(|r| r.ratio == ratio).collect();
            ratio_row(ratio, &group)
        })
        .collect();
    rows.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    sweep_csv::write_rows(&sweep_csv::sweep_csv_path(sweep_dir), &rows)
        .map_err(write_error(OUT))?;
    Ok(rows)
}

/// Every grid's complete run of every ratio, coarse to fine, with the states it recorded.
fn ratio_runs(results: &[JobResult]) -> Vec<(f64, Vec<RatioRun>)> {
    RATIOS
        .iter()
        .map(|&ratio| {
            let runs = results
                .iter()
                .filter(|r| r.ratio == ratio && r.complete)
                .map(|r| RatioRun {
                    ratio,
                    grid: r.grid,
                    states: r.states.clone(),
                })
                .collect();
            (ratio, runs)
        })
        .collect()
}

/// The runs' warnings as the study's answers carry them: a ratio's coarser grids are rungs
/// of its ladder, coarse by design, so only its finest grid's too-coarse warning is kept, with
/// advice this command can follow.
fn study_warnings(results: &[JobResult], quick: bool) -> Vec<String> {
    let advice = if quick {
        format!("; the full study (reproduce without {QUICK}) runs finer grids")
    } else {
        format!("; the study's grids are fixed: simulate this ratio with {ACCURACY} for its answer")
    };
    results
        .iter()
        .flat_map(|r| {
            let finest = !results
                .iter()
                .any(|o| o.ratio == r.ratio && o.grid.0 > r.grid.0);
            let advice = &advice;
            r.warnings().into_iter().filter_map(move |w| {
                if !w.contains(crate::analysis::convergence::COARSE_WARNING) {
                    Some(w)
                } else if finest {
                    Some(with_advice(&w, advice))
                } else {
                    None
                }
            })
        })
        .collect()
}

/// A too-coarse warning with its `simulate` advice (from
/// [`coarse_grid_advice`](crate::analysis::convergence::coarse_grid_advice) on) replaced by
/// `advice` (what the study's user can change); any other warning as it is.
fn with_advice(warning: &str, advice: &str) -> String {
    let simulate_advice = crate::analysis::convergence::coarse_grid_advice();
    match warning.split_once(simulate_advice.as_str()) {
        Some((head, _)) => format!("{head}{advice}"),
        None => warning.to_string(),
    }
}

/// The branch laws of each ratio: at Δx → 0 from the full study's grids, else the one
/// grid's (with a warning where grids could not be extrapolated together).
fn fit_branches(
    ratio_runs: &[(f64, Vec<RatioRun>)],
    warnings: &mut Vec<String>,
) -> Vec<BranchFits> {
    let mut fits: Vec<BranchFits> = Vec::new();
    for (ratio, runs) in ratio_runs {
        let Some(finest) = runs.last() else { continue };
        if runs.len() >= 2 {
            match limit_fits(*ratio, runs) {
                Some((f, _)) => fits.push(f),
                None => {
                    warnings.push(format!(
                        "R1/R2 = {ratio}: the branches of grids {:?} could not be extrapolated \
                         together; the finest grid's fits are shown, without uncertainties",
                        runs.iter().map(|r| r.grid.0).collect::<Vec<_>>()
                    ));
                    fits.push(branch_fits(finest));
                }
            }
        } else {
            fits.push(branch_fits(finest));
        }
    }
    fits
}

/// What every caption ends with: the grids, the backend and the pull-offs' time.
fn caption_tail(args: &StudyRequest, rows: &[SweepRow]) -> String {
    let backend = rows.first().map_or("?".to_string(), |r| r.backend.clone());
    let sweep_wall: f64 = rows.iter().map(|r| r.wall_s).sum();
    let grid_text = rows
        .iter()
        .map(|r| format!("{}: {}×{}", r.ratio, r.grid, r.ny))
        .collect::<Vec<_>>()
        .join(", ");
    format!(
        "R1/R2 = {grid_text} (Nx×Ny{}); backend {backend}; pull-offs {sweep_wall:.0} s in all",
        if args.quick {
            ""
        } else {
            ", the finest of three grids; laws and forces extrapolated to Δx → 0"
        }
    )
}

/// The study's figures: each chart written to its file in the output folder, with its
/// caption for the index.
struct Figures<'a> {
    out: &'a Path,
    formats: FigureFormats,
    figures: Vec<Figure>,
}

impl<'a> Figures<'a> {
    fn new(out: &'a Path, formats: FigureFormats) -> Self {
        Figures {
            out,
            formats,
            figures: Vec::new(),
        }
    }

    /// Write `chart` as `file` (its SVG name, and in the other formats) and list it with
    /// `caption`.
    fn add(
        &mut self,
        file: &str,
        chart: impl WriteFigure,
        caption: String,
    ) -> Result<(), RunError> {
        chart
            .write_figure(&self.out.join(file), self.formats)
            .map_err(write_error(OUT))?;
        self.figures.push(Figure {
            file: file.into(),
            caption,
        });
        Ok(())
    }
}

/// The finest runs and the fits of the ratios in `want`.
fn pick(runs: &[RatioRun], fits: &[BranchFits], want: &[f64]) -> (Vec<RatioRun>, Vec<BranchFits>) {
    let runs: Vec<RatioRun> = runs
        .iter()
        .filter(|r| want.contains(&r.ratio))
        .map(|r| RatioRun {
            ratio: r.ratio,
            grid: r.grid,
            states: r.states.clone(),
        })
        .collect();
    let fits = fits
        .iter()
        .filter(|f| want.contains(&f.ratio))
        .cloned()
        .collect();
    (runs, fits)
}

/// What the study's charts draw from: the runs, their rows, the finest run and the branch
/// fits of each ratio, the coefficient laws, and the ratios too coarse for their estimate.
struct StudyData<'a> {
    results: &'a [JobResult],
    rows: &'a [SweepRow],
    runs: &'a [RatioRun],
    fits: &'a [BranchFits],
    laws: &'a [CoefficientLaw],
    coarse: &'a [f64],
}

/// §8.1, §8.2, §8.4, §8.5 and §8.6: the pull-off curves, the axis ratio, the branch laws,
/// their coefficients and the adhesive force against R1/R2.
fn draw_study_charts(figures: &mut Figures, study: &StudyData, what: &str) -> Result<(), RunError> {
    let StudyData {
        results,
        rows,
        runs,
        fits,
        laws,
        coarse,
    } = *study;
    let coarse_text = coarse_caption(coarse);
    let curves = chart_data::sweep_curves(rows, row_curves(results, rows));
    let (curves_chart, _) = pulloff_curves_chart(rows, &curves);
    figures.add(
        "pulloff_curves.svg",
        curves_chart,
        format!("§8.1 Pull-off curves F̄(d̄) beside JKR (sphere) and JG. {what}."),
    )?;
    let (r2, _) = pick(runs, fits, &[2.0, 5.0, 10.0, 25.0]);
    figures.add(
        "axis_ratio.svg",
        axis_ratio_chart(&chart_data::axis_ratio_series(&r2, coarse)),
        format!("§8.2 Contact axis ratio b/a against F̄ beside JG's g(F̄).{coarse_text} {what}."),
    )?;
    let (r3, f3) = pick(runs, fits, &[2.0, 10.0, 25.0]);
    let branches = chart_data::branch_series(&r3, &f3, coarse);
    for (law, file, name) in [
        (BranchLaw::DOfC, "d_of_c.svg", "d̄(c̄), fit d̄ = A c̄² + B c̄^½"),
        (
            BranchLaw::FOfC,
            "f_of_c.svg",
            "F̄(c̄), fit F̄ = c1 c̄³ + c2 c̄^α",
        ),
        (BranchLaw::FOfD, "f_of_d.svg", "F̄(d̄) from both fits"),
    ] {
        figures.add(
            file,
            branch_chart(&branches, law),
            format!(
                "§8.4 {name}, on the adhesive branch (onset states), beside JG.{coarse_text} \
                 {what}."
            ),
        )?;
    }
    figures.add(
        "coefficients.svg",
        coefficients_chart(&chart_data::coefficient_series(laws)),
        format!(
            "§8.5 The branch-law coefficients against R1/R2 with fitted laws: {}.{coarse_text} \
             {what}.",
            laws_text(laws)
        ),
    )?;
    figures.add(
        "force_vs_ratio.svg",
        force_vs_ratio_chart(rows, &curves),
        format!(
            "§8.6 Adhesive force |min F̄| against R1/R2 beside JG's pull-off force, with the \
             fitted law.{coarse_text} {what}."
        ),
    )
}

/// What a caption says of the ratios too coarse for their estimate (empty where none is).
fn coarse_caption(coarse: &[f64]) -> String {
    if coarse.is_empty() {
        return String::new();
    }
    format!(
        " Hollow markers: R1/R2 = {}, whose grids are too coarse for their estimate (fewer \
         than {} elements across the contact's minor axis); they are not fitted.",
        coarse
            .iter()
            .map(|r| r.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        crate::analysis::convergence::COARSE_N_D
    )
}

/// The fitted coefficient laws in words, with their uncertainties.
fn laws_text(laws: &[CoefficientLaw]) -> String {
    laws.iter()
        .map(|c| match (&c.law, &c.uncertainty) {
            (Some(l), Some(u)) => format!(
                "{} = {} (± {:.3}, {:.3}, {:.3} on k1, k2, k3)",
                c.name,
                crate::text::power_law(l.k1, l.k2, l.k3),
                u[0],
                u[1],
                u[2]
            ),
            (Some(l), None) => format!("{} = {}", c.name, crate::text::power_law(l.k1, l.k2, l.k3)),
            (None, _) => format!(
                "{}: no law (fewer than {} resolved ratios)",
                c.name,
                crate::analysis::study_fits::MIN_LAW_POINTS
            ),
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The study's accuracy–cost charts: the sphere's answers as the program states them from
/// each of its grids and from its grids extrapolated together, their error against JKR's
/// exact 1/2 (stated uncertainties as bars) against wall time and against CG iterations.
fn draw_accuracy_cost(
    figures: &mut Figures,
    results: &[JobResult],
    backend: &str,
    quick: bool,
) -> Result<(), RunError> {
    use super::accuracy::{chart_rows, cost_chart, Cost, RunSeries, Variant};
    let mut runs: Vec<_> = results
        .iter()
        .filter(|r| r.ratio == 1.0)
        .filter_map(|r| r.summary.as_ref()?.runs.first().cloned())
        .collect();
    if runs.is_empty() {
        return Ok(());
    }
    runs.sort_by_key(|r| r.nx);
    let grids: Vec<String> = runs.iter().map(|r| r.nx.to_string()).collect();
    // The backend as the runs name it ("cpu"; the legend adds their precision).
    let series = [RunSeries {
        backend: runs[0].backend.clone(),
        variant: Variant::Plain,
        runs,
    }];
    let exact = crate::analysis::estimate::Estimate {
        value: 0.5,
        uncertainty: 0.0,
    };
    let rows = chart_rows(&series, Some(exact));
    for (cost, file, what) in [
        (Cost::Wall, "accuracy_cost.svg", "wall time"),
        (
            Cost::Iterations,
            "accuracy_cost_iterations.svg",
            "CG iterations (the same on every device)",
        ),
    ] {
        let chart = cost_chart(
            "The sphere: error of |min F̄| against cost (exact JKR value 1/2)",
            &series,
            &rows,
            cost,
        );
        figures.add(
            file,
            chart,
            format!(
                "Accuracy against cost: the sphere's adhesive force as the program states it \
                 from each grid (Nx = {}; the grid's force corrected by the convergence law){}, \
                 its error against JKR's exact 1/2 against {what}, with the stated uncertainty \
                 as a bar (a bar down to the axis' bottom: the interval holds 1/2). \
                 `jkrbem accuracy` draws the same for any ratio, backend and way of running \
                 (re-gridding, adhesive force only). Backend {backend}.",
                grids.join(", "),
                if quick {
                    ""
                } else {
                    ", and from the grids extrapolated together (dashed)"
                }
            ),
        )?;
    }
    Ok(())
}

/// The ratio whose pull-off curve is drawn beside the contact outlines of its marked states.
const MARKED_RATIO: f64 = 5.0;

/// The states marked on that curve.
const MARKED_STATES: usize = 4;

/// §8.1, the study's Fig. 2b: the pull-off curve of R1/R2 = 5 with four marked states (three
/// captured on the way down and the force minimum) beside their contact outlines.
fn draw_marked_states(
    figures: &mut Figures,
    results: &[JobResult],
    rows: &[SweepRow],
    backend: &str,
) -> Result<(), RunError> {
    let Some(row) = rows.iter().find(|r| r.ratio == MARKED_RATIO) else {
        return Ok(());
    };
    let Some(run) = run_of(results, row) else {
        return Ok(());
    };
    let marked = chart_data::marked_states(&run.contours, MARKED_STATES);
    let curve = super::curves::state_points(&run.states);
    let d_max = curve.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
    let reference = chart_data::reference_curve(MARKED_RATIO, d_max);
    let figure = crate::output::study_charts::marked_states_figure(
        MARKED_RATIO,
        run.grid,
        curve,
        (&reference.name, reference.points),
        &marked,
    );
    figures.add(
        &format!("pulloff_shapes_r{MARKED_RATIO}.svg"),
        figure,
        format!(
            "§8.1 (the study's Fig. 2b) Pull-off curve F̄(d̄) of R1/R2 = {MARKED_RATIO} ({}×{}) \
             beside {}, with {} states marked; right: the contact outline of each marked state, \
             in its colour, on equal scales (x along the major axis; lengths in c_r). Backend \
             {backend}.",
            run.grid.0,
            run.grid.1,
            reference.name,
            marked.len()
        ),
    )
}

/// §8.1 snapshots and §8.3 (the study's Fig. 3b): quarter contours at marked states against
/// the ellipses with the same half-axes, for R1/R2 = 1, 5 and 25.
fn draw_contours(
    figures: &mut Figures,
    results: &[JobResult],
    rows: &[SweepRow],
    backend: &str,
) -> Result<(), RunError> {
    for ratio in [1.0, 5.0, 25.0] {
        let Some(row) = rows.iter().find(|r| r.ratio == ratio) else {
            continue;
        };
        let contours: &[ContourRow] = run_of(results, row).map_or(&[], |r| &r.contours);
        figures.add(
            &format!("contours_r{ratio}.svg"),
            contour_chart(ratio, contours),
            format!(
                "§8.1/§8.3 (the study's Fig. 3b) Quarter contours of the contact during \
                 pull-off, R1/R2 = {ratio} \
                 ({}×{}), beside the ellipses with the same half-axes. Departure r/r_e − 1: \
                 {}. Backend {backend}.",
                row.grid,
                row.ny,
                departures_text(contours)
            ),
        )?;
    }
    Ok(())
}

/// Each snapshot's departure from its ellipse in words.
fn departures_text(contours: &[ContourRow]) -> String {
    let mut labels: Vec<String> = Vec::new();
    for c in contours {
        if labels.last() != Some(&c.label) {
            labels.push(c.label.clone());
        }
    }
    labels
        .iter()
        .filter_map(|l| contours.iter().find(|c| &c.label == l))
        .map(|c| {
            format!(
                "{} (c̄ = {:.2}): rms {:.1} %, max {:.1} %",
                c.label,
                c.c_bar,
                100.0 * c.departure_rms,
                100.0 * c.departure_max
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// §8.7: crossed cylinders, at the grids of the nearest ratios (quick: one coarse grid; full:
/// each angle's grid planned for a 2 % adhesive force), its chart copied beside the others.
fn crossed_step(
    args: &StudyRequest,
    backend: &str,
    figures: &mut Figures,
    failures: &mut Vec<String>,
    warnings: &mut Vec<String>,
    watch: &dyn Watch,
) -> Result<(), RunError> {
    let crossed_grid = if args.quick {
        crate::session::pulloffs::GridChoice::Fixed(128)
    } else {
        crate::session::pulloffs::GridChoice::Accuracy(0.02)
    };
    let crossed_dir = args.out.join("crossed");
    let crossed_req = CrossedRequest {
        radius: 0.01,
        angles: vec![90.0, 70.0, 50.0, 30.0, 16.1],
        young: 1.0e6,
        poisson: 0.5,
        work_of_adhesion: 0.05,
        grid: crossed_grid,
        steps: 200,
        margin: 0.08,
        backend: args.backend,
        jobs: args.jobs,
        out: crossed_dir.clone(),
        figures: figures.formats,
    };
    let t = Instant::now();
    match crossed(&crossed_req, &|p| p, watch) {
        Ok(done) => {
            failures.extend(
                done.failures
                    .iter()
                    .map(|f| format!("crossed cylinders: {f}")),
            );
            let advice = format!(
                "; the study's crossed cylinders run fixed grids: simulate that ratio with \
                 {ACCURACY} for its answer"
            );
            warnings.extend(
                done.warnings
                    .iter()
                    .map(|w| format!("crossed cylinders: {}", with_advice(w, &advice))),
            );
        }
        Err(e) => failures.push(format!("crossed cylinders: {e}")),
    }
    let crossed_svg = crossed_dir.join("crossed.svg");
    if crossed_svg.exists() {
        // A copy of each of its files (already written in the command line's words).
        let copies = figures
            .formats
            .files(&crossed_svg)
            .into_iter()
            .zip(figures.formats.files(&args.out.join("crossed.svg")));
        for (from, to) in copies {
            let bytes = std::fs::read(&from)
                .map_err(|e| failed(format!("cannot read {}: {e}", from.display())))?;
            crate::output::file::write_bytes(&to, &bytes).map_err(write_error(OUT))?;
        }
        figures.figures.push(Figure {
            file: "crossed.svg".into(),
            caption: format!(
                "§8.7 Crossed cylinders (R = 10 mm, E = 1 MPa, ν = 0.5, Δγ = 0.05 J/m²): adhesive \
                 force in N against crossing angle beside JG; {}, backend {backend}, \
                 {:.0} s.",
                crossed_grid.describe(),
                t.elapsed().as_secs_f64()
            ),
        });
    }
    Ok(())
}

/// One ratio's row of the study's sweep: one grid's, or the adhesive force extrapolated to
/// Δx → 0 from the runs of every grid (the finest run's row, marked failed, if a run failed).
fn ratio_row(ratio: f64, group: &[&JobResult]) -> SweepRow {
    let Some(finest) = group.last() else {
        return SweepRow::failed(ratio, (0, 0), 0.0, "no run".into(), jg_of(ratio));
    };
    if group.len() == 1 {
        return finest.row();
    }
    let reports: Option<Vec<_>> = group
        .iter()
        .map(|r| {
            let s = r.summary.as_ref()?;
            s.runs.first().filter(|run| run.min_reached).cloned()
        })
        .collect();
    match reports {
        Some(reports) => {
            let est = estimate::from_runs(&reports).ok();
            let result = AdhesiveResult::assemble(ratio, est, None, reports);
            SweepRow::from_summary(&Summary::new(&result))
        }
        None => finest.row(),
    }
}

/// One ratio's branch fits with their quality and, where extrapolated to Δx → 0, their
/// uncertainties (half-widths).
#[derive(serde::Serialize)]
struct FitRow {
    ratio: f64,
    a: Option<f64>,
    b: Option<f64>,
    d_r_squared: Option<f64>,
    d_rms: Option<f64>,
    c1: Option<f64>,
    c2: Option<f64>,
    alpha: Option<f64>,
    alpha_at_bound: Option<bool>,
    f_r_squared: Option<f64>,
    f_rms: Option<f64>,
    points: Option<usize>,
    a_uncertainty: Option<f64>,
    b_uncertainty: Option<f64>,
    c1_uncertainty: Option<f64>,
    c2_uncertainty: Option<f64>,
    alpha_uncertainty: Option<f64>,
    grids: String,
    /// Whether the ratio's grids are too coarse for its estimate (its fits are then left out
    /// of the coefficient laws).
    too_coarse: bool,
}

/// One coefficient's law k1·(R1/R2)^k2 + k3 with its quality and uncertainties.
#[derive(serde::Serialize)]
struct LawRow {
    coefficient: &'static str,
    k1: Option<f64>,
    k2: Option<f64>,
    k3: Option<f64>,
    r_squared: Option<f64>,
    rms: Option<f64>,
    /// The ratios the law was fitted to (those not too coarse for their estimate).
    ratios: usize,
    k1_uncertainty: Option<f64>,
    k2_uncertainty: Option<f64>,
    k3_uncertainty: Option<f64>,
}

/// fits.csv (per ratio: A, B, c1, c2, α with R², RMS residuals and uncertainties) and
/// coefficient_laws.csv (each coefficient's law across ratios).
fn write_fit_tables(
    dir: &Path,
    fits: &[BranchFits],
    laws: &[CoefficientLaw],
    coarse: &[f64],
) -> Result<(), RunError> {
    write_csv(
        &dir.join("fits.csv"),
        fits.iter().map(|f| {
            let d = f.d_of_c.as_ref();
            let p = f.f_of_c.as_ref();
            let u = |i: usize| f.uncertainty.map(|u| u[i]);
            FitRow {
                ratio: f.ratio,
                a: d.map(|d| d.a),
                b: d.map(|d| d.b),
                d_r_squared: d.map(|d| d.quality.r_squared),
                d_rms: d.map(|d| d.quality.rms_residual),
                c1: p.map(|p| p.c1),
                c2: p.map(|p| p.c2),
                alpha: p.map(|p| p.alpha),
                alpha_at_bound: p.map(|p| p.alpha_at_bound),
                f_r_squared: p.map(|p| p.quality.r_squared),
                f_rms: p.map(|p| p.quality.rms_residual),
                points: d.map(|d| d.quality.points),
                a_uncertainty: u(0),
                b_uncertainty: u(1),
                c1_uncertainty: u(2),
                c2_uncertainty: u(3),
                alpha_uncertainty: u(4),
                grids: f
                    .grids
                    .iter()
                    .map(|g| g.to_string())
                    .collect::<Vec<_>>()
                    .join(";"),
                too_coarse: coarse.contains(&f.ratio),
            }
        }),
    )?;
    write_csv(
        &dir.join("coefficient_laws.csv"),
        laws.iter().map(|c| {
            let law = c.law.as_ref();
            let u = |i: usize| c.uncertainty.map(|u| u[i]);
            LawRow {
                coefficient: c.name,
                k1: law.map(|l| l.k1),
                k2: law.map(|l| l.k2),
                k3: law.map(|l| l.k3),
                r_squared: law.map(|l| l.quality.r_squared),
                rms: law.map(|l| l.quality.rms_residual),
                ratios: c.points.len() - c.coarse.len(),
                k1_uncertainty: u(0),
                k2_uncertainty: u(1),
                k3_uncertainty: u(2),
            }
        }),
    )
}

/// Write serialisable rows as a CSV file, atomically.
fn write_csv<T: serde::Serialize>(
    path: &Path,
    rows: impl Iterator<Item = T>,
) -> Result<(), RunError> {
    crate::output::file::write_csv(path, None, rows).map_err(write_error(OUT))
}

/// index.html, as [`study_index::index_html`] writes it.
fn write_index(dir: &Path, page: &StudyPage) -> Result<(), RunError> {
    let html = study_index::index_html(page);
    crate::output::file::write_text(&dir.join("index.html"), &html).map_err(write_error(OUT))
}
