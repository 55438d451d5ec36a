//! A body's rest-frame geometry and its Lorentz-contracted board-frame shape.

use glam::DVec3;

use super::Worldline;
use crate::spacetime::ProperVelocity;

/// Contracts a rest-frame offset `r` along the direction `n` of `u` by `1/γ`
/// (the paper's §3.2.2): `r⊥ + n (n·r) / γ`.
///
/// Split into parts across and along the motion, so that no `1 − 1/γ` is
/// formed: the width along the motion keeps full relative precision when
/// `n` is a coordinate axis, and an absolute error of a few ε|r| otherwise
/// (3e-18 m for a puck, whatever γ).
#[inline]
pub fn contract(r: DVec3, u: ProperVelocity) -> DVec3 {
    let speed = u.0.length();
    if speed == 0.0 {
        return r;
    }
    let n = u.0 / speed;
    let along = n.dot(r);
    (r - n * along) + n * (along / u.gamma())
}

/// Geometry of a body in its own rest frame: vertices relative to its
/// reference point (a puck's centre on the board plane), and triangles.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RestShape {
    /// Vertex offsets from the reference point, rest frame, m.
    pub vertices: Vec<DVec3>,
    /// Counter-clockwise triangles (outward normals), indices into `vertices`.
    pub triangles: Vec<[u32; 3]>,
}

impl RestShape {
    /// A closed cylinder standing on the board: axis z, bottom at z = 0,
    /// top at `height`, `segments` vertices around each rim (≥ 3); built
    /// with parry ([`super::mesh::puck`]).
    pub fn puck(radius: f64, height: f64, segments: u32) -> Self {
        super::mesh::puck(radius, height, segments)
    }

    /// Board-frame vertex positions at board time `t`, with the rest shape
    /// contracted along the body's velocity of that moment when `contracted`
    /// is set (bodies are rigid about their reference point, the paper's
    /// §3.3.1 convention, so the shape follows the velocity at once).
    pub fn board_vertices_at<'a>(
        &'a self,
        worldline: &Worldline,
        t: f64,
        contracted: bool,
    ) -> impl Iterator<Item = DVec3> + 'a {
        let state = worldline.state_at(t);
        let u = if contracted {
            state.u
        } else {
            ProperVelocity::ZERO
        };
        self.vertices
            .iter()
            .map(move |&r| state.position + contract(r, u))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::Event;

    #[test]
    fn contraction_is_one_over_gamma_along_motion_only() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.6, 0.8, 0.0) * 0.8).unwrap();
        let gamma = u.gamma();
        let n = u.0.normalize();
        let along = contract(n * 2.0, u);
        assert!((along.length() - 2.0 / gamma).abs() < 1e-15);
        let across = contract(DVec3::new(-0.8, 0.6, 0.0), u);
        assert!((across - DVec3::new(-0.8, 0.6, 0.0)).length() < 1e-15);
        assert_eq!(contract(DVec3::X, ProperVelocity::ZERO), DVec3::X);
    }

    #[test]
    fn contraction_at_gamma_1e8_keeps_the_tiny_width() {
        let u = ProperVelocity(DVec3::new(1e8, 0.0, 0.0));
        let r = contract(DVec3::new(0.03, 0.01, 0.0), u);
        assert!((r.x / 3e-10 - 1.0).abs() < 1e-12, "{}", r.x);
        assert_eq!(r.y, 0.01);
        // Off-axis: absolute error of a few ε |r|.
        let n = DVec3::new(0.6, 0.8, 0.0);
        let r = contract(n * 0.03, ProperVelocity(n * 1e8));
        assert!((r - n * 3e-10).length() < 4.0 * f64::EPSILON * 0.03);
    }

    #[test]
    fn puck_shape_at_a_time_is_an_ellipse_of_semi_axes_r_over_gamma_and_r() {
        let shape = RestShape::puck(0.5, 0.1, 64);
        let u = ProperVelocity::try_from_beta(DVec3::new(0.8, 0.0, 0.0)).unwrap();
        let w = Worldline::new(Event::new(0.0, DVec3::new(1.0, 1.0, 0.0)), u, 1.0);
        let at = w.position_at(1.0);
        for p in shape.board_vertices_at(&w, 1.0, true) {
            let d = p - at;
            // (x γ / R)² + (y / R)² = 1 on the rim; the axis points at 0.
            let e = (d.x * 1.0 / 0.6 / 0.5).powi(2) + (d.y / 0.5).powi(2);
            assert!(e < 1.0 + 1e-12, "{e}");
        }
        let max_x = shape
            .board_vertices_at(&w, 1.0, false)
            .map(|p| p.x - at.x)
            .fold(0.0, f64::max);
        assert!((max_x - 0.5).abs() < 1e-15);
    }
}
