//! A simulation as a typed value: every parameter of [`params::SPECS`] as a field, defaults
//! filled from the schema, checked once, round-tripping through JSON. Both front ends (and a
//! batch's table) build one from the values they were given ([`Request::from_values`]) and
//! turn it into the session's [`SimulateRequest`] ([`Request::simulate_request`]): the choice of
//! one grid, several or an accuracy, the scene, the model options and the height map's reading
//! happen here, once.

use super::open::{BackendRequest, Convolution};
use super::simulate::{Mode, SimulateRequest, Sink};
use super::{input, refuse, RunError};
use crate::analysis::fields::FieldChoice;
use crate::backend::select::{BackendKind, Precision};
use crate::model::{Measure, ModelOptions, Onsets, Preload};
use crate::output::digest::InputFile;
use crate::output::figure::{FigureFormat, FigureFormats};
use crate::params::{self, values, Fallback, Spec, SPECS};
use crate::params::{
    ACCURACY, CONVOLUTION, EXTRAPOLATE, EXTRAPOLATE_GRIDS, FINAL_D, GRID, GRID_Y, HEIGHT_MAP,
    INDENTER, MEASURE, ONSETS, PRELOAD_AREA, PRELOAD_DEPTH, PRELOAD_FORCE, R1, RATIO, REGRID,
    ROUGHNESS, SPACING, START_RADIUS, STEPS, TIME_LIMIT, WINDOW_X, WINDOW_Y,
};
use crate::scene::height_map::HeightMap;
use crate::scene::{Indenter, MeasuredSurface, RoughShape, Scene};
use crate::setup::Preconditioner;
use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

mod map_file;

pub use map_file::MapReads;

/// The indenter shapes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Shape {
    /// A cone h = r·cot α.
    Cone,
    /// h = x²/(2 R1) + y²/(2 R2).
    Ellipsoid,
    /// A flat cylindrical punch.
    FlatPunch,
    /// A measured (or generated) topography.
    HeightMap,
    /// Axisymmetric h = s·rⁿ.
    PowerLaw,
}

impl Shape {
    /// The name the schema gives it ("flat-punch").
    pub fn name(self) -> &'static str {
        match self {
            Shape::Cone => "cone",
            Shape::Ellipsoid => "ellipsoid",
            Shape::FlatPunch => "flat-punch",
            Shape::HeightMap => "height-map",
            Shape::PowerLaw => "power-law",
        }
    }
}

/// One simulation's request: each field is the parameter of the same name in
/// [`params::SPECS`] (its unit, range and default are there). `None`: chosen for the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
#[allow(missing_docs)]
pub struct Request {
    pub indenter: Shape,
    pub ratio: Option<f64>,
    pub r1: Option<f64>,
    pub r2: Option<f64>,
    pub e_star: f64,
    pub work_of_adhesion: f64,
    pub radius: Option<f64>,
    pub exponent: Option<f64>,
    pub scale: Option<f64>,
    pub half_angle: Option<f64>,
    pub height_map: Option<PathBuf>,
    pub spacing: Option<f64>,
    pub roughness: Option<PathBuf>,
    pub window_x: Option<[f64; 2]>,
    pub window_y: Option<[f64; 2]>,
    pub grid: Option<usize>,
    pub grid_y: Option<usize>,
    pub start_radius: Option<f64>,
    pub steps: Option<usize>,
    pub onsets: Option<Onsets>,
    pub measure: Option<Measure>,
    pub regrid: bool,
    pub final_d: Option<f64>,
    pub margin: Option<f64>,
    pub preload_depth: Option<f64>,
    pub preload_force: Option<f64>,
    pub preload_area: Option<f64>,
    pub mesh_angle: f64,
    pub apex_offset: [f64; 2],
    pub cg_tolerance: f64,
    pub cg_max_iterations: usize,
    pub cg_accept: f64,
    pub cg_check_every: Option<usize>,
    pub max_sweeps: usize,
    pub preconditioner: Preconditioner,
    pub exact_cascade: bool,
    pub backend: BackendKind,
    /// A request recorded before it existed ran in the backend's own arithmetic.
    #[serde(default)]
    pub precision: Precision,
    pub convolution: Convolution,
    pub extrapolate: bool,
    pub extrapolate_grids: Option<Vec<usize>>,
    pub accuracy: Option<f64>,
    /// Seconds.
    pub time_limit: Option<f64>,
    pub fields: String,
    /// The formats of the charts; a request recorded before it existed wrote SVG.
    #[serde(default = "svg_only")]
    pub figure_format: Vec<FigureFormat>,
    pub out: Option<PathBuf>,
    pub summary: Option<PathBuf>,
}

/// [`FigureFormats::SVG`] as a request's list.
fn svg_only() -> Vec<FigureFormat> {
    vec![FigureFormat::Svg]
}

/// Nx of a one-grid run that names no grid.
pub const DEFAULT_GRID: usize = 256;

/// The parameters of [`ONE_GRID`] that `r` gives, in that order.
fn one_grid_parameters(r: &Request) -> Vec<&'static Spec> {
    let given = [
        r.grid.is_some(),
        r.grid_y.is_some(),
        r.steps.is_some(),
        r.onsets.is_some(),
        r.measure.is_some(),
        r.regrid,
        r.final_d.is_some(),
    ];
    ONE_GRID
        .into_iter()
        .zip(given)
        .filter_map(|(spec, given)| given.then_some(spec))
        .collect()
}

/// The parameters that only a single grid takes (giving one runs one grid).
const ONE_GRID: [&Spec; 7] = [GRID, GRID_Y, STEPS, ONSETS, MEASURE, REGRID, FINAL_D];

impl Request {
    /// The request of these checked values (from [`values::checked`]), each parameter not
    /// given taking its schema default.
    pub fn from_values(mut given: Map<String, Value>) -> Result<Request, RunError> {
        for spec in SPECS {
            if given.contains_key(spec.name) {
                continue;
            }
            let v = match spec.fallback {
                Fallback::Value(text) => values::from_text(spec, text).map_err(input)?,
                Fallback::Chosen(_) => Value::Null,
            };
            given.insert(spec.name.to_string(), v);
        }
        serde_json::from_value(Value::Object(given))
            .map_err(|e| input(format!("the request does not fit its schema (a bug): {e}")))
    }

    /// The request of `given` texts by parameter name (a batch's row), checked.
    pub fn from_texts<'a>(
        given: impl IntoIterator<Item = (&'a str, &'a str)>,
    ) -> Result<Request, RunError> {
        let map = values::checked(SPECS, given, values::from_text).map_err(input)?;
        Request::from_values(map)
    }

    /// The request of `given` JSON values by parameter name (Python, a request file), checked.
    pub fn from_json<'a>(
        given: impl IntoIterator<Item = (&'a str, &'a Value)>,
    ) -> Result<Request, RunError> {
        Request::from_values(Request::check_json(given).map_err(input)?)
    }

    /// The checked values of `given` JSON values by parameter name, or the refusal (which says
    /// whether a value was of the wrong type: Python raises a TypeError for it).
    pub fn check_json<'a>(
        given: impl IntoIterator<Item = (&'a str, &'a Value)>,
    ) -> Result<Map<String, Value>, values::Refusal> {
        values::checked(SPECS, given, values::from_json)
    }

    /// The request as JSON (every parameter, defaults included): what provenance records.
    pub fn to_json(&self) -> Value {
        serde_json::to_value(self).unwrap_or(Value::Null)
    }

    /// Refuse a shape's parameter given with another indenter (it would be ignored).
    fn refuse_foreign(&self, map_given: bool, rough_given: bool) -> Result<(), RunError> {
        use params::{EXPONENT, HALF_ANGLE, R2, RADIUS, SCALE};
        use Shape::*;
        let rough = self.roughness.is_some() || rough_given;
        let given: [(&Spec, bool, &[Shape]); 13] = [
            (RATIO, self.ratio.is_some(), &[Ellipsoid]),
            (R1, self.r1.is_some(), &[Ellipsoid]),
            (R2, self.r2.is_some(), &[Ellipsoid]),
            (
                START_RADIUS,
                self.start_radius.is_some(),
                &[Ellipsoid, PowerLaw, Cone, HeightMap],
            ),
            (RADIUS, self.radius.is_some(), &[FlatPunch]),
            (EXPONENT, self.exponent.is_some(), &[PowerLaw]),
            (SCALE, self.scale.is_some(), &[PowerLaw]),
            (HALF_ANGLE, self.half_angle.is_some(), &[Cone]),
            (
                HEIGHT_MAP,
                self.height_map.is_some() || map_given,
                &[HeightMap],
            ),
            (SPACING, self.spacing.is_some() && !rough, &[HeightMap]),
            (ROUGHNESS, rough, &[Ellipsoid, PowerLaw, FlatPunch, Cone]),
            (WINDOW_X, self.window_x.is_some(), &[HeightMap]),
            (WINDOW_Y, self.window_y.is_some(), &[HeightMap]),
        ];
        for (spec, given, shapes) in given {
            if given && !shapes.contains(&self.indenter) {
                let names: Vec<&str> = shapes.iter().map(|s| s.name()).collect();
                return Err(refuse(
                    spec,
                    format!(
                        "{spec} is for {INDENTER} {}, not {} (it would be ignored): leave it out, \
                     or give the indenter it is for",
                        names.join(" or "),
                        self.indenter.name()
                    ),
                ));
            }
        }
        let preloads = [
            (PRELOAD_DEPTH, self.preload_depth.is_some()),
            (PRELOAD_FORCE, self.preload_force.is_some()),
            (PRELOAD_AREA, self.preload_area.is_some()),
        ];
        let named: Vec<String> = preloads
            .iter()
            .filter(|(_, given)| *given)
            .map(|(spec, _)| spec.to_string())
            .collect();
        if named.len() > 1 {
            return Err(input(format!(
                "{} each set where the loading stops: give one",
                named.join(" and ")
            )));
        }
        if self.ratio.is_some() && self.r1.is_some() {
            return Err(refuse(
                RATIO,
                format!(
                    "{RATIO} and {R1} both set R1/R2: give one ({R1} with {}, or {RATIO})",
                    params::R2
                ),
            ));
        }
        Ok(())
    }

    /// The scene: the indenter and the materials. A height map (or the roughness added to a
    /// base shape) is read from its file, or is `map` where the caller holds it in memory
    /// (Python's array).
    pub fn scene(&self, map: Option<HeightMap>) -> Result<Scene, RunError> {
        self.scene_read(map).map(|(scene, _)| scene)
    }

    /// Like [`Request::scene`], with the record of every file read for it (none where the
    /// maps are in memory).
    pub fn scene_read(&self, map: Option<HeightMap>) -> Result<(Scene, Vec<InputFile>), RunError> {
        self.scene_sharing(map, &mut MapReads::default())
    }

    /// Like [`Request::scene_read`], its files read through `reads`: a file another request
    /// read there is not read again, and its map is shared.
    pub fn scene_sharing(
        &self,
        map: Option<HeightMap>,
        reads: &mut MapReads,
    ) -> Result<(Scene, Vec<InputFile>), RunError> {
        let mut read = Vec::new();
        let is_map = self.indenter == Shape::HeightMap;
        let (map, rough_map) = if is_map { (map, None) } else { (None, map) };
        self.refuse_foreign(map.is_some(), rough_map.is_some())?;
        let (e, w) = (self.e_star, self.work_of_adhesion);
        let r2 = self.r2.unwrap_or(1.0);
        let shape = match self.indenter {
            Shape::Ellipsoid => {
                let smooth = match self.r1 {
                    Some(r1) => Scene::new(r1, r2, e, w),
                    None => Scene::from_ratio(self.ratio.unwrap_or(5.0), r2, e, w),
                }
                .map_err(input)?;
                smooth.indenter
            }
            Shape::FlatPunch => Indenter::flat_punch(self.radius.unwrap_or(1.0)),
            Shape::PowerLaw => Indenter::power_law(
                self.exponent.unwrap_or(2.0),
                self.scale.unwrap_or(crate::scene::DEFAULT_POWER_LAW_SCALE),
            ),
            Shape::Cone => Indenter::cone(
                self.half_angle
                    .unwrap_or(crate::scene::indenter::DEFAULT_HALF_ANGLE),
            ),
            Shape::HeightMap => self.height_map_indenter(map, reads, &mut read)?,
        };
        let shape = match self.roughness_map(rough_map, reads, &mut read)? {
            Some((map, name)) => {
                let base = shape.checked().map_err(input)?;
                Indenter::Rough(Arc::new(RoughShape::new(base, map, &name).map_err(input)?))
            }
            None => shape,
        };
        Ok((Scene::with_indenter(shape, e, w).map_err(input)?, read))
    }

    /// The roughness to add to the base shape, with its name: `map` if given, else read
    /// from [`Request::roughness`] through `reads` (its record added to `read`); `None` for a
    /// smooth shape.
    fn roughness_map(
        &self,
        map: Option<HeightMap>,
        reads: &mut MapReads,
        read: &mut Vec<InputFile>,
    ) -> Result<Option<(HeightMap, String)>, RunError> {
        match (map, &self.roughness) {
            (Some(map), _) => Ok(Some((map, "the array given".to_string()))),
            (None, Some(path)) => {
                let Some(spacing) = self.spacing else {
                    return Err(refuse(
                        ROUGHNESS,
                        format!("{ROUGHNESS} needs {SPACING} (the nodes' spacing, length)"),
                    ));
                };
                let name = crate::text::printable(&path.display().to_string(), 200);
                let (map, file) = reads.read(path, &name, spacing, ROUGHNESS)?;
                read.push(file);
                Ok(Some((map, name)))
            }
            (None, None) => Ok(None),
        }
    }

    /// The measured surface: `map` if given, else read from [`Request::height_map`] through
    /// `reads` (its record added to `read`); placed on its period under the periodic
    /// convolution, else on the window asked for, else at its apex where it has one, else on
    /// the whole map.
    fn height_map_indenter(
        &self,
        map: Option<HeightMap>,
        reads: &mut MapReads,
        read: &mut Vec<InputFile>,
    ) -> Result<Indenter, RunError> {
        let (map, name) = match (map, &self.height_map) {
            (Some(map), _) => (map, "the array given".to_string()),
            (None, Some(path)) => {
                let Some(spacing) = self.spacing else {
                    return Err(refuse(
                        INDENTER,
                        format!(
                            "{INDENTER} height-map needs {HEIGHT_MAP} and {SPACING} (the nodes' \
                         spacing, length)"
                        ),
                    ));
                };
                let name = crate::text::printable(&path.display().to_string(), 200);
                let (map, file) = reads.read(path, &name, spacing, HEIGHT_MAP)?;
                read.push(file);
                (map, name)
            }
            (None, None) => {
                return Err(refuse(
                    INDENTER,
                    format!(
                        "{INDENTER} height-map needs {HEIGHT_MAP} and {SPACING} (the nodes' \
                     spacing, length)"
                    ),
                ))
            }
        };
        let surface = if self.convolution == Convolution::Periodic {
            // One period of a periodic surface: the domain is its period.
            MeasuredSurface::on_period(map, &name, self.window_x, self.window_y)
        } else if self.window_x.is_some() || self.window_y.is_some() {
            MeasuredSurface::on_window(map, &name, self.window_x, self.window_y)
        } else {
            MeasuredSurface::new(map, &name)
        }
        .map_err(input)?;
        Ok(Indenter::HeightMap(Arc::new(surface)))
    }

    /// The model options (the grid of a single run).
    pub fn options(&self) -> ModelOptions {
        let nx = self.grid.unwrap_or(DEFAULT_GRID);
        let measure = self.measure.unwrap_or(Measure::Curve);
        let onsets = self.onsets.unwrap_or(Onsets::NearMinimum);
        ModelOptions {
            nx,
            ny: self.grid_y,
            start_radius_bar: self
                .start_radius
                .unwrap_or(ModelOptions::default().start_radius_bar),
            steps: self
                .steps
                .unwrap_or(crate::model::default_steps(measure, onsets, self.regrid)),
            final_d_bar: self.final_d,
            margin: self.margin.unwrap_or(crate::model::default_margin(nx)),
            mesh_angle_deg: self.mesh_angle,
            apex_offset: (self.apex_offset[0], self.apex_offset[1]),
            cg_tolerance: self.cg_tolerance,
            cg_max_iterations: self.cg_max_iterations,
            cg_accept: self.cg_accept,
            max_sweeps: self.max_sweeps,
            preconditioner: self.preconditioner,
            onsets,
            loose_rounds: !self.exact_cascade,
            measure,
            regrid: self.regrid,
            preload: self.preload(),
            ..ModelOptions::default()
        }
    }

    /// The preload asked for (at most one is given: [`Request::check`] refuses more).
    fn preload(&self) -> Option<Preload> {
        self.preload_depth
            .map(Preload::Depth)
            .or(self.preload_force.map(Preload::Force))
            .or(self.preload_area.map(Preload::AreaFraction))
    }

    /// One grid, several or an accuracy. Parameters the choice would drop are refused: an
    /// accuracy chooses its grids, steps and measure itself, an extrapolation its grids.
    pub fn mode(&self) -> Result<Mode, RunError> {
        let one_grid = one_grid_parameters(self);
        let names = |specs: &[&Spec]| {
            specs
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        };
        if self.accuracy.is_some() {
            let mut dropped = one_grid.clone();
            if self.extrapolate {
                dropped.push(EXTRAPOLATE);
            }
            if !dropped.is_empty() {
                return Err(refuse(
                    ACCURACY,
                    format!(
                        "{ACCURACY} and {} cannot be given together: a run to an accuracy chooses \
                     its grids, load steps and measure itself (leave out {})",
                        dropped[0],
                        names(&dropped)
                    ),
                ));
            }
        }
        if self.extrapolate {
            if let Some(g) = one_grid.iter().find(|s| [GRID, GRID_Y].contains(s)) {
                return Err(refuse(
                    EXTRAPOLATE,
                    format!(
                    "{EXTRAPOLATE} and {g} cannot be given together: an extrapolation runs its \
                     own grids (give them as {EXTRAPOLATE_GRIDS})"
                ),
                ));
            }
        } else if self.extrapolate_grids.is_some() {
            return Err(refuse(
                EXTRAPOLATE_GRIDS,
                format!("{EXTRAPOLATE_GRIDS} is for {EXTRAPOLATE}: give both, or leave it out"),
            ));
        }
        // Only the ellipsoid has a convergence law: the other shapes run one grid.
        let one = self.indenter != Shape::Ellipsoid || !one_grid.is_empty();
        let extrapolate = self.extrapolate.then(|| self.extrapolate_grids.clone());
        let mode = Mode::choose(self.accuracy, extrapolate, one);
        if self.time_limit.is_some() && !matches!(mode, Mode::Accuracy(_)) {
            return Err(refuse(
                TIME_LIMIT,
                format!(
                    "{TIME_LIMIT} applies to a run to an accuracy ({ACCURACY} given, or none of \
                 {}, which run one grid)",
                    names(&ONE_GRID)
                ),
            ));
        }
        Ok(mode)
    }

    /// The backend asked for.
    pub fn backend(&self) -> BackendRequest {
        BackendRequest {
            kind: self.backend,
            precision: self.precision,
            convolution: self.convolution,
            check_every: self.cg_check_every,
        }
    }

    /// The session's request: `sink` says where the states and the summary go besides memory
    /// (the CLI's from [`Request::out`] and [`Request::summary`], a batch's to its scene's
    /// files, [`Sink::Memory`] for Python); `map` is a height map the caller holds in memory.
    pub fn simulate_request(
        &self,
        sink: Sink,
        map: Option<HeightMap>,
    ) -> Result<SimulateRequest, RunError> {
        self.simulate_request_sharing(sink, map, &mut MapReads::default())
    }

    /// Like [`Request::simulate_request`], its files read through `reads` (a batch's rows:
    /// each file read once, its map shared by the rows that name it).
    pub fn simulate_request_sharing(
        &self,
        sink: Sink,
        map: Option<HeightMap>,
        reads: &mut MapReads,
    ) -> Result<SimulateRequest, RunError> {
        let mode = self.mode()?;
        let fields = FieldChoice::parse(&self.fields).map_err(|_| {
            input(format!(
                "{} = {} is invalid",
                params::FIELDS,
                values::shown(&self.fields)
            ))
        })?;
        let time_limit = match self.time_limit {
            Some(t) => Some(Duration::try_from_secs_f64(t).map_err(|_| {
                refuse(
                    TIME_LIMIT,
                    format!("{TIME_LIMIT} = {} is invalid", crate::text::compact(t)),
                )
            })?),
            None => None,
        };
        self.backend().check()?;
        let (scene, input_files) = self.scene_sharing(map, reads)?;
        if self.convolution == Convolution::Periodic && scene.window_half().is_none() {
            return Err(refuse(
                CONVOLUTION,
                format!(
                "{CONVOLUTION} periodic is for a surface periodic over the domain, a height map \
                 that is one period of it (a nominally flat rough or a wavy surface): the {} is \
                 an isolated contact, which needs {CONVOLUTION} padded",
                scene.indenter.name()
            ),
            ));
        }
        Ok(SimulateRequest {
            scene,
            options: self.options(),
            backend: self.backend(),
            mode,
            sink,
            fields,
            time_limit,
            request: Some(self.to_json()),
            input_files,
            figures: FigureFormats::of(&self.figure_format),
        })
    }
}

#[cfg(test)]
mod tests;
