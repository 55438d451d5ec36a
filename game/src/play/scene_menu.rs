//! The scene menu (key M, or the panel's *scenes* button): pick any
//! shipped scene (built into the binary, [`crate::assets::SCENES`]) or,
//! in the desktop game, any shipped lesson ([`crate::assets::LESSONS`]),
//! or open a scene or lesson file by path. A scene starts afresh, paused
//! on its title and description as `play` opens one; a lesson starts in
//! its own process as `lightcone play LESSON.py` starts it (the window
//! does that, `play::lesson_host`). Opening either while a lesson runs
//! ends that lesson. Keyboard: M opens and closes it, Up/Down choose,
//! Enter opens the chosen entry, Tab reaches the path field (Enter there
//! opens the file), Esc closes.

use std::path::Path;

use lightcone_engine::scene::{self, Scene};

use crate::assets::{LESSONS, SCENES};
use crate::links::SceneSource;
use crate::model::GameState;

/// What the scene menu opens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Choice {
    /// The shipped scene `i` ([`SCENES`]).
    Scene(usize),
    /// The shipped lesson `i` ([`LESSONS`]).
    Lesson(usize),
    /// The file whose path is typed in the menu's field: a scene, or a
    /// lesson (`.py`).
    Typed,
}

/// What [`open`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Opened {
    /// Nothing: the menu says why (a bad file, a lesson in the browser).
    Nothing,
    /// A scene replaced the game.
    Scene,
    /// The choice is a lesson, checked: the window starts it.
    Lesson,
}

/// What the window tells the menu.
#[derive(Clone, Copy, Debug, Default)]
pub struct MenuContext<'a> {
    /// The window can start lessons (the desktop game: they need Python).
    pub lessons: bool,
    /// The lesson running now, by name, if one is.
    pub running: Option<&'a str>,
}

/// What a key did to the open menu.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MenuKey {
    /// Not the menu's key (or the menu is closed).
    NotMine,
    /// The menu's: it moved the choice or closed the menu.
    Taken,
    /// Enter: open this.
    Open(Choice),
}

/// Starts `scene` (from `source`) in place of the current one: board
/// time 0, paused on its title and description; the view, time scale and
/// overlays the player chose are kept, the eye goes to the new scene's
/// first observer.
pub fn switch(state: &mut GameState, scene: Scene, source: Option<SceneSource>) {
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
    fresh.source = source;
    *state = fresh;
}

/// Opens `choice`: a scene replaces the game here; a lesson is checked
/// (a typed path must name a `.py` file) and left for the window to
/// start. What cannot be opened is said in the menu.
pub fn open(state: &mut GameState, choice: Choice) -> Opened {
    match choice {
        Choice::Scene(i) => open_shipped(state, i),
        Choice::Lesson(i) if i < LESSONS.len() => Opened::Lesson,
        Choice::Lesson(_) => Opened::Nothing,
        Choice::Typed => {
            let path = state.scene_menu.path.clone();
            open_path(state, &path)
        }
    }
}

/// Opens shipped scene `i`, or says why not.
fn open_shipped(state: &mut GameState, i: usize) -> Opened {
    let Some((name, _)) = SCENES.get(i) else {
        return Opened::Nothing;
    };
    match crate::assets::shipped_scene(name) {
        Some(Ok(scene)) => {
            switch(state, scene, Some(SceneSource::Shipped((*name).to_owned())));
            Opened::Scene
        }
        Some(Err(e)) => {
            state.scene_menu.error = Some(e.to_string());
            Opened::Nothing
        }
        None => Opened::Nothing,
    }
}

/// Opens the scene file at `path`, or checks the lesson file there (for
/// the window to start), or says why not (the scene's located errors, a
/// missing lesson, a lesson in the browser).
pub fn open_path(state: &mut GameState, path: &str) -> Opened {
    let path = path.trim();
    if path.is_empty() {
        state.scene_menu.error =
            Some("type the path of a scene file (.toml) or a lesson (.py)".to_owned());
        return Opened::Nothing;
    }
    if Path::new(path).extension().is_some_and(|e| e == "py") {
        let why = if cfg!(target_arch = "wasm32") {
            Some(format!(
                "{path}: the page reads no files by name; drop the lesson file on the page (or open one of the lessons above)"
            ))
        } else if !Path::new(path).is_file() {
            Some(format!("{path}: no such lesson file"))
        } else {
            None
        };
        state.scene_menu.error = why;
        return if state.scene_menu.error.is_some() {
            Opened::Nothing
        } else {
            Opened::Lesson
        };
    }
    // Read once: the text parsed is the text a link would carry.
    let opened = scene::read_text(Path::new(path))
        .and_then(|text| scene::parse(&text, path).map(|scene| (scene, text)));
    match opened {
        Ok((scene, text)) => {
            let name = path.to_owned();
            switch(state, scene, Some(SceneSource::Text { name, text }));
            Opened::Scene
        }
        Err(e) => {
            state.scene_menu.error = Some(e.to_string());
            Opened::Nothing
        }
    }
}

/// The menu's entries in order: every shipped scene, then (when the
/// window can start them) every shipped lesson.
fn entries(lessons: bool) -> impl Iterator<Item = Choice> {
    let n = if lessons { LESSONS.len() } else { 0 };
    (0..SCENES.len())
        .map(Choice::Scene)
        .chain((0..n).map(Choice::Lesson))
}

/// A key pressed in the window (not taken by a text field): while the menu
/// is open ↑/↓/Enter/Esc act on it (M, which opens and closes it, is in
/// the window's action table, `play::actions`); `lessons` when the
/// window can start lessons (they are listed then).
pub fn key(state: &mut GameState, code: egui::Key, lessons: bool) -> MenuKey {
    let menu = &mut state.scene_menu;
    if !menu.open {
        return MenuKey::NotMine;
    }
    let n = entries(lessons).count();
    menu.selected %= n;
    match code {
        egui::Key::ArrowUp => menu.selected = (menu.selected + n - 1) % n,
        egui::Key::ArrowDown => menu.selected = (menu.selected + 1) % n,
        egui::Key::Escape => menu.open = false,
        egui::Key::Enter => {
            if let Some(choice) = entries(lessons).nth(menu.selected) {
                return MenuKey::Open(choice);
            }
        }
        _ => return MenuKey::NotMine,
    }
    MenuKey::Taken
}

/// The title line of a shipped scene's file (`title = "…"`), if it has one.
fn scene_title(text: &str) -> &str {
    text.lines()
        .find_map(|l| l.strip_prefix("title = "))
        .map_or("", |t| t.trim().trim_matches('"'))
}

/// The menu's window, when open. Returns what was clicked or entered.
pub fn window(ctx: &egui::Context, state: &mut GameState, shown: MenuContext) -> Option<Choice> {
    if !state.scene_menu.open {
        return None;
    }
    let mut open = true;
    let mut chosen = None;
    let title = if shown.lessons {
        "scenes and lessons (M)"
    } else {
        "scenes (M)"
    };
    egui::Window::new(title)
        .open(&mut open)
        .collapsible(false)
        .default_width(380.0)
        .anchor(egui::Align2::CENTER_CENTER, egui::vec2(0.0, 40.0))
        .show(ctx, |ui| {
            if let Some(name) = shown.running {
                ui.label(format!(
                    "The lesson {name} runs: opening a scene or another lesson ends it."
                ));
                ui.separator();
            }
            ui.small("Up/Down choose, Enter opens, Esc closes; or click");
            let menu = &mut state.scene_menu;
            let list = egui::ScrollArea::vertical().max_height(400.0);
            list.show(ui, |ui| {
                // The keys' choice is scrolled into view when it moves.
                let id = egui::Id::unique("lightcone scene menu selected");
                let entry_moved = ui.data(|d| d.get_temp::<usize>(id)) != Some(menu.selected);
                ui.data_mut(|d| d.insert_temp(id, menu.selected));
                for (i, choice) in entries(shown.lessons).enumerate() {
                    let label = match choice {
                        Choice::Scene(k) => {
                            if k == 0 {
                                ui.label(egui::RichText::new("scenes").strong());
                            }
                            let (name, text) = SCENES[k];
                            format!("{name}  {}", scene_title(text))
                        }
                        Choice::Lesson(k) => {
                            if k == 0 {
                                ui.label(egui::RichText::new("lessons").strong());
                            }
                            let (name, text) = LESSONS[k];
                            format!("{name}  {}", crate::assets::lesson_title(text))
                        }
                        Choice::Typed => continue,
                    };
                    let entry = ui.selectable_label(menu.selected == i, label);
                    if menu.selected == i && entry_moved {
                        entry.scroll_to_me(None);
                    }
                    if entry.clicked() {
                        menu.selected = i;
                        chosen = Some(choice);
                    }
                }
            });
            ui.separator();
            ui.horizontal(|ui| {
                ui.label("file:");
                let hint = if shown.lessons {
                    "path/to/scene.toml or lesson.py"
                } else {
                    "path/to/scene.toml"
                };
                let field = ui.add(
                    egui::TextEdit::singleline(&mut menu.path)
                        .hint_text(hint)
                        .desired_width(240.0),
                );
                let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
                if ui.button("open").clicked() || enter {
                    chosen = Some(Choice::Typed);
                }
            });
            if let Some(e) = &menu.error {
                ui.colored_label(egui::Color32::LIGHT_RED, e);
            }
        });
    if !open {
        state.scene_menu.open = false;
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::play::actions::UiAction;

    /// Presses `code` as the window does: the menu's key first, an entry
    /// it opens carried out through the action table.
    fn press(state: &mut GameState, code: egui::Key, lessons: bool) -> Option<UiAction> {
        match key(state, code, lessons) {
            MenuKey::NotMine => panic!("{code:?} is the menu's while it is open"),
            MenuKey::Taken => None,
            MenuKey::Open(choice) => UiAction::Open(choice).apply(state),
        }
    }

    #[test]
    fn keys_choose_and_start_a_shipped_scene_keeping_the_players_view() {
        let mut state = GameState::new(crate::assets::default_scene().unwrap());
        state.view = crate::model::ViewMode::Split;
        state.live_time = 3.0;
        UiAction::SceneMenu.apply(&mut state);
        assert!(state.scene_menu.open);
        let target = SCENES
            .iter()
            .position(|(n, _)| *n == "parallel_tracks.toml")
            .unwrap();
        while state.scene_menu.selected != target {
            assert_eq!(press(&mut state, egui::Key::ArrowDown, false), None);
        }
        // The window is told, so that a lesson that ran ends.
        let told = press(&mut state, egui::Key::Enter, false);
        assert_eq!(told, Some(UiAction::SceneOpened));
        assert_eq!(state.scene.pucks.len(), 5, "parallel_tracks has five pucks");
        assert_eq!(state.live_time, 0.0);
        assert!(state.paused && state.intro && !state.scene_menu.open);
        assert_eq!(state.view, crate::model::ViewMode::Split);
        // Closed, the arrows are the camera's again.
        assert_eq!(
            key(&mut state, egui::Key::ArrowDown, false),
            MenuKey::NotMine
        );
    }

    #[test]
    fn the_menu_lists_the_shipped_lessons_after_the_scenes_and_enter_opens_one() {
        let mut state = GameState::new(crate::assets::default_scene().unwrap());
        let title = state.scene.title.clone();
        UiAction::SceneMenu.apply(&mut state);
        // Up from the first entry wraps to the last: the last lesson.
        let last = Choice::Lesson(LESSONS.len() - 1);
        assert_eq!(press(&mut state, egui::Key::ArrowUp, true), None);
        assert_eq!(key(&mut state, egui::Key::Enter, true), MenuKey::Open(last));
        // Carried out, it is the window's to start; the scene is untouched.
        let told = UiAction::Open(last).apply(&mut state);
        assert_eq!(told, Some(UiAction::Open(last)));
        assert_eq!(state.scene.title, title);
        // Every lesson is an entry, with its title; without lessons (the
        // browser) the list wraps among the scenes only.
        let all: Vec<Choice> = entries(true).collect();
        assert_eq!(all.len(), SCENES.len() + LESSONS.len());
        for (i, (name, text)) in LESSONS.iter().enumerate() {
            assert_eq!(all[SCENES.len() + i], Choice::Lesson(i));
            assert!(
                !crate::assets::lesson_title(text).is_empty(),
                "{name} has no title line"
            );
        }
        state.scene_menu.selected = 0;
        press(&mut state, egui::Key::ArrowUp, false);
        assert_eq!(state.scene_menu.selected, SCENES.len() - 1);
    }

    #[test]
    fn a_bad_path_is_reported_in_the_menu_and_the_game_goes_on() {
        let mut state = GameState::new(crate::assets::default_scene().unwrap());
        let title = state.scene.title.clone();
        assert_eq!(open_path(&mut state, "no/such/scene.toml"), Opened::Nothing);
        let e = state.scene_menu.error.clone().unwrap();
        assert!(
            e.contains("no/such/scene.toml") && e.contains("cannot read"),
            "{e}"
        );
        assert_eq!(open_path(&mut state, "no/such/lesson.py"), Opened::Nothing);
        let e = state.scene_menu.error.clone().unwrap();
        assert!(e.contains("no such lesson file"), "{e}");
        assert_eq!(state.scene.title, title);
        // A lesson that is there is the window's to start.
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let lesson = root.join("scripts/lessons/gas.py");
        assert_eq!(
            open_path(&mut state, lesson.to_str().unwrap()),
            Opened::Lesson
        );
        assert!(state.scene_menu.error.is_none());
        assert_eq!(state.scene.title, title);
        let scene = root.join("assets/scenes/ten_pucks.toml");
        assert_eq!(
            open_path(&mut state, scene.to_str().unwrap()),
            Opened::Scene
        );
        assert_eq!(state.scene.pucks.len(), 10);
        assert!(state.scene_menu.error.is_none());
    }
}
