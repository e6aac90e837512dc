//! The flags of `jkrbem coverage`, with their help.

use super::super::parse::value;
use jkrbem::backend::select::BackendKind;
use jkrbem::params::{
    APEX_OFFSETS, EXPONENTS, GRIDS, HALF_ANGLES, MARGINS, MESH_ANGLES, RATIOS, RUNS_PER_CASE, SEEDS,
};
use jkrbem::studies::coverage::{CaseVariant, CoverageShape};
use std::path::PathBuf;

/// Arguments of `jkrbem coverage`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Shapes, comma-separated: `ellipsoid` (single-grid cases by its convergence law, the
    /// flags below), `flat-punch` (against Kendall's 1), `power-law` (against its JKR
    /// solution, one scene per --exponents), `cone` (against its JKR solution, one scene per
    /// --half-angles) and `rough-sphere` (one scene per --seeds, against a grid twice finer
    /// than --grids' finest): each case of the last four is an extrapolation
    /// over the ladder --grids [default 32,64,128] at four grid phases per grid, the phase set
    /// shifted by each --apex-offsets entry, at each --margins [default 0.08, 0.18].
    #[arg(long, value_enum, value_delimiter = ',', default_value = "ellipsoid")]
    pub shapes: Vec<CoverageShape>,
    /// The power law's exponents n, comma-separated (with --shapes power-law).
    #[arg(long, value_delimiter = ',', default_value = "1.5,3,8", value_parser = value::<f64>(EXPONENTS))]
    pub exponents: Vec<f64>,
    /// The cone's half-angles α in degrees, comma-separated (with --shapes cone). In its own
    /// normalisation every cone is one problem: other angles check only round-off.
    #[arg(long, value_delimiter = ',', default_value = "70", value_parser = value::<f64>(HALF_ANGLES))]
    pub half_angles: Vec<f64>,
    /// Seeds of the rough spheres' roughness, comma-separated (with --shapes rough-sphere:
    /// R = 1, rms slope 0.1, Hurst 0.8, cut-off 0.4, roll-off 1, pressed on to the sphere's
    /// first contact; each held against the same runs on a grid twice finer than --grids'
    /// finest). Each from 0 to 2⁶⁴ − 1.
    #[arg(long, value_delimiter = ',', default_value = "1,2,3", value_parser = value::<u64>(SEEDS))]
    pub seeds: Vec<u64>,
    /// Ratios R1/R2, comma-separated: 1 (the sphere, against JKR's exact 1/2) or ratios of the
    /// compiled-in reference table (against its Δx → 0 value) [default: every tabled ratio].
    #[arg(long, value_delimiter = ',', value_parser = value::<f64>(RATIOS))]
    pub ratios: Vec<f64>,
    /// Case grids Nx for every ratio, comma-separated (powers of two from 32, each fine enough
    /// for the ratio at every margin: checked before any work), each at least two
    /// levels below the finest grid of the ratio's reference ladder [default: that finest grid
    /// over 8 and over 4, not below the ladder's first grid; the sphere: 32, 64, 128].
    #[arg(long, value_delimiter = ',', value_parser = value::<usize>(GRIDS))]
    pub grids: Vec<usize>,
    /// Domain margins, comma-separated (relative to the initial contact's half-axes, in
    /// [0, 10]): each moves where the contact's edge falls between element centres (the grid
    /// phase) [default: 0.08, 0.13, 0.18, 0.23, 0.28].
    #[arg(long, value_delimiter = ',', value_parser = value::<f64>(MARGINS))]
    pub margins: Vec<f64>,
    /// How each grid is run, comma-separated: `fixed` (one Δx) and `regrid` (re-gridded to
    /// the shrinking contact); both with --measure adhesive-force.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "fixed,regrid"
    )]
    pub variants: Vec<CaseVariant>,
    /// Mesh angles θ in degrees, comma-separated (the grid turned against the contact's major
    /// axis, in [−90, 90]; 90 puts the minor axis along x): every case runs at each.
    #[arg(long, value_delimiter = ',', default_value = "0", value_parser = value::<f64>(MESH_ANGLES))]
    pub mesh_angles: Vec<f64>,
    /// Apex offsets within the element grid, comma-separated `x:y` pairs (elements, each in
    /// [−0.5, 0.5]; 0:0 puts the apex on an element corner): every case runs at each.
    #[arg(long, value_delimiter = ',', value_parser = parse_offset, default_value = "0:0")]
    pub apex_offsets: Vec<(f64, f64)>,
    /// Runs per case: each case is estimated from this many runs at consecutive margins of one
    /// grid together (as `reference --phases` does); every window of consecutive margins is a
    /// case. 1 to the number of --margins, at most 100.
    #[arg(long, default_value_t = 1, value_parser = value::<usize>(RUNS_PER_CASE))]
    pub runs_per_case: usize,
    /// Backend: `auto` (a hardware GPU if present, else the CPU), `cpu` or `gpu`.
    #[arg(long, value_enum, default_value_t = BackendKind::Auto)]
    pub backend: BackendKind,
    /// Output folder: every run's states and summary, coverage.csv (one row per case) and
    /// coverage-summary.csv (one row per ratio, then all). Runs already there that reached
    /// their force minimum are reused and estimated again with this program's law, where they
    /// record the same settings, ran on the backend asked for and their states reproduce their
    /// summary (as `reference` checks its runs); any other is run again, saying why.
    #[arg(long, default_value = "jkrbem-out/coverage")]
    pub out: PathBuf,
}

/// One `--apex-offsets` entry, `x:y` (elements), each in the schema's range.
fn parse_offset(text: &str) -> Result<(f64, f64), String> {
    let (x, y) = text
        .split_once(':')
        .ok_or_else(|| format!("{text:?} is not an offset: give x:y, e.g. 0.25:0.25"))?;
    value::<(f64, f64)>(APEX_OFFSETS)(&format!("{x},{y}"))
        .map_err(|e| e.replace("e.g. 0.25,-0.5", "written x:y, e.g. 0.25:-0.5"))
}
