//! Kooima's generalized perspective projection: a wall of the CAVE, the
//! off-axis frustum from an eye through its edges, and the two eyes of a
//! tracked head ("Generalized Perspective Projection", R. Kooima, 2008).

use glam::{DMat4, DQuat, DVec3, DVec4};
use thiserror::Error;

/// Default interocular distance (metres).
pub const DEFAULT_EYE_SEPARATION: f64 = 0.064;

/// Errors computing a projection.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ProjectionError {
    /// The eye is on or behind the wall plane (the wall faces away from it).
    #[error("eye is {distance:.4} m in front of the wall plane; it must be in front (> 0)")]
    EyeNotInFront {
        /// Signed distance from the wall plane along its normal.
        distance: f64,
    },
    /// `near` must be > 0 and `far` > `near`, both finite.
    #[error("invalid clip planes near = {near}, far = {far}")]
    ClipPlanes {
        /// Near distance.
        near: f64,
        /// Far distance.
        far: f64,
    },
    /// NaN/inf in the corners or the eye position.
    #[error("non-finite wall corner or eye position")]
    NonFinite,
    /// Wall corners are coincident or collinear.
    #[error("degenerate wall (zero width or height)")]
    DegenerateWall,
}

/// One projection surface, corners in tracker space.
#[derive(Debug, Clone, PartialEq)]
pub struct Wall {
    /// Unique name ("front", "floor", ...).
    pub name: String,
    /// Lower-left corner as seen from inside.
    pub lower_left: DVec3,
    /// Lower-right corner.
    pub lower_right: DVec3,
    /// Upper-left corner.
    pub upper_left: DVec3,
    /// Projector resolution `[width, height]`.
    pub pixels: [u32; 2],
}

impl Wall {
    /// The fourth corner.
    #[must_use]
    pub fn upper_right(&self) -> DVec3 {
        self.lower_right + (self.upper_left - self.lower_left)
    }
    /// Width in metres.
    #[must_use]
    pub fn width(&self) -> f64 {
        (self.lower_right - self.lower_left).length()
    }
    /// Height in metres.
    #[must_use]
    pub fn height(&self) -> f64 {
        (self.upper_left - self.lower_left).length()
    }
    /// Unit vector along the lower edge (screen +x).
    #[must_use]
    pub fn right(&self) -> DVec3 {
        (self.lower_right - self.lower_left).normalize_or_zero()
    }
    /// Unit vector along the left edge (screen +y).
    #[must_use]
    pub fn up(&self) -> DVec3 {
        (self.upper_left - self.lower_left).normalize_or_zero()
    }
    /// Unit normal pointing towards the viewer (`right × up`).
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.right().cross(self.up()).normalize_or_zero()
    }
    /// Projector aspect ratio (width / height in pixels).
    #[must_use]
    pub fn pixel_aspect(&self) -> f64 {
        f64::from(self.pixels[0]) / f64::from(self.pixels[1].max(1))
    }
    /// Off-axis projection for an eye at `eye` (tracker space).
    pub fn projection(
        &self,
        eye: DVec3,
        near: f64,
        far: f64,
    ) -> Result<WallProjection, ProjectionError> {
        off_axis_projection(
            self.lower_left,
            self.lower_right,
            self.upper_left,
            eye,
            near,
            far,
        )
    }
}

/// Extents of an off-axis frustum on the near plane (view space).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frustum {
    /// Left extent (x at the near plane).
    pub left: f64,
    /// Right extent.
    pub right: f64,
    /// Bottom extent (y at the near plane).
    pub bottom: f64,
    /// Top extent.
    pub top: f64,
    /// Near distance (> 0).
    pub near: f64,
    /// Far distance (> near).
    pub far: f64,
}

impl Frustum {
    /// Right-handed perspective matrix with wgpu's [0, 1] depth range (the
    /// same convention as glam's `perspective_rh` / `directx::frustum`):
    /// view space looks down -z, near maps to depth 0, far to 1.
    #[must_use]
    pub fn matrix(&self) -> DMat4 {
        let Frustum {
            left: l,
            right: r,
            bottom: b,
            top: t,
            near: n,
            far: f,
        } = *self;
        DMat4::from_cols(
            DVec4::new(2.0 * n / (r - l), 0.0, 0.0, 0.0),
            DVec4::new(0.0, 2.0 * n / (t - b), 0.0, 0.0),
            DVec4::new((r + l) / (r - l), (t + b) / (t - b), f / (n - f), -1.0),
            DVec4::new(0.0, 0.0, n * f / (n - f), 0.0),
        )
    }
}

/// Result of [`off_axis_projection`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallProjection {
    /// Frustum extents.
    pub frustum: Frustum,
    /// World (tracker) → view: rotates the wall's basis onto the axes and
    /// moves the eye to the origin.
    pub view: DMat4,
    /// Off-axis perspective (`frustum.matrix()`).
    pub projection: DMat4,
    /// `projection * view`.
    pub view_projection: DMat4,
    /// Perpendicular distance from the eye to the wall plane.
    pub eye_distance: f64,
}

/// Kooima's generalized perspective projection.
///
/// `pa`, `pb`, `pc`: the wall's lower-left, lower-right and upper-left
/// corners; `pe`: the eye; all in one right-handed frame. Returns a frustum
/// whose side planes pass through the wall edges, so the wall corners land
/// exactly on NDC (±1, ±1) for every eye position in front of the wall.
pub fn off_axis_projection(
    pa: DVec3,
    pb: DVec3,
    pc: DVec3,
    pe: DVec3,
    near: f64,
    far: f64,
) -> Result<WallProjection, ProjectionError> {
    if !(pa.is_finite() && pb.is_finite() && pc.is_finite() && pe.is_finite()) {
        return Err(ProjectionError::NonFinite);
    }
    if !(near.is_finite() && far.is_finite() && near > 0.0 && far > near) {
        return Err(ProjectionError::ClipPlanes { near, far });
    }
    // Screen basis: right, up, normal (towards the viewer).
    let vr = (pb - pa).normalize_or_zero();
    let vu = (pc - pa).normalize_or_zero();
    let vn = vr.cross(vu).normalize_or_zero();
    if vr == DVec3::ZERO || vu == DVec3::ZERO || vn == DVec3::ZERO {
        return Err(ProjectionError::DegenerateWall);
    }
    // Corners relative to the eye.
    let va = pa - pe;
    let vb = pb - pe;
    let vc = pc - pe;
    let d = -va.dot(vn);
    if d.is_nan() || d <= 1e-9 {
        return Err(ProjectionError::EyeNotInFront { distance: d });
    }
    let k = near / d;
    let frustum = Frustum {
        left: vr.dot(va) * k,
        right: vr.dot(vb) * k,
        bottom: vu.dot(va) * k,
        top: vu.dot(vc) * k,
        near,
        far,
    };
    // Rows of the rotation are the screen basis: M^T in Kooima's notation.
    let rot = DMat4::from_cols(
        DVec4::new(vr.x, vu.x, vn.x, 0.0),
        DVec4::new(vr.y, vu.y, vn.y, 0.0),
        DVec4::new(vr.z, vu.z, vn.z, 0.0),
        DVec4::W,
    );
    let view = rot * DMat4::from_translation(-pe);
    let projection = frustum.matrix();
    Ok(WallProjection {
        frustum,
        view,
        projection,
        view_projection: projection * view,
        eye_distance: d,
    })
}

/// Left and right eye positions for a head pose: the eyes sit at
/// `∓ separation / 2` along the head's local +x axis (the interocular axis).
/// A non-finite or negative separation is treated as 0 (mono).
#[must_use]
pub fn stereo_eyes(
    head_position: DVec3,
    head_orientation: DQuat,
    separation: f64,
) -> (DVec3, DVec3) {
    let sep = if separation.is_finite() && separation > 0.0 {
        separation
    } else {
        0.0
    };
    let q = head_orientation.normalize();
    let q = if q.is_finite() { q } else { DQuat::IDENTITY };
    let half = q * DVec3::new(0.5 * sep, 0.0, 0.0);
    (head_position - half, head_position + half)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cave::CaveConfig;

    const EXAMPLE: &str = include_str!("../../../assets/cave.toml");

    fn example() -> CaveConfig {
        CaveConfig::from_toml_str(EXAMPLE).expect("example config parses")
    }

    fn assert_mat_close(a: DMat4, b: DMat4, tol: f64) {
        let (a, b) = (a.to_cols_array(), b.to_cols_array());
        for i in 0..16 {
            assert!(
                (a[i] - b[i]).abs() < tol,
                "element {i}: {} vs {}\n{a:?}\n{b:?}",
                a[i],
                b[i]
            );
        }
    }

    #[test]
    fn centred_eye_gives_glam_perspective() {
        let c = example();
        let w = c.wall("front").expect("front");
        let eye = DVec3::new(0.0, 1.25, 0.0);
        let (near, far) = (0.05, 100.0);
        let p = w.projection(eye, near, far).expect("projection");
        let f = p.frustum;
        assert!((f.left + f.right).abs() < 1e-12 && (f.bottom + f.top).abs() < 1e-12);
        assert!((p.eye_distance - 1.5).abs() < 1e-12);
        let fov_y = 2.0 * (1.25f64 / 1.5).atan();
        let aspect = 3.0 / 2.5;
        #[allow(deprecated)]
        let expected = DMat4::perspective_rh(fov_y, aspect, near, far)
            * DMat4::look_at_rh(eye, eye - w.normal(), w.up());
        assert_mat_close(p.view_projection, expected, 1e-9);
        // The non-deprecated glam camera API agrees too.
        let expected2 = glam::dcamera::rh::proj::directx::perspective(fov_y, aspect, near, far)
            * glam::dcamera::rh::view::look_at_mat4(eye, eye - w.normal(), w.up());
        assert_mat_close(p.view_projection, expected2, 1e-9);
    }

    #[test]
    fn frustum_matrix_matches_glam() {
        let f = Frustum {
            left: -0.3,
            right: 0.1,
            bottom: -0.05,
            top: 0.2,
            near: 0.1,
            far: 50.0,
        };
        let g = glam::dcamera::rh::proj::directx::frustum(-0.3, 0.1, -0.05, 0.2, 0.1, 50.0);
        assert_mat_close(f.matrix(), g, 1e-12);
    }

    #[test]
    fn sideways_eye_makes_frustum_asymmetric() {
        let c = example();
        let w = c.wall("front").expect("front");
        let right = w
            .projection(DVec3::new(0.5, 1.25, 0.0), 0.1, 10.0)
            .expect("p");
        let f = right.frustum;
        // Eye moved right: more of the wall is to its left.
        assert!(f.left + f.right < -1e-6, "{f:?}");
        assert!((f.left - (-2.0 * 0.1 / 1.5)).abs() < 1e-12);
        assert!((f.right - (1.0 * 0.1 / 1.5)).abs() < 1e-12);
        let up = w
            .projection(DVec3::new(0.0, 2.0, 0.0), 0.1, 10.0)
            .expect("p");
        assert!(up.frustum.bottom + up.frustum.top < -1e-6);
    }

    fn ndc(m: DMat4, p: DVec3) -> DVec3 {
        m.project_point3(p)
    }

    #[test]
    fn wall_points_map_to_fixed_ndc_for_any_eye() {
        let c = example();
        let mut rng = crate::motion::Prng::new(99);
        for w in &c.walls {
            let pr = w.lower_right - w.lower_left;
            let pu = w.upper_left - w.lower_left;
            for _ in 0..50 {
                // Random eye inside the CAVE.
                let eye = DVec3::new(
                    -1.4 + 2.8 * rng.next_f64(),
                    0.1 + 2.3 * rng.next_f64(),
                    -1.4 + 2.8 * rng.next_f64(),
                );
                let m = w
                    .projection(eye, 0.01, 100.0)
                    .expect("eye inside")
                    .view_projection;
                let corners = [
                    (w.lower_left, -1.0, -1.0),
                    (w.lower_right, 1.0, -1.0),
                    (w.upper_left, -1.0, 1.0),
                    (w.upper_right(), 1.0, 1.0),
                ];
                for (p, x, y) in corners {
                    let n = ndc(m, p);
                    assert!(
                        (n.x - x).abs() < 1e-9 && (n.y - y).abs() < 1e-9,
                        "{} {n:?}",
                        w.name
                    );
                    assert!(n.z > 0.0 && n.z < 1.0);
                }
                // An interior wall point maps to its own (u, v) in NDC.
                let (u, v) = (rng.next_f64(), rng.next_f64());
                let n = ndc(m, w.lower_left + u * pr + v * pu);
                assert!((n.x - (2.0 * u - 1.0)).abs() < 1e-9);
                assert!((n.y - (2.0 * v - 1.0)).abs() < 1e-9);
            }
        }
    }

    #[test]
    fn off_wall_points_move_with_the_eye() {
        // The converse: a point not on the wall plane projects differently for
        // different eyes, and different wall points never share NDC.
        let c = example();
        let w = c.wall("front").expect("front");
        let a = w
            .projection(DVec3::new(-0.5, 1.2, 0.0), 0.1, 10.0)
            .expect("a");
        let b = w
            .projection(DVec3::new(0.7, 1.6, 0.5), 0.1, 10.0)
            .expect("b");
        let floating = DVec3::new(0.2, 1.0, -1.0);
        let (na, nb) = (
            ndc(a.view_projection, floating),
            ndc(b.view_projection, floating),
        );
        assert!((na.truncate() - nb.truncate()).length() > 1e-3);
        let p1 = ndc(a.view_projection, DVec3::new(0.0, 1.0, -1.5));
        let p2 = ndc(a.view_projection, DVec3::new(0.1, 1.0, -1.5));
        assert!((p1.x - p2.x).abs() > 1e-3);
    }

    #[test]
    fn near_and_far_map_to_zero_and_one() {
        let c = example();
        let w = c.wall("front").expect("front");
        let eye = DVec3::new(0.3, 1.5, 0.2);
        let p = w.projection(eye, 0.1, 20.0).expect("p");
        // Points straight ahead along -normal at near and far distance.
        let n = ndc(p.view_projection, eye - w.normal() * 0.1);
        let f = ndc(p.view_projection, eye - w.normal() * 20.0);
        assert!(n.z.abs() < 1e-12 && (f.z - 1.0).abs() < 1e-12);
    }

    #[test]
    fn projection_errors() {
        let c = example();
        let w = c.wall("front").expect("front");
        let behind = DVec3::new(0.0, 1.0, -2.0);
        assert!(matches!(
            w.projection(behind, 0.1, 10.0),
            Err(ProjectionError::EyeNotInFront { .. })
        ));
        let eye = DVec3::new(0.0, 1.0, 0.0);
        assert!(matches!(
            w.projection(eye, 0.0, 10.0),
            Err(ProjectionError::ClipPlanes { .. })
        ));
        assert!(matches!(
            w.projection(eye, 1.0, 0.5),
            Err(ProjectionError::ClipPlanes { .. })
        ));
        assert!(matches!(
            w.projection(DVec3::NAN, 0.1, 1.0),
            Err(ProjectionError::NonFinite)
        ));
        assert!(matches!(
            off_axis_projection(DVec3::ZERO, DVec3::ZERO, DVec3::Y, DVec3::Z, 0.1, 1.0),
            Err(ProjectionError::DegenerateWall)
        ));
    }

    #[test]
    fn stereo_eyes_follow_head_axis() {
        let p = DVec3::new(0.0, 1.7, 0.0);
        let (l, r) = stereo_eyes(p, DQuat::IDENTITY, 0.064);
        assert!((l - DVec3::new(-0.032, 1.7, 0.0)).length() < 1e-12);
        assert!((r - DVec3::new(0.032, 1.7, 0.0)).length() < 1e-12);
        // Head turned 90° left (about +y): its +x now points along -z.
        let q = DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2);
        let (l, r) = stereo_eyes(p, q, 0.064);
        assert!((r - (p + DVec3::new(0.0, 0.0, -0.032))).length() < 1e-12);
        assert!((l - (p + DVec3::new(0.0, 0.0, 0.032))).length() < 1e-12);
        // Non-unit orientation is normalised; bad separation means mono.
        let (l, r) = stereo_eyes(p, DQuat::IDENTITY * 2.0, f64::NAN);
        assert_eq!((l, r), (p, p));
        let c = example();
        let (l, r) = c.eyes(p, DQuat::IDENTITY);
        assert!(((r - l).length() - 0.064).abs() < 1e-12);
    }
}
