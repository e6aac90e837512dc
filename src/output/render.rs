//! Charts rendered from their SVG: parsed once by `usvg` (text laid out in the embedded DejaVu
//! Sans and converted to paths, so that every box is the real one), then rasterised to PNG by
//! `resvg` or converted to PDF by `svg2pdf`.
//!
//! The font: the charts ask for the family "sans-serif", which is mapped to DejaVu Sans, built
//! into the program (`data/fonts/DejaVuSans.ttf`, its licence beside it), so that a figure
//! renders the same on a machine without fonts (a cluster node) as on a desktop. The system's
//! fonts are loaded too, behind it, only for characters DejaVu Sans lacks.

use resvg::tiny_skia;
pub use resvg::usvg;
use std::sync::{Arc, OnceLock};
use usvg::fontdb;

/// DejaVu Sans 2.37 (Bitstream Vera licence, `data/fonts/LICENSE-DejaVu.txt`).
const DEJAVU_SANS: &[u8] = include_bytes!("../../data/fonts/DejaVuSans.ttf");

/// The family every chart's text is set in.
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// Resolution of a PNG (dots per inch); an SVG's pixel is 1/96 inch.
pub const PNG_DPI: f32 = 300.0;

/// Resolution of an SVG's user unit (pixels per inch, CSS).
const SVG_DPI: f32 = 96.0;

/// The largest PNG side rendered (pixels), so that a malformed size cannot ask for gigabytes.
const MAX_PNG_SIDE: u32 = 20_000;

/// The font database: the system's fonts (any DejaVu Sans regular among them removed, so that
/// the embedded one is the one used), then the embedded DejaVu Sans, with "sans-serif" mapped
/// to it. Loaded once per process.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = fontdb::Database::new();
            db.load_system_fonts();
            let system_dejavu: Vec<fontdb::ID> = db
                .faces()
                .filter(|f| {
                    f.families.iter().any(|(name, _)| name == FONT_FAMILY)
                        && f.style == fontdb::Style::Normal
                        && f.weight == fontdb::Weight::NORMAL
                        && f.stretch == fontdb::Stretch::Normal
                })
                .map(|f| f.id)
                .collect();
            for id in system_dejavu {
                db.remove_face(id);
            }
            db.load_font_data(DEJAVU_SANS.to_vec());
            db.set_sans_serif_family(FONT_FAMILY);
            Arc::new(db)
        })
        .clone()
}

/// `svg` parsed for rendering: its text laid out in the embedded DejaVu Sans ("sans-serif" and
/// any family not found fall back to it) and converted to paths, every node's bounding box in
/// canvas pixels (the SVG's user units, 1/96 inch). [`text_boxes`] lists the text's boxes.
pub fn svg_tree(svg: &str) -> Result<usvg::Tree, String> {
    let options = usvg::Options {
        font_family: FONT_FAMILY.to_string(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &options).map_err(|e| format!("the SVG could not be parsed: {e}"))
}

/// Every text element of `tree` (from [`svg_tree`]), in document order: its text (the chunks
/// joined) and the bounding box of its glyphs as drawn, `[left, top, right, bottom]` in canvas
/// pixels (y down). A text that draws nothing (blank) has no box and is left out.
pub fn text_boxes(tree: &usvg::Tree) -> Vec<(String, [f32; 4])> {
    let mut out = Vec::new();
    collect_text(tree.root(), &mut out);
    out
}

/// [`text_boxes`] of `group` and its descendants, appended to `out`.
fn collect_text(group: &usvg::Group, out: &mut Vec<(String, [f32; 4])>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => collect_text(g, out),
            usvg::Node::Text(t) => {
                let text: String = t.chunks().iter().map(|c| c.text()).collect();
                // The glyphs' own outline (the layout's box would add the line's ascent and
                // descent), in the text's coordinates, then through the text's transform (a
                // y-axis title is turned); none for a blank text.
                let flat = t.flattened();
                if let Some(b) = flat
                    .has_children()
                    .then(|| flat.bounding_box().transform(t.abs_transform()))
                    .flatten()
                {
                    out.push((text, [b.left(), b.top(), b.right(), b.bottom()]));
                }
            }
            usvg::Node::Path(_) | usvg::Node::Image(_) => {}
        }
    }
}

/// The size (pixels) of the PNG of a picture `size` SVG pixels large: at [`PNG_DPI`], each
/// side `round(side × 300/96)`.
pub fn png_size(size: usvg::Size) -> (u32, u32) {
    let scale = PNG_DPI / SVG_DPI;
    let side = |v: f32| (v * scale).round().max(1.0) as u32;
    (side(size.width()), side(size.height()))
}

/// `svg` as a PNG at [`PNG_DPI`] (its pixel size by [`png_size`], the resolution recorded in
/// the file) on a white background.
pub fn to_png(svg: &str) -> Result<Vec<u8>, String> {
    let tree = svg_tree(svg)?;
    let (w, h) = png_size(tree.size());
    if w > MAX_PNG_SIDE || h > MAX_PNG_SIDE {
        return Err(format!(
            "a PNG of {w} × {h} pixels is larger than the {MAX_PNG_SIDE} pixels a side allowed"
        ));
    }
    let mut pixmap = tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| format!("a PNG of {w} × {h} pixels could not be allocated"))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let size = tree.size();
    let transform =
        tiny_skia::Transform::from_scale(w as f32 / size.width(), h as f32 / size.height());
    resvg::render(&tree, transform, &mut pixmap.as_mut());
    let png = pixmap
        .encode_png()
        .map_err(|e| format!("the PNG could not be encoded: {e}"))?;
    Ok(with_resolution(png, PNG_DPI))
}

/// `svg` as a one-page PDF whose page is the picture's size at 96 pixels per inch (a 900-pixel
/// wide chart is 9.375 inches wide), its text embedded as text (a subset of the font).
pub fn to_pdf(svg: &str) -> Result<Vec<u8>, String> {
    let tree = svg_tree(svg)?;
    let page = svg2pdf::PageOptions { dpi: SVG_DPI };
    svg2pdf::to_pdf(&tree, svg2pdf::ConversionOptions::default(), page)
        .map_err(|e| format!("the PDF could not be written: {e}"))
}

/// `png` with a `pHYs` chunk saying `dpi` dots per inch, placed after the header (IHDR), so
/// that a document places the picture at its size; `png` as it is if it has no IHDR where a
/// PNG has it.
fn with_resolution(png: Vec<u8>, dpi: f32) -> Vec<u8> {
    // Signature (8 bytes), then IHDR: length (4), type (4), 13 bytes of data, CRC (4).
    const IHDR_END: usize = 8 + 4 + 4 + 13 + 4;
    if png.len() < IHDR_END || &png[12..16] != b"IHDR" {
        return png;
    }
    let per_metre = (f64::from(dpi) / 0.0254).round() as u32;
    let mut chunk = Vec::with_capacity(21);
    chunk.extend_from_slice(&9u32.to_be_bytes());
    chunk.extend_from_slice(b"pHYs");
    chunk.extend_from_slice(&per_metre.to_be_bytes());
    chunk.extend_from_slice(&per_metre.to_be_bytes());
    chunk.push(1); // unit: the metre
    let crc = crc32(&chunk[4..]);
    chunk.extend_from_slice(&crc.to_be_bytes());
    let mut out = Vec::with_capacity(png.len() + chunk.len());
    out.extend_from_slice(&png[..IHDR_END]);
    out.extend_from_slice(&chunk);
    out.extend_from_slice(&png[IHDR_END..]);
    out
}

/// CRC-32 (ISO-HDLC, the PNG chunk checksum) of `bytes`.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = 0xFFFF_FFFFu32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            let mask = (crc & 1).wrapping_neg();
            crc = (crc >> 1) ^ (0xEDB8_8320 & mask);
        }
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small chart: a caption, an axis label and a line.
    const SVG: &str = r##"<svg width="300" height="200" viewBox="0 0 300 200" xmlns="http://www.w3.org/2000/svg">
<rect x="0" y="0" width="300" height="200" fill="#FFFFFF"/>
<text x="150" y="30" dy="0.76em" text-anchor="middle" font-family="sans-serif" font-size="20" fill="#000000">F̄(d̄) ± Δx → 0</text>
<text x="20" y="180" font-family="sans-serif" font-size="14" fill="#000000">x</text>
<polyline fill="none" stroke="#1F77B4" stroke-width="2" points="40,150 260,60"/>
</svg>"##;

    #[test]
    fn the_crc_is_pngs() {
        // The CRC of an IEND chunk's type, as every PNG ends with it.
        assert_eq!(crc32(b"IEND"), 0xAE42_6082);
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }

    #[test]
    fn text_is_set_in_the_embedded_font_with_real_boxes() {
        let tree = svg_tree(SVG).unwrap();
        let boxes = text_boxes(&tree);
        assert_eq!(boxes.len(), 2, "{boxes:?}");
        let (caption, [l, t, r, b]) = &boxes[0];
        assert_eq!(caption, "F̄(d̄) ± Δx → 0");
        // Centred on x = 150; its baseline 0.76 em (15.2 px) below y = 30, the macron over
        // F reaching a little above y = 30 and the parentheses a little below the baseline.
        assert!((0.5 * (l + r) - 150.0).abs() < 3.0, "{l} {r}");
        assert!(*t > 22.0 && *t < 30.0 && *b > 45.2 && *b < 50.0, "{t} {b}");
        assert!(r - l > 100.0 && r - l < 250.0, "{l} {r}");
        let (x, [l, _, r, b]) = &boxes[1];
        assert_eq!(x, "x");
        assert!(*l >= 20.0 && *r < 30.0 && *b <= 180.5, "{l} {r} {b}");
        // Every face the text uses is the embedded one.
        let db = fonts();
        let sans = db.query(&fontdb::Query {
            families: &[fontdb::Family::SansSerif],
            ..fontdb::Query::default()
        });
        let face = sans.and_then(|id| db.face(id)).unwrap();
        assert!(matches!(face.source, fontdb::Source::Binary(_)), "{face:?}");
    }

    #[test]
    fn png_and_pdf_of_a_chart() {
        let png = to_png(SVG).unwrap();
        assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
        let be = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
        // 300 × 200 px at 96 dpi is 938 × 625 at 300 dpi.
        assert_eq!((be(16), be(20)), (938, 625));
        assert_eq!(&png[37..41], b"pHYs");
        assert_eq!(be(41), 11811);
        let decoded = tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!((decoded.width(), decoded.height()), (938, 625));
        // The background is white; the caption's ink is dark.
        assert_eq!(decoded.pixel(2, 2).unwrap().red(), 255);
        let dark = decoded
            .pixels()
            .iter()
            .filter(|p| p.red() < 80 && p.blue() < 80)
            .count();
        assert!(dark > 500, "{dark} dark pixels");
        let pdf = to_pdf(SVG).unwrap();
        assert!(pdf.starts_with(b"%PDF-"), "{:?}", &pdf[..8]);
        let text = String::from_utf8_lossy(&pdf);
        assert!(text.contains("DejaVu"), "the font is embedded");
        // The page: 300 × 200 px at 96 dpi is 225 × 150 pt.
        assert!(text.contains("/MediaBox [0 0 225 150]"), "{}", &text[..400]);
    }

    #[test]
    fn a_bad_svg_is_an_error_not_a_panic() {
        assert!(svg_tree("<svg").is_err());
        assert!(to_png("not svg").is_err());
        assert!(to_pdf("").is_err());
    }
}
