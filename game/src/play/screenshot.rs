//! `--screenshot`: the window's frame read back into a PNG, and beside it
//! the layout sidecar (`shot.json`) saying where the views, pucks and CAVE
//! walls are, for tests and for marking up slides.

use std::path::Path;

use lightcone_render::gpu::Gpu;
use lightcone_tracker::cave::CaveConfig;

use super::diagram::Placed;
use super::layout::{Plan, SceneArea, tiled_walls, wall_tiles};
use super::overlay::Drawn;
use crate::model::GameState;

/// Beside a screenshot, where its views, pucks, labels, magnifier and
/// diagram are (for tests and for marking up slides): the
/// [`super::sidecar::layout`] of the frame (the page publishes the same
/// as `window.lightconeLayout`), or in a CAVE the walls'. `drawn`: what
/// the overlays drew this frame.
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
    let text = super::sidecar::layout(state, area, diagram, (w, h), drawn).to_string();
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
