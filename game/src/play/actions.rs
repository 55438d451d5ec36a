//! The one table of what the player can do: every key and every panel
//! control becomes a [`UiAction`], and [`UiAction::apply`] is the one place
//! each is carried out, so no action is written twice.

use lightcone_engine::scene::Effect;

use super::scene_menu::Opened;
use crate::model::{Framing, GameState, ViewMode};

/// A drawing over the views that a key and a checkbox turn on and off.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Overlay {
    /// Trails (7).
    Trails,
    /// The ghost of the truth (8).
    Ghost,
    /// Velocity arrows (9).
    Arrows,
    /// The magnifier (0).
    Magnifier,
    /// The space-time diagram's window (Y).
    Diagram,
}

/// Something the player asked for, by key or in a panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum UiAction {
    /// Pause or run board time (and leave the scene's intro).
    Pause,
    /// Leave the scene's intro and run board time.
    Start,
    /// Back to the live edge.
    GoLive,
    /// The scene again from board time 0.
    Restart,
    /// The default view (camera fitted to the table, the eye at the first
    /// observer).
    ResetView,
    /// Stop the free eye.
    Halt,
    /// The free eye above the table.
    TopView,
    /// One overlay on or off.
    Toggle(Overlay),
    /// One effect on or off.
    ToggleEffect(Effect),
    /// The camera on the next puck (after the last: the table).
    CycleFollow,
    /// The camera on puck `i`, or on the table.
    Follow(Option<usize>),
    /// Orbit the free eye (radians about the vertical, of elevation).
    Orbit(f64, f64),
    /// Turn the free eye (radians of yaw, of pitch).
    Look(f64, f64),
    /// Zoom by a factor (> 1 in).
    Zoom(f64),
    /// Seen → truth → split → seen (`--views` ends in seen).
    CycleView,
    /// One view mode.
    SetView(ViewMode),
    /// Look through the scene's observer `i`, or the free eye.
    SetObserver(Option<usize>),
    /// Board seconds per real second.
    TimeScale(f64),
    /// Show board time `t`, paused.
    ReplayTo(f64),
    /// Restart with another speed of light, m/s.
    RestartWithC(f64),
    /// Open or close the scene menu.
    SceneMenu,
    /// Open what the scene menu offers: a scene in place of the game (a
    /// lesson that ran ends), or a lesson (the window starts it).
    Open(super::scene_menu::Choice),
    /// A scene opened from the menu replaced the game: the window ends
    /// the lesson that ran, if one did (what [`UiAction::apply`] returns
    /// for an [`UiAction::Open`] of a scene).
    SceneOpened,
    /// The CAVE walls for the next eye (mono, left, right).
    CycleCaveEye,
    /// Copy the link that opens this scene (key K, the browser page's
    /// *share* button; the page builds the link, [`crate::links`]).
    Share,
    /// Load the lesson file again.
    ReloadLesson,
    /// Answer `i` to the lesson's open question.
    Answer(usize),
    /// Put the cue on the next puck (keys: play without a mouse).
    CueNext,
    /// Turn the cued stroke, radians counter-clockwise from above.
    CueTurn(f64),
    /// Make the cued stroke this many times as strong.
    CueScale(f64),
    /// Strike the cued stroke.
    Strike,
}

/// One turn of the cue by `[` or `]`, radians.
const FIVE_DEGREES: f64 = std::f64::consts::PI / 36.0;

/// The keys, each with its action (the scene menu's own keys, while it is
/// open, come first: `play::scene_menu::key`). Keys are egui's, as the
/// window, the page and `egui_kittest` all hand them to the game
/// (`play::input::Input::keys`): by their place on the keyboard where the
/// platform says it (W, A, S, D fly on any layout), else by their label;
/// the keypad's + and − and Enter are these ones.
pub const KEYS: &[(egui::Key, UiAction)] = &[
    (egui::Key::P, UiAction::Pause),
    (egui::Key::Space, UiAction::Pause),
    (egui::Key::L, UiAction::GoLive),
    (egui::Key::X, UiAction::Halt),
    (egui::Key::Home, UiAction::ResetView),
    (egui::Key::Num7, UiAction::Toggle(Overlay::Trails)),
    (egui::Key::Num8, UiAction::Toggle(Overlay::Ghost)),
    (egui::Key::Num9, UiAction::Toggle(Overlay::Arrows)),
    (egui::Key::Num0, UiAction::Toggle(Overlay::Magnifier)),
    (egui::Key::Y, UiAction::Toggle(Overlay::Diagram)),
    (egui::Key::V, UiAction::TopView),
    (egui::Key::G, UiAction::CycleFollow),
    (egui::Key::ArrowLeft, UiAction::Orbit(-0.1, 0.0)),
    (egui::Key::ArrowRight, UiAction::Orbit(0.1, 0.0)),
    (egui::Key::ArrowUp, UiAction::Orbit(0.0, 0.08)),
    (egui::Key::ArrowDown, UiAction::Orbit(0.0, -0.08)),
    (egui::Key::Equals, UiAction::Zoom(1.25)),
    (egui::Key::Plus, UiAction::Zoom(1.25)),
    (egui::Key::Minus, UiAction::Zoom(0.8)),
    (egui::Key::E, UiAction::CycleCaveEye),
    (egui::Key::F5, UiAction::ReloadLesson),
    (egui::Key::T, UiAction::CycleView),
    (egui::Key::M, UiAction::SceneMenu),
    (egui::Key::K, UiAction::Share),
    (egui::Key::C, UiAction::CueNext),
    (egui::Key::OpenBracket, UiAction::CueTurn(FIVE_DEGREES)),
    (egui::Key::CloseBracket, UiAction::CueTurn(-FIVE_DEGREES)),
    (egui::Key::Comma, UiAction::CueScale(0.8)),
    (egui::Key::Period, UiAction::CueScale(1.25)),
    (egui::Key::Enter, UiAction::Strike),
    (egui::Key::Num1, UiAction::ToggleEffect(Effect::ALL[0])),
    (egui::Key::Num2, UiAction::ToggleEffect(Effect::ALL[1])),
    (egui::Key::Num3, UiAction::ToggleEffect(Effect::ALL[2])),
    (egui::Key::Num4, UiAction::ToggleEffect(Effect::ALL[3])),
    (egui::Key::Num5, UiAction::ToggleEffect(Effect::ALL[4])),
    (egui::Key::Num6, UiAction::ToggleEffect(Effect::ALL[5])),
];

/// The action of `key`, if it has one.
pub fn for_key(key: egui::Key) -> Option<UiAction> {
    KEYS.iter().find(|(k, _)| *k == key).map(|&(_, a)| a)
}

impl UiAction {
    /// Carries the action out on the game. Returns it back when it is not
    /// the game's but the window's (the CAVE eye, the lesson), for the
    /// window to carry out.
    pub fn apply(self, s: &mut GameState) -> Option<UiAction> {
        match self {
            UiAction::Pause => {
                s.paused = !s.paused;
                s.intro = false;
            }
            UiAction::Start => {
                s.intro = false;
                s.paused = false;
            }
            UiAction::GoLive => s.go_live(),
            UiAction::Restart => s.restart(),
            UiAction::ResetView => s.reset_view(),
            UiAction::Halt => s.halt(),
            UiAction::TopView => s.top_view(),
            UiAction::Toggle(o) => {
                let on = match o {
                    Overlay::Trails => &mut s.show.trails,
                    Overlay::Ghost => &mut s.show.ghost,
                    Overlay::Arrows => &mut s.show.arrows,
                    Overlay::Magnifier => &mut s.show.magnifier,
                    Overlay::Diagram => &mut s.show.diagram,
                };
                *on = !*on;
            }
            UiAction::ToggleEffect(e) => {
                let on = s.effects.is_on(e);
                s.effects.set(e, !on);
            }
            UiAction::CycleFollow => {
                let n = s.physics().len();
                let next = match s.follow {
                    None if n > 0 => Some(0),
                    Some(i) if i + 1 < n => Some(i + 1),
                    _ => None,
                };
                return UiAction::Follow(next).apply(s);
            }
            UiAction::Follow(f) => {
                s.follow = f;
                s.framing = Framing::Fit;
            }
            UiAction::Orbit(yaw, pitch) => s.orbit(yaw, pitch),
            UiAction::Look(yaw, pitch) => s.look(yaw, pitch),
            UiAction::Zoom(factor) => s.zoom_by(factor),
            UiAction::CycleView => {
                let next = match (&s.panes, s.view) {
                    (Some(_), _) => ViewMode::Seen,
                    (None, ViewMode::Seen) => ViewMode::Truth,
                    (None, ViewMode::Truth) => ViewMode::Split,
                    (None, ViewMode::Split) => ViewMode::Seen,
                };
                s.set_view(next);
            }
            UiAction::SetView(mode) => s.set_view(mode),
            UiAction::SetObserver(o) => s.observer = o,
            UiAction::TimeScale(x) => s.time_scale = x,
            UiAction::ReplayTo(t) => s.replay_to(t),
            UiAction::RestartWithC(c) => s.restart_with_c(c),
            UiAction::SceneMenu => s.scene_menu.open = !s.scene_menu.open,
            UiAction::CueNext => s.cue_next(),
            UiAction::CueTurn(a) => s.cue_turn(a),
            UiAction::CueScale(f) => s.cue_scale(f),
            UiAction::Strike => {
                if let Err(e) = s.strike() {
                    s.message = e;
                }
            }
            UiAction::Open(choice) => {
                return match super::scene_menu::open(s, choice) {
                    Opened::Scene => Some(UiAction::SceneOpened),
                    Opened::Lesson => Some(self),
                    Opened::Nothing => None,
                };
            }
            UiAction::CycleCaveEye
            | UiAction::Share
            | UiAction::ReloadLesson
            | UiAction::Answer(_)
            | UiAction::SceneOpened => {
                return Some(self);
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn game() -> GameState {
        GameState::new(crate::assets::default_scene().unwrap())
    }

    #[test]
    fn every_key_has_one_action_and_toggles_undo_themselves() {
        for (i, (k, _)) in KEYS.iter().enumerate() {
            assert!(
                KEYS[..i].iter().all(|(q, _)| q != k),
                "{k:?} is in the table twice"
            );
        }
        let mut g = game();
        let (show, effects) = (g.show, g.effects);
        for code in [
            egui::Key::Num1,
            egui::Key::Num4,
            egui::Key::Num7,
            egui::Key::Num8,
            egui::Key::Num9,
            egui::Key::Num0,
            egui::Key::Y,
        ] {
            let a = for_key(code).unwrap();
            assert_eq!(a.apply(&mut g), None);
            assert_ne!((g.show, g.effects), (show, effects), "{code:?}");
            a.apply(&mut g);
            assert_eq!((g.show, g.effects), (show, effects), "{code:?}");
        }
        // The window's own actions come back to it.
        assert_eq!(
            for_key(egui::Key::E).unwrap().apply(&mut g),
            Some(UiAction::CycleCaveEye)
        );
    }

    /// Play without a mouse: C cues the first puck towards the table's
    /// middle at γv = 1 m/s, `]` turns it 5° clockwise, `.` makes it 1.25×
    /// as strong, Enter strikes: the puck's proper velocity changes by
    /// exactly that stroke (u adds), and C again moves the cue on.
    #[test]
    fn the_cue_aims_and_strikes_by_keys_alone() {
        let mut g = game();
        let key = |g: &mut GameState, code| {
            assert_eq!(for_key(code).unwrap().apply(g), None, "{code:?}");
        };
        key(&mut g, egui::Key::C);
        let cue = g.cue.unwrap();
        assert_eq!(cue.puck, 0);
        let here = g.physics().worldline(0).position_at(g.live_time);
        let middle = (g.scene.table.size / 2.0).extend(0.0);
        let towards = (middle - here).with_z(0.0).normalize();
        assert!((cue.du - towards * (1.0 / g.scene.c)).length() < 1e-12);
        key(&mut g, egui::Key::CloseBracket);
        key(&mut g, egui::Key::Period);
        let a = -std::f64::consts::PI / 36.0;
        let want = DVec3::new(
            towards.x * a.cos() - towards.y * a.sin(),
            towards.x * a.sin() + towards.y * a.cos(),
            0.0,
        ) * (1.25 / g.scene.c);
        assert!((g.cue.unwrap().du - want).length() < 1e-12);
        let before = g.physics().worldline(0).proper_velocity_at(g.live_time).0;
        key(&mut g, egui::Key::Enter);
        assert!(g.cue.is_none(), "struck");
        let after = g.physics().worldline(0).proper_velocity_at(g.live_time).0;
        assert!(
            (after - before - want).length() < 1e-12,
            "{after} vs {before} + {want}"
        );
        key(&mut g, egui::Key::C);
        key(&mut g, egui::Key::C);
        assert_eq!(g.cue.unwrap().puck, 1 % g.physics().len());
    }

    #[test]
    fn g_cycles_the_followed_puck_through_every_puck_then_the_table() {
        let mut g = game();
        let n = g.physics().len();
        let mut seen = Vec::new();
        for _ in 0..=n {
            UiAction::CycleFollow.apply(&mut g);
            seen.push(g.follow);
        }
        let want: Vec<Option<usize>> = (0..n).map(Some).chain([None]).collect();
        assert_eq!(seen, want);
        assert_eq!(g.framing, Framing::Fit);
    }

    #[test]
    fn t_cycles_seen_truth_split_and_ends_views() {
        let mut g = game();
        let mut modes = Vec::new();
        for _ in 0..3 {
            UiAction::CycleView.apply(&mut g);
            modes.push(g.view);
        }
        assert_eq!(modes, [ViewMode::Truth, ViewMode::Split, ViewMode::Seen]);
        g.panes = Some(crate::model::Pane::parse_list("seen,truth", &g.scene).unwrap());
        g.view = ViewMode::Truth;
        UiAction::CycleView.apply(&mut g);
        assert_eq!((g.panes.is_none(), g.view), (true, ViewMode::Seen));
    }
}
