//! Every chart's files: the picture in each format asked for
//! ([`FIGURE_FORMAT`](crate::params::FIGURE_FORMAT): SVG, PDF, PNG), beside each other
//! with one stem (`f_of_d.svg`, `f_of_d.pdf`, `f_of_d.png`), and always `<stem>.plot.csv`,
//! the data the chart draws, one row per point (or cell) drawn, so that a figure can be drawn
//! again with another tool. A chart is named by its SVG path; the other files are derived
//! from it ([`FigureFormats::files`]).

use super::names::{figure_file as picture, plot_csv};
#[cfg(feature = "figures")]
use super::render;
use super::{file, OutputError};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Why a chart is not drawn in a build without the `figures` feature (the library alone, e.g.
/// the Python package's): its data are computed, but none of its files is written.
pub const NOT_DRAWN: &str =
    "this build of jkrbem has no figures (it was built without the `figures` feature), so \
     charts cannot be drawn";

/// A picture's file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FigureFormat {
    /// SVG, as plotters draws it (the text as text, in the viewer's sans-serif font).
    Svg,
    /// PDF, one page at the picture's size (96 pixels per inch), the text in the embedded
    /// DejaVu Sans ([`render::to_pdf`]).
    Pdf,
    /// PNG at 300 dpi on white ([`render::to_png`]).
    Png,
}

impl FigureFormat {
    /// Every format, in the order a chart's files are written.
    pub const ALL: [FigureFormat; 3] = [FigureFormat::Svg, FigureFormat::Pdf, FigureFormat::Png];

    /// Its name, which is also its files' extension ("svg").
    pub fn name(self) -> &'static str {
        match self {
            FigureFormat::Svg => "svg",
            FigureFormat::Pdf => "pdf",
            FigureFormat::Png => "png",
        }
    }

    /// The format of this name (as [`FigureFormat::name`] gives it), if any.
    pub fn parse(name: &str) -> Option<FigureFormat> {
        FigureFormat::ALL.into_iter().find(|f| f.name() == name)
    }
}

/// The formats every chart of a run is written in: one or more of [`FigureFormat`] (SVG
/// alone by default). Whatever they are, `<stem>.plot.csv` is written beside them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FigureFormats {
    /// Which of [`FigureFormat::ALL`] are asked for.
    asked: [bool; 3],
}

impl Default for FigureFormats {
    fn default() -> Self {
        FigureFormats::SVG
    }
}

impl FigureFormats {
    /// SVG alone (the default).
    pub const SVG: FigureFormats = FigureFormats {
        asked: [true, false, false],
    };

    /// These formats (repeats count once); SVG alone where `formats` is empty.
    pub fn of(formats: &[FigureFormat]) -> FigureFormats {
        if formats.is_empty() {
            return FigureFormats::SVG;
        }
        let mut asked = [false; 3];
        for (slot, format) in asked.iter_mut().zip(FigureFormat::ALL) {
            *slot = formats.contains(&format);
        }
        FigureFormats { asked }
    }

    /// These formats and `format`.
    pub fn with(mut self, format: FigureFormat) -> FigureFormats {
        self.asked[format as usize] = true;
        self
    }

    /// Whether `format` is asked for.
    pub fn contains(self, format: FigureFormat) -> bool {
        self.asked[format as usize]
    }

    /// The formats of a checked value of
    /// [`FIGURE_FORMAT`](crate::params::FIGURE_FORMAT) (a list of names, as
    /// [`values`](crate::params::values) gives it), or why not.
    pub fn from_value(value: &serde_json::Value) -> Result<FigureFormats, String> {
        let names: Option<Vec<FigureFormat>> = value.as_array().and_then(|a| {
            a.iter()
                .map(|v| v.as_str().and_then(FigureFormat::parse))
                .collect()
        });
        match names {
            Some(n) if !n.is_empty() => Ok(FigureFormats::of(&n)),
            _ => Err(format!(
                "{} = {value} is invalid (a bug: it was checked)",
                crate::params::FIGURE_FORMAT
            )),
        }
    }

    /// The formats written as the command line writes them ("svg,pdf,png"), checked as
    /// [`FIGURE_FORMAT`](crate::params::FIGURE_FORMAT) is; the refusal names it.
    pub fn parse(text: &str) -> Result<FigureFormats, String> {
        let value = crate::params::values::from_text(crate::params::FIGURE_FORMAT, text)?;
        FigureFormats::from_value(&value)
    }

    /// The formats asked for, in [`FigureFormat::ALL`]'s order.
    pub fn iter(self) -> impl Iterator<Item = FigureFormat> {
        FigureFormat::ALL
            .into_iter()
            .filter(move |f| self.contains(*f))
    }

    /// Every file the chart named `chart` (its SVG path) is written to: its picture in each
    /// format ([`names::figure_file`](super::names::figure_file)), then its data
    /// ([`names::plot_csv`](super::names::plot_csv)).
    pub fn files(self, chart: &Path) -> Vec<PathBuf> {
        self.iter()
            .map(|f| picture(chart, f))
            .chain([plot_csv(chart)])
            .collect()
    }

    /// The files of `chart` in words, for a message: the first with its path, the others by
    /// what follows the stem: "out/f.svg (also .plot.csv)", "out/f.svg (also .pdf, .png and
    /// .plot.csv)".
    pub fn shown(self, chart: &Path) -> String {
        let mut suffixes: Vec<String> = self.iter().map(|f| format!(".{}", f.name())).collect();
        suffixes.push(".plot.csv".into());
        let first = picture(chart, self.iter().next().unwrap_or(FigureFormat::Svg));
        let rest = &suffixes[1..];
        let also = match rest.split_last() {
            Some((last, others)) if !others.is_empty() => {
                format!("{} and {last}", others.join(", "))
            }
            _ => rest.concat(),
        };
        format!("{} (also {also})", first.display())
    }
}

/// One point a chart of curves draws (a line's vertex or a marker), as `<stem>.plot.csv`
/// records it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlotPoint {
    /// The series' legend label.
    pub series: String,
    /// How the series is drawn: `line`, `dashed`, `markers`, `line+markers` or
    /// `dashed+markers`.
    pub style: &'static str,
    /// x, in the chart's x unit.
    pub x: f64,
    /// y, in the chart's y unit.
    pub y: f64,
    /// The half-width of the point's vertical error bar, in the y unit (none where no bar is
    /// drawn).
    pub error: Option<f64>,
}

/// A chart that writes itself as a figure: its picture in each format asked for, and its
/// data as `<stem>.plot.csv` ([`write_figure`]).
pub trait WriteFigure {
    /// Write the chart to `path` (its SVG path) in each of `formats`, with its plot CSV.
    fn write_figure(&self, path: &Path, formats: FigureFormats) -> Result<(), OutputError>;
}

/// A row type of `<stem>.plot.csv`: its header, the fields' names in order.
pub trait PlotRecord: Serialize {
    /// The CSV header.
    const HEADER: &'static str;
}

impl PlotRecord for PlotPoint {
    const HEADER: &'static str = "series,style,x,y,error";
}

/// Write a chart: `svg` (the rendered document, or why it could not be drawn) to each of
/// `formats` beside `chart` (its SVG path), and `rows`, the data it draws, to
/// `<stem>.plot.csv` ([`names::plot_csv`](super::names::plot_csv)). Each file is written
/// atomically; the text is worded for the command line first (as every text file is,
/// [`file::write_text`]), so that every format says the same. The first failure is returned,
/// naming its file. Without the `figures` feature a PDF or PNG cannot be made: asking for one
/// fails with [`NOT_DRAWN`] (and no chart of this crate is drawn at all: its `svg` is that).
pub fn write_figure<T: PlotRecord>(
    chart: &Path,
    svg: Result<String, String>,
    rows: &[T],
    formats: FigureFormats,
) -> Result<(), OutputError> {
    let drawn = |path: &Path, reason: String| OutputError::Chart {
        path: path.display().to_string(),
        param: None,
        reason,
    };
    let svg = svg.map_err(|reason| drawn(chart, reason))?;
    let svg = crate::params::words::flags(&svg);
    for format in formats.iter() {
        let path = picture(chart, format);
        let bytes = match format {
            FigureFormat::Svg => svg.clone().into_bytes(),
            #[cfg(feature = "figures")]
            FigureFormat::Pdf => render::to_pdf(&svg).map_err(|e| drawn(&path, e))?,
            #[cfg(feature = "figures")]
            FigureFormat::Png => render::to_png(&svg).map_err(|e| drawn(&path, e))?,
            #[cfg(not(feature = "figures"))]
            FigureFormat::Pdf | FigureFormat::Png => return Err(drawn(&path, NOT_DRAWN.into())),
        };
        file::write_bytes(&path, &bytes)?;
    }
    file::write_csv(&plot_csv(chart), Some(T::HEADER), rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chart_names_its_files_by_its_stem() {
        let chart = Path::new("out/f_of_d.svg");
        assert_eq!(
            FigureFormats::default().files(chart),
            [
                Path::new("out/f_of_d.svg"),
                Path::new("out/f_of_d.plot.csv")
            ]
        );
        let all = FigureFormats::of(&[FigureFormat::Png, FigureFormat::Svg, FigureFormat::Pdf]);
        assert_eq!(
            all.files(Path::new("r.pressure.svg")),
            [
                "r.pressure.svg",
                "r.pressure.pdf",
                "r.pressure.png",
                "r.pressure.plot.csv"
            ]
            .map(PathBuf::from)
        );
        let pdf = FigureFormats::of(&[FigureFormat::Pdf]);
        assert_eq!(pdf.iter().collect::<Vec<_>>(), [FigureFormat::Pdf]);
        assert_eq!(pdf.with(FigureFormat::Svg).iter().count(), 2);
        assert_eq!(pdf.shown(chart), "out/f_of_d.pdf (also .plot.csv)");
        assert_eq!(
            all.shown(chart),
            "out/f_of_d.svg (also .pdf, .png and .plot.csv)"
        );
        assert_eq!(FigureFormats::of(&[]), FigureFormats::SVG);
        for f in FigureFormat::ALL {
            assert_eq!(FigureFormat::parse(f.name()), Some(f));
        }
        assert_eq!(FigureFormat::parse("jpeg"), None);
    }

    #[cfg(feature = "figures")]
    #[test]
    fn a_figure_is_written_in_every_format_with_its_data() {
        let dir = tempfile::tempdir().unwrap();
        let chart = dir.path().join("c.svg");
        let mut c = crate::output::line_chart::LineChart::new("t", "x", "y");
        c.push(
            "line ⟨margin⟩",
            vec![(0.0, 1.0), (0.1, 2.0 / 3.0)],
            0,
            crate::output::line_chart::Style::Line,
        );
        let all = FigureFormats::of(&FigureFormat::ALL);
        write_figure(&chart, c.to_svg(), &c.plot_points(), all).unwrap();
        let svg = std::fs::read_to_string(&chart).unwrap();
        assert!(
            svg.contains("--margin") && !svg.contains('⟨'),
            "worded for the CLI"
        );
        let pdf = std::fs::read(dir.path().join("c.pdf")).unwrap();
        assert!(pdf.starts_with(b"%PDF"));
        let png = std::fs::read(dir.path().join("c.png")).unwrap();
        assert!(png.starts_with(b"\x89PNG"));
        // The PNG is the SVG's width at 300 dpi (an SVG pixel is 1/96 inch).
        let svg_width: f64 = svg
            .split_once("width=\"")
            .and_then(|(_, r)| r.split_once('"'))
            .and_then(|(w, _)| w.parse().ok())
            .unwrap();
        let png_width = u32::from_be_bytes(png[16..20].try_into().unwrap());
        assert_eq!(png_width, (svg_width * 300.0 / 96.0).round() as u32);
        let csv = std::fs::read_to_string(dir.path().join("c.plot.csv")).unwrap();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "series,style,x,y,error");
        assert_eq!(lines.len(), 3, "{csv}");
        let row: Vec<&str> = lines[2].split(',').collect();
        assert_eq!(row[0], "line --margin");
        assert_eq!(row[1], "line");
        // Every number reads back as the one drawn.
        assert_eq!(row[2].parse::<f64>().unwrap(), 0.1);
        assert_eq!(row[3].parse::<f64>().unwrap(), 2.0 / 3.0);
        assert_eq!(row[4], "");
        // No temporary is left beside them.
        let names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names.len(), 4, "{names:?}");
        // A chart that could not be drawn names its file and writes nothing.
        let bad = dir.path().join("bad.svg");
        let e = write_figure::<PlotPoint>(&bad, Err("no".into()), &[], all).unwrap_err();
        assert!(e.to_string().contains("bad.svg"), "{e}");
        assert!(!bad.with_extension("plot.csv").exists());
    }

    #[cfg(not(feature = "figures"))]
    #[test]
    fn without_figures_a_chart_is_refused_and_nothing_written() {
        let dir = tempfile::tempdir().unwrap();
        let chart = dir.path().join("c.svg");
        let mut c = crate::output::line_chart::LineChart::new("t", "x", "y");
        c.push(
            "line",
            vec![(0.0, 1.0), (0.1, 2.0)],
            0,
            crate::output::line_chart::Style::Line,
        );
        // Its data are still there; the chart is not drawn, and writing it says why.
        assert_eq!(c.plot_points().len(), 2);
        assert_eq!(c.to_svg(), Err(NOT_DRAWN.to_string()));
        let e = c.write_figure(&chart, FigureFormats::SVG).unwrap_err();
        assert!(e.to_string().contains("c.svg"), "{e}");
        assert!(e.to_string().contains("`figures` feature"), "{e}");
        // A PDF or PNG of an SVG drawn elsewhere is refused too.
        let e = write_figure::<PlotPoint>(
            &chart,
            Ok("<svg/>".into()),
            &[],
            FigureFormats::of(&[FigureFormat::Png]),
        )
        .unwrap_err();
        assert!(e.to_string().contains("c.png"), "{e}");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
