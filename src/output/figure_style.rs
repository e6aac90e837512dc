//! The figures' style, in one place: a page-width canvas whose text prints at 9–11 pt, the
//! Okabe–Ito colours (safe for colour-blind readers) with a marker shape per colour (so that
//! series stay apart in greyscale), and the dash of fits and second references. The colours
//! and markers are `plotters`' (the `figures` feature); the sizes are every chart's.

#[cfg(feature = "figures")]
use plotters::coord::CoordTranslate;
#[cfg(feature = "figures")]
use plotters::element::{EmptyElement, PathElement, Polygon};
#[cfg(feature = "figures")]
use plotters::prelude::*;

/// Pixels per inch of an SVG's user unit (CSS px): a picture of [`PAGE_WIDTH`] px prints at
/// 170 mm.
pub const PX_PER_INCH: f64 = 96.0;

/// Width of a chart (px): 170 mm, a journal's two-column width, at [`PX_PER_INCH`].
pub const PAGE_WIDTH: u32 = 643;

/// Height of a chart's plot and axes (px): about two thirds of its width.
pub const PAGE_HEIGHT: u32 = 430;

/// Font of the title (px; 11 pt at [`PX_PER_INCH`]).
pub const TITLE_FONT: u32 = 15;

/// Font of the axis descriptions (px; 10.5 pt).
pub const AXIS_FONT: u32 = 14;

/// Font of the tick labels and the legend (px; 9 pt).
pub const LABEL_FONT: u32 = 12;

/// Margin around the plot (px).
pub const MARGIN: u32 = 12;

/// Height of the x axis' label area: tick labels and description (px).
pub const X_LABEL_AREA: u32 = 44;

/// Width of the y axis' label area: tick labels and description (px).
pub const Y_LABEL_AREA: u32 = 62;

/// Dash and gap (px) of dashed lines, in the plot and in the legend alike.
pub const DASH: (u32, u32) = (8, 5);

/// Width of the lines of curves (px).
pub const LINE_WIDTH: u32 = 2;

/// Radius of a marker (px).
pub const MARKER_RADIUS: i32 = 4;

/// Mean advance of a character of the sans-serif font, in em: DejaVu Sans (what the SVG's
/// "sans-serif" is drawn with here) averages about 0.5 em over mixed text; a little above,
/// so that estimated boxes hold the text.
pub const EM_PER_CHAR: f64 = 0.55;

/// The Okabe–Ito colours (Okabe & Ito 2008), in an order whose neighbours differ in lightness
/// too: blue, orange, bluish green, reddish purple, black, vermillion, sky blue, yellow.
#[cfg(feature = "figures")]
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(230, 159, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(0, 0, 0),
    RGBColor(213, 94, 0),
    RGBColor(86, 180, 233),
    RGBColor(240, 228, 66),
];

/// The colour of colour index `k`.
#[cfg(feature = "figures")]
pub fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// The estimated width (px) of `text` in a font of `size` px (see [`EM_PER_CHAR`]).
pub fn text_width(text: &str, size: u32) -> u32 {
    (text.chars().count() as f64 * EM_PER_CHAR * size as f64).ceil() as u32
}

/// Draw the markers of colour index `k` at `points` (in `area`'s coordinates): circles,
/// squares, triangles, diamonds or inverted triangles (by `k`), filled or hollow, of radius
/// `r` (px).
#[cfg(feature = "figures")]
pub fn draw_markers<DB, CT>(
    area: &DrawingArea<DB, CT>,
    points: &[CT::From],
    k: usize,
    r: i32,
    filled: bool,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    DB: DrawingBackend,
    CT: CoordTranslate,
    CT::From: Clone,
{
    let colour = colour(k);
    let style = if filled {
        colour.filled()
    } else {
        colour.stroke_width(LINE_WIDTH)
    };
    // Shapes of about the circle's area.
    let s = (r as f64 * 0.89).round() as i32;
    let t = (r as f64 * 1.3).round() as i32;
    let shape = match k % 5 {
        0 => None,
        1 => Some(vec![(-s, -s), (s, -s), (s, s), (-s, s)]),
        2 => Some(vec![(0, -t), (t, t * 3 / 4), (-t, t * 3 / 4)]),
        3 => Some(vec![(0, -t), (t, 0), (0, t), (-t, 0)]),
        _ => Some(vec![(0, t), (t, -t * 3 / 4), (-t, -t * 3 / 4)]),
    };
    for p in points {
        let at = EmptyElement::at(p.clone());
        match &shape {
            None => area.draw(&(at + Circle::new((0, 0), r, style)))?,
            Some(corners) if filled => area.draw(&(at + Polygon::new(corners.clone(), style)))?,
            Some(corners) => {
                let mut closed = corners.clone();
                closed.push(corners[0]);
                area.draw(&(at + PathElement::new(closed, style)))?
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_page_wide_chart_prints_at_170_mm() {
        let mm = PAGE_WIDTH as f64 / PX_PER_INCH * 25.4;
        assert!((mm - 170.0).abs() < 0.5, "{mm}");
        // 9 pt at least for the smallest text.
        assert!(LABEL_FONT as f64 * 72.0 / PX_PER_INCH >= 9.0);
    }

    #[cfg(feature = "figures")]
    #[test]
    fn neighbouring_colours_differ_in_greyscale() {
        let grey = |c: RGBColor| 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
        // Each differs from the next by a visible step of grey.
        for w in PALETTE.windows(2) {
            assert!((grey(w[0]) - grey(w[1])).abs() > 15.0, "{w:?}");
        }
    }
}
