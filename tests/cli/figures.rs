//! `--figure-format` (issue 45, item 5): every chart in each format asked for, beside each
//! other with one stem, and its data in `<stem>.plot.csv`, the rows being the points (or
//! cells) the chart draws; a format that is none of svg, pdf, png refused naming the flag;
//! the new files planned with the others, so that a clash is refused before any work.

use crate::common::{jkrbem, names_in, stderr, stdout, SHORT};
use std::path::Path;

/// The rows of a CSV file (header first), each cell as text.
fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_path(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    r.records()
        .map(|rec| rec.unwrap().iter().map(str::to_string).collect())
        .collect()
}

/// The `width="…"` of an SVG document (pixels).
fn svg_width(svg: &str) -> f64 {
    svg.split_once("width=\"")
        .and_then(|(_, r)| r.split_once('"'))
        .and_then(|(w, _)| w.parse().ok())
        .expect("the SVG's width")
}

/// Check the PDF and the PNG of the chart `stem` in `dir`: a PDF, and a PNG whose width is
/// the SVG's at 300 dpi (its pixels are 1/96 inch).
fn check_pictures(dir: &Path, stem: &str) {
    let pdf = std::fs::read(dir.join(format!("{stem}.pdf"))).unwrap();
    assert!(pdf.starts_with(b"%PDF-"), "{stem}.pdf");
    let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}.png");
    assert_eq!(&png[12..16], b"IHDR");
    let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
    assert_eq!(
        width,
        (svg_width(&svg) * 300.0 / 96.0).round() as u32,
        "{stem}.png"
    );
}

#[test]
fn a_sweep_writes_every_format_and_the_points_each_chart_draws() {
    let dir = tempfile::tempdir().unwrap();
    let o = jkrbem(
        &[
            "sweep",
            "--ratios",
            "1,2",
            "--grid",
            "32",
            "--steps",
            "20",
            "--backend",
            "cpu",
            "--figure-format",
            "svg,pdf,png",
            "--out",
            "sw",
        ],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let sw = dir.path().join("sw");
    for stem in ["force_vs_ratio", "pulloff_curves"] {
        check_pictures(&sw, stem);
        assert!(
            stdout(&o).contains(&format!("sw/{stem}.svg (also .pdf, .png and .plot.csv)")),
            "{}",
            stdout(&o)
        );
    }
    // Nothing but the run's files: no temporary, no lock left.
    let left = names_in(&sw, |n| n.starts_with('.') || n.contains(".tmp"));
    assert!(left.is_empty(), "{left:?}");
    // The rows of force_vs_ratio.plot.csv that are markers are sweep.csv's forces with their
    // stated uncertainties, every digit.
    let sweep = csv_rows(&sw.join("sweep.csv"));
    let col = |name: &str| sweep[0].iter().position(|h| h == name).unwrap();
    let (ratio, force, uncertainty) = (col("ratio"), col("f_ad_bar"), col("f_ad_bar_uncertainty"));
    let plot = csv_rows(&sw.join("force_vs_ratio.plot.csv"));
    assert_eq!(plot[0], ["series", "style", "x", "y", "error"]);
    // Answers are filled markers; grids too coarse for their estimate are hollow ones.
    let markers: Vec<&Vec<String>> = plot
        .iter()
        .filter(|r| r[1] == "markers" || r[1] == "hollow markers")
        .collect();
    assert_eq!(markers.len(), 2, "{plot:?}");
    let num = |t: &str| t.parse::<f64>().unwrap();
    for (m, row) in markers.iter().zip(&sweep[1..]) {
        assert_eq!(num(&m[2]), num(&row[ratio]));
        assert_eq!(num(&m[3]), num(&row[force]));
        assert_eq!(num(&m[4]), num(&row[uncertainty]));
        assert!(
            m[0].starts_with("jkrbem at Δx → 0") || m[0].starts_with("coarse grid"),
            "{m:?}"
        );
    }
    // The closed form is drawn as a line with no error bars.
    let jg: Vec<&Vec<String>> = plot.iter().filter(|r| r[1] == "line").collect();
    assert!(
        jg.len() > 10 && jg.iter().all(|r| r[4].is_empty()),
        "{jg:?}"
    );
    // The pull-off chart's markers of R1/R2 = 1 are the states' (d̄, F̄).
    let states = csv_rows(&sw.join("r1-n32.csv"));
    let (d, f) = (
        states[0].iter().position(|h| h == "d_bar").unwrap(),
        states[0].iter().position(|h| h == "f_bar").unwrap(),
    );
    let drawn: Vec<(f64, f64)> = csv_rows(&sw.join("pulloff_curves.plot.csv"))
        .iter()
        .skip(1)
        .filter(|r| r[1] == "markers" && r[0].starts_with("R1/R2 = 1 ("))
        .map(|r| (num(&r[2]), num(&r[3])))
        .collect();
    assert!(!drawn.is_empty());
    let recorded: Vec<(f64, f64)> = states[1..]
        .iter()
        .map(|r| (num(&r[d]), num(&r[f])))
        .collect();
    for p in &drawn {
        assert!(recorded.contains(p), "{p:?} is no recorded state");
    }
}

#[test]
fn a_pressure_map_in_pdf_alone_with_the_cells_it_draws() {
    use ndarray::{Array1, Array3};
    use ndarray_npy::NpzReader;
    let dir = tempfile::tempdir().unwrap();
    let mut args = SHORT.to_vec();
    args.extend([
        "--fields",
        "minimum",
        "--figure-format",
        "pdf",
        "--out",
        "r.csv",
    ]);
    let o = jkrbem(&args, dir.path());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let d = dir.path();
    assert!(std::fs::read(d.join("r.pressure.pdf"))
        .unwrap()
        .starts_with(b"%PDF-"));
    assert!(
        !d.join("r.pressure.svg").exists(),
        "only the formats asked for"
    );
    assert!(stdout(&o).contains("r.pressure.plot.csv"), "{}", stdout(&o));
    // The cells cover the contact: Σ p × width × height over them is Σ p Δx² over the grid.
    let mut npz = NpzReader::new(std::fs::File::open(d.join("r.fields.npz")).unwrap()).unwrap();
    let p: Array3<f64> = npz.by_name("pressure").unwrap();
    let dx: Array1<f64> = npz.by_name("dx").unwrap();
    let last = dx.len() - 1;
    let force = p.index_axis(ndarray::Axis(0), last).sum() * dx[last] * dx[last];
    let cells = csv_rows(&d.join("r.pressure.plot.csv"));
    assert_eq!(cells[0], ["x", "y", "p", "width", "height"]);
    let num = |t: &str| t.parse::<f64>().unwrap();
    let sum: f64 = cells[1..]
        .iter()
        .map(|c| num(&c[2]) * num(&c[3]) * num(&c[4]))
        .sum();
    assert!(
        (sum - force).abs() <= 1e-9 * force.abs(),
        "{sum} vs {force}"
    );
    // On a 32 grid no cell is a block of several: one row per element of the window, each
    // its element's pressure.
    let nx = p.shape()[2];
    assert!(cells.len() - 1 <= nx * p.shape()[1]);
    let values: Vec<f64> = p
        .index_axis(ndarray::Axis(0), last)
        .iter()
        .copied()
        .collect();
    for c in &cells[1..] {
        assert!(values.contains(&num(&c[2])), "{c:?}");
    }
}

#[test]
fn an_unknown_or_repeated_format_is_refused_naming_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let mut args = SHORT.to_vec();
    args.extend(["--fields", "minimum", "--figure-format", "svg,jpeg"]);
    args.extend(["--out", "r.csv"]);
    let o = jkrbem(&args, dir.path());
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("--figure-format")
            && err.contains("\"jpeg\"")
            && err.contains("svg, pdf, png"),
        "{err}"
    );
    assert!(
        !dir.path().join("r.csv").exists(),
        "refused before any work"
    );
    for (command, value, words) in [
        ("sweep", "tiff", ["\"tiff\" is not one of svg, pdf, png"]),
        ("bench", "png,png", ["png is given more than once"]),
        ("collect", "", ["one or more of svg, pdf, png"]),
    ] {
        let mut args = vec![command, "--figure-format", value];
        if command == "collect" {
            args.push("sw");
        }
        let o = jkrbem(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{command}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains("--figure-format"), "{command}: {err}");
        for w in words {
            assert!(err.contains(w), "{command}: {w:?} not in {err}");
        }
    }
    assert!(names_in(dir.path(), |_| true).is_empty());
}

#[test]
fn a_figure_file_is_planned_with_the_other_outputs() {
    // Each new file takes part in the check of one run's outputs against each other, before
    // any work: a summary named as the pressure map's PDF or its data is refused.
    let dir = tempfile::tempdir().unwrap();
    for (format, file) in [("pdf", "a.pressure.pdf"), ("png", "a.pressure.plot.csv")] {
        let mut args = SHORT.to_vec();
        args.extend([
            "--out",
            "a.csv",
            "--fields",
            "minimum",
            "--figure-format",
            format,
            "--summary",
            file,
        ]);
        let o = jkrbem(&args, dir.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let want = format!("--summary {file} is the same file as --fields {file}");
        assert!(stderr(&o).contains(&want), "{}", stderr(&o));
        assert!(names_in(dir.path(), |_| true).is_empty());
    }
}
