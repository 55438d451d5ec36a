//! `lightcone play [SCENE | LESSON.py]`: open the game window.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use super::looks::{Looks, open};
use crate::play::app::{self, Options};

/// The options of `play` beyond the scene.
#[derive(Default)]
pub struct Extras {
    /// Screenshot after `frames` frames, then quit.
    pub screenshot: Option<PathBuf>,
    /// Frames before the screenshot.
    pub frames: u32,
    /// iceoryx2 service of a head tracker.
    pub tracker: Option<String>,
    /// CAVE description.
    pub cave: Option<PathBuf>,
    /// Open a scene at this board time, paused.
    pub at: Option<f64>,
    /// How the pictures look (`--view`, `--views`, `--effects`, `--top`).
    pub looks: Looks,
    /// Show the live space-time diagram.
    pub diagram: bool,
    /// Show it in this puck's frame (implies `diagram`).
    pub diagram_frame: Option<String>,
    /// Serve a render cluster on this Zenoh endpoint (with `cave`).
    pub serve: Option<String>,
    /// Log each frame's CAVE eyes here (with `cave`).
    pub frame_log: Option<PathBuf>,
}

/// Loads the scene (the built-in default when `None`) or the lesson
/// (`.py`) and runs the game.
pub fn run(path: Option<&Path>, extras: Extras) -> ExitCode {
    let Extras {
        screenshot,
        frames,
        tracker,
        cave,
        at,
        looks,
        diagram,
        diagram_frame,
        serve,
        frame_log,
    } = extras;
    if let Some(t) = at
        && !(t.is_finite() && t >= 0.0)
    {
        crate::errln!("--at {t}: give a board time of 0 s or more");
        return ExitCode::FAILURE;
    }
    let cave_file = cave;
    let cave = match cave_file.as_deref().map(crate::cave::load).transpose() {
        Ok(c) => c,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    // The render nodes get the CAVE file's text from the master.
    let cluster = match (serve, &cave_file) {
        (Some(endpoint), Some(file)) => {
            // The nodes prove they hold the key beside the CAVE file.
            let key = crate::cluster::key::load(&crate::cluster::key::beside(file));
            let master = std::fs::read_to_string(file)
                .map_err(|e| format!("{}: {e}", file.display()))
                .and_then(|text| {
                    crate::cluster::master::ClusterMaster::serve(&endpoint, text, key?)
                });
            match master {
                Ok(m) => Some(m),
                Err(e) => {
                    crate::errln!("{e}");
                    return ExitCode::FAILURE;
                }
            }
        }
        (Some(_), None) => {
            crate::errln!("--serve needs --cave: the render nodes draw the CAVE's walls");
            return ExitCode::FAILURE;
        }
        (None, _) => None,
    };
    let (mut game, lesson) = match open(path) {
        Ok(opened) => opened,
        Err(e) => {
            crate::errln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    if let Some(t) = at {
        if lesson.is_some() {
            crate::errln!("--at is for scenes: a lesson runs its own time");
            return ExitCode::FAILURE;
        }
        game.show_at(t);
    }
    let file = path.unwrap_or(Path::new("the default scene"));
    if let Err(e) = looks.apply(&mut game, file) {
        crate::errln!("{e}");
        return ExitCode::FAILURE;
    }
    game.show.diagram = diagram || diagram_frame.is_some();
    if let Some(name) = diagram_frame {
        match crate::commands::diagram::puck_index(&game.scene, file, "--diagram-frame", &name) {
            Ok(i) => game.show.diagram_frame = Some(i),
            Err(e) => {
                crate::errln!("{e}");
                return ExitCode::FAILURE;
            }
        }
    }
    match app::run(Options {
        game,
        lesson,
        screenshot,
        frames: frames.max(1),
        tracker,
        cave,
        cluster,
        frame_log,
    }) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            crate::errln!("{e}");
            ExitCode::FAILURE
        }
    }
}
