//! Legends drawn as their series are, placed inside the plot in a corner that no data
//! occupy, or below the plot where no corner is free, so that the plot keeps the figure's
//! width and a legend never covers data.

use super::figure_style::{
    colour, draw_markers, text_width, LABEL_FONT, LINE_WIDTH, MARGIN, MARKER_RADIUS, Y_LABEL_AREA,
};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Height of one legend line (px).
const ROW: i32 = 17;

/// Width of a legend's line sample (px).
const SAMPLE: i32 = 30;

/// Padding inside the legend's frame (px).
const PAD: i32 = 6;

/// Gap between a legend inside the plot and the plot's frame (px).
const INSET: i32 = 6;

/// Most characters on one line of a legend label; a longer label wraps onto further lines.
pub const LINE_CHARS: usize = 48;

/// Spacing (px) at which the pixels a line passes through are sampled.
const LINE_SAMPLE: f64 = 3.0;

/// How a legend entry shows its series, drawn exactly as the series is: a line (solid, or
/// dashed with the series' own dash and gap), a marker (filled or hollow), or both.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// The series' colour index (its colour and marker shape).
    pub colour: usize,
    /// A line, solid (`None`) or dashed (dash, gap in px).
    pub line: Option<Option<(u32, u32)>>,
    /// A marker, filled (`true`) or hollow.
    pub marker: Option<bool>,
}

/// Where a plot's data fall, in the picture's pixels: what a legend must not cover.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PlotFrame {
    /// The plot area (left, top, right, bottom; px).
    pub area: (i32, i32, i32, i32),
    /// Pixels that data occupy: markers' centres and samples along lines and error bars.
    pub occupied: Vec<(i32, i32)>,
}

impl PlotFrame {
    /// Mark a marker at `p` (px) as occupied.
    pub fn mark(&mut self, p: (i32, i32)) {
        self.occupied.push(p);
    }

    /// Mark the pixels along the polyline `points` (px) as occupied.
    pub fn mark_line(&mut self, points: &[(i32, i32)]) {
        if let [only] = points {
            self.occupied.push(*only);
        }
        for w in points.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (dx, dy) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
            let n = ((dx.hypot(dy) / LINE_SAMPLE).ceil() as usize).max(1);
            for k in 0..=n {
                let t = k as f64 / n as f64;
                self.occupied
                    .push((a.0 + (t * dx).round() as i32, a.1 + (t * dy).round() as i32));
            }
        }
    }
}

/// A legend: its entries' labels, wrapped (see [`lines`]), and samples.
#[derive(Debug, Clone, PartialEq)]
pub struct Legend {
    entries: Vec<(Vec<String>, Sample)>,
    /// Columns the entries are laid out in (filled top to bottom, then left to right).
    columns: usize,
}

/// `label` cut into lines of at most [`LINE_CHARS`] characters, at spaces where it can be (a
/// longer word is cut where it must), so that a long label stays inside the picture.
pub fn lines(label: &str) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in label.split(' ') {
        let mut word: Vec<char> = word.chars().collect();
        let used = line.chars().count();
        if used > 0 && used + 1 + word.len() <= LINE_CHARS {
            line.push(' ');
            line.extend(word.iter());
            continue;
        }
        if used > 0 {
            lines.push(std::mem::take(&mut line));
        }
        while word.len() > LINE_CHARS {
            lines.push(word.drain(..LINE_CHARS).collect());
        }
        line = word.into_iter().collect();
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

impl Legend {
    /// The legend of `entries` (label, sample); an empty label is left out.
    pub fn new(entries: Vec<(String, Sample)>) -> Self {
        Legend {
            entries: entries
                .into_iter()
                .filter(|(label, _)| !label.is_empty())
                .map(|(label, sample)| (lines(&label), sample))
                .collect(),
            columns: 1,
        }
    }

    /// The same legend in `columns` columns (at least one).
    pub fn in_columns(&self, columns: usize) -> Self {
        Legend {
            entries: self.entries.clone(),
            columns: columns.max(1),
        }
    }

    /// Label lines in all.
    fn line_count(&self) -> usize {
        self.entries.iter().map(|(l, _)| l.len()).sum()
    }

    /// Each entry's column and first row: columns filled in order, each to at most the lines
    /// of an equal share (an entry is never split between columns).
    fn layout(&self) -> Vec<(usize, usize)> {
        let per_column = self.line_count().div_ceil(self.columns).max(1);
        let (mut column, mut row) = (0, 0);
        self.entries
            .iter()
            .map(|(lines, _)| {
                if row > 0 && row + lines.len() > per_column && column + 1 < self.columns {
                    (column, row) = (column + 1, 0);
                }
                let at = (column, row);
                row += lines.len();
                at
            })
            .collect()
    }

    /// Width of one column: the sample and the longest label line (px).
    fn column_width(&self) -> i32 {
        let text = self
            .entries
            .iter()
            .flat_map(|(lines, _)| lines)
            .map(|l| text_width(l, LABEL_FONT))
            .max()
            .unwrap_or(0);
        SAMPLE + 6 + text as i32 + PAD
    }

    /// The legend in as many columns (four at most) as `width` (px) holds; in one where none
    /// fits.
    pub fn fitted_to(&self, width: u32) -> Legend {
        (1..=4)
            .rev()
            .map(|c| self.in_columns(c))
            .find(|l| l.size().0 <= width)
            .unwrap_or_else(|| self.clone())
    }

    /// Whether there is nothing to show.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The legend's size with its frame (px).
    pub fn size(&self) -> (u32, u32) {
        if self.is_empty() {
            return (0, 0);
        }
        let layout = self.layout();
        let columns = layout.iter().map(|(c, _)| c + 1).max().unwrap_or(1);
        let rows = layout
            .iter()
            .zip(&self.entries)
            .map(|((_, row), (lines, _))| row + lines.len())
            .max()
            .unwrap_or(0);
        (
            (PAD + columns as i32 * self.column_width()) as u32,
            (2 * PAD) as u32 + ROW as u32 * rows as u32,
        )
    }

    /// A corner of `frame`'s plot area where the legend covers no data (top right, top left,
    /// bottom right, bottom left, in that order): its top-left pixel, or `None`.
    pub fn free_corner(&self, frame: &PlotFrame) -> Option<(i32, i32)> {
        let (w, h) = self.size();
        let (w, h) = (w as i32, h as i32);
        let (l, t, r, b) = frame.area;
        if w + 2 * INSET > r - l || h + 2 * INSET > b - t {
            return None;
        }
        let corners = [
            (r - INSET - w, t + INSET),
            (l + INSET, t + INSET),
            (r - INSET - w, b - INSET - h),
            (l + INSET, b - INSET - h),
        ];
        // A marker's or a thick line's extent around the pixels marked.
        let reach = MARKER_RADIUS + 2;
        corners.into_iter().find(|&(x, y)| {
            !frame.occupied.iter().any(|&(px, py)| {
                px >= x - reach && px <= x + w + reach && py >= y - reach && py <= y + h + reach
            })
        })
    }

    /// Draw the legend with its top-left corner at `at` (px in `area`): a white box with a
    /// thin frame, a row per label line, each entry's sample drawn as its series is.
    pub fn draw<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        at: (i32, i32),
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
        if self.is_empty() {
            return Ok(());
        }
        let (w, h) = self.size();
        let (x, y) = at;
        area.draw(&Rectangle::new(
            [(x, y), (x + w as i32, y + h as i32)],
            WHITE.filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(x, y), (x + w as i32, y + h as i32)],
            BLACK.mix(0.35).stroke_width(1),
        ))?;
        for ((lines, sample), (column, row)) in self.entries.iter().zip(self.layout()) {
            let x0 = x + PAD + column as i32 * self.column_width();
            let line_mid = |k: usize| y + PAD + ROW * (row + k) as i32 + ROW / 2;
            let mid = line_mid(0);
            let style = colour(sample.colour).stroke_width(LINE_WIDTH);
            match sample.line {
                Some(None) => {
                    area.draw(&PathElement::new(
                        vec![(x0, mid), (x0 + SAMPLE, mid)],
                        style,
                    ))?;
                }
                Some(Some((dash, gap))) => {
                    let mut s = x0;
                    while s < x0 + SAMPLE {
                        let end = (s + dash as i32).min(x0 + SAMPLE);
                        area.draw(&PathElement::new(vec![(s, mid), (end, mid)], style))?;
                        s = end + gap as i32;
                    }
                }
                None => {}
            }
            if let Some(filled) = sample.marker {
                draw_markers(
                    area,
                    &[(x0 + SAMPLE / 2, mid)],
                    sample.colour,
                    MARKER_RADIUS,
                    filled,
                )?;
            }
            for (k, line) in lines.iter().enumerate() {
                area.draw(&Text::new(
                    line.clone(),
                    (x0 + SAMPLE + 6, line_mid(k)),
                    TextStyle::from(("sans-serif", LABEL_FONT).into_font())
                        .pos(Pos::new(HPos::Left, VPos::Center)),
                ))?;
            }
        }
        Ok(())
    }
}

/// Render a chart whose plot `draw` draws (returning where its data fall) with `legend`
/// inside the plot in a free corner, or below the plot where none is free: an SVG document of
/// `size` px, taller by the legend where it goes below.
pub fn render_with_legend(
    size: (u32, u32),
    legend: &Legend,
    draw: impl Fn(&DrawingArea<SVGBackend, Shift>) -> Result<PlotFrame, String>,
) -> Result<String, String> {
    let mut inside = true;
    let mut area = (0, 0, 0, 0);
    let svg = super::chart::render_svg(size, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let frame = draw(root)?;
        area = frame.area;
        match legend.free_corner(&frame) {
            Some(at) => legend.draw(root, at).map_err(|e| e.to_string()),
            None => {
                inside = legend.is_empty();
                Ok(())
            }
        }
    })?;
    if inside {
        return Ok(with_plot_area(svg, area));
    }
    // Below the plot, from the plot's left edge, in as many columns as the width holds.
    let left = (MARGIN + Y_LABEL_AREA) as i32;
    let room = size.0 as i32 - left - MARGIN as i32;
    let legend = legend.fitted_to(room.max(0) as u32);
    let (_, h) = legend.size();
    let below = (size.0, size.1 + h + 8);
    let svg = super::chart::render_svg(below, |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (plot, rest) = root.split_vertically(size.1);
        area = draw(&plot)?.area;
        legend.draw(&rest, (left, 0)).map_err(|e| e.to_string())
    })?;
    Ok(with_plot_area(svg, area))
}

/// How an SVG written here records its plot area (left, top, right, bottom; px), in a comment
/// before its end, for checks of the layout.
pub const PLOT_AREA_NOTE: &str = "plot-area";

/// `svg` with its plot area `area` recorded (see [`PLOT_AREA_NOTE`]).
pub fn with_plot_area(svg: String, (l, t, r, b): (i32, i32, i32, i32)) -> String {
    match svg.rfind("</svg>") {
        Some(end) => format!(
            "{}<!-- {PLOT_AREA_NOTE} {l} {t} {r} {b} -->\n{}",
            &svg[..end],
            &svg[end..]
        ),
        None => svg,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Sample {
        Sample {
            colour: 0,
            line: Some(None),
            marker: None,
        }
    }

    #[test]
    fn a_long_label_wraps_and_keeps_every_word() {
        let grids = vec!["32"; 30].join(", ");
        let label = format!("jkrbem at Δx → 0, ± stated uncertainty (Nx = {grids})");
        let l = lines(&label);
        assert!(l.len() > 1 && l.iter().all(|x| x.chars().count() <= LINE_CHARS));
        assert_eq!(l.join(" "), label);
        let long_word = "x".repeat(130);
        assert_eq!(lines(&long_word).concat(), long_word);
        assert_eq!(lines("short"), vec!["short"]);
    }

    #[test]
    fn the_legend_takes_the_first_corner_free_of_data() {
        let legend = Legend::new(vec![("a curve".into(), sample())]);
        let mut frame = PlotFrame {
            area: (50, 10, 600, 400),
            occupied: Vec::new(),
        };
        let (w, _) = legend.size();
        assert_eq!(
            legend.free_corner(&frame),
            Some((600 - INSET - w as i32, 16))
        );
        // Data in the top right: the top left is taken.
        frame.mark_line(&[(400, 20), (590, 20)]);
        assert_eq!(legend.free_corner(&frame), Some((56, 16)));
        // Data along every edge: no corner is free.
        frame.mark_line(&[(60, 20), (60, 390), (590, 390)]);
        assert_eq!(legend.free_corner(&frame), None);
    }
}
