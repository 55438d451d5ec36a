//! Cheap lower bounds on when two pucks can next touch (they prune the
//! exact pair solves), and the window in which their centres stay within
//! reach: pure functions of two segments' motion, in board time (s).

use glam::{DVec2, DVec3};

use crate::worldline::Segment;

/// The later root `τ` of `vv τ² + 2 p τ + q = 0` (`vv > 0`), in a form
/// without cancellation: `−q / (p + √(p² − vv q))` for `p ≥ 0`, `(√(p² −
/// vv q) − p) / vv` otherwise; `None` when there is no real root. For
/// `|d + v τ|² = r²` it is when a point `d` (m) moving at `v` (m/s) leaves
/// the disc of radius `r` about the origin, with `p = d·v`, `q = |d|² −
/// r²`, `vv = |v|²`. Accurate to a few ulps whatever the signs (the
/// textbook `(−p + √…)/vv` loses every digit for `p ≫ 0`).
#[inline]
#[must_use]
pub fn later_root(p: f64, q: f64, vv: f64) -> Option<f64> {
    let disc = p * p - vv * q;
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    Some(if p >= 0.0 {
        -q / (p + root)
    } else {
        (root - p) / vv
    })
}

/// How long after now (s) two centres `d0` apart (m, b − a) moving apart
/// at `v` (m/s, b − a) stay within `reach` (m) of each other: the later root
/// of `|d0 + v τ|² = reach²` ([`later_root`]), if it is positive; `None` if
/// they never are within reach from now on (or do not move relative to
/// each other).
#[must_use]
pub fn leaves_reach(d0: DVec3, v: DVec3, reach: f64) -> Option<f64> {
    let vv = v.length_squared();
    if vv == 0.0 {
        return None;
    }
    let (p, q) = (d0.dot(v), d0.length_squared() - reach * reach);
    later_root(p, q, vv).filter(|&leave| leave > 0.0)
}

/// A lower bound on the board time at which pucks on segments `sa` and
/// `sb` (rest radii `ra`, `rb`, m) can touch from `now` on, when either is
/// braking (for two uniform segments [`disc_touch`] is sharper); `None`
/// when they never can. Each centre moves on a straight line, never faster
/// than at `now` (braking only slows it: `|x(t) − x(now)| ≤ |v(now)| (t −
/// now)`), and a braking one no farther than to where it stops. Every
/// Lorentz-contracted (or Born-rigid) body lies inside its rest disc, so
/// the pucks touch only once the two displacements together have closed
/// the gap between the rest discs, `|Δx(now)| − ra − rb`. The gap is
/// shrunk by 1e-9 relative so rounding never makes the bound late.
#[must_use]
pub fn braking_touch(sa: &Segment, ra: f64, sb: &Segment, rb: f64, now: f64) -> Option<f64> {
    let motion = |s: &Segment| {
        let x = s.position_at(now).truncate();
        let speed = s.velocity_at(now).truncate().length();
        let left = s.stop_time().map_or(f64::INFINITY, |stop| {
            (s.position_at(stop.max(now)).truncate() - x).length()
        });
        (x, speed, if s.is_rest() { 0.0 } else { left })
    };
    let (xa, va, la) = motion(sa);
    let (xb, vb, lb) = motion(sb);
    let gap = ((xb - xa).length() - (ra + rb)) * (1.0 - 1e-9) - 1e-12;
    if gap <= 0.0 {
        return Some(now);
    }
    if la + lb < gap {
        return None; // they stop apart
    }
    let closing = va + vb;
    (closing > 0.0).then(|| now + gap / closing)
}

/// A lower bound on when two pucks, moving uniformly as `a` and `b` say,
/// can next have a contact event or a velocity change of it, from board
/// time `now`: the board time at which their rest discs
/// first touch (`now` if they overlap), or `None` if they never do (they
/// miss or recede). Classical and cheap: a quadratic on the board.
///
/// Why it bounds: a contracted puck lies inside its rest disc, so the board
/// shapes cannot meet before the rest discs do; and at the earlier of the
/// two kicks of a pair-frame contact the board distance of the centres is
/// at most `R_a + R_b`. (In the pair frame let the kicks `K_a`, `K_b` be
/// `Δx′` apart, `p = Δx′·n` along the approach; the contact of the similar
/// ellipses gives `|Δx′|² = S² − u′²p²`. The event on the later puck's
/// worldline a proper time `λ` earlier, on the board slice of the first
/// kick, is then at interval `S² − (u′p − λ)² ≤ S²` from it, and board
/// simultaneous events' interval is their board distance squared.) The
/// reach is grown by 1e-9 so rounding never makes the bound late.
///
/// Each puck is given by its centre at `now` (m, board frame), its board
/// velocity (m/s) and its rest radius (m); the scanning puck's side is
/// worked out once for all its partners. The result is the same to
/// the bit with `a` and `b` exchanged (negating both `d` and `v` is exact),
/// so it does not depend on which of the pair is scanning.
#[inline]
#[must_use]
pub fn disc_touch(
    a_now: DVec2,
    a_v: DVec2,
    a_radius: f64,
    b_now: DVec2,
    b_v: DVec2,
    b_radius: f64,
    now: f64,
) -> Option<f64> {
    let d = b_now - a_now;
    let reach = (a_radius + b_radius) * (1.0 + 1e-9);
    let q = d.length_squared() - reach * reach;
    if q <= 0.0 {
        return Some(now);
    }
    let v = b_v - a_v;
    let p = d.dot(v);
    if p >= 0.0 {
        return None; // receding or parallel
    }
    let vv = v.length_squared();
    let disc = p * p - vv * q;
    if disc < 0.0 {
        return None; // they pass wide
    }
    // The earlier root of |d + v τ|² = reach², without cancellation.
    Some(now + q / (disc.sqrt() - p))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn later_root_solves_the_quadratic_in_both_branches() {
        // (τ − 2)(τ + 3) = τ² + τ − 6: vv = 1, p = 1/2, q = −6 → τ = 2.
        assert_eq!(later_root(0.5, -6.0, 1.0), Some(2.0));
        // (τ − 3)(τ + 2) = τ² − τ − 6: p = −1/2 → τ = 3.
        assert_eq!(later_root(-0.5, -6.0, 1.0), Some(3.0));
        // No real root: a point that passes wide of the disc.
        assert_eq!(later_root(-1.0, 2.0, 1.0), None);
    }

    #[test]
    fn later_root_keeps_its_digits_where_the_textbook_form_loses_them() {
        // A point leaving a disc fast (p² ≫ vv |q|): the root, from 50-digit
        // arithmetic (mpmath), is 9.99999995000000049999999375e-11.
        let (p, q, vv) = (1e8, -2e-2, 1e10);
        let exact = 9.999_999_950_000_001e-11;
        let stable = later_root(p, q, vv).unwrap();
        assert!(
            (stable - exact).abs() <= 4.0 * f64::EPSILON * exact,
            "{stable}"
        );
        let textbook = (-p + (p * p - vv * q).sqrt()) / vv;
        // The textbook form keeps only 8 digits here (5e-9 relative).
        assert!((textbook - exact).abs() > 1e-9 * exact);
    }

    #[test]
    fn leaves_reach_is_when_the_centres_part() {
        // Centres 1 m apart along x, parting at 2 m/s: within reach 3 m
        // until 1 + 2τ = 3, τ = 1 s.
        let d0 = DVec3::new(1.0, 0.0, 0.0);
        let v = DVec3::new(2.0, 0.0, 0.0);
        assert_eq!(leaves_reach(d0, v, 3.0), Some(1.0));
        // Closing from 5 m at 2 m/s: in reach from τ = 1 s to τ = 4 s.
        assert_eq!(leaves_reach(DVec3::new(5.0, 0.0, 0.0), -v, 3.0), Some(4.0));
        // Already parted, or not moving: never again.
        assert_eq!(leaves_reach(DVec3::new(5.0, 0.0, 0.0), v, 3.0), None);
        assert_eq!(leaves_reach(d0, DVec3::ZERO, 3.0), None);
    }
}
