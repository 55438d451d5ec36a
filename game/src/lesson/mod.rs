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
//! wheel. The game is shared with the [`World`] for the length of one
//! hook call (a pyclass cannot hold a borrow, so through a shared cell
//! the host takes back after): the hook acts on exactly what the student
//! sees. The window's and the page's hosts share nothing: each request
//! borrows their game (`lightcone_lesson::WorldCall`).
//!
//! A hook that raises does not take the game down: its traceback is shown,
//! the hooks stop, the game keeps the state it had (time pauses), and a
//! reload — of the edited file, without restarting — starts again. A hook
//! that runs past its time limit is stopped whatever it does
//! (`watchdog`); `lightcone lesson` runs each lesson in a child process
//! ([`supervise`]), and so does the window ([`remote`]: the lesson's
//! `World` there is a stand-in whose methods this host serves on the real
//! game). After `world.finish()` no hook runs again.

pub mod headless;
mod isolation;
pub mod lend;
mod line;
pub mod remote;
mod sandbox;
pub mod supervise;

mod watchdog;

pub use isolation::Isolation;

pub use watchdog::{GRACE, HARD_STOP_STATUS, HOOK_LIMIT};

use std::cell::RefCell;
use std::ffi::CString;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Once;
use std::time::SystemTime;

use lightcone_engine::report::CollisionLine;
use pyo3::prelude::*;
use pyo3::types::{PyModule, PyTuple};

use crate::model::GameState;
use lightcone_lesson::protocol::PRINTED_LINES;
use lightcone_python::{LessonUi, World};

/// The game as Python's `World` holds it while a hook runs.
type SharedGame = Rc<RefCell<dyn lightcone_lesson::LessonGame>>;

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

/// One lesson, running or failed.
pub struct LessonHost {
    path: PathBuf,
    /// The lesson's module (its globals), while it loads and runs.
    module: Option<Py<PyModule>>,
    /// Dropped attached to Python, on the host's thread (see `Drop`).
    world: std::mem::ManuallyDrop<Py<World>>,
    /// What the game holds while its real state is lent to the world.
    spare: Option<GameState>,
    /// Collisions already passed to `on_collision`.
    seen_collisions: u64,
    /// The world's generation those collisions belong to.
    generation: u64,
    /// The file's modification time at the last (re)load.
    modified: Option<SystemTime>,
    /// The traceback (or other message) of the failure that stopped the
    /// hooks, shown until a reload works.
    pub error: Option<String>,
    /// The failure in [`Self::error`] is the watchdog's stop (a hook over
    /// its time limit), not the lesson's own raise.
    pub timed_out: bool,
    /// How many times the lesson has been (re)loaded.
    pub loads: u32,
    /// The lesson called `world.finish()`: no hook runs again (until a
    /// reload).
    finished: bool,
    /// Longest a hook may run before it is stopped ([`HOOK_LIMIT`]).
    pub limit: std::time::Duration,
    /// The lesson's own process, when it runs in one (the window).
    remote: Option<remote::Remote>,
    /// How to start that process (`None`: the lesson runs in this one).
    isolation: Option<Isolation>,
    /// The game `setup` is building in the lesson's process.
    pending: Option<GameState>,
    /// A shipped lesson's name, and the private folder holding the copy
    /// of it that runs (removed with the host: the last field, dropped
    /// after the lesson's process ended).
    shipped: Option<(String, sandbox::Scratch)>,
}

pub use crate::lesson_game::empty_game;

impl LessonHost {
    /// Loads the lesson at `path` and runs its `setup`. Returns the host
    /// and the game to show: the lesson's, or — when the lesson fails
    /// before starting a game — `fallback`'s, with the error kept in
    /// [`Self::error`] for the screen. Fails only when Python itself cannot
    /// start.
    ///
    /// The hook time limit is [`HOOK_LIMIT`], or the seconds in the
    /// environment variable `LIGHTCONE_HOOK_LIMIT` (for tests and for
    /// teachers whose hooks compute a lot).
    pub fn load(
        path: &Path,
        fallback: impl FnOnce() -> GameState,
    ) -> Result<(Self, GameState), String> {
        let limit = limit_from_env()?;
        Self::load_with_limit(path, limit, fallback)
    }

    /// [`Self::load`], the lesson running in its own process (the window):
    /// nothing it does ends the game ([`remote`]). Waits for its `setup`
    /// (the window is not open yet).
    pub fn load_isolated(
        path: &Path,
        fallback: impl FnOnce() -> GameState,
        isolation: Isolation,
    ) -> Result<(Self, GameState), String> {
        Self::load_isolated_with_limit(path, limit_from_env()?, fallback, isolation)
    }

    /// Starts the lesson at `path` in its own process while the window
    /// runs (the scene menu), without waiting: its `setup` is served by
    /// the next frames ([`Self::serve`]), and replaces the game when it
    /// ends; meanwhile board time waits ([`Self::busy`]). A setup that
    /// fails leaves the game as it was, paused, with the traceback shown.
    /// Fails when Python cannot start or the hook limit in the
    /// environment is not a number of seconds.
    pub fn open_isolated(path: &Path, isolation: Isolation) -> Result<Self, String> {
        let mut host = Self::new(path, limit_from_env()?)?;
        host.start_remote(&isolation);
        host.isolation = Some(isolation);
        Ok(host)
    }

    /// [`Self::open_isolated`] for a lesson built into the binary
    /// (`crate::assets::LESSONS`: its file `name` and its `text`), run
    /// from a copy in a private temporary folder that lives as long as
    /// the host.
    pub fn open_shipped(name: &str, text: &str, isolation: Isolation) -> Result<Self, String> {
        let folder = sandbox::Scratch::new()?;
        let path = folder.path().join(name);
        std::fs::write(&path, text)
            .map_err(|e| format!("cannot copy the lesson {name} to {}: {e}", path.display()))?;
        let mut host = Self::open_isolated(&path, isolation)?;
        host.shipped = Some((name.to_owned(), folder));
        Ok(host)
    }

    /// The lesson's name for the screen: its file's path, or `(built in)
    /// NAME` for a shipped lesson.
    pub fn name(&self) -> String {
        match &self.shipped {
            Some((name, _)) => format!("(built in) {name}"),
            None => self.path.display().to_string(),
        }
    }

    /// [`Self::load_isolated`] with a hook time limit other than
    /// [`HOOK_LIMIT`].
    pub fn load_isolated_with_limit(
        path: &Path,
        limit: std::time::Duration,
        fallback: impl FnOnce() -> GameState,
        isolation: Isolation,
    ) -> Result<(Self, GameState), String> {
        let mut host = Self::new(path, limit)?;
        host.start_remote(&isolation);
        host.isolation = Some(isolation);
        let mut game = fallback();
        host.settle(&mut game);
        Ok((host, game))
    }

    /// The window's frame, as the lesson in its own process sees it. The
    /// hooks of a frame are sent by [`Self::after_step`], which does not
    /// wait; they run in the lesson's process while the game draws, and
    /// the next frame calls this, before board time moves, to take their
    /// ends (and their requests' answers) within `budget`
    /// ([`remote::FRAME_BUDGET`] at the start of a frame, zero right
    /// after drawing to answer what arrived meanwhile). A hook that is not
    /// done by then goes on over the next frames, board time waiting. A
    /// lesson run in this process needs none of it (a no-op).
    pub fn serve(&mut self, game: &mut GameState, budget: std::time::Duration) {
        if self.isolation.is_some() {
            self.poll(game, budget);
        }
    }

    /// Serves the lesson's process until no hook is out or waiting (each
    /// ends by its limit): for tests and the first load.
    pub fn settle(&mut self, game: &mut GameState) {
        while self.busy() {
            self.poll(game, std::time::Duration::from_millis(50));
        }
    }

    /// A host for the lesson at `path`, nothing loaded yet.
    fn new(path: &Path, limit: std::time::Duration) -> Result<Self, String> {
        init_python()?;
        let world = Python::attach(|py| Py::new(py, World::new(lesson_dir(path))))
            .map_err(|e| format!("cannot start the lesson host: {e}"))?;
        Ok(Self {
            path: path.to_path_buf(),
            module: None,
            world: std::mem::ManuallyDrop::new(world),
            spare: Some(empty_game()),
            seen_collisions: 0,
            generation: 0,
            modified: None,
            error: None,
            timed_out: false,
            loads: 0,
            finished: false,
            limit,
            remote: None,
            isolation: None,
            pending: None,
            shipped: None,
        })
    }

    /// [`Self::load`] with a hook time limit other than [`HOOK_LIMIT`].
    pub fn load_with_limit(
        path: &Path,
        limit: std::time::Duration,
        fallback: impl FnOnce() -> GameState,
    ) -> Result<(Self, GameState), String> {
        let mut host = Self::new(path, limit)?;
        let game = host.start().unwrap_or_else(fallback);
        Ok((host, game))
    }

    /// The lesson file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Reads and runs the file, then `setup(world)`. The new game, or
    /// `None` with [`Self::error`] set.
    fn start(&mut self) -> Option<GameState> {
        self.loads += 1;
        self.modified = modified(&self.path);
        let source = match std::fs::read_to_string(&self.path) {
            Ok(s) => s,
            Err(e) => {
                self.fail(format!(
                    "{}: cannot read the lesson: {e}",
                    self.path.display()
                ));
                return None;
            }
        };
        let result = Python::attach(|py| -> PyResult<Option<GameState>> {
            let dir = self.world.borrow(py).dir.display().to_string();
            // The module's own code and setup are timed like a hook.
            let running = watchdog::Running::start(self.limit, "setup");
            let module = load_module(py, &self.path, source, &dir)?;
            // A fresh world (screen, attributes, no game): setup builds it.
            let dir = self.world.borrow(py).dir.clone();
            *self.world = Py::new(py, World::new(dir))?;
            let world = self.world.bind(py);
            // The game setup builds, shared with the world while it runs.
            let building = Rc::new(RefCell::new(empty_game()));
            world
                .borrow_mut()
                .share(Some(building.clone() as SharedGame));
            let setup = module.call_method1("setup", (world,));
            drop(running);
            world.borrow_mut().share(None);
            keep_printed(world, drain_printed(py));
            setup?;
            let started = world.borrow().started();
            let game = Rc::try_unwrap(building)
                .map(RefCell::into_inner)
                .unwrap_or_else(|shared| shared.replace(empty_game()));
            if !started {
                return Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                    "{}: setup(world) did not call world.start(scene)",
                    self.path.display()
                )));
            }
            self.module = Some(module.unbind());
            Ok(Some(game))
        });
        match result {
            Ok(game) => {
                self.error = None;
                self.timed_out = false;
                let (generation, finished) = Python::attach(|py| {
                    let w = self.world.borrow(py);
                    (w.generation, w.ui.finished.is_some())
                });
                self.generation = generation;
                self.finished = finished;
                self.seen_collisions = 0;
                game
            }
            Err(e) => {
                let text = Python::attach(|py| traceback(py, &e));
                self.module = None;
                self.timed_out = watchdog::stopped();
                self.fail(text);
                None
            }
        }
    }

    /// Stops the hooks and keeps `message` for the screen (and stderr, for
    /// whoever started the game from a terminal).
    fn fail(&mut self, message: String) {
        crate::errln!("lesson {} stopped:\n{message}", self.path.display());
        self.error = Some(message);
    }

    /// Reloads the lesson file (edited or not) and runs `setup` again. On
    /// success the game is replaced by the lesson's new one; on failure the
    /// game is left exactly as it was and the error is shown.
    pub fn reload(&mut self, game: &mut GameState) {
        if let Some(isolation) = self.isolation.clone() {
            // The new process's setup replaces the game when it ends.
            self.start_remote(&isolation);
            self.poll(game, std::time::Duration::ZERO);
            return;
        }
        if let Some(new) = self.start() {
            *game = new;
        } else {
            game.paused = true;
        }
    }

    /// Reloads when the file changed on disk since the last load.
    pub fn reload_if_edited(&mut self, game: &mut GameState) -> bool {
        let now = modified(&self.path);
        if now.is_some() && now != self.modified {
            self.reload(game);
            true
        } else {
            false
        }
    }

    /// Whether hooks run: the lesson loaded, has not failed and has not
    /// called `world.finish()`.
    pub fn running(&self) -> bool {
        (self.module.is_some() || self.remote.is_some()) && self.error.is_none() && !self.finished
    }

    /// Whether the lesson called `world.finish()` (its hooks then stop, in
    /// the window as headless; the game itself goes on).
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// Whether the lesson finished with a closing message that waits for
    /// an event's light (`finish(after_light_from=…)`) still on its way.
    pub fn awaiting_light(&self) -> bool {
        self.finished && self.with_ui(|ui| ui.finish_light.is_some())
    }

    /// Shows the closing message once the light of the event it waits for
    /// has reached the eye looked through now (`game.eye()`: a scene
    /// observer's or the free eye's worldline at the board time shown, so
    /// a moving eye is caught wherever it flew). Call it after each step;
    /// returns whether the message is shown now (or never waited).
    pub fn watch_light(&mut self, game: &GameState) -> bool {
        if !self.finished {
            return false;
        }
        let eye = game.eye().event;
        let c = game.scene.c;
        Python::attach(|py| self.world.borrow_mut(py).ui.light_arrived(eye, c))
    }

    /// Calls `hook(world, *args)` if the lesson defines it, with the game
    /// lent to the world. A raise stops the hooks and pauses the game.
    fn call<F>(&mut self, game: &mut GameState, hook: &'static str, args: F)
    where
        F: for<'py> FnOnce(Python<'py>, &Bound<'py, World>) -> PyResult<Bound<'py, PyTuple>>,
    {
        if !self.running() {
            return;
        }
        let Some(spare) = self.spare.take() else {
            return;
        };
        // Python's World reaches the game through a shared cell for the
        // hook's length (a pyclass cannot hold a borrow); the host's own
        // handle takes it back after.
        let lent = Rc::new(RefCell::new(std::mem::replace(game, spare)));
        let limit = self.limit;
        let result = Python::attach(|py| {
            let world = self.world.bind(py);
            world.borrow_mut().share(Some(lent.clone() as SharedGame));
            let result = {
                // Only the hook itself is timed.
                let _running = watchdog::Running::start(limit, hook);
                match &self.module {
                    Some(m) => {
                        let m = m.bind(py);
                        match m.getattr(hook) {
                            Ok(f) => args(py, world).and_then(|a| f.call1(a).map(|_| ())),
                            Err(_) => Ok(()),
                        }
                    }
                    None => Ok(()),
                }
            };
            world.borrow_mut().share(None);
            keep_printed(world, drain_printed(py));
            let generation = world.borrow().generation;
            let finished = world.borrow().ui.finished.is_some();
            (
                generation,
                finished,
                result
                    .map_err(|e| format!("in {hook}:\n{}", traceback(py, &e)))
                    .and_then(|()| match take_thread_errors(py).into_iter().next() {
                        Some(error) => Err(error),
                        None => Ok(()),
                    }),
            )
        });
        let (generation, finished, outcome) = result;
        self.finished = finished;
        // The world let go of its handle: the host's is the only one
        // (`world.start` restarted the game in place, if it was called).
        let back = Rc::try_unwrap(lent)
            .map(RefCell::into_inner)
            .unwrap_or_else(|shared| shared.replace(empty_game()));
        self.spare = Some(std::mem::replace(game, back));
        if generation != self.generation {
            self.generation = generation;
            self.seen_collisions = 0;
        }
        if let Err(e) = outcome {
            game.paused = true;
            self.timed_out = watchdog::stopped();
            self.fail(e);
        }
    }

    /// Runs the hooks due after a frame: `on_collision` for each new
    /// collision, then `on_frame` if board time advanced since `before`.
    /// A lesson in its own process is sent the first of them, and this
    /// returns without waiting ([`Self::serve`] takes their ends).
    pub fn after_step(&mut self, game: &mut GameState, before: f64) {
        // `seen_collisions` is a global record index (the billiard may have
        // dropped records older than its replay window).
        let n = game.physics().collision_count();
        if n < self.seen_collisions {
            // The game restarted under the lesson (the c slider).
            self.seen_collisions = 0;
        }
        while self.running() && self.seen_collisions < game.physics().collision_count() {
            let i = self.seen_collisions;
            self.seen_collisions += 1;
            if game.physics().collisions_forgotten() > i {
                continue; // dropped before it was seen
            }
            let Some(record) = game.physics().collisions_from(i).first() else {
                continue;
            };
            let line = CollisionLine::new(game.physics(), record);
            if self.isolation.is_some() {
                let Ok(data) = serde_json::to_value(&line) else {
                    continue;
                };
                let event = serde_json::json!([{"$record": "Collision", "data": data}]);
                self.queue_remote("on_collision", event);
                continue;
            }
            let text = match serde_json::to_string(&line) {
                Ok(t) => t,
                Err(_) => continue,
            };
            self.call(game, "on_collision", move |py, world| {
                let data = py.import("json")?.call_method1("loads", (text,))?;
                let event = py
                    .import("lightcone.records")?
                    .getattr("Collision")?
                    .call1((data,))?;
                PyTuple::new(py, [world.clone().into_any(), event])
            });
        }
        if self.isolation.is_some() {
            if game.live_time > before {
                self.queue_remote("on_frame", serde_json::json!([game.live_time]));
            }
            self.poll(game, std::time::Duration::ZERO);
            return;
        }
        if game.live_time > before {
            let t = game.live_time;
            self.call(game, "on_frame", move |py, world| {
                PyTuple::new(
                    py,
                    [world.clone().into_any(), t.into_pyobject(py)?.into_any()],
                )
            });
        }
    }

    /// The student chose `choice` for the open question: record it, resume
    /// time if the question paused it, and run `on_answer`.
    pub fn answer(&mut self, game: &mut GameState, choice: usize) {
        let asked = Python::attach(|py| self.world.borrow_mut(py).ui.choose(choice));
        let Some((question, chosen, resume)) = asked else {
            return;
        };
        if resume {
            game.paused = false;
        }
        if self.isolation.is_some() {
            self.queue_remote("on_answer", serde_json::json!([question, chosen]));
            self.poll(game, std::time::Duration::ZERO);
            return;
        }
        self.call(game, "on_answer", move |py, world| {
            PyTuple::new(
                py,
                [
                    world.clone().into_any(),
                    question.into_pyobject(py)?.into_any(),
                    chosen.into_pyobject(py)?.into_any(),
                ],
            )
        });
    }
}

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

impl Drop for LessonHost {
    /// Releases the world here, attached: the world is unsendable, and a
    /// release left for whichever thread next attaches is refused (with an
    /// error printed) and leaks it.
    fn drop(&mut self) {
        // SAFETY: `world` is not used after this; the field is never
        // dropped otherwise (`ManuallyDrop`).
        Python::attach(|_| unsafe { std::mem::ManuallyDrop::drop(&mut self.world) });
    }
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

impl LessonHost {
    /// Looks at the lesson's screen without copying it.
    pub fn with_ui<R>(&self, f: impl FnOnce(&LessonUi) -> R) -> R {
        Python::attach(|py| f(&self.world.borrow(py).ui))
    }
}

#[cfg(test)]
mod tests;
