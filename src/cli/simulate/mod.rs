//! `jkrbem simulate`: one scene's pull-off (one grid, several extrapolated, or the grids an
//! accuracy needs). Parses the flags into a request for [`jkrbem::run::simulate`] and prints
//! what comes back.

use super::progress::Progress;
use super::stdout::{claim_stdout, is_stdout, write_stdout_bytes, Channel};
use super::{run_error, CliError};
use jkrbem::model::{Measure, ModelOptions, Onsets};
use jkrbem::output::states_csv::states_csv_bytes;
use jkrbem::run::open::BackendRequest;
use jkrbem::run::simulate::{failure_error, simulate, Mode, SimulateRequest, Sink};
use jkrbem::scene::Scene;
use std::path::PathBuf;

mod args;
mod indenter;

pub use args::Args;
pub use indenter::IndenterKind;

/// The accuracy of a bare `simulate` (relative): the adhesive force to 2 %.
pub use jkrbem::run::simulate::DEFAULT_ACCURACY;

/// Nx of a one-grid run that names no --grid.
pub const DEFAULT_GRID: usize = 256;

/// Which file of `simulate` goes to standard output (named `-`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnStdout {
    /// The states CSV (`--out -`).
    States,
    /// The summary JSON (`--summary -`).
    Summary,
}

impl Args {
    /// The scene of these arguments.
    pub fn scene(&self) -> Result<Scene, CliError> {
        use IndenterKind::*;
        let (e, w) = (self.e_star, self.work_of_adhesion);
        self.shape.refuse_foreign(&[
            ("--ratio", self.ratio.is_some(), &[Ellipsoid]),
            ("--r1", self.r1.is_some(), &[Ellipsoid]),
            ("--r2", self.r2.is_some(), &[Ellipsoid]),
            (
                "--start-radius",
                self.start_radius.is_some(),
                &[Ellipsoid, PowerLaw, HeightMap],
            ),
        ])?;
        if let (Some(_), Some(_)) = (self.ratio, self.r1) {
            return Err(super::input(
                "--ratio and --r1 both set R1/R2: give one (--r1 with --r2, or --ratio)",
            ));
        }
        let r2 = self.r2.unwrap_or(1.0);
        match (self.shape.other_shape()?, self.r1) {
            (None, Some(r1)) => Scene::new(r1, r2, e, w),
            (None, None) => Scene::from_ratio(self.ratio.unwrap_or(5.0), r2, e, w),
            (Some(shape), _) => Scene::with_indenter(shape, e, w),
        }
        .map_err(super::input)
    }

    /// The request these arguments make.
    pub fn request(&self) -> Result<SimulateRequest, CliError> {
        if self.apex_offset.len() != 2 {
            return Err(super::input(
                "--apex-offset takes two fractions of an element, along x and y: e.g. 0.25,0.5",
            ));
        }
        // Only the ellipsoid has a convergence law: the other shapes run one grid.
        let one_grid = self.shape.indenter != IndenterKind::Ellipsoid
            || self.grid.is_some()
            || self.grid_y.is_some()
            || self.steps.is_some()
            || self.onsets.is_some()
            || self.measure.is_some()
            || self.regrid
            || self.final_d.is_some();
        let extrapolate = self.extrapolate.then(|| self.extrapolate_grids.clone());
        let mode = Mode::choose(self.accuracy, extrapolate, one_grid);
        if self.time_limit.is_some() && !matches!(mode, Mode::Accuracy(_)) {
            return Err(super::input(
                "--time-limit applies to an --accuracy run (the default without --grid and \
                 the other one-grid flags, or --accuracy given)",
            ));
        }
        Ok(SimulateRequest {
            scene: self.scene()?,
            options: self.options(),
            backend: BackendRequest {
                kind: self.backend,
                convolution: self.convolution,
                check_every: self.cg_check_every,
            },
            mode,
            sink: self.sink()?,
            fields: self.fields.clone(),
            time_limit: self.time_limit,
        })
    }

    /// Where the states and the summary go: files, except one named `-` (standard output),
    /// which the command writes itself once the run ends.
    fn sink(&self) -> Result<Sink, CliError> {
        let on_stdout = self.stdout_claim()?;
        let file = |p: &Option<PathBuf>| p.clone().filter(|p| !is_stdout(p));
        Ok(match on_stdout {
            Some(OnStdout::States) => Sink::OneRunReturned {
                summary: file(&self.summary),
            },
            _ => Sink::Files {
                out: self.out.clone(),
                summary: file(&self.summary),
            },
        })
    }

    /// Which flag's file goes to standard output (`-`), if any (at most one may).
    pub fn stdout_claim(&self) -> Result<Option<OnStdout>, CliError> {
        claim_stdout(&[
            (OnStdout::States, "--out", self.out.as_deref()),
            (OnStdout::Summary, "--summary", self.summary.as_deref()),
        ])
    }

    /// The model options of these arguments.
    pub fn options(&self) -> ModelOptions {
        let nx = self.grid.unwrap_or(DEFAULT_GRID);
        ModelOptions {
            nx,
            ny: self.grid_y,
            start_radius_bar: self
                .start_radius
                .unwrap_or(ModelOptions::default().start_radius_bar),
            steps: self.steps.unwrap_or(jkrbem::model::default_steps(
                self.measure.unwrap_or(Measure::Curve),
                self.onsets.unwrap_or(Onsets::NearMinimum),
                self.regrid,
            )),
            final_d_bar: self.final_d,
            margin: self.margin.unwrap_or(jkrbem::model::default_margin(nx)),
            mesh_angle_deg: self.mesh_angle,
            // Two values, checked by the model ([0, 1) each); a wrong count gives NaN there.
            apex_offset: match self.apex_offset[..] {
                [x, y] => (x, y),
                _ => (f64::NAN, f64::NAN),
            },
            cg_tolerance: self.cg_tolerance,
            cg_max_iterations: self.cg_max_iterations,
            cg_accept: self.cg_accept,
            preconditioner: self.preconditioner,
            onsets: self.onsets.unwrap_or(Onsets::NearMinimum),
            loose_rounds: !self.exact_cascade,
            measure: self.measure.unwrap_or(Measure::Curve),
            regrid: self.regrid,
            ..ModelOptions::default()
        }
    }
}

/// Run `jkrbem simulate`.
pub fn run(args: Args) -> Result<(), CliError> {
    // The height map is read: no output may be that file (checked when they are claimed).
    if let (IndenterKind::HeightMap, Some(map)) = (args.shape.indenter, &args.shape.height_map) {
        jkrbem::output::file::note_input(map, "--height-map");
    }
    let request = args.request()?;
    let on_stdout = args.stdout_claim()?;
    let progress = Progress::new();
    let done = simulate(&request, &progress).map_err(run_error)?;
    if let Some(plan) = &done.plan {
        errln!("jkrbem: {plan}");
    }
    // The results on standard output: the summary's text, or the file asked for there (then
    // the text goes to standard error). The warnings go to standard error after it.
    let text = Channel::beside(on_stdout.is_some());
    match on_stdout {
        Some(OnStdout::Summary) => write_stdout_bytes(done.summary.to_json().as_bytes()),
        Some(OnStdout::States) => {
            for run in &done.runs {
                write_stdout_bytes(&states_csv_bytes(&run.states, run.onsets.name()));
            }
        }
        None => {}
    }
    text.print(&done.summary.to_text());
    for line in done.summary.warning_lines() {
        errln!("{line}");
    }
    for path in &done.states {
        text.line(&format!("states written to {}", path.display()));
    }
    for path in &done.field_files {
        text.line(&format!("fields written to {}", path.display()));
    }
    failure_error(done.failure).map_err(run_error)
}
