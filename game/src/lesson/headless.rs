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
    let (host, game) = LessonHost::load_with_limit(path, hook_limit, super::placeholder)?;
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
        LessonHost::load_isolated_with_limit(path, hook_limit, super::placeholder, isolation)?;
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
        let (finished, question) = host.with_ui(|ui| {
            let q = ui
                .question
                .as_ref()
                .filter(|q| q.chosen.is_none())
                .map(|q| {
                    let i = q.answer.unwrap_or(0);
                    (q.text.clone(), q.choices[i].clone(), i)
                });
            (ui.closing().is_some(), q)
        });
        if finished {
            break;
        }
        if let Some((text, choice, i)) = question {
            report(Progress::Answer(text.clone(), choice.clone()));
            answers.push((text, choice));
            host.answer(&mut game, i);
            host.settle(&mut game);
            new_claims(&host, &mut claims_seen, report);
            continue;
        }
        if game.live_time >= until {
            break;
        }
        // Nobody is there to press play.
        game.paused = false;
        let before = game.live_time;
        game.step(1.0 / fps);
        frames += 1;
        // Before the hooks: should one of them take the process down, the
        // parent knows the frame was reached.
        report(Progress::Frame {
            t: game.live_time,
            frames,
        });
        host.after_step(&mut game, before);
        host.settle(&mut game);
        host.watch_light(&game);
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
