//! How `play`, `render` and `record` open a scene or lesson and how its
//! pictures look: one opening and one set of look flags for all three.

use std::path::Path;

use lightcone_engine::scene;

use crate::lesson::LessonHost;
use crate::model::{GameState, ViewMode};

/// Opens the game `play`, `render` and `record` show: the scene file, the
/// built-in default scene (`None`), or the lesson (`.py`, started in its
/// own process: nothing it does ends the game; one that fails before it
/// starts a game leaves the default scene on the table, with the
/// traceback beside it). A scene opens paused on its title and
/// description. Errors name the file.
pub fn open(path: Option<&Path>) -> Result<(GameState, Option<LessonHost>), String> {
    if let Some(path) = path
        && path.extension().is_some_and(|e| e == "py")
    {
        if !path.is_file() {
            return Err(format!("{}: no such lesson file", path.display()));
        }
        let fallback = || match crate::assets::default_scene() {
            Ok(s) => GameState::new(s),
            Err(_) => GameState::new(
                scene::Scene::empty(glam::DVec2::new(2.84, 1.42), None)
                    .unwrap_or_else(|_| unreachable!("a carom table is a valid scene")),
            ),
        };
        let isolation = crate::lesson::supervise::window_isolation()?;
        let (host, game) = LessonHost::load_isolated(path, fallback, isolation)?;
        return Ok((game, Some(host)));
    }
    let scene = match path {
        Some(path) => scene::load(path),
        None => crate::assets::default_scene(),
    }
    .map_err(|e| e.to_string())?;
    let mut game = GameState::new(scene);
    game.paused = true;
    game.intro = true;
    Ok((game, None))
}

/// How the pictures look, as `play`, `render` and `record` are told on
/// their command lines.
#[derive(Default)]
pub struct Looks {
    /// The view (`--view`).
    pub view: Option<ViewMode>,
    /// Pictures side by side (`--views`, see [`crate::model::Pane::parse_list`]).
    pub views: Option<String>,
    /// Effects shown (`observe`'s syntax), instead of the scene's (`--effects`).
    pub effects: Option<String>,
    /// The camera above the table (`--top`).
    pub top: bool,
    /// The scene observer looked through, by name (`--observer`).
    pub observer: Option<String>,
}

impl Looks {
    /// Sets them on `game` (opened from `file`); a bad list or name is an
    /// error naming the flag (and the file, for an observer).
    pub fn apply(self, game: &mut GameState, file: &Path) -> Result<(), String> {
        if let Some(name) = self.observer {
            let i = super::names::observer_index(&game.scene, file, Some(&name))?;
            game.observer = Some(i);
        }
        if let Some(v) = self.view {
            game.set_view(v);
        }
        if let Some(spec) = self.views {
            game.panes = Some(crate::model::Pane::parse_list(&spec, &game.scene)?);
        }
        if let Some(spec) = self.effects {
            game.effects = crate::commands::observe::parse_effects(&spec, game.effects)?;
        }
        if self.top {
            game.top_view();
        }
        Ok(())
    }
}

/// The game of the scene or lesson at `path`, looking as `looks` says,
/// at board time `t` ([`go_to`]). `record` goes on from it.
pub fn open_at(
    path: &Path,
    looks: Looks,
    t: f64,
) -> Result<(GameState, Option<LessonHost>), String> {
    let (mut game, mut lesson) = open(Some(path))?;
    looks.apply(&mut game, path)?;
    go_to(&mut game, lesson.as_mut(), path, t)?;
    Ok((game, lesson))
}

/// Takes `game` (opened from `path`) to board time `t`: a scene is run
/// there and paused; with its lesson, board time runs there with the
/// hooks, questions answered with the lesson's own answers
/// ([`crate::lesson::headless::run_to`]; a lesson starts at 0, so `t` < 0
/// is an error; one that fails is left behind, see [`say_if_failed`]).
/// Errors name the file.
pub fn go_to(
    game: &mut GameState,
    lesson: Option<&mut LessonHost>,
    path: &Path,
    t: f64,
) -> Result<(), String> {
    let Some(host) = lesson else {
        game.show_at(t);
        return Ok(());
    };
    if t < 0.0 {
        return Err(format!(
            "--at {t}: a lesson starts at board time 0; give 0 s or more"
        ));
    }
    game.intro = false;
    let mut lesson = crate::lesson::headless::Isolated { host, game };
    crate::lesson::headless::run_to(&mut lesson, t).map_err(|e| format!("{}: {e}", path.display()))
}

/// Says on stderr that the lesson opened from `path` failed, if it did
/// (the board went on without it): once, after the pictures.
pub fn say_if_failed(lesson: Option<&LessonHost>, path: &Path) {
    if let Some(e) = lesson.and_then(|host| host.error.as_ref()) {
        crate::errln!("{}: the lesson failed: {e}", path.display());
    }
}
