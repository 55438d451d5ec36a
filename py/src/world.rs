//! `lightcone.World`: what a lesson's hooks are given. It is the running
//! game (board time, pucks, effects, view) plus the lesson's voice on
//! screen: text, questions that pause for a prediction, checked claims and
//! bar charts.
//!
//! The world shares the game with the game's lesson host for the length
//! of one hook call (`World::share`), so a hook acts on exactly what the
//! student sees; outside a hook the world has no game, and says so. Every
//! operation is `lightcone_lesson::WorldCall`'s (the same that answers a
//! lesson run in its own process or a browser's worker): this class only
//! converts arguments and results.

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;

use lightcone_lesson::{Claim, LessonGame, WorldCall, WorldCore, WorldResult};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::Scene;
use super::errors::world_err;

/// Told of each claim as it is checked: a lesson run in its own process
/// sends it to the game at once, so a process that dies later in the same
/// hook keeps what it claimed. One observer per process.
static CLAIM_OBSERVER: std::sync::OnceLock<fn(&Claim)> = std::sync::OnceLock::new();

/// Registers `f` to be told of every claim checked in this process, as it
/// is checked (the first registration holds).
pub fn observe_claims(f: fn(&Claim)) {
    let _ = CLAIM_OBSERVER.set(f);
}

/// The running game as a lesson sees it. Hooks receive it: `setup(world)`,
/// `on_frame(world, t)`, `on_collision(world, event)` and
/// `on_answer(world, question, choice)`. A lesson may keep its own
/// attributes on it (`world.hits = {}`); a reload starts a fresh world.
#[pyclass(module = "lightcone._lightcone", unsendable, dict)]
pub struct World {
    core: WorldCore,
    /// The game, shared by the host while a hook runs.
    game: Option<Rc<RefCell<dyn LessonGame>>>,
}

impl World {
    /// A world with no game yet, for the lesson in directory `dir`.
    #[must_use]
    pub fn new(dir: PathBuf) -> Self {
        Self {
            core: WorldCore::new(dir),
            game: None,
        }
    }

    /// Shares `game` with the world (for a hook; `None` when it ends). The
    /// host keeps its own handle on the same game.
    pub fn share(&mut self, game: Option<Rc<RefCell<dyn LessonGame>>>) {
        self.game = game;
    }

    /// Runs world operation `f` on the shared game.
    fn with_game<R>(
        &mut self,
        f: impl FnOnce(&mut WorldCall<'_>) -> WorldResult<R>,
    ) -> PyResult<R> {
        let mut held = match &self.game {
            Some(g) => Some(g.try_borrow_mut().map_err(|_| {
                pyo3::exceptions::PyRuntimeError::new_err(
                    "the game is busy (a world call inside another)",
                )
            })?),
            None => None,
        };
        let game = held.as_deref_mut();
        f(&mut self.core.on(game)).map_err(world_err)
    }
}

impl std::ops::Deref for World {
    type Target = WorldCore;
    fn deref(&self) -> &WorldCore {
        &self.core
    }
}

impl std::ops::DerefMut for World {
    fn deref_mut(&mut self) -> &mut WorldCore {
        &mut self.core
    }
}

#[pymethods]
impl World {
    /// Starts (or restarts) the game on `scene` at board time 0. Keeps the
    /// view, eye choice and time scale the student had.
    fn start(&mut self, scene: &Scene) -> PyResult<()> {
        self.with_game(|w| w.start(scene.inner.clone()))
    }

    /// Loads a scene file; a relative path is taken from the lesson's
    /// directory. Raises SceneError naming the file, line and field.
    fn load(&mut self, path: PathBuf) -> PyResult<Scene> {
        let inner = self.with_game(|w| w.load(path))?;
        Ok(Scene { inner })
    }

    /// A copy of the scene being played.
    #[getter]
    fn scene(&mut self) -> PyResult<Scene> {
        let inner = self.with_game(|w| Ok(w.game()?.scene().clone()))?;
        Ok(Scene { inner })
    }

    /// Board time the physics has reached, s.
    #[getter]
    fn t(&mut self) -> PyResult<f64> {
        self.with_game(|w| w.t())
    }

    /// Speed of light, m/s.
    #[getter]
    fn c(&mut self) -> PyResult<f64> {
        self.with_game(|w| w.c())
    }

    /// Whether time stands still.
    #[getter]
    fn paused(&mut self) -> PyResult<bool> {
        self.with_game(|w| w.paused())
    }

    #[setter]
    fn set_paused(&mut self, paused: bool) -> PyResult<()> {
        self.with_game(|w| w.set_paused(paused))
    }

    /// Stops time (the student can still fly and look around).
    fn pause(&mut self) -> PyResult<()> {
        self.set_paused(true)
    }

    /// Lets time run again.
    fn resume(&mut self) -> PyResult<()> {
        self.set_paused(false)
    }

    /// Board seconds per real second.
    #[getter]
    fn time_scale(&mut self) -> PyResult<f64> {
        self.with_game(|w| w.time_scale())
    }

    #[setter]
    fn set_time_scale(&mut self, scale: f64) -> PyResult<()> {
        self.with_game(|w| w.set_time_scale(scale))
    }

    /// Which pictures: "seen", "truth" or "split".
    #[getter]
    fn view(&mut self) -> PyResult<&'static str> {
        self.with_game(|w| w.view())
    }

    #[setter]
    fn set_view(&mut self, view: &str) -> PyResult<()> {
        self.with_game(|w| w.set_view(view))
    }

    /// The scene observer whose eye is used, or None for the free eye.
    #[getter]
    fn observer(&mut self) -> PyResult<Option<String>> {
        self.with_game(|w| w.observer())
    }

    #[setter]
    fn set_observer(&mut self, name: Option<&str>) -> PyResult<()> {
        self.with_game(|w| w.set_observer(name))
    }

    /// The effects shown, as a dict of flags.
    #[getter]
    fn effects<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (key, on) in self.with_game(|w| w.effects())? {
            d.set_item(key, on)?;
        }
        Ok(d)
    }

    /// Turns an effect on or off in the student's view.
    fn set_effect(&mut self, name: &str, on: bool) -> PyResult<()> {
        self.with_game(|w| w.set_effect(name, on))
    }

    /// Every puck now: the `state` dict of `lightcone simulate`.
    fn state<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        super::to_record(py, "State", &self.with_game(|w| w.state())?)
    }

    /// Every collision so far, as the dicts `lightcone simulate` prints.
    fn collisions<'py>(&mut self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let all = self.with_game(|w| w.collisions())?;
        all.iter()
            .map(|c| super::to_record(py, "Collision", c))
            .collect()
    }

    /// The proper velocity γβ of puck `name` now, as (x, y).
    fn velocity(&mut self, name: &str) -> PyResult<(f64, f64)> {
        self.with_game(|w| w.velocity(name))
    }

    /// Strikes puck `name` now: its proper velocity γβ (dimensionless)
    /// grows by `du` (two numbers: tuple, list or array).
    fn impulse(&mut self, name: &str, du: super::convert::Vector<2>) -> PyResult<()> {
        self.with_game(|w| w.impulse(name, du.pair()))
    }

    /// What `observer` (default: the first scene observer) sees at board
    /// time `at` s (default: now; `t` is the older name), as the dict
    /// `lightcone observe` prints. `effects`: None for those shown, or a
    /// list of effect names. A time after now raises NotComputedError.
    #[pyo3(signature = (observer = None, t = None, vertices = false, effects = None, at = None))]
    fn observe<'py>(
        &mut self,
        py: Python<'py>,
        observer: Option<&str>,
        t: Option<f64>,
        vertices: bool,
        effects: Option<Vec<String>>,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let report = self.with_game(|w| w.observe(observer, t, vertices, effects, at))?;
        super::to_record(py, "Observation", &report)
    }

    /// The space-time diagram for `observer` (default: the first scene
    /// observer) at board time `at` (default: now), as a `Frame` (see
    /// `Simulation.diagram`); `frame`: a puck whose lines of simultaneity
    /// to draw. With `path` (relative to the lesson), also saved, by the
    /// lesson's own process (a sandboxed lesson writes only in its
    /// temporary folder, `tempfile.gettempdir()`).
    #[pyo3(signature = (path = None, observer = None, size = (1000, 700), at = None, axis = "x", frame = None))]
    fn diagram(
        &mut self,
        path: Option<PathBuf>,
        observer: Option<&str>,
        size: (u32, u32),
        at: Option<f64>,
        axis: &str,
        frame: Option<&str>,
    ) -> PyResult<super::Frame> {
        let (image, t) = self.with_game(|w| w.diagram(observer, size, at, axis, frame))?;
        let picture = super::Frame::from_image(&image, t)?;
        if let Some(path) = path {
            picture.save(self.core.dir.join(path))?;
        }
        Ok(picture)
    }

    /// Opens (`on`) or closes the live space-time diagram in the window,
    /// drawing puck `frame`'s lines of simultaneity (None: only the
    /// board's), with board `axis` "x" or "y" across. Headless, it only
    /// records the choice.
    #[pyo3(signature = (on = true, frame = None, axis = "x"))]
    fn show_diagram(&mut self, on: bool, frame: Option<&str>, axis: &str) -> PyResult<()> {
        self.with_game(|w| w.show_diagram(on, frame, axis))
    }

    /// The line of simultaneity of puck `frame`'s rest frame through its
    /// event at board time `at` (default: now): see
    /// `Simulation.simultaneity`.
    #[pyo3(signature = (frame, at = None))]
    fn simultaneity<'py>(
        &mut self,
        py: Python<'py>,
        frame: &str,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let line = self.with_game(|w| w.simultaneity(frame, at))?;
        super::to_plain(py, &line)
    }

    /// Shows `text` as the lesson's message: replacing the previous one,
    /// or with `append=True` as a new line after it (64 KiB in all at
    /// most: ValueError past it).
    #[pyo3(signature = (text, append = false))]
    fn say(&mut self, text: &str, append: bool) -> PyResult<()> {
        self.with_game(|w| w.say(text, append))
    }

    /// Asks the student a question with `choices` (buttons) and pauses
    /// until they answer; `on_answer(world, question, choice)` then runs.
    /// `answer`: index of the right choice, to tell the student.
    #[pyo3(signature = (question, choices, answer = None))]
    fn ask(&mut self, question: &str, choices: Vec<String>, answer: Option<usize>) -> PyResult<()> {
        self.with_game(|w| w.ask(question, choices, answer))
    }

    /// Records a physics claim: shown as ✓/✗ with `detail`; a false claim
    /// fails the headless lesson run. Returns `ok`.
    #[pyo3(signature = (claim, ok, detail = ""))]
    fn check(&mut self, claim: &str, ok: bool, detail: &str) -> PyResult<bool> {
        let made = self.with_game(|w| w.check(claim, ok, detail))?;
        if let Some(f) = CLAIM_OBSERVER.get() {
            f(&made);
        }
        Ok(made.ok)
    }

    /// The claims checked so far, as (claim, ok, detail) tuples.
    #[getter]
    fn claims(&self) -> Vec<(String, bool, String)> {
        self.core.claims()
    }

    /// Draws a bar chart: `counts` over bins with `edges` (one more edge
    /// than counts), with `expected` per bin drawn as a line.
    #[pyo3(signature = (title, edges, counts, expected = None))]
    fn bars(
        &mut self,
        title: &str,
        edges: Vec<f64>,
        counts: Vec<f64>,
        expected: Option<Vec<f64>>,
    ) -> PyResult<()> {
        self.with_game(|w| w.bars(title, edges, counts, expected))
    }

    /// Ends the lesson with a closing `message`: no hook runs again (the
    /// game goes on for the student), and the message is shown at once,
    /// or, with `after_light_from = (t, x, y)` (a board event: board time
    /// s, position m on the cloth), once the light of that event has
    /// reached the eye looked through (for an eye at rest at distance d,
    /// at board time t + d / c), so the student has seen what the message
    /// explains. Raises ValueError for a number that is not finite.
    #[pyo3(signature = (message = "", after_light_from = None))]
    fn finish(
        &mut self,
        message: &str,
        after_light_from: Option<super::convert::Vector<3>>,
    ) -> PyResult<()> {
        self.with_game(|w| {
            w.finish(
                message,
                after_light_from.map(super::convert::Vector::triple),
            )
        })
    }

    /// Whether `finish` was called (then no further hook will run).
    #[getter]
    fn finished(&self) -> bool {
        self.core.finished()
    }

    fn __repr__(&mut self) -> String {
        self.with_game(|w| Ok(w.describe()))
            .unwrap_or_else(|e| format!("World(<{e}>)"))
    }
}
