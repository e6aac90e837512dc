//! The reference table of converged adhesive forces: per R1/R2, a ladder of grids (each run
//! with the apex on an element corner, re-gridded, stopped after the force minimum), refined
//! until the Δx → 0 limit is known within the target from the runs themselves (the law's k only
//! a weak prior, [`crate::analysis::estimate::reference`]). The convergence law that
//! `--accuracy` and single-grid estimates use is fitted to this table.

pub mod reuse;

use crate::analysis::convergence::{self, TableLaw};
use crate::analysis::estimate;
use crate::analysis::report::RunReport;
use crate::model::{Measure, Model, ModelError, ModelOptions, Onsets, MAX_GRID};
use crate::params::{ACCURACY, FIRST_GRID, MAX_GRID as MAX_GRID_SPEC, OUT, PHASES, RATIOS, TARGET};
use crate::scene::Scene;
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::simulate::{simulate, Mode, SimulateRequest, Sink};
use crate::session::{failed, input, refuse, RunError, Watch};
use serde::{Deserialize, Serialize};
use std::path::PathBuf;

/// The ratios of the reference table.
pub const REFERENCE_RATIOS: [f64; 12] = [
    1.0, 1.5, 2.0, 3.0, 5.0, 7.0, 10.0, 15.0, 20.0, 25.0, 35.0, 50.0,
];

/// Grids of a ladder at the least (the fit's model term needs three).
pub const MIN_LEVELS: usize = 3;

pub use crate::params::limits::MIN_FIRST_GRID;

pub use crate::params::limits::MAX_REFERENCE_PHASES as MAX_PHASES;

pub use crate::params::limits::MAX_REFERENCE_TARGET as MAX_TARGET;
pub use crate::params::limits::MIN_REFERENCE_TARGET as MIN_TARGET;

/// The step between the domain margins of one grid's runs (relative to the initial contact's
/// half-axes): the first run has the margin asked for, each further one this much more. 0.05
/// moves Δx by about 5 %, which moves the contact's edge by a few elements across a resolved
/// contact: the runs sample the grid phase rather than repeat one another.
pub const PHASE_MARGIN_STEP: f64 = 0.05;

/// The domain margins of one grid's `phases` runs: `base`, then [`PHASE_MARGIN_STEP`] more
/// for each further run.
pub fn phase_margins(base: f64, phases: usize) -> Vec<f64> {
    (0..phases.max(1))
        .map(|i| base + PHASE_MARGIN_STEP * i as f64)
        .collect()
}

/// A request for reference values.
#[derive(Debug, Clone)]
pub struct ReferenceRequest {
    /// The ratios R1/R2.
    pub ratios: Vec<f64>,
    /// The relative uncertainty wanted (e.g. 0.003).
    pub target: f64,
    /// Nx of the finest grid a ladder may reach.
    pub max_grid: usize,
    /// Nx of every ladder's first grid (`None`: the grid a 5 % plan takes for the ratio).
    pub first_grid: Option<usize>,
    /// Runs per grid, at the domain margins [`phase_margins`]: each an observation of the same
    /// limit at another grid phase (1: one run per grid, the default margin).
    pub phases: usize,
    /// The backend.
    pub backend: BackendRequest,
    /// The table (CSV); each ratio's runs go beside it in `<stem>-runs/`.
    pub out: PathBuf,
    /// The command line that produced it, written into every row.
    pub command: String,
}

/// One row of the reference table (dimensionless, physics §2 normalisation).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ReferenceRow {
    /// R1/R2.
    pub ratio: f64,
    /// |min F̄| at Δx → 0.
    pub f_ad_bar: Option<f64>,
    /// Its stated half-width (absolute).
    pub f_ad_bar_uncertainty: Option<f64>,
    /// c̄ at the force minimum at Δx → 0.
    pub c_bar_at_min: Option<f64>,
    /// Its stated half-width.
    pub c_bar_at_min_uncertainty: Option<f64>,
    /// d̄ at the force minimum at Δx → 0.
    pub d_bar_at_min: Option<f64>,
    /// Its stated half-width.
    pub d_bar_at_min_uncertainty: Option<f64>,
    /// The fitted first-order coefficient k of |min F̄| ≈ F0·(1 + k/n_d).
    pub k: Option<f64>,
    /// Its stated half-width (two standard deviations).
    #[serde(default)]
    pub k_uncertainty: Option<f64>,
    /// Whether the uncertainty reached the target.
    pub target_met: bool,
    /// The grids Nx of the ladder, coarse to fine, `;`-separated.
    pub grids: String,
    /// Runs per grid (each at another domain margin, [`phase_margins`]); 1 in tables written
    /// before the column existed.
    #[serde(default = "one_run_per_grid")]
    pub runs_per_grid: usize,
    /// n_d of the finest grid's run at the default margin.
    pub n_d: Option<f64>,
    /// CG iterations over all runs.
    pub cg_iterations: usize,
    /// Wall time over all runs (s).
    pub wall_s: f64,
    /// The command that produced the table.
    pub command: String,
}

/// The runs per grid of a row written before [`ReferenceRow::runs_per_grid`] existed.
fn one_run_per_grid() -> usize {
    1
}

/// What the request produced.
pub struct ReferenceDone {
    /// One row per ratio, in the order asked.
    pub rows: Vec<ReferenceRow>,
    /// The table.
    pub path: PathBuf,
    /// The convergence law fitted to the table as written (what `--accuracy` uses once this
    /// table is the compiled-in one); `None` where too few rows have a k.
    pub law: Option<TableLaw>,
}

/// The first grid of a ratio's ladder: the one a 5 % plan takes (n_d about 20–40).
fn first_grid(scene: &Scene, base: &ModelOptions) -> Result<usize, RunError> {
    let p = crate::plan::for_accuracy_one_grid(scene, 0.05, base).map_err(|e| {
        // The plan's refusal names the accuracy, which reference does not have: only what it
        // says of the grids is kept.
        let why = match e {
            ModelError::Invalid {
                param, expected, ..
            } if param == ACCURACY => expected,
            other => other.to_string(),
        };
        input(format!(
            "R1/R2 = {}: no first grid for its ladder ({FIRST_GRID}): {why}",
            crate::text::compact(scene.ratio()),
        ))
    })?;
    Ok(p.grids[0])
}

/// The options every run of a ladder shares (the grid and margin set per run).
fn ladder_options() -> ModelOptions {
    ModelOptions {
        steps: crate::plan::PLAN_STEPS,
        onsets: Onsets::NearMinimum,
        measure: Measure::AdhesiveForce,
        regrid: true,
        ..ModelOptions::default()
    }
}

/// The scene of R1/R2 = `ratio` (R2 = E* = Δγ = 1).
fn ratio_scene(ratio: f64) -> Result<Scene, RunError> {
    Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(input)
}

/// The grids a ratio's ladder may run, checked before any work.
#[derive(Debug, Clone, PartialEq)]
pub struct LadderGrids {
    /// Nx, coarse to fine (at least [`MIN_LEVELS`]).
    pub grids: Vec<usize>,
    /// Why the ladder stops below `--max-grid`, where the memory stops it.
    pub memory_cut: Option<String>,
}

/// The grids of R1/R2 = `ratio`'s ladder, coarse to fine, checked before any work: from the
/// first grid (`--first-grid`, or the one a 5 % plan takes), doubling up to `--max-grid`,
/// each built at every phase's margin and fitting in the memory `available` (bytes; `None`:
/// unchecked). Fewer than [`MIN_LEVELS`] is refused, naming the parameter to change.
pub fn ladder_grids(
    req: &ReferenceRequest,
    ratio: f64,
    available: Option<u64>,
) -> Result<LadderGrids, RunError> {
    let scene = ratio_scene(ratio)?;
    let base = ladder_options();
    let (first, whose) = match req.first_grid {
        Some(nx) => (nx, FIRST_GRID.to_string()),
        None => (
            first_grid(&scene, &base)?,
            "the grid a 5 % plan takes".to_string(),
        ),
    };
    let margins = phase_margins(base.margin, req.phases);
    let build = |nx: usize| -> Result<Vec<Model>, ModelError> {
        margins
            .iter()
            .map(|&margin| {
                let options = ModelOptions {
                    nx,
                    margin,
                    ..base.clone()
                };
                Model::build(&scene, &options)
            })
            .collect()
    };
    // The coarsest grid that resolves the contact at every margin.
    let coarsest = || {
        let mut nx = MIN_FIRST_GRID;
        while nx < MAX_GRID && build(nx).is_err() {
            nx *= 2;
        }
        nx
    };
    let mut grids = Vec::new();
    let mut too_large = None;
    let mut nx = first;
    while nx <= req.max_grid {
        let models = match build(nx) {
            Ok(m) => m,
            Err(ModelError::TooCoarse { .. }) if nx == first => {
                let fine = coarsest();
                return Err(refuse(
                    FIRST_GRID,
                    format!(
                    "{FIRST_GRID} {nx}: too coarse for R1/R2 = {ratio} (the contact would span \
                     too few elements); give {FIRST_GRID} {fine} or more"
                ),
                ));
            }
            Err(e) => {
                return Err(refuse(
                    MAX_GRID_SPEC,
                    format!("{MAX_GRID_SPEC} {}: grid {nx}: {e}", req.max_grid),
                ))
            }
        };
        let need = models.iter().map(Model::memory_estimate).max().unwrap_or(0);
        if let Some(a) = available.filter(|&a| need > a) {
            too_large = Some((nx, need, a));
            break;
        }
        grids.push(nx);
        nx *= 2;
    }
    if grids.len() >= MIN_LEVELS {
        return Ok(LadderGrids {
            grids,
            memory_cut: too_large.map(|(nx, need, a)| {
                format!(
                    "grid {nx} needs about {}, more than the {} available",
                    crate::plan::bytes_text(need),
                    crate::plan::bytes_text(a)
                )
            }),
        });
    }
    Err(short_ladder(
        req,
        ratio,
        (first, &whose),
        &grids,
        too_large,
        coarsest(),
    ))
}

/// Why a ladder of R1/R2 = `ratio` from `first` (named by `whose`) holds too few grids: only
/// `grids` fit below `--max-grid`, or the memory stopped it at `too_large` (grid, bytes needed,
/// bytes available). `coarsest` is the coarsest grid that resolves the contact.
fn short_ladder(
    req: &ReferenceRequest,
    ratio: f64,
    (first, whose): (usize, &str),
    grids: &[usize],
    too_large: Option<(usize, u64, u64)>,
    coarsest: usize,
) -> RunError {
    let list = if grids.is_empty() {
        "no grid".to_string()
    } else {
        format!(
            "only grid{} {}",
            if grids.len() == 1 { "" } else { "s" },
            grids
                .iter()
                .map(|g| g.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let max = req.max_grid;
    let coarser = if first > coarsest {
        format!("a coarser {FIRST_GRID} (from {coarsest}, the coarsest that resolves the contact)")
    } else {
        String::new()
    };
    input(match too_large {
        Some((nx, need, a)) => format!(
            "{MAX_GRID_SPEC} {max}: R1/R2 = {ratio}: the ladder from grid {first} ({whose}) fits \
             {list} in memory (grid {nx} needs about {}, more than the {} available), and a \
             ladder needs at least {MIN_LEVELS} grids: {}",
            crate::plan::bytes_text(need),
            crate::plan::bytes_text(a),
            if coarser.is_empty() {
                "no ladder fits on this machine".to_string()
            } else {
                format!("give {coarser}")
            }
        ),
        None => format!(
            "{MAX_GRID_SPEC} {max}: R1/R2 = {ratio}: the ladder from grid {first} ({whose}) has \
             {list} up to {MAX_GRID_SPEC} {max}, and a ladder needs at least {MIN_LEVELS} grids: \
             give {MAX_GRID_SPEC} {} or more{}",
            first << (MIN_LEVELS - 1),
            if coarser.is_empty() {
                String::new()
            } else {
                format!(", or {coarser}")
            }
        ),
    })
}

/// One ratio's ladder on `grids` ([`ladder_grids`]): runs on each in turn until the reference
/// estimate states `target` (with at least [`MIN_LEVELS`] grids), or the memory is reached.
fn ladder(
    req: &ReferenceRequest,
    ratio: f64,
    grids: &LadderGrids,
    watch: &dyn Watch,
) -> Result<(ReferenceRow, Vec<RunReport>), RunError> {
    let scene = ratio_scene(ratio)?;
    let base = ladder_options();
    let dir = runs_dir(&req.out);
    let mut runs: Vec<RunReport> = Vec::new();
    let mut est = None;
    let mut levels = 0;
    'grids: for &nx in &grids.grids {
        let margins = phase_margins(base.margin, req.phases);
        for (phase, margin) in margins.into_iter().enumerate() {
            let name = crate::output::names::reference_run(ratio, nx, phase, margin);
            let options = ModelOptions {
                nx,
                margin,
                ..base.clone()
            };
            match run_or_reuse(&scene, options, req.backend, &dir, &name, watch) {
                Ok(run) => runs.push(run),
                // A grid that no longer fits in memory (less is free than when the ladder was
                // checked) ends the ladder.
                Err(e) if e.is_input() && levels > 0 && e.message.contains("available") => {
                    watch.warning(&format!(
                        "R1/R2 = {ratio}: the ladder stops at grid {nx}: {e}"
                    ));
                    runs.retain(|r| r.nx != nx);
                    break 'grids;
                }
                Err(e) => return Err(e),
            }
        }
        levels += 1;
        if levels >= MIN_LEVELS {
            let e = estimate::reference(&runs).map_err(failed)?;
            let met = e.f_ad_bar.relative() <= req.target;
            watch.note(&format!(
                "R1/R2 = {ratio}: grids up to {nx}: {:.5} ± {:.5} (± {:.3} %)",
                e.f_ad_bar.value,
                e.f_ad_bar.uncertainty,
                100.0 * e.f_ad_bar.relative()
            ));
            est = Some(e);
            if met {
                break;
            }
            if let (Some(why), Some(&last)) = (&grids.memory_cut, grids.grids.last()) {
                if nx == last {
                    watch.warning(&format!(
                        "R1/R2 = {ratio}: the ladder stops at grid {nx}: {why}"
                    ));
                }
            }
        }
    }
    let e = est.ok_or_else(|| {
        failed(format!(
            "R1/R2 = {ratio}: fewer than {MIN_LEVELS} grids fit below {MAX_GRID_SPEC} {}",
            req.max_grid
        ))
    })?;
    let row = table_row(req, ratio, &e, &runs)?;
    Ok((row, runs))
}

/// The table's row of R1/R2 = `ratio` from its ladder's estimate `e` and `runs`.
fn table_row(
    req: &ReferenceRequest,
    ratio: f64,
    e: &crate::analysis::estimate::AdhesiveEstimate,
    runs: &[RunReport],
) -> Result<ReferenceRow, RunError> {
    // The finest grid's run at the default margin (the first of its grid): the planner's
    // re-gridding gain is measured against a model with that margin.
    let finest_nx = runs.iter().map(|r| r.nx).max().unwrap_or(0);
    let Some(finest) = runs.iter().find(|r| r.nx == finest_nx) else {
        return Err(failed(format!("R1/R2 = {ratio}: the ladder has no runs")));
    };
    let row = ReferenceRow {
        ratio,
        f_ad_bar: Some(e.f_ad_bar.value),
        f_ad_bar_uncertainty: Some(e.f_ad_bar.uncertainty),
        c_bar_at_min: e.c_bar_at_min.map(|v| v.value),
        c_bar_at_min_uncertainty: e.c_bar_at_min.map(|v| v.uncertainty),
        d_bar_at_min: e.d_bar_at_min.map(|v| v.value),
        d_bar_at_min_uncertainty: e.d_bar_at_min.map(|v| v.uncertainty),
        k: Some(e.k.value),
        k_uncertainty: Some(e.k.uncertainty),
        target_met: e.f_ad_bar.relative() <= req.target,
        grids: grids_text(runs),
        runs_per_grid: req.phases.max(1),
        n_d: finest.n_d,
        cg_iterations: runs.iter().map(|r| r.cg_iterations).sum(),
        wall_s: runs.iter().map(|r| r.wall_s).sum(),
        command: req.command.clone(),
    };
    Ok(row)
}

/// The distinct grids Nx of `runs`, coarse to fine, `;`-separated.
fn grids_text(runs: &[RunReport]) -> String {
    let mut grids: Vec<usize> = runs.iter().map(|r| r.nx).collect();
    grids.sort_unstable();
    grids.dedup();
    grids
        .iter()
        .map(|g| g.to_string())
        .collect::<Vec<_>>()
        .join(";")
}

/// The run of `options` on `scene` whose summary is `<dir>/<name>.json` (its states beside it
/// as `.csv`): an earlier job's where it finished with a force minimum, records the same
/// settings, ran on the backend asked for and its states reproduce its summary
/// ([`reuse::check`]; said on `watch`), else run now (saying on `watch` why an earlier one
/// was not reused). The summary records the run's settings under [`reuse::SETTINGS_KEY`]. A
/// run that stops early is a failure naming `name`.
pub(crate) fn run_or_reuse(
    scene: &Scene,
    options: ModelOptions,
    backend: BackendRequest,
    dir: &std::path::Path,
    name: &str,
    watch: &dyn Watch,
) -> Result<RunReport, RunError> {
    let summary = dir.join(format!("{name}.json"));
    let states = dir.join(format!("{name}.csv"));
    let settings = reuse::RunSettings::of(scene, &options, &backend);
    match reuse::check(&summary, &states, &settings, &backend) {
        Ok(Some(run)) => {
            watch.note(&format!("{name}: reusing {}", summary.display()));
            return Ok(run);
        }
        Ok(None) => {}
        Err(why) => watch.warning(&format!(
            "{name}: not reusing {}: {why}; running it again",
            summary.display()
        )),
    }
    let _claimed = Outputs::claim(&named(OUT, [&summary]))?;
    let one = SimulateRequest {
        scene: scene.clone(),
        options,
        backend,
        mode: Mode::Single,
        sink: Sink::Files {
            out: Some(states),
            summary: None,
        },
        fields: Default::default(),
        time_limit: None,
        request: None,
        input_files: Vec::new(),
        figures: Default::default(),
    };
    let done = simulate(&one, watch)?;
    write_summary(&summary, &done.summary, &settings)?;
    if let Some(f) = done.failure {
        return Err(failed(format!("{name}: {f}")));
    }
    done.summary
        .runs
        .into_iter()
        .next()
        .ok_or_else(|| failed(format!("{name}: the run wrote no summary")))
}

/// Write `summary` as JSON to `path` (atomically), with the run's `settings` added under
/// [`reuse::SETTINGS_KEY`].
fn write_summary(
    path: &std::path::Path,
    summary: &crate::output::summary::Summary,
    settings: &reuse::RunSettings,
) -> Result<(), RunError> {
    let mut v = serde_json::to_value(summary).map_err(failed)?;
    if let Some(object) = v.as_object_mut() {
        object.insert(
            reuse::SETTINGS_KEY.into(),
            serde_json::to_value(settings).map_err(failed)?,
        );
    }
    let text = serde_json::to_string_pretty(&v).map_err(failed)?;
    crate::output::file::write_text(path, &(text + "\n")).map_err(write_error(OUT))
}

pub use crate::output::names::reference_runs as runs_dir;

/// The rows of an existing table at `path` (none if there is no file). A file that is not a
/// reference table is refused rather than replaced.
fn existing_rows(path: &std::path::Path) -> Result<Vec<ReferenceRow>, RunError> {
    if !path.exists() {
        return Ok(Vec::new());
    }
    let mut r = csv::Reader::from_path(path).map_err(|e| {
        refuse(
            OUT,
            format!(
                "{OUT} {}: cannot read the existing table: {e}",
                path.display()
            ),
        )
    })?;
    r.deserialize()
        .collect::<Result<Vec<ReferenceRow>, _>>()
        .map_err(|e| {
            refuse(
                OUT,
                format!(
                    "{OUT} {} exists and is not a reference table ({e}): give another name",
                    path.display()
                ),
            )
        })
}

/// Compute the table: every ratio's ladder in turn, every one checked first
/// ([`ladder_grids`]) so that a request that cannot hold a ladder is refused before any work. The rows of an existing table for other
/// ratios are kept, so a table grows over several jobs; it is rewritten (whole, atomically,
/// sorted by ratio) after each ratio so that a long job keeps what it has finished.
pub fn reference(req: &ReferenceRequest, watch: &dyn Watch) -> Result<ReferenceDone, RunError> {
    if !(MIN_TARGET..=MAX_TARGET).contains(&req.target) {
        return Err(refuse(
            TARGET,
            format!(
                "{TARGET}: give a percentage in [{}, {}], e.g. 0.3%",
                crate::text::compact(MIN_TARGET * 100.0),
                crate::text::compact(MAX_TARGET * 100.0)
            ),
        ));
    }
    if req.ratios.is_empty() || req.ratios.iter().any(|r| !(1.0..=1000.0).contains(r)) {
        return Err(refuse(
            RATIOS,
            format!("{RATIOS}: give ratios R1/R2 in [1, 1000]"),
        ));
    }
    if !req.max_grid.is_power_of_two() || !(MIN_FIRST_GRID..=MAX_GRID).contains(&req.max_grid) {
        return Err(refuse(
            MAX_GRID_SPEC,
            format!(
                "{MAX_GRID_SPEC} {}: give a power of two from {MIN_FIRST_GRID} to {MAX_GRID}",
                req.max_grid
            ),
        ));
    }
    if let Some(nx) = req.first_grid {
        if !nx.is_power_of_two() || nx < MIN_FIRST_GRID || nx > req.max_grid {
            return Err(refuse(
                FIRST_GRID,
                format!(
                "{FIRST_GRID} {nx}: give a power of two from {MIN_FIRST_GRID} to {MAX_GRID_SPEC} \
                 ({})",
                req.max_grid
            ),
            ));
        }
    }
    if !(1..=MAX_PHASES).contains(&req.phases) {
        return Err(refuse(
            PHASES,
            format!(
                "{PHASES} {}: give the runs per grid, 1 to {MAX_PHASES}",
                req.phases
            ),
        ));
    }
    req.backend.check()?;
    // Every ratio's ladder, checked before any work.
    let available = crate::plan::available_memory().map_err(input)?;
    let ladders = req
        .ratios
        .iter()
        .map(|&ratio| ladder_grids(req, ratio, available))
        .collect::<Result<Vec<_>, _>>()?;
    let kept = existing_rows(&req.out)?;
    let _claimed = Outputs::claim(&named(OUT, [&req.out]))?;
    let mut table: Vec<ReferenceRow> = kept
        .into_iter()
        .filter(|r| !req.ratios.contains(&r.ratio))
        .collect();
    let mut rows = Vec::new();
    for (&ratio, grids) in req.ratios.iter().zip(&ladders) {
        let (row, _) = ladder(req, ratio, grids, watch)?;
        rows.push(row.clone());
        table.push(row);
        table.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
        crate::output::file::write_csv(&req.out, None, &table).map_err(write_error(OUT))?;
    }
    let written = std::fs::read_to_string(&req.out).unwrap_or_default();
    Ok(ReferenceDone {
        rows,
        path: req.out.clone(),
        law: convergence::fit_table_law(&convergence::table_points(&written)),
    })
}
