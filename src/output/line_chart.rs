//! Charts on linear axes (optionally a logarithmic x axis), written as SVG with `plotters`:
//! simulated states as markers, closed forms and fits as lines, each with a legend entry.

use super::chart::{render_svg, write_svg_document, PALETTE};
use super::OutputError;
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
    /// Corner of the legend.
    pub legend: SeriesLabelPosition,
    /// Size of the picture (pixels).
    pub size: (u32, u32),
}

impl LineChart {
    /// An empty 900 × 600 chart with linear axes.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x_log: false,
            curves: Vec::new(),
            legend: SeriesLabelPosition::UpperRight,
            size: (900, 600),
        }
    }

    /// Add a curve.
    pub fn push(&mut self, label: &str, points: Vec<(f64, f64)>, color: usize, style: Style) {
        self.curves.push(Curve {
            label: label.into(),
            points,
            color,
            style,
        });
    }

    /// The chart as an SVG document.
    pub fn to_svg(&self) -> Result<String, String> {
        render_svg(self.size, |root| self.draw(root).map_err(|e| e.to_string()))
    }

    /// Write the chart as SVG to `path`, creating its folder.
    pub fn write_svg(&self, path: &Path) -> Result<(), OutputError> {
        write_svg_document(path, self.to_svg())
    }

    /// x ticks: on a log axis log10 of 1, 2, 5 × 10^k inside the range; on a linear axis
    /// about ten round values.
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
    fn plotted(&self, c: &Curve) -> Vec<(f64, f64)> {
        c.points
            .iter()
            .filter(|(x, y)| x.is_finite() && y.is_finite() && (!self.x_log || *x > 0.0))
            .copied()
            .collect()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        root.fill(&WHITE)?;
        let all: Vec<(f64, f64)> = self.curves.iter().flat_map(|c| self.plotted(c)).collect();
        let range = |v: Vec<f64>| {
            let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            if !lo.is_finite() {
                return 0.0..1.0;
            }
            let pad = ((hi - lo) * 0.05).max(1e-9 * lo.abs().max(1.0));
            lo - pad..hi + pad
        };
        let (xr, yr) = (
            range(all.iter().map(|p| p.0).collect()),
            range(all.iter().map(|p| p.1).collect()),
        );
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
        } else {
            self.draw_on(root, plotters::coord::types::RangedCoordf64::from(xr), yr)
        }
    }

    fn draw_on<DB: DrawingBackend, X>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
        xr: X,
        yr: std::ops::Range<f64>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        X: plotters::coord::ranged1d::Ranged<ValueType = f64>
            + plotters::coord::ranged1d::ValueFormatter<f64>,
    {
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(xr, yr)?;
        let x_fmt = |v: &f64| format!("{}", (v * 1000.0).round() / 1000.0);
        let y_fmt = |v: &f64| format!("{}", (v * 1000.0).round() / 1000.0);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&x_fmt)
            .y_label_formatter(&y_fmt)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .bold_line_style(BLACK.mix(0.12))
            .draw()?;
        for c in &self.curves {
            let color = PALETTE[c.color % PALETTE.len()];
            let line = color.stroke_width(2);
            let pts = self.plotted(c);
            let anno = match c.style {
                Style::Line => chart.draw_series(LineSeries::new(pts, line))?,
                Style::Dashed => chart.draw_series(DashedLineSeries::new(pts, 8, 5, line))?,
                Style::Markers => {
                    chart.draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))?
                }
            };
            let style = c.style;
            let markers = style == Style::Markers;
            anno.label(c.label.as_str()).legend(move |(x, y)| {
                let path = if markers {
                    vec![]
                } else {
                    vec![(0, 0), (20, 0)]
                };
                EmptyElement::at((x, y))
                    + PathElement::new(path, line)
                    + Circle::new((10, 0), if markers { 4 } else { 0 }, color.filled())
            });
        }
        if !self.curves.is_empty() {
            chart
                .configure_series_labels()
                .position(self.legend.clone())
                .label_font(("sans-serif", 14))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .draw()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(svg.matches("<circle").count() >= 2);
        c.x_log = true;
        assert!(c.to_svg().unwrap().contains("<svg"));
    }
}
