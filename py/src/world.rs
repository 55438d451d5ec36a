//! `lightcone.World`: what a lesson's hooks are given. It is the running
//! game (board time, pucks, effects, view) plus the lesson's voice on
//! screen: text, questions that pause for a prediction, checked claims and
//! bar charts.
//!
//! The game lends its state to the world for the length of one hook call
//! (the game's lesson host), so a hook acts on exactly what the student
//! sees; outside a hook the world has no game, and says so. The world
//! reaches the game only through [`LessonGame`], which the game implements:
//! this crate does not depend on the game.

use std::any::Any;
use std::path::PathBuf;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::{Effect, Effects, Scene as SceneModel};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::Scene;

/// Which pictures the game shows: what is seen, the truth, or both side by
/// side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pictures {
    /// What the observer sees.
    Seen,
    /// The board as it is at the same board time.
    Truth,
    /// Both, side by side.
    Split,
}

/// What a lesson may read and change of the running game. The game
/// implements it on its state and lends that to the [`World`] for the
/// length of one hook; it takes it back with [`LessonGame::into_any`].
pub trait LessonGame: Any {
    /// The scene being played.
    fn scene(&self) -> &SceneModel;
    /// The pucks and their worldlines.
    fn billiard(&self) -> &Billiard;
    /// The pucks, to strike one.
    fn billiard_mut(&mut self) -> &mut Billiard;
    /// Board time the physics has reached, s.
    fn live_time(&self) -> f64;
    /// Whether time stands still.
    fn paused(&self) -> bool;
    /// Stops or restarts time.
    fn set_paused(&mut self, paused: bool);
    /// Board seconds per real second.
    fn time_scale(&self) -> f64;
    /// Sets board seconds per real second (checked by the caller).
    fn set_time_scale(&mut self, scale: f64);
    /// Which pictures are shown.
    fn pictures(&self) -> Pictures;
    /// Chooses the pictures shown.
    fn set_pictures(&mut self, pictures: Pictures);
    /// Index of the scene observer whose eye is used (`None`: free eye).
    fn observer(&self) -> Option<usize>;
    /// Chooses the eye (an index into the scene's observers, checked by
    /// the caller).
    fn set_observer(&mut self, observer: Option<usize>);
    /// The effects shown.
    fn effects(&self) -> Effects;
    /// The effects shown, to turn one on or off.
    fn effects_mut(&mut self) -> &mut Effects;
    /// Opens or closes the live space-time diagram, with the puck whose
    /// lines of simultaneity it draws (`None`: only the board's) and the
    /// board axis across.
    fn set_diagram(
        &mut self,
        on: bool,
        frame: Option<usize>,
        axis: lightcone_render::diagram::Axis,
    );
    /// The game itself, for the host to take it back.
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

/// Makes a new game at board time 0 on a scene (the game's constructor).
pub type NewGame = fn(SceneModel) -> Box<dyn LessonGame>;

/// A question on screen, waiting for (or answered with) a choice.
#[derive(Clone, Debug, PartialEq)]
pub struct Question {
    /// The question.
    pub text: String,
    /// The possible answers, shown as buttons.
    pub choices: Vec<String>,
    /// Index of the right answer, if the lesson gave one.
    pub answer: Option<usize>,
    /// Index the student chose, once they have.
    pub chosen: Option<usize>,
    /// The game was running when the question paused it (so answering
    /// resumes it).
    pub resume: bool,
}

/// A physics claim the lesson checked, shown as ✓ or ✗ (and failing the
/// headless run when false).
#[derive(Clone, Debug, PartialEq)]
pub struct Claim {
    /// What is claimed.
    pub claim: String,
    /// Whether it held.
    pub ok: bool,
    /// The numbers behind it.
    pub detail: String,
}

/// Most claims a lesson may check (the shipped lessons check a few
/// dozen): past it `check` raises, so a flood of claims cannot grow the
/// game's memory or its panel.
pub const MAX_CLAIMS: usize = 10_000;

/// Longest claim, or claim's detail, in bytes of UTF-8.
pub const MAX_CLAIM_BYTES: usize = 4096;

/// Most bar charts (by title) a lesson may show at once, and most bins a
/// chart may have.
pub const MAX_CHARTS: usize = 64;
/// See [`MAX_CHARTS`].
pub const MAX_BINS: usize = 10_000;

/// Told of each claim as it is checked: a lesson run in its own process
/// sends it to the game at once, so a process that dies later in the same
/// hook keeps what it claimed. One observer per process.
static CLAIM_OBSERVER: std::sync::OnceLock<fn(&Claim)> = std::sync::OnceLock::new();

/// Registers `f` to be told of every claim checked in this process, as it
/// is checked (the first registration holds).
pub fn observe_claims(f: fn(&Claim)) {
    let _ = CLAIM_OBSERVER.set(f);
}

/// A bar chart (for instance a speed histogram) with an optional expected
/// curve drawn over it.
#[derive(Clone, Debug, PartialEq)]
pub struct Bars {
    /// Title above the chart.
    pub title: String,
    /// Bin edges (one more than the counts).
    pub edges: Vec<f64>,
    /// Bar heights.
    pub counts: Vec<f64>,
    /// Expected heights per bin, drawn as a line.
    pub expected: Option<Vec<f64>>,
}

/// Everything the lesson has put on screen.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LessonUi {
    /// The lesson's current text.
    pub text: String,
    /// The current question.
    pub question: Option<Question>,
    /// Claims checked so far, in order.
    pub claims: Vec<Claim>,
    /// Charts, by title (a chart with the same title replaces the old).
    pub bars: Vec<Bars>,
    /// Set by `finish`: the closing message (no hook runs after it).
    pub finished: Option<String>,
    /// Set by `finish(after_light_from=…)`: the board event (board time s,
    /// position m on the cloth, z = 0) whose light the closing message
    /// waits for. The game clears it once that light has reached the eye
    /// looked through; until then the message is not shown.
    pub finish_light: Option<lightcone_engine::spacetime::Event>,
    /// The newest lines the lesson printed.
    pub printed: Vec<String>,
}

/// The running game as a lesson sees it. Hooks receive it: `setup(world)`,
/// `on_frame(world, t)`, `on_collision(world, event)` and
/// `on_answer(world, question, choice)`. A lesson may keep its own
/// attributes on it (`world.hits = {}`); a reload starts a fresh world.
#[pyclass(module = "lightcone._lightcone", unsendable, dict)]
pub struct World {
    /// The game, while a hook runs (lent by the host).
    pub game: Option<Box<dyn LessonGame>>,
    /// What the lesson shows.
    pub ui: LessonUi,
    /// Bumped by `start`, so the host knows the collision list restarted.
    pub generation: u64,
    /// The lesson file, to resolve relative paths.
    pub dir: PathBuf,
    /// Makes the game `start` starts.
    new_game: NewGame,
}

impl LessonUi {
    /// The closing message as the screen shows it: set by `finish`, and,
    /// when it waits for an event's light, once that light has arrived.
    pub fn closing(&self) -> Option<&str> {
        self.finished
            .as_deref()
            .filter(|_| self.finish_light.is_none())
    }
}

impl World {
    /// A world with no game yet, for the lesson in directory `dir`;
    /// `world.start(scene)` makes one with `new_game`.
    pub fn new(dir: PathBuf, new_game: NewGame) -> Self {
        Self {
            game: None,
            ui: LessonUi::default(),
            generation: 0,
            dir,
            new_game,
        }
    }

    /// The lesson's screen.
    pub fn ui(&self) -> &LessonUi {
        &self.ui
    }

    fn game(&self) -> PyResult<&dyn LessonGame> {
        self.game.as_deref().ok_or_else(no_game)
    }

    fn game_mut(&mut self) -> PyResult<&mut dyn LessonGame> {
        match self.game.as_deref_mut() {
            Some(g) => Ok(g),
            None => Err(no_game()),
        }
    }
}

fn no_game() -> PyErr {
    PyRuntimeError::new_err(
        "the world has no game here: call world.start(scene) in setup(world), and use the world only inside a hook",
    )
}

#[pymethods]
impl World {
    /// Starts (or restarts) the game on `scene` at board time 0. Keeps the
    /// view, eye choice and time scale the student had.
    fn start(&mut self, scene: &Scene) {
        let mut game = (self.new_game)(scene.inner.clone());
        if let Some(old) = &self.game {
            game.set_pictures(old.pictures());
            game.set_time_scale(old.time_scale());
            if old
                .observer()
                .is_some_and(|i| i < game.scene().observers.len())
            {
                game.set_observer(old.observer());
            }
        }
        self.game = Some(game);
        self.generation += 1;
    }

    /// Loads a scene file; a relative path is taken from the lesson's
    /// directory. Raises SceneError naming the file, line and field.
    fn load(&self, path: PathBuf) -> PyResult<Scene> {
        let path = if path.is_relative() {
            self.dir.join(path)
        } else {
            path
        };
        lightcone_engine::scene::load(&path)
            .map(|inner| Scene { inner })
            .map_err(|e| super::errors::ScenePyErr::from(e).into())
    }

    /// A copy of the scene being played.
    #[getter]
    fn scene(&self) -> PyResult<Scene> {
        Ok(Scene {
            inner: self.game()?.scene().clone(),
        })
    }

    /// Board time the physics has reached, s.
    #[getter]
    fn t(&self) -> PyResult<f64> {
        Ok(self.game()?.live_time())
    }

    /// Speed of light, m/s.
    #[getter]
    fn c(&self) -> PyResult<f64> {
        Ok(self.game()?.scene().c)
    }

    /// Whether time stands still.
    #[getter]
    fn paused(&self) -> PyResult<bool> {
        Ok(self.game()?.paused())
    }

    #[setter]
    fn set_paused(&mut self, paused: bool) -> PyResult<()> {
        self.game_mut()?.set_paused(paused);
        Ok(())
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
    fn time_scale(&self) -> PyResult<f64> {
        Ok(self.game()?.time_scale())
    }

    #[setter]
    fn set_time_scale(&mut self, scale: f64) -> PyResult<()> {
        if !(scale.is_finite() && scale > 0.0 && scale <= 1e6) {
            return Err(PyValueError::new_err(format!(
                "time_scale = {scale}: give a number in (0, 1e6]"
            )));
        }
        self.game_mut()?.set_time_scale(scale);
        Ok(())
    }

    /// Which pictures: "seen", "truth" or "split".
    #[getter]
    fn view(&self) -> PyResult<&'static str> {
        Ok(match self.game()?.pictures() {
            Pictures::Seen => "seen",
            Pictures::Truth => "truth",
            Pictures::Split => "split",
        })
    }

    #[setter]
    fn set_view(&mut self, view: &str) -> PyResult<()> {
        let mode = match view {
            "seen" => Pictures::Seen,
            "truth" => Pictures::Truth,
            "split" => Pictures::Split,
            other => {
                return Err(PyValueError::new_err(format!(
                    "view {other:?}: use \"seen\", \"truth\" or \"split\""
                )));
            }
        };
        self.game_mut()?.set_pictures(mode);
        Ok(())
    }

    /// The scene observer whose eye is used, or None for the free eye.
    #[getter]
    fn observer(&self) -> PyResult<Option<String>> {
        let g = self.game()?;
        Ok(g.observer()
            .and_then(|i| g.scene().observers.get(i))
            .map(|o| o.name.clone()))
    }

    #[setter]
    fn set_observer(&mut self, name: Option<&str>) -> PyResult<()> {
        let g = self.game_mut()?;
        let observer = match name {
            None => None,
            Some(n) => Some(super::observer_index(g.scene(), Some(n))?),
        };
        g.set_observer(observer);
        Ok(())
    }

    /// The effects shown, as a dict of flags.
    #[getter]
    fn effects<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let g = self.game()?;
        let d = PyDict::new(py);
        for e in Effect::ALL {
            d.set_item(e.key(), g.effects().is_on(e))?;
        }
        Ok(d)
    }

    /// Turns an effect on or off in the student's view.
    fn set_effect(&mut self, name: &str, on: bool) -> PyResult<()> {
        let e = super::effect(name)?;
        self.game_mut()?.effects_mut().set(e, on);
        Ok(())
    }

    /// Every puck now: the `state` dict of `lightcone simulate`.
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let g = self.game()?;
        super::state(py, g.billiard(), g.live_time())
    }

    /// Every collision so far, as the dicts `lightcone simulate` prints.
    fn collisions<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        super::collisions(py, self.game()?.billiard())
    }

    /// The proper velocity γβ of puck `name` now, as (x, y).
    fn velocity(&self, name: &str) -> PyResult<(f64, f64)> {
        let g = self.game()?;
        super::velocity(g.billiard(), name, g.live_time())
    }

    /// Strikes puck `name` now: its proper velocity γβ (dimensionless)
    /// grows by `du` (two numbers: tuple, list or array).
    fn impulse(&mut self, name: &str, du: super::convert::Vector<2>) -> PyResult<()> {
        let g = self.game_mut()?;
        let t = g.live_time();
        super::impulse(g.billiard_mut(), name, t, du.pair())
    }

    /// What `observer` (default: the first scene observer) sees at board
    /// time `at` s (default: now; `t` is the older name), as the dict
    /// `lightcone observe` prints. `effects`: None for those shown, or a
    /// list of effect names. A time after now raises NotComputedError.
    #[pyo3(signature = (observer = None, t = None, vertices = false, effects = None, at = None))]
    fn observe<'py>(
        &self,
        py: Python<'py>,
        observer: Option<&str>,
        t: Option<f64>,
        vertices: bool,
        effects: Option<Vec<String>>,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let g = self.game()?;
        if t.is_some() && at.is_some() {
            return Err(PyValueError::new_err("observe: give at or t, not both"));
        }
        let t = super::past_time(at.or(t), g.live_time())?;
        let fx = super::effects_from(g.effects(), effects)?;
        super::observation(py, g.scene(), g.billiard(), t, observer, vertices, fx)
    }

    /// The space-time diagram for `observer` (default: the first scene
    /// observer) at board time `at` (default: now), as a `Frame` (see
    /// `Simulation.diagram`); `frame`: a puck whose lines of simultaneity
    /// to draw. With `path` (relative to the lesson), also saved.
    #[pyo3(signature = (path = None, observer = None, size = (1000, 700), at = None, axis = "x", frame = None))]
    #[allow(clippy::too_many_arguments)]
    fn diagram(
        &self,
        path: Option<PathBuf>,
        observer: Option<&str>,
        size: (u32, u32),
        at: Option<f64>,
        axis: &str,
        frame: Option<&str>,
    ) -> PyResult<super::Frame> {
        let g = self.game()?;
        let t = super::past_time(at, g.live_time())?;
        let path = path.map(|p| self.dir.join(p));
        super::diagram::diagram_frame(
            g.scene(),
            g.billiard(),
            t,
            observer,
            size,
            axis,
            frame,
            path,
        )
    }

    /// Opens (`on`) or closes the live space-time diagram in the window,
    /// drawing puck `frame`'s lines of simultaneity (None: only the
    /// board's), with board `axis` "x" or "y" across. Headless, it only
    /// records the choice.
    #[pyo3(signature = (on = true, frame = None, axis = "x"))]
    fn show_diagram(&mut self, on: bool, frame: Option<&str>, axis: &str) -> PyResult<()> {
        let axis = lightcone_render::diagram::Axis::parse(axis).map_err(PyValueError::new_err)?;
        let g = self.game_mut()?;
        let frame = frame
            .map(|f| super::puck_index(g.billiard(), f))
            .transpose()?;
        g.set_diagram(on, frame, axis);
        Ok(())
    }

    /// The line of simultaneity of puck `frame`'s rest frame through its
    /// event at board time `at` (default: now): see
    /// `Simulation.simultaneity`.
    #[pyo3(signature = (frame, at = None))]
    fn simultaneity<'py>(
        &self,
        py: Python<'py>,
        frame: &str,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let g = self.game()?;
        let t = super::past_time(at, g.live_time())?;
        super::diagram::simultaneity(py, g.scene(), g.billiard(), frame, t)
    }

    /// Shows `text` as the lesson's message: replacing the previous one,
    /// or with `append=True` as a new line after it.
    #[pyo3(signature = (text, append = false))]
    fn say(&mut self, text: &str, append: bool) {
        if append && !self.ui.text.is_empty() {
            self.ui.text.push('\n');
            self.ui.text.push_str(text);
        } else {
            self.ui.text = text.to_owned();
        }
    }

    /// Asks the student a question with `choices` (buttons) and pauses
    /// until they answer; `on_answer(world, question, choice)` then runs.
    /// `answer`: index of the right choice, to tell the student.
    #[pyo3(signature = (question, choices, answer = None))]
    fn ask(&mut self, question: &str, choices: Vec<String>, answer: Option<usize>) -> PyResult<()> {
        if choices.is_empty() {
            return Err(PyValueError::new_err("ask: give at least one choice"));
        }
        if let Some(a) = answer
            && a >= choices.len()
        {
            return Err(PyValueError::new_err(format!(
                "ask: answer {a} is not a choice index (0 to {})",
                choices.len() - 1
            )));
        }
        // A question asked over an unanswered one inherits its promise to
        // resume.
        let open = self
            .ui
            .question
            .as_ref()
            .is_some_and(|q| q.chosen.is_none() && q.resume);
        let g = self.game_mut()?;
        let resume = !g.paused() || open;
        g.set_paused(true);
        self.ui.question = Some(Question {
            text: question.to_owned(),
            choices,
            answer,
            chosen: None,
            resume,
        });
        Ok(())
    }

    /// Records a physics claim: shown as ✓/✗ with `detail`; a false claim
    /// fails the headless lesson run. Returns `ok`.
    #[pyo3(signature = (claim, ok, detail = ""))]
    fn check(&mut self, claim: &str, ok: bool, detail: &str) -> PyResult<bool> {
        if self.ui.claims.len() >= MAX_CLAIMS {
            return Err(PyValueError::new_err(format!(
                "world.check: a lesson may check at most {MAX_CLAIMS} claims; this is one more"
            )));
        }
        if claim.len().max(detail.len()) > MAX_CLAIM_BYTES {
            return Err(PyValueError::new_err(format!(
                "world.check: a claim or its detail of {} bytes; give at most {MAX_CLAIM_BYTES}",
                claim.len().max(detail.len())
            )));
        }
        let made = Claim {
            claim: claim.to_owned(),
            ok,
            detail: detail.to_owned(),
        };
        if let Some(f) = CLAIM_OBSERVER.get() {
            f(&made);
        }
        self.ui.claims.push(made);
        Ok(ok)
    }

    /// The claims checked so far, as (claim, ok, detail) tuples.
    #[getter]
    fn claims(&self) -> Vec<(String, bool, String)> {
        self.ui
            .claims
            .iter()
            .map(|c| (c.claim.clone(), c.ok, c.detail.clone()))
            .collect()
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
        if edges.len() != counts.len() + 1 || counts.is_empty() {
            return Err(PyValueError::new_err(format!(
                "bars {title:?}: {} edges for {} counts; give one more edge than counts",
                edges.len(),
                counts.len()
            )));
        }
        if expected.as_ref().is_some_and(|e| e.len() != counts.len()) {
            return Err(PyValueError::new_err(format!(
                "bars {title:?}: expected has a different length from counts"
            )));
        }
        let all = edges.iter().chain(&counts).chain(expected.iter().flatten());
        if all.clone().any(|x| !x.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "bars {title:?}: every number must be finite"
            )));
        }
        if counts.len() > MAX_BINS {
            return Err(PyValueError::new_err(format!(
                "bars {title:?}: {} bins; give at most {MAX_BINS}",
                counts.len()
            )));
        }
        if title.len() > MAX_CLAIM_BYTES {
            return Err(PyValueError::new_err(format!(
                "bars: a title of {} bytes; give at most {MAX_CLAIM_BYTES}",
                title.len()
            )));
        }
        if self.ui.bars.len() >= MAX_CHARTS && !self.ui.bars.iter().any(|b| b.title == title) {
            return Err(PyValueError::new_err(format!(
                "bars {title:?}: a lesson may show at most {MAX_CHARTS} charts (one per title)"
            )));
        }
        let chart = Bars {
            title: title.to_owned(),
            edges,
            counts,
            expected,
        };
        match self.ui.bars.iter_mut().find(|b| b.title == title) {
            Some(b) => *b = chart,
            None => self.ui.bars.push(chart),
        }
        Ok(())
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
        let light = match after_light_from {
            None => None,
            Some(v) => {
                let (t, x, y) = v.triple();
                if !(t.is_finite() && x.is_finite() && y.is_finite()) {
                    return Err(PyValueError::new_err(format!(
                        "finish: after_light_from = ({t}, {x}, {y}): give a board event (t s, x m, y m) of finite numbers"
                    )));
                }
                let at = glam::DVec3::new(x, y, 0.0);
                Some(lightcone_engine::spacetime::Event::new(t, at))
            }
        };
        self.ui.finished = Some(message.to_owned());
        self.ui.finish_light = light;
        Ok(())
    }

    /// Whether `finish` was called (then no further hook will run).
    #[getter]
    fn finished(&self) -> bool {
        self.ui.finished.is_some()
    }

    fn __repr__(&self) -> String {
        match &self.game {
            Some(g) => format!(
                "World({:?}, t = {:.3} s, {} pucks)",
                g.scene().title,
                g.live_time(),
                g.billiard().len()
            ),
            None => "World(no game)".to_owned(),
        }
    }
}
