//! `lightcone play [SCENE]`: open the game window.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use lightcone_engine::scene;

use crate::play::app::{self, Options};

/// Loads the scene (the default one when `None`) and runs the game.
pub fn run(path: Option<&Path>, screenshot: Option<PathBuf>, frames: u32) -> ExitCode {
    let path = path.unwrap_or(Path::new(crate::DEFAULT_SCENE));
    if path.extension().is_some_and(|e| e == "py") {
        eprintln!(
            "{}: Python lessons are not supported yet (they come with the lessons issue); give a scene .toml",
            path.display()
        );
        return ExitCode::FAILURE;
    }
    let scene = match scene::load(path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    match app::run(Options {
        scene,
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
