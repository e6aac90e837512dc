//! A heat map of one state's contact pressure, written as SVG with `plotters`: the region
//! around the contact (its cells averaged in blocks where the grid is finer than the picture),
//! compression red and tension blue on a scale symmetric about zero and set by the contact's
//! interior (the edge's tension singularity would leave the interior white; cells beyond the
//! scale are drawn at its ends, and the colour bar says so), the contact's outline (the
//! element sides between contact and no contact), and a colour bar in force/length².

#[cfg(feature = "figures")]
use super::chart::{linear_tick_label, plot_frame, render_svg};
use super::figure::{write_figure, FigureFormats, PlotRecord};
#[cfg(feature = "figures")]
use super::figure_style::{AXIS_FONT, LABEL_FONT, MARGIN, PAGE_WIDTH, TITLE_FONT};
#[cfg(feature = "figures")]
use super::legend::with_plot_area;
use super::OutputError;
use crate::analysis::fields::StateFields;
#[cfg(feature = "figures")]
use plotters::prelude::*;
#[cfg(feature = "figures")]
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// The most cells the picture draws along a side.
const MAX_CELLS: usize = 160;
/// The width of the colour bar's zone: the bar, its labels and its title (px).
#[cfg(feature = "figures")]
const BAR_ZONE: u32 = 125;
/// The colour bar's own width (px).
#[cfg(feature = "figures")]
const BAR_WIDTH: i32 = 16;
/// The share of the interior's |p| below the colour scale's end (dimensionless).
const SCALE_QUANTILE: f64 = 0.98;
/// The free border around the contact's box (relative to its size).
const BORDER: f64 = 0.15;

/// The colour of p/scale ∈ [−1, 1]: blue (tension) through white to red (compression).
#[cfg(feature = "figures")]
fn colour(t: f64) -> RGBColor {
    let t = t.clamp(-1.0, 1.0);
    let fade = |v: f64| (255.0 * (1.0 - v.abs())) as u8;
    if t >= 0.0 {
        RGBColor(255, fade(t), fade(t))
    } else {
        RGBColor(fade(t), fade(t), 255)
    }
}

/// The contact's bounding box as index ranges [i0, i1) × [j0, j1), or `None` where no element
/// is in contact.
pub(crate) fn contact_box(f: &StateFields) -> Option<(usize, usize, usize, usize)> {
    let (mut i0, mut i1, mut j0, mut j1) = (f.nx, 0, f.ny, 0);
    for j in 0..f.ny {
        for i in 0..f.nx {
            if f.contact[j * f.nx + i] {
                (i0, i1, j0, j1) = (i0.min(i), i1.max(i + 1), j0.min(j), j1.max(j + 1));
            }
        }
    }
    (i1 > i0 && j1 > j0).then_some((i0, i1, j0, j1))
}

/// The index ranges [i0, i1) × [j0, j1) around the contact, with the border.
pub(crate) fn window(f: &StateFields) -> (usize, usize, usize, usize) {
    let Some((i0, i1, j0, j1)) = contact_box(f) else {
        return (0, f.nx, 0, f.ny);
    };
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

/// Without the `figures` feature no chart is drawn: always
/// [`NOT_DRAWN`](super::figure::NOT_DRAWN).
#[cfg(not(feature = "figures"))]
pub fn pressure_svg(_f: &StateFields, _title: &str) -> Result<String, String> {
    Err(super::figure::NOT_DRAWN.into())
}

/// The SVG heat map of `f`'s pressure, titled `title`.
#[cfg(feature = "figures")]
pub fn pressure_svg(f: &StateFields, title: &str) -> Result<String, String> {
    let (i0, i1, j0, j1) = window(f);
    let (scale, peak) = colour_scale(f);
    let half = 0.5 * f.dx;
    let (x0, x1) = (f.x[i0] - half, f.x[i1 - 1] + half);
    let (y0, y1) = (f.y[j0] - half, f.y[j1 - 1] + half);
    // Equal scales on x and y: the plot's height follows the window's aspect (within limits).
    let (x_labels, y_labels) = (40, 60);
    let map_w = PAGE_WIDTH - BAR_ZONE;
    let plot_w = (map_w - 2 * MARGIN - y_labels) as f64;
    let plot_h = (plot_w * (y1 - y0) / (x1 - x0)).clamp(160.0, 1.4 * plot_w);
    let extra_h = 2 * MARGIN + x_labels + TITLE_FONT + 12;
    let size = (PAGE_WIDTH, plot_h as u32 + extra_h);
    let mut area = (0, 0, 0, 0);
    let svg = render_svg(size, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (map, _) = root.split_horizontally(map_w);
        let mut chart = ChartBuilder::on(&map)
            .caption(title, ("sans-serif", TITLE_FONT))
            .margin(MARGIN)
            .x_label_area_size(x_labels)
            .y_label_area_size(y_labels)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .disable_mesh()
            .label_style(("sans-serif", LABEL_FONT))
            .axis_desc_style(("sans-serif", AXIS_FONT))
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
        area = plot_frame(&chart).area;
        let (_, top, _, bottom) = area;
        draw_colour_bar(root, (map_w as i32 + 8, top, bottom), scale, peak)
    })?;
    Ok(with_plot_area(svg, area))
}

/// The colour scale of `f`'s map and the largest |p| (force/length²): the
/// [`SCALE_QUANTILE`] quantile of |p| over the contact's interior elements (those whose four
/// neighbours are in contact too), or the largest |p| where there is no interior.
pub(crate) fn colour_scale(f: &StateFields) -> (f64, f64) {
    let peak = f
        .pressure
        .iter()
        .fold(0.0f64, |m, p| m.max(p.abs()))
        .max(f64::MIN_POSITIVE);
    let c = |i: usize, j: usize| f.contact[j * f.nx + i];
    let mut interior: Vec<f64> = Vec::new();
    for j in 1..f.ny.saturating_sub(1) {
        for i in 1..f.nx.saturating_sub(1) {
            if c(i, j) && c(i - 1, j) && c(i + 1, j) && c(i, j - 1) && c(i, j + 1) {
                interior.push(f.pressure[j * f.nx + i].abs());
            }
        }
    }
    if interior.is_empty() {
        return (peak, peak);
    }
    interior.sort_by(f64::total_cmp);
    let k = ((interior.len() - 1) as f64 * SCALE_QUANTILE).round() as usize;
    (interior[k].max(f64::MIN_POSITIVE).min(peak), peak)
}

/// The colour bar at `(x, top, bottom)` (px in `root`): p from −scale to +scale
/// (force/length²), five labels to its right and its title beside them; where `peak` lies
/// beyond the scale, two lines above the bar say that the colours are clipped there.
#[cfg(feature = "figures")]
fn draw_colour_bar(
    root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    (x, top, bottom): (i32, i32, i32),
    scale: f64,
    peak: f64,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<_>| e.to_string();
    let label = TextStyle::from(("sans-serif", LABEL_FONT).into_font())
        .pos(Pos::new(HPos::Left, VPos::Center));
    // Where the colours are clipped, two lines above the bar say so; the bar starts below.
    let line = LABEL_FONT as i32 + 4;
    let top = if peak > scale * (1.0 + 1e-9) {
        let note = [
            format!("clipped at ±{}", linear_tick_label(scale)),
            format!("(|p| up to {})", linear_tick_label(peak)),
        ];
        for (k, text) in note.into_iter().enumerate() {
            root.draw(&Text::new(
                text,
                (x, top + line * k as i32 + line / 2),
                label.clone(),
            ))
            .map_err(err)?;
        }
        top + 2 * line + 6
    } else {
        top
    };
    let steps = 100;
    let height = (bottom - top).max(1) as f64;
    for k in 0..steps {
        // Band k from the bottom (−scale) up.
        let (lo, hi) = (k as f64 / steps as f64, (k + 1) as f64 / steps as f64);
        let y = |t: f64| bottom - (t * height).round() as i32;
        root.draw(&Rectangle::new(
            [(x, y(hi)), (x + BAR_WIDTH, y(lo))],
            colour(2.0 * (lo + hi) / 2.0 - 1.0).filled(),
        ))
        .map_err(err)?;
    }
    root.draw(&Rectangle::new(
        [(x, top), (x + BAR_WIDTH, bottom)],
        BLACK.mix(0.5).stroke_width(1),
    ))
    .map_err(err)?;
    for k in 0..=4 {
        let t = k as f64 / 4.0;
        let y = bottom - (t * height).round() as i32;
        root.draw(&PathElement::new(
            vec![(x + BAR_WIDTH, y), (x + BAR_WIDTH + 4, y)],
            BLACK.stroke_width(1),
        ))
        .map_err(err)?;
        let value = linear_tick_label(scale * (2.0 * t - 1.0)).replace('-', "−");
        root.draw(&Text::new(value, (x + BAR_WIDTH + 7, y), label.clone()))
            .map_err(err)?;
    }
    let title = "p (force/length²)";
    let vertical = TextStyle::from(("sans-serif", AXIS_FONT).into_font())
        .transform(FontTransform::Rotate270)
        .pos(Pos::new(HPos::Center, VPos::Center));
    root.draw(&Text::new(
        title,
        (x + BAR_WIDTH + 7 + 58, (top + bottom) / 2),
        vertical,
    ))
    .map_err(err)?;
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
