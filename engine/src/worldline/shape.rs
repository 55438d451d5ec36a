//! A body's rest-frame geometry and the Lorentz contraction of one offset
//! (along a worldline, segment by segment: [`super::contraction`]).

use glam::DVec3;

use crate::spacetime::ProperVelocity;

/// Contracts a rest-frame offset `r` along the direction `n` of `u` by `1/γ`
/// (the paper's §3.2.2): `r⊥ + n (n·r) / γ`.
///
/// Split into parts across and along the motion, so that no `1 − 1/γ` is
/// formed: the width along the motion keeps full relative precision when
/// `n` is a coordinate axis, and an absolute error of a few ε|r| otherwise
/// (3e-18 m for a puck, whatever γ).
#[inline]
#[must_use]
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
    #[must_use]
    pub fn puck(radius: f64, height: f64, segments: u32) -> Self {
        super::mesh::puck(radius, height, segments)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
