//! Running a lesson without a window: the same host and game as `play`,
//! stepped at a fixed frame rate, with questions answered automatically
//! (the lesson's right answer, else the first choice). This is how the
//! tests check that every lesson's physics claims hold.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::LessonHost;

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
fn new_claims(host: &LessonHost, seen: &mut usize, report: &mut dyn FnMut(Progress)) {
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
    let (host, game) = LessonHost::load_with_limit(path, hook_limit, super::empty_game)?;
    Ok(drive(path, host, game, until, fps, report))
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
    let (host, game) =
        LessonHost::load_isolated_with_limit(path, hook_limit, super::empty_game, isolation)?;
    Ok(drive(path, host, game, until, fps, &mut |_| {}))
}

/// Steps `game` and runs `host`'s hooks until the lesson finishes, fails,
/// or board time reaches `until`.
fn drive(
    path: &Path,
    mut host: LessonHost,
    mut game: crate::model::GameState,
    until: f64,
    fps: f64,
    report: &mut dyn FnMut(Progress),
) -> Outcome {
    let mut frames = 0u64;
    let mut answers = Vec::new();
    let mut claims_seen = 0;
    new_claims(&host, &mut claims_seen, report);
    // Enough frames for `until` at any time scale the lesson sets, with a
    // hard cap against a lesson that pauses forever.
    let max_frames = 10_000_000u64;
    // Ctrl-C (`crate::interrupt`) stops between frames.
    // A closing message that waits for an event's light (`finish(after_light_from=…)`)
    // keeps board time running until that light reaches the eye: the
    // run ends when the student would see it.
    host.watch_light(&game);
    while (host.running() || host.awaiting_light())
        && frames < max_frames
        && !crate::interrupt::interrupted()
    {
        let turned = turn(&mut host, &mut game, fps, until, &mut |t| {
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
        new_claims(&host, &mut claims_seen, report);
    }
    let (claims, finished) = host.with_ui(|ui| {
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
        t: game.live_time,
        frames,
        finished,
        error: host.error.clone(),
        stopped: (host.error.is_some() && host.timed_out).then_some(Stop::Timeout),
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
pub fn turn(
    host: &mut LessonHost,
    game: &mut crate::model::GameState,
    fps: f64,
    until: f64,
    stepped: &mut dyn FnMut(f64),
) -> Turn {
    let (finished, question) = host.with_ui(|ui| {
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
        host.answer(game, i);
        host.settle(game);
        return Turn::Answered(text, choice);
    }
    if game.live_time >= until {
        return Turn::Reached;
    }
    game.paused = false;
    let before = game.live_time;
    game.step(1.0 / fps);
    stepped(game.live_time);
    host.after_step(game, before);
    host.settle(game);
    host.watch_light(game);
    Turn::Stepped
}

/// Frames a lesson may go without moving board time while it is run to a
/// time (`render`, `record`): 10 minutes at 60 frames a second.
const STILL_FRAMES: u32 = 36_000;

/// Runs `game` with its lesson `host` to board time `t` (s), as the
/// window would with a student who gives the lesson's own answers, at 60
/// frames a real second: the hooks run, questions are answered, and once
/// the lesson has finished (or failed: its error is on `host`) the board
/// goes on without it. Returns at the first frame at or past `t`, or an
/// error when board time stands still for `STILL_FRAMES` frames (the
/// lesson paused it, or set no time scale) or Ctrl-C is pressed.
pub fn run_to(
    host: &mut LessonHost,
    game: &mut crate::model::GameState,
    t: f64,
) -> Result<(), String> {
    const FPS: f64 = 60.0;
    let mut still = 0u32;
    while game.live_time < t {
        if crate::interrupt::interrupted() {
            return Err("interrupted".to_owned());
        }
        let before = game.live_time;
        let lesson_on = host.running() || host.awaiting_light();
        let turned = if lesson_on {
            turn(host, game, FPS, t, &mut |_| {})
        } else {
            Turn::Finished
        };
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
    game.view_time = game.live_time;
    Ok(())
}
