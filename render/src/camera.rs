//! Framing: the camera direction and field of view that show a set of
//! points (the table) inside a viewport, from a given eye.
//!
//! The one camera model is the engine's ([`lightcone_engine::camera`]: the
//! eye is the observer, framing turns the camera and widens or narrows its
//! field of view, never moves it). These are its functions with the
//! renderer's [`Camera`] (which adds the GPU's view-projection matrix), so
//! the window, headless renders and the schedule's views frame alike.

use glam::DVec3;
use lightcone_engine::camera as model;

use super::frame::Camera;

pub use model::{FOV_RANGE, basis, table_corners};

impl From<Camera> for model::Camera {
    fn from(c: Camera) -> Self {
        Self {
            forward: c.forward,
            fovy: c.fovy,
        }
    }
}

/// The camera that shows every point of `points` (relative to the eye)
/// inside a viewport of `aspect` = width / height with `margin` on each
/// side, narrowed by `zoom`: [`lightcone_engine::camera::fit`].
#[must_use]
pub fn fit(points: &[DVec3], aspect: f64, margin: f64, zoom: f64) -> Camera {
    model::fit(points, aspect, margin, zoom).into()
}

/// Looking along `forward` with field of view `fovy` narrowed by `zoom`:
/// [`lightcone_engine::camera::zoomed`].
#[must_use]
pub fn zoomed(forward: DVec3, fovy: f64, zoom: f64) -> Camera {
    model::zoomed(forward, fovy, zoom).into()
}

/// Normalised device coordinates of `p` (relative to the eye) through
/// `camera`, `None` behind it: [`lightcone_engine::camera::ndc`].
#[must_use]
pub fn ndc(camera: &Camera, aspect: f64, p: DVec3) -> Option<(f64, f64)> {
    model::ndc(&(*camera).into(), aspect, p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn the_renderer_frames_as_the_engine_does() {
        let eye = DVec3::new(1.42, -0.9, 0.9);
        let points: Vec<DVec3> = table_corners(DVec2::new(2.84, 1.42), 0.04, 0.06)
            .into_iter()
            .map(|p| p - eye)
            .collect();
        for aspect in [0.6, 1.0, 16.0 / 9.0] {
            let ours = fit(&points, aspect, 0.1, 1.5);
            let engine = model::fit(&points, aspect, 0.1, 1.5);
            assert_eq!((ours.forward, ours.fovy), (engine.forward, engine.fovy));
            for &p in &points {
                assert_eq!(ndc(&ours, aspect, p), model::ndc(&engine, aspect, p));
            }
        }
    }
}
