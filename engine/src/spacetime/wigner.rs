//! Thomas–Wigner rotation: two boosts in different directions compose to a
//! boost *and a rotation*.
//!
//! A body at proper velocity `u₁` (board frame) whose velocity changes with
//! no torque (every contact on this table) takes as its new rest frame the
//! old one boosted, *in the old rest frame*, to the new velocity. Written
//! with pure boosts `B(u)` from the board,
//!
//! ```text
//! B(u₁) · B(u′) = B(u₂) · R(ε)
//! ```
//!
//! where `u′` is the new velocity seen from the old rest frame (axes of the
//! pure boost `B(u₁)`), `u₂` the new board velocity, and `R(ε)` a rotation
//! by the Wigner angle `ε` about the axis `−(u₁ × u′)` (opposite to the
//! sense in which the velocity turned). With `γ = √(1 + u²)`,
//!
//! ```text
//! tan(|ε|/2) = |u₁ × u′| / ((γ₁ + 1)(γ′ + 1) + u₁·u′)
//! ```
//!
//! the half-angle form of the textbook result (e.g. Wikipedia, "Wigner
//! rotation": `tan(ε/2) = sin θ / (k + cos θ)`, `k² = (γ₁+1)(γ′+1) /
//! ((γ₁−1)(γ′−1))`, multiplied through by `|u₁||u′|` using
//! `γ − 1 = u²/(γ + 1)`). Every term is a product or a sum of terms that
//! cannot cancel (the denominator exceeds `(γ₁+1)(γ′+1) − |u₁||u′| > 0`), so
//! the angle keeps its digits at any γ. Limits (tested): |ε| ≈ u₁u′ sin θ / 2
//! for slow bodies (Thomas precession's small-angle law), and |ε| → θ, the
//! angle between the two boosts, when both are ultra-relativistic.
//!
//! On the table (2+1 dimensions) every rotation is about the board normal
//! `+z` and angles add: a puck's orientation is the sum of the Wigner angles
//! of its velocity changes.

use glam::DVec3;

use crate::spacetime::{Boost, ProperVelocity};

/// The Wigner angle `ε` of `B(u₁)·B(u′) = B(u₂)·R(ε)`, radians,
/// counter-clockwise about `+z`: negative when `(u₁ × u′)·z > 0` (the rest
/// frame turns against the velocity; checked against the matrix product). `u₁`: the first
/// boost (board → old rest frame); `u′`: the second, measured in the old
/// rest frame's (pure-boost) axes. Both dimensionless proper velocities
/// `γβ`. Exact to a few ulps at any γ the engine holds.
#[must_use]
pub fn wigner_angle(u1: ProperVelocity, u_prime: ProperVelocity) -> f64 {
    let cross = u1.0.cross(u_prime.0);
    // In the board plane the rotation is about ±z; out of it, about the
    // cross product's axis (its length is the sine term either way).
    let sine = if cross.x == 0.0 && cross.y == 0.0 {
        cross.z
    } else {
        cross.length() * cross.z.signum()
    };
    let cosine = (u1.gamma() + 1.0) * (u_prime.gamma() + 1.0) + u1.0.dot(u_prime.0);
    -2.0 * sine.atan2(cosine)
}

/// The rest-frame rotation a torque-free velocity change from `from` to `to`
/// (both board-frame proper velocities) adds to a body's orientation,
/// radians counter-clockwise about `+z`: the Wigner angle of the board's
/// boost to `from` followed by the boost, in that rest frame, to `to`.
///
/// A change along the line of motion (or from or to rest) adds nothing.
#[must_use]
pub fn rotation_of_velocity_change(from: ProperVelocity, to: ProperVelocity) -> f64 {
    let in_old_rest_frame = Boost::into_frame(from).apply_velocity(to);
    wigner_angle(from, in_old_rest_frame)
}

/// A rest-frame direction (unit, in the board plane) rotated by `angle`
/// counter-clockwise about `+z`.
#[inline]
#[must_use]
pub fn rotate_about_normal(direction: DVec3, angle: f64) -> DVec3 {
    let (s, c) = angle.sin_cos();
    DVec3::new(
        c * direction.x - s * direction.y,
        s * direction.x + c * direction.y,
        direction.z,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DMat3, DVec3};

    /// The 2+1 Lorentz matrix (ct, x, y) of the pure boost taking rest-frame
    /// coordinates of a body at proper velocity `u` to board coordinates.
    fn boost_matrix(u: DVec3) -> DMat3 {
        let g = (1.0 + u.length_squared()).sqrt();
        let (ux, uy) = (u.x, u.y);
        let k = 1.0 / (g + 1.0);
        DMat3::from_cols(
            DVec3::new(g, ux, uy),
            DVec3::new(ux, 1.0 + k * ux * ux, k * ux * uy),
            DVec3::new(uy, k * ux * uy, 1.0 + k * uy * uy),
        )
    }

    /// The angle of the spatial rotation left in `B(u₂)⁻¹ · Λ` (a matrix
    /// reference, trustworthy at moderate γ).
    fn rotation_left(u1: DVec3, u_prime: DVec3) -> (DVec3, f64) {
        let lambda = boost_matrix(u1) * boost_matrix(u_prime);
        // The new board velocity is the image of the rest 4-velocity.
        let image = lambda * DVec3::X;
        let u2 = DVec3::new(image.y, image.z, 0.0);
        let r = boost_matrix(-u2) * lambda;
        (u2, r.y_axis.z.atan2(r.y_axis.y))
    }

    #[test]
    fn matches_the_matrix_composition_at_moderate_speeds() {
        let cases = [
            (DVec3::new(0.8, 0.0, 0.0), DVec3::new(0.0, 0.9, 0.0)),
            (DVec3::new(2.0, 1.0, 0.0), DVec3::new(-1.5, 3.0, 0.0)),
            (DVec3::new(0.1, -0.3, 0.0), DVec3::new(5.0, 0.2, 0.0)),
            (DVec3::new(-3.0, 0.5, 0.0), DVec3::new(0.0, -0.7, 0.0)),
        ];
        for (a, b) in cases {
            let (u2, reference) = rotation_left(a, b);
            let ours = wigner_angle(ProperVelocity(a), ProperVelocity(b));
            assert!(
                (ours - reference).abs() < 1e-12,
                "{a} {b}: {ours} vs {reference}"
            );
            let composed = crate::spacetime::compose(ProperVelocity(a), ProperVelocity(b));
            assert!((composed.0 - u2).length() < 1e-12 * u2.length().max(1.0));
        }
    }

    #[test]
    fn perpendicular_equal_boosts_closed_form() {
        // Two perpendicular boosts of equal proper speed u: the textbook
        // tan(ε/2) = sin θ/(k + cos θ) with θ = 90°, k = (γ+1)/(γ−1), i.e.
        // tan(ε/2) = (γ−1)/(γ+1) = u²/(γ+1)², checked from u = 10⁻³ to 10⁸.
        for u in [1e-3_f64, 0.5, 3.0, 1e3, 1e8] {
            let g = (1.0 + u * u).sqrt();
            let expected = -2.0 * (u * u).atan2((g + 1.0) * (g + 1.0));
            let got = wigner_angle(
                ProperVelocity(DVec3::new(u, 0.0, 0.0)),
                ProperVelocity(DVec3::new(0.0, u, 0.0)),
            );
            assert!((got - expected).abs() <= 1e-15 * expected.abs().max(1e-300) + 1e-300);
            // Ultra-relativistic: the rotation tends to the 90° between them.
            if u >= 1e8 {
                assert!((got + core::f64::consts::FRAC_PI_2).abs() < 1e-7);
            }
            // Classical limit: ε ≈ u²/2 (Thomas precession's small-angle law).
            if u <= 1e-3 {
                assert!((got / (-0.5 * u * u) - 1.0).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn collinear_changes_add_no_rotation() {
        let a = ProperVelocity(DVec3::new(3.0, 4.0, 0.0));
        let b = ProperVelocity(DVec3::new(-30.0, -40.0, 0.0));
        assert_eq!(rotation_of_velocity_change(a, b), 0.0);
        assert_eq!(
            rotation_of_velocity_change(ProperVelocity(DVec3::ZERO), a),
            0.0
        );
        assert_eq!(
            rotation_of_velocity_change(a, ProperVelocity(DVec3::ZERO)),
            0.0
        );
    }

    #[test]
    fn rotating_a_direction() {
        let d = rotate_about_normal(DVec3::X, core::f64::consts::FRAC_PI_2);
        assert!((d - DVec3::Y).length() < 1e-15);
    }
}
