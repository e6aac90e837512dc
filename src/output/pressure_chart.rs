//! A heat map of one state's contact pressure, written as SVG with `plotters`: the region
//! around the contact (its cells averaged in blocks where the grid is finer than the picture),
//! compression red and tension blue on a scale symmetric about zero, the contact's outline
//! (the element sides between contact and no contact), and a colour bar in force/length².

use super::chart::{linear_tick_label, render_svg};
use super::figure::{write_figure, FigureFormats, PlotRecord};
use super::OutputError;
use crate::analysis::fields::StateFields;
use plotters::prelude::*;
use std::path::Path;

/// The most cells the picture draws along a side.
const MAX_CELLS: usize = 160;
/// The colour bar's width (pixels).
const BAR_WIDTH: u32 = 150;
/// The free border around the contact's box (relative to its size).
const BORDER: f64 = 0.15;

/// The colour of p/scale ∈ [−1, 1]: blue (tension) through white to red (compression).
fn colour(t: f64) -> RGBColor {
    let t = t.clamp(-1.0, 1.0);
    let fade = |v: f64| (255.0 * (1.0 - v.abs())) as u8;
    if t >= 0.0 {
        RGBColor(255, fade(t), fade(t))
    } else {
        RGBColor(fade(t), fade(t), 255)
    }
}

/// The index ranges [i0, i1) × [j0, j1) around the contact, with the border.
fn window(f: &StateFields) -> (usize, usize, usize, usize) {
    let (mut i0, mut i1, mut j0, mut j1) = (f.nx, 0, f.ny, 0);
    for j in 0..f.ny {
        for i in 0..f.nx {
            if f.contact[j * f.nx + i] {
                (i0, i1, j0, j1) = (i0.min(i), i1.max(i + 1), j0.min(j), j1.max(j + 1));
            }
        }
    }
    if i1 <= i0 || j1 <= j0 {
        return (0, f.nx, 0, f.ny);
    }
    let grow = |lo: usize, hi: usize, n: usize| {
        let b = ((hi - lo) as f64 * BORDER).ceil() as usize + 1;
        (lo.saturating_sub(b), (hi + b).min(n))
    };
    let (i0, i1) = grow(i0, i1, f.nx);
    let (j0, j1) = grow(j0, j1, f.ny);
    (i0, i1, j0, j1)
}

/// One cell the heat map draws: a block of elements (one element where the grid is no finer
/// than the picture; narrower at the window's edge) and its mean pressure, as
/// `<stem>.plot.csv` records it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PressureCell {
    /// The block's centre along x (length).
    pub x: f64,
    /// The block's centre along y (length).
    pub y: f64,
    /// The block's mean pressure (force/length²; p < 0 tensile).
    pub p: f64,
    /// The block's width along x (length).
    pub width: f64,
    /// The block's height along y (length).
    pub height: f64,
}

impl PlotRecord for PressureCell {
    const HEADER: &'static str = "x,y,p,width,height";
}

/// The cells the heat map of `f` draws, row by row from the lowest y: the window around the
/// contact (its bounding box and a border of 15 %), its elements averaged in square blocks so
/// that at most 160 cells lie along a side.
pub fn pressure_cells(f: &StateFields) -> Vec<PressureCell> {
    let (i0, i1, j0, j1) = window(f);
    let block = (i1 - i0).max(j1 - j0).div_ceil(MAX_CELLS).max(1);
    let half = 0.5 * f.dx;
    let mut cells = Vec::new();
    for jb in (j0..j1).step_by(block) {
        for ib in (i0..i1).step_by(block) {
            let (ie, je) = ((ib + block).min(i1), (jb + block).min(j1));
            let mut sum = 0.0;
            for j in jb..je {
                for i in ib..ie {
                    sum += f.pressure[j * f.nx + i];
                }
            }
            let (xa, xb) = (f.x[ib] - half, f.x[ie - 1] + half);
            let (ya, yb) = (f.y[jb] - half, f.y[je - 1] + half);
            cells.push(PressureCell {
                x: 0.5 * (xa + xb),
                y: 0.5 * (ya + yb),
                p: sum / ((ie - ib) * (je - jb)) as f64,
                width: xb - xa,
                height: yb - ya,
            });
        }
    }
    cells
}

/// The SVG heat map of `f`'s pressure, titled `title`.
pub fn pressure_svg(f: &StateFields, title: &str) -> Result<String, String> {
    let (i0, i1, j0, j1) = window(f);
    let scale = f
        .pressure
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs()))
        .max(f64::MIN_POSITIVE);
    let half = 0.5 * f.dx;
    let (x0, x1) = (f.x[i0] - half, f.x[i1 - 1] + half);
    let (y0, y1) = (f.y[j0] - half, f.y[j1 - 1] + half);
    // Equal scales on x and y: the plot's height follows the window's aspect (within limits).
    let (plot_w, extra_w, extra_h) = (560.0, 84.0, 98.0);
    let plot_h = (plot_w * (y1 - y0) / (x1 - x0)).clamp(160.0, 800.0);
    let map_w = (plot_w + extra_w) as u32;
    let size = (map_w + BAR_WIDTH, (plot_h + extra_h) as u32);
    render_svg(size, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (map, bar) = root.split_horizontally(map_w);
        let mut chart = ChartBuilder::on(&map)
            .caption(title, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .disable_mesh()
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 13))
            .x_desc("x (length)")
            .y_desc("y (length)")
            .x_label_formatter(&|v| linear_tick_label(*v))
            .y_label_formatter(&|v| linear_tick_label(*v))
            .draw()
            .map_err(|e| e.to_string())?;
        let cells = pressure_cells(f).into_iter().map(|c| {
            let (hw, hh) = (0.5 * c.width, 0.5 * c.height);
            Rectangle::new(
                [(c.x - hw, c.y - hh), (c.x + hw, c.y + hh)],
                colour(c.p / scale).filled(),
            )
        });
        chart.draw_series(cells).map_err(|e| e.to_string())?;
        // The outline: every element side between a contact element and one out of contact.
        let c = |i: usize, j: usize| f.contact[j * f.nx + i];
        let mut sides = Vec::new();
        for j in j0..j1 {
            for i in i0..i1 {
                let (x, y) = (f.x[i], f.y[j]);
                if i + 1 < i1 && c(i, j) != c(i + 1, j) {
                    sides.push(vec![(x + half, y - half), (x + half, y + half)]);
                }
                if j + 1 < j1 && c(i, j) != c(i, j + 1) {
                    sides.push(vec![(x - half, y + half), (x + half, y + half)]);
                }
            }
        }
        chart
            .draw_series(
                sides
                    .into_iter()
                    .map(|s| PathElement::new(s, BLACK.stroke_width(1))),
            )
            .map_err(|e| e.to_string())?;
        draw_colour_bar(&bar, scale)
    })
}

/// The colour bar: p from −scale to +scale (force/length²), with five labels.
fn draw_colour_bar(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    scale: f64,
) -> Result<(), String> {
    let mut chart = ChartBuilder::on(area)
        .margin_top(40)
        .margin_bottom(52)
        .margin_right(30)
        .y_label_area_size(72)
        .build_cartesian_2d(0.0..1.0, -scale..scale)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(5)
        .y_desc("p (force/length²)")
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 13))
        .y_label_formatter(&|v| linear_tick_label(*v))
        .draw()
        .map_err(|e| e.to_string())?;
    let steps = 100;
    let band = 2.0 * scale / steps as f64;
    chart
        .draw_series((0..steps).map(|k| {
            let lo = -scale + k as f64 * band;
            Rectangle::new(
                [(0.0, lo), (1.0, lo + band)],
                colour((lo + 0.5 * band) / scale).filled(),
            )
        }))
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// Write [`pressure_svg`] to `path` (its SVG path) in each of `formats`, and its cells
/// ([`pressure_cells`]) to `<stem>.plot.csv`.
pub fn write_pressure_chart(
    path: &Path,
    f: &StateFields,
    title: &str,
    formats: FigureFormats,
) -> Result<(), OutputError> {
    write_figure(path, pressure_svg(f, title), &pressure_cells(f), formats)
}
