//! Standard output: written without ever panicking, and named `-` where a flag asks for a
//! file of results (`simulate --out -`, `--summary -`, `theory --out -`). When the results go
//! there, everything else a command would print there goes to standard error instead
//! ([`Channel`]).

use super::CliError;
use std::fmt;
use std::io::{self, Write};
use std::path::Path;
use std::sync::Mutex;

/// The name that stands for standard output where a flag names a file.
pub const STDOUT_NAME: &str = "-";

/// The first error standard output gave, if any; once set, nothing more is written there.
static STDOUT_ERROR: Mutex<Option<io::Error>> = Mutex::new(None);

/// Write to standard output without ever panicking (the `out!`/`outln!` macros). A reader that
/// went away (a closed pipe: `jkrbem … | head -1`) ends the output quietly while the run goes
/// on and writes its files; any other error (`> /dev/full`) is kept and reported at the exit
/// ([`finish_stdout`]), with exit code 1.
pub fn write_stdout(args: fmt::Arguments) {
    let text = jkrbem::params::words::flags(&args.to_string());
    with_stdout(|w| w.write_all(text.as_bytes()));
}

/// Write `bytes` (a file's worth of results) to standard output, as [`write_stdout`] does.
pub fn write_stdout_bytes(bytes: &[u8]) {
    match std::str::from_utf8(bytes) {
        // A summary's JSON names parameters by marker, as a file of it names them by flag.
        Ok(text) if text.contains(jkrbem::params::OPEN) => {
            let text = jkrbem::params::words::flags(text);
            with_stdout(|w| w.write_all(text.as_bytes()))
        }
        _ => with_stdout(|w| w.write_all(bytes)),
    }
}

/// Run `write` on the locked standard output unless it has failed before; keep its error.
fn with_stdout(write: impl FnOnce(&mut io::StdoutLock) -> io::Result<()>) {
    let Ok(mut failed) = STDOUT_ERROR.lock() else {
        return;
    };
    if failed.is_none() {
        if let Err(e) = write(&mut io::stdout().lock()) {
            *failed = Some(e);
        }
    }
}

/// Flush standard output and say what it could not take: `None` if all was written or its
/// reader went away (a broken pipe ends quietly), else the error in words.
pub fn finish_stdout() -> Option<String> {
    let mut failed = STDOUT_ERROR.lock().ok()?;
    if failed.is_none() {
        if let Err(e) = io::stdout().lock().flush() {
            *failed = Some(e);
        }
    }
    match failed.as_ref()? {
        e if e.kind() == io::ErrorKind::BrokenPipe => None,
        e => Some(format!("cannot write to standard output: {e}")),
    }
}

/// Whether `path` names standard output (`-`).
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == STDOUT_NAME
}

/// Of `(what, flag, path)` triples, the `what` whose file is standard output, if any; two
/// that both name it are refused (one stream cannot hold two files).
pub fn claim_stdout<T: Copy>(files: &[(T, &str, Option<&Path>)]) -> Result<Option<T>, CliError> {
    let mut claimed: Option<(T, &str)> = None;
    for &(what, flag, path) in files {
        if path.is_some_and(is_stdout) {
            if let Some((_, first)) = claimed {
                return Err(super::input(format!(
                    "{first} and {flag} both name standard output (-): one stream holds one \
                     file; give the other a file name"
                )));
            }
            claimed = Some((what, flag));
        }
    }
    Ok(claimed.map(|(what, _)| what))
}

/// Refuse `-` for a flag that names a folder (or a file with others beside it): standard
/// output holds one file of results.
pub fn not_stdout(flag: &str, path: &Path, command: &str) -> Result<(), CliError> {
    if is_stdout(path) {
        return Err(super::input(format!(
            "{flag} -: standard output holds a single file of results, and `jkrbem {command}` \
             writes several files where {flag} says; give a name"
        )));
    }
    Ok(())
}

/// Where a command's messages other than its results go: standard output, unless the results
/// themselves go there (then standard error, so that the stream holds only the file).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    /// Standard output.
    Stdout,
    /// Standard error.
    Stderr,
}

impl Channel {
    /// Standard error if the results take standard output (`results_there`), else stdout.
    pub fn beside(results_there: bool) -> Self {
        if results_there {
            Channel::Stderr
        } else {
            Channel::Stdout
        }
    }

    /// Write `text` (whole lines) to this channel.
    pub fn print(self, text: &str) {
        match self {
            Channel::Stdout => write_stdout(format_args!("{text}")),
            Channel::Stderr => {
                let _ = io::stderr().lock().write_all(text.as_bytes());
            }
        }
    }

    /// Write `line` and a newline to this channel.
    pub fn line(self, line: &str) {
        self.print(&format!("{line}\n"));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dash_is_standard_output_and_only_one_flag_may_take_it() {
        let dash = Path::new("-");
        let file = Path::new("s.csv");
        assert!(is_stdout(dash) && !is_stdout(file) && !is_stdout(Path::new("./-")));
        let one = claim_stdout(&[(1, "--out", Some(file)), (2, "--summary", Some(dash))]);
        assert_eq!(one.unwrap(), Some(2));
        let none = claim_stdout(&[(1, "--out", None), (2, "--summary", Some(file))]);
        assert_eq!(none.unwrap(), None);
        let both = claim_stdout(&[(1, "--out", Some(dash)), (2, "--summary", Some(dash))]);
        let e = both.unwrap_err().to_string();
        assert!(e.contains("--out") && e.contains("--summary"), "{e}");
        assert!(not_stdout("--out", dash, "sweep").is_err());
        assert!(not_stdout("--out", file, "sweep").is_ok());
        assert_eq!(Channel::beside(true), Channel::Stderr);
        assert_eq!(Channel::beside(false), Channel::Stdout);
    }
}
