//! The one declaration of every parameter a request takes (scene, indenter, model options,
//! plan, outputs): its name, unit, range, default and help, and the words each front end gives
//! it (the CLI's flag, the Python keyword, which is the name). Both front ends derive their
//! arguments from [`SPECS`]; requests are checked against it ([`values`]) and built from it
//! (the session's request); the library's messages name a parameter by its [`Spec`] (displayed as
//! a marker that each front end words in its own names, [`words`]).

pub mod limits;
pub mod values;
pub mod words;

mod field_choice;
pub use field_choice::FieldChoice;

mod study_table;
mod table;

pub use study_table::*;
pub use table::*;

use std::fmt;

/// The kind of value a parameter takes, with its range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// A real number in a range (dimensionless or in the parameter's unit).
    Real(Range),
    /// A whole number in [min, max].
    Count(u64, u64),
    /// A power of two in [min, max].
    PowerOfTwo(u64, u64),
    /// On or off (a CLI flag without a value; a Python bool).
    Switch,
    /// One of these names (the CLI writes them with hyphens, Python with underscores; both
    /// are accepted).
    Choice(&'static [&'static str]),
    /// A file's path (Python: a path, or for a height map an array).
    File,
    /// A relative accuracy: the CLI writes a percentage with its `%` ("2%"), Python a fraction
    /// (0.02); either lies in [min, max] as a fraction.
    Fraction(f64, f64),
    /// A duration: the CLI writes it with its unit ("90s", "20min", "2h"), Python in seconds;
    /// in [min, max] seconds.
    Seconds(f64, f64),
    /// Two real numbers, each in the range (the CLI writes "x,y", Python a pair).
    Pair(Range),
    /// 2 to 8 increasing powers of two in [min, max] (the CLI writes "64,128,256").
    Grids(u64, u64),
    /// Which states' fields are kept: "none", "minimum", "every:K" or "states:I,J".
    States,
    /// One or more of these names, none repeated (the CLI writes them comma-separated,
    /// "svg,pdf"; Python a list or the same text).
    Choices(&'static [&'static str]),
}

/// A range of real numbers, each end closed or open.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The lower end.
    pub lo: f64,
    /// The upper end.
    pub hi: f64,
    /// Whether the lower end itself is excluded.
    pub lo_open: bool,
    /// Whether the upper end itself is excluded.
    pub hi_open: bool,
}

impl Range {
    /// [lo, hi].
    pub const fn closed(lo: f64, hi: f64) -> Range {
        Range {
            lo,
            hi,
            lo_open: false,
            hi_open: false,
        }
    }

    /// (lo, hi).
    pub const fn open(lo: f64, hi: f64) -> Range {
        Range {
            lo,
            hi,
            lo_open: true,
            hi_open: true,
        }
    }

    /// [lo, hi).
    pub const fn upper_open(lo: f64, hi: f64) -> Range {
        Range {
            lo,
            hi,
            lo_open: false,
            hi_open: true,
        }
    }

    /// Whether `v` lies in the range (never for NaN).
    pub fn contains(&self, v: f64) -> bool {
        let above = if self.lo_open {
            v > self.lo
        } else {
            v >= self.lo
        };
        let below = if self.hi_open {
            v < self.hi
        } else {
            v <= self.hi
        };
        above && below
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = crate::text::compact;
        write!(
            f,
            "{}{}, {}{}",
            if self.lo_open { '(' } else { '[' },
            c(self.lo),
            c(self.hi),
            if self.hi_open { ')' } else { ']' }
        )
    }
}

/// What a parameter is when it is not given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fallback {
    /// This value, written as the CLI writes it.
    Value(&'static str),
    /// Chosen for the scene or the run, as said here (e.g. "fitted to the contact's aspect").
    Chosen(&'static str),
}

/// The front ends that take a parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fronts {
    /// The command line and Python alike.
    Both,
    /// The command line only (a file it writes).
    Cli,
}

/// What a parameter belongs to (the order of `--help` and of the docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Group {
    /// The indenter and the materials.
    Scene,
    /// The grid, the domain and the load path.
    Model,
    /// The conjugate-gradient solves and the backend.
    Solver,
    /// One grid, several extrapolated, or an accuracy.
    Plan,
    /// What is written, and where.
    Output,
    /// The other commands' own: their lists of ratios, grids and cases, ladders, shards and
    /// jobs ([`STUDY_SPECS`]).
    Study,
}

/// One parameter: its name (the Python keyword, the JSON key of a request and the column of a
/// batch's table), its flag, unit, kind and range, default and help.
#[derive(Debug, PartialEq)]
pub struct Spec {
    /// The name, e.g. "mesh_angle".
    pub name: &'static str,
    /// The command-line flag, e.g. "--mesh-angle".
    pub flag: &'static str,
    /// The unit ("length", "force/length²", "degrees", "" for a dimensionless number).
    pub unit: &'static str,
    /// Its kind and range.
    pub kind: Kind,
    /// Its value when not given.
    pub fallback: Fallback,
    /// What it belongs to.
    pub group: Group,
    /// Which front ends take it.
    pub fronts: Fronts,
    /// What it sets, in a sentence or a paragraph (units, ranges and defaults are added from
    /// the fields above where a front end shows it).
    pub help: &'static str,
}

/// A parameter that both front ends take.
const fn spec(
    name: &'static str,
    flag: &'static str,
    group: Group,
    unit: &'static str,
    kind: Kind,
    fallback: Fallback,
    help: &'static str,
) -> Spec {
    Spec {
        name,
        flag,
        unit,
        kind,
        fallback,
        group,
        fronts: Fronts::Both,
        help,
    }
}

/// `spec` taken by the command line only (a file it writes, a command Python lacks).
const fn cli_only(spec: Spec) -> Spec {
    Spec {
        fronts: Fronts::Cli,
        ..spec
    }
}

/// The marker that stands for a parameter's name in a message: each front end replaces it by
/// its own word for the parameter ([`words::render`]).
pub const OPEN: char = '⟨';
/// The end of a [`OPEN`] marker.
pub const CLOSE: char = '⟩';

impl fmt::Display for Spec {
    /// The parameter's marker, `⟨name⟩`, which the front end words.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{OPEN}{}{CLOSE}", self.name)
    }
}

/// Every parameter a message can name: a simulation's ([`SPECS`]), then the other commands'
/// ([`STUDY_SPECS`]), then the roughness generator's ([`ROUGHNESS_SPECS`]).
pub fn all() -> impl Iterator<Item = &'static Spec> {
    SPECS
        .iter()
        .chain(STUDY_SPECS)
        .chain(ROUGHNESS_SPECS)
        .copied()
}

/// The parameter of this name, if any (of [`SPECS`] or [`STUDY_SPECS`]).
pub fn by_name(name: &str) -> Option<&'static Spec> {
    all().find(|s| s.name == name)
}

/// The parameter of this flag (`--mesh-angle`), if any (of [`SPECS`] or [`STUDY_SPECS`]).
pub fn by_flag(flag: &str) -> Option<&'static Spec> {
    all().find(|s| s.flag == flag)
}

/// The parameters a command takes under a flag that another command spells alike but
/// bounds otherwise: (command, its parameter). They are no parameters of their own (their
/// names and flags are those of [`all`]'s, which a message names), only their ranges differ.
pub const COMMAND_SPECS: &[(&str, &Spec)] = &[
    ("roughness", ROUGHNESS_GRID),
    ("roughness", ROUGHNESS_GRID_Y),
];

/// The parameter `command` (`sweep`, `roughness`, …) takes under `flag`, with the range its
/// values are checked against: the command's own where it bounds the flag otherwise
/// ([`COMMAND_SPECS`]), else the parameter of that flag ([`by_flag`]), if any.
pub fn of_command(command: &str, flag: &str) -> Option<&'static Spec> {
    COMMAND_SPECS
        .iter()
        .find(|(c, s)| *c == command && s.flag == flag)
        .map(|(_, s)| *s)
        .or_else(|| by_flag(flag))
}

/// The parameter a column of a batch's table names: by its name (`mesh_angle`) or its flag,
/// with or without the dashes (`--mesh-angle`, `mesh-angle`), if any.
pub fn by_column(header: &str) -> Option<&'static Spec> {
    let h = header.trim();
    let h = h.strip_prefix("--").unwrap_or(h);
    by_name(&h.replace('-', "_"))
}

impl Spec {
    /// The range and default in words, as `--help` and the docs add them to [`Spec::help`]
    /// (e.g. "degrees, in [−360, 360]; default 0").
    pub fn terms(&self) -> String {
        let mut parts: Vec<String> = Vec::new();
        let range = match self.kind {
            Kind::Real(r) | Kind::Pair(r) => Some(format!("in {r}")),
            Kind::Count(lo, hi) => Some(format!("from {lo} to {hi}")),
            Kind::PowerOfTwo(lo, hi) => Some(format!("a power of two from {lo} to {hi}")),
            Kind::Grids(lo, hi) => {
                Some(format!("2 to 8 increasing powers of two from {lo} to {hi}"))
            }
            Kind::Choice(names) => Some(format!("one of {}", names.join(", "))),
            Kind::Choices(names) => Some(format!(
                "one or more of {}, comma-separated",
                names.join(", ")
            )),
            Kind::Fraction(lo, hi) => Some(format!(
                "a percentage in [{}, {}]",
                crate::text::compact(lo * 100.0),
                crate::text::compact(hi * 100.0)
            )),
            Kind::Seconds(..) => Some("from 1 s to 30 days".to_string()),
            Kind::Switch | Kind::File | Kind::States => None,
        };
        if !self.unit.is_empty() {
            parts.push(self.unit.to_string());
        }
        parts.extend(range);
        let mut text = parts.join(", ");
        let default = match self.fallback {
            Fallback::Value(v) if self.kind != Kind::Switch => format!("default {v}"),
            Fallback::Value(_) => String::new(),
            Fallback::Chosen(how) => format!("default: {how}"),
        };
        if !default.is_empty() {
            if !text.is_empty() {
                text.push_str("; ");
            }
            text.push_str(&default);
        }
        text
    }
}

#[cfg(test)]
mod tests;
