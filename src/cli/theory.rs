//! `jkrbem theory`: closed-form curves.

use super::parse::value;
use super::stdout::{is_stdout, write_stdout_bytes, Channel};
use super::{input, CliError};
use clap::ValueEnum;
use jkrbem::params::{OUT, POINTS, RATIO};
use jkrbem::session::claim::{write_error, Outputs};
use jkrbem::theory::{self, TheoryModel};
use std::path::PathBuf;

/// Which closed form.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModelChoice {
    /// Non-adhesive elliptic Hertz contact.
    Hertz,
    /// JKR (sphere only: --ratio 1).
    Jkr,
    /// Johnson–Greenwood (2005) approximate theory for an elliptical contact.
    Jg,
}

/// Arguments of `jkrbem theory`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The closed form.
    #[arg(long, value_enum)]
    pub model: ModelChoice,
    /// Axis ratio R1/R2, in [1, 1000] (exactly 1 for JKR).
    #[arg(long, default_value_t = 1.0, value_parser = value::<f64>(RATIO))]
    pub ratio: f64,
    /// Number of points on the curve, 2 to 1000000.
    #[arg(long, default_value_t = 400, value_parser = value::<usize>(POINTS))]
    pub points: usize,
    /// Output CSV with columns c_bar,f_bar,d_bar,a_bar,b_bar (`-`: standard output, the
    /// other lines then on standard error) [default: jkrbem-out/theory-<model>-r<ratio>.csv].
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Run `jkrbem theory`.
pub fn run(args: Args) -> Result<(), CliError> {
    let (model, name) = match args.model {
        ModelChoice::Hertz => (TheoryModel::Hertz, "hertz"),
        ModelChoice::Jkr => (TheoryModel::Jkr, "jkr"),
        ModelChoice::Jg => (TheoryModel::Jg, "jg"),
    };
    jkrbem::scene::Scene::from_ratio(args.ratio, 1.0, 1.0, 1.0).map_err(input)?;
    let curve = theory::curve(model, args.ratio, args.points).map_err(|e| {
        input(format!(
            "--ratio {}: {e}",
            jkrbem::text::compact(args.ratio)
        ))
    })?;
    let out = args
        .out
        .unwrap_or_else(|| jkrbem::output::names::theory_default(name, args.ratio));
    let header = Some("c_bar,f_bar,d_bar,a_bar,b_bar");
    let rows = curve
        .iter()
        .map(|p| (p.c_bar, p.f_bar, p.d_bar, p.a_bar, p.b_bar));
    // `--out -`: the CSV on standard output, and the lines below on standard error.
    let text = Channel::beside(is_stdout(&out));
    if is_stdout(&out) {
        let mut bytes = Vec::new();
        jkrbem::output::file::csv_to(&mut bytes, header, rows).map_err(super::failed)?;
        write_stdout_bytes(&bytes);
    } else {
        let _claimed = Outputs::claim(&[(out.clone(), OUT.into())])?;
        jkrbem::output::file::write_csv(&out, header, rows).map_err(write_error(OUT))?;
        text.line(&format!(
            "{} points of {} at R1/R2 = {} written to {}",
            curve.len(),
            name.to_uppercase(),
            args.ratio,
            out.display()
        ));
    }
    if model != TheoryModel::Hertz {
        let p = theory::pull_off(model, args.ratio).map_err(input)?;
        let f = p.force_min;
        let e = p.end_of_contact;
        text.line(&format!(
            "force-controlled pull-off (min F̄): F̄ = {:.6}, c̄ = {:.6}, d̄ = {:.6}, ā = {:.6}, b̄ = {:.6}",
            f.f_bar, f.c_bar, f.d_bar, f.a_bar, f.b_bar
        ));
        text.line(&format!(
            "displacement-controlled end of contact (min d̄): F̄ = {:.6}, c̄ = {:.6}, d̄ = {:.6}",
            e.f_bar, e.c_bar, e.d_bar
        ));
    }
    Ok(())
}
