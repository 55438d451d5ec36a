//! Where a frame's views, pucks, labels, magnifier and diagram are, as
//! JSON: the sidecar `play --screenshot` and `render` write beside their
//! PNG, and what the page publishes as `window.lightconeLayout` (opened
//! at a board time, `?at=`), so that the window's and the page's pictures are measured
//! by the same numbers.

use lightcone_render::frame::ViewKind;

use super::diagram::Placed;
use super::layout::SceneArea;
use super::overlay::{Drawn, caption, markers};
use super::shown::ring_colour;
use crate::model::GameState;

/// Where the frame's views, pucks, labels, magnifier and diagram are
/// (for tests and for marking up slides): `{"views": [{"rect":
/// [x, y, w, h], "kind", "caption"}], "pucks": [{"name", "view", "centre":
/// [x, y], "ring_px", "ring_colour": [r, g, b], "clock_s"}], "labels":
/// [{"puck", "view", "rect": [x, y, w, h], "text": "name" | "clock"}],
/// "magnifier": null | {"puck", "view", "rect", "body": [x, y, w, h],
/// "colour": [r, g, b], "beta", "gamma", "length_over_width",
/// "contraction", "light_delay"}, "diagram": {"rect": [x, y, w, h], "x":
/// [m, m], "t": [s, s]} or null, "scene_pucks": n}`, physical px from the
/// top left; the diagram's rect is where its data is drawn, board x (or y)
/// `x` across it and board time `t` up it. `drawn`: what the overlays drew
/// this frame.
#[must_use]
pub fn layout(
    state: &GameState,
    area: SceneArea,
    diagram: Option<Placed>,
    (w, h): (f32, f32),
    drawn: &Drawn,
) -> serde_json::Value {
    let rects = area.rects(&state.pane_list(), w, h);
    let views: Vec<serde_json::Value> = rects
        .iter()
        .map(|(r, p)| {
            serde_json::json!({
                "rect": r,
                "kind": match p.kind { ViewKind::Seen => "seen", ViewKind::Truth => "truth" },
                "caption": caption(state, *p),
            })
        })
        .collect();
    let pucks: Vec<serde_json::Value> = markers(state, &rects)
        .iter()
        .map(|m| {
            let c = ring_colour(state.scene.pucks[m.puck].color);
            serde_json::json!({
                "name": state.scene.pucks[m.puck].name,
                "view": m.view,
                "centre": [m.centre.x, m.centre.y],
                "ring_px": 2.0 * m.ring,
                "ring_colour": [c.r(), c.g(), c.b()],
                "clock_s": m.clock,
            })
        })
        .collect();
    let labels: Vec<serde_json::Value> = drawn
        .labels
        .iter()
        .map(|l| {
            serde_json::json!({
                "puck": state.scene.pucks[l.puck].name,
                "view": l.view,
                "rect": l.rect,
                "text": if l.is_name { "name" } else { "clock" },
            })
        })
        .collect();
    let magnifier = drawn.magnifier.as_ref().map(|m| {
        let c = ring_colour(state.scene.pucks[m.puck].color);
        serde_json::json!({
            "puck": state.scene.pucks[m.puck].name,
            "view": m.view,
            "rect": m.rect,
            "body": m.body,
            "colour": [c.r(), c.g(), c.b()],
            "beta": m.beta,
            "gamma": m.gamma,
            "length_over_width": m.length_over_width,
            "contraction": m.contraction,
            "light_delay": m.light_delay,
        })
    });
    serde_json::json!({
        "views": views,
        "pucks": pucks,
        "labels": labels,
        "magnifier": magnifier,
        "scene_pucks": state.physics().len(),
        "diagram": diagram.map(|d| serde_json::json!({
            "rect": [d.area.left, d.area.top, d.area.width, d.area.height],
            "x": [d.x.0, d.x.1],
            "t": [d.t.0, d.t.1],
        })),
    })
}
