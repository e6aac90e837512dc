//! Figures of several [`LineChart`]s side by side, each in an equal share of the page's width:
//! the study's Fig. 2b (a pull-off curve with marked states, and the contact shapes of those
//! states). Each panel keeps its own axes, title and legend; a legend goes inside its panel
//! where a corner is free of data, else below the panels (never over the data).

#[cfg(feature = "figures")]
use super::chart::render_svg;
use super::figure::{write_figure, FigureFormats, PlotPoint};
use super::figure_style::{PAGE_HEIGHT, PAGE_WIDTH};
#[cfg(feature = "figures")]
use super::legend::{with_plot_area, Legend};
use super::line_chart::LineChart;
use super::OutputError;
#[cfg(feature = "figures")]
use plotters::prelude::*;
use std::path::Path;

/// Space between the panels and the legends below them (px).
#[cfg(feature = "figures")]
const GAP: u32 = 8;

/// Charts drawn side by side in one figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Panels {
    /// The panels, left to right.
    pub charts: Vec<LineChart>,
    /// The size of the panels together, legends below them excluded (px).
    pub size: (u32, u32),
}

impl Panels {
    /// `charts` side by side on the page's width ([`PAGE_WIDTH`] × [`PAGE_HEIGHT`]).
    pub fn new(charts: Vec<LineChart>) -> Self {
        Panels {
            charts,
            size: (PAGE_WIDTH, PAGE_HEIGHT),
        }
    }

    /// The figure as an SVG document. Its recorded plot area
    /// ([`PLOT_AREA_NOTE`](super::legend::PLOT_AREA_NOTE)) spans the panels' plot areas, from
    /// the first one's left edge to the last one's right.
    #[cfg(feature = "figures")]
    pub fn to_svg(&self) -> Result<String, String> {
        let n = self.charts.len().max(1) as u32;
        let cell = self.size.0 / n;
        let legends: Vec<Legend> = self.charts.iter().map(|c| c.legend()).collect();
        let mut placed = vec![None; legends.len()];
        let mut areas = Vec::new();
        let svg = render_svg(self.size, |root| {
            self.draw(root, &legends, &mut placed, &mut areas)
        })?;
        if placed
            .iter()
            .zip(&legends)
            .all(|(p, l)| p.is_some() || l.is_empty())
        {
            return Ok(with_plot_area(svg, span(&areas)));
        }
        // A legend with no free corner: every legend without one goes below its panel, in as
        // many columns as the panel's width holds.
        let below: Vec<Option<Legend>> = placed
            .iter()
            .zip(&legends)
            .map(|(p, l)| (p.is_none() && !l.is_empty()).then(|| l.fitted_to(cell)))
            .collect();
        let extra = below
            .iter()
            .flatten()
            .map(|l| l.size().1)
            .max()
            .unwrap_or(0);
        let tall = (self.size.0, self.size.1 + extra + GAP);
        let mut areas = Vec::new();
        let svg = render_svg(tall, |root| {
            let (top, _) = root.split_vertically(self.size.1);
            let mut inside = placed.clone();
            self.draw(&top, &legends, &mut inside, &mut areas)?;
            for (k, legend) in below.iter().enumerate() {
                if let Some(legend) = legend {
                    let x = (k as u32 * cell) as i32
                        + (cell.saturating_sub(legend.size().0) / 2) as i32;
                    legend
                        .draw(root, (x, (self.size.1 + GAP) as i32))
                        .map_err(|e| e.to_string())?;
                }
            }
            Ok(())
        })?;
        Ok(with_plot_area(svg, span(&areas)))
    }

    /// Without the `figures` feature no chart is drawn: always
    /// [`NOT_DRAWN`](super::figure::NOT_DRAWN).
    #[cfg(not(feature = "figures"))]
    pub fn to_svg(&self) -> Result<String, String> {
        Err(super::figure::NOT_DRAWN.into())
    }

    /// Draw every panel in its share of `root`'s width, and each legend whose `placed` entry
    /// is unset in a free corner of its panel (recording where); `areas` gets the panels' plot
    /// areas.
    #[cfg(feature = "figures")]
    fn draw(
        &self,
        root: &DrawingArea<SVGBackend, plotters::coord::Shift>,
        legends: &[Legend],
        placed: &mut [Option<(i32, i32)>],
        areas: &mut Vec<(i32, i32, i32, i32)>,
    ) -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let cells = root.split_evenly((1, self.charts.len().max(1)));
        for (k, (chart, cell)) in self.charts.iter().zip(&cells).enumerate() {
            let frame = chart.draw(cell).map_err(|e| e.to_string())?;
            areas.push(frame.area);
            if placed[k].is_none() {
                placed[k] = legends[k].free_corner(&frame);
            }
            if let Some(at) = placed[k] {
                // The corner is in the root's pixels; so is the root's drawing.
                legends[k].draw(root, at).map_err(|e| e.to_string())?;
            }
        }
        Ok(())
    }

    /// Every point the panels draw, each series named with its panel's title first
    /// ("title: series").
    pub fn plot_points(&self) -> Vec<PlotPoint> {
        self.charts
            .iter()
            .flat_map(|c| {
                c.plot_points().into_iter().map(|mut p| {
                    p.series = format!("{}: {}", c.title, p.series);
                    p
                })
            })
            .collect()
    }

    /// Write the figure to `path` (its SVG path) in each of `formats`, and the points it
    /// draws to `<stem>.plot.csv` ([`write_figure`]).
    pub fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        write_figure(path, self.to_svg(), &self.plot_points(), formats)
    }
}

/// The box from the first plot area's left and top to the last one's right and bottom.
#[cfg(feature = "figures")]
fn span(areas: &[(i32, i32, i32, i32)]) -> (i32, i32, i32, i32) {
    let l = areas.iter().map(|a| a.0).min().unwrap_or(0);
    let t = areas.iter().map(|a| a.1).min().unwrap_or(0);
    let r = areas.iter().map(|a| a.2).max().unwrap_or(0);
    let b = areas.iter().map(|a| a.3).max().unwrap_or(0);
    (l, t, r, b)
}

impl super::figure::WriteFigure for Panels {
    fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError> {
        Panels::write_figure(self, path, formats)
    }
}

// Every test draws the chart.
#[cfg(all(test, feature = "figures"))]
mod tests {
    use super::*;
    use crate::output::line_chart::Style;

    fn chart(title: &str, shift: f64) -> LineChart {
        let mut c = LineChart::new(title, "x", "y");
        c.push(
            "a curve",
            (0..20)
                .map(|i| (i as f64, (i as f64 + shift).sin()))
                .collect(),
            0,
            Style::Line,
        );
        c
    }

    #[test]
    fn two_panels_share_the_width_and_name_their_series() {
        let p = Panels::new(vec![chart("left", 0.0), chart("right", 1.0)]);
        let svg = p.to_svg().unwrap();
        assert_eq!(svg.matches("\nleft\n").count(), 1, "{svg}");
        assert_eq!(svg.matches("\nright\n").count(), 1);
        let note = svg
            .split("<!-- plot-area ")
            .nth(1)
            .and_then(|s| s.split(" -->").next())
            .unwrap();
        let v: Vec<i32> = note.split(' ').map(|x| x.parse().unwrap()).collect();
        // From the left panel's plot to the right one's: most of the page.
        assert!(
            v[0] < (PAGE_WIDTH / 4) as i32 && v[2] > (3 * PAGE_WIDTH / 4) as i32,
            "{v:?}"
        );
        let points = p.plot_points();
        assert_eq!(points.len(), 40);
        assert!(points[0].series.starts_with("left: ") && points[39].series.starts_with("right: "));
    }
}
