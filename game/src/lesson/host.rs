//! The window's lesson host: the lesson runs in its own process
//! ([`super::remote`]), and the game stays with the front end that shows
//! it (the window's `Stage`, `render`/`record`'s run). Each call takes
//! that game by `&mut`: a request from the lesson borrows it for the
//! request's length, so the game has one owner and the lesson's process
//! holds none of it.

use std::path::Path;

use super::isolation::Isolation;
use super::state::LessonState;
use super::{remote, sandbox};
use crate::model::GameState;

/// One lesson, in its own process, running or failed.
pub struct LessonHost {
    pub(super) state: LessonState,
    /// The lesson's process, while it runs.
    pub(super) remote: Option<remote::Remote>,
    /// How to start that process.
    pub(super) isolation: Isolation,
    /// The game `setup` is building in the lesson's process.
    pub(super) pending: Option<GameState>,
    /// A shipped lesson's name, and the private folder holding the copy
    /// of it that runs (removed with the host: the last field, dropped
    /// after the lesson's process ended).
    shipped: Option<(String, sandbox::Scratch)>,
}

impl std::ops::Deref for LessonHost {
    type Target = LessonState;
    fn deref(&self) -> &LessonState {
        &self.state
    }
}

impl std::ops::DerefMut for LessonHost {
    fn deref_mut(&mut self) -> &mut LessonState {
        &mut self.state
    }
}

impl LessonHost {
    /// Loads the lesson at `path` in its own process (the window): nothing
    /// it does ends the game ([`remote`]). Waits for its `setup` (the
    /// window is not open yet). Returns the host and the game to show:
    /// the lesson's, or — when the lesson fails before starting a game —
    /// `fallback`'s, with the error kept in [`LessonState::error`] for the
    /// screen. Fails only when Python itself cannot start or the hook
    /// limit in `LIGHTCONE_HOOK_LIMIT` is not a number of seconds.
    pub fn load_isolated(
        path: &Path,
        fallback: impl FnOnce() -> GameState,
        isolation: Isolation,
    ) -> Result<(Self, GameState), String> {
        Self::load_isolated_with_limit(path, super::limit_from_env()?, fallback, isolation)
    }

    /// [`Self::load_isolated`] with a hook time limit other than
    /// [`super::HOOK_LIMIT`].
    pub fn load_isolated_with_limit(
        path: &Path,
        limit: std::time::Duration,
        fallback: impl FnOnce() -> GameState,
        isolation: Isolation,
    ) -> Result<(Self, GameState), String> {
        let mut host = Self::new(path, limit, isolation)?;
        let mut game = fallback();
        host.settle(&mut game);
        Ok((host, game))
    }

    /// Starts the lesson at `path` in its own process while the window
    /// runs (the scene menu), without waiting: its `setup` is served by
    /// the next frames ([`Self::serve`]), and replaces the game when it
    /// ends; meanwhile board time waits ([`Self::busy`]). A setup that
    /// fails leaves the game as it was, paused, with the traceback shown.
    /// Fails when Python cannot start or the hook limit in the
    /// environment is not a number of seconds.
    pub fn open_isolated(path: &Path, isolation: Isolation) -> Result<Self, String> {
        Self::new(path, super::limit_from_env()?, isolation)
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

    /// A host for the lesson at `path`, its process started and its
    /// `setup` queued.
    fn new(path: &Path, limit: std::time::Duration, isolation: Isolation) -> Result<Self, String> {
        let mut host = Self {
            state: LessonState::new(path, limit)?,
            remote: None,
            isolation,
            pending: None,
            shipped: None,
        };
        host.start_remote();
        Ok(host)
    }

    /// The lesson's name for the screen: its file's path, or `(built in)
    /// NAME` for a shipped lesson.
    #[must_use]
    pub fn name(&self) -> String {
        match &self.shipped {
            Some((name, _)) => format!("(built in) {name}"),
            None => self.path.display().to_string(),
        }
    }

    /// The window's frame, as the lesson in its own process sees it. The
    /// hooks of a frame are sent by [`Self::after_step`], which does not
    /// wait; they run in the lesson's process while the game draws, and
    /// the next frame calls this, before board time moves, to take their
    /// ends (and their requests' answers) within `budget`
    /// ([`remote::FRAME_BUDGET`] at the start of a frame, zero right
    /// after drawing to answer what arrived meanwhile). A hook that is not
    /// done by then goes on over the next frames, board time waiting.
    pub fn serve(&mut self, game: &mut GameState, budget: std::time::Duration) {
        self.poll(game, budget);
    }

    /// Serves the lesson's process until no hook is out or waiting (each
    /// ends by its limit): for headless runs and the first load.
    pub fn settle(&mut self, game: &mut GameState) {
        while self.busy() {
            self.poll(game, std::time::Duration::from_millis(50));
        }
    }

    /// Reloads the lesson file (edited or not) in a new process; its
    /// `setup` replaces the game when it ends, and a setup that fails
    /// leaves the game as it was, paused, with the error shown.
    pub fn reload(&mut self, game: &mut GameState) {
        self.start_remote();
        self.poll(game, std::time::Duration::ZERO);
    }

    /// Reloads when the file changed on disk since the last load.
    pub fn reload_if_edited(&mut self, game: &mut GameState) -> bool {
        let edited = self.edited();
        if edited {
            self.reload(game);
        }
        edited
    }

    /// Whether hooks run: the lesson's process is up, the lesson has not
    /// failed and has not called `world.finish()`.
    #[must_use]
    pub fn running(&self) -> bool {
        self.remote.is_some() && self.error.is_none() && !self.finished
    }

    /// Shows the closing message once the light of the event it waits for
    /// has reached the eye looked through now (a scene observer's or the
    /// free eye's worldline at the board time shown, so a moving eye is
    /// caught wherever it flew). Call it after each step; returns whether
    /// the message is shown now (or never waited).
    pub fn watch_light(&mut self, game: &GameState) -> bool {
        self.state.watch_light(game)
    }

    /// Sends the hooks due after a frame: `on_collision` for each new
    /// collision, then `on_frame` if board time advanced since `before`.
    /// Returns without waiting for them ([`Self::serve`] takes their ends).
    pub fn after_step(&mut self, game: &mut GameState, before: f64) {
        while self.running() {
            let Some(line) = self.state.next_collision(game) else {
                break;
            };
            let Ok(data) = serde_json::to_value(&line) else {
                continue;
            };
            let event = serde_json::json!([{"$record": "Collision", "data": data}]);
            self.queue_remote("on_collision", event);
        }
        if game.live_time > before {
            self.queue_remote("on_frame", serde_json::json!([game.live_time]));
        }
        self.poll(game, std::time::Duration::ZERO);
    }

    /// The student chose `choice` for the open question: record it, resume
    /// time if the question paused it, and send `on_answer`.
    pub fn answer(&mut self, game: &mut GameState, choice: usize) {
        let asked = pyo3::Python::attach(|py| self.world.borrow_mut(py).ui.choose(choice));
        let Some((question, chosen, resume)) = asked else {
            return;
        };
        if resume {
            game.paused = false;
        }
        self.queue_remote("on_answer", serde_json::json!([question, chosen]));
        self.poll(game, std::time::Duration::ZERO);
    }
}
