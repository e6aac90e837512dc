//! Line charts on log–log axes, written as SVG with `plotters`: any number of labelled series
//! of (x, y) points, each drawn as a line through markers. Ticks sit at the series' own x
//! values when there are few of them (grid sizes), otherwise on a 1–2–5 sequence.

use super::OutputError;
use plotters::prelude::*;
use std::path::Path;

/// Most distinct x values that still get one tick each.
const MAX_DATA_TICKS: usize = 12;

/// Colours of series groups (the "tab10" palette), picked by a series' colour index.
pub(crate) const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

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
    /// Size of the picture (pixels).
    pub size: (u32, u32),
    /// Put x ticks at the data's own x values when there are few (grid sizes); otherwise on
    /// a 1–2–5 sequence (times).
    pub x_data_ticks: bool,
    /// Corner of the legend.
    pub legend: SeriesLabelPosition,
}

impl LogLogChart {
    /// An empty 900 × 600 chart.
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
            size: (900, 600),
            x_data_ticks: true,
            legend: SeriesLabelPosition::UpperLeft,
        }
    }

    /// Add a series.
    pub fn push(&mut self, series: Series) {
        self.series.push(series);
    }

    /// The chart as an SVG document.
    pub fn to_svg(&self) -> Result<String, String> {
        render_svg(self.size, |root| self.draw(root).map_err(|e| e.to_string()))
    }

    /// Write the chart as SVG to `path`, creating its folder.
    pub fn write_svg(&self, path: &Path) -> Result<(), OutputError> {
        write_svg_document(path, self.to_svg())
    }

    fn points(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series.iter().flat_map(|s| plottable(&s.points))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        root.fill(&WHITE)?;
        let (xs, ys): (Vec<f64>, Vec<f64>) = self.points().unzip();
        let (x_range, x_ticks) = axis(&xs, self.x_data_ticks);
        let (y_range, y_ticks) = axis(&ys, false);
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 20))
            .margin(20)
            .x_label_area_size(50)
            .y_label_area_size(75)
            .build_cartesian_2d(
                x_range.log_scale().with_key_points(x_ticks),
                y_range.log_scale().with_key_points(y_ticks),
            )?;
        let tick = |v: &f64| tick_label(*v);
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", 14))
            .axis_desc_style(("sans-serif", 16))
            .bold_line_style(BLACK.mix(0.12))
            .draw()?;
        for s in &self.series {
            let color = PALETTE[s.color % PALETTE.len()];
            let line = color.stroke_width(2);
            let pts: Vec<(f64, f64)> = plottable(&s.points).collect();
            let anno = if s.dashed {
                chart.draw_series(DashedLineSeries::new(pts.clone(), 9, 6, line))?
            } else {
                chart.draw_series(LineSeries::new(pts.clone(), line))?
            };
            let marker = if s.dashed { line } else { color.filled() };
            // A short line through a marker, as the series is drawn.
            let (l, r) = if s.dashed { (-5, 5) } else { (0, 0) };
            anno.label(s.label.as_str()).legend(move |(x, y)| {
                EmptyElement::at((x + 12, y))
                    + PathElement::new(vec![(-14, 0), (l, 0)], line)
                    + PathElement::new(vec![(r, 0), (14, 0)], line)
                    + Circle::new((0, 0), 4, marker)
            });
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 4, marker)))?;
        }
        if !self.series.is_empty() {
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

/// Render a chart drawn by `draw` into an SVG document of `size` pixels.
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

/// Write a rendered SVG document (or the renderer's error) to `path`, creating its folder,
/// atomically ([`super::file`]).
pub(crate) fn write_svg_document(
    path: &Path,
    svg: Result<String, String>,
) -> Result<(), OutputError> {
    let svg = svg.map_err(|reason| OutputError::Chart {
        path: path.display().to_string(),
        flag: None,
        reason,
    })?;
    super::file::write_bytes(path, svg.as_bytes())
}

/// The points of a series that have a place on log axes.
fn plottable(points: &[(f64, f64)]) -> impl Iterator<Item = (f64, f64)> + '_ {
    points
        .iter()
        .copied()
        .filter(|&(x, y)| x.is_finite() && x > 0.0 && y.is_finite() && y > 0.0)
}

/// The range of one axis, padded by a fifth of a decade either side, and its ticks: the
/// data's own values when `data_ticks` and there are at most [`MAX_DATA_TICKS`] of them,
/// otherwise the 1–2–5 values inside the range (only the decades if those are too many).
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
    if v == 0.0 || !v.is_finite() {
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
    fn few_x_values_are_their_own_ticks() {
        let (r, t) = axis(&[64.0, 128.0, 256.0, 64.0], true);
        assert_eq!(t, vec![64.0, 128.0, 256.0]);
        assert!(r.start < 64.0 && r.end > 256.0);
        let (_, t) = axis(&[0.3, 40.0], false);
        assert_eq!(t.first(), Some(&0.2));
        assert!(t.contains(&1.0) && t.contains(&50.0));
    }

    #[test]
    fn a_chart_renders_to_svg() {
        let mut c = LogLogChart::new("t", "x (unit)", "y (ms)");
        c.push(Series {
            label: "a".into(),
            points: vec![(16.0, 0.1), (32.0, 0.4), (64.0, -1.0)],
            color: 0,
            dashed: false,
        });
        c.push(Series {
            label: "b".into(),
            points: vec![(16.0, 0.2), (32.0, 0.9)],
            color: 1,
            dashed: true,
        });
        let svg = c.to_svg().unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..50]);
        assert!(svg.contains("y (ms)") && svg.contains("\n32\n</text>"));
    }
}
