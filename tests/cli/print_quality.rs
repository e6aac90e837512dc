//! Every chart the program makes, rendered as a reader sees it (usvg, with the embedded
//! font's real glyph metrics) and checked for what a figure in a paper must not have: text
//! that overlaps other text or leaves the canvas, a plot that takes less than two thirds of
//! the figure's width, and tick labels that read "-0".

use crate::common;

use jkrbem::output::legend::PLOT_AREA_NOTE;
use jkrbem::output::render::{svg_tree, text_boxes};
use std::path::{Path, PathBuf};

/// Least share of the figure's width its plot area takes.
const PLOT_SHARE: f64 = 2.0 / 3.0;

/// Overlap (px²) two text boxes may share: glyph boxes of neighbouring lines touch.
const OVERLAP_PX2: f32 = 2.0;

/// Every SVG under `dir`, sorted.
fn svgs(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(svgs(&p));
        } else if p.extension().is_some_and(|x| x == "svg") {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// What is wrong with one rendered chart (empty: nothing).
fn faults(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap();
    let name = path.file_name().unwrap().to_string_lossy().to_string();
    let tree = svg_tree(&svg).unwrap_or_else(|e| panic!("{name}: {e}"));
    let size = tree.size();
    let (w, h) = (size.width(), size.height());
    let boxes = text_boxes(&tree);
    let mut out = Vec::new();
    assert!(!boxes.is_empty(), "{name}: no text was rendered");
    for (text, [x0, y0, x1, y1]) in &boxes {
        if *x0 < -0.5 || *y0 < -0.5 || *x1 > w + 0.5 || *y1 > h + 0.5 {
            out.push(format!(
                "{name}: {text:?} leaves the {w}×{h} canvas at [{x0:.1}, {y0:.1}, {x1:.1}, {y1:.1}]"
            ));
        }
        let t = text.trim();
        if t == "-0" || t == "−0" || t == "-0.0" {
            out.push(format!("{name}: a label reads {t:?}"));
        }
    }
    for (i, (a, ba)) in boxes.iter().enumerate() {
        for (b, bb) in &boxes[i + 1..] {
            let ox = (ba[2].min(bb[2]) - ba[0].max(bb[0])).max(0.0);
            let oy = (ba[3].min(bb[3]) - ba[1].max(bb[1])).max(0.0);
            if ox * oy > OVERLAP_PX2 {
                out.push(format!(
                    "{name}: {a:?} and {b:?} overlap ({:.0} px²)",
                    ox * oy
                ));
            }
        }
    }
    let note = svg
        .split(&format!("<!-- {PLOT_AREA_NOTE} "))
        .nth(1)
        .and_then(|r| r.split(" -->").next())
        .unwrap_or_else(|| panic!("{name}: no plot area recorded"));
    let v: Vec<f64> = note.split(' ').map(|x| x.parse().unwrap()).collect();
    let share = (v[2] - v[0]) / w as f64;
    if share < PLOT_SHARE {
        out.push(format!(
            "{name}: the plot takes {:.0} % of the width",
            100.0 * share
        ));
    }
    out
}

#[test]
fn slow_every_chart_renders_cleanly_for_print() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let runs: [&[&str]; 5] = [
        &[
            "reproduce",
            "--quick",
            "--backend",
            "cpu",
            "--jobs",
            "2",
            "--out",
            "study",
        ],
        &[
            "simulate",
            "--ratio",
            "3",
            "--grid",
            "64",
            "--backend",
            "cpu",
            "--fields",
            "minimum",
            "--out",
            "fields/s.csv",
        ],
        // The sphere: its profile chart draws JKR's closed form beside the elements.
        &[
            "simulate",
            "--ratio",
            "1",
            "--grid",
            "64",
            "--backend",
            "cpu",
            "--fields",
            "minimum",
            "--out",
            "fields/sphere.csv",
        ],
        &[
            "accuracy",
            "--grids",
            "32,64",
            "--backends",
            "cpu",
            "--out",
            "accuracy",
        ],
        &[
            "bench",
            "--backends",
            "cpu",
            "--grids",
            "16,32",
            "--pulloff-max-grid",
            "0",
            "--repeats",
            "1",
            "--out",
            "bench",
        ],
    ];
    for args in runs {
        let o = common::jkrbem(args, d);
        assert!(o.status.success(), "{args:?}: {}", common::stderr(&o));
    }
    let files = svgs(d);
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
        .collect();
    println!("{} charts: {names:?}", files.len());
    // The study's eleven, two pressure maps and two profiles, the accuracy chart and the
    // bench chart.
    assert!(files.len() >= 17, "{names:?}");
    for name in ["s.profile.svg", "sphere.profile.svg"] {
        assert!(names.iter().any(|n| n == name), "no {name}: {names:?}");
    }
    let all: Vec<String> = files.iter().flat_map(|p| faults(p)).collect();
    assert!(all.is_empty(), "{}", all.join("\n"));
}

#[test]
fn the_checks_catch_overlapping_and_cut_text_a_narrow_plot_and_minus_zero() {
    // A made-up figure with each fault: each is found.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.svg");
    let svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="300" height="200">
<text x="10" y="50" font-family="sans-serif" font-size="14">first label</text>
<text x="20" y="52" font-family="sans-serif" font-size="14">second label</text>
<text x="250" y="100" font-family="sans-serif" font-size="14">cut at the edge</text>
<text x="100" y="150" font-family="sans-serif" font-size="14">-0</text>
<!-- {PLOT_AREA_NOTE} 10 10 150 190 -->
</svg>"#
    );
    std::fs::write(&path, svg).unwrap();
    let found = faults(&path);
    println!("{}", found.join("\n"));
    assert!(found.iter().any(|f| f.contains("overlap")), "{found:?}");
    assert!(found.iter().any(|f| f.contains("leaves")), "{found:?}");
    assert!(found.iter().any(|f| f.contains("reads")), "{found:?}");
    assert!(
        found.iter().any(|f| f.contains("of the width")),
        "{found:?}"
    );
}
