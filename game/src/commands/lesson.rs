//! `lightcone lesson FILE.py`: run a lesson headless and report its claims.

use std::path::Path;
use std::process::ExitCode;

use crate::lesson::headless;

/// Runs the lesson; prints each claim (or the JSON outcome with `json`).
/// Fails when the lesson raised or a claim did not hold.
pub fn run(path: &Path, until: f64, fps: f64, hook_limit: f64, json: bool) -> ExitCode {
    if !path.is_file() {
        eprintln!("{}: no such lesson file", path.display());
        return ExitCode::FAILURE;
    }
    if !(hook_limit.is_finite() && hook_limit > 0.0 && hook_limit <= 86_400.0) {
        eprintln!("--hook-limit {hook_limit}: give seconds in (0, 86400]");
        return ExitCode::FAILURE;
    }
    let limit = std::time::Duration::from_secs_f64(hook_limit);
    let outcome = match headless::run(path, until, fps, limit) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    if json {
        match serde_json::to_string_pretty(&outcome) {
            Ok(text) => println!("{text}"),
            Err(e) => eprintln!("cannot write the outcome: {e}"),
        }
    } else {
        for (q, a) in &outcome.answers {
            println!("? {q} -> {a}");
        }
        for c in &outcome.claims {
            let mark = if c.ok { "ok  " } else { "FAIL" };
            println!("{mark} {}: {}", c.claim, c.detail);
        }
        match (&outcome.error, &outcome.finished) {
            (Some(_), _) => {} // already on stderr
            (None, Some(msg)) => println!("finished at t = {:.3} s: {msg}", outcome.t),
            (None, None) => println!("stopped at t = {:.3} s without finish()", outcome.t),
        }
    }
    let failed = outcome.claims.iter().filter(|c| !c.ok).count();
    if outcome.error.is_some() {
        eprintln!("{}: the lesson raised (traceback above)", path.display());
        ExitCode::FAILURE
    } else if failed > 0 {
        eprintln!(
            "{}: {failed} of {} claims failed",
            path.display(),
            outcome.claims.len()
        );
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
