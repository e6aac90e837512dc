//! The flags of `jkrbem simulate`, derived from the request schema
//! ([`jkrbem::params::SPECS`]): one flag per parameter, its help, unit, range and default
//! from there. What is given is kept as text, by parameter name, for
//! [`jkrbem::session::request::Request::from_texts`] to check.

use clap::{Arg, ArgAction, ArgMatches, FromArgMatches};
use jkrbem::params::{Kind, Spec, SPECS};

/// The texts given to `jkrbem simulate`, by parameter name, in the schema's order.
#[derive(Debug, Clone, Default)]
pub struct Args {
    /// (name, text) of each parameter given; a switch given is "true".
    pub given: Vec<(&'static str, String)>,
}

/// The clap argument of one parameter.
fn arg(spec: &'static Spec) -> Arg {
    let terms = spec.terms();
    let help = if terms.is_empty() {
        spec.help.to_string()
    } else {
        format!("{} [{terms}]", spec.help)
    };
    let help = jkrbem::params::words::flags(&help);
    let a = Arg::new(spec.name)
        .long(&spec.flag[2..])
        .help(help)
        .help_heading(heading(spec));
    match spec.kind {
        Kind::Switch => a.action(ArgAction::SetTrue),
        _ => a
            .action(ArgAction::Set)
            .value_name(value_name(spec))
            .allow_hyphen_values(true),
    }
}

/// The `--help` section a parameter is listed in.
fn heading(spec: &Spec) -> &'static str {
    use jkrbem::params::Group::*;
    match spec.group {
        Scene => "Scene (indenter and materials)",
        Model => "Grid, domain and load path",
        Solver => "Solves and backend",
        Plan => "One grid, several, or an accuracy",
        Output => "Outputs",
        Study => "Studies",
    }
}

/// The placeholder `--help` shows for a parameter's value.
fn value_name(spec: &Spec) -> &'static str {
    match spec.kind {
        Kind::Real(_) => "X",
        Kind::Count(..) | Kind::PowerOfTwo(..) => "N",
        Kind::Choice(_) => "NAME",
        Kind::Choices(_) => "NAME,…",
        Kind::File => "FILE",
        Kind::Fraction(..) => "PERCENT",
        Kind::Seconds(..) => "DURATION",
        Kind::Pair(_) => "X,Y",
        Kind::Grids(..) => "N,N,…",
        Kind::Switch | Kind::States => "WHICH",
    }
}

impl clap::Args for Args {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        SPECS
            .iter()
            .enumerate()
            .fold(cmd, |cmd, (i, &spec)| cmd.arg(arg(spec).display_order(i)))
    }
    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for Args {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut given = Vec::new();
        for spec in SPECS {
            match spec.kind {
                Kind::Switch => {
                    if m.get_flag(spec.name) {
                        given.push((spec.name, "true".to_string()));
                    }
                }
                _ => {
                    if let Some(v) = m.get_one::<String>(spec.name) {
                        given.push((spec.name, v.clone()));
                    }
                }
            }
        }
        Ok(Args { given })
    }
    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(m)?;
        Ok(())
    }
}
