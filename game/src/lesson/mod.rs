//! Lessons: Python scripts run inside the game by an embedded interpreter.
//!
//! A lesson is a `.py` file with hooks:
//!
//! - `setup(world)` (required): build or load a scene and `world.start(scene)`;
//! - `on_frame(world, t)`: after every frame in which board time advanced;
//! - `on_collision(world, event)`: for each collision, with its
//!   `lightcone.records.Collision` (attributes, or keys as in the JSON
//!   `lightcone simulate` prints);
//! - `on_answer(world, question, choice)`: when the student answers a
//!   question asked with `world.ask`.
//!
//! The interpreter is embedded (`append_to_inittab`, then auto-initialised)
//! with the game's own copy of the `lightcone` module, so a lesson always
//! talks to the engine it is shown in, never to a different installed
//! wheel. Two hosts run a lesson: [`LessonHost`], the window's (and
//! `render`/`record`'s), runs it in its own process ([`remote`]) and
//! borrows the front end's game for each request the lesson makes
//! (`lightcone_lesson::WorldCall`); [`LocalLesson`], `lightcone lesson`'s
//! child's, runs it in this process and owns the game in one shared cell
//! that Python's [`World`] is given for each hook. Either way the game has
//! one owner, and a hook acts on exactly what the student sees.
//!
//! A hook that raises does not take the game down: its traceback is shown,
//! the hooks stop, the game keeps the state it had (time pauses), and a
//! reload — of the edited file, without restarting — starts again. A hook
//! that runs past its time limit is stopped whatever it does
//! (`watchdog`); `lightcone lesson` runs each lesson in a child process
//! ([`supervise`]), and so does the window ([`remote`]: the lesson's
//! `World` there is a stand-in whose methods [`LessonHost`] serves on the
//! real game). After `world.finish()` no hook runs again.

pub mod headless;
mod host;
mod isolation;
pub mod lend;
mod line;
mod local;
pub mod remote;
mod sandbox;
mod state;
pub mod supervise;

mod watchdog;

pub use host::LessonHost;
pub use isolation::Isolation;
pub use local::LocalLesson;
pub use state::LessonState;

pub use watchdog::{GRACE, HARD_STOP_STATUS, HOOK_LIMIT};

use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::sync::Once;

use pyo3::prelude::*;
use pyo3::types::PyModule;

use lightcone_lesson::protocol::PRINTED_LINES;
use lightcone_python::World;

/// The `lightcone` package's Python side, installed in the embedded
/// interpreter around the embedded extension module.
const PACKAGE_INIT: &str = include_str!("../../../py/python/lightcone/__init__.py");
/// Its `records` module (the TypedDicts of the records).
const PACKAGE_RECORDS: &str = include_str!("../../../py/python/lightcone/records.py");

/// Python run once when the interpreter starts (`bootstrap.py`, beside this
/// file): installs that package and the panel's copy of `sys.stdout`.
const BOOTSTRAP: &str = include_str!("bootstrap.py");

/// Starts the embedded interpreter once, with `lightcone` importable.
fn init_python() -> Result<(), String> {
    static INIT: Once = Once::new();
    INIT.call_once(|| {
        use lend::lightcone_embedded;
        pyo3::append_to_inittab!(lightcone_embedded);
        Python::initialize();
    });
    Python::attach(|py| -> PyResult<()> {
        if py
            .import("sys")?
            .getattr("modules")?
            .contains("lightcone")?
        {
            return Ok(());
        }
        let bootstrap = embedded_module(
            py,
            BOOTSTRAP,
            c"<lightcone game>/lesson/bootstrap.py",
            c"lightcone_bootstrap",
        )?;
        bootstrap.call_method1("install", (PACKAGE_INIT, PACKAGE_RECORDS))?;
        let stop = pyo3::wrap_pyfunction!(watchdog::hook_stop, py)?;
        bootstrap.call_method1("guard", (stop,))?;
        watchdog::guard();
        Ok(())
    })
    .map_err(|e| format!("cannot start the embedded Python: {e}"))
}

/// A module of the game's own Python (`source`, a `.py` file beside this
/// one, included in the binary), named `name` and shown as `file` in
/// tracebacks.
fn embedded_module<'py>(
    py: Python<'py>,
    source: &str,
    file: &std::ffi::CStr,
    name: &std::ffi::CStr,
) -> PyResult<Bound<'py, PyModule>> {
    let code =
        CString::new(source).map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    PyModule::from_code(py, &code, file, name)
}

/// What lessons printed since the last call, as lines (the embedded
/// `sys.stdout` keeps a copy for the lesson panel).
fn drain_printed(py: Python<'_>) -> Vec<String> {
    let taken = py.import("sys").and_then(|sys| {
        let out = sys.getattr("stdout")?;
        if !out.hasattr("lines")? {
            return Ok(Vec::new());
        }
        let parts: Vec<String> = out.getattr("lines")?.extract()?;
        out.setattr("lines", pyo3::types::PyList::empty(py))?;
        Ok::<_, PyErr>(parts)
    });
    taken
        .unwrap_or_default()
        .concat()
        .lines()
        .map(str::to_owned)
        .collect()
}

/// Errors that ended threads the lesson started, since the last call (the
/// bootstrap's `threading.excepthook` keeps them).
fn take_thread_errors(py: Python<'_>) -> Vec<String> {
    py.import("lightcone_bootstrap")
        .and_then(|b| b.call_method0("take_thread_errors"))
        .and_then(|errors| errors.extract())
        .unwrap_or_default()
}

/// Keeps the newest printed lines on the world's screen.
fn keep_printed(world: &Bound<'_, World>, lines: Vec<String>) {
    if lines.is_empty() {
        return;
    }
    let mut w = world.borrow_mut();
    w.ui.printed.extend(lines);
    let n = w.ui.printed.len();
    if n > PRINTED_LINES {
        w.ui.printed.drain(..n - PRINTED_LINES);
    }
}

/// The traceback of `err` as Python prints it.
fn traceback(py: Python<'_>, err: &PyErr) -> String {
    let formatted = py.import("traceback").and_then(|tb| {
        let lines = tb.call_method1(
            "format_exception",
            (
                err.get_type(py),
                err.value(py),
                err.traceback(py)
                    .map_or_else(|| py.None().into_bound(py), |t| t.into_any()),
            ),
        )?;
        lines.extract::<Vec<String>>()
    });
    match formatted {
        Ok(lines) => lines.concat().trim_end().to_owned(),
        Err(_) => err.to_string(),
    }
}

/// Runs the lesson's file (its `source`, read from `path`) as a new module
/// whose directory `dir` comes first on `sys.path` (so it can import
/// helpers beside it); fails if it has no `setup`.
fn load_module<'py>(
    py: Python<'py>,
    path: &Path,
    source: String,
    dir: &str,
) -> PyResult<Bound<'py, PyModule>> {
    let code = CString::new(source)
        .map_err(|_| pyo3::exceptions::PySyntaxError::new_err("the lesson contains a NUL byte"))?;
    let file = CString::new(path.display().to_string()).unwrap_or_default();
    // A name no other load used: `from_code` would run the code in an
    // existing module of the same name (another host's lesson).
    static LOADED: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = LOADED.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
    let name = CString::new(format!("lightcone_lesson_{n}")).unwrap_or_default();
    let sys_path = py.import("sys")?.getattr("path")?;
    if !sys_path.contains(dir)? {
        sys_path.call_method1("insert", (0, dir))?;
    }
    let module = PyModule::from_code(py, &code, &file, &name)?;
    if !module.hasattr("setup")? {
        return Err(pyo3::exceptions::PyAttributeError::new_err(format!(
            "{}: a lesson needs a function setup(world) that calls world.start(scene)",
            path.display()
        )));
    }
    Ok(module)
}

/// Whether the lesson `source` (named `name`) is Python that compiles:
/// `Err` with the syntax error, located (the lesson's code is not run).
pub fn check_syntax(name: &str, source: &str) -> Result<(), String> {
    init_python()?;
    Python::attach(|py| {
        py.import("builtins")
            .and_then(|b| b.getattr("compile"))
            .and_then(|compile| compile.call1((source, name, "exec")))
            .map(|_| ())
            .map_err(|e| traceback(py, &e))
    })
}

pub use crate::lesson_game::empty_game;

/// The hook limit: [`HOOK_LIMIT`], or the seconds in `LIGHTCONE_HOOK_LIMIT`.
fn limit_from_env() -> Result<std::time::Duration, String> {
    match std::env::var("LIGHTCONE_HOOK_LIMIT") {
        Err(_) => Ok(HOOK_LIMIT),
        Ok(text) => match text.trim().parse::<f64>() {
            Ok(s) if s.is_finite() && s > 0.0 && s <= 86_400.0 => {
                Ok(std::time::Duration::from_secs_f64(s))
            }
            _ => Err(format!(
                "LIGHTCONE_HOOK_LIMIT={text:?}: give seconds in (0, 86400]"
            )),
        },
    }
}

/// The lesson's directory (relative paths in it are taken from there).
fn lesson_dir(path: &Path) -> PathBuf {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .map(Path::to_path_buf)
        .unwrap_or_else(|| PathBuf::from("."))
}

#[cfg(test)]
mod tests;
