//! Where a result comes from, as every summary and field file states it: the program, its
//! version and commit, when it ran, the scene in the user's units, every option that shaped
//! the run, the backend and device, and (for the CLI) the command line.

use super::digest::InputFile;
use serde::Serialize;
use serde_json::Value;

/// The provenance of a result.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Provenance {
    /// "jkrbem".
    pub program: &'static str,
    /// The crate's version.
    pub version: &'static str,
    /// The git commit it was built from, where known.
    pub git_commit: Option<&'static str>,
    /// When the result was made (UTC, RFC 3339).
    pub date: String,
    /// The scene in the user's units: the indenter and its parameters (lengths), E*
    /// (force/length²) and Δγ (force/length).
    pub scene: Value,
    /// Every option that shaped the run (grid, domain, load path, CG, protocol, mode).
    pub options: Value,
    /// The backend asked for, and what ran: name, arithmetic and device of each run.
    pub backend: Value,
    /// The command line, where the result comes from the `jkrbem` command.
    pub command: Option<String>,
    /// The request as its schema completed it (every parameter by name, defaults filled),
    /// where the result answers one (`simulate`, a batch's scene): what a batch's `--resume`
    /// compares and `collect` tabulates.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub request: Option<Value>,
    /// Every file the scene was read from (height map, roughness), with the size and CRC-32
    /// of what was read: what a batch's `--resume` and `collect` check the files against.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub input_files: Vec<InputFile>,
}

impl Provenance {
    /// The provenance of a result made now from `scene`, `options` and `backend`.
    pub fn now(scene: Value, options: Value, backend: Value, command: Option<String>) -> Self {
        Provenance {
            program: "jkrbem",
            version: env!("CARGO_PKG_VERSION"),
            git_commit: option_env!("JKRBEM_GIT_COMMIT"),
            date: humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string(),
            scene,
            options,
            backend,
            command,
            request: None,
            input_files: Vec::new(),
        }
    }
}
