//! The scene menu (key M, or the panel's *scenes* button): pick any
//! shipped scene (built into the binary, [`crate::assets::SCENES`]) or
//! open a scene file by path, and start it afresh, paused on its title and
//! description as `play` opens one. Keyboard: M opens and closes it, Up/Down
//! choose, Enter starts the chosen scene, Tab reaches the path field
//! (Enter there opens the file), Esc closes. While a lesson runs the
//! lesson owns the scene, and the menu says so.

use std::path::Path;

use lightcone_engine::scene::{self, Scene};
use winit::keyboard::KeyCode;

use crate::model::GameState;

/// Starts `scene` in place of the current one: board time 0, paused on
/// its title and description; the view, time scale and overlays the
/// player chose are kept, the eye goes to the new scene's first observer.
pub fn switch(state: &mut GameState, scene: Scene) {
    let mut fresh = GameState::new(scene);
    fresh.paused = true;
    fresh.intro = true;
    fresh.view = state.view;
    fresh.time_scale = state.time_scale;
    fresh.show = state.show;
    fresh.show.diagram_frame = None;
    fresh.scene_menu = std::mem::take(&mut state.scene_menu);
    fresh.scene_menu.open = false;
    fresh.scene_menu.error = None;
    *state = fresh;
}

/// Opens shipped scene `i`, or says why not.
fn open_shipped(state: &mut GameState, i: usize) {
    let Some((name, _)) = crate::assets::SCENES.get(i) else {
        return;
    };
    match crate::assets::shipped_scene(name) {
        Some(Ok(scene)) => switch(state, scene),
        Some(Err(e)) => state.scene_menu.error = Some(e.to_string()),
        None => {}
    }
}

/// Opens the scene file at `path`, or says why not (the scene's located
/// errors, a lesson given instead of a scene).
pub fn open_path(state: &mut GameState, path: &str) {
    let path = path.trim();
    if path.is_empty() {
        state.scene_menu.error = Some("type the path of a scene file (.toml)".to_owned());
        return;
    }
    if Path::new(path).extension().is_some_and(|e| e == "py") {
        state.scene_menu.error = Some(format!(
            "{path} is a lesson: open it with `lightcone play {path}`"
        ));
        return;
    }
    match scene::load(Path::new(path)) {
        Ok(scene) => switch(state, scene),
        Err(e) => state.scene_menu.error = Some(e.to_string()),
    }
}

/// A key pressed in the window (not taken by a text field): while the menu
/// is open ↑/↓/Enter/Esc act on it (M, which opens and closes it, is in
/// the window's action table, `play::actions`). Returns whether the key
/// was the menu's.
pub fn key(state: &mut GameState, code: KeyCode, lesson: bool) -> bool {
    let menu = &mut state.scene_menu;
    if !menu.open {
        return false;
    }
    let n = crate::assets::SCENES.len();
    match code {
        KeyCode::ArrowUp => menu.selected = (menu.selected + n - 1) % n,
        KeyCode::ArrowDown => menu.selected = (menu.selected + 1) % n,
        KeyCode::Escape => menu.open = false,
        KeyCode::Enter | KeyCode::NumpadEnter => {
            if !lesson {
                let i = menu.selected;
                open_shipped(state, i);
            }
        }
        _ => return false,
    }
    true
}

/// The menu's window, when open.
pub fn window(ctx: &egui::Context, state: &mut GameState, lesson: bool) {
    if !state.scene_menu.open {
        return;
    }
    let mut open = true;
    let mut chosen = None;
    let mut path_entered = false;
    egui::Window::new("scenes (M)")
        .open(&mut open)
        .collapsible(false)
        .default_width(360.0)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 60.0))
        .show(ctx, |ui| {
            if lesson {
                ui.label("A lesson runs: its scene is the lesson's. Reload (F5) restarts it.");
                return;
            }
            ui.small("Up/Down choose, Enter starts, Esc closes; or click");
            let menu = &mut state.scene_menu;
            for (i, (name, text)) in crate::assets::SCENES.iter().enumerate() {
                // The title line of the file, if it has one.
                let title = text
                    .lines()
                    .find_map(|l| l.strip_prefix("title = "))
                    .map(|t| t.trim().trim_matches('"'))
                    .unwrap_or("");
                let label = format!("{name}  {title}");
                let response = ui.selectable_label(menu.selected == i, label);
                if response.clicked() {
                    menu.selected = i;
                    chosen = Some(i);
                }
            }
            ui.separator();
            ui.horizontal(|ui| {
                ui.label("file:");
                let field = ui.add(
                    egui::TextEdit::singleline(&mut menu.path)
                        .hint_text("path/to/scene.toml")
                        .desired_width(220.0),
                );
                let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                if ui.button("open").clicked() || enter {
                    path_entered = true;
                }
            });
            if let Some(e) = &menu.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
        });
    if !open {
        state.scene_menu.open = false;
    }
    if let Some(i) = chosen {
        open_shipped(state, i);
    } else if path_entered {
        let path = state.scene_menu.path.clone();
        open_path(state, &path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::play::actions::UiAction;

    #[test]
    fn keys_choose_and_start_a_shipped_scene_keeping_the_players_view() {
        let mut state = GameState::new(crate::assets::default_scene().unwrap());
        state.view = crate::model::ViewMode::Split;
        state.live_time = 3.0;
        UiAction::SceneMenu.apply(&mut state);
        assert!(state.scene_menu.open);
        let target = crate::assets::SCENES
            .iter()
            .position(|(n, _)| *n == "parallel_tracks.toml")
            .unwrap();
        while state.scene_menu.selected != target {
            assert!(key(&mut state, KeyCode::ArrowDown, false));
        }
        assert!(key(&mut state, KeyCode::Enter, false));
        assert_eq!(state.scene.pucks.len(), 5, "parallel_tracks has five pucks");
        assert_eq!(state.live_time, 0.0);
        assert!(state.paused && state.intro && !state.scene_menu.open);
        assert_eq!(state.view, crate::model::ViewMode::Split);
        // Closed, the arrows are the camera's again.
        assert!(!key(&mut state, KeyCode::ArrowDown, false));
        // While a lesson runs, Enter starts nothing.
        UiAction::SceneMenu.apply(&mut state);
        key(&mut state, KeyCode::ArrowUp, true);
        key(&mut state, KeyCode::Enter, true);
        assert_eq!(state.scene.pucks.len(), 5);
    }

    #[test]
    fn a_bad_path_is_reported_in_the_menu_and_the_game_goes_on() {
        let mut state = GameState::new(crate::assets::default_scene().unwrap());
        let title = state.scene.title.clone();
        open_path(&mut state, "no/such/scene.toml");
        let e = state.scene_menu.error.clone().unwrap();
        assert!(
            e.contains("no/such/scene.toml") && e.contains("cannot read"),
            "{e}"
        );
        open_path(&mut state, "scripts/lessons/gas.py");
        assert!(state.scene_menu.error.as_ref().unwrap().contains("lesson"));
        assert_eq!(state.scene.title, title);
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        open_path(&mut state, dir.join("ten_pucks.toml").to_str().unwrap());
        assert_eq!(state.scene.pucks.len(), 10);
        assert!(state.scene_menu.error.is_none());
    }
}
