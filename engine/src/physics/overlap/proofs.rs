//! Cheap one-sided proofs about the overlap of two pucks on the board
//! ([`apart_throughout`], [`overlap_certain`]): a few support evaluations
//! that decide most pairs without the scan of [`super::gap_min`], and say
//! nothing (`false`) where they cannot.

use super::*;

/// Whether two uniformly moving pucks are proved apart on the board at
/// every board time in `[t0, t1]`, in the sense the overlap tests compute
/// it: [`gap_min`] (and so [`gap`]) is negative for the centres' separation
/// at any such time, so [`penetration`] finds nothing there and
/// [`first_touch`] on that interval returns `None`. A cheap, one-sided
/// test (a few support evaluations, no search): `false` says nothing.
///
/// Why it holds: for a fixed unit direction `m` the function `h_a(m) +
/// h_b(m) − m·d(t)` is linear in `t` (the separation `d` is) and lies
/// above the gap function `G(t)` at every `t`. [`gap_min`] returns the
/// minimum over a set of directions that contains its scan directions, so
/// its value is at most that line's, evaluated with the same arithmetic,
/// for any scan direction. Each candidate scan direction (those nearest
/// the line of centres at `t0`, at `t1` and at the centres' closest
/// approach) is negative on a sub-interval of `[t0, t1]` (a line is below a
/// level on a half-line); if these sub-intervals cover `[t0, t1]`, every
/// evaluation there is negative. Each line is required below `−margin`,
/// with `margin` a thousand times the rounding of the positions, supports
/// and dot products (relative `1e-12` of the lengths involved), so
/// rounding can never make a computed value positive.
#[must_use]
pub fn apart_throughout(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    t0: f64,
    t1: f64,
) -> bool {
    if a.is_braking() || b.is_braking() || t1.partial_cmp(&t0) != Some(std::cmp::Ordering::Greater)
    {
        return false;
    }
    let d0 = b.position_at(t0) - a.position_at(t0);
    let d1 = b.position_at(t1) - a.position_at(t1);
    // What the positions are computed from bounds their rounding.
    let scale = radius_a
        + radius_b
        + l1(a.start.position)
        + l1(b.start.position)
        + (l1(a.velocity()) + l1(b.velocity()))
            * (t0.abs() + t1.abs() + a.start.t.abs() + b.start.t.abs());
    let margin = 1e-12 * scale;
    if !margin.is_finite() {
        return false;
    }
    // The centres' closest approach on the interval (parameter s ∈ [0, 1]).
    let v = d1 - d0;
    let vv = v.length_squared();
    let s = if vv > 0.0 {
        (-d0.dot(v) / vv).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let closest = d0 + v * s;
    let (cos, sin) = scan();
    let (oa, ob) = (Outline::of(a, radius_a), Outline::of(b, radius_b));
    let step = std::f64::consts::TAU / SAMPLES as f64;
    let nearest = |w: DVec3| -> usize {
        let k = (rough_angle(w.y, w.x) / step).round();
        // The angle is in [−π, π]: k in [−45, 45], wrapped into the scan's
        // range. (Any k is sound; the nearest is the likeliest to prove.)
        (k as i64).rem_euclid(SAMPLES as i64) as usize
    };
    // Covered so far: [0, left) by rising lines, (right, 1] by falling ones.
    let (mut left, mut right) = (0.0f64, 1.0f64);
    for w in [closest, d0, d1] {
        if w.length_squared() == 0.0 {
            continue;
        }
        let k0 = nearest(w);
        for k in [k0, (k0 + 1) % SAMPLES, (k0 + SAMPLES - 1) % SAMPLES] {
            let (g0, g1) = (
                gap_along(&oa, &ob, cos[k], sin[k], d0),
                gap_along(&oa, &ob, cos[k], sin[k], d1),
            );
            match (g0 <= -margin, g1 <= -margin) {
                (true, true) => return true,
                // Below −margin from 0 to where the line crosses it.
                (true, false) => left = left.max((-margin - g0) / (g1 - g0)),
                // Below −margin from where it crosses to 1.
                (false, true) => right = right.min((-margin - g0) / (g1 - g0)),
                (false, false) => {}
            }
            if left > right {
                return true;
            }
        }
    }
    false
}

/// `|x| + |y| + |z|`, m (at least the length: a cheap bound for margins).
fn l1(w: DVec3) -> f64 {
    w.x.abs() + w.y.abs() + w.z.abs()
}

/// `atan2(y, x)` to within 3e-4 rad (a polynomial on the octant): enough to
/// pick the scan direction nearest a vector, and much cheaper than libm's.
fn rough_angle(y: f64, x: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, PI};
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    if hi == 0.0 {
        return 0.0;
    }
    let r = lo / hi;
    let r2 = r * r;
    let mut angle = ((-0.046_496_474_9 * r2 + 0.159_314_22) * r2 - 0.327_622_764) * r2 * r + r;
    if ay > ax {
        angle = FRAC_PI_2 - angle;
    }
    if x < 0.0 {
        angle = PI - angle;
    }
    if y < 0.0 { -angle } else { angle }
}

/// Whether two pucks are proved to overlap on the board at board time `t`
/// in the sense [`penetration`] computes it (it then returns a depth): a
/// cheap, one-sided test (`false` says nothing).
///
/// Why it holds: a point `p` inside both shapes, at "elliptic radius" `s <
/// 1` of each (the shape scaled by `s` about its centre reaches `p`), has a
/// disc of radius `(1 − s) R/γ` about it inside that shape (the shape is
/// convex and contains its disc of radius `R/γ`). Then for every unit `m`,
/// `h_a(m) ≥ m·(p − x_a) + δ_a` and `h_b(m) ≥ −m·(p − x_b) + δ_b`, so the
/// gap function is at least `δ_a + δ_b` everywhere, and so is every value
/// [`gap_min`] and [`gap`]'s line of centres compute, up to rounding. The
/// point is taken on the line of centres where the two elliptic radii are
/// equal; `δ_a + δ_b` must exceed a margin of `1e-12` of the lengths
/// involved (a thousand times their rounding).
#[must_use]
pub fn overlap_certain(a: &Segment, radius_a: f64, b: &Segment, radius_b: f64, t: f64) -> bool {
    if a.is_braking() || b.is_braking() {
        return false;
    }
    let d = b.position_at(t) - a.position_at(t);
    // Elliptic norm of an offset: 1 on the shape's boundary.
    let norm = |s: &Segment, radius: f64, w: DVec3| {
        let map = s.lorentz_map();
        let n = map.direction();
        let along = n.dot(w);
        let across = w - n * along;
        ((along / map.inverse_gamma()).powi(2) + across.length_squared()).sqrt() / radius
    };
    let (na, nb) = (norm(a, radius_a, d), norm(b, radius_b, d));
    if !(na > 0.0 && nb > 0.0 && (na + nb).is_finite()) {
        return false;
    }
    // p = x_a + λ d with λ na = (1 − λ) nb: both elliptic radii equal s.
    let s = na * nb / (na + nb);
    let inner = |s_: &Segment, radius: f64| radius * s_.lorentz_map().inverse_gamma();
    let depth = (1.0 - s) * (inner(a, radius_a) + inner(b, radius_b));
    let scale = radius_a
        + radius_b
        + l1(a.start.position)
        + l1(b.start.position)
        + (l1(a.velocity()) + l1(b.velocity())) * (t.abs() + a.start.t.abs() + b.start.t.abs());
    depth > 1e-12 * scale
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::{Event, ProperVelocity};
    use crate::worldline::Worldline;

    /// Random pairs of uniformly moving pucks, near each other (the seeded
    /// `gas::Rng`, deterministic): proper velocities up to 3 (γ ≈ 3.2), radii 0.02–0.04.
    fn random_pairs(n: usize) -> Vec<(Worldline, f64, Worldline, f64)> {
        let mut rng = crate::physics::gas::Rng::new(0x2545_f491_4f6c_dd1d);
        let mut next = move || rng.next_f64();
        (0..n)
            .map(|_| {
                let mut puck = |x: f64| {
                    let u = DVec3::new(6.0 * next() - 3.0, 6.0 * next() - 3.0, 0.0);
                    let at = DVec3::new(x + 0.1 * next(), 0.1 * next(), 0.0);
                    let w = Worldline::new(Event::new(0.0, at), ProperVelocity(u), 1.0);
                    (w, 0.02 + 0.02 * next())
                };
                let (a, ra) = puck(0.0);
                let (b, rb) = puck(0.03);
                (a, ra, b, rb)
            })
            .collect()
    }

    #[test]
    fn apart_throughout_is_never_wrong_and_often_decides() {
        let (mut proved, mut apart_at_start) = (0, 0);
        for (a, ra, b, rb) in random_pairs(4000) {
            let (sa, sb) = (a.last(), b.last());
            let (t0, t1) = (0.0, 0.02);
            if penetration(sa, ra, sb, rb, t0).is_none() {
                apart_at_start += 1;
            }
            if !apart_throughout(sa, ra, sb, rb, t0, t1) {
                continue;
            }
            proved += 1;
            for k in 0..=50 {
                let t = t0 + (t1 - t0) * k as f64 / 50.0;
                let d = sb.position_at(t) - sa.position_at(t);
                assert!(gap_min(sa, ra, sb, rb, d).0 < 0.0, "overlap at {t}");
            }
            assert_eq!(first_touch(sa, ra, sb, rb, t0, t1), None);
        }
        assert!(proved * 2 > apart_at_start, "{proved} of {apart_at_start}");
    }

    #[test]
    fn overlap_certain_is_never_wrong_and_often_decides() {
        let (mut proved, mut overlapping) = (0, 0);
        for (a, ra, b, rb) in random_pairs(4000) {
            let (sa, sb) = (a.last(), b.last());
            let found = penetration(sa, ra, sb, rb, 0.0).is_some();
            overlapping += usize::from(found);
            if overlap_certain(sa, ra, sb, rb, 0.0) {
                proved += 1;
                assert!(found);
            }
        }
        assert!(proved * 2 > overlapping, "{proved} of {overlapping}");
    }

    #[test]
    fn rough_angle_is_within_3e4_of_atan2() {
        for k in 0..10_000 {
            let theta = -3.2 + 6.4 * k as f64 / 10_000.0;
            let (y, x) = (3.0 * theta.sin(), 3.0 * theta.cos());
            let err = (rough_angle(y, x) - y.atan2(x)).abs();
            assert!(
                err < 3e-4 || (err - std::f64::consts::TAU).abs() < 3e-4,
                "{theta}: {err}"
            );
        }
        assert_eq!(rough_angle(0.0, 0.0), 0.0);
    }
}
