//! Ctrl-C (SIGINT): long commands stop promptly with exit 130.
//!
//! [`install`] is called once, first thing in `main`. Until a command says
//! it [`watch`]es the flag, Ctrl-C ends the process at once with exit 130
//! (as before: nothing was lost that a loop could have saved). A command
//! whose loop polls [`interrupted`] calls [`watch`] first: Ctrl-C then only
//! sets the flag, and the loop stops, writes what it has, and returns
//! [`EXIT_INTERRUPTED`]. A second Ctrl-C always ends the process at once.
//! A loop that may spend long inside one call it cannot poll from (the
//! engine's step, deep in a braking cluster) calls [`watch_within`]
//! instead: if it has not stopped `grace` after Ctrl-C, the process ends
//! with exit 130 anyway, keeping what it has written and flushed.

use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::time::Duration;

/// Exit status of a command stopped by Ctrl-C (128 + SIGINT).
pub const EXIT_INTERRUPTED: u8 = 130;

static INTERRUPTED: AtomicBool = AtomicBool::new(false);
static WATCHED: AtomicBool = AtomicBool::new(false);
static PRESSES: AtomicU32 = AtomicU32::new(0);
/// [`watch_within`]'s grace, ms (0: none, the loop always stops itself).
static GRACE_MS: AtomicU64 = AtomicU64::new(0);

/// Installs the handler. Failure (another handler is installed) leaves the
/// default: Ctrl-C ends the process.
pub fn install() {
    let _ = ctrlc::set_handler(|| {
        let presses = PRESSES.fetch_add(1, Ordering::SeqCst) + 1;
        INTERRUPTED.store(true, Ordering::SeqCst);
        if !WATCHED.load(Ordering::SeqCst) || presses > 1 {
            crate::output::eprint_quiet("interrupted\n");
            std::process::exit(i32::from(EXIT_INTERRUPTED));
        }
        let grace = GRACE_MS.load(Ordering::SeqCst);
        if presses == 1 && grace > 0 {
            std::thread::spawn(move || {
                std::thread::sleep(Duration::from_millis(grace));
                crate::output::eprint_quiet(&format!(
                    "interrupted: still inside one long step {:.1} s after Ctrl-C, so stopped \
                     there; what was written before is kept\n",
                    grace as f64 / 1000.0
                ));
                std::process::exit(i32::from(EXIT_INTERRUPTED));
            });
        }
    });
}

/// As [`watch`], for a loop that may be inside one long call when Ctrl-C
/// comes: the process ends with exit 130 `grace` later if the loop has not
/// returned by then (its output is to be flushed as it goes).
pub fn watch_within(grace: Duration) {
    GRACE_MS.store(
        u64::try_from(grace.as_millis()).unwrap_or(u64::MAX).max(1),
        Ordering::SeqCst,
    );
    watch();
}

/// Says that the caller polls [`interrupted`] and stops by itself.
pub fn watch() {
    WATCHED.store(true, Ordering::SeqCst);
}

/// Whether Ctrl-C was pressed since the start.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// Exit code 130, after saying so on stderr.
pub fn exit_code(what: &str) -> ExitCode {
    crate::output::eprint_quiet(&format!("interrupted: {what}\n"));
    ExitCode::from(EXIT_INTERRUPTED)
}
