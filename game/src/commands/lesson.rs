//! `lightcone lesson FILE.py...`: run lessons headless and report their
//! claims. Each lesson runs in a child process ([`supervise`]), so that
//! nothing it does can hang or crash the run.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use crate::lesson::headless::Outcome;
use crate::lesson::supervise::{self, Limits};
use crate::output::Stop;

/// The options of `lesson` beyond the files.
pub struct Options {
    /// Board time to stop at, s.
    pub until: f64,
    /// Frames per real second.
    pub fps: f64,
    /// Longest a hook may run, s.
    pub hook_limit: f64,
    /// Address-space limit of each lesson's process, MiB.
    pub memory_limit: u64,
    /// Longest a lesson runs, real time, s.
    pub time_limit: f64,
    /// This is the child process of a `lesson` run (internal).
    pub child: bool,
    /// This is the lesson's process of a window (internal).
    pub window_child: bool,
    /// Print each outcome as one JSON line.
    pub json: bool,
}

/// Runs each lesson; prints each claim (or one JSON outcome per line with
/// `json`). The exit status is the worst of the lessons': 0 all passed,
/// 1 a claim failed or a lesson raised (or a bad argument), 3 a hook was
/// stopped at its time limit, 4 a lesson's process died.
pub fn run(paths: &[PathBuf], options: Options) -> ExitCode {
    if !(options.hook_limit.is_finite()
        && options.hook_limit > 0.0
        && options.hook_limit <= 86_400.0)
    {
        crate::errln!(
            "--hook-limit {}: give seconds in (0, 86400]",
            options.hook_limit
        );
        return ExitCode::FAILURE;
    }
    if options.memory_limit < 256 {
        crate::errln!(
            "--memory-limit {}: give at least 256 MiB",
            options.memory_limit
        );
        return ExitCode::FAILURE;
    }
    let limits = Limits {
        until: options.until,
        fps: options.fps,
        hook: std::time::Duration::from_secs_f64(options.hook_limit),
        memory_mb: options.memory_limit,
        run: std::time::Duration::from_secs_f64(options.time_limit),
    };
    if options.window_child {
        return match paths {
            [path] => ExitCode::from(crate::lesson::remote::child(
                path,
                limits.hook,
                limits.memory_mb,
            )),
            _ => ExitCode::FAILURE,
        };
    }
    if options.child {
        return match paths {
            [path] => ExitCode::from(supervise::child(path, limits)),
            _ => ExitCode::FAILURE,
        };
    }
    // Ctrl-C stops the lesson running, shows what it did, and ends the run.
    crate::interrupt::watch();
    let mut worst = 0u8;
    for path in paths {
        worst = worst.max(one(path, limits, options.json));
        if crate::interrupt::interrupted() {
            return crate::interrupt::exit_code(&format!("{} stopped", path.display()));
        }
    }
    ExitCode::from(worst)
}

/// Runs one lesson and prints its outcome; its exit status.
fn one(path: &Path, limits: Limits, json: bool) -> u8 {
    let what = match std::fs::metadata(path) {
        Ok(m) if m.is_file() => None,
        Ok(m) if m.is_dir() => Some("is a directory, not a lesson file"),
        Ok(_) => Some("is not a regular file (a FIFO or device): give a lesson's .py file"),
        Err(_) => Some("no such lesson file"),
    };
    if let Some(what) = what {
        crate::errln!("{}: {what}", path.display());
        return 1;
    }
    // The header first, so that a long lesson shows which one runs.
    if !json {
        match crate::outln!("== {}", path.display()) {
            Ok(()) => {}
            Err(Stop::Closed) => return 0,
            Err(Stop::Failed(msg)) => {
                crate::errln!("{msg}");
                return 1;
            }
        }
    }
    let outcome = match supervise::run(path, limits) {
        Ok(o) => o,
        Err(e) => {
            crate::errln!("{e}");
            return 1;
        }
    };
    match show(&outcome, json) {
        Ok(()) => {}
        // The reader closed stdout (`| head`): stop quietly.
        Err(Stop::Closed) => return 0,
        Err(Stop::Failed(msg)) => {
            crate::errln!("{msg}");
            return 1;
        }
    }
    let failed = outcome.claims.iter().filter(|c| !c.ok).count();
    if outcome.error.is_some() {
        crate::errln!("{}: the lesson was stopped (reason above)", path.display());
    } else if failed > 0 {
        crate::errln!(
            "{}: {failed} of {} claims failed",
            path.display(),
            outcome.claims.len()
        );
    }
    outcome.status()
}

/// Prints the outcome: JSON, or one line per answer and claim (after the
/// `== FILE` header [`one`] printed).
fn show(outcome: &Outcome, json: bool) -> Result<(), Stop> {
    if json {
        // One compact object per line (one line per lesson file).
        return match serde_json::to_string(outcome) {
            Ok(text) => crate::outln!("{text}"),
            Err(e) => Err(Stop::Failed(format!("cannot write the outcome: {e}"))),
        };
    }
    for (q, a) in &outcome.answers {
        crate::outln!("? {q} -> {a}")?;
    }
    for c in &outcome.claims {
        let mark = if c.ok { "ok  " } else { "FAIL" };
        crate::outln!("{mark} {}: {}", c.claim, c.detail)?;
    }
    match (&outcome.error, &outcome.finished) {
        (Some(_), _) => Ok(()), // already on stderr
        (None, Some(msg)) => crate::outln!("finished at t = {:.3} s: {msg}", outcome.t),
        (None, None) => crate::outln!("stopped at t = {:.3} s without finish()", outcome.t),
    }
}
