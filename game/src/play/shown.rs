//! One picture on the screen, as the overlays read it: what its view
//! showed at the last frame (eye, camera, effects), where a point it saw
//! falls in its rectangle, and the colour a puck is marked in there.

use glam::{DVec2, DVec3, Vec4};

use crate::model::{GameState, Pane};
use lightcone_engine::ecs::Entity;
use lightcone_engine::optics::Eye;
use lightcone_engine::scene::Effects;
use lightcone_render::frame::Camera;

/// Width / height of a rectangle `[x, y, w, h]`.
pub fn aspect(rect: [f32; 4]) -> f64 {
    f64::from(rect[2].max(1.0)) / f64::from(rect[3].max(1.0))
}

/// Screen position (physical px) of a point at `p` relative to the eye in
/// the observer's frame, inside `rect`; `None` behind the camera.
pub fn project(camera: &Camera, rect: [f32; 4], p: DVec3) -> Option<DVec2> {
    let m = camera.view_proj(rect[2] / rect[3]);
    let clip = m * Vec4::new(p.x as f32, p.y as f32, p.z as f32, 1.0);
    if clip.w <= 1e-6 {
        return None;
    }
    let (x, y) = (clip.x / clip.w, clip.y / clip.w);
    Some(DVec2::new(
        f64::from(rect[0] + (x + 1.0) / 2.0 * rect[2]),
        f64::from(rect[1] + (1.0 - y) / 2.0 * rect[3]),
    ))
}

/// The colour a puck is ringed and named in: its own, lightened when too
/// dark to see on the dark room (a black puck).
pub fn ring_colour(c: lightcone_engine::scene::Color) -> egui::Color32 {
    let y = 0.2126 * f32::from(c.r) + 0.7152 * f32::from(c.g) + 0.0722 * f32::from(c.b);
    if y < 40.0 {
        let mix = |x: u8| ((f32::from(x) + 200.0) / 2.0) as u8;
        egui::Color32::from_rgb(mix(c.r), mix(c.g), mix(c.b))
    } else {
        egui::Color32::from_rgb(c.r, c.g, c.b)
    }
}

/// What one picture's view saw at the last frame: the view entity, its eye,
/// its camera and its effects.
pub struct Shown {
    /// The view entity.
    pub view: Entity,
    /// The eye (observation event, observer's proper velocity).
    pub eye: Eye,
    /// The camera.
    pub camera: Camera,
    /// The effects the view has.
    pub effects: Effects,
}

/// What the picture `pane` showed at the last frame; `None` before its view
/// ran.
pub fn shown(state: &GameState, pane: Pane) -> Option<Shown> {
    let view = state.view_of(pane)?;
    Some(Shown {
        view,
        eye: state.apparent(view)?.eye?,
        camera: state.camera(view)?,
        effects: state.view_effects(view),
    })
}
