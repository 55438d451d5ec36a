//! The player's hands: keys become [`UiAction`]s (held ones fly the eye),
//! the mouse aims the cue, turns, orbits and zooms; on a touch screen
//! (a tablet, a Chromebook) one finger aims and strikes the cue as the
//! left button does.

use std::collections::HashSet;

use glam::{DVec2, DVec3};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, Touch, TouchPhase, WindowEvent};

use super::actions::{self, UiAction};
use super::scene_menu::MenuKey;
use super::shown::project;
use crate::model::{GameState, Pane};

/// The keys a focused control takes from the game ([`Input::keys`]).
const FOCUS_KEYS: [egui::Key; 7] = [
    egui::Key::Space,
    egui::Key::Enter,
    egui::Key::Tab,
    egui::Key::ArrowLeft,
    egui::Key::ArrowRight,
    egui::Key::ArrowUp,
    egui::Key::ArrowDown,
];

/// What the keyboard and mouse hold between events.
#[derive(Default)]
pub struct Input {
    /// The window can start lessons (the scene menu lists them).
    lessons: bool,
    /// Keys held down (egui's, by their place on the keyboard where known).
    keys: HashSet<egui::Key>,
    /// The cursor, physical px.
    cursor: DVec2,
    /// Right-drag turns the free eye.
    looking: bool,
    /// Middle-drag orbits the eye about the table (or the followed puck).
    orbiting: bool,
    /// Puck being aimed and where the drag started (physical px).
    aiming: Option<(usize, DVec2)>,
    /// The finger that aims the cue (the first one down), by its id.
    finger: Option<u64>,
}

impl Input {
    /// No key held, no drag; `lessons` when the window can start lessons
    /// (the desktop game).
    pub fn new(lessons: bool) -> Self {
        Self {
            lessons,
            ..Self::default()
        }
    }

    /// An event of the main window, whose pictures are at `rects`;
    /// `consumed` when egui took it. Mouse moves that are actions go to
    /// `actions`; the cue is aimed and struck on `state`. (Keys reach the
    /// game through egui: [`Self::keys`].)
    pub fn event(
        &mut self,
        event: &WindowEvent,
        consumed: bool,
        state: &mut GameState,
        rects: &[([f32; 4], Pane)],
        actions: &mut Vec<UiAction>,
    ) {
        match event {
            WindowEvent::CursorMoved { position, .. } => {
                let p = DVec2::new(position.x, position.y);
                let d = p - self.cursor;
                if self.looking {
                    actions.push(UiAction::Look(-d.x * 0.004, -d.y * 0.004));
                }
                if self.orbiting {
                    actions.push(UiAction::Orbit(-d.x * 0.006, d.y * 0.006));
                }
                self.cursor = p;
                self.drag(state, rects);
            }
            WindowEvent::MouseWheel { delta, .. } if !consumed => {
                let lines = match *delta {
                    MouseScrollDelta::LineDelta(_, y) => f64::from(y),
                    MouseScrollDelta::PixelDelta(p) => p.y / 40.0,
                };
                actions.push(UiAction::Zoom(1.1f64.powf(lines)));
            }
            WindowEvent::Touch(touch) => self.touch(touch, consumed, state, rects),
            &WindowEvent::MouseInput {
                state: s, button, ..
            } if !consumed || s == ElementState::Released => match (button, s) {
                (MouseButton::Left, ElementState::Pressed) => self.press(state, rects),
                (MouseButton::Left, ElementState::Released) => self.release(state),
                (MouseButton::Right, s) => self.looking = s == ElementState::Pressed,
                (MouseButton::Middle, s) => self.orbiting = s == ElementState::Pressed,
                _ => {}
            },
            _ => {}
        }
    }

    /// The keys pressed and released since the last frame, as egui has
    /// them from any of the game's windows (the window, the page's canvas,
    /// the CAVE's output windows, or `egui_kittest`): a press is the open
    /// scene menu's key first, then the action table's
    /// ([`actions::KEYS`]), unless a field is being typed into (the c
    /// field) or a control reached by Tab takes the key (Space, Enter,
    /// Tab, the arrows); held keys fly the eye ([`Self::flight`]), until
    /// released or the window loses the keyboard.
    /// A key is known by its place on the keyboard where the platform
    /// gives it (W, A, S, D on any layout), else by its label.
    pub fn keys(
        &mut self,
        ctx: &egui::Context,
        state: &mut GameState,
        actions: &mut Vec<UiAction>,
    ) {
        // Typing into a field (the c field, the scene menu's path): its
        // keys are the field's.
        let typing = ctx.text_edit_focused();
        // A control reached by Tab takes the keys that press it or move
        // on (Space, Enter, Tab, the arrows); the rest still play (egui
        // itself hands the focus back on Escape).
        let focused = ctx.memory(|m| m.focused()).is_some();
        let events = ctx.input(|i| i.events.clone());
        for event in events {
            if matches!(event, egui::Event::WindowFocused(false)) {
                // No release comes for what was held when the window lost
                // the keyboard: nothing flies on.
                self.keys.clear();
                continue;
            }
            let egui::Event::Key {
                key,
                physical_key,
                pressed,
                repeat,
                ..
            } = event
            else {
                continue;
            };
            let key = physical_key.unwrap_or(key);
            if !pressed {
                self.keys.remove(&key);
                continue;
            }
            if typing || (focused && FOCUS_KEYS.contains(&key)) {
                continue;
            }
            if !repeat {
                match super::scene_menu::key(state, key, self.lessons) {
                    MenuKey::NotMine => actions.extend(actions::for_key(key)),
                    MenuKey::Taken => {}
                    MenuKey::Open(choice) => actions.push(UiAction::Open(choice)),
                }
            }
            self.keys.insert(key);
        }
    }

    /// The direction the held keys fly the eye (unit, or zero): W/S
    /// forward and back along `forward` flattened, A/D sideways, R/F up
    /// and down.
    pub fn flight(&self, forward: DVec3) -> DVec3 {
        let flat = DVec3::new(forward.x, forward.y, 0.0).normalize_or(DVec3::X);
        let side = flat.cross(DVec3::Z);
        let mut dir = DVec3::ZERO;
        for (key, d) in [
            (egui::Key::W, flat),
            (egui::Key::S, -flat),
            (egui::Key::D, side),
            (egui::Key::A, -side),
            (egui::Key::R, DVec3::Z),
            (egui::Key::F, -DVec3::Z),
        ] {
            if self.keys.contains(&key) {
                dir += d;
            }
        }
        dir.normalize_or_zero()
    }

    /// The rectangle and picture in which the cue picks pucks: the one
    /// under the cursor (the last one when none is).
    fn pick_rect(&self, rects: &[([f32; 4], Pane)]) -> Option<([f32; 4], Pane)> {
        let (x, y) = (self.cursor.x as f32, self.cursor.y as f32);
        rects
            .iter()
            .copied()
            .find(|(r, _)| x >= r[0] && x < r[0] + r[2] && y >= r[1] && y < r[1] + r[3])
            .or_else(|| rects.last().copied())
    }

    /// A finger on the screen: the first one down (not on a panel) is the
    /// cursor with the left button held, so it aims and strikes the cue;
    /// a lifted finger strikes, a cancelled touch drops the aim.
    fn touch(
        &mut self,
        touch: &Touch,
        consumed: bool,
        state: &mut GameState,
        rects: &[([f32; 4], Pane)],
    ) {
        let at = DVec2::new(touch.location.x, touch.location.y);
        match touch.phase {
            TouchPhase::Started if self.finger.is_none() && !consumed => {
                self.finger = Some(touch.id);
                self.cursor = at;
                self.press(state, rects);
            }
            _ if self.finger != Some(touch.id) => {}
            TouchPhase::Started | TouchPhase::Moved => {
                self.cursor = at;
                self.drag(state, rects);
            }
            TouchPhase::Ended => {
                self.finger = None;
                self.cursor = at;
                self.release(state);
            }
            TouchPhase::Cancelled => {
                self.finger = None;
                if self.aiming.take().is_some() {
                    state.cue = None;
                }
            }
        }
    }

    /// Left press: the puck seen nearest the cursor (within 30 px) is aimed.
    fn press(&mut self, state: &GameState, rects: &[([f32; 4], Pane)]) {
        let Some((rect, pane)) = self.pick_rect(rects) else {
            return;
        };
        let Some(view) = state.view_of(pane) else {
            return;
        };
        let Some(camera) = state.camera(view) else {
            return;
        };
        let best = state
            .centres(view)
            .iter()
            .filter_map(|c| {
                project(&camera, rect, c.seen.position).map(|p| (c.puck, p.distance(self.cursor)))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((i, d)) = best
            && d < 30.0
        {
            self.aiming = Some((i, self.cursor));
        }
    }

    /// The cursor moved while aiming: the pull so far is the stroke.
    fn drag(&mut self, state: &mut GameState, rects: &[([f32; 4], Pane)]) {
        let Some((puck, start)) = self.aiming else {
            return;
        };
        let f = self
            .pick_rect(rects)
            .and_then(|(_, p)| state.view_of(p))
            .and_then(|v| state.camera(v))
            .map_or_else(|| state.forward(), |c| c.forward);
        let flat = DVec3::new(f.x, f.y, 0.0).normalize_or(DVec3::Y);
        let right = flat.cross(DVec3::Z);
        let d = self.cursor - start;
        // 60 px of pull = 1 m/s of proper velocity γv.
        let pull = (right * d.x - flat * d.y) / 60.0;
        state.aim(puck, pull.truncate());
    }

    /// Left release: the aimed stroke is struck.
    fn release(&mut self, state: &mut GameState) {
        if self.aiming.take().is_some()
            && let Err(e) = state.strike()
        {
            state.message = e;
        }
    }
}
