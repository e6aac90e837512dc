//! Timing the backends: per backend and grid, the convolution, one CG iteration and (on small
//! grids) a whole pull-off, optionally the GPU's kernels one by one; the rows are written as
//! CSV and a chart. The timing itself is [`crate::bench`].

#[cfg(feature = "gpu")]
use crate::backend::select::AnyBackend;
use crate::backend::select::{self, BackendKind, Opened, Precision};
use crate::bench::{self, BenchOptions, GridProfile, Measurement, PulloffProfile};
use crate::model::{default_steps, Measure, Model, ModelOptions, Onsets, MAX_GRID, MIN_GRID};
use crate::output::bench::{timing_chart, write_csv, BenchRow};
use crate::output::figure::FigureFormats;
#[cfg(feature = "gpu")]
use crate::output::profile::{self, ProfileRow};
use crate::params::{
    BACKENDS, CG_ITERATIONS, GRIDS, OUT, PRECISIONS, PROFILE, PULLOFF_MAX_GRID, REPEATS,
};
use crate::scene::Scene;
use crate::session::claim::{named, write_error, Outputs};
use crate::session::open::backend_error;
use crate::session::provenance::word;
use crate::session::Watch;
use crate::session::{input, refuse, RunError};
use std::path::PathBuf;

pub use crate::params::limits::MAX_REPEATS;
pub use crate::params::limits::MAX_TIMED_CG_ITERATIONS;

/// A request to time the backends.
#[derive(Debug, Clone)]
pub struct BenchRequest {
    /// Backends to time (cpu, gpu); empty: cpu, plus gpu when it opens.
    pub backends: Vec<BackendKind>,
    /// The arithmetic each backend is timed in (auto, f64, f32); empty: auto, the backend's
    /// own. A backend that has not one of them (the GPU has no f64) skips it.
    pub precisions: Vec<Precision>,
    /// Grids Nx (powers of two ≥ 16; sorted and deduplicated here).
    pub grids: Vec<usize>,
    /// Time a whole pull-off only on grids up to this Nx (0: none).
    pub pulloff_max_grid: usize,
    /// What the pull-off computes: the whole curve, or only the adhesive force (its default
    /// load steps then [`crate::model::MEASURE_STEPS`], as `simulate` takes them).
    pub measure: Measure,
    /// Timed samples per quantity (median reported).
    pub repeats: usize,
    /// CG iterations per timed solve.
    pub cg_iterations: usize,
    /// R1/R2 of the scene.
    pub ratio: f64,
    /// c̄0 of the initial contact.
    pub start_radius: f64,
    /// Free margin around the initial contact (relative; `None`: each grid's
    /// [`crate::model::default_margin`]).
    pub margin: Option<f64>,
    /// Also profile the GPU's kernels.
    pub profile: bool,
    /// Folder for bench.csv, bench.svg (and profile.csv).
    pub out: PathBuf,
    /// The formats of the chart, with its `bench.plot.csv`.
    pub figures: FigureFormats,
}

/// What the timing produced.
pub struct BenchDone {
    /// One row per backend and grid measured.
    pub rows: Vec<BenchRow>,
    /// The measurements behind the rows, in the same order.
    pub measured: Vec<Measurement>,
    /// The kernel profiles (with `profile`).
    pub profiles: Vec<GridProfile>,
    /// The whole pull-offs' profiles (with `profile`, on the GPU, where a pull-off ran).
    pub pulloff_profiles: Vec<PulloffProfile>,
    /// The files written.
    pub files: Vec<PathBuf>,
    /// What failed or stopped early, one line each.
    pub problems: Vec<String>,
}

/// The parameters and values that name a backend in an arithmetic ("⟨backends⟩ cpu", and
/// " ⟨precisions⟩ f32" unless it is the backend's own).
fn flag(kind: BackendKind, precision: Precision) -> String {
    let backend = format!("{BACKENDS} {}", word(kind));
    match precision {
        Precision::Auto => backend,
        _ => format!("{backend} {PRECISIONS} {}", word(precision)),
    }
}

/// The grids asked for, sorted and without repeats; refused unless all are powers of two from
/// 16 to 65536.
fn grids(args: &BenchRequest) -> Result<Vec<usize>, RunError> {
    if args.grids.is_empty() {
        return Err(refuse(
            GRIDS,
            format!("{GRIDS} is empty: give e.g. {GRIDS} 64,128,256"),
        ));
    }
    if let Some(bad) = args
        .grids
        .iter()
        .find(|&&g| !(MIN_GRID..=MAX_GRID).contains(&g) || !g.is_power_of_two())
    {
        return Err(refuse(
            GRIDS,
            format!(
                "{GRIDS} {bad} is invalid: every grid must be a power of two from {MIN_GRID} to \
             {MAX_GRID} (e.g. {GRIDS} 64,128,256)"
            ),
        ));
    }
    let mut g = args.grids.clone();
    g.sort_unstable();
    g.dedup();
    Ok(g)
}

/// Open `which` in `precision` for `model`'s grid.
fn open(which: BackendKind, precision: Precision, model: &Model) -> Result<Opened, RunError> {
    let named = |m: String| format!("{}: {m}", flag(which, precision));
    select::open_in(which, precision, &model.grid_setup(), false)
        .map_err(|e| backend_error(e).map_message(named))
}

/// Check the request, claim its outputs, open every backend, time every grid and write the
/// rows. `watch` receives progress notes.
pub fn bench(args: &BenchRequest, watch: &dyn Watch) -> Result<BenchDone, RunError> {
    let grids = grids(args)?;
    let (scene, models) = bench_models(args, &grids)?;
    let csv = args.out.join("bench.csv");
    let svg = args.out.join("bench.svg");
    let profile_csv = args.out.join("profile.csv");
    let pulloff_profile_csv = args.out.join("pulloff-profile.csv");
    let mut targets = vec![csv.clone()];
    targets.extend(args.figures.files(&svg));
    if args.profile {
        if cfg!(not(feature = "gpu")) {
            return Err(refuse(
                PROFILE,
                format!(
                "{PROFILE} times GPU kernels, and this jkrbem was built without the `gpu` feature"
            ),
            ));
        }
        targets.push(profile_csv.clone());
        if args.pulloff_max_grid > 0 {
            targets.push(pulloff_profile_csv.clone());
        }
    }
    let _claimed = Outputs::claim(&named(OUT, &targets))?;

    // Open every backend on the first grid before any work, so a missing one is refused
    // up front; the default takes the GPU only if it opens.
    let mut backends = open_backends(args, &models[0], watch)?;
    let mut got = Collected::default();
    for (which, precision, first) in &mut backends {
        for (k, (model, &grid)) in models.iter().zip(&grids).enumerate() {
            let opened = match if k == 0 { first.take() } else { None } {
                Some(o) => o,
                None => match open(*which, *precision, model) {
                    Ok(o) => o,
                    Err(e) => {
                        watch.note(&format!("bench: skipped grid {grid}: {e}"));
                        got.problems.push(format!("grid {grid}: {e}"));
                        continue;
                    }
                },
            };
            measure_one(
                args,
                (*which, *precision),
                model,
                grid,
                opened,
                watch,
                &mut got,
            );
        }
    }
    let Collected {
        rows,
        #[cfg(feature = "gpu")]
        profile_rows,
        profiles,
        pulloff_profiles,
        measured,
        problems,
    } = got;

    write_csv(&csv, &rows).map_err(write_error(OUT))?;
    #[cfg_attr(not(feature = "gpu"), allow(unused_mut))]
    let mut files = vec![csv.clone()];
    files.extend(args.figures.files(&svg));
    #[cfg(feature = "gpu")]
    if args.profile {
        profile::write_csv(&profile_csv, &profile_rows).map_err(write_error(OUT))?;
        files.push(profile_csv.clone());
        if args.pulloff_max_grid > 0 {
            let rows: Vec<_> = pulloff_profiles
                .iter()
                .flat_map(profile::pulloff_rows)
                .collect();
            profile::write_pulloff_csv(&pulloff_profile_csv, &rows).map_err(write_error(OUT))?;
            files.push(pulloff_profile_csv.clone());
        }
    }
    let title = format!(
        "jkrbem bench: R1/R2 = {}, medians of {} samples",
        scene.ratio(),
        args.repeats
    );
    timing_chart(&rows, &title)
        .write_figure(&svg, args.figures)
        .map_err(write_error(OUT))?;
    Ok(BenchDone {
        rows,
        measured,
        profiles,
        pulloff_profiles,
        files,
        problems,
    })
}

/// The scene and one model per grid, every parameter checked and the largest grid's memory
/// too.
fn bench_models(args: &BenchRequest, grids: &[usize]) -> Result<(Scene, Vec<Model>), RunError> {
    if !(1..=MAX_REPEATS).contains(&args.repeats) {
        return Err(refuse(
            REPEATS,
            format!(
                "{REPEATS} {} is invalid: give 1 to {MAX_REPEATS}",
                args.repeats
            ),
        ));
    }
    if !(1..=MAX_TIMED_CG_ITERATIONS).contains(&args.cg_iterations) {
        return Err(refuse(
            CG_ITERATIONS,
            format!(
                "{CG_ITERATIONS} {} is invalid: give 1 to {MAX_TIMED_CG_ITERATIONS}",
                args.cg_iterations
            ),
        ));
    }
    if args.pulloff_max_grid > MAX_GRID {
        return Err(refuse(
            PULLOFF_MAX_GRID,
            format!(
                "{PULLOFF_MAX_GRID} {} is invalid: give 0 (no pull-off) to {MAX_GRID}",
                args.pulloff_max_grid
            ),
        ));
    }
    let scene = Scene::from_ratio(args.ratio, 1.0, 1.0, 1.0).map_err(input)?;
    let models = grids
        .iter()
        .map(|&nx| {
            let opt = ModelOptions {
                nx,
                measure: args.measure,
                steps: default_steps(args.measure, Onsets::NearMinimum, false),
                start_radius_bar: args.start_radius,
                margin: args.margin.unwrap_or(crate::model::default_margin(nx)),
                ..ModelOptions::default()
            };
            Model::build(&scene, &opt).map_err(input)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let refs: Vec<&Model> = models.iter().collect();
    crate::plan::check_memory(&refs, 1, GRIDS).map_err(input)?;
    Ok((scene, models))
}

/// What the measurements gave so far.
#[derive(Default)]
struct Collected {
    rows: Vec<BenchRow>,
    #[cfg(feature = "gpu")]
    profile_rows: Vec<ProfileRow>,
    profiles: Vec<GridProfile>,
    pulloff_profiles: Vec<PulloffProfile>,
    measured: Vec<Measurement>,
    problems: Vec<String>,
}

/// A backend to time, in an arithmetic, and its opening on the first grid (taken by it).
type ToTime = (BackendKind, Precision, Option<Opened>);

/// The backends asked for (both by default) in each arithmetic asked for, each opened on the
/// first grid; a default backend that does not open is skipped with a note, one asked for
/// that does not is refused; an arithmetic a backend has not (f64 on the GPU) is skipped with
/// a note, unless nothing is left.
fn open_backends(
    args: &BenchRequest,
    first: &Model,
    watch: &dyn Watch,
) -> Result<Vec<ToTime>, RunError> {
    let mut backends: Vec<ToTime> = Vec::new();
    let requested = if args.backends.is_empty() {
        vec![BackendKind::Cpu, BackendKind::Gpu]
    } else {
        args.backends.clone()
    };
    let precisions = if args.precisions.is_empty() {
        vec![Precision::Auto]
    } else {
        args.precisions.clone()
    };
    let mut refused = None;
    for which in requested {
        for &precision in &precisions {
            if backends
                .iter()
                .any(|(b, p, _)| *b == which && *p == precision)
            {
                continue;
            }
            if let Some(why) = precision.refusal(which) {
                let why = format!("{}: {why}", flag(which, precision));
                watch.note(&format!("bench: skipped {why}"));
                refused.get_or_insert(why);
                continue;
            }
            match open(which, precision, first) {
                Ok(o) => backends.push((which, precision, Some(o))),
                Err(e) if args.backends.is_empty() => {
                    watch.note(&format!("bench: {} skipped: {e}", flag(which, precision)));
                }
                Err(e) => return Err(e),
            }
        }
    }
    match (backends.is_empty(), refused) {
        (true, Some(why)) => Err(input(why)),
        _ => Ok(backends),
    }
}

/// Measure one backend on one grid (and profile its kernels with `--profile`), adding the
/// row, the measurement and any problem to `got`.
fn measure_one(
    args: &BenchRequest,
    (which, precision): (BackendKind, Precision),
    model: &Model,
    grid: usize,
    opened: Opened,
    watch: &dyn Watch,
    got: &mut Collected,
) {
    let mut any = opened.backend;
    let device = any.device_summary();
    // The pull-off reads CG's residual at the backend's own interval, as `simulate`'s does
    // (every iteration on the CPU, every 8 on the GPU).
    let model = &Model {
        cg: crate::model::CgSettings {
            check_every: any.check_every(),
            ..model.cg
        },
        ..model.clone()
    };
    let options = BenchOptions {
        repeats: args.repeats,
        cg_iterations: args.cg_iterations,
        pulloff: grid <= args.pulloff_max_grid,
    };
    let label = format!("{} {}×{}", flag(which, precision), model.nx, model.ny);
    watch.note(&format!("bench: {label}: {}", opened.note));
    let mut progress = |what: &str| watch.note(&format!("bench: {label}: timing {what}"));
    let result = crate::with_backend!(&mut any, b =>
        bench::measure(b, model, &options, &mut progress));
    #[cfg(feature = "gpu")]
    if let (true, AnyBackend::Gpu(g), Ok(_)) = (args.profile, &mut any, &result) {
        watch.note(&format!("bench: {label}: profiling the kernels"));
        match bench::profile_cg_iteration(g, model, args.cg_iterations.max(20)) {
            Ok(p) => {
                got.profile_rows
                    .extend(profile::rows(grid, model.nx, model.ny, &p));
                got.profiles.push(GridProfile {
                    label: label.clone(),
                    kernels: p,
                    floor_bytes: crate::backend::gpu::traffic::cg_iteration_floor(
                        model.nx, model.ny, true,
                    ) as f64,
                });
            }
            Err(e) => {
                watch.note(&format!("bench: {label}: no profile: {e}"));
                got.problems.push(format!("{label}: no profile: {e}"));
            }
        }
        let timed = result.as_ref().ok().and_then(|m| m.pulloff.as_ref());
        if let Some(timed) = timed.filter(|t| t.error.is_none()) {
            watch.note(&format!("bench: {label}: profiling a whole pull-off"));
            match bench::profile_pulloff(g, model, timed, label.clone()) {
                Ok(p) => got.pulloff_profiles.push(p),
                Err(e) => {
                    watch.note(&format!("bench: {label}: no pull-off profile: {e}"));
                    got.problems
                        .push(format!("{label}: no pull-off profile: {e}"));
                }
            }
        }
    }
    match result {
        Ok(m) => {
            if let Some(e) = m.pulloff.as_ref().and_then(|p| p.error.as_ref()) {
                watch.note(&format!("bench: {label}: the pull-off stopped early: {e}"));
                got.problems
                    .push(format!("{label}: the pull-off stopped early: {e}"));
            }
            got.rows.push(BenchRow::new(&m, &device, grid));
            got.measured.push(m);
        }
        Err(e) => {
            watch.note(&format!("bench: {label}: failed: {e}"));
            got.problems.push(format!("{label}: {e}"));
        }
    }
}
