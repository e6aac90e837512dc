//! How honest the stated uncertainties are: single-grid runs of the reference table's ratios at
//! many grid phases (the domain's margin moves where the contact's edge falls between element
//! centres), on fixed and re-gridded grids, each run's estimate ([`estimate::single_grid`],
//! with the compiled-in convergence law) held against its reference: JKR's exact 1/2 for the
//! sphere, else the table's Δx → 0 value from a ladder at least two levels finer than the
//! case's grid. A case may also be several runs at consecutive margins estimated together, as
//! `reference --phases` does. Runs already in the output folder are reused
//! and estimated again, so that a new law is checked on the same runs in seconds.

use super::reference::run_or_reuse;
use crate::analysis::convergence::{self, TableValue};
use crate::analysis::estimate;
use crate::analysis::generic_limit;
use crate::model::{Measure, Model, ModelError, ModelOptions, Onsets, MAX_GRID, MAX_MARGIN};
use crate::params::{
    words, Spec, APEX_OFFSET, APEX_OFFSETS, BACKEND, GRID, GRIDS, MARGIN, MARGINS, MESH_ANGLE,
    MESH_ANGLES, OUT, RATIOS, RUNS_PER_CASE, SHAPES, VARIANTS,
};
use crate::scene::Scene;
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::BackendRequest;
use crate::session::refuse;
use crate::session::{failed, input, RunError, Watch};
use crate::solver::edge_advice;
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

/// Levels a case's grid must lie below the finest grid of its reference's ladder (halvings):
/// the reference is then known far better than a case's own estimate.
pub const LEVELS_BELOW_REFERENCE: u32 = 2;

/// The sphere's case grids (its reference, 1/2, is exact).
pub const SPHERE_GRIDS: [usize; 3] = [32, 64, 128];

pub use crate::params::limits::MAX_RUNS_PER_CASE;

/// The default domain margins: the default one and four more, 0.05 apart.
pub const DEFAULT_MARGINS: [f64; 5] = [0.08, 0.13, 0.18, 0.23, 0.28];

/// How each case's grid is run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum CaseVariant {
    /// The same Δx throughout (`--measure adhesive-force`).
    Fixed,
    /// Re-gridded to the shrinking contact (`--measure adhesive-force --regrid`).
    Regrid,
}

impl CaseVariant {
    /// "fixed" or "regrid".
    pub fn name(self) -> &'static str {
        match self {
            CaseVariant::Fixed => "fixed",
            CaseVariant::Regrid => "regrid",
        }
    }
}

impl fmt::Display for CaseVariant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A request for the coverage study.
#[derive(Debug, Clone)]
pub struct CoverageRequest {
    /// The ratios R1/R2 (each 1 or a ratio of the compiled-in reference table).
    pub ratios: Vec<f64>,
    /// Case grids Nx for every ratio (`None`: [`case_grids`]).
    pub grids: Option<Vec<usize>>,
    /// Domain margins (relative to the initial contact's half-axes).
    pub margins: Vec<f64>,
    /// Fixed, re-gridded or both.
    pub variants: Vec<CaseVariant>,
    /// Mesh angles θ (degrees, the grid against the major axis): each case runs at each.
    pub mesh_angles: Vec<f64>,
    /// Apex offsets within the element grid (elements along x and y, each in [−0.5, 0.5]):
    /// each case runs at each.
    pub apex_offsets: Vec<(f64, f64)>,
    /// Runs per case (1 to the number of margins): each case is estimated from this many runs
    /// at consecutive margins of one grid and variant together, as `reference --phases` does;
    /// the cases are every such window of margins.
    pub runs_per_case: usize,
    /// The backend.
    pub backend: BackendRequest,
    /// Output folder: every run's states and summary, coverage.csv and coverage-summary.csv.
    pub out: PathBuf,
}

/// One case: a run's single-grid estimate against its reference.
#[derive(Debug, Clone, Serialize)]
pub struct CoverageCase {
    /// R1/R2.
    pub ratio: f64,
    /// "Nx×Ny".
    pub grid: String,
    /// The domain margin (the first of the case's runs).
    pub margin: f64,
    /// Runs the case's estimate is made from (at consecutive margins).
    pub runs: usize,
    /// fixed or regrid.
    pub variant: &'static str,
    /// The mesh angle θ (degrees).
    pub mesh_angle_deg: f64,
    /// The apex offset along x (elements).
    pub apex_offset_x: f64,
    /// The apex offset along y (elements).
    pub apex_offset_y: f64,
    /// Elements across the minor axis at the minimum (the runs' mean).
    pub n_d: Option<f64>,
    /// The runs' own |min F̄| (uncorrected; their mean).
    pub f_ad_bar_grid: f64,
    /// Its estimate of the Δx → 0 limit.
    pub f_ad_bar: f64,
    /// The estimate's stated half-width (absolute).
    pub uncertainty: f64,
    /// The reference (1/2 for the sphere, else the table's value).
    pub reference: f64,
    /// The reference's own stated half-width (0 for the sphere).
    pub reference_uncertainty: f64,
    /// f_ad_bar − reference (absolute, signed).
    pub error: f64,
    /// Whether the stated interval holds the reference.
    pub held: bool,
    /// uncertainty / |error| (dimensionless; large: the interval is wide for this case).
    pub width_over_error: f64,
    /// c̄ at the minimum: the case's estimate.
    pub c_bar_at_min: Option<f64>,
    /// Its stated half-width.
    pub c_bar_uncertainty: Option<f64>,
    /// Its reference (JKR's 2^(−1/3) for the sphere, else the table's).
    pub c_bar_reference: Option<f64>,
    /// The reference's half-width.
    pub c_bar_reference_uncertainty: Option<f64>,
    /// Whether |c̄ − reference| ≤ the two half-widths together.
    pub c_bar_held: Option<bool>,
    /// d̄ at the minimum: the case's estimate.
    pub d_bar_at_min: Option<f64>,
    /// Its stated half-width.
    pub d_bar_uncertainty: Option<f64>,
    /// Its reference (JKR's for the sphere, else the table's).
    pub d_bar_reference: Option<f64>,
    /// The reference's half-width.
    pub d_bar_reference_uncertainty: Option<f64>,
    /// Whether |d̄ − reference| ≤ the two half-widths together.
    pub d_bar_held: Option<bool>,
}

/// A case's c̄ or d̄ at the minimum against its reference (JKR's exact value for the sphere,
/// else the table's): held if the distance is at most the case's half-width plus the
/// reference's own (all absolute, dimensionless).
#[derive(Debug, Clone, Copy, Default)]
struct PositionCheck {
    estimate: Option<f64>,
    uncertainty: Option<f64>,
    reference: Option<f64>,
    reference_uncertainty: Option<f64>,
    held: Option<bool>,
}

impl PositionCheck {
    /// The check of `estimate` against `reference` (value, half-width); empty if either is
    /// missing.
    fn of(estimate: Option<estimate::Estimate>, reference: Option<(f64, f64)>) -> Self {
        let (Some(e), Some((r, ru))) = (estimate, reference) else {
            return Self::default();
        };
        Self {
            estimate: Some(e.value),
            uncertainty: Some(e.uncertainty),
            reference: Some(r),
            reference_uncertainty: Some(ru),
            held: Some((e.value - r).abs() <= e.uncertainty + ru),
        }
    }
}

/// The cases of one ratio (or of all), summed up.
#[derive(Debug, Clone, Serialize)]
pub struct CoverageSummary {
    /// R1/R2, or "all".
    pub ratio: String,
    /// Cases.
    pub cases: usize,
    /// Cases whose stated interval holds the reference.
    pub held: usize,
    /// held / cases.
    pub held_fraction: f64,
    /// The median of uncertainty / |error| (the "not needlessly wide": at most 3).
    pub median_width_over_error: f64,
    /// The RMS of error / (uncertainty / 2): 1 for intervals of two calibrated standard
    /// deviations.
    pub rms_error_over_sd: f64,
    /// The smallest stated half-width, relative.
    pub half_width_min: f64,
    /// The largest stated half-width, relative.
    pub half_width_max: f64,
    /// Cases with a c̄ check (and a d̄ check).
    pub position_cases: usize,
    /// Of those, cases whose c̄ interval holds its reference.
    pub c_bar_held: usize,
    /// Of those, cases whose d̄ interval holds its reference.
    pub d_bar_held: usize,
}

/// What the study produced.
#[derive(Debug, Clone)]
pub struct CoverageDone {
    /// Every case, by ratio, grid, margin and variant.
    pub cases: Vec<CoverageCase>,
    /// One line per ratio, then "all".
    pub summary: Vec<CoverageSummary>,
    /// coverage.csv.
    pub csv: PathBuf,
    /// coverage-summary.csv.
    pub summary_csv: PathBuf,
}

/// What a case of one ratio is held against.
#[derive(Debug, Clone, Copy)]
struct CaseReference {
    /// |min F̄| and its half-width.
    f_ad_bar: (f64, f64),
    /// c̄ at the minimum and its half-width, where known.
    c_bar_at_min: Option<(f64, f64)>,
    /// d̄ at the minimum and its half-width, where known.
    d_bar_at_min: Option<(f64, f64)>,
    /// The finest grid of its ladder (`None` for the sphere's exact JKR values).
    finest: Option<usize>,
}

/// The reference of R1/R2 = `ratio`: JKR's exact minimum for the sphere (|F̄| 1/2,
/// c̄ = 2^(−1/3), d̄), else the table's row.
fn reference_of(ratio: f64, table: &[TableValue]) -> Result<CaseReference, RunError> {
    if ratio == 1.0 {
        let jkr = crate::theory::jkr::jkr_force_min();
        return Ok(CaseReference {
            f_ad_bar: (-jkr.f_bar, 0.0),
            c_bar_at_min: Some((jkr.c_bar, 0.0)),
            d_bar_at_min: Some((jkr.d_bar, 0.0)),
            finest: None,
        });
    }
    let row = table.iter().find(|r| r.ratio == ratio).ok_or_else(|| {
        refuse(
            RATIOS,
            format!(
                "{RATIOS} {ratio}: the reference table has no row for it; give 1 or one of {}",
                table
                    .iter()
                    .map(|r| crate::text::compact(r.ratio))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        )
    })?;
    Ok(CaseReference {
        f_ad_bar: (row.f_ad_bar, row.uncertainty),
        c_bar_at_min: row.c_bar_at_min,
        d_bar_at_min: row.d_bar_at_min,
        finest: row.grids.last().copied(),
    })
}

/// The default case grids of a ratio whose reference ladder is `ladder` (coarse to fine): its
/// finest grid over 8 and over 4, those not below its first grid (where the convergence law
/// was measured); the sphere's are [`SPHERE_GRIDS`].
pub fn case_grids(ladder: Option<&[usize]>) -> Vec<usize> {
    let Some(ladder) = ladder.filter(|l| !l.is_empty()) else {
        return SPHERE_GRIDS.to_vec();
    };
    let finest = ladder[ladder.len() - 1];
    [finest / 8, finest / 4]
        .into_iter()
        .filter(|&g| g >= ladder[0])
        .collect()
}

/// The coarsest case grid (Nx): coarser grids are not yet in the first-order regime the
/// convergence law describes ([`crate::plan::MIN_PLAN_GRID`]).
pub const MIN_CASE_GRID: usize = crate::plan::MIN_PLAN_GRID;

/// The parameters of `jkrbem coverage`: advice from a run that names any other (a
/// simulation's parameter, which coverage sets to its default) is followed by what to change
/// here.
pub const COVERAGE_SPECS: [&Spec; 11] = [
    RATIOS,
    SHAPES,
    crate::params::EXPONENTS,
    GRIDS,
    MARGINS,
    VARIANTS,
    MESH_ANGLES,
    APEX_OFFSETS,
    RUNS_PER_CASE,
    BACKEND,
    OUT,
];

/// The parameter of coverage that sets what a run's parameter `p` sets, where coverage sets
/// it (a case's margin, grid and placement come from coverage's lists); `None` for one that
/// coverage leaves at its default.
fn coverage_spec(p: &'static Spec) -> Option<&'static Spec> {
    if COVERAGE_SPECS.contains(&p) {
        Some(p)
    } else if p == MARGIN {
        Some(MARGINS)
    } else if p == GRID {
        Some(GRIDS)
    } else if p == MESH_ANGLE {
        Some(MESH_ANGLES)
    } else if p == APEX_OFFSET {
        Some(APEX_OFFSETS)
    } else {
        None
    }
}

/// How the grid lies against the contact in a case: its mesh angle θ (degrees) and the
/// apex's offset within the element grid (elements).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// θ (degrees).
    pub mesh_angle_deg: f64,
    /// The apex offset (elements along x and y).
    pub apex_offset: (f64, f64),
}

impl Placement {
    /// The name of a case's run placed so ([`crate::output::names::coverage_case`]).
    fn case_name(&self, ratio: f64, nx: usize, margin: f64, variant: CaseVariant) -> String {
        crate::output::names::coverage_case(
            ratio,
            nx,
            margin,
            variant,
            self.mesh_angle_deg,
            self.apex_offset,
        )
    }
}

/// The options of a case's run on grid `nx` at `margin` run as `variant`, placed `at`.
fn case_options(nx: usize, margin: f64, variant: CaseVariant, at: Placement) -> ModelOptions {
    let regrid = variant == CaseVariant::Regrid;
    ModelOptions {
        nx,
        margin,
        regrid,
        mesh_angle_deg: at.mesh_angle_deg,
        apex_offset: at.apex_offset,
        measure: Measure::AdhesiveForce,
        onsets: Onsets::NearMinimum,
        steps: crate::model::default_steps(Measure::AdhesiveForce, Onsets::NearMinimum, regrid),
        ..ModelOptions::default()
    }
}

/// Refuse, before any work, a case grid coverage cannot run: not a power of two from
/// [`MIN_CASE_GRID`] to [`MAX_GRID`], or too coarse for the scene at one of the margins (the
/// message names `--grids` and the coarsest grid that resolves it).
fn check_case_grid(
    scene: &Scene,
    nx: usize,
    margins: &[f64],
    variants: &[CaseVariant],
    placements: &[Placement],
) -> Result<(), RunError> {
    if !nx.is_power_of_two() || !(MIN_CASE_GRID..=MAX_GRID).contains(&nx) {
        return Err(refuse(
            GRIDS,
            format!(
            "{GRIDS} {nx}: give powers of two from {MIN_CASE_GRID} to {MAX_GRID} (coarser grids \
             are not yet in the first-order regime the estimates assume)"
        ),
        ));
    }
    let builds = |nx: usize| -> Result<(), ModelError> {
        for &margin in margins {
            for &variant in variants {
                for &at in placements {
                    Model::build(scene, &case_options(nx, margin, variant, at))?;
                }
            }
        }
        Ok(())
    };
    match builds(nx) {
        Ok(()) => Ok(()),
        Err(ModelError::TooCoarse { .. }) => {
            let mut fine = nx * 2;
            while fine < MAX_GRID && builds(fine).is_err() {
                fine *= 2;
            }
            Err(refuse(
                GRIDS,
                format!(
                    "{GRIDS} {nx}: too coarse for R1/R2 = {} (the contact would span too few \
                 elements at the {MARGINS} and {MESH_ANGLES} asked); give {GRIDS} {fine} or finer",
                    crate::text::compact(scene.ratio())
                ),
            ))
        }
        Err(e) => Err(refuse(
            GRIDS,
            format!("{GRIDS} {nx} with these {MARGINS}, {MESH_ANGLES} and {APEX_OFFSETS}: {e}"),
        )),
    }
}

/// A run's failure in coverage's words: the advice of a contact at the domain's edge
/// ([`edge_advice`]) becomes coverage's (larger margins or finer grids); every parameter the
/// message names is coverage's that sets it ([`coverage_spec`]: the margin as the margins, the
/// grid as the grids, …), and one that coverage does not set is followed by a note that
/// coverage runs with its default.
fn in_coverage_words(e: RunError) -> RunError {
    if e.is_input() {
        return e;
    }
    let param = e.param.map(|p| coverage_spec(p).unwrap_or(p));
    let m = e.message;
    let m = m.replace(
        &edge_advice(),
        &format!("use larger {MARGINS} or finer {GRIDS}"),
    );
    let foreign: Vec<String> = words::named(&m)
        .into_iter()
        .filter(|p| coverage_spec(p).is_none())
        .map(|p| p.to_string())
        .collect();
    let m = words::render(&m, &|p| coverage_spec(p).unwrap_or(p).to_string());
    if foreign.is_empty() {
        return RunError { param, ..failed(m) };
    }
    RunError {
        param,
        ..failed(format!(
            "{m}\n  (coverage runs every case with the defaults of {}, which it does not set: \
             change {GRIDS} or {MARGINS}, or run that case with `jkrbem simulate`)",
            foreign.join(", ")
        ))
    }
}

/// Check the request, then run (or reuse) every case, estimate each and sum them up.
pub fn coverage(req: &CoverageRequest, watch: &dyn Watch) -> Result<CoverageDone, RunError> {
    check_request(req)?;
    req.backend.check()?;
    let plan = plan_cases(req)?;
    let csv = req.out.join("coverage.csv");
    let summary_csv = req.out.join("coverage-summary.csv");
    let _claimed = Outputs::claim(&named(OUT, [&csv, &summary_csv]))?;
    let mut cases = Vec::new();
    for (ratio, grids, reference) in plan {
        let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(input)?;
        for &nx in &grids {
            for &variant in &req.variants {
                for at in placements(req) {
                    // This grid's, variant's and placement's run at every margin, in order.
                    let mut runs = Vec::new();
                    for &margin in &req.margins {
                        let name = at.case_name(ratio, nx, margin, variant);
                        let options = case_options(nx, margin, variant, at);
                        let run =
                            run_or_reuse(&scene, options, req.backend, &req.out, &name, watch)
                                .map_err(in_coverage_words)?;
                        runs.push((margin, run));
                    }
                    for window in runs.windows(req.runs_per_case) {
                        cases.push(case_of(ratio, nx, variant, at, window, &reference)?);
                    }
                }
            }
        }
    }
    let mut summary: Vec<CoverageSummary> = req
        .ratios
        .iter()
        .filter_map(|&r| {
            let mine: Vec<&CoverageCase> = cases.iter().filter(|c| c.ratio == r).collect();
            summarise(&crate::text::compact(r), &mine)
        })
        .collect();
    // By placement, where several were asked for: the mesh angles, then the apex offsets.
    if req.mesh_angles.len() > 1 {
        for &a in &req.mesh_angles {
            let mine: Vec<&CoverageCase> = cases.iter().filter(|c| c.mesh_angle_deg == a).collect();
            summary.extend(summarise(
                &format!("angle {}", crate::text::compact(a)),
                &mine,
            ));
        }
    }
    if req.apex_offsets.len() > 1 {
        for &(x, y) in &req.apex_offsets {
            let mine: Vec<&CoverageCase> = cases
                .iter()
                .filter(|c| (c.apex_offset_x, c.apex_offset_y) == (x, y))
                .collect();
            let name = format!(
                "offset {}:{}",
                crate::text::compact(x),
                crate::text::compact(y)
            );
            summary.extend(summarise(&name, &mine));
        }
    }
    summary.extend(summarise("all", &cases.iter().collect::<Vec<_>>()));
    crate::output::file::write_csv(&csv, None, &cases).map_err(write_error(OUT))?;
    crate::output::file::write_csv(&summary_csv, None, &summary).map_err(write_error(OUT))?;
    Ok(CoverageDone {
        cases,
        summary,
        csv,
        summary_csv,
    })
}

/// Refuse a request without ratios, margins or variants, or with margins or a window the
/// runs cannot have.
fn check_request(req: &CoverageRequest) -> Result<(), RunError> {
    if req.ratios.is_empty()
        || req.margins.is_empty()
        || req.variants.is_empty()
        || req.mesh_angles.is_empty()
        || req.apex_offsets.is_empty()
    {
        return Err(refuse(
            RATIOS,
            format!(
                "{RATIOS}, {MARGINS}, {VARIANTS}, {MESH_ANGLES} and {APEX_OFFSETS}: give at least \
             one of each"
            ),
        ));
    }
    if !(1..=req.margins.len().min(MAX_RUNS_PER_CASE)).contains(&req.runs_per_case) {
        return Err(refuse(
            RUNS_PER_CASE,
            format!(
                "{RUNS_PER_CASE} {}: give 1 to the number of {MARGINS} ({}), at most \
             {MAX_RUNS_PER_CASE}",
                req.runs_per_case,
                req.margins.len()
            ),
        ));
    }
    if let Some(m) = req
        .margins
        .iter()
        .find(|m| !(0.0..=MAX_MARGIN).contains(*m))
    {
        return Err(refuse(
            MARGINS,
            format!("{MARGINS} {m}: give margins in [0, {MAX_MARGIN}]"),
        ));
    }
    Ok(())
}

/// (ratio, its case grids, its reference) per ratio, every one checked before any work.
fn plan_cases(req: &CoverageRequest) -> Result<Vec<(f64, Vec<usize>, CaseReference)>, RunError> {
    let table = convergence::reference_values();
    let mut plan = Vec::new();
    for &ratio in &req.ratios {
        let scene = Scene::from_ratio(ratio, 1.0, 1.0, 1.0).map_err(input)?;
        let reference = reference_of(ratio, &table)?;
        let ladder = table
            .iter()
            .find(|r| r.ratio == ratio && ratio != 1.0)
            .map(|r| r.grids.as_slice());
        let grids = match &req.grids {
            Some(g) => g.clone(),
            None => case_grids(ladder),
        };
        if let Some(finest) = reference.finest {
            if let Some(too_fine) = grids
                .iter()
                .find(|&&g| g << LEVELS_BELOW_REFERENCE > finest)
            {
                return Err(refuse(
                    GRIDS,
                    format!(
                        "{GRIDS} {too_fine}: the reference of R1/R2 = {ratio} comes from grids up \
                     to {finest}; give grids up to {} (at least {LEVELS_BELOW_REFERENCE} levels \
                     coarser, so that the reference is known far better than a case)",
                        finest >> LEVELS_BELOW_REFERENCE
                    ),
                ));
            }
        }
        for &nx in &grids {
            check_case_grid(&scene, nx, &req.margins, &req.variants, &placements(req))?;
        }
        plan.push((ratio, grids, reference));
    }
    Ok(plan)
}

/// Every placement of the request: each mesh angle with each apex offset.
fn placements(req: &CoverageRequest) -> Vec<Placement> {
    req.mesh_angles
        .iter()
        .flat_map(|&a| {
            req.apex_offsets.iter().map(move |&o| Placement {
                mesh_angle_deg: a,
                apex_offset: o,
            })
        })
        .collect()
}

/// The case of one window of runs (`runs_per_case` margins of one grid and variant): its
/// estimate against the reference.
fn case_of(
    ratio: f64,
    nx: usize,
    variant: CaseVariant,
    at: Placement,
    window: &[(f64, crate::analysis::report::RunReport)],
    reference: &CaseReference,
) -> Result<CoverageCase, RunError> {
    let reports: Vec<_> = window.iter().map(|(_, r)| r.clone()).collect();
    let name = at.case_name(ratio, nx, window[0].0, variant);
    let e = estimate::from_runs(&reports)
        .map_err(|why| failed(format!("{name} ({} runs): {why}", reports.len())))?;
    let mean = |get: fn(&crate::analysis::report::RunReport) -> Option<f64>| {
        let v: Option<Vec<f64>> = reports.iter().map(get).collect();
        v.map(|v| v.iter().sum::<f64>() / v.len() as f64)
    };
    let (f, u) = (e.f_ad_bar.value, e.f_ad_bar.uncertainty);
    let (reference_value, reference_uncertainty) = reference.f_ad_bar;
    let error = f - reference_value;
    let c = PositionCheck::of(e.c_bar_at_min, reference.c_bar_at_min);
    let d = PositionCheck::of(e.d_bar_at_min, reference.d_bar_at_min);
    Ok(CoverageCase {
        ratio,
        grid: reports[0].grid.clone(),
        margin: window[0].0,
        runs: reports.len(),
        variant: variant.name(),
        mesh_angle_deg: at.mesh_angle_deg,
        apex_offset_x: at.apex_offset.0,
        apex_offset_y: at.apex_offset.1,
        n_d: mean(|r| r.n_d),
        f_ad_bar_grid: mean(|r| r.f_ad_bar).unwrap_or(f64::NAN),
        f_ad_bar: f,
        uncertainty: u,
        reference: reference_value,
        reference_uncertainty,
        error,
        held: error.abs() <= u,
        width_over_error: if error == 0.0 {
            f64::INFINITY
        } else {
            u / error.abs()
        },
        c_bar_at_min: c.estimate,
        c_bar_uncertainty: c.uncertainty,
        c_bar_reference: c.reference,
        c_bar_reference_uncertainty: c.reference_uncertainty,
        c_bar_held: c.held,
        d_bar_at_min: d.estimate,
        d_bar_uncertainty: d.uncertainty,
        d_bar_reference: d.reference,
        d_bar_reference_uncertainty: d.reference_uncertainty,
        d_bar_held: d.held,
    })
}

/// The summary line of `cases` (`None` if there are none).
pub fn summarise(name: &str, cases: &[&CoverageCase]) -> Option<CoverageSummary> {
    if cases.is_empty() {
        return None;
    }
    let n = cases.len();
    let held = cases.iter().filter(|c| c.held).count();
    let mut ratios: Vec<f64> = cases.iter().map(|c| c.width_over_error).collect();
    ratios.sort_by(f64::total_cmp);
    let median = if n % 2 == 1 {
        ratios[n / 2]
    } else {
        0.5 * (ratios[n / 2 - 1] + ratios[n / 2])
    };
    let z2 = cases
        .iter()
        .map(|c| (2.0 * c.error / c.uncertainty).powi(2))
        .sum::<f64>();
    let relative = |c: &&CoverageCase| c.uncertainty / c.f_ad_bar.abs();
    Some(CoverageSummary {
        ratio: name.to_string(),
        cases: n,
        held,
        held_fraction: held as f64 / n as f64,
        median_width_over_error: median,
        rms_error_over_sd: (z2 / n as f64).sqrt(),
        half_width_min: cases.iter().map(relative).fold(f64::INFINITY, f64::min),
        half_width_max: cases.iter().map(relative).fold(0.0, f64::max),
        position_cases: cases.iter().filter(|c| c.c_bar_held.is_some()).count(),
        c_bar_held: cases.iter().filter(|c| c.c_bar_held == Some(true)).count(),
        d_bar_held: cases.iter().filter(|c| c.d_bar_held == Some(true)).count(),
    })
}

/// A shape whose stated uncertainties coverage checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum CoverageShape {
    /// The ellipsoid, by its convergence law ([`coverage`]).
    Ellipsoid,
    /// The flat punch, extrapolated without a law ([`generic_coverage`]), against Kendall's 1.
    FlatPunch,
    /// The power law, extrapolated without a law, against its JKR solution.
    PowerLaw,
    /// The cone, extrapolated without a law, against its JKR solution.
    Cone,
    /// A generated rough sphere ([`rough_sphere`], one scene per seed), extrapolated without
    /// a law, against the same runs on a grid twice finer than any its estimate used.
    RoughSphere,
}

impl fmt::Display for CoverageShape {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            CoverageShape::Ellipsoid => "ellipsoid",
            CoverageShape::FlatPunch => "flat-punch",
            CoverageShape::PowerLaw => "power-law",
            CoverageShape::Cone => "cone",
            CoverageShape::RoughSphere => "rough-sphere",
        })
    }
}

/// What a case of a shape without a convergence law is held against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Truth {
    /// The closed form of the Δx → 0 limit: its name and |min F̄| (Kendall's 1, the power
    /// law's JKR solution).
    ClosedForm(&'static str, f64),
    /// The mean over the grid phases of the same runs on a grid twice finer than any the
    /// case's estimate used (a shape without a closed form, e.g. a rough surface): its
    /// half-width is the phases' spread over √P at that grid (the remaining discretisation
    /// error of that grid is not counted: a truth only where it is far below the case's).
    FinerGrid,
}

/// A request for the coverage study of shapes without a convergence law: each case is one
/// extrapolation ([`generic_limit::limit`]) of a scene on a ladder of grids, each grid at the
/// grid phases [`crate::plan::GENERIC_PHASES`] shifted by one of `phase_shifts`, held against
/// its [`Truth`].
#[derive(Debug, Clone)]
pub struct GenericCoverageRequest {
    /// The scenes, each with its truth and a name for its files and rows.
    pub scenes: Vec<(String, Scene, Truth)>,
    /// The ladder of grids Nx (at least two, increasing).
    pub grids: Vec<usize>,
    /// Domain margins: each is a case (they move where the contact's edge falls, too).
    pub margins: Vec<f64>,
    /// Shifts of the phase set (elements along x and y): each is a case.
    pub phase_shifts: Vec<(f64, f64)>,
    /// The backend.
    pub backend: BackendRequest,
    /// Output folder: every run, generic-coverage.csv and generic-coverage-summary.csv.
    pub out: PathBuf,
}

/// One case of a shape without a convergence law.
#[derive(Debug, Clone, Serialize)]
pub struct GenericCoverageCase {
    /// The scene's name ("flat-punch", "power-law-n3").
    pub shape: String,
    /// The ladder, "32,64,128".
    pub grids: String,
    /// The domain margin.
    pub margin: f64,
    /// The shift of the phase set along x (elements).
    pub shift_x: f64,
    /// The shift of the phase set along y (elements).
    pub shift_y: f64,
    /// Whether the estimate was refused (the row's numbers are then NaN and it counts as not
    /// held).
    pub refused: bool,
    /// The finest grid's mean over its phases.
    pub f_ad_bar_grid: f64,
    /// The estimate of the limit.
    pub f_ad_bar: f64,
    /// Its stated half-width.
    pub uncertainty: f64,
    /// The order of convergence the estimate used.
    pub order: f64,
    /// Whether the grids estimated it (else first order was assumed).
    pub order_estimated: bool,
    /// The truth.
    pub reference: f64,
    /// The truth's own half-width (0 for a closed form).
    pub reference_uncertainty: f64,
    /// f_ad_bar − reference.
    pub error: f64,
    /// Whether |error| ≤ uncertainty + reference_uncertainty.
    pub held: bool,
    /// uncertainty / |error|.
    pub width_over_error: f64,
}

/// What the generic study produced.
#[derive(Debug, Clone)]
pub struct GenericCoverageDone {
    /// Every case.
    pub cases: Vec<GenericCoverageCase>,
    /// One line per shape, then "all".
    pub summary: Vec<CoverageSummary>,
    /// generic-coverage.csv.
    pub csv: PathBuf,
    /// generic-coverage-summary.csv.
    pub summary_csv: PathBuf,
}

/// The roughness of coverage's rough spheres: rms slope (dimensionless).
pub const ROUGH_SPHERE_SLOPE: f64 = 0.1;
/// Their Hurst exponent.
pub const ROUGH_SPHERE_HURST: f64 = 0.8;
/// Their short-wavelength cut-off λ_s (length, R = 1): 2 elements at 32² on the default
/// margin's domain (Δx ≈ 0.19), 16 at 256², so that every grid of the ladder sees the same surface and
/// the coarsest resolves its shortest wavelength.
pub const ROUGH_SPHERE_CUTOFF: f64 = 0.4;
/// Their roll-off wavelength λ_r (length).
pub const ROUGH_SPHERE_ROLLOFF: f64 = 1.0;
/// Nodes of their roughness map along each side, at spacing [`ROUGH_SPHERE_SPACING`]
/// (length): the map spans ±4, past the domain (±3.1 at margin 0.08) of every margin up
/// to 0.38.
pub const ROUGH_SPHERE_NODES: usize = 640;
/// The spacing of their roughness map (length).
pub const ROUGH_SPHERE_SPACING: f64 = 0.0125;

/// A rough sphere of coverage (R = 1, E* = Δγ = 1): the generator's roughness
/// ([`ROUGH_SPHERE_SLOPE`], [`ROUGH_SPHERE_HURST`], [`ROUGH_SPHERE_CUTOFF`],
/// [`ROUGH_SPHERE_ROLLOFF`]) of `seed` added to the sphere; pressed on to the sphere's first
/// contact before its pull-off (a rough shape's default).
pub fn rough_sphere(seed: u64) -> Result<Scene, RunError> {
    use crate::scene::roughness::{generate, RoughnessParams};
    use crate::scene::{Indenter, RoughShape};
    let params = RoughnessParams {
        cutoff: Some(ROUGH_SPHERE_CUTOFF),
        rolloff: Some(ROUGH_SPHERE_ROLLOFF),
        seed,
        ..RoughnessParams::with_rms_slope(
            ROUGH_SPHERE_NODES,
            ROUGH_SPHERE_SPACING,
            ROUGH_SPHERE_HURST,
            ROUGH_SPHERE_SLOPE,
        )
    };
    let map = generate(&params).map_err(input)?;
    let base = Indenter::ellipsoid(1.0, 1.0);
    let source = format!("generated, seed {seed}");
    let rough = RoughShape::new(base, map, &source).map_err(input)?;
    Scene::with_indenter(Indenter::Rough(std::sync::Arc::new(rough)), 1.0, 1.0).map_err(input)
}

/// The scenes of `shape`, E* = Δγ = 1, each with its name and truth: a flat punch of radius 1
/// or the power law h = 0.5·rⁿ for each of `exponents` or the cone of each of `half_angles`
/// (degrees) (their closed forms), or a rough sphere
/// for each of `seeds` ([`rough_sphere`], against a finer grid).
pub fn generic_scenes(
    shape: CoverageShape,
    exponents: &[f64],
    half_angles: &[f64],
    seeds: &[u64],
) -> Result<Vec<(String, Scene, Truth)>, RunError> {
    use crate::scene::{Indenter, DEFAULT_POWER_LAW_SCALE};
    let indenters: Vec<Indenter> = match shape {
        CoverageShape::Ellipsoid => Vec::new(),
        CoverageShape::FlatPunch => vec![Indenter::flat_punch(1.0)],
        CoverageShape::PowerLaw => exponents
            .iter()
            .map(|&n| Indenter::power_law(n, DEFAULT_POWER_LAW_SCALE))
            .collect(),
        CoverageShape::Cone => half_angles.iter().map(|&a| Indenter::cone(a)).collect(),
        CoverageShape::RoughSphere => {
            return seeds
                .iter()
                .map(|&seed| {
                    Ok((
                        format!("rough-sphere-s{seed}"),
                        rough_sphere(seed)?,
                        Truth::FinerGrid,
                    ))
                })
                .collect();
        }
    };
    indenters
        .into_iter()
        .map(|i| {
            let scene = Scene::with_indenter(i, 1.0, 1.0).map_err(input)?;
            let truth = match scene.indenter.exact_adhesive_force(1.0, 1.0) {
                Some((name, f)) => Truth::ClosedForm(name, f),
                None => Truth::FinerGrid,
            };
            Ok((scene.tag(), scene, truth))
        })
        .collect()
}

/// `v` wrapped into [−0.5, 0.5] (an apex offset, elements).
fn wrap_offset(v: f64) -> f64 {
    let w = v - v.round();
    if w < -0.5 {
        w + 1.0
    } else {
        w
    }
}

/// The runs of one scene on grid `nx` at `margin`, at every phase of the set shifted by
/// `shift` (run or reused from `req.out`).
fn generic_runs(
    req: &GenericCoverageRequest,
    (name, scene): (&str, &Scene),
    nx: usize,
    margin: f64,
    shift: (f64, f64),
    watch: &dyn Watch,
) -> Result<Vec<crate::analysis::report::RunReport>, RunError> {
    crate::plan::GENERIC_PHASES
        .iter()
        .map(|&(x, y)| {
            let apex_offset = (wrap_offset(x + shift.0), wrap_offset(y + shift.1));
            let options = ModelOptions {
                nx,
                margin,
                apex_offset,
                measure: Measure::AdhesiveForce,
                onsets: Onsets::NearMinimum,
                steps: crate::model::default_steps(
                    Measure::AdhesiveForce,
                    Onsets::NearMinimum,
                    false,
                ),
                ..ModelOptions::default()
            };
            let file = format!(
                "{name}-n{nx}-m{}-o{}_{}",
                crate::text::compact(margin),
                crate::text::compact(apex_offset.0),
                crate::text::compact(apex_offset.1)
            );
            run_or_reuse(scene, options, req.backend, &req.out, &file, watch)
                .map_err(in_coverage_words)
        })
        .collect()
}

/// The [`Truth::FinerGrid`] of a case: the mean over the grid phases of the same runs on a
/// grid twice finer than the ladder's finest, and the phases' spread over √P.
fn finer_grid_truth(
    req: &GenericCoverageRequest,
    (name, scene): (&str, &Scene),
    margin: f64,
    shift: (f64, f64),
    watch: &dyn Watch,
) -> Result<(f64, f64), RunError> {
    let nx = req.grids[req.grids.len() - 1] * 2;
    let fine = generic_runs(req, (name, scene), nx, margin, shift, watch)?;
    let v: Vec<f64> = fine.iter().filter_map(|r| r.f_ad_bar).collect();
    if v.len() < 2 {
        return Err(failed(format!(
            "{name}: the finer grid {nx} did not reach the force minimum"
        )));
    }
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    Ok((mean, sd / n.sqrt()))
}

/// Run (or reuse) every case of shapes without a convergence law, extrapolate each and hold
/// it against its truth. Every grid is checked to build before any work.
pub fn generic_coverage(
    req: &GenericCoverageRequest,
    watch: &dyn Watch,
) -> Result<GenericCoverageDone, RunError> {
    if req.scenes.is_empty() || req.margins.is_empty() || req.phase_shifts.is_empty() {
        return Err(refuse(
            SHAPES,
            format!("{SHAPES}, {MARGINS} and {APEX_OFFSETS}: give at least one of each"),
        ));
    }
    if req.grids.len() < 2 || req.grids.windows(2).any(|w| w[1] <= w[0]) {
        return Err(refuse(
            GRIDS,
            format!(
                "{GRIDS}: the shapes without a convergence law take a ladder of two or more \
             increasing grids, e.g. 32,64,128"
            ),
        ));
    }
    req.backend.check()?;
    for (name, scene, truth) in &req.scenes {
        let finer = matches!(truth, Truth::FinerGrid).then(|| req.grids[req.grids.len() - 1] * 2);
        for nx in req.grids.iter().copied().chain(finer) {
            for &margin in &req.margins {
                let options = ModelOptions {
                    nx,
                    margin,
                    ..ModelOptions::default()
                };
                Model::build(scene, &options)
                    .map_err(|e| refuse(GRIDS, format!("{GRIDS} {nx} for {name}: {e}")))?;
            }
        }
    }
    let csv = req.out.join("generic-coverage.csv");
    let summary_csv = req.out.join("generic-coverage-summary.csv");
    let _claimed = Outputs::claim(&named(OUT, [&csv, &summary_csv]))?;
    let mut cases = Vec::new();
    for (name, scene, truth) in &req.scenes {
        for &margin in &req.margins {
            for &shift in &req.phase_shifts {
                // A run that fails (a contact at the domain's edge, say) makes its case a
                // refusal, counted as not held, rather than ending the study.
                let ran = (|| -> Result<_, RunError> {
                    let mut runs = Vec::new();
                    for &nx in &req.grids {
                        runs.extend(generic_runs(req, (name, scene), nx, margin, shift, watch)?);
                    }
                    let truth = match *truth {
                        Truth::ClosedForm(_, f) => (f, 0.0),
                        Truth::FinerGrid => {
                            finer_grid_truth(req, (name, scene), margin, shift, watch)?
                        }
                    };
                    Ok((runs, truth))
                })();
                let (runs, (reference, reference_uncertainty)) = match ran {
                    Ok(r) => r,
                    Err(e) if !e.is_input() => {
                        let why = e.message;
                        watch.warning(&format!("{name}, margin {margin}: a run failed: {why}"));
                        (Vec::new(), (f64::NAN, f64::NAN))
                    }
                    Err(e) => return Err(e),
                };
                let limit = generic_limit::grids_of(&runs).and_then(|g| generic_limit::limit(&g));
                let finest = req.grids[req.grids.len() - 1];
                let own: Vec<f64> = runs
                    .iter()
                    .filter(|r| r.nx == finest)
                    .filter_map(|r| r.f_ad_bar)
                    .collect();
                let own = own.iter().sum::<f64>() / own.len() as f64;
                let grids = req
                    .grids
                    .iter()
                    .map(|g| g.to_string())
                    .collect::<Vec<_>>()
                    .join(",");
                let case = match limit {
                    Ok(l) => {
                        let error = l.value - reference;
                        GenericCoverageCase {
                            shape: name.clone(),
                            grids,
                            margin,
                            shift_x: shift.0,
                            shift_y: shift.1,
                            refused: false,
                            f_ad_bar_grid: own,
                            f_ad_bar: l.value,
                            uncertainty: l.uncertainty,
                            order: l.order,
                            order_estimated: l.order_estimated,
                            reference,
                            reference_uncertainty,
                            error,
                            held: error.abs() <= l.uncertainty + reference_uncertainty,
                            width_over_error: if error == 0.0 {
                                f64::INFINITY
                            } else {
                                l.uncertainty / error.abs()
                            },
                        }
                    }
                    Err(why) => {
                        watch.warning(&format!("{name}, margin {margin}: refused: {why}"));
                        GenericCoverageCase {
                            shape: name.clone(),
                            grids,
                            margin,
                            shift_x: shift.0,
                            shift_y: shift.1,
                            refused: true,
                            f_ad_bar_grid: own,
                            f_ad_bar: f64::NAN,
                            uncertainty: f64::NAN,
                            order: f64::NAN,
                            order_estimated: false,
                            reference,
                            reference_uncertainty,
                            error: f64::NAN,
                            held: false,
                            width_over_error: f64::NAN,
                        }
                    }
                };
                cases.push(case);
            }
        }
    }
    let mut summary: Vec<CoverageSummary> = req
        .scenes
        .iter()
        .filter_map(|(name, _, _)| {
            let mine: Vec<&GenericCoverageCase> =
                cases.iter().filter(|c| &c.shape == name).collect();
            summarise_generic(name, &mine)
        })
        .collect();
    summary.extend(summarise_generic("all", &cases.iter().collect::<Vec<_>>()));
    crate::output::file::write_csv(&csv, None, &cases).map_err(write_error(OUT))?;
    crate::output::file::write_csv(&summary_csv, None, &summary).map_err(write_error(OUT))?;
    Ok(GenericCoverageDone {
        cases,
        summary,
        csv,
        summary_csv,
    })
}

/// The summary line of generic cases (`None` if there are none): as [`summarise`], a refused
/// case counted as not held and left out of the widths.
pub fn summarise_generic(name: &str, cases: &[&GenericCoverageCase]) -> Option<CoverageSummary> {
    if cases.is_empty() {
        return None;
    }
    let answered: Vec<CoverageCase> = cases
        .iter()
        .filter(|c| !c.refused)
        .map(|c| CoverageCase {
            ratio: 1.0,
            grid: c.grids.clone(),
            margin: c.margin,
            runs: 1,
            variant: "fixed",
            mesh_angle_deg: 0.0,
            apex_offset_x: c.shift_x,
            apex_offset_y: c.shift_y,
            n_d: None,
            f_ad_bar_grid: c.f_ad_bar_grid,
            f_ad_bar: c.f_ad_bar,
            uncertainty: c.uncertainty,
            reference: c.reference,
            reference_uncertainty: c.reference_uncertainty,
            error: c.error,
            held: c.held,
            width_over_error: c.width_over_error,
            c_bar_at_min: None,
            c_bar_uncertainty: None,
            c_bar_reference: None,
            c_bar_reference_uncertainty: None,
            c_bar_held: None,
            d_bar_at_min: None,
            d_bar_uncertainty: None,
            d_bar_reference: None,
            d_bar_reference_uncertainty: None,
            d_bar_held: None,
        })
        .collect();
    let refs: Vec<&CoverageCase> = answered.iter().collect();
    let mut s = summarise(name, &refs).unwrap_or(CoverageSummary {
        ratio: name.to_string(),
        cases: 0,
        held: 0,
        held_fraction: 0.0,
        median_width_over_error: f64::NAN,
        rms_error_over_sd: f64::NAN,
        half_width_min: f64::NAN,
        half_width_max: f64::NAN,
        position_cases: 0,
        c_bar_held: 0,
        d_bar_held: 0,
    });
    s.cases = cases.len();
    s.held_fraction = s.held as f64 / s.cases as f64;
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(error: f64, uncertainty: f64) -> CoverageCase {
        CoverageCase {
            ratio: 1.0,
            grid: "64×64".into(),
            margin: 0.08,
            runs: 1,
            variant: "fixed",
            mesh_angle_deg: 0.0,
            apex_offset_x: 0.0,
            apex_offset_y: 0.0,
            n_d: Some(30.0),
            f_ad_bar_grid: 0.53,
            f_ad_bar: 0.5 + error,
            uncertainty,
            reference: 0.5,
            reference_uncertainty: 0.0,
            error,
            held: error.abs() <= uncertainty,
            width_over_error: uncertainty / error.abs(),
            c_bar_at_min: Some(0.8),
            c_bar_uncertainty: Some(0.05),
            c_bar_reference: Some(0.79),
            c_bar_reference_uncertainty: Some(0.0),
            c_bar_held: Some(true),
            d_bar_at_min: None,
            d_bar_uncertainty: None,
            d_bar_reference: None,
            d_bar_reference_uncertainty: None,
            d_bar_held: None,
        }
    }

    #[test]
    fn the_summary_counts_held_cases_and_takes_the_median_ratio() {
        let cases = [case(0.001, 0.004), case(-0.003, 0.004), case(0.005, 0.004)];
        let refs: Vec<&CoverageCase> = cases.iter().collect();
        let s = summarise("1", &refs).unwrap();
        assert_eq!((s.cases, s.held), (3, 2));
        assert_eq!((s.position_cases, s.c_bar_held, s.d_bar_held), (3, 3, 0));
        assert!((s.median_width_over_error - 0.004 / 0.003).abs() < 1e-12);
        let rms = ((0.25f64 + 2.25 + 6.25) / 3.0).sqrt();
        assert!((s.rms_error_over_sd - rms).abs() < 1e-12);
        assert!(summarise("none", &[]).is_none());
    }

    #[test]
    fn a_position_is_held_within_its_half_width_and_its_reference_s() {
        let e = |value, uncertainty| Some(estimate::Estimate { value, uncertainty });
        assert_eq!(
            PositionCheck::of(e(0.80, 0.011), Some((0.79, 0.0))).held,
            Some(true)
        );
        assert_eq!(
            PositionCheck::of(e(0.80, 0.005), Some((0.79, 0.004))).held,
            Some(false)
        );
        assert_eq!(
            PositionCheck::of(e(0.80, 0.005), Some((0.79, 0.006))).held,
            Some(true)
        );
        assert_eq!(PositionCheck::of(None, Some((0.79, 0.0))).held, None);
        assert_eq!(PositionCheck::of(e(0.8, 0.1), None).reference, None);
    }

    #[test]
    fn a_run_s_advice_is_given_in_coverage_s_flags() {
        use crate::solver::cg::CgEnd;
        use crate::solver::SolverError;
        let shown = |e: SolverError| {
            let e = in_coverage_words(failed(format!("r1-n16: {e}")));
            words::flags(&e.to_string())
        };
        // A contact at the domain's edge: the solver's advice (a larger margin or a smaller
        // first contact) in what coverage can change.
        let e = shown(SolverError::ContactAtEdge {
            d_bar: 2.25,
            elements: 8,
        });
        assert!(e.contains("use larger --margins or finer --grids"), "{e}");
        assert!(
            !e.contains("--margin ") && !e.contains("--start-radius") && !e.contains("defaults"),
            "{e}"
        );
        // Advice that names parameters coverage leaves at their defaults says so, each once.
        let e = shown(SolverError::CgNotConverged {
            d_bar: 1.5,
            first: CgEnd::IterationLimit,
            end: CgEnd::IterationLimit,
            residual: 1e-3,
            iterations: 10_000,
            tolerance: 1e-8,
            accept: 1e-5,
        });
        assert!(
            e.contains(
                "the defaults of --cg-max-iterations, --cg-tolerance, --cg-accept, \
                 --preconditioner, which it does not set"
            ),
            "{e}"
        );
        assert!(!e.contains('⟨'), "{e}");
    }

    #[test]
    fn case_grids_lie_two_levels_below_the_ladder_and_not_below_its_start() {
        assert_eq!(case_grids(Some(&[256, 512, 1024])), vec![256]);
        assert_eq!(case_grids(Some(&[128, 256, 512, 1024])), vec![128, 256]);
        assert_eq!(case_grids(Some(&[64, 128, 256, 512])), vec![64, 128]);
        assert_eq!(case_grids(None), SPHERE_GRIDS.to_vec());
    }
}
