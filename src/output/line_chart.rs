//! Charts on linear axes (optionally a logarithmic x axis), written as SVG with `plotters`:
//! simulated states as markers, closed forms and fits as lines drawn over them, each with a
//! legend entry drawn as its curve is, inside the plot where a corner is free of data, else
//! below it (never over the data). Shapes (contours) can be drawn with equal scales on both
//! axes.

#[cfg(feature = "figures")]
use super::chart::{linear_tick_label, plot_frame};
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

/// How a curve is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A solid line (closed forms).
    Line,
    /// A dashed line (fits, second references).
    Dashed,
    /// Markers only (simulated states).
    Markers,
    /// Hollow markers only: points set apart from the filled ones (from grids too coarse to
    /// be answers, say), with error bars like [`Style::Markers`].
    Hollow,
}

/// One labelled curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// Points (x, y) in the chart's units; non-finite points are left out.
    pub points: Vec<(f64, f64)>,
    /// Colour index.
    pub color: usize,
    /// Line, dashed line or markers.
    pub style: Style,
    /// Half-widths of vertical error bars, one per point (markers only; empty: none).
    pub errors: Vec<f64>,
}

/// A chart of [`Curve`]s.
#[derive(Debug, Clone, PartialEq)]
pub struct LineChart {
    /// Caption above the plot.
    pub title: String,
    /// x-axis description (normalised quantity or unit).
    pub x_label: String,
    /// y-axis description.
    pub y_label: String,
    /// Logarithmic x axis (ticks at 1, 2, 5 × 10^k).
    pub x_log: bool,
    /// The curves, drawn in order.
    pub curves: Vec<Curve>,
    /// Size of the plot and its axes (px); a legend that fits in no corner of the plot is
    /// added below.
    pub size: (u32, u32),
    /// Draw x and y on the same scale (one unit is as long on both axes), for shapes such as
    /// contours; the ranges are widened to fill the plot.
    pub equal_scales: bool,
}

/// An estimate as a chart draws it: (x, y) and the half-width of its stated uncertainty (in
/// y's unit).
pub type Estimate = ((f64, f64), f64);

/// The least height (px) of the plot of a chart with equal scales.
#[cfg(feature = "figures")]
const MIN_EQUAL_HEIGHT: u32 = 150;

impl LineChart {
    /// An empty chart of the page's width ([`PAGE_WIDTH`] × [`PAGE_HEIGHT`]) with linear
    /// axes.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_log: false,
            curves: Vec::new(),
            size: (PAGE_WIDTH, PAGE_HEIGHT),
            equal_scales: false,
        }
    }

    /// Add a curve.
    pub fn push(&mut self, label: &str, points: Vec<(f64, f64)>, color: usize, style: Style) {
        self.curves.push(Curve {
            label: label.into(),
            points,
            color,
            style,
            errors: Vec::new(),
        });
    }

    /// Add markers with vertical error bars of half-width `errors` (one per point, in the
    /// y unit; a non-finite one draws no bar).
    pub fn push_with_errors(
        &mut self,
        label: &str,
        points: Vec<(f64, f64)>,
        errors: Vec<f64>,
        color: usize,
    ) {
        self.curves.push(Curve {
            label: label.into(),
            points,
            color,
            style: Style::Markers,
            errors,
        });
    }

    /// Add estimates ((x, y), half-width of the stated uncertainty): `answers` as filled
    /// markers with error bars labelled `label`, and `coarse` ones (from grids too coarse for
    /// their estimate) as hollow markers labelled `coarse_label`; an empty group adds nothing.
    pub fn push_estimates(
        &mut self,
        (label, answers): (&str, Vec<Estimate>),
        (coarse_label, coarse): (&str, Vec<Estimate>),
        color: usize,
    ) {
        for (label, group, style) in [
            (label, answers, Style::Markers),
            (coarse_label, coarse, Style::Hollow),
        ] {
            if !group.is_empty() {
                let (points, errors) = group.into_iter().unzip();
                self.curves.push(Curve {
                    label: label.into(),
                    points,
                    color,
                    style,
                    errors,
                });
            }
        }
    }

    /// The chart as an SVG document: the plot at [`LineChart::size`], the legend inside it
    /// or below.
    #[cfg(feature = "figures")]
    pub fn to_svg(&self) -> Result<String, String> {
        render_with_legend(self.fitted_size(), &self.legend(), |root| {
            self.draw(root).map_err(|e| e.to_string())
        })
    }

    /// Without the `figures` feature no chart is drawn: always
    /// [`NOT_DRAWN`](super::figure::NOT_DRAWN).
    #[cfg(not(feature = "figures"))]
    pub fn to_svg(&self) -> Result<String, String> {
        Err(super::figure::NOT_DRAWN.into())
    }

    /// The legend, each entry drawn as its curve is.
    #[cfg(feature = "figures")]
    pub(super) fn legend(&self) -> Legend {
        Legend::new(
            self.curves
                .iter()
                .map(|c| {
                    let (line, marker) = match c.style {
                        Style::Line => (Some(None), None),
                        Style::Dashed => (Some(Some(DASH)), None),
                        Style::Markers => (None, Some(true)),
                        Style::Hollow => (None, Some(false)),
                    };
                    (
                        c.label.clone(),
                        Sample {
                            colour: c.color,
                            line,
                            marker,
                        },
                    )
                })
                .collect(),
        )
    }

    /// Widen `xr` and `yr` so that one unit spans as many pixels on both axes of a plot of
    /// `pixels` (width, height): an axis whose data (`centred`, x then y) lie on both sides of
    /// 0 (a whole outline) about its centre, any other (a quarter contour from its axes)
    /// keeping its lower end.
    #[cfg(feature = "figures")]
    fn equalised(
        xr: std::ops::Range<f64>,
        yr: std::ops::Range<f64>,
        pixels: (u32, u32),
        centred: (bool, bool),
    ) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
        let (pw, ph) = (pixels.0.max(1) as f64, pixels.1.max(1) as f64);
        let per_pixel = ((xr.end - xr.start) / pw).max((yr.end - yr.start) / ph);
        let widen = |r: std::ops::Range<f64>, span: f64, centred: bool| {
            if centred {
                let mid = 0.5 * (r.start + r.end);
                mid - 0.5 * span..mid + 0.5 * span
            } else {
                r.start..r.start + span
            }
        };
        (
            widen(xr, per_pixel * pw, centred.0),
            widen(yr, per_pixel * ph, centred.1),
        )
    }

    /// Write the chart to `path` (its SVG path) in each of `formats`, and the points it draws
    /// to `<stem>.plot.csv` ([`write_figure`]), creating the folder.
    pub fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        write_figure(path, self.to_svg(), &self.plot_points(), formats)
    }

    /// Every point the chart draws, curve by curve: a line's vertices or the markers, those
    /// with a place on the axes (finite; positive x on a log axis), each marker with the
    /// half-width of its error bar where one is drawn.
    pub fn plot_points(&self) -> Vec<PlotPoint> {
        self.curves
            .iter()
            .flat_map(|c| {
                let style = match c.style {
                    Style::Line => "line",
                    Style::Dashed => "dashed",
                    Style::Markers => "markers",
                    Style::Hollow => "hollow markers",
                };
                let bars = matches!(c.style, Style::Markers | Style::Hollow);
                self.plotted_with_errors(c)
                    .into_iter()
                    .map(move |((x, y), e)| PlotPoint {
                        series: c.label.clone(),
                        style,
                        x,
                        y,
                        error: (bars && e > 0.0).then_some(e),
                    })
            })
            .collect()
    }

    /// x ticks: on a log axis log10 of 1, 2, 5 × 10^k inside the range; on a linear axis
    /// about ten round values.
    #[cfg(feature = "figures")]
    fn x_ticks(&self, r: &std::ops::Range<f64>) -> Vec<f64> {
        if self.x_log {
            let decades = r.start.floor() as i32..=r.end.ceil() as i32;
            return decades
                .flat_map(|e| [1.0f64, 2.0, 5.0].map(|m| m.log10() + e as f64))
                .filter(|v| r.contains(v))
                .collect();
        }
        let raw = (r.end - r.start) / 10.0;
        let mag = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * mag)
            .find(|s| *s >= raw)
            .unwrap_or(raw);
        let first = (r.start / step).ceil() as i64;
        let last = (r.end / step).floor() as i64;
        (first..=last).map(|k| k as f64 * step).collect()
    }

    /// A curve's finite points (positive x on a log axis).
    #[cfg(feature = "figures")]
    fn plotted(&self, c: &Curve) -> Vec<(f64, f64)> {
        self.plotted_with_errors(c)
            .into_iter()
            .map(|(p, _)| p)
            .collect()
    }

    /// A curve's finite points with their error half-widths (0 where none is given).
    fn plotted_with_errors(&self, c: &Curve) -> Vec<((f64, f64), f64)> {
        c.points
            .iter()
            .enumerate()
            .filter(|(_, (x, y))| x.is_finite() && y.is_finite() && (!self.x_log || *x > 0.0))
            .map(|(i, &p)| {
                let e = c
                    .errors
                    .get(i)
                    .copied()
                    .filter(|e| e.is_finite() && *e > 0.0);
                (p, e.unwrap_or(0.0))
            })
            .collect()
    }

    /// Every point, and the ends of its error bar: what must be in range.
    #[cfg(feature = "figures")]
    fn extent(&self) -> Vec<(f64, f64)> {
        self.curves
            .iter()
            .flat_map(|c| self.plotted_with_errors(c))
            .flat_map(|((x, y), e)| [(x, y - e), (x, y + e)])
            .collect()
    }

    /// The linear ranges of x and y that hold `points`, padded by 5 % either side.
    #[cfg(feature = "figures")]
    fn ranges(points: &[(f64, f64)]) -> (std::ops::Range<f64>, std::ops::Range<f64>) {
        let range = |v: Vec<f64>| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            if !lo.is_finite() {
                return 0.0..1.0;
            }
            let pad = ((hi - lo) * 0.05).max(1e-9 * lo.abs().max(1.0));
            lo - pad..hi + pad
        };
        (
            range(points.iter().map(|p| p.0).collect()),
            range(points.iter().map(|p| p.1).collect()),
        )
    }

    /// The size of the plot and its axes (px): [`LineChart::size`], or with equal scales its
    /// height fitted to the data's aspect (at least [`MIN_EQUAL_HEIGHT`] px of plot), so that a
    /// slender shape fills the plot's width rather than a corner of a square.
    #[cfg(feature = "figures")]
    fn fitted_size(&self) -> (u32, u32) {
        if !self.equal_scales || self.x_log {
            return self.size;
        }
        let (xr, yr) = Self::ranges(&self.extent());
        let around = 2 * MARGIN + X_LABEL_AREA + TITLE_FONT + 10;
        let width = self.size.0.saturating_sub(2 * MARGIN + Y_LABEL_AREA) as f64;
        let aspect = (yr.end - yr.start) / (xr.end - xr.start);
        let height = (width * aspect).clamp(MIN_EQUAL_HEIGHT as f64, 4.0 * width);
        (
            self.size.0,
            (height.ceil() as u32 + around).min(self.size.1),
        )
    }

    #[cfg(feature = "figures")]
    pub(super) fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<PlotFrame, DrawingAreaErrorKind<DB::ErrorType>> {
        let all = self.extent();
        let (xr, yr) = Self::ranges(&all);
        if self.x_log {
            // The data's own extent, padded by a factor (a linear pad could reach x ≤ 0).
            let lo = all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let hi = all.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
            let (lo, hi) = if lo.is_finite() {
                (lo, hi)
            } else {
                (1.0, 10.0)
            };
            let (lo, hi) = (lo / 1.1, hi.max(lo * 1.5) * 1.1);
            let ticks = self.x_ticks(&(lo.log10()..hi.log10()));
            let ticks: Vec<f64> = ticks.iter().map(|t| 10f64.powf(*t)).collect();
            self.draw_on(root, (lo..hi).log_scale().with_key_points(ticks), yr)
        } else if self.equal_scales {
            // The plot's size in pixels: the area less the title, margins and label areas.
            let (w, h) = root.dim_in_pixel();
            let font: TextStyle = ("sans-serif", TITLE_FONT).into();
            let title = root
                .estimate_text_size(&self.title, &font)
                .map_or(24, |(_, th)| th + 2 * (th / 2).min(5));
            let pixels = (
                w.saturating_sub(2 * MARGIN + Y_LABEL_AREA),
                h.saturating_sub(2 * MARGIN + X_LABEL_AREA + title),
            );
            // The data's own extent (not the padded range, which reaches below 0 for any
            // shape drawn from an axis) says whether an axis is centred.
            let straddles = |v: fn(&(f64, f64)) -> f64| {
                all.iter().any(|p| v(p) < 0.0) && all.iter().any(|p| v(p) > 0.0)
            };
            let centred = (straddles(|p| p.0), straddles(|p| p.1));
            let (xr, yr) = Self::equalised(xr, yr, pixels, centred);
            self.draw_on(root, plotters::coord::types::RangedCoordf64::from(xr), yr)
        } else {
            self.draw_on(root, plotters::coord::types::RangedCoordf64::from(xr), yr)
        }
    }

    #[cfg(feature = "figures")]
    fn draw_on<DB: DrawingBackend, X>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        xr: X,
        yr: std::ops::Range<f64>,
    ) -> Result<PlotFrame, DrawingAreaErrorKind<DB::ErrorType>>
    where
        X: plotters::coord::ranged1d::Ranged<ValueType = f64>
            + plotters::coord::ranged1d::ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", TITLE_FONT))
            .margin(MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA)
            .build_cartesian_2d(xr, yr)?;
        let x_fmt = |v: &f64| linear_tick_label(*v);
        let y_fmt = |v: &f64| linear_tick_label(*v);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .label_style(("sans-serif", LABEL_FONT))
            .axis_desc_style(("sans-serif", AXIS_FONT))
            .bold_line_style(BLACK.mix(0.1))
            .light_line_style(TRANSPARENT)
            .draw()?;
        let mut frame = plot_frame(&chart);
        // Markers (the data) first, then the lines they are compared with, on top.
        let is_markers = |c: &&Curve| matches!(c.style, Style::Markers | Style::Hollow);
        let markers = self.curves.iter().filter(is_markers);
        let lines = self.curves.iter().filter(|c| !is_markers(c));
        for c in markers.chain(lines) {
            let line = colour(c.color).stroke_width(LINE_WIDTH);
            let pts = self.plotted(c);
            let pixels: Vec<(i32, i32)> = pts.iter().map(|p| chart.backend_coord(p)).collect();
            match c.style {
                Style::Line => {
                    chart.draw_series(LineSeries::new(pts, line))?;
                    frame.mark_line(&pixels);
                }
                Style::Dashed => {
                    chart.draw_series(DashedLineSeries::new(pts, DASH.0, DASH.1, line))?;
                    frame.mark_line(&pixels);
                }
                Style::Markers | Style::Hollow => {
                    let bars: Vec<((f64, f64), f64)> = self
                        .plotted_with_errors(c)
                        .into_iter()
                        .filter(|(_, e)| *e > 0.0)
                        .collect();
                    chart.draw_series(bars.iter().map(|&((x, y), e)| {
                        ErrorBar::new_vertical(
                            x,
                            y - e,
                            y,
                            y + e,
                            colour(c.color).stroke_width(1),
                            6,
                        )
                    }))?;
                    for &((x, y), e) in &bars {
                        let ends = [(x, y - e), (x, y + e)].map(|p| chart.backend_coord(&p));
                        frame.mark_line(&ends);
                    }
                    let filled = c.style == Style::Markers;
                    draw_markers(chart.plotting_area(), &pts, c.color, MARKER_RADIUS, filled)?;
                    pixels.iter().for_each(|&p| frame.mark(p));
                }
            };
        }
        Ok(frame)
    }
}

impl super::figure::WriteFigure for LineChart {
    fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        LineChart::write_figure(self, path, formats)
    }
}

// Every test draws the chart.
#[cfg(all(test, feature = "figures"))]
mod tests {
    use super::*;
    use crate::output::figure_style::PALETTE;

    #[test]
    fn a_chart_with_lines_and_markers_renders_to_svg() {
        let mut c = LineChart::new("F̄(d̄)", "d̄", "F̄");
        c.push(
            "JKR",
            (0..50)
                .map(|i| (i as f64 / 10.0, (i as f64).sin()))
                .collect(),
            0,
            Style::Line,
        );
        c.push(
            "simulated",
            vec![(0.5, 0.1), (1.0, f64::NAN), (2.0, 0.3)],
            1,
            Style::Markers,
        );
        let svg = c.to_svg().unwrap();
        assert!(svg.contains("<svg") && svg.contains("JKR") && svg.contains("simulated"));
        // The second colour's markers are squares: two in the plot, one in the legend.
        assert!(svg.matches("<polygon").count() >= 3);
        // Error bars: three lines each (the bar and its two caps), within the range a line
        // already fixes; a bar beyond it widens the range.
        let frame = || {
            let mut c = LineChart::new("bars", "x", "y");
            c.push("frame", vec![(0.0, 0.0), (4.0, 1.0)], 0, Style::Line);
            c
        };
        let mut plain = frame();
        plain.push("m", vec![(1.0, 0.2), (3.0, 0.25)], 1, Style::Markers);
        let mut bars = frame();
        bars.push_with_errors("m", vec![(1.0, 0.2), (3.0, 0.25)], vec![0.05, 0.1], 1);
        let count = |svg: &str| svg.matches("<line").count() + svg.matches("<polyline").count();
        let (n0, n1) = (
            count(&plain.to_svg().unwrap()),
            count(&bars.to_svg().unwrap()),
        );
        assert_eq!(n1, n0 + 6, "{n0} → {n1}");
        // The data drawn: the line's vertices without bars, each marker with its bar's
        // half-width; the simulated curve's NaN point is not drawn, so not listed.
        let rows: Vec<(String, &str, f64, f64, Option<f64>)> = bars
            .plot_points()
            .into_iter()
            .map(|p| (p.series, p.style, p.x, p.y, p.error))
            .collect();
        assert_eq!(
            rows,
            [
                ("frame".into(), "line", 0.0, 0.0, None),
                ("frame".into(), "line", 4.0, 1.0, None),
                ("m".into(), "markers", 1.0, 0.2, Some(0.05)),
                ("m".into(), "markers", 3.0, 0.25, Some(0.1)),
            ]
        );
        let simulated: Vec<(f64, f64)> = c
            .plot_points()
            .iter()
            .filter(|p| p.series == "simulated")
            .map(|p| (p.x, p.y))
            .collect();
        assert_eq!(simulated, [(0.5, 0.1), (2.0, 0.3)]);
        let mut wide = frame();
        wide.push_with_errors("m", vec![(1.0, 0.2)], vec![3.0], 1);
        let ticks: Vec<String> = texts(&wide.to_svg().unwrap())
            .into_iter()
            .map(|t| t.2)
            .collect();
        assert!(
            ticks.iter().any(|t| t == "3"),
            "the bar's top is in range: {ticks:?}"
        );
        c.x_log = true;
        assert!(c.to_svg().unwrap().contains("<svg"));
    }

    /// (x, y, text) of every text element of an SVG written by plotters.
    fn texts(svg: &str) -> Vec<(f64, f64, String)> {
        let mut out = Vec::new();
        for part in svg.split("<text ").skip(1) {
            let attr = |name: &str| -> f64 {
                let key = format!("{name}=\"");
                part.split_once(&key)
                    .and_then(|(_, r)| r.split_once('"'))
                    .and_then(|(v, _)| v.parse().ok())
                    .unwrap_or(f64::NAN)
            };
            let body = part
                .split_once('>')
                .map(|(_, r)| r.split("</text>").next().unwrap_or("").trim().to_string())
                .unwrap_or_default();
            out.push((attr("x"), attr("y"), body));
        }
        out
    }

    /// (x, y) of every circle of radius `r` in an SVG written by plotters.
    fn circles(svg: &str, r: u32) -> Vec<(f64, f64)> {
        svg.split("<circle ")
            .skip(1)
            .filter(|c| c.contains(&format!("r=\"{r}\"")))
            .map(|c| {
                let attr = |name: &str| -> f64 {
                    let key = format!("{name}=\"");
                    c.split_once(&key)
                        .and_then(|(_, r)| r.split_once('"'))
                        .and_then(|(v, _)| v.parse().ok())
                        .unwrap()
                };
                (attr("cx"), attr("cy"))
            })
            .collect()
    }

    #[test]
    fn the_legend_never_covers_data() {
        // Before: the legend box was drawn in a corner of the plot, over data points; then
        // in a panel beside the plot that took 40 % of the figure's width.
        let legend_text = |c: &LineChart, label: &str| {
            texts(&c.to_svg().unwrap())
                .into_iter()
                .find(|t| t.2 == label)
                .unwrap_or_else(|| panic!("no legend text {label}"))
        };
        // Data everywhere: the legend goes below the plot.
        let mut c = LineChart::new("t", "x", "y");
        let pts: Vec<(f64, f64)> = (0..=20)
            .flat_map(|i| (0..=20).map(move |j| (i as f64, j as f64)))
            .collect();
        c.push("everywhere", pts, 0, Style::Markers);
        c.push("a line", vec![(0.0, 0.0), (20.0, 20.0)], 1, Style::Line);
        for label in ["everywhere", "a line"] {
            let (_, y, _) = legend_text(&c, label);
            assert!(y > c.size.1 as f64, "{label} at y = {y}, inside the plot");
        }
        assert!(
            circles(&c.to_svg().unwrap(), MARKER_RADIUS as u32)
                .iter()
                .filter(|&&(_, y)| y < c.size.1 as f64)
                .count()
                >= 441
        );
        // Data in the lower left only: the legend sits inside, in the top right.
        let mut c = LineChart::new("t", "x", "y");
        c.push(
            "low",
            vec![(0.0, 0.0), (1.0, 0.5), (2.0, 0.2)],
            0,
            Style::Markers,
        );
        c.push("frame", vec![(0.0, 0.0), (10.0, 0.3)], 1, Style::Line);
        c.push("top", vec![(0.0, 4.0)], 2, Style::Markers);
        let (x, y, _) = legend_text(&c, "low");
        assert!(
            x > 0.5 * c.size.0 as f64 && y < 0.5 * c.size.1 as f64,
            "{x}, {y}"
        );
    }

    #[test]
    fn legend_samples_are_drawn_as_their_curves() {
        // Before: a dashed curve (JKR/JG in the pull-off chart) had a solid legend sample.
        let mut c = LineChart::new("t", "x", "y");
        c.push("solid", vec![(0.0, 0.0), (1.0, 1.0)], 0, Style::Line);
        c.push("dashed", vec![(0.0, 1.0), (1.0, 0.0)], 1, Style::Dashed);
        let svg = c.to_svg().unwrap();
        // The lines cross every corner, so the legend is below the plot.
        let below = c.size.1 as f64;
        // Line pieces in the legend, by colour.
        let pieces = |color: RGBColor| {
            let hex = format!("#{:02X}{:02X}{:02X}", color.0, color.1, color.2);
            svg.split("<polyline ")
                .skip(1)
                .filter(|p| p.contains(&hex))
                .filter(|p| {
                    p.split_once("points=\"")
                        .and_then(|(_, r)| r.split([',', ' ']).nth(1))
                        .and_then(|y| y.trim().parse::<f64>().ok())
                        .is_some_and(|y| y > below)
                })
                .count()
        };
        assert_eq!(pieces(PALETTE[0]), 1, "the solid sample is one line");
        assert!(pieces(PALETTE[1]) >= 3, "the dashed sample is dashed");
    }

    #[test]
    fn no_axis_reads_minus_zero() {
        // Before: `reproduce --quick` drew "-0" ticks on f_of_c.svg, f_of_d.svg and
        // d_of_c.svg, whose axes cross zero.
        for (lo, hi) in [
            (-0.3, 0.7),
            (-0.55, 3.4),
            (-1.3, 0.45),
            (-0.07, 0.02),
            (-0.62, 0.11),
            (-2.1, 9.7),
        ] {
            let mut c = LineChart::new("t", "x", "y");
            c.push(
                "a line",
                (0..=40)
                    .map(|i| {
                        let t = i as f64 / 40.0;
                        (lo + (hi - lo) * t, hi - (hi - lo) * t * t)
                    })
                    .collect(),
                0,
                Style::Line,
            );
            let labels: Vec<String> = texts(&c.to_svg().unwrap())
                .into_iter()
                .map(|t| t.2)
                .collect();
            assert!(labels.iter().any(|t| t == "0"), "{lo}..{hi}: {labels:?}");
            assert!(
                !labels
                    .iter()
                    .any(|t| t.starts_with('-') && t.parse::<f64>() == Ok(0.0)),
                "{lo}..{hi}: {labels:?}"
            );
        }
    }

    #[test]
    fn equal_scales_centre_a_whole_outline_and_keep_a_quarter_at_its_axes() {
        // A quarter contour (data from 0, padded a little below): x widened upward only.
        let (x, y) = LineChart::equalised(-0.05..1.05, -0.05..1.05, (400, 200), (false, false));
        assert_eq!((x.start, y.start), (-0.05, -0.05));
        assert!((x.end - 2.15).abs() < 1e-12 && (y.end - 1.05).abs() < 1e-12);
        // A whole outline (data on both sides of 0): x widened about its centre.
        let (x, _) = LineChart::equalised(-1.1..1.1, -1.1..1.1, (400, 200), (true, true));
        assert!((x.start + 2.2).abs() < 1e-12 && (x.end - 2.2).abs() < 1e-12);
    }

    #[test]
    fn equal_scales_draw_a_unit_as_long_on_both_axes() {
        // Before: contours were drawn with unequal scales, so a slender contact looked round.
        let mut c = LineChart::new("contours", "x", "y");
        c.push(
            "points",
            vec![(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (4.0, 0.3)],
            0,
            Style::Markers,
        );
        c.equal_scales = true;
        let svg = c.to_svg().unwrap();
        // The four markers, then the legend's.
        let p = circles(&svg, MARKER_RADIUS as u32);
        assert_eq!(p.len(), 5, "{p:?}");
        let along_x = p[1].0 - p[0].0;
        let along_y = p[0].1 - p[2].1;
        assert!(along_x > 20.0, "{along_x}");
        assert!(
            (along_x - along_y).abs() <= 1.5,
            "one unit is {along_x} px along x and {along_y} px along y"
        );
        c.equal_scales = false;
        let p = circles(&c.to_svg().unwrap(), MARKER_RADIUS as u32);
        assert!(((p[1].0 - p[0].0) - (p[0].1 - p[2].1)).abs() > 10.0);
    }
}
