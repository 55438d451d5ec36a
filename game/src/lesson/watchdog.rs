//! Stops a lesson hook that runs too long, whatever it does. A watchdog
//! thread watches the running hook's start time; past the limit it
//! interrupts the hook in three ways, strongest last:
//!
//! 1. **A `TimeoutError` that cannot be swallowed.** The interpreter is
//!    asked (`Py_AddPendingCall`, and the `SIGUSR2` handler the lesson
//!    bootstrap installs) to raise `TimeoutError` in the hook, and from then
//!    on a C trace function raises it again at every line and every call
//!    until the hook returns. A lesson's `except Exception:` or
//!    `except BaseException:` catches the first one, and the next is raised
//!    on the handler's own first line, outside any `try`: the hook unwinds.
//! 2. **Blocking calls are broken.** `SIGUSR2` is sent to the hook's thread
//!    (every 50 ms while the hook is over its limit), so `time.sleep`,
//!    `input()`, a socket read or a thread `join` returns with `EINTR` and
//!    Python runs the handler, which raises.
//! 3. **A hard stop.** A hook still running [`GRACE`] after its limit (a
//!    long C builtin such as `sum(range(10**12))` never returns to Python)
//!    ends the process with exit status [`HARD_STOP_STATUS`] and the reason
//!    on stderr: the game cannot be saved from inside, but it does not hang.
//!    `lightcone lesson` runs each lesson in a child process
//!    ([`super::supervise`]), and so does the window ([`super::remote`]):
//!    the parent reports it and carries on.
//!
//! Signals and pending calls reach only the process's main thread, where
//! the game and `lightcone lesson` run hooks; hooks run on other threads
//! (unit tests) are timed but not interrupted, and never hard-stopped.

use std::ffi::{c_int, c_void};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Mutex, OnceLock};
use std::time::{Duration, Instant};

use pyo3::ffi;
use pyo3::prelude::*;

pub use lightcone_lesson::protocol::HOOK_LIMIT;

/// How long after its limit a hook that did not stop ends the process
/// (the protocol's, as for a browser's worker).
pub const GRACE: Duration = lightcone_lesson::protocol::HOOK_GRACE;

/// Exit status of a process whose hook could not be stopped.
pub const HARD_STOP_STATUS: i32 = 3;

/// Milliseconds (since [`epoch`]) at which the running hook started, plus
/// one; 0 when no hook runs.
static STARTED: AtomicU64 = AtomicU64::new(0);
/// The limit in force, ms.
static LIMIT_MS: AtomicU64 = AtomicU64::new(0);
/// When the watchdog last interrupted the running hook (ms + 1; 0: not yet).
static FIRED: AtomicU64 = AtomicU64::new(0);
/// The running hook was interrupted at least once (kept after it returns,
/// until the next hook starts).
static STOPPED: AtomicBool = AtomicBool::new(false);
/// The trace function is installed.
static TRACING: AtomicBool = AtomicBool::new(false);
/// The running hook runs on the process's main thread.
static ON_MAIN: AtomicBool = AtomicBool::new(false);
/// `pthread_self()` of the thread running the hook.
static THREAD: AtomicU64 = AtomicU64::new(0);
/// The name of the running hook, for messages.
static HOOK: Mutex<&'static str> = Mutex::new("");
/// Told when a hook starts (its name) and ends (`None`).
static OBSERVER: OnceLock<fn(Option<&'static str>)> = OnceLock::new();

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

fn hook_name() -> &'static str {
    *HOOK.lock().unwrap_or_else(|e| e.into_inner())
}

/// What the lesson is told when its hook is stopped.
fn message() -> String {
    format!(
        "the lesson hook {} ran for more than {} s and was stopped (an endless loop, or a call that waits?)",
        hook_name(),
        LIMIT_MS.load(Ordering::SeqCst) as f64 / 1000.0
    )
}

/// Whether the last hook (the running one, or the one that just returned)
/// was interrupted by the watchdog.
pub fn stopped() -> bool {
    STOPPED.load(Ordering::SeqCst)
}

/// Registers `f` to be told when each hook starts and ends (the child
/// process of `lightcone lesson` tells its parent). Once per process.
pub fn observe_hooks(f: fn(Option<&'static str>)) {
    let _ = OBSERVER.set(f);
}

/// The trace function installed once a hook is over its limit: raises
/// `TimeoutError` at every call and every line until the hook returns.
unsafe extern "C" fn trace(
    _obj: *mut ffi::PyObject,
    _frame: *mut ffi::PyFrameObject,
    what: c_int,
    _arg: *mut ffi::PyObject,
) -> c_int {
    if (what == ffi::PyTrace_LINE || what == ffi::PyTrace_CALL) && overdue() {
        set_timeout_error();
        return -1;
    }
    0
}

/// Sets `TimeoutError` as the current exception (GIL held).
fn set_timeout_error() {
    let text = std::ffi::CString::new(message()).unwrap_or_default();
    // SAFETY: called with the GIL held; the interpreter copies the string.
    unsafe { ffi::PyErr_SetString(ffi::PyExc_TimeoutError, text.as_ptr()) }
}

/// Arms the trace function on the current thread (GIL held, on the hook's
/// thread). `PyEval_SetTrace` runs the audit hooks, and a Python one (a
/// lesson's own) can fail it: then the next interrupt tries again.
fn arm() {
    if TRACING.load(Ordering::SeqCst) {
        return;
    }
    // SAFETY: GIL held; `trace` is 'static and ignores its object, which
    // is `True` only to tell that this trace is the one installed.
    let installed = unsafe {
        ffi::PyEval_SetTrace(Some(trace), ffi::Py_True());
        let gettrace = ffi::PySys_GetObject(c"gettrace".as_ptr());
        let current = if gettrace.is_null() {
            std::ptr::null_mut()
        } else {
            ffi::PyObject_CallNoArgs(gettrace)
        };
        let ours = current == ffi::Py_True();
        if current.is_null() {
            ffi::PyErr_Clear();
        } else {
            ffi::Py_DecRef(current);
        }
        ours
    };
    TRACING.store(installed, Ordering::SeqCst);
}

/// Audit events a lesson may not cause: starting processes (a fork of the
/// game copies its window and GPU state; a fork bomb takes the machine).
const NO_PROCESSES: [&std::ffi::CStr; 7] = [
    c"os.fork",
    c"os.forkpty",
    c"os.system",
    c"os.exec",
    c"os.spawn",
    c"os.posix_spawn",
    c"subprocess.Popen",
];

unsafe extern "C" {
    fn PySys_AddAuditHook(
        hook: Option<
            unsafe extern "C" fn(*const std::ffi::c_char, *mut ffi::PyObject, *mut c_void) -> c_int,
        >,
        data: *mut c_void,
    ) -> c_int;
}

/// The audit hook: refuses to start processes or to signal the game's own
/// processes (the lesson's, the game's that runs it, a process group). In C, not Python: a Python hook would run Python code (and the
/// watchdog's pending interrupts) inside `PyEval_SetTrace`.
unsafe extern "C" fn audit(
    event: *const std::ffi::c_char,
    args: *mut ffi::PyObject,
    _data: *mut c_void,
) -> c_int {
    // SAFETY: the interpreter passes a NUL-terminated event name and, for
    // os.kill, a tuple (pid, signal); the GIL is held.
    unsafe {
        let event = std::ffi::CStr::from_ptr(event);
        let refuse = |message: String| {
            let text = std::ffi::CString::new(message).unwrap_or_default();
            ffi::PyErr_SetString(ffi::PyExc_PermissionError, text.as_ptr());
            -1
        };
        if NO_PROCESSES.contains(&event) {
            return refuse(format!(
                "a lesson may not start processes ({})",
                event.to_string_lossy()
            ));
        }
        if event == c"os.kill" && !args.is_null() {
            let pid = ffi::PyTuple_GetItem(args, 0);
            if pid.is_null() {
                ffi::PyErr_Clear();
                return 0;
            }
            let pid = ffi::PyLong_AsLong(pid);
            if pid == -1 && !ffi::PyErr_Occurred().is_null() {
                ffi::PyErr_Clear();
                return 0;
            }
            // Its own process, the game that runs it (its parent) or a
            // whole process group (pid ≤ 0) holding either.
            if pid <= 0
                || pid == libc::getpid() as std::ffi::c_long
                || pid == libc::getppid() as std::ffi::c_long
            {
                return refuse("a lesson may not signal the game's own processes".to_owned());
            }
        }
        if event == c"os.killpg" {
            return refuse("a lesson may not signal a process group".to_owned());
        }
        0
    }
}

/// Installs the audit hook (once; GIL held).
pub fn guard() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // SAFETY: `audit` is 'static and takes no data.
        unsafe {
            PySys_AddAuditHook(Some(audit), std::ptr::null_mut());
        }
    });
}

/// Runs on the interpreter's main thread at the next bytecode boundary.
extern "C" fn pending(_: *mut c_void) -> c_int {
    // The hook may have ended between the request and now: then nothing.
    if !overdue() {
        return 0;
    }
    arm();
    set_timeout_error();
    -1
}

/// The `SIGUSR2` handler (given to `guard` in `bootstrap.py`, which
/// installs it; a Rust function, so the student's traceback shows no frame
/// of ours): raises `TimeoutError` if the
/// running hook is over its limit, and arms the trace.
#[pyfunction]
#[pyo3(name = "_hook_stop", signature = (*_signal))]
pub fn hook_stop(_signal: &Bound<'_, pyo3::types::PyTuple>) -> PyResult<()> {
    if overdue() {
        arm();
        return Err(pyo3::exceptions::PyTimeoutError::new_err(message()));
    }
    Ok(())
}

/// Whether `SIGUSR2` has a handler (Python's): a lesson that set it to
/// `SIG_DFL` would otherwise have the process killed by the signal.
fn sigusr2_handled() -> bool {
    // SAFETY: a zeroed sigaction is a valid out-parameter; a null new
    // action only reads the current one.
    unsafe {
        let mut old: libc::sigaction = std::mem::zeroed();
        libc::sigaction(libc::SIGUSR2, std::ptr::null(), &mut old) == 0
            && old.sa_sigaction != libc::SIG_DFL
            && old.sa_sigaction != libc::SIG_IGN
    }
}

/// Interrupts the overdue hook: a pending call, and `SIGUSR2` to break a
/// blocking call.
fn interrupt() {
    // SAFETY: Py_AddPendingCall may be called from any thread without the
    // GIL; the function pointer is 'static and takes no argument. A full
    // queue only refuses the call.
    unsafe {
        ffi::Py_AddPendingCall(Some(pending), std::ptr::null_mut());
    }
    if ON_MAIN.load(Ordering::SeqCst) && sigusr2_handled() {
        // SAFETY: the thread id was taken by pthread_self on the hook's
        // thread, which is the process's main thread and outlives us.
        unsafe {
            libc::pthread_kill(
                THREAD.load(Ordering::SeqCst) as libc::pthread_t,
                libc::SIGUSR2,
            );
        }
    }
}

/// Ends the process: the hook would not stop.
fn hard_stop() -> ! {
    crate::errln!(
        "{}; it could not be interrupted (a long computation inside one call, such as a C builtin), so the process ends with status {HARD_STOP_STATUS}",
        message()
    );
    // SAFETY: _exit ends the process at once, without running anything that
    // could wait for the thread stuck in the hook.
    unsafe { libc::_exit(HARD_STOP_STATUS) }
}

fn spawn_watchdog() {
    static SPAWN: std::sync::Once = std::sync::Once::new();
    SPAWN.call_once(|| {
        let _ = std::thread::Builder::new()
            .name("lesson watchdog".into())
            .spawn(|| {
                loop {
                    std::thread::sleep(Duration::from_millis(10));
                    if !overdue() {
                        continue;
                    }
                    let now = now_ms();
                    let last = FIRED.load(Ordering::SeqCst);
                    if last == 0 || now + 1 >= last + 50 {
                        FIRED.store(now + 1, Ordering::SeqCst);
                        STOPPED.store(true, Ordering::SeqCst);
                        interrupt();
                    }
                    let started = STARTED.load(Ordering::SeqCst);
                    let limit = LIMIT_MS.load(Ordering::SeqCst);
                    if started != 0
                        && ON_MAIN.load(Ordering::SeqCst)
                        && now + 1 >= started + limit + GRACE.as_millis() as u64
                    {
                        hard_stop();
                    }
                }
            });
    });
}

/// Whether the calling thread is the process's main thread.
fn on_main_thread() -> bool {
    // SAFETY: plain system calls without arguments.
    unsafe { libc::getpid() == libc::gettid() }
}

/// Marks hook `name` as running, with `limit`, until dropped. Create and
/// drop it with the GIL held, on the thread that runs the hook.
pub struct Running(());

impl Running {
    /// Hook `name` starts.
    pub fn start(limit: Duration, name: &'static str) -> Self {
        spawn_watchdog();
        *HOOK.lock().unwrap_or_else(|e| e.into_inner()) = name;
        LIMIT_MS.store(limit.as_millis().max(1) as u64, Ordering::SeqCst);
        FIRED.store(0, Ordering::SeqCst);
        STOPPED.store(false, Ordering::SeqCst);
        ON_MAIN.store(on_main_thread(), Ordering::SeqCst);
        // SAFETY: pthread_self has no preconditions.
        THREAD.store(unsafe { libc::pthread_self() } as u64, Ordering::SeqCst);
        if let Some(f) = OBSERVER.get() {
            f(Some(name));
        }
        STARTED.store(now_ms() + 1, Ordering::SeqCst);
        Self(())
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        STARTED.store(0, Ordering::SeqCst);
        if TRACING.swap(false, Ordering::SeqCst) {
            // SAFETY: the GIL is held (see `Running`), on the thread whose
            // trace was set.
            unsafe { ffi::PyEval_SetTrace(None, std::ptr::null_mut()) }
        }
        if let Some(f) = OBSERVER.get() {
            f(None);
        }
    }
}
