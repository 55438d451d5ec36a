//! The emission event, exactly: on a piecewise-linear worldline, a binary
//! search over segments, then a stable closed-form root.
//!
//! A vertex rigidly attached to a body at rest-frame offset `r` moves, on
//! segment `k`, as `x(t) = cₖ(t) + rₖ` with `cₖ` the centre's straight line
//! and `rₖ` the offset placed by the body's shape on that segment (its
//! [`SegmentShape`]: contracted along the segment's velocity, or the rest
//! shape; the kernels take the shape as data, [`ShapeMaps`]). Its light
//! reaches the observation event `(t₀, x₀)` from the event at look-back
//! time `τ` where `|x₀ − x(t₀ − τ)| = c τ`:
//!
//! ```text
//! (c² − v²) τ² − 2 (d·v) τ − |d|² = 0,   d = x₀ − x(t₀) (extrapolated on the segment)
//! ```
//!
//! with `c² − v² = c²/γ²` exact, solved in its cancellation-free form.
//! `f(t) = c (t₀ − t) − |x₀ − x(t)|` decreases along a worldline, so the
//! segment holding the root is the last one whose start has `f ≥ 0`
//! (found for the body's centre by a search galloping back from the newest
//! segment, O(log m) for m segments back; then a walk of usually zero
//! steps for the point). At a kink the contracted offset jumps; if the
//! jump carries the vertex across the light cone the emission is taken at
//! the kink (where jumps at kinks close together make the point's test
//! change sign more than once, the crossing nearest the centre's).
//!
//! On a **braking** segment (sliding friction) every material point of the
//! Born-rigid body moves on a braking hyperbola of its own
//! ([`crate::worldline::sliding::Braking::material_point`]), and its
//! emission event is the intersection of the past light cone with that
//! hyperbola, a stable quadratic
//! ([`crate::worldline::sliding::Braking::emission_time`]); after the stop
//! the point rests.

use glam::DVec3;

use crate::spacetime::{Event, ProperVelocity};
use crate::worldline::{Segment, SegmentShape, ShapeMaps, Worldline};

/// Where and how fast a point was when it emitted the light seen. (One is
/// written for every vertex of every view each frame, so it holds only
/// what the later effects read: 56 bytes.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Emission {
    /// The emission event, board frame.
    pub event: Event,
    /// The emitter's proper velocity then (for the Doppler factor).
    pub u: ProperVelocity,
}

/// The vertex's position at the start of segment `s`, of shape `shape`.
#[inline]
fn start_position(s: &Segment, shape: SegmentShape, offset: DVec3) -> DVec3 {
    s.start.position + shape.place(s, s.start.t, offset)
}

/// `f` at the start of segment `k`: ≥ 0 when that event is in (or on) the
/// observation's past light cone.
#[inline]
fn in_past_cone(
    segments: &[Segment],
    k: usize,
    shapes: &impl ShapeMaps,
    offset: DVec3,
    observation: Event,
    c: f64,
) -> bool {
    let s = &segments[k];
    let a = start_position(s, shapes.on_segment(k, s), offset);
    c * (observation.t - s.start.t) >= (observation.position - a).length()
}

/// Index of the segment holding the emission for a point at `offset`
/// (rest frame, from the reference point) of a body of shape `shapes`:
/// the newest segment whose start (with its shape) is in the
/// observation's past light cone, or 0 if none is. O(log m) for an
/// emission `m` segments before the newest.
///
/// The search gallops back from the newest segment (1, 2, 4, … back),
/// then bisects between the last two probes: an observation usually sees
/// a body's recent past, so the probes stay among the newest segments
/// (in cache, where a bisection of the whole worldline would read old
/// ones from memory), and a body that has not changed since its light
/// left is found at the first probe. Where the cone test is monotone
/// along the worldline (inside before the crossing, outside after) this
/// is the crossing, as any search finds it; where a kink's jump in the
/// contracted offset makes it change sign more than once within that
/// jump, the segment is one of the crossings.
pub fn segment_index(
    worldline: &Worldline,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    observation: Event,
) -> usize {
    let c = worldline.speed_of_light();
    let segments = worldline.segments();
    // The reference point itself (offset zero, the usual case) needs no
    // shape: every shape places it at the centre.
    let inside = |k: usize| {
        if offset == DVec3::ZERO {
            let s = &segments[k];
            c * (observation.t - s.start.t) >= (observation.position - s.start.position).length()
        } else {
            in_past_cone(segments, k, shapes, offset, observation, c)
        }
    };
    let n = segments.len();
    if n == 0 {
        return 0;
    }
    // Every probe at or after `hi` was outside (`hi = n`: none yet).
    let mut hi = n;
    let mut back = 1;
    let mut lo = loop {
        let k = n.saturating_sub(back);
        if inside(k) {
            break k;
        }
        if k == 0 {
            return 0;
        }
        hi = k;
        back *= 2;
    };
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if inside(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

/// Moves a segment index found for a nearby point (the body's centre) to
/// the one for this point: the vertices of a body share the search, and
/// this walk is usually zero or one step.
pub fn refine_index(
    worldline: &Worldline,
    mut k: usize,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    observation: Event,
) -> usize {
    let c = worldline.speed_of_light();
    let segments = worldline.segments();
    while k > 0 && !in_past_cone(segments, k, shapes, offset, observation, c) {
        k -= 1;
    }
    while k + 1 < segments.len() && in_past_cone(segments, k + 1, shapes, offset, observation, c) {
        k += 1;
    }
    k
}

/// The emission event on segment `k` (see the module doc).
pub fn solve_on_segment(
    worldline: &Worldline,
    k: usize,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    observation: Event,
) -> Emission {
    let segments = worldline.segments();
    let s = &segments[k];
    let c = worldline.speed_of_light();
    let shape = shapes.on_segment(k, s);
    if s.is_braking() {
        return solve_on_braking(worldline, k, offset, shape, observation);
    }
    let a = start_position(s, shape, offset);
    let v = s.velocity();
    let since_start = observation.t - s.start.t;
    let d = observation.position - (a + v * since_start);
    let tau = light_catch_up(d, v, c, s.gamma());
    let mut dt = since_start - tau; // emission time relative to the segment start
    if k > 0 {
        dt = dt.max(0.0);
    }
    if let Some(next) = segments.get(k + 1) {
        dt = dt.min(next.start.t - s.start.t);
    }
    Emission {
        event: Event::new(s.start.t + dt, a + v * dt),
        u: s.u,
    }
}

/// [`solve_on_segment`] on a braking segment: the point's own braking
/// hyperbola (Born-rigid body, [`SegmentShape::BornRigid`]; otherwise the
/// centre's, shifted by the point's fixed offset), its emission in closed
/// form; uniform backwards before the first segment's start, at rest after
/// the stop.
fn solve_on_braking(
    worldline: &Worldline,
    k: usize,
    offset: DVec3,
    shape: SegmentShape,
    observation: Event,
) -> Emission {
    let segments = worldline.segments();
    let s = &segments[k];
    let c = worldline.speed_of_light();
    let n = s.direction();
    let centre = s.braking_law();
    let fixed = || (start_position(s, shape, offset), centre);
    let (start, law) = match shape {
        SegmentShape::BornRigid => {
            let r = s.rotate(offset);
            let along = n.dot(r);
            let across = r - n * along;
            match centre.material_point(along) {
                Ok((off0, law)) => (s.start.position + across + n * off0, law),
                Err(_) => fixed(),
            }
        }
        SegmentShape::Rest | SegmentShape::Lorentz(_) => fixed(),
    };
    let t_obs = observation.t - s.start.t;
    let end = segments
        .get(k + 1)
        .map_or(f64::INFINITY, |next| next.start.t - s.start.t);
    let at = |dt: f64| {
        let dt = dt.min(end);
        Emission {
            event: Event::new(s.start.t + dt, start + n * law.distance_at(dt)),
            u: ProperVelocity(n * law.proper_speed_at(dt)),
        }
    };
    if let Some(dt) = law.emission_time(start, n, observation.position, t_obs) {
        return at(dt);
    }
    // Not on the hyperbola: before the start, or after the stop.
    if c * t_obs < (observation.position - start).length() {
        if k > 0 {
            return at(0.0);
        }
        // Before the first segment: its start motion extends back.
        let v = s.velocity();
        let d = observation.position - (start + v * t_obs);
        let dt = t_obs - light_catch_up(d, v, c, s.gamma());
        return Emission {
            event: Event::new(s.start.t + dt, start + v * dt),
            u: s.u,
        };
    }
    let rest = start + n * law.stopping_distance();
    let dt = t_obs - (observation.position - rest).length() / c;
    at(dt.max(law.stop_time()))
}

/// The emission event of the point at rest-frame `offset` from the
/// reference point of the body moving along `worldline` with the shape
/// `shapes`, for light reaching `observation`. Before the first segment the
/// body keeps its initial motion (the worldline's convention), so there is
/// always an answer.
pub fn solve(
    worldline: &Worldline,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    observation: Event,
) -> Emission {
    // The centre's segment, then the point's walk from it: the same
    // answer as [`super::batch::solve_body`] with the centre as reference, also where
    // the point's own cone test is not monotone (kinks close together).
    let k = segment_index(worldline, DVec3::ZERO, shapes, observation);
    let k = refine_index(worldline, k, offset, shapes, observation);
    solve_on_segment(worldline, k, offset, shapes, observation)
}

/// The board-frame-simultaneous "emission" (light delay off): the point of
/// the body of shape `shapes` where it is at the observation's board time.
pub fn simultaneous(
    worldline: &Worldline,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    t: f64,
) -> Emission {
    simultaneous_on(worldline, worldline.segment_index_at(t), offset, shapes, t)
}

/// [`simultaneous`] on segment `k`, the one in force at board time `t`
/// (`Worldline::segment_index_at`), found once for all of a body's points.
pub fn simultaneous_on(
    worldline: &Worldline,
    k: usize,
    offset: DVec3,
    shapes: &impl ShapeMaps,
    t: f64,
) -> Emission {
    let s = &worldline.segments()[k];
    Emission {
        event: Event::new(
            t,
            s.position_at(t) + shapes.on_segment(k, s).place(s, t, offset),
        ),
        u: s.u_at(t),
    }
}

/// Stable positive root `τ` of `(c² − v²) τ² − 2 (d·v) τ − |d|² = 0`: the
/// time light from the origin takes to reach a point that starts at `d` and
/// moves with velocity `v` (`|v| < c`).
#[must_use]
pub fn light_catch_up(d: DVec3, v: DVec3, c: f64, gamma: f64) -> f64 {
    let a = (c / gamma) * (c / gamma); // c² − v², exact via γ
    let dv = d.dot(v);
    let dd = d.length_squared();
    if dd == 0.0 {
        return 0.0;
    }
    let root = (dv * dv + a * dd).sqrt();
    if dv <= 0.0 {
        dd / (root - dv)
    } else {
        // As a product (the batched kernel divides once per segment).
        (dv + root) * (1.0 / a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worldline::ContractedShape;

    const C: f64 = 1.42;

    /// The galloping search finds what its definition says: the newest
    /// segment whose start is in the past light cone (0 if none), on
    /// worldlines of 1 to 2 000 segments seen from their start to long
    /// after their end. For the centre of a body moving slower than light
    /// the cone test is monotone along the worldline, so this is also the
    /// segment the bisection of the whole worldline found before.
    #[test]
    fn segment_search_finds_the_newest_segment_inside_the_cone() {
        let mut rng = crate::physics::gas::Rng::new(0x2545_F491_4F6C_DD1D);
        let mut next = move || rng.next_f64();
        for len in [1usize, 2, 3, 7, 40, 333, 2000] {
            let u = |x: f64, y: f64| ProperVelocity(DVec3::new(x, y, 0.0) * 3.0);
            let mut w = Worldline::new(Event::new(0.0, DVec3::new(1.0, 0.5, 0.0)), u(0.3, -0.2), C);
            let mut t = 0.0;
            for _ in 1..len {
                t += 0.001 + 0.05 * next();
                w.push(t, u(next() - 0.5, next() - 0.5)).unwrap();
            }
            let shapes = ContractedShape::of(&w);
            for _ in 0..200 {
                let eye = DVec3::new(4.0 * next() - 1.0, 4.0 * next() - 1.0, next());
                let observation = Event::new((t + 3.0) * next() - 0.5, eye);
                let inside = |k: usize| {
                    let s = &w.segments()[k];
                    C * (observation.t - s.start.t) >= (eye - s.start.position).length()
                };
                let newest = (0..w.segments().len())
                    .rev()
                    .find(|&k| inside(k))
                    .unwrap_or(0);
                // Monotone: inside up to it, outside after.
                assert!((0..=newest).all(inside) || newest == 0);
                assert_eq!(
                    segment_index(&w, DVec3::ZERO, &shapes, observation),
                    newest,
                    "{len} segments, {observation:?}"
                );
            }
        }
    }

    #[test]
    fn uniform_motion_closed_form_retarded_time() {
        // A point moving along x at v passes x = 0 at t = 0; an observer at
        // (0, h) at time t₀ sees it at the retarded time t_r, the earlier
        // root of c²(t₀ − t)² = (v t)² + h² (textbook quadratic formula).
        let beta = 0.8;
        let u = ProperVelocity::try_from_beta(DVec3::new(beta, 0.0, 0.0)).unwrap();
        let w = Worldline::new(Event::new(0.0, DVec3::ZERO), u, C);
        for (t0, h) in [(1.0, 0.5), (3.0, 2.0), (-2.0, 0.1), (0.0, 1.0)] {
            let e = solve(
                &w,
                DVec3::ZERO,
                &ContractedShape::of(&w),
                Event::new(t0, DVec3::new(0.0, h, 0.0)),
            );
            // (c² − v²) t² − 2 c² t₀ t + c² t₀² − h² = 0, earlier root.
            let v = beta * C;
            let (a, b, cc) = (C * C - v * v, -2.0 * C * C * t0, C * C * t0 * t0 - h * h);
            let t_r = (-b - (b * b - 4.0 * a * cc).sqrt()) / (2.0 * a);
            assert!(
                (e.event.t - t_r).abs() < 1e-12,
                "{t0} {h}: {} vs {t_r}",
                e.event.t
            );
            let dist = (e.event.position - DVec3::new(0.0, h, 0.0)).length();
            assert!((dist - C * (t0 - e.event.t)).abs() < 1e-12);
        }
    }

    #[test]
    fn across_a_kink_the_emission_is_continuous_for_the_centre() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.6, 0.0, 0.0)).unwrap();
        let mut w = Worldline::new(Event::new(0.0, DVec3::new(1.0, 0.5, 0.0)), u, C);
        w.push(
            1.0,
            ProperVelocity::try_from_beta(DVec3::new(-0.3, 0.4, 0.0)).unwrap(),
        )
        .unwrap();
        let eye = DVec3::new(0.5, -1.0, 0.8);
        let mut last: Option<Emission> = None;
        for i in 0..400 {
            let t0 = 0.5 + 0.01 * f64::from(i);
            let e = solve(
                &w,
                DVec3::ZERO,
                &ContractedShape::of(&w),
                Event::new(t0, eye),
            );
            // On the cone, on the worldline.
            assert!((C * (t0 - e.event.t) - (eye - e.event.position).length()).abs() < 1e-12);
            assert!((w.position_at(e.event.t) - e.event.position).length() < 1e-12);
            if let Some(l) = last {
                assert!(e.event.t > l.event.t && e.event.t - l.event.t < 0.02);
            }
            last = Some(e);
        }
    }

    #[test]
    fn before_the_first_event_the_initial_motion_extends_back() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.5, 0.0, 0.0)).unwrap();
        let w = Worldline::new(Event::new(10.0, DVec3::new(1.0, 0.0, 0.0)), u, C);
        let e = solve(
            &w,
            DVec3::ZERO,
            &ContractedShape::of(&w),
            Event::new(0.0, DVec3::new(1.0, 1.0, 0.0)),
        );
        assert!(e.event.t < 0.0);
        assert!((w.position_at(e.event.t) - e.event.position).length() < 1e-12);
    }

    #[test]
    fn shared_search_matches_independent_search() {
        let mut w = Worldline::new(
            Event::new(0.0, DVec3::new(0.2, 0.5, 0.0)),
            ProperVelocity(DVec3::new(2.0, 0.3, 0.0)),
            C,
        );
        for k in 1..50 {
            let u = ProperVelocity(DVec3::new(if k % 2 == 0 { 2.0 } else { -2.0 }, 0.3, 0.0));
            w.push(0.1 * f64::from(k), u).unwrap();
        }
        let offsets: Vec<DVec3> = (0..16)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / 16.0;
                DVec3::new(a.cos(), a.sin(), 0.5) * 0.03
            })
            .collect();
        let obs = Event::new(3.7, DVec3::new(1.0, -1.0, 0.5));
        let mut shared = Vec::new();
        let shapes = ContractedShape::of(&w);
        crate::optics::batch::solve_body(&w, &offsets, DVec3::ZERO, &shapes, obs, &mut shared);
        for (r, e) in offsets.iter().zip(&shared) {
            assert_eq!(*e, solve(&w, *r, &shapes, obs));
        }
    }

    #[test]
    fn on_a_braking_worldline_the_emission_is_on_the_cone_and_the_body() {
        // A puck braking to rest (μg = 1.5 m/s², c = 1.42 m/s), then resting
        // (explicit rest segment). For the centre and rim points, at times
        // before, during and after the stop, the emission event lies on the
        // observation's past light cone (1e-12) and on the point's own
        // worldline: the centre's plus the Born-rigid offset then (1e-12).
        let u = ProperVelocity(DVec3::new(2.0, 0.8, 0.0));
        let mut w = Worldline::braking(Event::new(0.0, DVec3::new(0.4, 0.3, 0.0)), u, C, 1.5);
        let stop = w.come_to_rest().unwrap();
        let shapes = ContractedShape::of(&w);
        let eye = DVec3::new(1.2, -1.0, 0.7);
        let mut last_t = f64::NEG_INFINITY;
        for i in 0..300 {
            let t0 = 0.5 + 0.02 * f64::from(i);
            for r in [
                DVec3::ZERO,
                DVec3::new(0.03, 0.0, 0.0),
                DVec3::new(-0.02, 0.02, 0.01),
            ] {
                let e = solve(&w, r, &shapes, Event::new(t0, eye));
                let on_cone = C * (t0 - e.event.t) - (eye - e.event.position).length();
                assert!(on_cone.abs() < 1e-12, "{t0} {r}: {on_cone}");
                let s = w.segment_at(e.event.t);
                let body = w.position_at(e.event.t) + s.place_at(e.event.t, r);
                assert!(
                    (body - e.event.position).length() < 1e-12,
                    "{t0} {r}: {body} vs {}",
                    e.event.position
                );
                if r == DVec3::ZERO {
                    assert!(e.event.t >= last_t);
                    last_t = e.event.t;
                    // Proper velocity then: the braking law's.
                    let expect = w.proper_velocity_at(e.event.t);
                    assert!((e.u.0 - expect.0).length() < 1e-12);
                }
            }
        }
        assert!(last_t > stop, "the run should see the puck at rest");
    }
}
