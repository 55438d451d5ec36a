//! Relativity of simultaneity: which board events a moving body's frame
//! calls simultaneous with a given event.
//!
//! In the rest frame of a body with proper velocity `u` (board frame), the
//! events simultaneous with `through` form the hyperplane
//! `t = t₀ + v·(x − x₀) / c²` of board spacetime, with `v = c u / γ`: along
//! the body's motion, events further ahead are simultaneous with *later*
//! board times (the plane tilts up along `v`). On a
//! space-time diagram (one board axis across, board time up) its trace is the
//! line of slope `v_axis / c²` (s per m), the body's "now".

use glam::DVec3;

use super::{Event, ProperVelocity};

/// The board time of the event at board position `at` that the rest frame
/// of a body moving with proper velocity `u` calls simultaneous with event
/// `through`: `t₀ + (u/γ)·(at − x₀) / c` (s). `c` in m/s, positions in m.
/// For `u = 0` it is `through.t` (the board frame's own simultaneity).
#[must_use]
pub fn simultaneous_board_time(through: Event, u: ProperVelocity, c: f64, at: DVec3) -> f64 {
    through.t + u.0.dot(at - through.position) / (u.gamma() * c)
}

/// The slope `dt/dr` (s/m) of that hyperplane in board coordinates: `v / c²`.
#[must_use]
pub fn simultaneity_slope(u: ProperVelocity, c: f64) -> DVec3 {
    u.0 / (u.gamma() * c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::Boost;

    /// Every event the function calls simultaneous has the same time as
    /// `through` once boosted into the body's rest frame (the Lorentz boost
    /// in light-cone coordinates, independent code), at speeds up to γ = 10⁶.
    #[test]
    fn simultaneous_events_share_the_rest_frame_time() {
        let c = 1.42;
        let through = Event::new(2.5, DVec3::new(1.0, 0.7, 0.0));
        for u in [
            DVec3::ZERO,
            DVec3::new(0.75, 0.0, 0.0),
            DVec3::new(-3.0, 4.0, 0.0),
            DVec3::new(1e3, 2e2, 0.0),
            DVec3::new(0.0, -1e6, 0.0),
        ] {
            let u = ProperVelocity(u);
            let boost = Boost::into_frame(u);
            let t0 = boost.apply(through.separation_to(through, c)).ct;
            for at in [
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(2.84, 1.42, 0.0),
                DVec3::new(-5.0, 3.0, 0.0),
            ] {
                let t = simultaneous_board_time(through, u, c, at);
                let other = Event::new(t, at);
                let sep = boost.apply(through.separation_to(other, c));
                // The boost multiplies the separation (metres) by up to 2γ.
                let scale = u.gamma() * (at - through.position).length().max(1.0);
                assert!(
                    (sep.ct - t0).abs() <= 1e-14 * scale,
                    "u {:?} at {at}: rest-frame c·Δt' = {}",
                    u.0,
                    sep.ct
                );
            }
        }
    }

    #[test]
    fn slope_is_v_over_c_squared() {
        // β = 0.6 along x: v = 0.6 c, slope 0.6 / c.
        let u = ProperVelocity::try_from_beta(DVec3::new(0.6, 0.0, 0.0)).unwrap();
        let s = simultaneity_slope(u, 2.0);
        assert!((s.x - 0.3).abs() < 1e-15 && s.y == 0.0, "{s}");
    }
}
