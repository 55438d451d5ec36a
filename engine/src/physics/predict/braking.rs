//! Contacts on decelerating worldlines (sliding friction): puck–cushion and
//! puck–puck prediction when at least one puck is on a braking segment
//! ([`crate::worldline::sliding`]), exact to the rounding of the shapes'
//! separation, with a root isolation that cannot miss a contact.
//!
//! ## The shapes
//!
//! At board time `t` a puck is taken as its rest disc contracted by its
//! *instantaneous* `1/γ(t)` along its (fixed) direction of motion: the shape
//! of the uniform motion tangent to its worldline then
//! ([`Segment::tangent_at`]). The Born-rigid braking body
//! (`worldline::sliding`) differs from it by at most `R ρ β²/2` along the
//! motion, `ρ = R μg/c²` (1.5·10⁻³ R for the paper's table with μ = 0.2,
//! 10⁻¹⁴ R at c = 10⁶ m/s); optics draws the Born-rigid body.
//!
//! ## Puck–cushion: a monotone gap
//!
//! Along an axis-aligned cushion's normal `k` the gap is
//! `G(t) = s (L − x_k(t)) − h_k(t)`, with `h_k = R √(1 + u⊥²)/γ` the
//! half-width ([`puck_cushion::half_width`]). A braking puck moves along a
//! fixed line, so if it heads for the cushion `x_k` only grows; and
//! `h_k² = R² (1 + u² sin²φ)/(1 + u²)` grows as `u` falls. So `G` is
//! *decreasing*: it has at most one root on `[now, t_stop]`, bracketed by
//! `G(now) > 0 ≥ G(t_stop)` and found by bisection to adjacent floats. A
//! puck that stops with `G(t_stop) ≥ 0` never touches it (it may rest
//! against it with no event).
//!
//! ## Puck–puck: root isolation by proved bounds
//!
//! The *separation* `σ(t)` is minus the signed gap of the two board shapes
//! ([`overlap::gap`]): positive while they are apart, and then a lower
//! bound of their distance (the line-of-centres axis, or the widest one).
//! The distance changes no faster than
//!
//! ```text
//! L = V + 0.385 (R_a a_a + R_b a_b)/c,   V ≥ max |v_b(t) − v_a(t)|
//! ```
//!
//! (`V` the smaller of `|v_a(now)| + |v_b(now)|`, board speeds only falling
//! while braking, and a bound on the relative speed from the proper speeds'
//! linear fall and the directions: `relative_speed_bound`; the support `R|contract(m)|`
//! changes at `R |d(1/γ)/dt| = R (a/c) u/γ³ ≤ 0.385 R a/c`, and the distance
//! of convex bodies is 1-Lipschitz in each body's support). Along one axis
//! `m` the separation is sharper than that: it moves at `m·(v_b − v_a)`,
//! which changes by at most `(a_a + a_b) Δt` (a braking puck's board
//! acceleration is `a/γ³ ≤ a`), plus the supports' change. The search
//! ([`isolation::first_contact_before`](super::isolation)) proves stretches
//! of `[now, t_end]` apart with these bounds, depth-first, earliest first,
//! so the first interval whose end overlaps contains the *first* contact,
//! and closes in on it superlinearly (the module doc there). No fixed step
//! is taken: a stretch is only ever discarded by a bound. The window ends
//! when the last braking puck stops (then both rest, or the rest of the
//! motion is uniform and the closed form of [`puck_puck::predict`] takes
//! over).
//!
//! A touch at which the pucks are not closing along the contact normal (a
//! puck that comes to rest against another) is no contact: it rests there
//! with no event, so there is no Zeno sequence of ever smaller bounces.
//!
//! ## Limits
//!
//! * A touch at which the pair is not closing ends the search of that
//!   window (a graze, or a puck stopping against another); a later contact
//!   of the same pair on the same segments would be missed. Uniform motion
//!   cannot graze and then meet; braking motion could, in contrived cases.
//! * Pucks overlapping and opening at `now` are searched from the first
//!   time a doubling step finds them apart, not from a proven bracket.
//! * The search is the cost of friction (BENCHMARKS.md, Friction): the
//!   event loop prunes pairs first (`predict::bounds::braking_apart_until`
//!   from its packed records, then `predict::bounds::braking_kick`, both
//!   on rest discs grown so that they bound the earlier kick, which can
//!   come before the contact) and
//!   stops the search at its earliest event so far ([`pair_before`]); a
//!   probe where the rest discs overlap is a local axis search from the
//!   last probe's axis, and an overlap scan only where that neither finds
//!   the shapes apart nor shows them overlapping or touching to rounding
//!   (at a contact's probes the shapes touch to rounding: there the scan
//!   was a tenth of a dense gas's loop).
//!
//! ## The collision convention
//!
//! Unchanged: the contact event is where the board shapes first touch; each
//! puck's velocity changes at the event on its centre's worldline that is
//! *simultaneous with the contact in the pair frame* (the normalised sum of
//! the two 4-velocities, taken at the kicks themselves: a fixed point found
//! by Newton's method on both kicks, the frame's turn with them in its
//! Jacobian, `braking_kicks`);
//! the normal is the pair frame's, the gradient of the summed similar
//! ellipses at the centres' separation there, as in [`puck_puck`].

use glam::{DVec2, DVec3};

use super::braking_kicks::in_pair_frame;
use super::braking_motion::Motion;
use super::isolation::{Probe, Rates, bisect, first_contact_before};
use super::puck_cushion::{self, Cushion, CushionContact};
use super::puck_puck::{self, Mover, PairContact};
use crate::physics::overlap;
use crate::spacetime::{Event, ProperVelocity};
use crate::worldline::Segment;

/// `tan(π/12)`: the axis search from the line of centres looks 30° either
/// side of it ([`overlap::refine_within`]).
const WIDE: f64 = 0.267_949_192_431_122_7;

/// Bound on `R |d(1/γ)/dt| / (R a / c)`: `max u/(1 + u²)^{3/2} = 2/(3√3)`.
const SHAPE_RATE: f64 = 0.385;

/// The next contact, at board time ≥ `now`, of a puck on `segment` (any
/// kind) with `cushion`; for a braking segment by the monotone gap (module
/// doc), otherwise [`puck_cushion::predict`].
#[must_use]
pub fn cushion(
    segment: &Segment,
    radius: f64,
    table: DVec2,
    cushion: Cushion,
    now: f64,
) -> Option<CushionContact> {
    if !segment.is_braking() {
        return puck_cushion::predict(segment, radius, table, cushion, now);
    }
    let k = cushion.axis();
    let s = cushion.outward_sign();
    if segment.direction()[k] * s <= 0.0 {
        return None; // moving away or along: the direction never changes
    }
    let end = segment.stop_time()?;
    if now >= end {
        return None;
    }
    let line = cushion.line(table);
    let gap = |t: f64| {
        s * (line - segment.position_at(t)[k])
            - puck_cushion::half_width(radius, segment.u_at(t), k)
    };
    let t = if gap(now) <= 0.0 {
        now // touching (or past, by rounding) and moving in
    } else {
        if gap(end) >= -1e-12 * radius {
            return None; // stops short of it, or against it (to rounding)
        }
        bisect(gap, now, end)
    };
    Some(CushionContact {
        t,
        point: segment.position_at(t)
            + puck_cushion::support_offset(radius, segment.u_at(t), cushion),
    })
}

/// The board time of [`cushion`]'s contact alone, s (the same value),
/// without working out the contact point for a uniform segment.
#[must_use]
pub fn cushion_time(
    segment: &Segment,
    radius: f64,
    table: DVec2,
    cushion: Cushion,
    now: f64,
) -> Option<f64> {
    if !segment.is_braking() {
        return puck_cushion::time(segment, radius, table, cushion, now);
    }
    self::cushion(segment, radius, table, cushion, now).map(|hit| hit.t)
}

/// A bound on the relative board speed `|v_b − v_a|` of two segments
/// (each braking along its direction, uniform or at rest) over board times
/// `[from, end]`, m/s: how fast the centres' offset, and so the
/// separation of two shapes that keep their form, can change.
///
/// The sum of the speeds at `from` bounds it (speeds only fall). So does
/// the part along and the part across: with `gᵢ` the speeds and `dᵢ` the
/// directions, `v_b − v_a = (g_b − g_a) d_b + g_a (d_b − d_a)` (or the
/// same with `a` and `b` swapped), where `|g_b − g_a| ≤ c |s_b − s_a|`
/// (the speed `c s/√(1 + s²)` of proper speed `s` changes at most `c`
/// per unit of `s`) and the proper speeds fall linearly, `sᵢ(t) = sᵢ(from)
/// − aᵢ (t − from)/c` (clamped at 0, which only narrows their
/// difference). The smaller bound is returned: for two pucks moving
/// nearly together (a cluster at restitution 0 on the cloth) it is their
/// small relative speed, not the sum, and the root isolation, whose step
/// is the separation over this bound, takes a few steps instead of tens
/// of thousands (issue 34, item 5).
fn relative_speed_bound(sa: &Segment, sb: &Segment, from: f64, end: f64, c: f64) -> f64 {
    let (ga, gb) = (speed_at(sa, from), speed_at(sb, from));
    if from < sa.start.t.max(sb.start.t) {
        // A segment not yet begun (its start values hold before it) would
        // brake later than the linear law from `from` says: the sum only.
        return ga + gb;
    }
    let (pa, pb) = (sa.u_at(from).0.length(), sb.u_at(from).0.length());
    let across = ga.min(gb) * (sb.direction() - sa.direction()).length();
    let along =
        c * (pb - pa).abs() + (sb.deceleration() - sa.deceleration()).abs() * (end - from).max(0.0);
    (ga + gb).min(across + along)
}

/// The board speed of a segment at `t` (its largest from `t` on), m/s.
fn speed_at(s: &Segment, t: f64) -> f64 {
    s.velocity_at(t).length()
}

/// Separation of the two board shapes at `t` (> 0 apart; a lower bound of
/// their distance) and the unit axis, from `a` towards `b`.
fn separation(a: &Segment, ra: f64, b: &Segment, rb: f64, t: f64) -> (f64, DVec3) {
    let (oa, ob) = outlines_at(a, ra, b, rb, t);
    let d = b.position_at(t) - a.position_at(t);
    let (g, m) = overlap::gap_of(&oa, &ob, d);
    (-g, m)
}

/// [`separation`] for the root isolation's probes: the same sign, and where
/// the rest discs overlap the widest separation (not only the line of
/// centres') when a local search from `hint` (the last probe's axis) finds
/// the shapes apart, which then needs no scan ([`overlap::refine_near`]: a
/// local minimum below zero is the global one). The value is the
/// separation along the axis returned, which the bounds of
/// [`isolation`](super::isolation) need.
///
/// Where the rest discs overlap and the local search finds them not apart,
/// an overlap is taken as shown when [`overlap::overlap_near`] finds a
/// point inside both near its axis, or a touch to rounding (4 ε of the
/// radii) when [`overlap::touch_shown`] bounds the widest separation from
/// that axis (no scan either); otherwise the scan decides.
fn separation_near(
    oa: &overlap::Outline,
    ob: &overlap::Outline,
    d: DVec3,
    hint: Option<DVec3>,
) -> (f64, DVec3) {
    let (ra, rb) = (oa.radius(), ob.radius());
    let dist = d.length();
    // A touch to rounding shown from the axis found also needs no scan
    // (the probes at a contact: most scans were there).
    let slack = 4.0 * f64::EPSILON * (ra + rb);
    let local = |refined: Option<(f64, DVec3)>| {
        refined.filter(|&(g, m)| {
            g < 0.0
                || overlap::overlap_near(oa, ob, d, m)
                || overlap::touch_shown(oa, ob, d, m, slack)
        })
    };
    if dist < ra + rb && dist > 0.0 {
        // Within rounding of the touch the sign decides the contact's time,
        // so it must not depend on which probes came before: the axis is
        // then searched from the line of centres, a function of `t` alone.
        let canonical = 1e-12 * (ra + rb);
        let warm = hint.and_then(|m0| local(overlap::refine_warm(oa, ob, d, m0)));
        let found = warm.filter(|&(g, _)| g.abs() > canonical).or_else(|| {
            let centres = d / dist;
            local(overlap::refine_warm_within(oa, ob, d, centres, WIDE))
                .or_else(|| local(overlap::refine_within(oa, ob, d, centres, WIDE)))
        });
        if let Some((g, m)) = found {
            return (-g, m);
        }
    }
    let (g, m) = overlap::gap_of(oa, ob, d);
    (-g, m)
}

/// The two pucks' board shapes at `t`: those of their tangent segments
/// ([`Segment::tangent_at`]), without building them.
fn outlines_at(
    a: &Segment,
    ra: f64,
    b: &Segment,
    rb: f64,
    t: f64,
) -> (overlap::Outline, overlap::Outline) {
    (
        overlap::Outline::moving(a.u_at(t), ra, a.speed_of_light()),
        overlap::Outline::moving(b.u_at(t), rb, b.speed_of_light()),
    )
}

/// The next contact of two pucks, at least one on a braking segment, from
/// board time `now` (module doc). `None` if they never touch while closing.
///
/// Pucks overlapping on the board at `now` and closing there (a contact that
/// rounding placed just past) meet at once, as in the frictionless loop: a
/// board contact (`on_board`) at `now` along the penetration direction.
#[must_use]
pub fn pair(a: Mover, b: Mover, c: f64, now: f64) -> Option<PairContact> {
    pair_before(a, b, c, now, f64::INFINITY)
}

/// [`pair`], for a caller that only wants a contact whose earlier kick (or
/// the contact itself) is at or before board time `horizon` (s; the event
/// loop's earliest event so far): the same contact, to the bits, when there
/// is one, and `None` or a later contact otherwise. The root isolation then
/// stops at `horizon` plus the most a kick can precede its contact: the
/// kick on a centre is simultaneous with the contact in the pair frame,
/// whose velocity (a weighted mean of the pucks') is below `β c`, the
/// largest board speed now (braking only slows), and the contact is within
/// a rest radius `R` of the centre, so the kick is at most `β R / (c (1 −
/// β²))` earlier, doubled: against rounding, and for a kick before `now`
/// (a contact within about `R/c` of it), where the pucks were faster. The
/// doubling covers a speed there up to `√(1 − (1 − β²)/2)`. Limit: a
/// braking puck near `c` whose kick falls that far before `now` would
/// have its contact cut (processed later than the full search would);
/// not met in the tests (random pairs to γ ≈ 20, the reference-loop
/// braking gases).
pub fn pair_before(a: Mover, b: Mover, c: f64, now: f64, horizon: f64) -> Option<PairContact> {
    pair_with_bound(a, b, c, now, horizon, relative_speed_bound)
}

/// How fast two segments' centres can move apart or together over a
/// window (`sa`, `sb`, `from`, `end`, `c`), m/s: the root isolation's
/// Lipschitz constant, before the shapes' own change is added.
type SpeedBound = fn(&Segment, &Segment, f64, f64, f64) -> f64;

/// [`pair_before`] with the relative-speed bound given (a test compares
/// [`relative_speed_bound`] with the plain sum of the speeds).
fn pair_with_bound(
    a: Mover,
    b: Mover,
    c: f64,
    now: f64,
    horizon: f64,
    speed_bound: SpeedBound,
) -> Option<PairContact> {
    let (sa, sb) = (a.segment, b.segment);
    let (ra, rb) = (a.radius, b.radius);
    // Moving alike for good: one start time, one proper velocity and one
    // deceleration give one velocity at every later board time, to the
    // bit (a pair the board moved together at restitution 0). Their
    // relative velocity is zero, so however their shapes widen as they
    // slow they never *close* (the contact the search below would find is
    // a touch without closing, which is no event either); the search would
    // only have to prove a separation that stays at the touch apart over
    // the whole braking, subdividing without end.
    if sa.start.t == sb.start.t && sa.u == sb.u && sa.deceleration() == sb.deceleration() {
        return None;
    }
    // Each braking law worked out once for the whole search.
    let (motion_a, motion_b) = (Motion::of(sa), Motion::of(sb));
    let end = [&motion_a, &motion_b]
        .iter()
        .filter_map(|m| m.stop_time())
        .fold(now, f64::max);
    let (speed_a, speed_b) = (
        |t: f64| motion_a.velocity_at(t).length(),
        |t: f64| motion_b.velocity_at(t).length(),
    );
    let still = |t: f64| 1e-12 * (speed_a(t) + speed_b(t)).max(f64::MIN_POSITIVE);
    let closing =
        |t: f64, m: DVec3| m.dot(motion_b.velocity_at(t) - motion_a.velocity_at(t)) < -still(t);
    // A probe of the root isolation at board time `t`: the separation
    // along an axis and its rate there (`exact_slope`: the supports' rate
    // included, both segments begun by then). Each probe starts its axis
    // search from the last probe's axis (`hint`).
    let hint = std::cell::Cell::new(None);
    let probe_at = |t: f64, exact_slope: bool| {
        let (a, b) = (motion_a.at(t, ra), motion_b.at(t, rb));
        let d = b.position - a.position;
        let (sigma, m) = separation_near(&a.outline, &b.outline, d, hint.get());
        hint.set(Some(m));
        let mut rate = m.dot(b.velocity - a.velocity);
        if exact_slope {
            rate -= a.outline.support_rate(m.x, m.y, a.inverse_gamma_rate)
                + b.outline.support_rate(m.x, m.y, b.inverse_gamma_rate);
        }
        Probe { sigma, rate }
    };
    // The separation now is the search's first probe where that shows
    // them apart (an axis with σ > 0 separates them); only where it does
    // not, or no search follows, the overlap is measured (`separation`, the
    // penetration's axis for a contact at once), and the search then
    // starts afresh.
    let exact_now = sa.start.t <= now && sb.start.t <= now;
    let mut first = (end > now)
        .then(|| probe_at(now, exact_now))
        .filter(|p| p.sigma > 0.0);
    if first.is_none() {
        hint.set(None);
    }
    let (s0, m0) = match first {
        Some(p) => (p.sigma, DVec3::ZERO),
        None => separation(sa, ra, sb, rb, now),
    };
    let mut from = now;
    if s0 <= 0.0 && !closing(now, m0) {
        // Overlapping (or touching) and opening: no event while they part.
        // Braking can turn the relative motion, so look on from the first
        // time they are apart (steps doubling from a rounding-sized one).
        let mut h = 1e-12 * (end - now).max(f64::MIN_POSITIVE);
        loop {
            from = now + h;
            if from >= end {
                return None;
            }
            if separation(sa, ra, sb, rb, from).0 > 0.0 {
                break;
            }
            h *= 2.0;
        }
    } else if s0 <= 0.0 {
        let (ta, tb) = (sa.tangent_at(now), sb.tangent_at(now));
        return Some(PairContact {
            contact: Event::new(now, overlap::contact_point_at(sa, ra, sb, rb, now, m0)),
            kicks: [
                Event::new(now, sa.position_at(now)),
                Event::new(now, sb.position_at(now)),
            ],
            gamma_pair: ta.gamma().max(tb.gamma()),
            on_board: true,
            normal: overlap::contact_normal(sa, ra, sb, rb, now, (-s0, m0)),
            pair_frame: ProperVelocity::ZERO,
        });
    }
    // How far past `horizon` a contact can be whose kick is not.
    let beta = (speed_a(now).max(speed_b(now)) / c).min(1.0);
    let lead = 2.0 * beta * ra.max(rb) / (c * (1.0 - beta * beta));
    let cut = horizon + lead + 1e-9 * (horizon.abs() + lead);
    if end > from {
        let lip = speed_bound(sa, sb, from, end, c) * (1.0 + 1e-9)
            + SHAPE_RATE * (ra * sa.deceleration() + rb * sb.deceleration()) / c;
        // The probes' slopes and how fast they can change (isolation's
        // module doc). With both segments begun, a probe's rate is the
        // exact slope of the separation along its axis, supports included;
        // the slope's own rate is then bounded by the relative
        // acceleration (`a/γ³ ≤ a` each) plus the supports' curvature in
        // time, `R (a/c)² (1 + 0.385² γ)` each (from `|d(1/γ)/dt| ≤ 0.385
        // a/c`, `|d²(1/γ)/dt²| ≤ (a/c)²`, `∂h/∂(1/γ) ≤ R` and `∂²h/∂(1/γ)²
        // ≤ 0.385 R γ`; γ at most the segment's start value). A segment
        // that begins inside the window changes its supports' rate at
        // once there, so then the rate is the centres' part only and the
        // supports' change is bounded by the shape rate.
        let exact_slope = sa.start.t <= from && sb.start.t <= from;
        let accel = sa.deceleration() + sb.deceleration();
        let curvature = |s: &Segment, r: f64| {
            let k = s.deceleration() / c;
            r * k * k * (1.0 + 0.15 * s.u.gamma())
        };
        // The separation's rounding: the centres' offset is the difference
        // of two positions, each rounded to a few ulps of its size, and
        // the supports are the radii's size.
        let floor = 4.0
            * f64::EPSILON
            * (sa.position_at(from).length() + sb.position_at(from).length() + ra + rb);
        let rates = if exact_slope {
            Rates {
                lip,
                shape: 0.0,
                accel: (accel + curvature(sa, ra) + curvature(sb, rb)) * (1.0 + 1e-9),
                floor,
            }
        } else {
            Rates {
                lip,
                shape: SHAPE_RATE * (ra * sa.deceleration() + rb * sb.deceleration()) / c
                    * (1.0 + 1e-9),
                accel: accel * (1.0 + 1e-9),
                floor,
            }
        };
        // The first probe, at `now`, made already where it showed them
        // apart (then `from` is `now`).
        let probe = |t: f64| match first.take() {
            Some(p) if t == from => p,
            _ => probe_at(t, exact_slope),
        };
        if let Some(t) = first_contact_before(probe, from, end, rates, cut) {
            // The axis there, as the probes find it from `t` alone.
            let (a, b) = (motion_a.at(t, ra), motion_b.at(t, rb));
            let (_, m) = separation_near(&a.outline, &b.outline, b.position - a.position, None);
            // A braking puck that would stop within rounding of the touch
            // rests against the other: no event (no Zeno bounces).
            let left = |m: &Motion| {
                let s = m.segment;
                if s.is_braking() {
                    let law = &m.law;
                    law.stopping_distance() - law.distance_at(t - s.start.t)
                } else if s.is_rest() {
                    0.0
                } else {
                    f64::INFINITY
                }
            };
            let scale = 1e-12 * (ra + rb) + 1e-15 * sa.position_at(t).length();
            if closing(t, m) && left(&motion_a).max(left(&motion_b)) > scale {
                let point =
                    overlap::contact_point(&a.outline, &b.outline, a.position, b.position, m);
                return Some(in_pair_frame(&motion_a, &motion_b, Event::new(t, point), c));
            }
            // Touching without closing: comes to rest against it. Nothing
            // later on this window either (the braking puck stops there).
            return None;
        }
    }
    // Both at rest, or what still moves moves uniformly: the closed form
    // (whose contact and kicks, from `end` on, are past a horizon before
    // it).
    if end > cut {
        return None;
    }
    let (ta, tb) = (sa.tangent_at(end), sb.tangent_at(end));
    // A braking segment stopped by `end` is at rest there, though its
    // tangent's proper speed, worked out at the stop, can be a rounding
    // above zero (two stopped pucks were found to meet 10¹⁵ s later).
    let stopped = |s: &Segment, tangent: &Segment| {
        tangent.is_rest() || s.stop_time().is_some_and(|stop| stop <= end)
    };
    if stopped(sa, &ta) && stopped(sb, &tb) {
        return None;
    }
    puck_puck::predict(
        Mover {
            segment: &ta,
            radius: ra,
        },
        Mover {
            segment: &tb,
            radius: rb,
        },
        c,
        end,
    )
}

/// The board time at which the centre of a puck on the braking `segment`
/// leaves the disc of radius `margin` about `shell` (∞ if it stops inside),
/// from `now` on: the line meets the circle at a path length found by a
/// stable quadratic, and the braking law is inverted in closed form,
/// `t(s) = (s/c)(2γ₀ − s a/c²)/(u₀ + u(s))`, `u(s)² = (γ₀ − s a/c²)² − 1`.
#[must_use]
pub fn shell_exit(segment: &Segment, shell: DVec2, margin: f64, now: f64) -> f64 {
    let Some(stop) = segment.stop_time() else {
        return f64::INFINITY;
    };
    if now >= stop {
        return f64::INFINITY;
    }
    let d = segment.position_at(now).truncate() - shell;
    let q = d.length_squared() - margin * margin;
    if q >= 0.0 {
        return now;
    }
    let n = segment.direction().truncate();
    let nn = n.length_squared();
    let p = d.dot(n);
    let root = (p * p - nn * q).sqrt();
    let sigma = if p >= 0.0 {
        -q / (p + root)
    } else {
        (root - p) / nn
    };
    let law = segment.braking_law();
    let s = law.distance_at(now - segment.start.t) + sigma;
    if s >= law.stopping_distance() {
        return f64::INFINITY;
    }
    let c = law.c;
    let x = s * law.deceleration / (c * c);
    let g = law.gamma0() - x;
    let u = ((g - 1.0) * (g + 1.0)).max(0.0).sqrt();
    let t = (s / c) * (2.0 * law.gamma0() - x) / (law.u0 + u);
    (segment.start.t + t).max(now)
}

#[cfg(test)]
#[path = "braking_tests.rs"]
mod tests;
