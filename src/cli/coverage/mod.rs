//! `jkrbem coverage`: how honest the stated uncertainties are. Parses the flags; the work is
//! [`jkrbem::studies::coverage`].

mod args;

use super::progress::Progress;
use super::{no_repeats, run_error, CliError};
pub use args::Args;
use jkrbem::session::open::BackendRequest;
use jkrbem::studies::coverage::{
    coverage, generic_coverage, generic_scenes, CaseVariant, CoverageRequest, CoverageShape,
    CoverageSummary, GenericCoverageRequest, DEFAULT_MARGINS,
};
use jkrbem::studies::reference::REFERENCE_RATIOS;

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
    no_repeats("--half-angles", &args.half_angles)?;
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
            scenes.extend(
                generic_scenes(s, &args.exponents, &args.half_angles, &args.seeds)
                    .map_err(run_error)?,
            );
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
