//! `--screenshot`: the window's frame read back into a PNG, and beside it
//! the layout sidecar (`shot.json`) saying where the views, pucks and CAVE
//! walls are, for tests and for marking up slides.

use std::path::Path;

use lightcone_render::frame::ViewKind;
use lightcone_render::gpu::Gpu;
use lightcone_tracker::cave::CaveConfig;

use super::diagram::Placed;
use super::layout::{Plan, SceneArea, tiled_walls, wall_tiles};
use super::overlay::{Drawn, caption, markers};
use super::shown::ring_colour;
use crate::model::GameState;

/// Beside a screenshot, where its views, pucks, labels, magnifier and
/// diagram are (for tests and for marking up slides): `{"views": [{"rect":
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
pub fn save_layout(
    state: &GameState,
    cave: Option<&CaveConfig>,
    area: SceneArea,
    diagram: Option<Placed>,
    path: &Path,
    (w, h): (f32, f32),
    drawn: &Drawn,
) -> Result<(), String> {
    if let Some(c) = cave {
        return save_cave_layout(state, c, area, path, (w, h));
    }
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
    let text = serde_json::json!({
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
    .to_string();
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// In a CAVE, beside the main window's screenshot: the walls tiled
/// there (`{"walls": [{"rect": [x, y, w, h], "wall": name}], "outputs":
/// [name], "scene_pucks": n}`, physical px from the top left; the
/// walls no output shows, or all of them when every wall has one), and
/// the outputs saved beside it as `<shot>.<name>.png`.
fn save_cave_layout(
    state: &GameState,
    cave: &CaveConfig,
    area: SceneArea,
    path: &Path,
    (w, h): (f32, f32),
) -> Result<(), String> {
    let (left, width) = area.span(w);
    let tiles: Vec<serde_json::Value> = wall_tiles(cave, &tiled_walls(cave), left, width, h)
        .iter()
        .filter_map(|(r, plan)| match plan {
            Plan::Wall(i) => Some(serde_json::json!({
                "rect": r,
                "wall": cave.walls[*i].name,
            })),
            Plan::Desktop(_) => None,
        })
        .collect();
    let outputs: Vec<&str> = cave.outputs.iter().map(|o| o.name.as_str()).collect();
    let text = serde_json::json!({
        "walls": tiles,
        "outputs": outputs,
        "scene_pucks": state.physics().len(),
    })
    .to_string();
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Saves the surface's frame `texture` (configured as `config`) as a PNG at
/// `path`, once what was drawn into it is done.
pub fn save_frame(
    gpu: &Gpu,
    config: &wgpu::SurfaceConfiguration,
    texture: &wgpu::Texture,
    path: &Path,
) -> Result<(), String> {
    let mut encoder = gpu
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("screenshot"),
        });
    let size = (config.width, config.height);
    let (buffer, padded) =
        lightcone_render::headless::copy_to_buffer(gpu, texture, size, &mut encoder);
    gpu.queue.submit([encoder.finish()]);
    save(gpu, config, &buffer, padded, path)
}

/// Reads the screenshot buffer back and writes it as PNG (RGBA; BGRA
/// surfaces are swizzled).
fn save(
    gpu: &Gpu,
    config: &wgpu::SurfaceConfiguration,
    buffer: &wgpu::Buffer,
    padded: u32,
    path: &Path,
) -> Result<(), String> {
    let (w, h) = (config.width, config.height);
    let mut rgba = lightcone_render::headless::read_rows(gpu, buffer, padded, w, h)?;
    lightcone_render::headless::opaque_rgba(&mut rgba, config.format);
    lightcone_render::headless::Image {
        width: w,
        height: h,
        rgba,
    }
    .save_png(path)
}
