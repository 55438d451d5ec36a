//! What both lesson hosts keep of a lesson: its file, the world whose
//! screen (text, question, claims, what it printed) the panel shows, how
//! far its hooks have seen the collisions, and how it stopped. The host
//! that runs the lesson in this process ([`super::LocalLesson`]) and the
//! one that runs it in its own ([`super::LessonHost`]) each hold one.

use std::path::{Path, PathBuf};
use std::time::{Duration, SystemTime};

use lightcone_engine::report::CollisionLine;
use lightcone_python::{LessonUi, World};
use pyo3::prelude::*;

use crate::model::GameState;

/// One lesson's file, screen and progress, whichever process runs it.
pub struct LessonState {
    pub(super) path: PathBuf,
    /// The world: in this process, what the hooks are given; for a lesson
    /// in its own process, the world whose operations answer its requests
    /// (`WorldCall`). Either way its screen is the panel's. Dropped
    /// attached to Python, on the host's thread (see `Drop`).
    pub(super) world: std::mem::ManuallyDrop<Py<World>>,
    /// Collisions already passed to `on_collision` (a global record index:
    /// the billiard may have dropped older records).
    pub(super) seen_collisions: u64,
    /// The world's generation those collisions belong to (`world.start`
    /// in a hook restarts the collision list).
    pub(super) generation: u64,
    /// The file's modification time at the last (re)load.
    pub(super) modified: Option<SystemTime>,
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
    pub(super) finished: bool,
    /// Longest a hook may run before it is stopped ([`super::HOOK_LIMIT`]).
    pub limit: Duration,
}

impl LessonState {
    /// The state of the lesson at `path`, nothing loaded yet: starts the
    /// embedded interpreter (once a process) and a world with no game.
    pub(super) fn new(path: &Path, limit: Duration) -> Result<Self, String> {
        super::init_python()?;
        let world = Python::attach(|py| Py::new(py, World::new(super::lesson_dir(path))))
            .map_err(|e| format!("cannot start the lesson host: {e}"))?;
        Ok(Self {
            path: path.to_path_buf(),
            world: std::mem::ManuallyDrop::new(world),
            seen_collisions: 0,
            generation: 0,
            modified: None,
            error: None,
            timed_out: false,
            loads: 0,
            finished: false,
            limit,
        })
    }

    /// The lesson file.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Whether the lesson called `world.finish()` (its hooks then stop, in
    /// the window as headless; the game itself goes on).
    #[must_use]
    pub fn finished(&self) -> bool {
        self.finished
    }

    /// Whether the lesson finished with a closing message that waits for
    /// an event's light (`finish(after_light_from=…)`) still on its way.
    #[must_use]
    pub fn awaiting_light(&self) -> bool {
        self.finished && self.with_ui(|ui| ui.finish_light.is_some())
    }

    /// Looks at the lesson's screen without copying it.
    pub fn with_ui<R>(&self, f: impl FnOnce(&LessonUi) -> R) -> R {
        Python::attach(|py| f(&self.world.borrow(py).ui))
    }

    /// Stops the hooks and keeps `message` for the screen (and stderr, for
    /// whoever started the game from a terminal).
    pub(super) fn fail(&mut self, message: String) {
        crate::errln!("lesson {} stopped:\n{message}", self.path.display());
        self.error = Some(message);
    }

    /// A (re)load begins: counted, the file's time noted, the last
    /// failure forgotten, the collisions seen from the start. (Whether the
    /// lesson has finished is its world's: a fresh world's once setup ran,
    /// the old one's when a reload fails before that.)
    pub(super) fn begin_load(&mut self) {
        self.loads += 1;
        self.modified = modified(&self.path);
        self.error = None;
        self.timed_out = false;
        self.seen_collisions = 0;
    }

    /// Whether the file changed on disk since the last load.
    pub(super) fn edited(&self) -> bool {
        let now = modified(&self.path);
        now.is_some() && now != self.modified
    }

    /// Replaces the world by a fresh one (screen, attributes, no game) in
    /// the same directory: a (re)load starts from it.
    pub(super) fn fresh_world(&mut self, py: Python<'_>) -> PyResult<()> {
        let dir = self.world.borrow(py).dir.clone();
        *self.world = Py::new(py, World::new(dir))?;
        Ok(())
    }

    /// Takes the world's generation and finish after a hook: a
    /// `world.start` in it restarted the collision list.
    pub(super) fn after_hook(&mut self, py: Python<'_>) {
        let w = self.world.borrow(py);
        let (generation, finished) = (w.generation, w.ui.finished.is_some());
        drop(w);
        self.finished = finished;
        if generation != self.generation {
            self.generation = generation;
            self.seen_collisions = 0;
        }
    }

    /// The next collision of `game` the hooks have not seen (marked seen),
    /// skipping records the billiard dropped before they were seen;
    /// `None` when there is none.
    pub(super) fn next_collision(&mut self, game: &GameState) -> Option<CollisionLine> {
        let physics = game.physics();
        if physics.collision_count() < self.seen_collisions {
            // The game restarted under the lesson (the c slider).
            self.seen_collisions = 0;
        }
        while self.seen_collisions < physics.collision_count() {
            let i = self.seen_collisions;
            self.seen_collisions += 1;
            if physics.collisions_forgotten() > i {
                continue; // dropped before it was seen
            }
            if let Some(record) = physics.collisions_from(i).first() {
                return Some(CollisionLine::new(physics, record));
            }
        }
        None
    }

    /// Shows the closing message once the light of the event it waits for
    /// has reached the eye looked through now (`game.eye()`: a scene
    /// observer's or the free eye's worldline at the board time shown, so
    /// a moving eye is caught wherever it flew). Returns whether the
    /// message is shown now (or never waited).
    pub(super) fn watch_light(&mut self, game: &GameState) -> bool {
        if !self.finished {
            return false;
        }
        let eye = game.eye().event;
        let c = game.scene.c;
        Python::attach(|py| self.world.borrow_mut(py).ui.light_arrived(eye, c))
    }
}

impl Drop for LessonState {
    /// Releases the world here, attached: the world is unsendable, and a
    /// release left for whichever thread next attaches is refused (with an
    /// error printed) and leaks it.
    fn drop(&mut self) {
        // SAFETY: `world` is not used after this; the field is never
        // dropped otherwise (`ManuallyDrop`).
        Python::attach(|_| unsafe { std::mem::ManuallyDrop::drop(&mut self.world) });
    }
}

/// The modification time of the file at `path`, if it can be read.
fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}
