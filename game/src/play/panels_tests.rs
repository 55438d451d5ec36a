//! The controls panel driven as a screen reader and a keyboard drive it
//! (egui_kittest, through egui's AccessKit tree): every control has a
//! name, a click or a key on it asks for its `UiAction`, the c field
//! takes a typed value, and Tab reaches every control in the order the
//! panel shows them.

use egui_kittest::kittest::{NodeT, Queryable, by};
use egui_kittest::{Harness, Node};
use lightcone_engine::scene::Effect;

use super::{Hud, panels};
use crate::model::GameState;
use crate::play::actions::UiAction;

/// What one harness holds: the game, the panel's context, and every
/// action the panel asked for (each carried out on the game, as the window
/// does).
struct Panel {
    game: GameState,
    input: crate::play::input::Input,
    hud: Hud,
    asked: Vec<UiAction>,
}

fn harness() -> Harness<'static, Panel> {
    let game = GameState::new(crate::assets::default_scene().expect("the default scene"));
    let hud = Hud {
        tracker: None,
        tracker_colour: egui::Color32::GRAY,
        clocks: false,
        lesson: None,
        lessons: true,
        share: false,
    };
    Harness::builder()
        .with_size(egui::vec2(1280.0, 1000.0))
        .build_ui_state(
            |ui, p: &mut Panel| {
                let mut actions = Vec::new();
                // The keys first, as the window's frame takes them
                // (`Stage::panels`).
                p.input.keys(ui.ctx(), &mut p.game, &mut actions);
                panels(ui, &mut p.game, &p.hud, None, (1280, 1000), &mut actions);
                for action in actions {
                    p.asked.push(action);
                    let _ = action.apply(&mut p.game);
                }
            },
            Panel {
                game,
                input: crate::play::input::Input::new(true),
                hud,
                asked: Vec::new(),
            },
        )
}

/// The name a screen reader gives each control of the panel, top to
/// bottom (the `scene's c` button's name carries the scene's c).
fn control_names(game: &GameState) -> Vec<String> {
    let mut names: Vec<String> = [
        "other scenes and lessons… (M)",
        "pause (P)",
        "live (L)",
        "restart",
        "view (Home)",
        "time scale",
        "board time (s)",
        "c (m/s)",
    ]
    .iter()
    .map(|s| (*s).to_owned())
    .collect();
    names.push(format!("scene's c ({})", super::short_speed(game.scene_c)));
    names.extend(Effect::ALL.iter().map(|e| e.key().to_owned()));
    names.extend(
        [
            "trails (7)",
            "ghost (8)",
            "arrows (9)",
            "magnifier (0)",
            "space-time diagram (Y)",
            "seen",
            "truth",
            "split",
            "eye",
            "camera on (G)",
            "from above (V)",
        ]
        .iter()
        .map(|s| (*s).to_owned()),
    );
    names
}

/// Is `node` something a user acts on (a screen reader announces it as a
/// control)?
fn is_control(node: &Node<'_>) -> bool {
    use egui::accesskit::Role;
    matches!(
        node.accesskit_node().role(),
        Role::Button
            | Role::CheckBox
            | Role::Slider
            | Role::SpinButton
            | Role::ComboBox
            | Role::TextInput
            | Role::Tab
            | Role::RadioButton
    )
}

#[test]
fn every_control_of_the_panel_has_a_name_a_screen_reader_reads() {
    let mut h = harness();
    h.run();
    for name in control_names(&h.state().game) {
        // A slider is named twice: the slider and the number beside it.
        assert!(
            h.query_all_by_label(&name).next().is_some(),
            "no control named {name:?}"
        );
    }
    let unnamed: Vec<String> = h
        .query_all(by().predicate(|_| true))
        .filter(is_control)
        .filter(|n| {
            n.accesskit_node()
                .label()
                .is_none_or(|l| l.trim().is_empty())
        })
        .map(|n| format!("{n:?}"))
        .collect();
    assert!(unnamed.is_empty(), "controls without a name: {unnamed:#?}");
}

#[test]
fn a_click_on_a_control_asks_for_its_action_and_the_game_follows() {
    let mut h = harness();
    h.run();
    let paused = h.state().game.paused;
    h.get_by_label("pause (P)").click();
    h.run();
    assert_eq!(h.state().asked, vec![UiAction::Pause]);
    assert_eq!(h.state().game.paused, !paused);
    h.get_by_label("trails (7)").click();
    h.run();
    assert!(
        h.state()
            .asked
            .contains(&UiAction::Toggle(crate::play::actions::Overlay::Trails))
    );
    // The same through AccessKit's own action (what a screen reader's
    // "activate" sends), not a pointer.
    h.state_mut().asked.clear();
    h.get_by_label("from above (V)").click_accesskit();
    h.run();
    assert_eq!(h.state().asked, vec![UiAction::TopView]);
}

/// The speed of light is typed, not only dragged: a value set on the c
/// control (as a screen reader or the keyboard enters it) restarts the
/// scene under that c, keeping momentum, and the scene's c button takes
/// it back.
#[test]
fn c_takes_a_typed_value_and_the_scenes_c_comes_back() {
    let mut h = harness();
    h.run();
    let scene_c = h.state().game.scene_c;
    h.get(by().label("c (m/s)").role(egui::accesskit::Role::Slider))
        .set_value_accesskit(250.0);
    h.run();
    assert!(
        h.state()
            .asked
            .iter()
            .any(|a| matches!(a, UiAction::RestartWithC(c) if (*c - 250.0).abs() < 1e-9)),
        "{:?}",
        h.state().asked
    );
    assert!((h.state().game.scene.c - 250.0).abs() < 1e-9);
    let back = format!("scene's c ({})", super::short_speed(scene_c));
    h.get_by_label(&back).click();
    h.run();
    assert_eq!(h.state().game.scene.c, scene_c);
}

/// Keyboard only: Tab walks the panel's controls in the order they are
/// shown, reaching every enabled one; Space on a focused button presses it.
#[test]
fn tab_reaches_every_control_in_order_and_space_presses_it() {
    let mut h = harness();
    h.run();
    // The scene's-c button is disabled while c is the scene's: not a stop.
    let scene_c = format!("scene's c ({})", super::short_speed(h.state().game.scene_c));
    let names: Vec<String> = control_names(&h.state().game)
        .into_iter()
        .filter(|n| *n != scene_c)
        .collect();
    let mut focused: Vec<String> = Vec::new();
    for _ in 0..4 * names.len() {
        h.key_press(egui::Key::Tab);
        h.run();
        if let Some(node) = h
            .query_all(by().predicate(|_| true))
            .find(|n| n.is_focused())
            && let Some(label) = node.accesskit_node().label()
            && focused.last() != Some(&label)
        {
            focused.push(label);
        }
    }
    let order: Vec<usize> = names
        .iter()
        .map(|name| {
            focused
                .iter()
                .position(|f| f == name)
                .unwrap_or_else(|| panic!("Tab never reaches {name:?}: {focused:?}"))
        })
        .collect();
    // The first visit of each control comes in the panel's order.
    for pair in order.windows(2) {
        assert!(pair[0] < pair[1], "Tab order {focused:?}");
    }
    // Tab to "pause (P)" from the top, then Space.
    let mut h = harness();
    h.run();
    for _ in 0..names.len() * 2 {
        h.key_press(egui::Key::Tab);
        h.run();
        if h.get_by_label("pause (P)").is_focused() {
            break;
        }
    }
    assert!(h.get_by_label("pause (P)").is_focused());
    let paused = h.state().game.paused;
    h.key_press(egui::Key::Space);
    h.run();
    assert_eq!(h.state().game.paused, !paused);
}

/// Play by keys alone, through egui as the window and the page hand keys
/// to the game: C cues the first puck, `]` turns the cue 5° clockwise, `.`
/// makes it 1.25× as strong, Enter strikes (the puck's proper velocity
/// changes by the stroke); while the c field is being typed into, the
/// keys are the field's; a control reached by Tab keeps Enter and Space
/// (pressing it) while the other keys play, and Escape gives them back.
#[test]
fn the_cue_aims_and_strikes_by_keys_through_egui() {
    let mut h = harness();
    h.run();
    h.key_press(egui::Key::C);
    h.run();
    let cue = h.state().game.cue.expect("C cues a puck");
    assert_eq!(cue.puck, 0);
    h.key_press(egui::Key::CloseBracket);
    h.key_press(egui::Key::Period);
    h.run();
    let a = -std::f64::consts::PI / 36.0;
    let du = cue.du;
    let want = glam::DVec3::new(
        du.x * a.cos() - du.y * a.sin(),
        du.x * a.sin() + du.y * a.cos(),
        0.0,
    ) * 1.25;
    let turned = h.state().game.cue.expect("still cued").du;
    assert!((turned - want).length() < 1e-12, "{turned} against {want}");
    // The first puck's proper velocity at the live time.
    let u_now = |h: &Harness<'static, Panel>| {
        let game = &h.state().game;
        game.physics()
            .worldline(0)
            .proper_velocity_at(game.live_time)
            .0
    };
    let before = u_now(&h);
    h.key_press(egui::Key::Enter);
    h.run();
    assert!(h.state().game.cue.is_none(), "Enter strikes");
    let after = u_now(&h);
    assert!(
        (after - before - want).length() < 1e-12,
        "{after} vs {before} + {want}"
    );
    assert_eq!(
        h.state().asked,
        vec![
            UiAction::CueNext,
            UiAction::CueTurn(-std::f64::consts::PI / 36.0),
            UiAction::CueScale(1.25),
            UiAction::Strike
        ]
    );

    // Typing into the c field: its keys are the field's.
    let mut h = harness();
    h.run();
    h.get(
        by().label("c (m/s)")
            .role(egui::accesskit::Role::SpinButton),
    )
    .focus();
    h.run();
    h.key_press(egui::Key::C);
    h.key_press(egui::Key::P);
    h.run();
    assert!(
        h.state().game.cue.is_none(),
        "C typed into the c field cued"
    );
    assert!(
        !h.state().asked.contains(&UiAction::Pause),
        "{:?}",
        h.state().asked
    );

    // A control reached by Tab takes Enter; Escape gives it back.
    let mut h = harness();
    h.run();
    h.key_press(egui::Key::C);
    h.run();
    h.get_by_label("live (L)").focus();
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    assert!(
        h.state().game.cue.is_some(),
        "Enter on a focused control struck"
    );
    assert_eq!(h.state().asked.last(), Some(&UiAction::GoLive));
    // The other keys still play.
    let paused = h.state().game.paused;
    h.key_press(egui::Key::P);
    h.run();
    assert_eq!(h.state().game.paused, !paused, "P with a control focused");
    h.key_press(egui::Key::Escape);
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    assert!(
        h.state().game.cue.is_none(),
        "Enter after Escape did not strike"
    );
}
