//! The window runs a lesson in its own process (`lightcone lesson FILE
//! --window-child`, the same binary), so that nothing the lesson does — a
//! crash through `ctypes`, a memory bomb, a C call that never returns —
//! ends the game (docs/window_lesson_isolation.md).
//!
//! The game stays in the window's process. The lesson's process holds a
//! `World` stand-in (`remote.py`) whose methods are requests to the
//! game's process, answered on the real game by the world's own
//! operations (`lightcone_lesson::protocol::reply_line` on a `WorldCall`
//! of the host's world that borrows the game for one request: the same
//! operations Python's `lightcone.World` wraps, and the browser's page
//! answers its worker with). Both ways, JSON lines:
//!
//! - game → lesson: a call (`{"call": hook, "args": [...], "snapshot": {...}}`)
//!   and the answer to each request (`{"ok": value}` or
//!   `{"error": [kind, message]}`, with a fresh snapshot). The snapshot
//!   (t, c, paused, time_scale, view, observer, effects) answers the
//!   common getters without a round trip;
//! - lesson → game: `Up`, a request or the end of the hook.
//!
//! The game reads the lesson's lines on a thread into a channel and writes
//! its own on another, so the frame loop never blocks on the lesson. The
//! frame is pipelined: a frame's hooks are sent after its step and run
//! while it is drawn; the next frame takes their ends, waiting at most
//! [`FRAME_BUDGET`] (`LessonHost::serve`); while a hook is out, board time
//! waits (the window keeps drawing). Nothing the lesson
//! sends is trusted: a line over `protocol::MAX_LINE` bytes, a message that is not
//! an `Up`, a request for something the game does not serve, or a
//! message when no call is out ends the lesson's process, with the reason.
//!
//! Limits: the lesson's process runs its hooks under its own watchdog
//! (`super::watchdog`: `TimeoutError` at the limit, so the teacher gets
//! a traceback at the right line); the game kills its process group at
//! limit + [`KILL_AFTER`]. A process that ends (a signal, an exit status,
//! memory beyond its `RLIMIT_AS`) is reported with
//! `supervise::how_it_ended`'s words. Either way the game keeps its
//! state, paused, hooks stop, and a reload starts a new process.

use std::collections::VecDeque;
use std::io::{BufReader, Write};
use std::path::Path;
use std::process::Child;
use std::sync::Mutex;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use pyo3::prelude::*;
use pyo3::types::PyModule;
use serde_json::Value;

use super::isolation::Isolation;
use super::line::read_line;
use super::supervise::{self, KILL_AFTER};
use super::{LessonHost, drain_printed, keep_printed, traceback, watchdog};
use crate::lesson_game::empty_game;
use crate::model::GameState;
use lightcone_lesson::protocol::{self, Up};
use lightcone_lesson::{LessonGame, WorldCall};

/// How long a frame waits for the lesson before it draws: a hook that
/// takes longer goes on over the next frames while board time waits.
pub const FRAME_BUDGET: Duration = Duration::from_millis(10);

/// How many messages a poll handles past its budget (those already
/// arrived): a hook's requests and its end, without waiting.
const READY_AT_ONCE: usize = 16;

/// The hooks, by the names a call carries.
const HOOKS: [&str; 4] = ["setup", "on_frame", "on_collision", "on_answer"];

/// The Python of both sides (`remote.py`, beside this file).
const REMOTE_PY: &str = include_str!("remote.py");

/// `remote.py` as a module, loaded once per interpreter (whole before any
/// thread sees it).
fn module(py: Python<'_>) -> PyResult<Bound<'_, PyModule>> {
    static MODULE: pyo3::sync::PyOnceLock<Py<PyModule>> = pyo3::sync::PyOnceLock::new();
    let m = MODULE.get_or_try_init(py, || -> PyResult<Py<PyModule>> {
        let m = super::embedded_module(
            py,
            REMOTE_PY,
            c"<lightcone game>/lesson/remote.py",
            c"lightcone_remote",
        )?;
        Ok(m.unbind())
    })?;
    Ok(m.bind(py).clone())
}

// ---- The lesson's process.

/// Where the lesson's process writes (its original standard output).
static UP: Mutex<Option<std::fs::File>> = Mutex::new(None);
/// Where it reads its calls and answers (its original standard input).
static DOWN: Mutex<Option<BufReader<std::fs::File>>> = Mutex::new(None);

fn send_up(line: &[u8]) {
    let mut guard = UP.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(out) = guard.as_mut() {
        let mut all = Vec::with_capacity(line.len() + 1);
        all.extend_from_slice(line);
        all.push(b'\n');
        if out.write_all(&all).is_err() {
            std::process::exit(0); // the game is gone
        }
    }
}

/// The next line from the game, or `None` when the game closed the pipe.
fn read_down() -> Option<String> {
    let mut guard = DOWN.lock().unwrap_or_else(|e| e.into_inner());
    let reader = guard.as_mut()?;
    let line = read_line(reader).ok()??;
    String::from_utf8(line).ok()
}

/// The lesson's `World` asks the game: sends `line`, waits for the answer.
#[pyfunction]
#[pyo3(name = "_request")]
fn request(py: Python<'_>, line: &str) -> String {
    send_up(line.as_bytes());
    match py.detach(read_down) {
        Some(answer) => answer,
        // The game is gone: nothing is left to teach.
        None => std::process::exit(0),
    }
}

/// The lesson's side (`lightcone lesson FILE --window-child`): runs the
/// calls the game sends until the game closes the pipe. Returns the exit
/// status.
pub fn child(path: &Path, limit: Duration, memory_mb: u64) -> u8 {
    let up = match supervise::child_process(memory_mb) {
        Ok(f) => f,
        Err(e) => {
            crate::errln!("{e}");
            return 1;
        }
    };
    // The calls come on standard input; the lesson gets a pipe nobody
    // writes to instead (`input()` waits, as in a terminal).
    // SAFETY: plain system calls on this process's own descriptors; the
    // pipe's write end stays open (unused) for the life of the process.
    let down = unsafe {
        let fd = libc::dup(0);
        let mut pipe = [0; 2];
        if fd < 0 || libc::pipe(pipe.as_mut_ptr()) != 0 || libc::dup2(pipe[0], 0) < 0 {
            crate::errln!("cannot set up the lesson's process");
            return 1;
        }
        <std::fs::File as std::os::fd::FromRawFd>::from_raw_fd(fd)
    };
    *UP.lock().unwrap_or_else(|e| e.into_inner()) = Some(up);
    *DOWN.lock().unwrap_or_else(|e| e.into_inner()) = Some(BufReader::new(down));
    if let Err(e) = super::init_python() {
        crate::errln!("{e}");
        return 1;
    }
    let dir = super::lesson_dir(path);
    // Before the lesson's code runs (`begin` loads it): the interpreter
    // has started.
    if let Err(e) = supervise::sandboxed(path) {
        crate::errln!("{e}");
        return 1;
    }
    let world = Python::attach(|py| -> PyResult<Py<PyAny>> {
        let f = pyo3::wrap_pyfunction!(request, py)?;
        let w = module(py)?
            .getattr("World")?
            .call1((f, dir.display().to_string()))?;
        Ok(w.unbind())
    });
    let world = match world {
        Ok(w) => w,
        Err(e) => {
            crate::errln!("cannot start the lesson's world: {e}");
            return 1;
        }
    };
    let mut lesson: Option<Py<PyModule>> = None;
    // Waiting for the next call, the interpreter is free: threads the
    // lesson started run then (and an error that ends one is reported
    // after the next hook), instead of only while a hook waits.
    while let Some(line) = Python::attach(|py| py.detach(read_down)) {
        let done =
            Python::attach(|py| run_call(py, &line, world.bind(py), path, limit, &mut lesson));
        match serde_json::to_vec(&done) {
            Ok(bytes) => send_up(&bytes),
            Err(_) => return 1,
        }
    }
    0
}

/// Runs the call in `line` on the lesson; what to tell the game.
fn run_call(
    py: Python<'_>,
    line: &str,
    world: &Bound<'_, PyAny>,
    path: &Path,
    limit: Duration,
    lesson: &mut Option<Py<PyModule>>,
) -> Up {
    let done = |error: Option<String>, timed_out: bool, hooks: Vec<String>| Up::Done {
        error,
        timed_out,
        printed: protocol::printed_tail(drain_printed(py)),
        hooks,
    };
    let begun = module(py)
        .and_then(|m| m.call_method1("begin", (world, line)))
        .and_then(|r| r.extract::<(String, Bound<'_, pyo3::types::PyTuple>)>());
    let (name, args) = match begun {
        Ok(x) => x,
        Err(e) => {
            return done(
                Some(format!("a call the lesson cannot read: {e}")),
                false,
                vec![],
            );
        }
    };
    let Some(hook) = HOOKS.iter().copied().find(|h| *h == name) else {
        return done(Some(format!("no such hook {name:?}")), false, vec![]);
    };
    let result = {
        let _running = watchdog::Running::start(limit, hook);
        if hook == "setup" {
            std::fs::read_to_string(path)
                .map_err(|e| {
                    pyo3::exceptions::PyOSError::new_err(format!(
                        "{}: cannot read the lesson: {e}",
                        path.display()
                    ))
                })
                .and_then(|source| {
                    let dir = super::lesson_dir(path).display().to_string();
                    super::load_module(py, path, source, &dir)
                })
                .and_then(|m| {
                    *lesson = Some(m.clone().unbind());
                    m.call_method1("setup", args).map(|_| ())
                })
        } else {
            match lesson.as_ref().map(|m| m.bind(py).getattr(hook)) {
                Some(Ok(f)) => f.call1(args).map(|_| ()),
                _ => Ok(()),
            }
        }
    };
    let timed_out = watchdog::stopped();
    let hooks = match (hook, lesson.as_ref()) {
        ("setup", Some(m)) => HOOKS[1..]
            .iter()
            .filter(|h| m.bind(py).hasattr(**h).unwrap_or(false))
            .map(|h| (*h).to_owned())
            .collect(),
        _ => vec![],
    };
    let error = result.err().map(|e| {
        let tb = traceback(py, &e);
        if hook == "setup" {
            tb
        } else {
            format!("in {hook}:\n{tb}")
        }
    });
    // Else a thread the lesson started may have failed since the last call.
    let error = error.or_else(|| super::take_thread_errors(py).into_iter().next());
    done(error, timed_out, hooks)
}

// ---- The game's side.

/// What the reader thread passes on.
enum FromChild {
    Line(Up),
    /// A line the game does not accept, and why.
    Bad(String),
    /// The lesson's process closed its output (it ended).
    Closed,
}

/// The lesson's process, seen from the game.
pub(crate) struct Remote {
    child: Child,
    /// Its standard input, non-blocking: a short line goes straight in.
    stdin: std::sync::Arc<std::process::ChildStdin>,
    /// Lines that did not fit at once, for a thread to write (so a lesson
    /// that does not read never blocks the game), and how many are there.
    backlog: mpsc::Sender<Vec<u8>>,
    queued: std::sync::Arc<std::sync::atomic::AtomicUsize>,
    up: mpsc::Receiver<FromChild>,
    /// The call out: its hook and when it was sent.
    out: Option<(&'static str, Instant)>,
    /// Calls waiting for the one out to end.
    queue: VecDeque<(&'static str, Value)>,
    /// The hooks the lesson defines (known after `setup`).
    hooks: Vec<String>,
    memory_mb: u64,
    /// Its temporary folder, removed after it (the last field: dropped
    /// after `Drop` ended the process).
    _scratch: super::sandbox::Scratch,
}

impl Remote {
    fn spawn(path: &Path, limit: Duration, isolation: &Isolation) -> Result<Self, String> {
        let args: Vec<std::ffi::OsString> = vec![
            "lesson".into(),
            "--hook-limit".into(),
            limit.as_secs_f64().to_string().into(),
            "--memory-limit".into(),
            isolation.memory_mb.to_string().into(),
            "--window-child".into(),
            // The file last, after `--`: a name that starts with `-`.
            "--".into(),
            path.as_os_str().to_owned(),
        ];
        let (mut child, scratch) = supervise::spawn(&isolation.exe, &args)?;
        let (Some(stdin), Some(stdout)) = (child.stdin.take(), child.stdout.take()) else {
            supervise::kill_group(child.id());
            let _ = child.wait();
            return Err("cannot talk to the lesson's process".to_owned());
        };
        // SAFETY: sets a flag on our own end of the pipe.
        unsafe {
            use std::os::fd::AsRawFd;
            let fd = stdin.as_raw_fd();
            libc::fcntl(
                fd,
                libc::F_SETFL,
                libc::fcntl(fd, libc::F_GETFL) | libc::O_NONBLOCK,
            );
        }
        let stdin = std::sync::Arc::new(stdin);
        let queued = std::sync::Arc::new(std::sync::atomic::AtomicUsize::new(0));
        let (backlog, to_write) = mpsc::channel::<Vec<u8>>();
        let (pipe, count) = (stdin.clone(), queued.clone());
        std::thread::spawn(move || {
            for line in to_write {
                if write_all_waiting(&pipe, &line).is_err() {
                    break; // the lesson's process is gone
                }
                count.fetch_sub(1, std::sync::atomic::Ordering::SeqCst);
            }
        });
        // Bounded: a lesson that floods the pipe waits for the game (its
        // lines do not pile up in the game's memory).
        let (tx, up) = mpsc::sync_channel(4);
        // What it prints goes to the game's stderr, bounded: past the
        // bound the game stops it.
        if let Some(printed) = child.stderr.take() {
            let tx = tx.clone();
            supervise::forward_printed(printed, move |why| {
                let _ = tx.send(FromChild::Bad(why));
            });
        }
        std::thread::spawn(move || {
            let mut reader = BufReader::new(stdout);
            loop {
                let msg = match read_line(&mut reader) {
                    Ok(None) => FromChild::Closed,
                    Err(e) => FromChild::Bad(e),
                    Ok(Some(line)) => match serde_json::from_slice::<Up>(&line) {
                        Ok(up) => FromChild::Line(up),
                        Err(e) => FromChild::Bad(format!(
                            "it sent a message the game does not understand ({e})"
                        )),
                    },
                };
                let last = !matches!(msg, FromChild::Line(_));
                if tx.send(msg).is_err() || last {
                    break;
                }
            }
        });
        Ok(Self {
            child,
            stdin,
            backlog,
            queued,
            up,
            out: None,
            queue: VecDeque::new(),
            hooks: Vec::new(),
            memory_mb: isolation.memory_mb,
            _scratch: scratch,
        })
    }

    /// Sends `line`: straight into the pipe when it fits at once (a
    /// write of at most `PIPE_BUF` bytes is whole or nothing) and no
    /// earlier line waits; else through the writer thread.
    fn send(&self, mut line: Vec<u8>) {
        use std::sync::atomic::Ordering;
        line.push(b'\n');
        if self.queued.load(Ordering::SeqCst) == 0 && line.len() <= libc::PIPE_BUF {
            match (&*self.stdin).write(&line) {
                Ok(n) if n == line.len() => return,
                Err(e) if e.kind() != std::io::ErrorKind::WouldBlock => return, // gone
                _ => {}
            }
        }
        self.queued.fetch_add(1, Ordering::SeqCst);
        let _ = self.backlog.send(line);
    }

    /// Kills the process group and waits for it, giving a process that is
    /// ending by itself `grace` to do so (so its own exit status is read).
    fn end(&mut self, grace: Duration) -> Option<std::process::ExitStatus> {
        let until = Instant::now() + grace;
        while Instant::now() < until {
            if let Ok(Some(status)) = self.child.try_wait() {
                supervise::kill_group(self.child.id());
                return Some(status);
            }
            std::thread::sleep(Duration::from_millis(5));
        }
        supervise::kill_group(self.child.id());
        self.child.wait().ok()
    }
}

/// Writes all of `line` to the non-blocking `pipe`, waiting for room.
fn write_all_waiting(pipe: &std::process::ChildStdin, mut line: &[u8]) -> std::io::Result<()> {
    use std::os::fd::AsRawFd;
    while !line.is_empty() {
        match (&*pipe).write(line) {
            Ok(0) => return Err(std::io::ErrorKind::WriteZero.into()),
            Ok(n) => line = &line[n..],
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                let mut fd = libc::pollfd {
                    fd: pipe.as_raw_fd(),
                    events: libc::POLLOUT,
                    revents: 0,
                };
                // SAFETY: one valid pollfd for the call's length.
                unsafe { libc::poll(&mut fd, 1, -1) };
            }
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(())
}

impl Drop for Remote {
    fn drop(&mut self) {
        if matches!(self.child.try_wait(), Ok(None)) {
            supervise::kill_group(self.child.id());
        }
        let _ = self.child.wait();
    }
}

impl LessonHost {
    /// Starts a new process for the lesson and queues its `setup` (the
    /// window's load and reload).
    pub(super) fn start_remote(&mut self) {
        self.begin_load();
        self.finished = false; // a fresh world, below
        self.remote = None; // ends the old process
        self.pending = None;
        if let Err(e) = Python::attach(|py| self.fresh_world(py)) {
            return self.fail(format!("cannot start the lesson host: {e}"));
        }
        match Remote::spawn(&self.path, self.limit, &self.isolation) {
            Ok(mut r) => {
                r.queue.push_back(("setup", Value::Array(vec![])));
                self.remote = Some(r);
            }
            Err(e) => self.fail(e),
        }
    }

    /// Whether a hook is out in the lesson's process (or waiting to be):
    /// board time waits meanwhile.
    pub fn busy(&self) -> bool {
        self.remote
            .as_ref()
            .is_some_and(|r| r.out.is_some() || !r.queue.is_empty())
    }

    /// The hook out in the lesson's process and how long it has run.
    pub fn hook_running(&self) -> Option<(&'static str, Duration)> {
        let (hook, since) = self.remote.as_ref()?.out?;
        Some((hook, since.elapsed()))
    }

    /// Queues `hook(world, *args)` if the lesson defines it.
    pub(super) fn queue_remote(&mut self, hook: &'static str, args: Value) {
        if !self.running() {
            return;
        }
        if let Some(r) = &mut self.remote
            && r.hooks.iter().any(|h| h == hook)
        {
            r.queue.push_back((hook, args));
        }
    }

    /// Runs `f` on the world for one request, borrowing the game: the
    /// student's, or in `setup` the game the lesson is building (shown
    /// once setup has ended well).
    fn on_world<R>(
        &mut self,
        game: &mut GameState,
        setup: bool,
        f: impl FnOnce(&mut WorldCall<'_>) -> R,
    ) -> R {
        let target = if setup {
            self.pending.get_or_insert_with(empty_game)
        } else {
            game
        };
        let (result, generation) = Python::attach(|py| {
            let mut world = self.state.world.borrow_mut(py);
            let result = f(&mut world.on(Some(target)));
            (result, world.generation)
        });
        if !setup && generation != self.generation {
            // world.start in a hook: the collision list restarted.
            self.generation = generation;
            self.seen_collisions = 0;
        }
        result
    }

    /// Serves the lesson's process for at most `budget`: sends the next
    /// queued call, answers its requests on `game`, takes the end of its
    /// hook, and stops it at its limit or when it misbehaves. With a zero
    /// budget it never waits: it handles what has already arrived (at
    /// most [`READY_AT_ONCE`] messages) and sends the next call.
    pub(super) fn poll(&mut self, game: &mut GameState, budget: Duration) {
        let deadline = Instant::now() + budget;
        let mut handled = 0;
        loop {
            let Some(remote) = self.remote.as_mut() else {
                return;
            };
            let (hook, since) = match remote.out {
                Some(out) => out,
                None => {
                    // Nothing comes unasked: a line now is a breach.
                    match remote.up.try_recv() {
                        Ok(FromChild::Line(_)) => {
                            let why = "it sent a message while no call was out".to_owned();
                            return self.stop(game, Some(why), false);
                        }
                        Ok(FromChild::Bad(reason)) => return self.stop(game, Some(reason), false),
                        Ok(FromChild::Closed) | Err(mpsc::TryRecvError::Disconnected) => {
                            return self.stop(game, None, false);
                        }
                        Err(mpsc::TryRecvError::Empty) => {}
                    }
                    let Some((hook, args)) = remote.queue.pop_front() else {
                        return;
                    };
                    if hook != "setup" && (self.state.error.is_some() || self.state.finished) {
                        remote.queue.clear();
                        return;
                    }
                    // Built from the game itself, without Python (no game
                    // yet in `setup`).
                    let shown = (hook != "setup").then_some(&*game as &dyn LessonGame);
                    let line = protocol::call_line(shown, hook, &args);
                    let Some(remote) = self.remote.as_mut() else {
                        return;
                    };
                    remote.send(line.into_bytes());
                    let out = (hook, Instant::now());
                    remote.out = Some(out);
                    out
                }
            };
            let kill_at = since + self.limit + KILL_AFTER;
            let now = Instant::now();
            let wait = deadline.min(kill_at).saturating_duration_since(now);
            let Some(remote) = self.remote.as_mut() else {
                return;
            };
            let received = remote.up.recv_timeout(wait);
            if received.is_ok() {
                handled += 1;
            }
            match received {
                Ok(FromChild::Line(Up::Request { op, args, kwargs })) => {
                    if !protocol::serves(&op) {
                        return self.stop(
                            game,
                            Some(format!(
                                "it asked the game for {op:?}, which the game does not serve"
                            )),
                            false,
                        );
                    }
                    let reply = self.on_world(game, hook == "setup", |world| {
                        protocol::reply_line(world, &op, &args, &kwargs)
                    });
                    if let Some(r) = &self.remote {
                        r.send(reply.into_bytes());
                    }
                }
                Ok(FromChild::Line(Up::Done {
                    error,
                    timed_out,
                    printed,
                    hooks,
                })) => {
                    remote.out = None;
                    if hook == "setup" {
                        remote.hooks = hooks;
                    }
                    self.hook_done(game, hook, error, timed_out, printed);
                }
                Ok(FromChild::Bad(reason)) => return self.stop(game, Some(reason), false),
                Ok(FromChild::Closed) | Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return self.stop(game, None, false);
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    if Instant::now() >= kill_at {
                        return self.stop(game, None, true);
                    }
                    if Instant::now() >= deadline {
                        return; // nothing more has arrived
                    }
                    continue;
                }
            }
            // Past the budget, what has already arrived is still handled
            // (a bounded number of messages: a flood waits for the next
            // frame).
            if Instant::now() >= deadline && handled >= READY_AT_ONCE {
                return;
            }
        }
    }

    /// The lesson's hook ended.
    fn hook_done(
        &mut self,
        game: &mut GameState,
        hook: &'static str,
        error: Option<String>,
        timed_out: bool,
        printed: Vec<String>,
    ) {
        let (generation, finished) = Python::attach(|py| {
            let world = self.world.bind(py);
            // What the lesson printed is untrusted text: keep a bounded tail.
            let lines = protocol::printed_tail(printed);
            keep_printed(world, lines);
            let w = world.borrow();
            (w.generation, w.ui.finished.is_some())
        });
        self.finished = finished;
        if let Some(error) = error {
            let error = lightcone_lesson::cut(&error, lightcone_lesson::MAX_TEXT_BYTES);
            game.paused = true;
            self.timed_out = timed_out;
            self.pending = None;
            self.remote = None;
            return self.fail(error);
        }
        if hook == "setup" {
            match self.pending.take() {
                Some(new) if generation > 0 => {
                    *game = new;
                    self.generation = generation;
                    self.seen_collisions = 0;
                }
                _ => {
                    game.paused = true;
                    self.remote = None;
                    let message = format!(
                        "{}: setup(world) did not call world.start(scene)",
                        self.path.display()
                    );
                    self.fail(message);
                }
            }
        }
    }

    /// Ends the lesson's process and shows why: `reason` (it misbehaved),
    /// or — `None` — how it ended by itself, or (`killed`) that its hook
    /// passed its limit and could not be interrupted. The game keeps its
    /// state, paused.
    fn stop(&mut self, game: &mut GameState, reason: Option<String>, killed: bool) {
        let Some(mut remote) = self.remote.take() else {
            return;
        };
        let place = match remote.out {
            Some((hook, _)) => format!("in {hook}"),
            None => "between hooks".to_owned(),
        };
        let over = remote
            .out
            .is_some_and(|(_, since)| since.elapsed() > self.limit);
        let grace = if killed || reason.is_some() {
            Duration::ZERO
        } else {
            Duration::from_millis(200)
        };
        let status = remote.end(grace);
        let message = match (reason, status) {
            (Some(reason), _) => {
                format!("{place}: the lesson's process misbehaved: {reason}; it was stopped")
            }
            (None, Some(s))
                if !(killed || over && s.code() == Some(watchdog::HARD_STOP_STATUS)) =>
            {
                format!(
                    "{place}: the lesson's process {}; the lesson stopped there",
                    supervise::how_it_ended(s, remote.memory_mb)
                )
            }
            (None, _) => supervise::uninterruptible(&place, self.limit),
        };
        self.timed_out = killed || over;
        self.pending = None;
        game.paused = true;
        self.fail(message);
    }
}

#[cfg(test)]
#[path = "remote_tests.rs"]
mod tests;
