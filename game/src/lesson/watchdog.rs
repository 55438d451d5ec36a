//! Stops a lesson hook that runs too long (an endless loop in a teacher's
//! script would otherwise freeze the game). A watchdog thread watches the
//! running hook's start time; past [`HOOK_LIMIT`] it asks the interpreter,
//! through `Py_AddPendingCall`, to raise `TimeoutError` in the hook. The
//! lesson then fails like any lesson that raises: its traceback is shown and
//! the game goes on.
//!
//! Pending calls run on the interpreter's main thread only, which is where
//! the game (and `lightcone lesson`) run hooks; hooks run on other threads
//! (unit tests) are not interrupted.

use std::ffi::{c_int, c_void};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use pyo3::ffi;

/// Longest a single hook may run.
pub const HOOK_LIMIT: Duration = Duration::from_secs(10);

/// Milliseconds (since [`epoch`]) at which the running hook started, plus
/// one; 0 when no hook runs.
static STARTED: AtomicU64 = AtomicU64::new(0);
/// The limit in force, ms.
static LIMIT_MS: AtomicU64 = AtomicU64::new(0);
/// An interrupt was already requested for the running hook.
static FIRED: AtomicBool = AtomicBool::new(false);

fn epoch() -> Instant {
    static EPOCH: OnceLock<Instant> = OnceLock::new();
    *EPOCH.get_or_init(Instant::now)
}

fn now_ms() -> u64 {
    epoch().elapsed().as_millis() as u64
}

/// Whether the running hook has passed its limit.
fn overdue() -> bool {
    let started = STARTED.load(Ordering::SeqCst);
    started != 0 && now_ms() + 1 >= started + LIMIT_MS.load(Ordering::SeqCst)
}

/// Runs on the interpreter's main thread at the next bytecode boundary.
extern "C" fn raise_timeout(_: *mut c_void) -> c_int {
    // The hook may have ended between the request and now: then nothing.
    if !overdue() {
        return 0;
    }
    let message = format!(
        "the lesson hook ran for more than {} s (an endless loop?) and was stopped\0",
        LIMIT_MS.load(Ordering::SeqCst) / 1000
    );
    // SAFETY: called by the interpreter with the GIL held, on its main
    // thread; the message is NUL-terminated and outlives the call (the
    // interpreter copies it into the exception).
    unsafe {
        ffi::PyErr_SetString(ffi::PyExc_TimeoutError, message.as_ptr().cast());
    }
    -1
}

fn spawn_watchdog() {
    static SPAWN: std::sync::Once = std::sync::Once::new();
    SPAWN.call_once(|| {
        let _ = std::thread::Builder::new()
            .name("lesson watchdog".into())
            .spawn(|| {
                loop {
                    std::thread::sleep(Duration::from_millis(50));
                    if overdue() && !FIRED.swap(true, Ordering::SeqCst) {
                        // SAFETY: Py_AddPendingCall may be called from any
                        // thread without the GIL; the function pointer is
                        // 'static and takes no argument.
                        unsafe {
                            ffi::Py_AddPendingCall(Some(raise_timeout), std::ptr::null_mut());
                        }
                        // Added from this thread, the call does not wake the
                        // main thread's eval loop by itself (CPython sets
                        // the eval breaker only for a thread that can run
                        // it); asking for the GIL does.
                        pyo3::Python::attach(|_| {});
                    }
                }
            });
    });
}

/// Marks a hook as running until dropped.
pub struct Running(());

impl Running {
    /// A hook starts, with `limit`.
    pub fn start(limit: Duration) -> Self {
        spawn_watchdog();
        LIMIT_MS.store(limit.as_millis().max(1) as u64, Ordering::SeqCst);
        FIRED.store(false, Ordering::SeqCst);
        STARTED.store(now_ms() + 1, Ordering::SeqCst);
        Self(())
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        STARTED.store(0, Ordering::SeqCst);
    }
}
