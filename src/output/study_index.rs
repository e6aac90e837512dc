//! The study's `index.html`: every chart with its caption, the adhesive force per ratio, the
//! branch laws per ratio (with their uncertainties where extrapolated to Δx → 0) beside JKR's,
//! and every warning.

use crate::analysis::study_fits::BranchFits;
use crate::output::sweep_csv::SweepRow;
use std::fmt::Write as _;

/// One chart of the report: its file name and caption.
pub struct Figure {
    /// The SVG's file name, beside index.html.
    pub file: String,
    /// What it shows and how it was made.
    pub caption: String,
}

/// What the page shows.
pub struct StudyPage<'a> {
    /// The charts, in order.
    pub figures: &'a [Figure],
    /// The adhesive force of every ratio.
    pub rows: &'a [SweepRow],
    /// The branch laws of every ratio.
    pub fits: &'a [BranchFits],
    /// Warnings about the results.
    pub warnings: &'a [String],
    /// Wall time of the whole study (s).
    pub wall_s: f64,
    /// Whether it ran the quick grids.
    pub quick: bool,
}

/// Text made safe for HTML.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;").replace('<', "&lt;")
}

/// The page as HTML.
pub fn index_html(page: &StudyPage) -> String {
    let mut html = String::from(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>jkrbem: the study</title>\
         <style>body{font-family:sans-serif;max-width:960px;margin:2em auto;color:#222}\
         figure{margin:2em 0}img{width:100%;border:1px solid #ddd}\
         figcaption{font-size:0.95em;color:#444}table{border-collapse:collapse}\
         td,th{border:1px solid #ccc;padding:3px 8px;text-align:right}</style></head><body>\n",
    );
    let _ = writeln!(
        html,
        "<h1>jkrbem: adhesive contact of ellipsoids</h1><p>{} run, {:.0} s in all. \
         Normalisation: F̄ = F/(3π Re Δγ), c̄ = c/c_r, d̄ = d·Re/c_r² (physics §2).</p>",
        if page.quick {
            "Quick (one coarse grid per ratio)"
        } else {
            "Full (three grids per ratio, extrapolated to Δx → 0)"
        },
        page.wall_s
    );
    html.push_str(
        "<table><tr><th>R1/R2</th><th>grid</th><th>|min F̄| at Δx → 0</th><th>JG</th>\
         <th>n_d</th><th>wall (s)</th></tr>\n",
    );
    for r in page.rows {
        let f = |v: Option<f64>| v.map_or("—".into(), |v| format!("{v:.4}"));
        let _ = writeln!(
            html,
            "<tr><td>{}</td><td>{}×{}</td><td>{}{}</td><td>{}</td><td>{}</td><td>{:.1}</td></tr>",
            r.ratio,
            r.grid,
            r.ny,
            f(r.f_ad_bar),
            r.f_ad_bar_uncertainty
                .map_or(String::new(), |u| format!(" ± {u:.4}")),
            f(r.jg_f_ad_bar),
            r.n_d.map_or("—".into(), |v| format!("{v:.0}")),
            r.wall_s
        );
    }
    html.push_str("</table>\n");
    html.push_str(&fits_table(page.fits));
    if !page.warnings.is_empty() {
        html.push_str("<h2>Warnings</h2><ul>\n");
        for w in page.warnings {
            let _ = writeln!(html, "<li>{}</li>", escape(w));
        }
        html.push_str("</ul>\n");
    }
    for f in page.figures {
        let _ = writeln!(
            html,
            "<figure><img src=\"{0}\" alt=\"{0}\"><figcaption>{1}</figcaption></figure>",
            f.file,
            escape(&f.caption)
        );
    }
    html.push_str("</body></html>\n");
    html
}

/// The branch laws per ratio: each coefficient with its half-width where known, and JKR's.
fn fits_table(fits: &[BranchFits]) -> String {
    let mut html = String::from(
        "<h2>Branch laws d̄ = A c̄² + B c̄^½, F̄ = c1 c̄³ + c2 c̄^α</h2>\
         <table><tr><th>R1/R2</th><th>A</th><th>B</th><th>c1</th><th>c2</th><th>α</th>\
         <th>grids</th></tr>\n",
    );
    let r2 = std::f64::consts::SQRT_2;
    let _ = writeln!(
        html,
        "<tr><td>JKR</td><td>1</td><td>{:.4}</td><td>1</td><td>{:.4}</td><td>1.5</td><td></td></tr>",
        -2.0 / 3.0 * r2,
        -r2
    );
    for f in fits {
        let d = f.d_of_c.as_ref();
        let p = f.f_of_c.as_ref();
        let values = [
            d.map(|d| d.a),
            d.map(|d| d.b),
            p.map(|p| p.c1),
            p.map(|p| p.c2),
            p.map(|p| p.alpha),
        ];
        let _ = write!(html, "<tr><td>{}</td>", f.ratio);
        for (i, v) in values.iter().enumerate() {
            let cell = match (v, f.uncertainty) {
                (Some(v), Some(u)) => format!("{v:.4} ± {:.4}", u[i]),
                (Some(v), None) => format!("{v:.4}"),
                (None, _) => "—".into(),
            };
            let _ = write!(html, "<td>{cell}</td>");
        }
        let grids: Vec<String> = f.grids.iter().map(|g| g.to_string()).collect();
        let _ = writeln!(html, "<td>{}</td></tr>", grids.join(", "));
    }
    html.push_str("</table>\n");
    html
}
