//! `jkrbem coverage`: how honest the stated uncertainties are. Parses the flags; the work is
//! [`jkrbem::studies::coverage`].

use super::parse::value;
use super::progress::Progress;
use super::{no_repeats, run_error, CliError};
use jkrbem::backend::select::BackendKind;
use jkrbem::params::{
    APEX_OFFSETS, EXPONENTS, GRIDS, MARGINS, MESH_ANGLES, RATIOS, RUNS_PER_CASE, SEEDS,
};
use jkrbem::session::open::BackendRequest;
use jkrbem::studies::coverage::{
    coverage, generic_coverage, generic_scenes, CaseVariant, CoverageRequest, CoverageShape,
    CoverageSummary, GenericCoverageRequest, DEFAULT_MARGINS,
};
use jkrbem::studies::reference::REFERENCE_RATIOS;
use std::path::PathBuf;

/// Arguments of `jkrbem coverage`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Shapes, comma-separated: `ellipsoid` (single-grid cases by its convergence law, the
    /// flags below), `flat-punch` (against Kendall's 1) and `power-law` (against its JKR
    /// solution, one scene per --exponents) and `rough-sphere` (one scene per --seeds, against
    /// a grid twice finer than --grids' finest): each case of the last three is an extrapolation
    /// over the ladder --grids [default 32,64,128] at four grid phases per grid, the phase set
    /// shifted by each --apex-offsets entry, at each --margins [default 0.08, 0.18].
    #[arg(long, value_enum, value_delimiter = ',', default_value = "ellipsoid")]
    pub shapes: Vec<CoverageShape>,
    /// The power law's exponents n, comma-separated (with --shapes power-law).
    #[arg(long, value_delimiter = ',', default_value = "1.5,3,8", value_parser = value::<f64>(EXPONENTS))]
    pub exponents: Vec<f64>,
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

/// Refuse the ellipsoid's flags (--ratios, --variants, --mesh-angles, --runs-per-case) away
/// from their defaults where --shapes holds no ellipsoid: they would be ignored.
fn ellipsoid_flags_need_the_ellipsoid(args: &Args) -> Result<(), CliError> {
    if args.shapes.contains(&CoverageShape::Ellipsoid) {
        return Ok(());
    }
    let given = [
        ("--ratios", !args.ratios.is_empty()),
        (
            "--variants",
            args.variants != [CaseVariant::Fixed, CaseVariant::Regrid],
        ),
        ("--mesh-angles", args.mesh_angles != [0.0]),
        ("--runs-per-case", args.runs_per_case != 1),
    ];
    match given.iter().find(|g| g.1) {
        Some((flag, _)) => Err(super::input(format!(
            "{flag}: it sets the ellipsoid's cases, and --shapes holds no ellipsoid (the other \
             shapes are extrapolated over --grids at four grid phases, shifted by each \
             --apex-offsets entry); add ellipsoid to --shapes or leave {flag} out"
        ))),
        None => Ok(()),
    }
}

/// Run `jkrbem coverage`.
pub fn run(args: Args) -> Result<(), CliError> {
    super::stdout::not_stdout("--out", &args.out, "coverage")?;
    no_repeats("--shapes", &args.shapes)?;
    no_repeats("--exponents", &args.exponents)?;
    no_repeats("--seeds", &args.seeds)?;
    ellipsoid_flags_need_the_ellipsoid(&args)?;
    let generic: Vec<CoverageShape> = args
        .shapes
        .iter()
        .copied()
        .filter(|s| *s != CoverageShape::Ellipsoid)
        .collect();
    if !generic.is_empty() {
        let mut scenes = Vec::new();
        for &s in &generic {
            scenes.extend(generic_scenes(s, &args.exponents, &args.seeds).map_err(run_error)?);
        }
        let margins = if args.margins.is_empty() {
            vec![0.08, 0.18]
        } else {
            args.margins.clone()
        };
        no_repeats("--margins", &margins)?;
        no_repeats("--grids", &args.grids)?;
        let req = GenericCoverageRequest {
            scenes,
            grids: if args.grids.is_empty() {
                vec![32, 64, 128]
            } else {
                args.grids.clone()
            },
            margins,
            phase_shifts: args.apex_offsets.clone(),
            backend: BackendRequest {
                kind: args.backend,
                ..BackendRequest::default()
            },
            out: args.out.clone(),
        };
        let done = generic_coverage(&req, &Progress::new()).map_err(run_error)?;
        print_summary("shape", &done.summary);
        outln!(
            "written {} and {}",
            done.csv.display(),
            done.summary_csv.display()
        );
    }
    if !args.shapes.contains(&CoverageShape::Ellipsoid) {
        return Ok(());
    }
    let ratios = if args.ratios.is_empty() {
        REFERENCE_RATIOS.to_vec()
    } else {
        args.ratios
    };
    let margins = if args.margins.is_empty() {
        DEFAULT_MARGINS.to_vec()
    } else {
        args.margins
    };
    no_repeats("--ratios", &ratios)?;
    no_repeats("--margins", &margins)?;
    no_repeats("--grids", &args.grids)?;
    no_repeats("--variants", &args.variants)?;
    let req = CoverageRequest {
        ratios,
        grids: (!args.grids.is_empty()).then_some(args.grids),
        margins,
        variants: args.variants,
        mesh_angles: args.mesh_angles,
        apex_offsets: args.apex_offsets,
        runs_per_case: args.runs_per_case,
        backend: BackendRequest {
            kind: args.backend,
            ..BackendRequest::default()
        },
        out: args.out,
    };
    let done = coverage(&req, &Progress::new()).map_err(run_error)?;
    print_summary("R1/R2", &done.summary);
    outln!(
        "written {} and {}",
        done.csv.display(),
        done.summary_csv.display()
    );
    Ok(())
}

/// The summary table, one line per row of `summary`, the first column headed `what`.
fn print_summary(what: &str, summary: &[CoverageSummary]) {
    let w = summary
        .iter()
        .map(|s| s.ratio.chars().count())
        .max()
        .unwrap_or(5)
        .max(5);
    outln!(
        "{:<w$}   cases  held          median width/|error|  RMS error/sd  half-widths      \
         c̄ held  d̄ held (of)",
        what
    );
    for s in summary {
        outln!(
            "{:<w$} {:>7}  {:>4} ({:>5.1} %)  {:>20.2}  {:>12.2}  {:>6.2}–{:<6.2} %  {:>6}  {:>6} ({})",
            s.ratio,
            s.cases,
            s.held,
            100.0 * s.held_fraction,
            s.median_width_over_error,
            s.rms_error_over_sd,
            100.0 * s.half_width_min,
            100.0 * s.half_width_max,
            s.c_bar_held,
            s.d_bar_held,
            s.position_cases
        );
    }
}

/// One `--apex-offsets` entry, `x:y` (elements), each in the schema's range.
fn parse_offset(text: &str) -> Result<(f64, f64), String> {
    let (x, y) = text
        .split_once(':')
        .ok_or_else(|| format!("{text:?} is not an offset: give x:y, e.g. 0.25:0.25"))?;
    value::<(f64, f64)>(APEX_OFFSETS)(&format!("{x},{y}"))
        .map_err(|e| e.replace("e.g. 0.25,-0.5", "written x:y, e.g. 0.25:-0.5"))
}
