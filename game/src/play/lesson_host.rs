//! The lesson in the window's frame: its hooks are served around the
//! frame's drawing, board time waits while one is out in the lesson's
//! process, an edited lesson file reloads by itself, the student's
//! answers and reloads reach it, and a closing message that waits for an
//! event's light is shown once that light reaches the eye. The scene menu
//! starts, replaces and ends lessons here.

use std::time::{Duration, Instant};

use super::actions::UiAction;
use super::scene_menu::Choice;
use crate::lesson::{Isolation, LessonHost};
use crate::model::GameState;

/// How often the lesson file is looked at for edits.
const RELOAD_CHECK: Duration = Duration::from_millis(500);

/// The lesson driving the game, if one was given.
pub struct HostedLesson {
    /// The lesson.
    pub host: Option<LessonHost>,
    /// When the lesson file was last looked at for edits.
    reload_checked: Instant,
    /// How a lesson opened from the scene menu is started (or why none
    /// can be).
    isolation: Result<Isolation, String>,
}

impl HostedLesson {
    /// Hosts `host` (none: no lesson); lessons opened from the scene menu
    /// start their process as `isolation` says.
    pub fn new(host: Option<LessonHost>, isolation: Result<Isolation, String>) -> Self {
        Self {
            host,
            reload_checked: Instant::now(),
            isolation,
        }
    }

    /// Starts `choice` (a shipped lesson, or the lesson file typed in the
    /// scene menu) in place of the lesson that ran, if one did (its
    /// process ends). The game is replaced when the new lesson's `setup`
    /// ends, over the next frames; until then board time waits. What
    /// cannot start is said in the menu, and the game goes on as it was.
    fn open(&mut self, choice: Choice, state: &mut GameState) {
        let isolation = match &self.isolation {
            Ok(i) => i.clone(),
            Err(e) => {
                state.scene_menu.error = Some(e.clone());
                return;
            }
        };
        let opened = match choice {
            Choice::Lesson(i) => match crate::assets::LESSONS.get(i) {
                Some((name, text)) => LessonHost::open_shipped(name, text, isolation),
                None => return,
            },
            Choice::Typed => {
                let path = state.scene_menu.path.trim().to_owned();
                LessonHost::open_isolated(std::path::Path::new(&path), isolation)
            }
            Choice::Scene(_) => return,
        };
        match opened {
            Ok(host) => {
                // The old lesson's process ends here (its host dropped).
                self.host = Some(host);
                self.reload_checked = Instant::now();
                state.scene_menu.open = false;
                state.scene_menu.error = None;
                // Nothing moves until the new lesson's setup has built its game.
                state.intro = false;
                state.paused = true;
            }
            Err(e) => state.scene_menu.error = Some(e),
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
            lesson.watch_light(state);
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

    /// A reload or an answer, a lesson opened from the scene menu, or a
    /// scene opened there (which ends the lesson that ran); other actions
    /// are not the lesson's.
    pub fn act(&mut self, action: UiAction, state: &mut GameState) {
        match action {
            UiAction::Open(choice) => return self.open(choice, state),
            UiAction::SceneOpened => {
                // Its process ends with its host.
                self.host = None;
                return;
            }
            _ => {}
        }
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
