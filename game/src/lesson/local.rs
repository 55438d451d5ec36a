//! A lesson run in this process (`lightcone lesson`'s supervised child,
//! and the tests): its hooks are Python calls on the game this host owns.
//!
//! The game is held in one shared cell ([`Rc`]`<`[`RefCell`]`<GameState>>`):
//! the host keeps it, and Python's `World` is given the same cell for the
//! length of each hook (a pyclass cannot hold a borrow), so a hook acts on
//! exactly the game the host steps, and a world kept past its hook has no
//! game and says so. A reload's `setup` builds a new game in a cell of its
//! own, which becomes the host's only once setup has ended well (a failed
//! reload leaves the game as it was).

use std::cell::{RefCell, RefMut};
use std::path::Path;
use std::rc::Rc;

use pyo3::prelude::*;
use pyo3::types::{PyModule, PyTuple};

use super::state::LessonState;
use super::{drain_printed, keep_printed, traceback, watchdog};
use crate::lesson_game::empty_game;
use crate::model::GameState;
use lightcone_python::World;

/// The game as Python's `World` holds it while a hook runs.
type SharedGame = Rc<RefCell<dyn lightcone_lesson::LessonGame>>;

/// A lesson run in this process, and the game it runs on.
pub struct LocalLesson {
    state: LessonState,
    /// The lesson's module (its globals), once loaded without error.
    module: Option<Py<PyModule>>,
    /// The game: this host's, shared with the world for each hook.
    game: Rc<RefCell<GameState>>,
}

impl std::ops::Deref for LocalLesson {
    type Target = LessonState;
    fn deref(&self) -> &LessonState {
        &self.state
    }
}

impl std::ops::DerefMut for LocalLesson {
    fn deref_mut(&mut self) -> &mut LessonState {
        &mut self.state
    }
}

impl LocalLesson {
    /// Loads the lesson at `path` and runs its `setup`. The game is the
    /// lesson's, or — when the lesson fails before starting one —
    /// `fallback`'s, with the error kept in [`LessonState::error`] for the
    /// screen. Fails only when Python itself cannot start or the hook
    /// limit in `LIGHTCONE_HOOK_LIMIT` is not a number of seconds.
    pub fn load(path: &Path, fallback: impl FnOnce() -> GameState) -> Result<Self, String> {
        Self::load_with_limit(path, super::limit_from_env()?, fallback)
    }

    /// [`Self::load`] with a hook time limit other than
    /// [`super::HOOK_LIMIT`].
    pub fn load_with_limit(
        path: &Path,
        limit: std::time::Duration,
        fallback: impl FnOnce() -> GameState,
    ) -> Result<Self, String> {
        let mut state = LessonState::new(path, limit)?;
        let (module, game) = match setup(&mut state) {
            Some((module, game)) => (Some(module), game),
            None => (None, Rc::new(RefCell::new(fallback()))),
        };
        Ok(Self {
            state,
            module,
            game,
        })
    }

    /// The game, to step or look at. Taking `&mut self`, one borrow at a
    /// time, and none across a call on this host (a hook borrows it too):
    /// the borrow checker sees to both.
    pub fn game(&mut self) -> RefMut<'_, GameState> {
        self.game.borrow_mut()
    }

    /// Whether hooks run: the lesson loaded, has not failed and has not
    /// called `world.finish()`.
    #[must_use]
    pub fn running(&self) -> bool {
        self.module.is_some() && self.error.is_none() && !self.finished
    }

    /// Reloads the lesson file (edited or not) and runs `setup` again. On
    /// success the game is the lesson's new one; on failure the game is
    /// left exactly as it was, paused, and the error is shown.
    pub fn reload(&mut self) {
        match setup(&mut self.state) {
            Some((module, game)) => {
                self.module = Some(module);
                self.game = game;
            }
            None => {
                self.module = None;
                self.game().paused = true;
            }
        }
    }

    /// Reloads when the file changed on disk since the last load.
    pub fn reload_if_edited(&mut self) -> bool {
        let edited = self.edited();
        if edited {
            self.reload();
        }
        edited
    }

    /// Shows the closing message once the light of the event it waits for
    /// has reached the eye looked through now (a scene observer's or the
    /// free eye's worldline at the board time shown, so a moving eye is
    /// caught wherever it flew). Call it after each step; returns whether
    /// the message is shown now (or never waited).
    pub fn watch_light(&mut self) -> bool {
        let game = self.game.borrow();
        self.state.watch_light(&game)
    }

    /// Runs the hooks due after a frame: `on_collision` for each new
    /// collision, then `on_frame` if board time advanced since `before`.
    pub fn after_step(&mut self, before: f64) {
        while self.running() {
            let Some(line) = self.state.next_collision(&self.game.borrow()) else {
                break;
            };
            self.call("on_collision", move |py, world| {
                let event = lightcone_python::to_record(py, "Collision", &line)?;
                PyTuple::new(py, [world.clone().into_any(), event])
            });
        }
        let t = self.game.borrow().live_time;
        if t > before {
            self.call("on_frame", move |py, world| {
                PyTuple::new(
                    py,
                    [world.clone().into_any(), t.into_pyobject(py)?.into_any()],
                )
            });
        }
    }

    /// The student chose `choice` for the open question: record it, resume
    /// time if the question paused it, and run `on_answer`.
    pub fn answer(&mut self, choice: usize) {
        let asked = Python::attach(|py| self.world.borrow_mut(py).ui.choose(choice));
        let Some((question, chosen, resume)) = asked else {
            return;
        };
        if resume {
            self.game().paused = false;
        }
        self.call("on_answer", move |py, world| {
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

    /// Calls `hook(world, *args)` if the lesson defines it, the world
    /// given the host's game for the call. A raise stops the hooks and
    /// pauses the game.
    fn call<F>(&mut self, hook: &'static str, args: F)
    where
        F: for<'py> FnOnce(Python<'py>, &Bound<'py, World>) -> PyResult<Bound<'py, PyTuple>>,
    {
        if !self.running() {
            return;
        }
        let limit = self.limit;
        let outcome = Python::attach(|py| {
            let world = self.state.world.bind(py).clone();
            world
                .borrow_mut()
                .share(Some(self.game.clone() as SharedGame));
            let result = {
                // Only the hook itself is timed.
                let _running = watchdog::Running::start(limit, hook);
                match self.module.as_ref().map(|m| m.bind(py).getattr(hook)) {
                    Some(Ok(f)) => args(py, &world).and_then(|a| f.call1(a).map(|_| ())),
                    _ => Ok(()),
                }
            };
            world.borrow_mut().share(None);
            keep_printed(&world, drain_printed(py));
            self.state.after_hook(py);
            result
                .map_err(|e| format!("in {hook}:\n{}", traceback(py, &e)))
                .and_then(
                    |()| match super::take_thread_errors(py).into_iter().next() {
                        Some(error) => Err(error),
                        None => Ok(()),
                    },
                )
        });
        if let Err(e) = outcome {
            self.game().paused = true;
            self.timed_out = watchdog::stopped();
            self.fail(e);
        }
    }

    /// The world the hooks are given (for the tests).
    #[cfg(test)]
    pub(super) fn world(&self) -> &Py<World> {
        &self.state.world
    }
}

/// Reads and runs the lesson file, then `setup(world)` on a fresh world
/// and a new game. The module and the game setup built, or `None` with
/// the failure kept in `state`.
fn setup(state: &mut LessonState) -> Option<(Py<PyModule>, Rc<RefCell<GameState>>)> {
    state.begin_load();
    let path = state.path.clone();
    let source = match std::fs::read_to_string(&path) {
        Ok(s) => s,
        Err(e) => {
            state.fail(format!("{}: cannot read the lesson: {e}", path.display()));
            return None;
        }
    };
    let result = Python::attach(|py| -> PyResult<(Py<PyModule>, Rc<RefCell<GameState>>)> {
        let dir = state.world.borrow(py).dir.display().to_string();
        // The module's own code and setup are timed like a hook.
        let running = watchdog::Running::start(state.limit, "setup");
        let module = super::load_module(py, &path, source, &dir)?;
        // A fresh world (screen, attributes, no game): setup builds it.
        state.fresh_world(py)?;
        let world = state.world.bind(py);
        // The game setup builds, given to the world while it runs.
        let building = Rc::new(RefCell::new(empty_game()));
        world
            .borrow_mut()
            .share(Some(building.clone() as SharedGame));
        let called = module.call_method1("setup", (world,));
        drop(running);
        world.borrow_mut().share(None);
        keep_printed(world, drain_printed(py));
        called?;
        if !world.borrow().started() {
            return Err(pyo3::exceptions::PyRuntimeError::new_err(format!(
                "{}: setup(world) did not call world.start(scene)",
                path.display()
            )));
        }
        Ok((module.unbind(), building))
    });
    match result {
        Ok(built) => {
            Python::attach(|py| state.after_hook(py));
            state.seen_collisions = 0;
            Some(built)
        }
        Err(e) => {
            let text = Python::attach(|py| traceback(py, &e));
            state.timed_out = watchdog::stopped();
            state.fail(text);
            None
        }
    }
}
