//! Running a lesson without a window: the same host and game as `play`,
//! stepped at a fixed frame rate, with questions answered automatically
//! (the lesson's right answer, else the first choice). This is how the
//! tests check that every lesson's physics claims hold.

use std::ops::DerefMut;
use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{LessonHost, LessonState, LocalLesson};
use crate::model::GameState;

/// A lesson as a run without a student drives it: in this process
/// ([`LocalLesson`], which owns its game) or in its own ([`Isolated`]:
/// the window's host and the game it serves, each hook waited for).
pub trait Driven {
    /// The lesson's screen, error and finish.
    fn lesson(&self) -> &LessonState;
    /// Whether its hooks run.
    fn running(&self) -> bool;
    /// The game it runs on.
    fn game(&mut self) -> impl DerefMut<Target = GameState> + '_;
    /// Answers the open question with choice `i`, `on_answer` run to its end.
    fn answer(&mut self, i: usize);
    /// The hooks of a step from board time `before`, run to their end.
    fn after_step(&mut self, before: f64);
    /// Whether the closing message is shown (its light has arrived).
    fn watch_light(&mut self) -> bool;
}

impl Driven for LocalLesson {
    fn lesson(&self) -> &LessonState {
        self
    }
    fn running(&self) -> bool {
        LocalLesson::running(self)
    }
    fn game(&mut self) -> impl DerefMut<Target = GameState> + '_ {
        LocalLesson::game(self)
    }
    fn answer(&mut self, i: usize) {
        LocalLesson::answer(self, i);
    }
    fn after_step(&mut self, before: f64) {
        LocalLesson::after_step(self, before);
    }
    fn watch_light(&mut self) -> bool {
        LocalLesson::watch_light(self)
    }
}

/// The window's host and the game it serves, driven as a headless run
/// drives a lesson: each hook waited for.
pub struct Isolated<'a> {
    /// The host, its lesson in its own process.
    pub host: &'a mut LessonHost,
    /// The game (the caller's).
    pub game: &'a mut GameState,
}

impl Driven for Isolated<'_> {
    fn lesson(&self) -> &LessonState {
        self.host
    }
    fn running(&self) -> bool {
        self.host.running()
    }
    fn game(&mut self) -> impl DerefMut<Target = GameState> + '_ {
        &mut *self.game
    }
    fn answer(&mut self, i: usize) {
        self.host.answer(self.game, i);
        self.host.settle(self.game);
    }
    fn after_step(&mut self, before: f64) {
        self.host.after_step(self.game, before);
        self.host.settle(self.game);
    }
    fn watch_light(&mut self) -> bool {
        self.host.watch_light(self.game)
    }
}

/// A claim as the run reports it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct ClaimLine {
    /// What was claimed.
    pub claim: String,
    /// Whether it held.
    pub ok: bool,
    /// The numbers behind it.
    pub detail: String,
}

/// How a headless run ended.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Outcome {
    /// The lesson file.
    pub file: String,
    /// Board time reached, s.
    pub t: f64,
    /// Frames stepped.
    pub frames: u64,
    /// The closing message, if the lesson called `finish`.
    pub finished: Option<String>,
    /// The traceback or message that stopped the lesson, if any.
    pub error: Option<String>,
    /// Why the host stopped the lesson, if it did: [`Stop::Timeout`] (a
    /// hook over its time limit) or [`Stop::Died`] (the lesson's process
    /// ended: `os._exit` through a loophole, a crash, out of memory).
    pub stopped: Option<Stop>,
    /// Every claim checked, in order.
    pub claims: Vec<ClaimLine>,
    /// Questions asked and the choices given, in order.
    pub answers: Vec<(String, String)>,
}

/// Why the host stopped a lesson.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// A hook ran past its time limit.
    Timeout,
    /// The lesson's process ended or crashed.
    Died,
}

impl Outcome {
    /// No error, and no claim failed.
    pub fn passed(&self) -> bool {
        self.error.is_none() && self.claims.iter().all(|c| c.ok)
    }

    /// The exit status `lightcone lesson` gives this outcome: 0 passed, 1
    /// a claim failed or the lesson raised, 3 a hook was stopped at its
    /// time limit, 4 the lesson's process died.
    pub fn status(&self) -> u8 {
        match (self.stopped, self.passed()) {
            (Some(Stop::Timeout), _) => 3,
            (Some(Stop::Died), _) => 4,
            (None, true) => 0,
            (None, false) => 1,
        }
    }
}

/// What a run reports as it goes (to the parent of a child run, see
/// [`super::supervise`]).
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Progress {
    /// A frame was stepped: board time, frames so far.
    Frame {
        /// Board time, s.
        t: f64,
        /// Frames stepped.
        frames: u64,
    },
    /// A new claim was checked.
    Claim(ClaimLine),
    /// A question was answered.
    Answer(String, String),
}

/// Tells `report` of the claims made since the first `seen`.
fn new_claims(host: &LessonState, seen: &mut usize, report: &mut dyn FnMut(Progress)) {
    let new: Vec<ClaimLine> = host.with_ui(|ui| {
        ui.claims
            .iter()
            .skip(*seen)
            .map(|c| ClaimLine {
                claim: c.claim.clone(),
                ok: c.ok,
                detail: c.detail.clone(),
            })
            .collect()
    });
    *seen += new.len();
    for c in new {
        report(Progress::Claim(c));
    }
}

/// Runs the lesson at `path` until it calls `finish` (and, when its
/// closing message waits for an event's light, until that light reaches
/// the eye), fails, or board time passes `until`, stepping `1 / fps` real seconds a frame; a hook running
/// longer than `hook_limit` is stopped with TimeoutError.
pub fn run(
    path: &Path,
    until: f64,
    fps: f64,
    hook_limit: std::time::Duration,
) -> Result<Outcome, String> {
    run_reporting(path, until, fps, hook_limit, &mut |_| {})
}

/// [`run`], telling `report` of each frame, claim and answer as it comes.
pub fn run_reporting(
    path: &Path,
    until: f64,
    fps: f64,
    hook_limit: std::time::Duration,
    report: &mut dyn FnMut(Progress),
) -> Result<Outcome, String> {
    if !(until.is_finite() && until >= 0.0) {
        return Err(format!("--until {until}: give a board time ≥ 0"));
    }
    if !(fps.is_finite() && fps > 0.0) {
        return Err(format!("--fps {fps}: give a positive frame rate"));
    }
    // Headless, a lesson that fails before starting a game needs no table.
    let mut lesson = LocalLesson::load_with_limit(path, hook_limit, super::empty_game)?;
    Ok(drive(path, &mut lesson, until, fps, report))
}

/// [`run`] with the lesson in its own process, as the window runs it
/// ([`super::remote`]), each hook waited for: the same outcome as [`run`]
/// for a lesson that behaves (the tests compare them).
pub fn run_isolated(
    path: &Path,
    until: f64,
    fps: f64,
    hook_limit: std::time::Duration,
    isolation: super::isolation::Isolation,
) -> Result<Outcome, String> {
    let (mut host, mut game) =
        LessonHost::load_isolated_with_limit(path, hook_limit, super::empty_game, isolation)?;
    let mut lesson = Isolated {
        host: &mut host,
        game: &mut game,
    };
    Ok(drive(path, &mut lesson, until, fps, &mut |_| {}))
}

/// Steps the lesson's game and runs its hooks until it finishes, fails,
/// or board time reaches `until`.
fn drive(
    path: &Path,
    host: &mut impl Driven,
    until: f64,
    fps: f64,
    report: &mut dyn FnMut(Progress),
) -> Outcome {
    let mut frames = 0u64;
    let mut answers = Vec::new();
    let mut claims_seen = 0;
    new_claims(host.lesson(), &mut claims_seen, report);
    // Enough frames for `until` at any time scale the lesson sets, with a
    // hard cap against a lesson that pauses forever.
    let max_frames = 10_000_000u64;
    // Ctrl-C (`crate::interrupt`) stops between frames.
    // A closing message that waits for an event's light (`finish(after_light_from=…)`)
    // keeps board time running until that light reaches the eye: the
    // run ends when the student would see it.
    host.watch_light();
    while (host.running() || host.lesson().awaiting_light())
        && frames < max_frames
        && !crate::interrupt::interrupted()
    {
        let turned = turn(host, fps, until, &mut |t| {
            frames += 1;
            // Before the hooks: should one of them take the process down,
            // the parent knows the frame was reached.
            report(Progress::Frame { t, frames });
        });
        match turned {
            Turn::Finished | Turn::Reached => break,
            Turn::Answered(text, choice) => {
                report(Progress::Answer(text.clone(), choice.clone()));
                answers.push((text, choice));
            }
            Turn::Stepped => {}
        }
        new_claims(host.lesson(), &mut claims_seen, report);
    }
    let t = host.game().live_time;
    let lesson = host.lesson();
    let (claims, finished) = lesson.with_ui(|ui| {
        (
            ui.claims
                .iter()
                .map(|c| ClaimLine {
                    claim: c.claim.clone(),
                    ok: c.ok,
                    detail: c.detail.clone(),
                })
                .collect(),
            ui.finished.clone(),
        )
    });
    Outcome {
        file: path.display().to_string(),
        t,
        frames,
        finished,
        error: lesson.error.clone(),
        stopped: (lesson.error.is_some() && lesson.timed_out).then_some(Stop::Timeout),
        claims,
        answers,
    }
}

/// What one turn of a lesson run without a student did.
pub enum Turn {
    /// The lesson has finished (its closing message is up): nothing done.
    Finished,
    /// Board time had reached the end asked for: nothing done.
    Reached,
    /// The open question was answered with the lesson's own answer (the
    /// first choice when it names none): its text and the choice's.
    Answered(String, String),
    /// Board time moved one frame (`1 / fps` real seconds) and the hooks
    /// that frame raised ran to their end.
    Stepped,
}

/// One turn of a lesson with nobody at the window: answers its open
/// question, or, before board time `until`, presses play and steps one
/// frame; `stepped(t)` hears the frame's board time before its hooks run.
pub fn turn(host: &mut impl Driven, fps: f64, until: f64, stepped: &mut dyn FnMut(f64)) -> Turn {
    let (finished, question) = host.lesson().with_ui(|ui| {
        let q = ui.open_question().map(|q| {
            let i = q.lessons_own();
            (q.text.clone(), q.choices[i].clone(), i)
        });
        (ui.closing().is_some(), q)
    });
    if finished {
        return Turn::Finished;
    }
    if let Some((text, choice, i)) = question {
        host.answer(i);
        return Turn::Answered(text, choice);
    }
    let (before, now) = {
        let mut game = host.game();
        if game.live_time >= until {
            return Turn::Reached;
        }
        game.paused = false;
        let before = game.live_time;
        game.step(1.0 / fps);
        (before, game.live_time)
    };
    stepped(now);
    host.after_step(before);
    host.watch_light();
    Turn::Stepped
}

/// Frames a lesson may go without moving board time while it is run to a
/// time (`render`, `record`): 10 minutes at 60 frames a second.
const STILL_FRAMES: u32 = 36_000;

/// Runs the lesson `host` and its game to board time `t` (s), as the
/// window would with a student who gives the lesson's own answers, at 60
/// frames a real second: the hooks run, questions are answered, and once
/// the lesson has finished (or failed: its error is on `host`) the board
/// goes on without it. Returns at the first frame at or past `t`, or an
/// error when board time stands still for `STILL_FRAMES` frames (the
/// lesson paused it, or set no time scale) or Ctrl-C is pressed.
pub fn run_to(host: &mut impl Driven, t: f64) -> Result<(), String> {
    const FPS: f64 = 60.0;
    let mut still = 0u32;
    while host.game().live_time < t {
        if crate::interrupt::interrupted() {
            return Err("interrupted".to_owned());
        }
        let before = host.game().live_time;
        let lesson_on = host.running() || host.lesson().awaiting_light();
        let turned = if lesson_on {
            turn(host, FPS, t, &mut |_| {})
        } else {
            Turn::Finished
        };
        let mut game = host.game();
        if matches!(turned, Turn::Finished) {
            game.paused = false;
            game.step(1.0 / FPS);
        }
        if game.live_time > before {
            still = 0;
        } else {
            still += 1;
            if still >= STILL_FRAMES {
                return Err(format!(
                    "the lesson's board time stands still at {:.3} s (paused, or a time scale of 0), \
                     before {t} s",
                    game.live_time
                ));
            }
        }
    }
    let mut game = host.game();
    game.view_time = game.live_time;
    Ok(())
}
