//! The egui panels of the game's window: the controls on the left, the
//! lesson's panel on the right, the diagram and scene-menu windows, the
//! scene's intro and the clocks over the pictures. Every button, checkbox,
//! slider and choice of the controls asks through a [`UiAction`], as the
//! keys do (the diagram's and the scene menu's own fields are theirs).

use lightcone_engine::scene::Effect;

use super::actions::{Overlay, UiAction};
use super::layout::SceneArea;
use super::lesson_panel::LessonStatus;
use crate::model::{GameState, ViewMode};

/// What the panels show besides the game state.
pub struct Hud {
    /// The tracker's status line.
    pub tracker: Option<String>,
    /// Its colour (green when live).
    pub tracker_colour: egui::Color32,
    /// Draw the clocks over the desktop views (not over CAVE walls).
    pub clocks: bool,
    /// The lesson running, by name (it owns c).
    pub lesson: Option<String>,
    /// The window can start lessons (the desktop game: they need Python);
    /// the scene menu lists them then.
    pub lessons: bool,
    /// Offer a *share* button (the browser page: it copies the link that
    /// opens this scene, see [`crate::links`]).
    pub share: bool,
}

/// The panels and the clocks drawn on the pucks, in a window of `size`
/// (physical px). Clicks become `actions`. Returns the area left for the
/// views.
pub fn panels(
    ui: &mut egui::Ui,
    state: &mut GameState,
    hud: &Hud,
    lesson: Option<&dyn LessonStatus>,
    size: (u32, u32),
    actions: &mut Vec<UiAction>,
) -> SceneArea {
    let ctx = ui.ctx().clone();
    let ppp = ctx.pixels_per_point();
    // Only a lesson's panel takes room on the right.
    let mut right = size.0 as f32;
    if let Some(host) = lesson {
        egui::Panel::right("lesson")
            .default_size(340.0)
            .show(ui, |ui| super::lesson_panel::show(ui, host, actions));
        right = ui.available_rect_before_wrap().right() * ppp;
    }
    egui::Panel::left("controls")
        .default_size(260.0)
        .show(ui, |ui| controls(ui, state, hud, actions));
    let left = ui.available_rect_before_wrap().left() * ppp;
    if state.show.diagram {
        let at = egui::pos2(left / ppp + 12.0, (size.1 as f32 / ppp - 500.0).max(8.0));
        super::diagram::window(&ctx, state, at, actions);
    }
    let menu = super::scene_menu::MenuContext {
        lessons: hud.lessons,
        running: hud.lesson.as_deref(),
    };
    if let Some(choice) = super::scene_menu::window(&ctx, state, menu) {
        actions.push(UiAction::Open(choice));
    }
    if state.intro {
        intro(state, &ctx, (left + right) / 2.0 / ppp, 12.0, actions);
    }
    if hud.clocks {
        super::overlay::layer(&ctx, state, left, right, size.1 as f32);
    }
    SceneArea { left, right }
}

/// The left panel, top to bottom.
fn controls(ui: &mut egui::Ui, s: &GameState, hud: &Hud, actions: &mut Vec<UiAction>) {
    ui.heading("Lightcone");
    ui.label(&s.scene.title);
    let menu = if hud.lessons {
        "other scenes and lessons… (M)"
    } else {
        "other scenes… (M)"
    };
    ui.horizontal(|ui| {
        if ui.small_button(menu).clicked() {
            actions.push(UiAction::SceneMenu);
        }
        if hud.share
            && ui
                .small_button("share")
                .on_hover_text(
                    "copy a link that opens this scene (a file of your own travels in the link)",
                )
                .clicked()
        {
            actions.push(UiAction::Share);
        }
    });
    ui.separator();
    time_controls(ui, s, actions);
    ui.separator();
    light_and_effects(ui, s, hud, actions);
    view_controls(ui, s, actions);
    ui.separator();
    puck_table(ui, s);
    status_lines(ui, s, hud);
    ui.separator();
    ui.small(
        "Drag from a puck to aim the cue (pull back, release to strike); \
         or C, [ ], , . and Enter.",
    );
    // Where a browser user looks for what the desktop game has.
    #[cfg(target_arch = "wasm32")]
    ui.small(
        "In the browser: lessons run their Python in the page (Pyodide, \
         started the first time a lesson opens); no head tracker, CAVE or \
         render cluster (desktop only: see docs/web.md).",
    );
}

/// Play, pause, live, restart; the time scale, the board-time slider and
/// the replay window.
fn time_controls(ui: &mut egui::Ui, s: &GameState, actions: &mut Vec<UiAction>) {
    ui.horizontal(|ui| {
        let pause = if s.paused { "play (P)" } else { "pause (P)" };
        for (label, action) in [
            (pause, UiAction::Pause),
            ("live (L)", UiAction::GoLive),
            ("restart", UiAction::Restart),
            ("view (Home)", UiAction::ResetView),
        ] {
            if ui.button(label).clicked() {
                actions.push(action);
            }
        }
    });
    let mut scale = s.time_scale;
    if ui
        .add(
            egui::Slider::new(&mut scale, 0.01..=4.0)
                .logarithmic(true)
                .text("time scale"),
        )
        .changed()
    {
        actions.push(UiAction::TimeScale(scale));
    }
    let mut t = s.view_time;
    let live = s.live_time.max(1e-9);
    // The replay window: the past before it is forgotten.
    let oldest = s
        .physics()
        .forgotten_before()
        .map_or(0.0, |f| f.clamp(0.0, live));
    if ui
        .add(egui::Slider::new(&mut t, oldest..=live).text("board time (s)"))
        .changed()
    {
        actions.push(UiAction::ReplayTo(t));
    }
    ui.label(format!(
        "replay window: the last {:.0} min of board time{}",
        crate::model::REPLAY_WINDOW / 60.0,
        if oldest > 0.0 {
            format!(" (before {oldest:.0} s is forgotten)")
        } else {
            String::new()
        }
    ));
    // Always one line (the panel below does not shift when a replay
    // starts or ends).
    if s.replaying() {
        ui.colored_label(
            egui::Color32::YELLOW,
            "replay: what was seen then (L: live)",
        );
    } else {
        ui.colored_label(egui::Color32::from_gray(140), "live");
    }
}

/// The speed of light, the effects and the overlays.
fn light_and_effects(ui: &mut egui::Ui, s: &GameState, hud: &Hud, actions: &mut Vec<UiAction>) {
    let mut c = s.scene.c;
    // A lesson sets c itself (restarting under it would break its
    // bookkeeping). The slider spans 0.2 m/s to 1 km/s (about 60 px a
    // decade at the panel's width); the number beside it takes any c the
    // scene rules accept when typed (10⁶ m/s: Newton). A drag applies when
    // it ends, a typed value when it is entered.
    ui.add_enabled_ui(hud.lesson.is_none(), |ui| {
        ui.horizontal(|ui| {
            let slider = ui.add(
                egui::Slider::new(&mut c, 0.2..=1.0e3)
                    .logarithmic(true)
                    .clamping(egui::SliderClamping::Never)
                    .max_decimals(3)
                    .text("c (m/s)"),
            );
            if slider.drag_stopped() || (slider.changed() && !slider.dragged()) {
                actions.push(UiAction::RestartWithC(c));
            }
        });
        let scene_c = format!("scene's c ({})", short_speed(s.scene_c));
        if ui
            .add_enabled(s.scene.c != s.scene_c, egui::Button::new(scene_c))
            .on_hover_text("back to the c the scene or lesson was written for")
            .clicked()
        {
            actions.push(UiAction::RestartWithC(s.scene_c));
        }
    });
    ui.label("effects (1–6):");
    for e in Effect::ALL {
        let mut on = s.effects.is_on(e);
        if ui.checkbox(&mut on, e.key()).changed() {
            actions.push(UiAction::ToggleEffect(e));
        }
    }
    let mut overlay = |ui: &mut egui::Ui, mut on: bool, label: &str, o: Overlay| {
        if ui.checkbox(&mut on, label).changed() {
            actions.push(UiAction::Toggle(o));
        }
    };
    ui.horizontal(|ui| {
        overlay(ui, s.show.trails, "trails (7)", Overlay::Trails);
        overlay(ui, s.show.ghost, "ghost (8)", Overlay::Ghost);
        overlay(ui, s.show.arrows, "arrows (9)", Overlay::Arrows);
    });
    ui.horizontal(|ui| {
        overlay(ui, s.show.magnifier, "magnifier (0)", Overlay::Magnifier);
        overlay(
            ui,
            s.show.diagram,
            "space-time diagram (Y)",
            Overlay::Diagram,
        );
    });
    if s.effects.doppler {
        super::overlay::doppler_legend(ui);
    }
}

/// The view mode, the eye looked through, the puck followed, the zoom and
/// the free eye's velocity.
fn view_controls(ui: &mut egui::Ui, s: &GameState, actions: &mut Vec<UiAction>) {
    ui.label("view (T):");
    ui.horizontal(|ui| {
        let mut mode = s.panes.is_none().then_some(s.view);
        ui.selectable_value(&mut mode, Some(ViewMode::Seen), "seen");
        ui.selectable_value(&mut mode, Some(ViewMode::Truth), "truth");
        ui.selectable_value(&mut mode, Some(ViewMode::Split), "split");
        if s.panes.is_some() {
            let _ = ui.selectable_label(true, "--views");
        }
        if let Some(m) = mode
            && (s.panes.is_some() || m != s.view)
        {
            actions.push(UiAction::SetView(m));
        }
    });
    let mut observer = s.observer;
    egui::ComboBox::from_label("eye")
        .selected_text(match s.observer {
            None => "you (WASD, R/F, right-drag)".to_owned(),
            Some(i) => s.scene.observers[i].name.clone(),
        })
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut observer, None, "you");
            for (i, o) in s.scene.observers.iter().enumerate() {
                ui.selectable_value(&mut observer, Some(i), &o.name);
            }
        });
    if observer != s.observer {
        actions.push(UiAction::SetObserver(observer));
    }
    let follow_name = |f: Option<usize>| match f {
        Some(i) if i < s.scene.pucks.len() => s.scene.pucks[i].name.clone(),
        _ => "the table".to_owned(),
    };
    let mut follow = s.follow;
    egui::ComboBox::from_label("camera on (G)")
        .selected_text(follow_name(follow))
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut follow, None, "the table");
            for (i, p) in s.scene.pucks.iter().enumerate() {
                ui.selectable_value(&mut follow, Some(i), &p.name);
            }
        });
    if follow != s.follow {
        actions.push(UiAction::Follow(follow));
    }
    ui.horizontal(|ui| {
        if ui.button("from above (V)").clicked() {
            actions.push(UiAction::TopView);
        }
        ui.label(format!("zoom {:.2}× (wheel)", s.zoom));
    });
    // The eye looked through: the free eye (which X stops) or a scene
    // observer (on its own worldline).
    let looked = s.observer.and_then(|i| s.scene.observers.get(i));
    let u = match looked {
        Some(_) => s.eye().u,
        None => s.eye_velocity(),
    };
    let eb = u.beta();
    let who = looked.map_or("your".to_owned(), |o| format!("{}'s", o.name));
    let stops = if looked.is_some() { "" } else { " (X stops)" };
    ui.label(format!(
        "{who} β = ({:.3}, {:.3}, {:.3}), γ = {:.4}{stops}",
        eb.x,
        eb.y,
        eb.z,
        u.gamma()
    ));
}

/// Every puck's speed, γ and proper time at the board time shown.
fn puck_table(ui: &mut egui::Ui, s: &GameState) {
    ui.label("pucks now (board frame):");
    egui::Grid::new("pucks").striped(true).show(ui, |ui| {
        ui.label("name");
        ui.label("|β|");
        ui.label("γ");
        ui.label("τ (s)");
        ui.end_row();
        for i in 0..s.physics().len() {
            let st = s.physics().worldline(i).state_at(s.view_time);
            ui.label(s.physics().name(i));
            ui.label(format!("{:.4}", st.u.beta().length()));
            ui.label(format!("{:.4}", st.u.gamma()));
            ui.label(format!("{:.3}", st.proper_time));
            ui.end_row();
        }
    });
}

/// The last collision, the cue being aimed, the tracker's status and the
/// game's message.
fn status_lines(ui: &mut egui::Ui, s: &GameState, hud: &Hud) {
    if let Some(c) = s.last_collision() {
        ui.label(format!("last collision: {c}"));
    }
    if let Some(cue) = s.cue {
        let u = lightcone_engine::spacetime::ProperVelocity(
            s.physics()
                .worldline(cue.puck)
                .proper_velocity_at(s.live_time)
                .0
                + cue.du,
        );
        ui.colored_label(
            egui::Color32::LIGHT_BLUE,
            format!(
                "cue on {}: β = {:.6}, γ = {:.4}",
                s.physics().name(cue.puck),
                u.beta().length(),
                u.gamma()
            ),
        );
    }
    if let Some(line) = &hud.tracker {
        ui.separator();
        ui.colored_label(hud.tracker_colour, line);
    }
    if !s.message.is_empty() {
        ui.colored_label(egui::Color32::LIGHT_RED, &s.message);
    }
    let clocks: Vec<f64> = s
        .sim
        .views()
        .iter()
        .flat_map(|&v| s.centres(v))
        .map(|c| c.clock)
        .collect();
    for hint in s.hints(&clocks) {
        ui.colored_label(egui::Color32::from_rgb(255, 210, 120), hint);
    }
}

/// The scene's title and description at the top of the views, with a
/// start button (Space or P also starts), its top centre at `(x, y)`
/// (points).
fn intro(state: &GameState, ctx: &egui::Context, x: f32, y: f32, actions: &mut Vec<UiAction>) {
    egui::Area::new(egui::Id::unique("intro"))
        .fixed_pos(egui::pos2(x, y))
        .pivot(egui::Align2::CENTER_TOP)
        .order(egui::Order::Foreground)
        .show(ctx, |ui| {
            egui::Frame::window(ui.style()).show(ui, |ui| {
                ui.set_max_width(420.0);
                ui.heading(&state.scene.title);
                if !state.scene.description.is_empty() {
                    ui.add(
                        egui::Label::new(
                            egui::RichText::new(&state.scene.description).size(15.0),
                        )
                        .wrap(),
                    );
                }
                ui.separator();
                ui.small(
                    "Drag from a puck to strike it. Wheel: zoom; middle-drag or arrows: orbit; \
                     V: from above; G: follow a puck; Home: reset the view; T: seen / truth / split.",
                );
                if ui.button("start (Space)").clicked() {
                    actions.push(UiAction::Start);
                }
            });
        });
}

/// A render node's one line of status (it shows only its walls).
pub fn node_status(ui: &mut egui::Ui, message: &str) {
    egui::Area::new(egui::Id::unique("node status"))
        .anchor(egui::Align2::LEFT_BOTTOM, egui::vec2(8.0, -8.0))
        .show(ui.ctx(), |ui| {
            ui.label(
                egui::RichText::new(message)
                    .small()
                    .color(egui::Color32::GRAY),
            );
        });
}

/// `c` in m/s in a few characters: `1.42 m/s`, `300 m/s`, `1e6 m/s`.
fn short_speed(c: f64) -> String {
    if c >= 1.0e4 {
        format!("{c:.0e} m/s")
    } else {
        format!("{} m/s", (c * 1000.0).round() / 1000.0)
    }
}

#[cfg(test)]
#[path = "panels_tests.rs"]
mod tests;
