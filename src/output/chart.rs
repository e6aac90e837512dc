//! Line charts on log–log axes, written as SVG with `plotters`: any number of labelled series
//! of (x, y) points, each drawn as a line through markers. Ticks sit at the series' own x
//! values when there are few of them (grid sizes), otherwise on a 1–2–5 sequence. The legend
//! sits inside the plot in a corner free of data, or below it (`legend`), and shows each
//! series as it is drawn; the style is `figure_style`'s (the helpers here serve the linear
//! charts too).

use super::figure::{write_figure, FigureFormats, PlotPoint};
#[cfg(feature = "figures")]
use super::figure_style::{
    colour, draw_markers, AXIS_FONT, DASH, LABEL_FONT, LINE_WIDTH, MARGIN, MARKER_RADIUS,
    TITLE_FONT, X_LABEL_AREA, Y_LABEL_AREA,
};
use super::figure_style::{PAGE_HEIGHT, PAGE_WIDTH};
#[cfg(feature = "figures")]
use super::legend::{render_with_legend, Legend, PlotFrame, Sample};
use super::OutputError;
#[cfg(feature = "figures")]
use plotters::prelude::*;
use std::path::Path;

/// Most distinct x values that still get one tick each.
#[cfg(feature = "figures")]
const MAX_DATA_TICKS: usize = 12;

/// One labelled series of points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Points (x, y) in the chart's units; points with x or y not finite and positive have no
    /// place on log axes and are left out.
    pub points: Vec<(f64, f64)>,
    /// Colour index (series of one group, e.g. one backend, share it).
    pub color: usize,
    /// Dashed line and hollow markers, to tell a second family of series apart.
    pub dashed: bool,
    /// Half-widths of vertical error bars, one per point, in y's unit (empty: none; a
    /// non-finite or non-positive one draws no bar). A bar whose lower end is not positive
    /// runs down to the axis' bottom.
    pub errors: Vec<f64>,
}

/// A chart of [`Series`] on logarithmic x and y axes.
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogChart {
    /// Caption above the plot.
    pub title: String,
    /// x-axis description, with its unit.
    pub x_label: String,
    /// y-axis description, with its unit.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Size of the plot and its axes (px); a legend that fits in no corner of the plot is
    /// added below.
    pub size: (u32, u32),
    /// Put x ticks at the data's own x values when there are few (grid sizes); otherwise on
    /// a 1–2–5 sequence (times).
    pub x_data_ticks: bool,
}

impl LogLogChart {
    /// An empty chart of the page's width ([`PAGE_WIDTH`] × [`PAGE_HEIGHT`]).
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        LogLogChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            size: (PAGE_WIDTH, PAGE_HEIGHT),
            x_data_ticks: true,
        }
    }

    /// Add a series.
    pub fn push(&mut self, series: Series) {
        self.series.push(series);
    }

    /// The chart as an SVG document: the plot at [`LogLogChart::size`], the legend inside it
    /// or below.
    #[cfg(feature = "figures")]
    pub fn to_svg(&self) -> Result<String, String> {
        render_with_legend(self.size, &self.legend(), |root| {
            self.draw(root).map_err(|e| e.to_string())
        })
    }

    /// Without the `figures` feature no chart is drawn: always
    /// [`NOT_DRAWN`](super::figure::NOT_DRAWN).
    #[cfg(not(feature = "figures"))]
    pub fn to_svg(&self) -> Result<String, String> {
        Err(super::figure::NOT_DRAWN.into())
    }

    /// The legend: a line through a marker, dashed and hollow for dashed series.
    #[cfg(feature = "figures")]
    fn legend(&self) -> Legend {
        Legend::new(
            self.series
                .iter()
                .map(|s| {
                    (
                        s.label.clone(),
                        Sample {
                            colour: s.color,
                            line: Some(s.dashed.then_some(DASH)),
                            marker: Some(!s.dashed),
                        },
                    )
                })
                .collect(),
        )
    }

    /// Write the chart to `path` (its SVG path) in each of `formats`, and the points it draws
    /// to `<stem>.plot.csv` ([`write_figure`]), creating the folder.
    pub fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        write_figure(path, self.to_svg(), &self.plot_points(), formats)
    }

    /// Every point the chart draws, series by series: those with a place on log axes (x and
    /// y finite and positive), each drawn as a marker on the series' line.
    pub fn plot_points(&self) -> Vec<PlotPoint> {
        self.series
            .iter()
            .flat_map(|s| {
                let style = if s.dashed {
                    "dashed+markers"
                } else {
                    "line+markers"
                };
                plottable_with_errors(s).map(move |((x, y), e)| PlotPoint {
                    series: s.label.clone(),
                    style,
                    x,
                    y,
                    error: e,
                })
            })
            .collect()
    }

    /// Every point with a place on the axes, and the top of its error bar: what the ranges
    /// must hold.
    #[cfg(feature = "figures")]
    fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series.iter().flat_map(|s| {
            plottable_with_errors(s)
                .flat_map(|((x, y), e)| std::iter::once((x, y)).chain(e.map(|e| (x, y + e))))
        })
    }

    #[cfg(feature = "figures")]
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<PlotFrame, DrawingAreaErrorKind<DB::ErrorType>> {
        let (xs, ys): (Vec<f64>, Vec<f64>) = self.points().unzip();
        let (x_range, x_ticks) = axis(&xs, self.x_data_ticks);
        let (y_range, y_ticks) = axis(&ys, false);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", TITLE_FONT))
            .margin(MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA)
            .build_cartesian_2d(
                x_range.log_scale().with_key_points(x_ticks),
                y_range.clone().log_scale().with_key_points(y_ticks),
            )?;
        let tick = |v: &f64| tick_label(*v);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", LABEL_FONT))
            .axis_desc_style(("sans-serif", AXIS_FONT))
            .bold_line_style(BLACK.mix(0.1))
            .light_line_style(TRANSPARENT)
            .draw()?;
        let mut frame = plot_frame(&chart);
        for s in &self.series {
            let line = colour(s.color).stroke_width(LINE_WIDTH);
            let pts: Vec<(f64, f64)> = plottable(&s.points).collect();
            draw_markers(
                chart.plotting_area(),
                &pts,
                s.color,
                MARKER_RADIUS,
                !s.dashed,
            )?;
            if s.dashed {
                chart.draw_series(DashedLineSeries::new(pts.clone(), DASH.0, DASH.1, line))?;
            } else {
                chart.draw_series(LineSeries::new(pts.clone(), line))?;
            }
            let pixels: Vec<(i32, i32)> = pts.iter().map(|p| chart.backend_coord(p)).collect();
            // Bars from y − e (or the axis' bottom, where that is not positive) to y + e.
            let bars: Vec<((f64, f64), f64, f64)> = plottable_with_errors(s)
                .filter_map(|((x, y), e)| {
                    let e = e?;
                    Some(((x, y), (y - e).max(y_range.start), y + e))
                })
                .collect();
            chart.draw_series(bars.iter().map(|&((x, y), low, high)| {
                ErrorBar::new_vertical(x, low, y, high, colour(s.color).stroke_width(1), 6)
            }))?;
            for &((x, _), low, high) in &bars {
                let ends = [(x, low), (x, high)].map(|p| chart.backend_coord(&p));
                frame.mark_line(&ends);
            }
            frame.mark_line(&pixels);
        }
        Ok(frame)
    }
}

/// The plot area of `chart` in the picture's pixels, with nothing marked yet.
#[cfg(feature = "figures")]
pub(crate) fn plot_frame<DB: DrawingBackend, CT: plotters::coord::CoordTranslate>(
    chart: &ChartContext<'_, DB, CT>,
) -> PlotFrame {
    let (x, y) = chart.plotting_area().get_pixel_range();
    PlotFrame {
        area: (x.start, y.start, x.end, y.end),
        occupied: Vec::new(),
    }
}

/// Render a chart drawn by `draw` into an SVG document of `size` pixels.
#[cfg(feature = "figures")]
pub(crate) fn render_svg(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend, plotters::coord::Shift>) -> Result<(), String>,
) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        draw(&root)?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// The points of a series that have a place on log axes, each with its error bar's
/// half-width where it has one.
fn plottable_with_errors(s: &Series) -> impl Iterator<Item = ((f64, f64), Option<f64>)> + '_ {
    s.points
        .iter()
        .enumerate()
        .filter(|(_, &(x, y))| x.is_finite() && x > 0.0 && y.is_finite() && y > 0.0)
        .map(|(i, &p)| {
            let e = s
                .errors
                .get(i)
                .copied()
                .filter(|e| e.is_finite() && *e > 0.0);
            (p, e)
        })
}

/// The points of a series that have a place on log axes.
#[cfg(feature = "figures")]
fn plottable(points: &[(f64, f64)]) -> impl Iterator<Item = (f64, f64)> + '_ {
    points
        .iter()
        .copied()
        .filter(|&(x, y)| x.is_finite() && x > 0.0 && y.is_finite() && y > 0.0)
}

/// The range of one axis, padded by a fifth of a decade either side, and its ticks: the
/// data's own values when `data_ticks` and there are at most [`MAX_DATA_TICKS`] of them,
/// otherwise the 1–2–5 values inside the range (only the decades if those are too many).
#[cfg(feature = "figures")]
fn axis(values: &[f64], data_ticks: bool) -> (std::ops::Range<f64>, Vec<f64>) {
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (lo, hi) = if lo.is_finite() {
        (lo, hi)
    } else {
        (1.0, 10.0)
    };
    let pad = 10f64.powf(0.2);
    let range = lo / pad..hi * pad;
    let mut distinct: Vec<f64> = values.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    if data_ticks && (2..=MAX_DATA_TICKS).contains(&distinct.len()) {
        return (range, distinct);
    }
    let decades = (range.start.log10().floor() as i32)..=(range.end.log10().ceil() as i32);
    let in_range = |v: &f64| range.contains(v);
    let ticks: Vec<f64> = decades
        .clone()
        .flat_map(|e| [1.0, 2.0, 5.0].map(|m| m * 10f64.powi(e)))
        .filter(in_range)
        .collect();
    let ticks = if ticks.len() > 15 {
        decades.map(|e| 10f64.powi(e)).filter(in_range).collect()
    } else {
        ticks
    };
    (range, ticks)
}

/// A tick value with three significant digits and no trailing zeros ("0.002", "1.5", "256");
/// scientific notation outside [10⁻³, 10⁵).
pub fn tick_label(v: f64) -> String {
    if v == 0.0 {
        // −0 (from arithmetic on the tick values) reads as 0.
        return "0".into();
    }
    if !v.is_finite() {
        return format!("{v}");
    }
    let e = v.abs().log10().floor() as i32;
    if !(-3..5).contains(&e) {
        return format!("{v:.1e}").replace(".0e", "e");
    }
    let s = format!("{v:.*}", (2 - e).max(0) as usize);
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A tick value of a linear axis, rounded to three decimals ("0.25", "-1.5", "3"); a value
/// that rounds to zero reads "0", never "-0".
pub fn linear_tick_label(v: f64) -> String {
    let rounded = (v * 1000.0).round() / 1000.0;
    // Adding +0 turns −0 into +0 and leaves every other value as it is.
    format!("{}", rounded + 0.0)
}

impl super::figure::WriteFigure for LogLogChart {
    fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        LogLogChart::write_figure(self, path, formats)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick_label(0.002), "0.002");
        assert_eq!(tick_label(1.5), "1.5");
        assert_eq!(tick_label(256.0), "256");
        assert_eq!(tick_label(20.0), "20");
        assert_eq!(tick_label(1e-5), "1e-5");
    }

    #[test]
    fn no_tick_label_reads_minus_zero() {
        // Before: a tick a rounding error below zero (−1e-17) read "-0" on the linear charts
        // of `reproduce` (f_of_c.svg, f_of_d.svg, d_of_c.svg), and −0 read "-0" on log ones.
        for v in [-0.0, -1e-17, -4e-4, -0.0004999, 1e-17, 0.0] {
            assert_eq!(linear_tick_label(v), "0", "{v:e}");
        }
        assert_eq!(tick_label(-0.0), "0");
        assert_eq!(linear_tick_label(-0.25), "-0.25");
        assert_eq!(linear_tick_label(-0.0005), "-0.001");
        assert_eq!(linear_tick_label(1.5), "1.5");
        assert_eq!(linear_tick_label(-2.0), "-2");
        // Ticks as an axis computes them (k steps from a start), many a rounding error off 0.
        for (start, step) in [(-0.3, 0.1), (-0.35, 0.05), (-1.2, 0.2), (-0.07, 0.01)] {
            for k in 0..=100 {
                let t = linear_tick_label(start + k as f64 * step);
                assert_ne!(t, "-0", "{start} + {k} × {step}");
            }
        }
    }

    #[cfg(feature = "figures")]
    #[test]
    fn a_long_legend_label_wraps_inside_the_picture() {
        // Before: a 30-ratio sweep's label ran past the picture's right edge.
        let grids = vec!["32"; 30].join(", ");
        let label = format!("jkrbem at Δx → 0, ± stated uncertainty (Nx = {grids})");
        let mut c = LogLogChart::new("t", "x", "y");
        c.push(Series {
            label,
            points: vec![(1.0, 1.0), (2.0, 3.0)],
            color: 0,
            dashed: false,
            errors: Vec::new(),
        });
        let svg = c.to_svg().unwrap();
        let width: f64 = svg
            .split_once("width=\"")
            .and_then(|(_, r)| r.split_once('"'))
            .and_then(|(w, _)| w.parse().ok())
            .unwrap();
        for part in svg.split("<text").skip(1) {
            let x: f64 = part
                .split_once(" x=\"")
                .and_then(|(_, r)| r.split_once('"'))
                .and_then(|(x, _)| x.parse().ok())
                .unwrap();
            let text = part
                .split_once('>')
                .unwrap()
                .1
                .split("</text>")
                .next()
                .unwrap();
            let right = x + crate::output::figure_style::text_width(text.trim(), LABEL_FONT) as f64;
            assert!(right <= width, "{text:?} ends at {right} > {width}");
        }
    }

    #[cfg(feature = "figures")]
    #[test]
    fn few_x_values_are_their_own_ticks() {
        let (r, t) = axis(&[64.0, 128.0, 256.0, 64.0], true);
        assert_eq!(t, vec![64.0, 128.0, 256.0]);
        assert!(r.start < 64.0 && r.end > 256.0);
        let (_, t) = axis(&[0.3, 40.0], false);
        assert_eq!(t.first(), Some(&0.2));
        assert!(t.contains(&1.0) && t.contains(&50.0));
    }

    #[cfg(feature = "figures")]
    #[test]
    fn a_chart_renders_to_svg() {
        let mut c = LogLogChart::new("t", "x (unit)", "y (ms)");
        c.push(Series {
            label: "a".into(),
            points: vec![(16.0, 0.1), (32.0, 0.4), (64.0, -1.0)],
            color: 0,
            dashed: false,
            errors: Vec::new(),
        });
        c.push(Series {
            label: "b".into(),
            points: vec![(16.0, 0.2), (32.0, 0.9)],
            color: 1,
            dashed: true,
            errors: Vec::new(),
        });
        let svg = c.to_svg().unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..50]);
        // Its data: every point drawn, the one at y < 0 (no place on a log axis) left out.
        let points = c.plot_points();
        let drawn: Vec<(&str, &str, f64, f64)> = points
            .iter()
            .map(|p| (p.series.as_str(), p.style, p.x, p.y))
            .collect();
        assert_eq!(
            drawn,
            [
                ("a", "line+markers", 16.0, 0.1),
                ("a", "line+markers", 32.0, 0.4),
                ("b", "dashed+markers", 16.0, 0.2),
                ("b", "dashed+markers", 32.0, 0.9)
            ]
        );
        assert!(c.plot_points().iter().all(|p| p.error.is_none()));
        assert!(svg.contains("y (ms)") && svg.contains("\n32\n</text>"));
    }
}
