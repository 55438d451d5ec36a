//! The one camera model: a pinhole at the eye, looking along a direction
//! (observer's frame) with a vertical field of view; and the framing that
//! turns and widens it to show a set of apparent points (the table) in a
//! viewport, as the window, `render`, Python and the CAVE all use it.
//!
//! The eye itself is the observer (light delay and aberration depend on
//! where it is), so framing never moves it: it turns the camera and widens
//! or narrows its field of view. Points are given relative to the eye in the
//! observer's frame (as a view's apparent positions are), so a moving eye's
//! aberration is framed too.

use glam::{DVec2, DVec3};

/// A pinhole camera at the eye.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Viewing direction (observer's frame, axes parallel to the board's).
    pub forward: DVec3,
    /// Vertical field of view, radians.
    pub fovy: f64,
}

impl Camera {
    /// Looking along `forward` with a 60° vertical field of view.
    #[must_use]
    pub fn looking(forward: DVec3) -> Self {
        Self {
            forward,
            fovy: std::f64::consts::FRAC_PI_3,
        }
    }
}

/// Margin a fitted framing leaves on each side, as a fraction of the
/// half-size.
pub const FIT_MARGIN: f64 = 0.08;

/// How a view's camera is aimed each frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Framing {
    /// Along a fixed direction (observer's frame), field of view `fovy`
    /// narrowed by `zoom`.
    Look {
        /// Viewing direction.
        forward: DVec3,
        /// Vertical field of view before zoom, radians.
        fovy: f64,
        /// Zoom (> 1 narrows).
        zoom: f64,
    },
    /// Turned and widened to show the whole table (as seen) in a viewport
    /// of `aspect` = width / height with [`FIT_MARGIN`], then zoomed; with
    /// `follow`, turned to keep that puck's apparent centre in the middle.
    Fit {
        /// Viewport width / height.
        aspect: f64,
        /// Zoom (> 1 narrows).
        zoom: f64,
        /// Puck index to keep in the middle.
        follow: Option<usize>,
    },
}

/// The viewport aspect (width / height) a framing assumes until told the
/// real one: 16:9.
pub const DEFAULT_ASPECT: f64 = 16.0 / 9.0;

impl Default for Framing {
    fn default() -> Self {
        Self::Fit {
            aspect: DEFAULT_ASPECT,
            zoom: 1.0,
            follow: None,
        }
    }
}

/// The narrowest and widest vertical fields of view a framing may use,
/// radians.
pub const FOV_RANGE: (f64, f64) = (0.02, 2.8);

/// The up vector for `forward`: +z, or +y looking straight up or down.
fn up_for(forward: DVec3) -> DVec3 {
    if forward.cross(DVec3::Z).length() < 1e-6 {
        DVec3::Y
    } else {
        DVec3::Z
    }
}

/// The camera's right and up axes for `forward` (unit), as the renderer's
/// view matrix builds them.
#[must_use]
pub fn basis(forward: DVec3) -> (DVec3, DVec3) {
    let right = forward.cross(up_for(forward)).normalize();
    let up = right.cross(forward);
    (right, up)
}

/// The camera looking at `points` (relative to the eye) from the eye, so
/// that they fill a viewport of `aspect` = width / height with `margin`
/// (a fraction of the half-size, e.g. 0.08) left on each side, then zoomed
/// by `zoom` (> 1 narrows the view about its centre). Points behind the eye
/// are ignored; with none in front, looks at their mean direction with
/// a 60° field.
#[must_use]
pub fn fit(points: &[DVec3], aspect: f64, margin: f64, zoom: f64) -> Camera {
    let aspect = if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    };
    let zoom = if zoom.is_finite() && zoom > 0.0 {
        zoom
    } else {
        1.0
    };
    let ahead: Vec<DVec3> = points
        .iter()
        .filter(|p| p.length() > 1e-9)
        .map(|p| p.normalize())
        .collect();
    // Start from the mean direction to the points, which sees all of them
    // whenever they span less than a half space.
    let mut forward = ahead.iter().sum::<DVec3>().normalize_or(DVec3::Y);
    // The points' extents in the image plane of `f` (x0, x1, y0, y1), or
    // `None` if one is not in front of it.
    let extents = |f: DVec3| {
        let (right, up) = basis(f);
        let (mut e, mut ok) = ([f64::MAX, f64::MIN, f64::MAX, f64::MIN], true);
        for p in &ahead {
            let z = p.dot(f);
            if z <= 1e-3 {
                ok = false;
                break;
            }
            let (x, y) = (p.dot(right) / z, p.dot(up) / z);
            e = [e[0].min(x), e[1].max(x), e[2].min(y), e[3].max(y)];
        }
        (ok && !ahead.is_empty()).then_some(e)
    };
    let Some(mut e) = extents(forward) else {
        return Camera {
            forward,
            fovy: std::f64::consts::FRAC_PI_3,
        };
    };
    // Re-aim, damped, at the middle of the extents until centred; a step
    // that would put a point behind the camera is not taken.
    for _ in 0..40 {
        let (right, up) = basis(forward);
        let (mx, my) = ((e[0] + e[1]) / 2.0, (e[2] + e[3]) / 2.0);
        if mx.abs() < 1e-7 && my.abs() < 1e-7 {
            break;
        }
        let next = (forward + (right * mx + up * my) * 0.7).normalize();
        match extents(next) {
            Some(n) => {
                forward = next;
                e = n;
            }
            None => break,
        }
    }
    let half_x = e[0].abs().max(e[1].abs());
    let half_y = e[2].abs().max(e[3].abs());
    let tan_half = half_y.max(half_x / aspect) * (1.0 + margin);
    let fovy = 2.0 * (tan_half / zoom).atan();
    Camera {
        forward,
        fovy: fovy.clamp(FOV_RANGE.0, FOV_RANGE.1),
    }
}

/// A camera with field of view `fovy` narrowed by `zoom` (> 1 zooms in),
/// within [`FOV_RANGE`].
#[must_use]
pub fn zoomed(forward: DVec3, fovy: f64, zoom: f64) -> Camera {
    let zoom = if zoom.is_finite() && zoom > 0.0 {
        zoom
    } else {
        1.0
    };
    Camera {
        forward,
        fovy: (2.0 * ((fovy / 2.0).tan() / zoom).atan()).clamp(FOV_RANGE.0, FOV_RANGE.1),
    }
}

/// Where a point relative to the eye lands in a viewport of `aspect`, in
/// normalised device coordinates (x right, y up, both in [−1, 1] when
/// visible); `None` behind the eye.
#[must_use]
pub fn ndc(camera: &Camera, aspect: f64, p: DVec3) -> Option<(f64, f64)> {
    let f = camera.forward.normalize_or(DVec3::Y);
    let (right, up) = basis(f);
    let z = p.dot(f);
    if z <= 0.0 {
        return None;
    }
    let t = (camera.fovy / 2.0).tan();
    Some((p.dot(right) / z / (t * aspect), p.dot(up) / z / t))
}

/// The corners of the table's playing area and of its cushions' outer top
/// edge (board frame, m): what a framing must show.
#[must_use]
pub fn table_corners(size: DVec2, cushion_height: f64, cushion_width: f64) -> Vec<DVec3> {
    let mut v = Vec::with_capacity(8);
    for (lo, hi, z) in [
        (DVec2::ZERO, size, 0.0),
        (
            DVec2::splat(-cushion_width),
            size + DVec2::splat(cushion_width),
            cushion_height,
        ),
    ] {
        for (x, y) in [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)] {
            v.push(DVec3::new(x, y, z));
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fitted_table_fills_the_viewport_with_its_margin() {
        let eye = DVec3::new(1.42, -0.9, 0.9);
        let points: Vec<DVec3> = table_corners(DVec2::new(2.84, 1.42), 0.04, 0.06)
            .into_iter()
            .map(|p| p - eye)
            .collect();
        for aspect in [0.6, 0.85, 1.0, 16.0 / 9.0, 3.0] {
            let cam = fit(&points, aspect, 0.1, 1.0);
            let (mut ax, mut ay) = (0.0f64, 0.0f64);
            for &p in &points {
                let (x, y) = ndc(&cam, aspect, p).unwrap();
                assert!(x.abs() <= 1.0 / 1.1 + 1e-9 && y.abs() <= 1.0 / 1.1 + 1e-9);
                ax = ax.max(x.abs());
                ay = ay.max(y.abs());
            }
            // Tight on one axis.
            assert!((ax.max(ay) - 1.0 / 1.1).abs() < 1e-3, "{aspect}: {ax} {ay}");
            // Zooming in by 2 halves the extent.
            let z = fit(&points, aspect, 0.1, 2.0);
            let (x, _) = ndc(&z, aspect, points[1]).unwrap();
            let (x1, _) = ndc(&cam, aspect, points[1]).unwrap();
            assert!((x - 2.0 * x1).abs() < 1e-3);
        }
    }

    #[test]
    fn from_low_beside_a_corner_every_corner_is_in_view() {
        // The simultaneity scene's off-centre eye, low by the near corner.
        let eye = DVec3::new(0.4, -0.8, 0.5);
        let points: Vec<DVec3> = table_corners(DVec2::new(2.84, 1.42), 0.04, 0.06)
            .into_iter()
            .map(|p| p - eye)
            .collect();
        for aspect in [0.8, 1.6] {
            let cam = fit(&points, aspect, 0.08, 1.0);
            let mut widest = 0.0f64;
            for &p in &points {
                let (x, y) = ndc(&cam, aspect, p).unwrap();
                assert!(x.abs() <= 1.0 / 1.08 + 1e-9 && y.abs() <= 1.0 / 1.08 + 1e-9);
                widest = widest.max(x.abs()).max(y.abs());
            }
            assert!(widest > 0.85, "{aspect}: {widest}");
        }
    }

    #[test]
    fn from_straight_above_the_board_fits_too() {
        let eye = DVec3::new(1.42, 0.71, 3.0);
        let points: Vec<DVec3> = table_corners(DVec2::new(2.84, 1.42), 0.04, 0.06)
            .into_iter()
            .map(|p| p - eye)
            .collect();
        let cam = fit(&points, 1.5, 0.05, 1.0);
        assert!(cam.forward.z < -0.999);
        for &p in &points {
            let (x, y) = ndc(&cam, 1.5, p).unwrap();
            assert!(x.abs() <= 1.0 && y.abs() <= 1.0);
        }
    }
}
