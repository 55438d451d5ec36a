//! The world a lesson's hooks are given, without Python: the running game
//! (board time, pucks, effects, view) and the lesson's voice on screen,
//! with every operation checked. Python's `lightcone.World` wraps a
//! [`WorldCore`]; the protocol's server (`crate::protocol`) answers a
//! lesson run elsewhere with the same operations.
//!
//! The world does not own the game: the game stays with its host (the
//! window's or the page's game, a headless run's), and each call borrows
//! it ([`WorldCore::on`] makes the [`WorldCall`] for one request or one
//! hook), so a lesson acts on exactly what the student sees and the host
//! never hands its game over.

use std::path::PathBuf;

use lightcone_engine::report::{CollisionLine, ObserveReport, StateLine};
use lightcone_engine::scene::{Effect, Scene};
use lightcone_engine::spacetime::Event;

use crate::error::{ErrorKind, WorldError, WorldResult};
use crate::query::{self, SimultaneityLine};
use crate::{Bars, Claim, LessonGame, LessonUi, MAX_BINS, MAX_CHARTS, MAX_CLAIM_BYTES, MAX_CLAIMS};
use crate::{MAX_CHOICES, MAX_TEXT_BYTES};
use crate::{Pictures, Question};

/// What a lesson's world keeps between calls: what it shows, whether it
/// has started a game, and its directory.
pub struct WorldCore {
    /// What the lesson shows.
    pub ui: LessonUi,
    /// Bumped by `start`, so the host knows the collision list restarted;
    /// 0 until the lesson's first `world.start(scene)` (until then the
    /// world has no game to speak of).
    pub generation: u64,
    /// The lesson file's directory, to resolve relative paths.
    pub dir: PathBuf,
}

/// The world for one call (a request, or a hook run in this process):
/// the lesson's [`WorldCore`] and the game it acts on, borrowed from the
/// game's host for that call. Every world operation is a method of it.
pub struct WorldCall<'a> {
    core: &'a mut WorldCore,
    /// The host's game (`None`: the world is used where there is none,
    /// outside a hook).
    game: Option<&'a mut (dyn LessonGame + 'static)>,
}

/// The message of the error every game operation gives outside a hook.
pub const NO_GAME: &str = "the world has no game here: call world.start(scene) in setup(world), and use the world only inside a hook";

fn no_game() -> WorldError {
    WorldError::new(ErrorKind::Runtime, NO_GAME)
}

impl WorldCore {
    /// A world with no game yet, for the lesson in directory `dir`.
    #[must_use]
    pub fn new(dir: PathBuf) -> Self {
        Self {
            ui: LessonUi::default(),
            generation: 0,
            dir,
        }
    }

    /// The world for one call on `game`, the host's (in `setup`, the game
    /// the lesson is building: `world.start` starts it on its scene).
    /// `None`: there is no game here (game operations say so).
    pub fn on<'a>(&'a mut self, game: Option<&'a mut (dyn LessonGame + 'static)>) -> WorldCall<'a> {
        WorldCall { core: self, game }
    }

    /// Whether the lesson has started a game (`world.start`).
    #[must_use]
    pub fn started(&self) -> bool {
        self.generation > 0
    }

    /// The claims checked so far, as (claim, ok, detail).
    #[must_use]
    pub fn claims(&self) -> Vec<(String, bool, String)> {
        self.ui
            .claims
            .iter()
            .map(|c| (c.claim.clone(), c.ok, c.detail.clone()))
            .collect()
    }

    /// Whether `finish` was called (then no further hook will run).
    #[must_use]
    pub fn finished(&self) -> bool {
        self.ui.finished.is_some()
    }
}

impl std::ops::Deref for WorldCall<'_> {
    type Target = WorldCore;
    fn deref(&self) -> &WorldCore {
        self.core
    }
}

impl std::ops::DerefMut for WorldCall<'_> {
    fn deref_mut(&mut self) -> &mut WorldCore {
        self.core
    }
}

impl WorldCall<'_> {
    /// The game, or why there is none (outside a hook, or before
    /// `world.start`).
    pub fn game(&self) -> WorldResult<&dyn LessonGame> {
        match &self.game {
            Some(g) if self.core.started() => Ok(&**g),
            _ => Err(no_game()),
        }
    }

    /// The game to change, or why there is none.
    pub fn game_mut(&mut self) -> WorldResult<&mut dyn LessonGame> {
        let started = self.core.started();
        match &mut self.game {
            Some(g) if started => Ok(&mut **g),
            _ => Err(no_game()),
        }
    }

    /// Starts (or restarts) the game on `scene` at board time 0. A
    /// restart keeps the view, eye choice and time scale the student had.
    pub fn start(&mut self, scene: Scene) -> WorldResult<()> {
        let restart = self.core.started();
        let g = self.game.as_deref_mut().ok_or_else(no_game)?;
        let kept = restart.then(|| (g.pictures(), g.time_scale(), g.observer()));
        g.restart(scene);
        if let Some((pictures, scale, observer)) = kept {
            g.set_pictures(pictures);
            g.set_time_scale(scale);
            if observer.is_some_and(|i| i < g.scene().observers.len()) {
                g.set_observer(observer);
            }
        }
        self.core.generation += 1;
        Ok(())
    }

    /// Loads a scene file; a relative path is taken from the lesson's
    /// directory. A scene error names the file, line and field.
    pub fn load(&self, path: PathBuf) -> WorldResult<Scene> {
        let path = if path.is_relative() {
            self.dir.join(path)
        } else {
            path
        };
        Ok(lightcone_engine::scene::load(&path)?)
    }

    /// Board time the physics has reached, s.
    pub fn t(&self) -> WorldResult<f64> {
        Ok(self.game()?.live_time())
    }

    /// Speed of light, m/s.
    pub fn c(&self) -> WorldResult<f64> {
        Ok(self.game()?.scene().c)
    }

    /// Whether time stands still.
    pub fn paused(&self) -> WorldResult<bool> {
        Ok(self.game()?.paused())
    }

    /// Stops (`true`) or restarts time.
    pub fn set_paused(&mut self, paused: bool) -> WorldResult<()> {
        self.game_mut()?.set_paused(paused);
        Ok(())
    }

    /// Board seconds per real second.
    pub fn time_scale(&self) -> WorldResult<f64> {
        Ok(self.game()?.time_scale())
    }

    /// Sets board seconds per real second, in (0, 10⁶].
    pub fn set_time_scale(&mut self, scale: f64) -> WorldResult<()> {
        if !(scale.is_finite() && scale > 0.0 && scale <= 1e6) {
            return Err(WorldError::value(format!(
                "time_scale = {scale}: give a number in (0, 1e6]"
            )));
        }
        self.game_mut()?.set_time_scale(scale);
        Ok(())
    }

    /// Which pictures: "seen", "truth" or "split".
    pub fn view(&self) -> WorldResult<&'static str> {
        Ok(self.game()?.pictures().name())
    }

    /// Chooses the pictures by name (see [`Self::view`]).
    pub fn set_view(&mut self, view: &str) -> WorldResult<()> {
        let mode = Pictures::named(view).ok_or_else(|| {
            WorldError::value(format!(
                "view {view:?}: use \"seen\", \"truth\" or \"split\""
            ))
        })?;
        self.game_mut()?.set_pictures(mode);
        Ok(())
    }

    /// The scene observer whose eye is used, or `None` for the free eye.
    pub fn observer(&self) -> WorldResult<Option<String>> {
        let g = self.game()?;
        Ok(g.observer()
            .and_then(|i| g.scene().observers.get(i))
            .map(|o| o.name.clone()))
    }

    /// Chooses the eye: a scene observer by name, or `None` for the free eye.
    pub fn set_observer(&mut self, name: Option<&str>) -> WorldResult<()> {
        let g = self.game_mut()?;
        let observer = match name {
            None => None,
            Some(n) => Some(query::observer_index(g.scene(), Some(n))?),
        };
        g.set_observer(observer);
        Ok(())
    }

    /// The effects shown: each effect's key and whether it is on.
    pub fn effects(&self) -> WorldResult<Vec<(&'static str, bool)>> {
        let shown = self.game()?.effects();
        Ok(Effect::ALL
            .iter()
            .map(|e| (e.key(), shown.is_on(*e)))
            .collect())
    }

    /// Turns an effect on or off in the student's view.
    pub fn set_effect(&mut self, name: &str, on: bool) -> WorldResult<()> {
        let e = query::effect(name)?;
        self.game_mut()?.effects_mut().set(e, on);
        Ok(())
    }

    /// Every puck now: the `state` record of `lightcone simulate`.
    pub fn state(&self) -> WorldResult<StateLine> {
        let g = self.game()?;
        Ok(StateLine::new(g.billiard(), g.live_time()))
    }

    /// Every collision so far, as the records `lightcone simulate` prints.
    pub fn collisions(&self) -> WorldResult<Vec<CollisionLine>> {
        let b = self.game()?.billiard();
        Ok(b.collisions()
            .iter()
            .map(|c| CollisionLine::new(b, c))
            .collect())
    }

    /// The proper velocity γβ of puck `name` now, (x, y).
    pub fn velocity(&self, name: &str) -> WorldResult<(f64, f64)> {
        let g = self.game()?;
        query::velocity(g.billiard(), name, g.live_time())
    }

    /// Strikes puck `name` now: its proper velocity γβ grows by `du`.
    pub fn impulse(&mut self, name: &str, du: (f64, f64)) -> WorldResult<()> {
        let g = self.game_mut()?;
        let t = g.live_time();
        query::impulse(g.billiard_mut(), name, t, du)
    }

    /// What `observer` (default: the first scene observer) sees at board
    /// time `at` (default: now; `t` is the older name): the report
    /// `lightcone observe` prints. `effects`: `None` for those shown, or
    /// effect keys. A time after now is a `NotComputed` error.
    pub fn observe(
        &self,
        observer: Option<&str>,
        t: Option<f64>,
        vertices: bool,
        effects: Option<Vec<String>>,
        at: Option<f64>,
    ) -> WorldResult<ObserveReport> {
        let g = self.game()?;
        if t.is_some() && at.is_some() {
            return Err(WorldError::value("observe: give at or t, not both"));
        }
        let t = query::past_time(at.or(t), g.live_time())?;
        let fx = query::effects_from(g.effects(), effects)?;
        query::observation(g.scene(), g.billiard(), t, observer, vertices, fx)
    }

    /// The space-time diagram at board time `at` (default: now) and that
    /// time (see [`query::diagram`]).
    pub fn diagram(
        &self,
        observer: Option<&str>,
        size: (u32, u32),
        at: Option<f64>,
        axis: &str,
        frame: Option<&str>,
    ) -> WorldResult<(lightcone_render::headless::Image, f64)> {
        let g = self.game()?;
        let t = query::past_time(at, g.live_time())?;
        let image = query::diagram(g.scene(), g.billiard(), t, observer, size, axis, frame)?;
        Ok((image, t))
    }

    /// Opens (`on`) or closes the live space-time diagram, drawing puck
    /// `frame`'s lines of simultaneity (`None`: only the board's), with
    /// board `axis` "x" or "y" across.
    pub fn show_diagram(&mut self, on: bool, frame: Option<&str>, axis: &str) -> WorldResult<()> {
        let axis = lightcone_render::diagram::Axis::parse(axis).map_err(WorldError::value)?;
        let g = self.game_mut()?;
        let frame = frame
            .map(|f| query::puck_index(g.billiard(), f))
            .transpose()?;
        g.set_diagram(on, frame, axis);
        Ok(())
    }

    /// The line of simultaneity of puck `frame`'s rest frame through its
    /// event at board time `at` (default: now).
    pub fn simultaneity(&self, frame: &str, at: Option<f64>) -> WorldResult<SimultaneityLine> {
        let g = self.game()?;
        let t = query::past_time(at, g.live_time())?;
        query::simultaneity(g.scene(), g.billiard(), frame, t)
    }

    /// Shows `text` as the lesson's message: replacing the previous one,
    /// or with `append` as a new line after it. Refused past
    /// [`MAX_TEXT_BYTES`] in all.
    pub fn say(&mut self, text: &str, append: bool) -> WorldResult<()> {
        let append = append && !self.ui.text.is_empty();
        let total = text.len() + if append { self.ui.text.len() + 1 } else { 0 };
        if total > MAX_TEXT_BYTES {
            return Err(WorldError::value(format!(
                "world.say: the lesson's message would be {total} bytes; at most {MAX_TEXT_BYTES} are shown"
            )));
        }
        if append {
            self.ui.text.push('\n');
            self.ui.text.push_str(text);
        } else {
            self.ui.text = text.to_owned();
        }
        Ok(())
    }

    /// Asks the student a question with `choices` and pauses until they
    /// answer. `answer`: index of the right choice.
    pub fn ask(
        &mut self,
        question: &str,
        choices: Vec<String>,
        answer: Option<usize>,
    ) -> WorldResult<()> {
        if choices.is_empty() {
            return Err(WorldError::value("ask: give at least one choice"));
        }
        if choices.len() > MAX_CHOICES {
            return Err(WorldError::value(format!(
                "ask: {} choices; give at most {MAX_CHOICES}",
                choices.len()
            )));
        }
        let longest = choices
            .iter()
            .map(String::len)
            .chain([question.len()])
            .max();
        if longest.is_some_and(|n| n > MAX_CLAIM_BYTES) {
            return Err(WorldError::value(format!(
                "ask: a question or choice of more than {MAX_CLAIM_BYTES} bytes"
            )));
        }
        if let Some(a) = answer
            && a >= choices.len()
        {
            return Err(WorldError::value(format!(
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

    /// Records a physics claim, shown as ✓/✗ with `detail`; returns it.
    pub fn check(&mut self, claim: &str, ok: bool, detail: &str) -> WorldResult<Claim> {
        if self.ui.claims.len() >= MAX_CLAIMS {
            return Err(WorldError::value(format!(
                "world.check: a lesson may check at most {MAX_CLAIMS} claims; this is one more"
            )));
        }
        if claim.len().max(detail.len()) > MAX_CLAIM_BYTES {
            return Err(WorldError::value(format!(
                "world.check: a claim or its detail of {} bytes; give at most {MAX_CLAIM_BYTES}",
                claim.len().max(detail.len())
            )));
        }
        let made = Claim {
            claim: claim.to_owned(),
            ok,
            detail: detail.to_owned(),
        };
        self.ui.claims.push(made.clone());
        Ok(made)
    }

    /// Draws a bar chart: `counts` over bins with `edges` (one more edge
    /// than counts), with `expected` per bin drawn as a line.
    pub fn bars(
        &mut self,
        title: &str,
        edges: Vec<f64>,
        counts: Vec<f64>,
        expected: Option<Vec<f64>>,
    ) -> WorldResult<()> {
        if edges.len() != counts.len() + 1 || counts.is_empty() {
            return Err(WorldError::value(format!(
                "bars {title:?}: {} edges for {} counts; give one more edge than counts",
                edges.len(),
                counts.len()
            )));
        }
        if expected.as_ref().is_some_and(|e| e.len() != counts.len()) {
            return Err(WorldError::value(format!(
                "bars {title:?}: expected has a different length from counts"
            )));
        }
        let all = edges.iter().chain(&counts).chain(expected.iter().flatten());
        if all.clone().any(|x| !x.is_finite()) {
            return Err(WorldError::value(format!(
                "bars {title:?}: every number must be finite"
            )));
        }
        if counts.len() > MAX_BINS {
            return Err(WorldError::value(format!(
                "bars {title:?}: {} bins; give at most {MAX_BINS}",
                counts.len()
            )));
        }
        if title.len() > MAX_CLAIM_BYTES {
            return Err(WorldError::value(format!(
                "bars: a title of {} bytes; give at most {MAX_CLAIM_BYTES}",
                title.len()
            )));
        }
        if self.ui.bars.len() >= MAX_CHARTS && !self.ui.bars.iter().any(|b| b.title == title) {
            return Err(WorldError::value(format!(
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

    /// Ends the lesson with a closing `message`: no hook runs again, and
    /// the message is shown at once or, with `after_light_from = (t, x,
    /// y)` (a board event: s, m), once that event's light has reached the
    /// eye looked through.
    pub fn finish(
        &mut self,
        message: &str,
        after_light_from: Option<(f64, f64, f64)>,
    ) -> WorldResult<()> {
        if message.len() > MAX_TEXT_BYTES {
            return Err(WorldError::value(format!(
                "finish: a message of {} bytes; give at most {MAX_TEXT_BYTES}",
                message.len()
            )));
        }
        let light = match after_light_from {
            None => None,
            Some((t, x, y)) => {
                if !(t.is_finite() && x.is_finite() && y.is_finite()) {
                    return Err(WorldError::value(format!(
                        "finish: after_light_from = ({t}, {x}, {y}): give a board event (t s, x m, y m) of finite numbers"
                    )));
                }
                Some(Event::new(t, glam::DVec3::new(x, y, 0.0)))
            }
        };
        self.ui.finished = Some(message.to_owned());
        self.ui.finish_light = light;
        Ok(())
    }

    /// `World(title, t = …, n pucks)`, or `World(no game)`.
    #[must_use]
    pub fn describe(&self) -> String {
        match self.game() {
            Ok(g) => format!(
                "World({:?}, t = {:.3} s, {} pucks)",
                g.scene().title,
                g.live_time(),
                g.billiard().len()
            ),
            Err(_) => "World(no game)".to_owned(),
        }
    }
}

/// `text` cut to at most `max` bytes (at a character's boundary), with
/// "…" when cut: for what a lesson sends that the game shows (a
/// traceback, a printed line), whatever its length.
#[must_use]
pub fn cut(text: &str, max: usize) -> String {
    if text.len() <= max {
        return text.to_owned();
    }
    let mut end = max;
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    format!("{}…", &text[..end])
}
