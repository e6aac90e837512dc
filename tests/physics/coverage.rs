//! How honest the stated uncertainties are (`jkrbem coverage`). Fast tier: the command runs its
//! cases, writes one row per case and a summary, reuses its runs, and refuses bad input before
//! any work. Slow tier: single-grid runs at many grid phases (domain margins, fixed and
//! re-gridded) of the sphere, against JKR's exact 1/2, and of R1/R2 = 1.5, 5, 10, 25 and 50,
//! against the committed reference table (ladders at least two levels finer): at least 90 % of
//! the stated intervals must hold the reference, and they must not be needlessly wide; the
//! same for c̄ and d̄ at the minimum.

#[cfg(feature = "cli")]
use crate::common;

#[cfg(feature = "cli")]
use common::{jkrbem, stderr};
use jkrbem::backend::select::BackendKind;
use jkrbem::session::open::BackendRequest;
use jkrbem::session::Quiet;
use jkrbem::studies::coverage::{
    coverage, summarise, CaseVariant, CoverageCase, CoverageRequest, CoverageSummary,
};

#[cfg(feature = "cli")]
#[test]
fn the_coverage_command_writes_every_case_and_reuses_its_runs() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "coverage",
        "--ratios",
        "1",
        "--grids",
        "32",
        "--margins",
        "0.08,0.13",
        "--variants",
        "regrid",
        "--backend",
        "cpu",
        "--out",
        "cov",
    ];
    let o = jkrbem(&args, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("cov/coverage.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "ratio,grid,margin,runs,variant,mesh_angle_deg,apex_offset_x,apex_offset_y,n_d,\
         f_ad_bar_grid,f_ad_bar,uncertainty,reference,\
         reference_uncertainty,error,held,width_over_error,c_bar_at_min,c_bar_uncertainty,\
         c_bar_reference,c_bar_reference_uncertainty,c_bar_held,d_bar_at_min,d_bar_uncertainty,\
         d_bar_reference,d_bar_reference_uncertainty,d_bar_held"
    );
    assert_eq!(lines.count(), 2, "{text}");
    let summary = std::fs::read_to_string(dir.path().join("cov/coverage-summary.csv")).unwrap();
    assert!(
        summary.lines().any(|l| l.starts_with("all,2,")),
        "{summary}"
    );
    for m in ["0.08", "0.13"] {
        assert!(dir
            .path()
            .join(format!("cov/r1-n32-m{m}-regrid.json"))
            .exists());
    }
    // A second study on the same folder runs nothing: it estimates the same runs again.
    let again = jkrbem(&args, dir.path());
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(!stderr(&again).contains("Δx ="), "{}", stderr(&again));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("cov/coverage.csv")).unwrap(),
        text
    );
}

#[cfg(feature = "cli")]
#[test]
fn bad_coverage_requests_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    for bad in [
        // No reference for a ratio outside the table.
        vec!["coverage", "--ratios", "4", "--out", "c"],
        // A case grid less than two levels below its reference's finest grid (512 for 5).
        vec!["coverage", "--ratios", "5", "--grids", "256", "--out", "c"],
        vec![
            "coverage",
            "--ratios",
            "1",
            "--margins",
            "-0.1",
            "--out",
            "c",
        ],
        vec!["coverage", "--ratios", "1,1", "--out", "c"],
    ] {
        let o = jkrbem(&bad, dir.path());
        assert_eq!(o.status.code(), Some(2), "{bad:?}: {}", stderr(&o));
    }
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// The CPU backend, for a study.
fn cpu() -> BackendRequest {
    BackendRequest {
        kind: BackendKind::Cpu,
        ..BackendRequest::default()
    }
}

/// The summary of `cases` as one ("all"), printed, after checking that at least nine in ten of
/// the stated intervals hold the reference: of |min F̄|, and of c̄ and d̄ at the minimum.
fn nine_in_ten(cases: &[&CoverageCase]) -> CoverageSummary {
    let s = summarise("all", cases).unwrap();
    let (n, held, p, c, d) = (
        s.cases,
        s.held,
        s.position_cases,
        s.c_bar_held,
        s.d_bar_held,
    );
    println!("held {held} of {n}; c̄ held {c} of {p}, d̄ held {d} of {p}");
    assert!(10 * held >= 9 * n, "only {held} of {n} intervals hold");
    assert!(10 * c >= 9 * p, "c̄: only {c} of {p} intervals hold");
    assert!(10 * d >= 9 * p, "d̄: only {d} of {p} intervals hold");
    s
}

/// The study of `ratios` on `grids` (`None`: the default case grids) at `margins`, fixed and
/// re-gridded, on the CPU; prints and returns every case.
fn study(
    ratios: &[f64],
    grids: Option<Vec<usize>>,
    margins: &[f64],
    out: &std::path::Path,
) -> Vec<CoverageCase> {
    placed_study(ratios, grids, margins, (&[0.0], &[(0.0, 0.0)]), out)
}

/// [`study`] at every mesh angle (degrees) and apex offset (elements) of `placements`.
fn placed_study(
    ratios: &[f64],
    grids: Option<Vec<usize>>,
    margins: &[f64],
    placements: (&[f64], &[(f64, f64)]),
    out: &std::path::Path,
) -> Vec<CoverageCase> {
    let req = CoverageRequest {
        ratios: ratios.to_vec(),
        grids,
        margins: margins.to_vec(),
        variants: vec![CaseVariant::Fixed, CaseVariant::Regrid],
        mesh_angles: placements.0.to_vec(),
        apex_offsets: placements.1.to_vec(),
        runs_per_case: 1,
        backend: cpu(),
        out: out.to_path_buf(),
    };
    let done = coverage(&req, &Quiet).unwrap();
    println!(
        "R1/R2  grid      margin  variant  angle  offset     stated            reference  \
         error %  width/|error|"
    );
    for c in &done.cases {
        println!(
            "{:5} {:9} {:7} {:7}  {:5} {:4}:{:<4}  {:.5} ± {:.5}  {:.5}  {:+7.3}  {:6.2}",
            c.ratio,
            c.grid,
            c.margin,
            c.variant,
            c.mesh_angle_deg,
            c.apex_offset_x,
            c.apex_offset_y,
            c.f_ad_bar,
            c.uncertainty,
            c.reference,
            100.0 * c.error / c.reference,
            c.width_over_error
        );
    }
    done.cases
}

#[test]
#[ignore = "slow tier: 42 pull-offs, about 90 s"]
fn stated_intervals_hold_the_limit_at_least_nine_times_in_ten() {
    let dir = tempfile::tempdir().unwrap();
    // The sphere against 1/2 at six margins; 1.5, 5 and 10 on 64 columns at three; slender
    // contacts on their default case grid (two levels below their ladders) at three.
    let all = [
        study(
            &[1.0],
            Some(vec![64]),
            &[0.08, 0.12, 0.16, 0.2, 0.24, 0.28],
            dir.path(),
        ),
        study(
            &[1.5, 5.0, 10.0],
            Some(vec![64]),
            &[0.08, 0.16, 0.24],
            dir.path(),
        ),
        study(&[25.0, 50.0], None, &[0.08, 0.16, 0.24], dir.path()),
    ];
    let cases: Vec<&CoverageCase> = all.iter().flatten().collect();
    // Where the minimum lies, too: c̄ and d̄ against JKR's for the sphere, the table's
    // otherwise (each interval widened by the table's own half-width).
    let s = nine_in_ten(&cases);
    let (n, rms) = (s.cases, s.rms_error_over_sd);
    println!(
        "RMS of error / stated sd = {rms:.2}; median half-width / |error| = {:.2}",
        s.median_width_over_error
    );
    assert!(n >= 40, "{n} cases");
    assert!(rms >= 0.5, "intervals needlessly wide: RMS {rms:.2}");
    assert_eq!(s.position_cases, n);
}

#[test]
#[ignore = "slow tier: 48 pull-offs on turned meshes and offset apexes, about 2 minutes"]
fn stated_intervals_hold_on_turned_meshes_and_offset_apexes() {
    let dir = tempfile::tempdir().unwrap();
    // The sphere, 3:1 and 5:1 on 64 columns at two margins, each turned by 30° and by 90°, with
    // the apex on an element corner and a quarter element off it in both directions.
    let cases = placed_study(
        &[1.0, 3.0, 5.0],
        Some(vec![64]),
        &[0.08, 0.18],
        (&[30.0, 90.0], &[(0.0, 0.0), (0.25, 0.25)]),
        dir.path(),
    );
    let all: Vec<&CoverageCase> = cases.iter().collect();
    assert_eq!(nine_in_ten(&all).cases, 48);
}

/// The generic study of `shapes` (power-law exponents `exponents`) on the ladder `grids` at
/// `margins`, the phase set shifted by each of `shifts`, on the CPU; prints every case.
fn generic_study(
    shapes: &[jkrbem::studies::coverage::CoverageShape],
    exponents: &[f64],
    grids: &[usize],
    margins: &[f64],
    shifts: &[(f64, f64)],
    out: &std::path::Path,
) -> jkrbem::studies::coverage::GenericCoverageDone {
    use jkrbem::studies::coverage::{generic_coverage, generic_scenes, GenericCoverageRequest};
    let mut scenes = Vec::new();
    for &s in shapes {
        scenes.extend(generic_scenes(s, exponents, &[70.0], &[1]).unwrap());
    }
    let req = GenericCoverageRequest {
        scenes,
        grids: grids.to_vec(),
        margins: margins.to_vec(),
        phase_shifts: shifts.to_vec(),
        backend: cpu(),
        out: out.to_path_buf(),
    };
    let done = generic_coverage(&req, &Quiet).unwrap();
    for c in &done.cases {
        println!(
            "{:16} {:10} {:5} {:5}:{:<5} {:.5} ± {:.5} (p {:.2}{}) against {:.5}: {:+.3} %",
            c.shape,
            c.grids,
            c.margin,
            c.shift_x,
            c.shift_y,
            c.f_ad_bar,
            c.uncertainty,
            c.order,
            if c.order_estimated { ", estimated" } else { "" },
            c.reference,
            100.0 * c.error / c.reference
        );
    }
    done
}

#[cfg(feature = "cli")]
#[test]
fn the_coverage_command_checks_shapes_without_a_law() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "coverage",
        "--shapes",
        "flat-punch",
        "--grids",
        "32,64",
        "--margins",
        "0.08",
        "--backend",
        "cpu",
        "--out",
        "cov",
    ];
    let o = jkrbem(&args, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(dir.path().join("cov/generic-coverage.csv")).unwrap();
    let mut lines = text.lines();
    assert!(lines
        .next()
        .unwrap()
        .starts_with("shape,grids,margin,shift_x,shift_y,refused,"));
    let row = lines.next().unwrap();
    assert!(
        row.starts_with("flat-punch,\"32,64\",0.08,0.0,0.0,false,"),
        "{row}"
    );
    assert_eq!(lines.count(), 0);
    // No ellipsoid asked for: no ellipsoid study.
    assert!(!dir.path().join("cov/coverage.csv").exists());
    // A ladder of one grid is refused before any work.
    let one = jkrbem(
        &[
            "coverage",
            "--shapes",
            "power-law",
            "--grids",
            "64",
            "--out",
            "c1",
        ],
        dir.path(),
    );
    assert_eq!(one.status.code(), Some(2), "{}", stderr(&one));
    assert!(stderr(&one).contains("--grids"), "{}", stderr(&one));
}

#[test]
#[ignore = "slow tier: 240 pull-offs up to 128², about 10 minutes on 2 cores"]
fn slow_generic_intervals_hold_their_closed_forms_nine_times_in_ten() {
    use jkrbem::studies::coverage::CoverageShape;
    let dir = tempfile::tempdir().unwrap();
    let done = generic_study(
        &[CoverageShape::FlatPunch, CoverageShape::PowerLaw],
        &[1.5, 3.0, 5.0, 8.0],
        &[32, 64, 128],
        &[0.08],
        &[(0.0, 0.0), (0.125, 0.0), (0.1, 0.3)],
        dir.path(),
    );
    let all = done.summary.last().unwrap();
    println!("held {} of {}", all.held, all.cases);
    assert_eq!(all.cases, 15);
    assert!(
        10 * all.held >= 9 * all.cases,
        "only {} of {}",
        all.held,
        all.cases
    );
}
