//! Every file name a run writes, in one place: the commands, the session layer and the
//! charts all take their names from here.

use super::figure::FigureFormat;
use crate::text::compact;
use std::fmt::Display;
use std::path::{Path, PathBuf};

/// The states file of R1/R2 = `ratio` on grid Nx `grid` in a sweep (or study) folder:
/// `dir/r<ratio>-n<grid>.csv`.
pub fn sweep_states(dir: &Path, ratio: f64, grid: usize) -> PathBuf {
    dir.join(format!("r{ratio}-n{grid}.csv"))
}

/// The summary file of a whole sweep: `dir/sweep.csv`.
pub fn sweep_csv(dir: &Path) -> PathBuf {
    dir.join("sweep.csv")
}

/// The file of shard `k` of `n` (1-based): `dir/sweep-shard-K-of-N.json`.
pub fn shard(dir: &Path, (k, n): (usize, usize)) -> PathBuf {
    dir.join(format!("sweep-shard-{k}-of-{n}.json"))
}

/// The states file of a batch's scene `id` in the batch's folder: `dir/scene-<id>.csv` (the
/// stem of its per-grid files `scene-<id>-n<Nx>.csv` where it runs several grids).
pub fn scene_states(dir: &Path, id: &str) -> PathBuf {
    dir.join(format!("scene-{id}.csv"))
}

/// The summary JSON of a batch's scene `id`: `dir/scene-<id>.json`.
pub fn scene_summary(dir: &Path, id: &str) -> PathBuf {
    dir.join(format!("scene-{id}.json"))
}

/// The record of a batch (every scene, its id and its request) that a batch run writes in
/// its folder: `dir/batch.json`, or `dir/batch-shard-K-of-N.json` for shard K of N.
pub fn batch_manifest(dir: &Path, shard: Option<(usize, usize)>) -> PathBuf {
    match shard {
        None => dir.join("batch.json"),
        Some((k, n)) => dir.join(format!("batch-shard-{k}-of-{n}.json")),
    }
}

/// (K, N) of a batch's record named `name` (`batch-shard-K-of-N.json`; `None` inside for
/// `batch.json`), or `None` for any other name.
pub fn parse_batch_manifest(name: &str) -> Option<Option<(usize, usize)>> {
    if name == "batch.json" {
        return Some(None);
    }
    let rest = name.strip_prefix("batch-shard-")?.strip_suffix(".json")?;
    let (k, n) = rest.split_once("-of-")?;
    let digits = |t: &str| !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit());
    if !digits(k) || !digits(n) {
        return None;
    }
    Some(Some((k.parse().ok()?, n.parse().ok()?)))
}

/// The merged table of a batch: `dir/batch.csv`.
pub fn batch_csv(dir: &Path) -> PathBuf {
    dir.join("batch.csv")
}

/// The wall times of a batch's scenes, kept out of [`batch_csv`]: `dir/batch-timings.csv`.
pub fn batch_timings(dir: &Path) -> PathBuf {
    dir.join("batch-timings.csv")
}

/// A sweep's charts in `dir`: `force_vs_ratio.svg` and `pulloff_curves.svg`.
pub fn sweep_charts(dir: &Path) -> [PathBuf; 2] {
    [
        dir.join("force_vs_ratio.svg"),
        dir.join("pulloff_curves.svg"),
    ]
}

/// The contours file beside a states file: `<stem>.contours.csv`.
pub fn contours(states: &Path) -> PathBuf {
    let stem = states
        .file_stem()
        .map_or_else(|| "states".into(), |s| s.to_string_lossy().into_owned());
    states.with_file_name(format!("{stem}.contours.csv"))
}

/// A file beside a states file: `<stem>.<suffix>`.
fn beside(states: &Path, suffix: &str) -> PathBuf {
    let stem = states
        .file_stem()
        .map_or_else(|| "states".into(), |s| s.to_string_lossy().into_owned());
    states.with_file_name(format!("{stem}.{suffix}"))
}

/// The fields of a run's picked states beside its states file: `<stem>.fields.npz`.
pub fn fields_npz(states: &Path) -> PathBuf {
    beside(states, "fields.npz")
}

/// The picture of the pressure at the force minimum beside a states file:
/// `<stem>.pressure.svg`.
pub fn pressure_chart(states: &Path) -> PathBuf {
    beside(states, "pressure.svg")
}

/// The accuracy chart against CG iterations beside the one against wall time (`svg`):
/// `<stem>_iterations.svg`.
pub fn iterations_chart(svg: &Path) -> PathBuf {
    let stem = svg
        .file_stem()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    svg.with_file_name(format!("{stem}_iterations.svg"))
}

/// The chart of the pressure along the contact's x and y axes at the force minimum beside a
/// states file: `<stem>.profile.svg`.
pub fn profile_chart(states: &Path) -> PathBuf {
    beside(states, "profile.svg")
}

/// The file of the chart named `chart` (its SVG path) in `format`: the same stem, the
/// format's extension (`f_of_d.pdf`).
pub fn figure_file(chart: &Path, format: FigureFormat) -> PathBuf {
    chart.with_extension(format.name())
}

/// The data file of the chart named `chart` (its SVG path): `<stem>.plot.csv` beside it. The
/// `.plot` keeps it apart from every other CSV a run writes (`<stem>.csv`, the states and the
/// tables, and `<stem>.contours.csv`).
pub fn plot_csv(chart: &Path) -> PathBuf {
    chart.with_extension("plot.csv")
}

/// The summary JSON beside a states file: `<stem>.json`.
pub fn summary_beside(states: &Path) -> PathBuf {
    states.with_extension("json")
}

/// The files one batch job writes: its states, its summary JSON and its contours.
pub fn run_files(states: &Path) -> [PathBuf; 3] {
    [
        states.to_path_buf(),
        summary_beside(states),
        contours(states),
    ]
}

/// The default states file of one `simulate` run: `jkrbem-out/simulate-r<ratio>-n<nx>.csv`,
/// with `-a<degrees>` added for a turned mesh.
pub fn simulate_default(tag: &str, nx: usize, mesh_degrees: Option<f64>) -> PathBuf {
    let angle = mesh_degrees.map_or(String::new(), |d| format!("-a{d}"));
    PathBuf::from(format!("jkrbem-out/simulate-{tag}-n{nx}{angle}.csv"))
}

/// The default stem of a several-grid `simulate` (`what`: "simulate" or "extrapolate").
pub fn simulate_stem(what: &str, tag: &str) -> PathBuf {
    PathBuf::from(format!("jkrbem-out/{what}-{tag}.csv"))
}

/// The states file of grid `nx` of a several-grid run with stem `stem`: `<stem>-n<nx>.csv`.
pub fn grid_states(stem: &Path, nx: usize) -> PathBuf {
    let name = stem
        .file_stem()
        .map_or("states".into(), |s| s.to_string_lossy().into_owned());
    stem.with_file_name(format!("{name}-n{nx}.csv"))
}

/// The states file of grid `nx` at grid phase `phase` (its index among the apex offsets run)
/// of a several-grid run with stem `stem`: `<stem>-n<nx>-p<phase>.csv`.
pub fn grid_phase_states(stem: &Path, nx: usize, phase: usize) -> PathBuf {
    let name = stem
        .file_stem()
        .map_or("states".into(), |s| s.to_string_lossy().into_owned());
    stem.with_file_name(format!("{name}-n{nx}-p{phase}.csv"))
}

/// The default file of a `theory` curve (`model`: hertz, jkr or jg).
pub fn theory_default(model: &str, ratio: f64) -> PathBuf {
    PathBuf::from(format!("jkrbem-out/theory-{model}-r{ratio}.csv"))
}

/// The states file of the crossed cylinders at `angle` degrees on grid `nx`.
pub fn crossed_states(dir: &Path, angle: f64, nx: usize) -> PathBuf {
    dir.join(format!("theta{angle}-n{nx}.csv"))
}

/// The folder of a reference table's runs: `<stem>-runs/` beside it.
pub fn reference_runs(table: &Path) -> PathBuf {
    let stem = table
        .file_stem()
        .map_or("reference".into(), |s| s.to_string_lossy().into_owned());
    table.with_file_name(format!("{stem}-runs"))
}

/// The name (no extension) of a reference ladder's run of R1/R2 = `ratio` on grid `nx` at
/// its `phase`-th margin `margin` (the first keeps the name of a ladder with one run per
/// grid, so that its runs are reused).
pub fn reference_run(ratio: f64, nx: usize, phase: usize, margin: f64) -> String {
    if phase == 0 {
        format!("r{ratio}-n{nx}")
    } else {
        format!("r{ratio}-n{nx}-m{margin}")
    }
}

/// The name (no extension) of one coverage case's run: `r<ratio>-n<nx>-m<margin>-<variant>`,
/// with `-a<degrees>` on a turned mesh and `-o<x>_<y>` for an apex off the element corner
/// (neither for the aligned default, so that earlier studies' runs keep their names).
pub fn coverage_case(
    ratio: f64,
    nx: usize,
    margin: f64,
    variant: impl Display,
    mesh_angle_deg: f64,
    apex_offset: (f64, f64),
) -> String {
    let mut name = format!("r{ratio}-n{nx}-m{margin}-{variant}");
    if mesh_angle_deg != 0.0 {
        name.push_str(&format!("-a{}", compact(mesh_angle_deg)));
    }
    if apex_offset != (0.0, 0.0) {
        name.push_str(&format!(
            "-o{}_{}",
            compact(apex_offset.0),
            compact(apex_offset.1)
        ));
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_the_ones_the_docs_give() {
        let d = Path::new("sw");
        assert_eq!(sweep_states(d, 2.5, 64), Path::new("sw/r2.5-n64.csv"));
        assert_eq!(
            run_files(&sweep_states(d, 1.0, 32)),
            [
                PathBuf::from("sw/r1-n32.csv"),
                PathBuf::from("sw/r1-n32.json"),
                PathBuf::from("sw/r1-n32.contours.csv")
            ]
        );
        assert_eq!(shard(d, (2, 8)), Path::new("sw/sweep-shard-2-of-8.json"));
        assert_eq!(
            simulate_default("r5", 128, Some(30.0)),
            Path::new("jkrbem-out/simulate-r5-n128-a30.csv")
        );
        assert_eq!(
            grid_states(Path::new("runs/r5.csv"), 128),
            Path::new("runs/r5-n128.csv")
        );
        assert_eq!(
            reference_runs(Path::new("t/adhesive-force.csv")),
            Path::new("t/adhesive-force-runs")
        );
        assert_eq!(reference_run(5.0, 64, 1, 0.1), "r5-n64-m0.1");
        assert_eq!(scene_summary(d, "a1"), Path::new("sw/scene-a1.json"));
        assert_eq!(
            batch_manifest(d, Some((2, 4))),
            Path::new("sw/batch-shard-2-of-4.json")
        );
        for (k, n) in [(2, 4), (1, 1)] {
            let name = format!("batch-shard-{k}-of-{n}.json");
            assert_eq!(parse_batch_manifest(&name), Some(Some((k, n))));
        }
        assert_eq!(parse_batch_manifest("batch.json"), Some(None));
        assert_eq!(parse_batch_manifest("batch-shard-x-of-4.json"), None);
        assert_eq!(parse_batch_manifest("batch.csv"), None);
        let chart = pressure_chart(Path::new("r/a.csv"));
        assert_eq!(
            figure_file(&chart, FigureFormat::Png),
            Path::new("r/a.pressure.png")
        );
        assert_eq!(plot_csv(&chart), Path::new("r/a.pressure.plot.csv"));
        let profile = profile_chart(Path::new("r/a.csv"));
        assert_eq!(profile, Path::new("r/a.profile.svg"));
        assert_eq!(plot_csv(&profile), Path::new("r/a.profile.plot.csv"));
    }
}
