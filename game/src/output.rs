//! Writing what the commands print: one place that decides what a failed
//! write means.
//!
//! - stdout closed by its reader (`lightcone check … | head`): the command
//!   stops quietly, exit 0, as `head` asked for no more;
//! - any other write error (a full disk, `-o /dev/full`): a message naming
//!   what could not be written, exit 1.
//!
//! Messages to stderr never fail a command (there is nowhere left to say so).

use std::io::{ErrorKind, Write};
use std::process::ExitCode;

/// Why a command stops writing early.
#[derive(Debug)]
pub enum Stop {
    /// The reader closed stdout: stop quietly.
    Closed,
    /// A write failed; the message says what and why.
    Failed(String),
}

impl Stop {
    /// The exit code for this stop, after saying why (to stderr) if needed.
    pub fn exit(self) -> ExitCode {
        match self {
            Stop::Closed => ExitCode::SUCCESS,
            Stop::Failed(msg) => {
                eprint_quiet(&format!("{msg}\n"));
                ExitCode::FAILURE
            }
        }
    }

    /// A write error on `what` (e.g. "stdout" or a file name).
    pub fn from_io(what: &str, e: &std::io::Error) -> Self {
        if e.kind() == ErrorKind::BrokenPipe {
            Stop::Closed
        } else {
            Stop::Failed(format!("{what}: cannot write: {e}"))
        }
    }
}

impl From<Stop> for ExitCode {
    fn from(s: Stop) -> Self {
        s.exit()
    }
}

/// Writes `text` to stdout and flushes it.
pub fn print(text: &str) -> Result<(), Stop> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| Stop::from_io("stdout", &e))
}

/// Writes `text` to stderr, ignoring failure.
pub fn eprint_quiet(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err.write_all(text.as_bytes());
    let _ = err.flush();
}

/// `println!` for commands: writes a line to stdout and evaluates to
/// `Result<(), Stop>`; use with `?` or [`Stop::exit`].
#[macro_export]
macro_rules! outln {
    () => { $crate::output::print("\n") };
    ($($arg:tt)*) => { $crate::output::print(&format!("{}\n", format_args!($($arg)*))) };
}

/// `eprintln!` that never panics (stderr closed or broken).
#[macro_export]
macro_rules! errln {
    ($($arg:tt)*) => { $crate::output::eprint_quiet(&format!("{}\n", format_args!($($arg)*))) };
}

/// Writes `text` to stdout; if that fails, ends the process as [`Stop`]
/// says (exit 0 quietly on a closed pipe, else a message and exit 1). For
/// commands that print as they go and hold nothing to save (benchmarks).
pub fn print_or_exit(text: &str) {
    if let Err(stop) = print(text) {
        let code = match stop {
            Stop::Closed => 0,
            Stop::Failed(msg) => {
                eprint_quiet(&format!("{msg}\n"));
                1
            }
        };
        std::process::exit(code);
    }
}

/// `println!` that ends the process on a write error (see
/// [`print_or_exit`]).
#[macro_export]
macro_rules! sayln {
    () => { $crate::output::print_or_exit("\n") };
    ($($arg:tt)*) => { $crate::output::print_or_exit(&format!("{}\n", format_args!($($arg)*))) };
}

/// Refuses an output path that names the input file itself (`simulate
/// s.toml --out s.toml` once replaced the scene with JSON): a message
/// naming both. Paths that do not exist yet are never the input.
/// (Desktop-only: the browser build writes no files.)
#[cfg(not(target_arch = "wasm32"))]
pub fn not_the_input(out: &std::path::Path, input: &std::path::Path) -> Result<(), String> {
    use std::os::unix::fs::MetadataExt;
    let same = match (std::fs::metadata(out), std::fs::metadata(input)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    };
    if same {
        Err(format!(
            "{}: is the scene file {} itself; write the output somewhere else",
            out.display(),
            input.display()
        ))
    } else {
        Ok(())
    }
}
