//! The lesson in the window's frame: its hooks are served around the
//! frame's drawing, board time waits while one is out in the lesson's
//! process, an edited lesson file reloads by itself, and the student's
//! answers and reloads reach it.

use std::time::{Duration, Instant};

use super::actions::UiAction;
use crate::lesson::LessonHost;
use crate::model::GameState;

/// How often the lesson file is looked at for edits.
const RELOAD_CHECK: Duration = Duration::from_millis(500);

/// The lesson driving the game, if one was given.
pub struct HostedLesson {
    /// The lesson.
    pub host: Option<LessonHost>,
    /// When the lesson file was last looked at for edits.
    reload_checked: Instant,
}

impl HostedLesson {
    /// Hosts `host` (none: no lesson).
    pub fn new(host: Option<LessonHost>) -> Self {
        Self {
            host,
            reload_checked: Instant::now(),
        }
    }

    /// Steps the game's board time by `dt` (real seconds) with the lesson
    /// around it: the hooks sent last frame ran in the lesson's process
    /// while that frame was drawn, so their ends are taken first (waiting
    /// at most a frame's budget); board time waits while a hook is still
    /// out; then the lesson sees the step, and reloads if its file was
    /// edited (checked twice a second).
    pub fn step(&mut self, state: &mut GameState, dt: f64, now: Instant) {
        if let Some(lesson) = &mut self.host {
            lesson.serve(state, crate::lesson::remote::FRAME_BUDGET);
        }
        let before = state.live_time;
        if !self.host.as_ref().is_some_and(LessonHost::busy) {
            state.step(dt);
        }
        if let Some(lesson) = &mut self.host {
            lesson.after_step(state, before);
            if now - self.reload_checked > RELOAD_CHECK {
                self.reload_checked = now;
                lesson.reload_if_edited(state);
            }
        }
    }

    /// After the frame is drawn: answers what the lesson asked meanwhile,
    /// so its hook can end before the next frame.
    pub fn after_draw(&mut self, state: &mut GameState) {
        if let Some(lesson) = &mut self.host {
            lesson.serve(state, Duration::ZERO);
        }
    }

    /// A reload or an answer (other actions are not the lesson's).
    pub fn act(&mut self, action: UiAction, state: &mut GameState) {
        let Some(lesson) = &mut self.host else {
            return;
        };
        match action {
            UiAction::ReloadLesson => lesson.reload(state),
            UiAction::Answer(i) => lesson.answer(state, i),
            _ => {}
        }
    }
}
