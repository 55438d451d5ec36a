//! `lightcone lesson FILE.py`: run a lesson headless and report its claims.

use std::path::Path;
use std::process::ExitCode;

use crate::lesson::headless;
use crate::output::Stop;

/// Runs the lesson; prints each claim (or the JSON outcome with `json`).
/// Fails when the lesson raised or a claim did not hold; Ctrl-C stops it
/// between frames (exit 130, with what it had shown so far).
pub fn run(path: &Path, until: f64, fps: f64, hook_limit: f64, json: bool) -> ExitCode {
    if path.extension().is_none_or(|e| e != "py") {
        crate::errln!("{}: a lesson is a .py file", path.display());
        return ExitCode::from(2);
    }
    if !path.is_file() {
        crate::errln!("{}: no such lesson file", path.display());
        return ExitCode::FAILURE;
    }
    if !(hook_limit.is_finite() && hook_limit > 0.0 && hook_limit <= 86_400.0) {
        crate::errln!("--hook-limit {hook_limit}: give seconds in (0, 86400]");
        return ExitCode::from(2);
    }
    let limit = std::time::Duration::from_secs_f64(hook_limit);
    crate::interrupt::watch();
    let outcome = match headless::run(path, until, fps, limit) {
        Ok(o) => o,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    if let Err(stop) = show(&outcome, json) {
        return stop.exit();
    }
    let failed = outcome.claims.iter().filter(|c| !c.ok).count();
    if crate::interrupt::interrupted() {
        crate::interrupt::exit_code(&format!(
            "{} stopped at t = {:.3} s",
            path.display(),
            outcome.t
        ))
    } else if outcome.error.is_some() {
        crate::errln!("{}: the lesson raised (traceback above)", path.display());
        ExitCode::FAILURE
    } else if failed > 0 {
        crate::errln!(
            "{}: {failed} of {} claims failed",
            path.display(),
            outcome.claims.len()
        );
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Prints the outcome: JSON, or one line per answer and claim.
fn show(outcome: &headless::Outcome, json: bool) -> Result<(), Stop> {
    if json {
        return match serde_json::to_string_pretty(outcome) {
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
