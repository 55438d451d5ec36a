//! `lightcone play [SCENE | LESSON.py]`: open the game window.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use lightcone_engine::scene;

use crate::lesson::LessonHost;
use crate::play::app::{self, Options};
use crate::play::state::GameState;

/// Loads the scene (the default one when `None`) or the lesson (`.py`) and
/// runs the game.
pub fn run(path: Option<&Path>, screenshot: Option<PathBuf>, frames: u32) -> ExitCode {
    let path = path.unwrap_or(Path::new(crate::DEFAULT_SCENE));
    let (game, lesson) = if path.extension().is_some_and(|e| e == "py") {
        if !path.is_file() {
            eprintln!("{}: no such lesson file", path.display());
            return ExitCode::FAILURE;
        }
        // A lesson that fails before it starts a game leaves the default
        // scene on the table, with the traceback beside it.
        let fallback = || match scene::load(Path::new(crate::DEFAULT_SCENE)) {
            Ok(s) => GameState::new(s),
            Err(_) => GameState::new(
                scene::Scene::empty(glam::DVec2::new(2.84, 1.42), None)
                    .unwrap_or_else(|_| unreachable!("a carom table is a valid scene")),
            ),
        };
        match LessonHost::load(path, fallback) {
            Ok((host, game)) => (game, Some(host)),
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::FAILURE;
            }
        }
    } else {
        match scene::load(path) {
            Ok(s) => (GameState::new(s), None),
            Err(e) => {
                eprintln!("{e}");
                return ExitCode::FAILURE;
            }
        }
    };
    match app::run(Options {
        game,
        lesson,
        screenshot,
        frames: frames.max(1),
    }) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::FAILURE
        }
    }
}
