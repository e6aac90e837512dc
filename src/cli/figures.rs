//! `--figure-format` of the commands that draw charts besides `simulate` (sweep, collect,
//! crossed, accuracy, bench, reproduce): the schema's parameter
//! ([`FIGURE_FORMAT`](jkrbem::params::FIGURE_FORMAT)), checked as `simulate` checks it.

use jkrbem::output::figure::FigureFormats;

/// The formats every chart of the command is written in.
#[derive(Debug, Clone, clap::Args)]
pub struct FigureArgs {
    /// Formats every chart is written in, comma-separated, beside each other with one stem:
    /// `svg`; `pdf`, one page at the picture's size (96 pixels per inch), its text in the
    /// built-in DejaVu Sans; `png`, 300 dpi on white. Whatever they are, each chart's data
    /// goes to <stem>.plot.csv beside it (one row per point drawn: series, style, x, y,
    /// error) [one or more of svg, pdf, png]
    #[arg(
        long = "figure-format",
        value_name = "NAME,…",
        default_value = "svg",
        value_parser = formats,
        allow_hyphen_values = true
    )]
    pub figure_format: FigureFormats,
}

/// The formats of `text` ("svg,pdf"), or why not, naming the flag.
fn formats(text: &str) -> Result<FigureFormats, String> {
    FigureFormats::parse(text).map_err(|e| jkrbem::params::words::flags(&e))
}
