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
/// when they never can. Every Lorentz-contracted (or Born-rigid) body lies
/// inside its rest disc, so the pucks touch only once their rest discs
/// do. Two bounds of when that can be, the later returned:
///
/// * Each centre moves on a straight line, never faster than at `now`
///   (braking only slows it: `|x(t) − x(now)| ≤ |v(now)| (t − now)`), and a
///   braking one no farther than to where it stops: the gap between the
///   rest discs, `|Δx(now)| − ra − rb`, must be closed at the sum of the
///   speeds.
/// * Up to `limit` (s; the caller only asks whether they can touch before
///   it), each centre is within `a τ²/2` of where uniform motion at its
///   velocity at `now` would take it, `τ = t − now` (its board deceleration
///   is `a/γ³ ≤ a`, `a` its proper one; it is uniform before its segment
///   begins), so the rest discs can meet only where the uniform motions'
///   centres come within `ra + rb + (a_a + a_b) τ_max²/2`: [`disc_touch`]
///   with that reach. Past `limit` this says nothing, so a time after
///   `limit` is returned where it finds none before.
///
/// The gap is shrunk, and the reach grown, by 1e-9 relative so rounding
/// never makes the bound late.
///
/// Each puck is given by its [`BrakingReach`] at `now` (one puck's is
/// worked out once for all its partners).
#[must_use]
pub fn braking_touch(
    a: &BrakingReach,
    ra: f64,
    b: &BrakingReach,
    rb: f64,
    now: f64,
    limit: f64,
) -> Option<f64> {
    let (xa, va, la) = (a.position, a.velocity, a.left);
    let (xb, vb, lb) = (b.position, b.velocity, b.left);
    let gap = ((xb - xa).length() - (ra + rb)) * (1.0 - 1e-9) - 1e-12;
    if gap <= 0.0 {
        return Some(now);
    }
    if la + lb < gap {
        return None; // they stop apart
    }
    let closing = va.length() + vb.length();
    if closing.is_nan() || closing <= 0.0 {
        return None;
    }
    let first = now + gap / closing;
    if !(first <= limit && limit.is_finite()) {
        return Some(first);
    }
    let tau = limit - now;
    let slack = 0.5 * (a.deceleration + b.deceleration) * tau * tau;
    let reach = ra + rb + slack * (1.0 + 1e-9);
    match disc_touch(xa, va, 0.5 * reach, xb, vb, 0.5 * reach, now) {
        Some(t) if t <= limit => Some(t.max(first)),
        _ => Some(limit.next_up()),
    }
}

/// A lower bound on the board time of the earlier kick of a contact of
/// two pucks when either brakes, up to `limit` as [`braking_touch`]: the
/// pucks reach as `a` and `b` from `now` (rest radii `ra`, `rb`, m; speed
/// of light `c`, m/s). The kicks are simultaneous with the contact in the
/// pair frame, not on the board: for uniform motions the rest discs touch
/// by the earlier kick ([`disc_touch`]), and a kick precedes its contact
/// by at most `lead = 2 β R / (c (1 − β²))` (`β` the larger board speed
/// now over `c`, `R` the larger radius: the lead of
/// `braking::pair_before`, doubled there for a kick before now), over
/// which each braking centre leaves its tangent line by at most `a
/// lead²/2`; each disc is grown by twice that ([`kick_growth`]).
/// [`braking_touch`] alone bounds the contact, not the kick: a puck's
/// prediction pruned by it passed over a kick 1.2 ms before it, in a
/// 5 000-puck gas on the cloth (c = 1.42 m/s, whose contact came 7 ms
/// after that kick), and took a later contact first.
#[must_use]
pub fn braking_kick(
    a: &BrakingReach,
    ra: f64,
    b: &BrakingReach,
    rb: f64,
    c: f64,
    now: f64,
    limit: f64,
) -> Option<f64> {
    let beta = a.velocity.length().max(b.velocity.length()) / c;
    let grown = kick_growth(beta, ra.max(rb), c, a.deceleration + b.deceleration);
    braking_touch(a, ra + grown, b, rb + grown, now, limit)
}

/// How much [`braking_kick`] grows each rest disc: `(a_a + a_b) lead² / 2`,
/// `lead = 2 β R / (c (1 − β²))` (m; `beta` the larger board speed over
/// `c`, `radius` the larger rest radius R, m, `decelerations` the sum of
/// the two proper decelerations `a_a + a_b`, m/s², 0 for one that does not
/// brake).
#[must_use]
pub fn kick_growth(beta: f64, radius: f64, c: f64, decelerations: f64) -> f64 {
    let beta = beta.min(1.0 - 1e-9);
    let lead = 2.0 * beta * radius / (c * (1.0 - beta) * (1.0 + beta));
    0.5 * decelerations * lead * lead
}

/// What [`braking_apart_until`] reads of one puck: its current segment's
/// start (board time s, centre m), its board velocity there (m/s), its rest
/// radius (m) and whether it brakes.
#[derive(Clone, Copy, Debug)]
pub struct SegmentStart {
    /// Board time the segment starts, s.
    pub t0: f64,
    /// Centre at `t0`, m (board plane).
    pub x0: DVec2,
    /// Board velocity at `t0`, m/s (its largest on the segment).
    pub v: DVec2,
    /// Rest radius, m.
    pub radius: f64,
    /// Whether the segment brakes.
    pub braking: bool,
}

/// A first test for two pucks of which at least one brakes, before
/// [`BrakingReach`] and [`braking_touch`]: `true` if their rest discs stay
/// apart from board time `now` to `limit` (s), shown without the braking
/// law (no root, no division). A braking centre's board speed only falls,
/// so it moves at most its segment's start speed `|v|` per second; and it
/// falls behind its uniform extrapolation from the start, `x0 + v (t −
/// t0)`, by at most `a (t − t0)²/2`, `a` ≥ its proper deceleration (the
/// board deceleration `a/γ³` is smaller until it stops; after the stop the
/// lag grows at `|v|`, and `a (t − t0) ≥ a t_stop = c u₀ ≥ |v|`). So the
/// centres are at least their extrapolations' distance less both lags
/// apart now, and close by at most `(|v_a| + |v_b|) (limit − now)`. A pair
/// shown apart here is one [`braking_touch`] would also put past `limit`
/// (its rest discs do not touch by then); `false` says nothing. The reach
/// is grown by 1e-9 relative and 1e-12 m against rounding.
#[must_use]
pub fn braking_apart_until(
    a: &SegmentStart,
    b: &SegmentStart,
    deceleration: f64,
    now: f64,
    limit: f64,
) -> bool {
    if !(limit.is_finite() && deceleration.is_finite()) {
        return false;
    }
    let lag = |s: &SegmentStart| {
        if s.braking {
            let run = (now - s.t0).max(0.0);
            0.5 * deceleration * run * run
        } else {
            0.0
        }
    };
    let (xa, xb) = (a.x0 + a.v * (now - a.t0), b.x0 + b.v * (now - b.t0));
    let reach = (a.radius
        + b.radius
        + lag(a)
        + lag(b)
        + (a.v.length() + b.v.length()) * (limit - now).max(0.0))
        * (1.0 + 1e-9)
        + 1e-12;
    (xb - xa).length_squared() > reach * reach
}

/// What [`braking_touch`] needs of one puck at a board time: where its
/// centre is (m, board plane), its board velocity (m/s), how far it still
/// moves before it stops (m; ∞ if it never does, 0 at rest), and its proper
/// deceleration (m/s², 0 unless it brakes).
#[derive(Clone, Copy, Debug)]
pub struct BrakingReach {
    position: DVec2,
    velocity: DVec2,
    left: f64,
    deceleration: f64,
}

impl BrakingReach {
    /// The puck on `segment` at board time `now`.
    #[must_use]
    pub fn of(segment: &Segment, now: f64) -> Self {
        if !segment.is_braking() {
            return Self {
                position: segment.position_at(now).truncate(),
                velocity: segment.velocity_at(now).truncate(),
                left: if segment.is_rest() {
                    0.0
                } else {
                    f64::INFINITY
                },
                deceleration: 0.0,
            };
        }
        // Along its straight path: the stopping distance less the distance
        // already run, by the braking law's closed forms (`sliding`:
        // `u = u₀ − a t/c`, run `c t (u₀ + u)/(γ₀ + γ)`, stopping distance
        // `(c²/a) u₀²/(γ₀ + 1)`) from the segment's own `γ₀`: one square
        // root. They differ from the worldline's by rounding, far less than
        // the bound's gap is shrunk by.
        let c = segment.speed_of_light();
        let per_second = segment.deceleration() / c;
        let u0 = segment.u.0.dot(segment.direction());
        let g0 = segment.gamma();
        let stopping = c / per_second * (u0 * u0 / (g0 + 1.0));
        let run = (now - segment.start.t).max(0.0);
        let u = (u0 - per_second * run).max(0.0);
        let g = (1.0 + u * u).sqrt();
        let run_distance = if u > 0.0 {
            c * run * (u0 + u) / (g0 + g)
        } else {
            stopping
        };
        let position = if run > 0.0 {
            segment.start.position + segment.direction() * run_distance
        } else {
            segment.position_at(now)
        };
        let left = (stopping - run_distance).max(0.0);
        let speed = c * u / g;
        Self {
            position: position.truncate(),
            velocity: (segment.direction() * speed).truncate(),
            left,
            deceleration: segment.deceleration(),
        }
    }
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

    /// `braking_apart_until` against the worldlines themselves: random
    /// pairs (braking, stopped, not yet started, uniform, at rest) whose
    /// centres are sampled every 1e-4 s from now to the limit; wherever the
    /// test says apart, the rest discs are apart at every sample. It must
    /// also say apart often, or it prunes nothing.
    #[test]
    fn the_first_braking_bound_never_calls_touching_rest_discs_apart() {
        use crate::spacetime::{Event, ProperVelocity};
        use crate::worldline::Worldline;
        let mut rng = crate::physics::gas::Rng::new(0xb4a_7e5);
        let mut next = move || rng.next_f64();
        let (c, r, a) = (1.42, 0.0305, 1.96);
        let (mut apart, mut cases) = (0, 0);
        let puck = |braking: bool, next: &mut dyn FnMut() -> f64| {
            let start = Event::new(0.3 * next(), DVec3::new(0.4 * next(), 0.4 * next(), 0.0));
            let beta = DVec3::new(next() - 0.5, next() - 0.5, 0.0) * 1.6;
            let u = ProperVelocity::try_from_beta(beta.clamp_length_max(0.8))
                .unwrap_or(ProperVelocity::ZERO);
            let u = if next() < 0.1 {
                ProperVelocity::ZERO
            } else {
                u
            };
            let w = Worldline::braking(start, u, c, if braking { a } else { 0.0 });
            let s = *w.last();
            let hot = SegmentStart {
                t0: s.start.t,
                x0: s.start.position.truncate(),
                v: s.velocity().truncate(),
                radius: r,
                braking: s.is_braking(),
            };
            (s, hot)
        };
        for _ in 0..3000 {
            let (brakes_a, brakes_b) = (next() < 0.8, next() < 0.8);
            let (sa, ha) = puck(brakes_a, &mut next);
            let (sb, hb) = puck(brakes_b, &mut next);
            let now = 0.2 + 1.5 * next();
            let limit = now + 0.1 * next();
            cases += 1;
            if !braking_apart_until(&ha, &hb, a, now, limit) {
                continue;
            }
            apart += 1;
            let steps = ((limit - now) / 1e-4).ceil() as usize + 1;
            for k in 0..=steps {
                let t = now + (limit - now) * k as f64 / steps as f64;
                let d = (sb.position_at(t) - sa.position_at(t)).length();
                assert!(d > 2.0 * r, "called apart, but {d} m at {t} s");
            }
        }
        assert!(
            apart > cases / 4 && apart < cases,
            "{apart} of {cases} called apart"
        );
    }

    /// `braking_kick` against the contacts themselves: random braking
    /// pairs (c = 1.42 m/s, μg = 1.96 m/s², up to β = 0.95, the dense
    /// gas's radius), each pair's next contact found exactly
    /// (`braking::pair_before`); its earlier kick is never before the
    /// bound (asked with the kick as the limit). The rest discs' own touch
    /// (`braking_touch`, the bound a prediction used to prune with) comes
    /// after the kick in some of them: the test must see that, or it
    /// checks nothing a plain disc bound would not pass.
    #[test]
    fn the_braking_kick_bound_is_never_after_the_earlier_kick() {
        use crate::physics::predict::braking::pair_before;
        use crate::physics::predict::puck_puck::Mover;
        use crate::spacetime::{Event, ProperVelocity};
        use crate::worldline::Worldline;
        let mut rng = crate::physics::gas::Rng::new(0x006b_1c4e);
        let mut next = move || rng.next_f64();
        let (c, r, a) = (1.42, 0.0305, 1.96);
        let (mut contacts, mut touch_late) = (0, 0);
        for _ in 0..20_000 {
            let puck = |at: DVec3, next: &mut dyn FnMut() -> f64| {
                let start = Event::new(0.05 * next(), at);
                let beta = DVec3::new(next() - 0.5, next() - 0.5, 0.0) * 2.0;
                let u = ProperVelocity::try_from_beta(beta.clamp_length_max(0.95))
                    .unwrap_or(ProperVelocity::ZERO);
                *Worldline::braking(start, u, c, a).last()
            };
            let sa = puck(DVec3::ZERO, &mut next);
            let d = 2.0 * r + 0.2 * next();
            let angle = std::f64::consts::TAU * next();
            let sb = puck(DVec3::new(d * angle.cos(), d * angle.sin(), 0.0), &mut next);
            let now = 0.05;
            if (sb.position_at(now) - sa.position_at(now)).length() <= 2.0 * r {
                continue;
            }
            let mover = |s| Mover {
                segment: s,
                radius: r,
            };
            let Some(hit) = pair_before(mover(&sa), mover(&sb), c, now, f64::INFINITY) else {
                continue;
            };
            let kick = hit.kicks[0].t.min(hit.kicks[1].t);
            if kick <= now {
                continue;
            }
            contacts += 1;
            let (ra, rb) = (BrakingReach::of(&sa, now), BrakingReach::of(&sb, now));
            let bound = braking_kick(&ra, r, &rb, r, c, now, kick);
            assert!(
                bound.is_some_and(|t| t <= kick),
                "kick at {kick} s, bound {bound:?} (contact at {} s)",
                hit.contact.t
            );
            if braking_touch(&ra, r, &rb, r, now, kick).is_some_and(|t| t > kick) {
                touch_late += 1;
            }
        }
        assert!(
            contacts > 1500 && touch_late >= 3,
            "{contacts} contacts, {touch_late} with the rest discs' touch after the kick"
        );
    }

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
