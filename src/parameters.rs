//! The parameters that the library's range checks name, each with the flag the command line
//! gives it and the keyword a Python caller gives it. The library's messages name a
//! parameter by its flag (`--mesh-angle = 95 is invalid: …`); [`as_keywords`] turns such a
//! message into one that names the keywords (`mesh_angle = 95 is invalid: …`), so that a
//! front end other than the CLI never shows a flag its user cannot type.

/// One parameter: its flag, its keyword and what it sets (with its unit).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Parameter {
    /// The command-line flag, e.g. "--mesh-angle".
    pub flag: &'static str,
    /// The Python keyword, e.g. "mesh_angle".
    pub keyword: &'static str,
    /// What it sets, with its unit.
    pub meaning: &'static str,
}

/// A parameter of [`PARAMETERS`].
const fn p(flag: &'static str, keyword: &'static str, meaning: &'static str) -> Parameter {
    Parameter {
        flag,
        keyword,
        meaning,
    }
}

/// Every parameter a message of `scene`, `model`, `plan` or a simulation can name.
pub const PARAMETERS: &[Parameter] = &[
    p("--ratio", "ratio", "the axis ratio R1/R2 (dimensionless)"),
    p(
        "--r1",
        "r1",
        "the ellipsoid's larger radius of curvature R1 (length)",
    ),
    p(
        "--r2",
        "r2",
        "the ellipsoid's smaller radius of curvature R2 (length)",
    ),
    p(
        "--e-star",
        "e_star",
        "the effective modulus E* (force/length²)",
    ),
    p(
        "--work-of-adhesion",
        "work_of_adhesion",
        "the work of adhesion Δγ (force/length)",
    ),
    p("--indenter", "indenter", "the indenter's shape"),
    p("--radius", "radius", "the flat punch's radius (length)"),
    p(
        "--exponent",
        "exponent",
        "the power law's exponent n (dimensionless)",
    ),
    p(
        "--scale",
        "scale",
        "the power law's height at r = 1 (length)",
    ),
    p("--height-map", "height_map", "the measured surface's file"),
    p(
        "--spacing",
        "spacing",
        "the measured surface's node spacing (length)",
    ),
    p(
        "--young",
        "young",
        "the cylinders' Young's modulus (force/length²)",
    ),
    p(
        "--poisson",
        "poisson",
        "the cylinders' Poisson's ratio (dimensionless)",
    ),
    p(
        "--angle",
        "angle",
        "the angle between crossed cylinders (degrees)",
    ),
    p(
        "--angles",
        "angles",
        "the angles between crossed cylinders (degrees)",
    ),
    p("--grid", "grid", "elements along x (a power of two)"),
    p("--fields", "fields", "the states whose fields are kept"),
    p("--grid-y", "grid_y", "elements along y (a power of two)"),
    p(
        "--start-radius",
        "start_radius",
        "the first contact's mean radius c̄0 (in c_r)",
    ),
    p(
        "--steps",
        "steps",
        "load steps to the expected end of contact",
    ),
    p(
        "--final-d",
        "final_d",
        "the approach d̄ at which a run stops (dimensionless)",
    ),
    p(
        "--margin",
        "margin",
        "the free margin around the first contact (relative)",
    ),
    p(
        "--mesh-angle",
        "mesh_angle",
        "the grid's angle to the major axis (degrees)",
    ),
    p(
        "--apex-offset",
        "apex_offset",
        "the apex within its element (elements, x and y)",
    ),
    p(
        "--cg-tolerance",
        "cg_tolerance",
        "CG's relative residual (dimensionless)",
    ),
    p(
        "--cg-accept",
        "cg_accept",
        "the residual a failed solve is accepted at (relative)",
    ),
    p(
        "--cg-max-iterations",
        "cg_max_iterations",
        "CG's iteration limit per solve",
    ),
    p(
        "--measure",
        "measure",
        "what a run is for (curve or adhesive force)",
    ),
    p(
        "--onsets",
        "onsets",
        "which detachment onsets a run locates",
    ),
    p(
        "--accuracy",
        "accuracy",
        "the relative uncertainty aimed at",
    ),
    p(
        "--extrapolate-grids",
        "extrapolate_grids",
        "the grids an extrapolation runs",
    ),
    p(
        "--backend",
        "backend",
        "the backend that solves (cpu, gpu, auto)",
    ),
    p("--jobs", "jobs", "runs at a time"),
    p(
        "--convolution",
        "convolution",
        "padded (exact) or periodic (to show its error)",
    ),
    p(
        "--extrapolate",
        "extrapolate",
        "whether to extrapolate from several grids",
    ),
    p(
        "--time-limit",
        "time_limit",
        "the wall-clock time an accuracy run may take (s)",
    ),
    p("--out", "out", "where the states are written"),
    p("--summary", "summary", "where the summary JSON is written"),
];

/// The parameter set by `flag`, if the library names it.
pub fn by_flag(flag: &str) -> Option<&'static Parameter> {
    PARAMETERS.iter().find(|p| p.flag == flag)
}

/// `message` with every flag of [`PARAMETERS`] replaced by its keyword; other text (and
/// flags the library does not name) is kept as it is.
pub fn as_keywords(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some((before, token, after)) = next_flag(rest) {
        out.push_str(before);
        out.push_str(by_flag(token).map_or(token, |p| p.keyword));
        rest = after;
    }
    out.push_str(rest);
    out
}

/// The first flag-like token of `text` ("--" and the lower-case letters, digits and hyphens
/// that follow), with the text before and after it.
fn next_flag(text: &str) -> Option<(&str, &str, &str)> {
    let at = text.find("--")?;
    let tail = &text[at..];
    let len = 2 + tail[2..]
        .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
        .unwrap_or(tail.len() - 2);
    Some((&text[..at], &tail[..len], &tail[len..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flags_and_keywords_are_unique_and_spelt_alike() {
        for (i, a) in PARAMETERS.iter().enumerate() {
            assert_eq!(a.keyword, a.flag[2..].replace('-', "_"), "{a:?}");
            for b in &PARAMETERS[i + 1..] {
                assert_ne!(a.flag, b.flag);
            }
        }
    }

    #[test]
    fn messages_name_keywords_and_keep_unknown_flags() {
        assert_eq!(
            as_keywords("--grid-y 64 is too small: use --grid-y 128, or a smaller --grid"),
            "grid_y 64 is too small: use grid_y 128, or a smaller grid"
        );
        assert_eq!(as_keywords("--gridx and --"), "--gridx and --");
        assert_eq!(as_keywords("no flag: σ_c"), "no flag: σ_c");
        assert_eq!(as_keywords("(--mesh-angle)."), "(mesh_angle).");
    }

    /// Every flag that a message of `scene`, `model` or `plan` names is a parameter here, so
    /// that a Python caller never reads a flag.
    #[test]
    fn every_flag_the_library_names_is_listed() {
        let sources = [
            include_str!("model/mod.rs"),
            include_str!("model/grid.rs"),
            include_str!("model/steps.rs"),
            include_str!("model/error.rs"),
            include_str!("scene/mod.rs"),
            include_str!("scene/indenter.rs"),
            include_str!("scene/measured.rs"),
            include_str!("plan.rs"),
            include_str!("analysis/crossed.rs"),
            include_str!("run/simulate.rs"),
            include_str!("run/open.rs"),
        ];
        for source in sources {
            let code = source.split("#[cfg(test)]").next().unwrap();
            let mut rest = code;
            while let Some((_, flag, after)) = next_flag(rest) {
                if flag[2..].starts_with(|c: char| c.is_ascii_lowercase()) {
                    assert!(by_flag(flag).is_some(), "{flag} is not in PARAMETERS");
                }
                rest = after;
            }
        }
    }
}
