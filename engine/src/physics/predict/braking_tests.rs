//! The braking predictions checked against closed forms, dense
//! bisections and the plain Lipschitz bound (`super` is
//! `physics::predict::braking`).

use super::*;
use crate::spacetime::{Boost, FourVector};
use crate::worldline::Worldline;

const C: f64 = 1.42;
const R: f64 = 0.0305;
const TABLE: DVec2 = DVec2::new(2.84, 1.42);

/// A puck of radius [`R`] on `segment`.
fn mover(segment: &Segment) -> Mover<'_> {
    Mover { segment, radius: R }
}

fn braking(x: f64, y: f64, u: DVec3, a: f64) -> Worldline {
    Worldline::braking(
        Event::new(0.0, DVec3::new(x, y, 0.0)),
        ProperVelocity(u),
        C,
        a,
    )
}

#[test]
fn cushion_contact_head_on_matches_the_closed_form() {
    // Along x towards x1: the front at x0 + s(t) + R/γ(t) reaches W.
    // s(t) + R/γ(t) = W − x0 solved independently by bisection on the
    // closed forms of sliding.rs (distance, γ).
    for (u0, a) in [(0.3, 1.962), (3.0, 1.962), (300.0, 0.5), (1e4, 1.0)] {
        let x0 = 1.0;
        let w = braking(x0, 0.7, DVec3::new(u0, 0.0, 0.0), a);
        let s = w.last();
        let law = s.braking_law();
        let target = TABLE.x - x0;
        let reach = |t: f64| law.distance_at(t) + R / law.gamma_at(t) - target;
        if reach(law.stop_time()) < 0.0 {
            assert!(cushion(s, R, TABLE, Cushion::X1, 0.0).is_none(), "{u0}");
            continue;
        }
        let (mut lo, mut hi) = (0.0, law.stop_time());
        for _ in 0..300 {
            let mid = 0.5 * (lo + hi);
            if reach(mid) < 0.0 { lo = mid } else { hi = mid }
        }
        let hit = cushion(s, R, TABLE, Cushion::X1, 0.0).expect("reaches the cushion");
        assert!((hit.t - hi).abs() <= 1e-12 * hi, "{u0}: {} vs {hi}", hit.t);
        assert!((hit.point.x - TABLE.x).abs() < 1e-12);
        assert!(cushion(s, R, TABLE, Cushion::X0, 0.0).is_none());
    }
}

#[test]
fn a_puck_that_stops_short_or_against_a_cushion_never_meets_it() {
    // u₀ small: stops after (c²/a)(γ₀ − 1) ≈ 0.0257 m.
    let a = 1.962;
    let w = braking(1.0, 0.7, DVec3::new(0.1, 0.0, 0.0), a);
    let stop = w.last().braking_law().stopping_distance();
    // A table whose cushion is exactly where it stops.
    let table = DVec2::new(1.0 + stop + R, 1.42);
    assert!(cushion(w.last(), R, table, Cushion::X1, 0.0).is_none());
    let table = DVec2::new(1.0 + stop + R + 1e-6, 1.42);
    assert!(cushion(w.last(), R, table, Cushion::X1, 0.0).is_none());
    let table = DVec2::new(1.0 + stop + R - 1e-6, 1.42);
    assert!(cushion(w.last(), R, table, Cushion::X1, 0.0).is_some());
}

/// The exact separation, sampled densely and bisected: the reference.
fn reference_pair(a: &Segment, b: &Segment, end: f64) -> Option<f64> {
    let sep = |t: f64| separation(a, R, b, R, t).0;
    let n = 20_000;
    let mut prev = 0.0;
    for k in 1..=n {
        let t = end * k as f64 / n as f64;
        if sep(t) <= 0.0 {
            let (mut lo, mut hi) = (prev, t);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if sep(mid) > 0.0 { lo = mid } else { hi = mid }
            }
            return Some(hi);
        }
        prev = t;
    }
    None
}

#[test]
fn pair_contact_on_braking_worldlines_matches_a_bisection_on_the_gap() {
    let a_dec = 1.962;
    let mut checked = 0;
    for (ua, ub, pb) in [
        (
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::ZERO,
            DVec3::new(1.8, 0.7, 0.0),
        ),
        (
            DVec3::new(2.0, 0.3, 0.0),
            DVec3::new(-0.5, 0.0, 0.0),
            DVec3::new(1.6, 0.75, 0.0),
        ),
        (
            DVec3::new(20.0, 0.0, 0.0),
            DVec3::new(-3.0, 1.0, 0.0),
            DVec3::new(2.2, 0.62, 0.0),
        ),
        (
            DVec3::new(0.8, 0.8, 0.0),
            DVec3::new(0.0, -0.4, 0.0),
            DVec3::new(1.4, 1.1, 0.0),
        ),
    ] {
        let wa = braking(1.0, 0.7, ua, a_dec);
        let wb = braking(pb.x, pb.y, ub, a_dec);
        let (sa, sb) = (wa.last(), wb.last());
        let end = sa.stop_time().unwrap().max(sb.stop_time().unwrap_or(0.0));
        let ours = pair(mover(sa), mover(sb), C, 0.0);
        let reference = reference_pair(sa, sb, end);
        match (ours, reference) {
            (Some(hit), Some(t)) => {
                assert!(
                    (hit.contact.t - t).abs() <= 1e-12 * t,
                    "{ua}: {} vs {t}",
                    hit.contact.t
                );
                checked += 1;
            }
            (None, None) => {}
            (x, y) => panic!("{ua}: {x:?} vs {y:?}"),
        }
    }
    assert!(checked >= 3, "{checked}");
}

/// Pucks braking nearly together (the clusters of a gas on the cloth at
/// restitution 0): relative proper velocities 10⁻⁹ to 10⁻¹ of a speed
/// up to γβ = 3, closing or opening at any angle, decelerations equal
/// or up to 5 % apart, 0 to 3 mm apart. The contact found with the
/// relative-speed bound is the one found with the plain sum of the
/// speeds (a bound that needs no argument: the centres' offset changes
/// no faster), to 1e-12 s, and where one finds none the other finds
/// none. Where the sum's search gives up (its 200 000 evaluations, so
/// it says none) and ours finds one, ours is checked to be the first
/// touch on a grid of 2 000 times before it. The bound is checked to be
/// well below the sum for most pairs (else the test would not test it).
#[test]
fn the_relative_speed_bound_finds_the_contacts_the_sum_of_speeds_finds() {
    let sum: SpeedBound = |sa, sb, from, _, _| speed_at(sa, from) + speed_at(sb, from);
    let mut rng = crate::physics::gas::Rng::new(0x2545_f491_4f6c_dd1d);
    let mut next = move || rng.next_f64();
    let (mut met, mut apart, mut hard, mut tighter) = (0, 0, 0, 0);
    for _ in 0..600 {
        let speed = 3.0 * next();
        let heading = std::f64::consts::TAU * next();
        let u = DVec3::new(heading.cos(), heading.sin(), 0.0) * speed;
        let rel = 10f64.powf(-9.0 + 8.0 * next()) * speed.max(1e-3);
        let turn = std::f64::consts::TAU * next();
        let du = DVec3::new(turn.cos(), turn.sin(), 0.0) * rel;
        let side = std::f64::consts::TAU * next();
        let offset = DVec3::new(side.cos(), side.sin(), 0.0) * (2.0 * R + 3e-3 * next());
        let dec = 1.962;
        let dec_b = if next() < 0.5 {
            dec
        } else {
            dec * (1.0 + 0.05 * next())
        };
        let wa = braking(1.0, 0.7, u, dec);
        let wb = braking(1.0 + offset.x, 0.7 + offset.y, u + du, dec_b);
        let (ma, mb) = (mover(wa.last()), mover(wb.last()));
        if separation(wa.last(), R, wb.last(), R, 0.0).0 <= 0.0 {
            continue;
        }
        let reference = pair_with_bound(ma, mb, C, 0.0, f64::INFINITY, sum);
        let ours = pair_with_bound(ma, mb, C, 0.0, f64::INFINITY, relative_speed_bound);
        let end = wa
            .last()
            .stop_time()
            .unwrap_or(0.0)
            .max(wb.last().stop_time().unwrap_or(0.0));
        if relative_speed_bound(wa.last(), wb.last(), 0.0, end, C)
            < 0.1 * sum(wa.last(), wb.last(), 0.0, end, C)
        {
            tighter += 1;
        }
        match (ours, reference) {
            (Some(x), Some(y)) => {
                assert!(
                    (x.contact.t - y.contact.t).abs() <= 1e-12 * y.contact.t.max(1e-3),
                    "{u} {du}: {} vs {}",
                    x.contact.t,
                    y.contact.t
                );
                met += 1;
            }
            (None, None) => apart += 1,
            (Some(x), None) => {
                // The sum's search ran out of evaluations (it returns
                // `None` then): ours must be the first touch.
                hard += 1;
                let sep = |t: f64| separation(wa.last(), R, wb.last(), R, t).0;
                assert!(sep(x.contact.t) <= 0.0);
                assert!((0..2000).all(|k| sep(x.contact.t * f64::from(k) / 2000.0) > 0.0));
            }
            (None, Some(y)) => panic!("{u} {du}: missed the contact at {}", y.contact.t),
        }
    }
    assert!(
        met > 50 && apart > 50 && tighter > 300,
        "{met} met, {apart} apart, {hard} hard, {tighter} with a bound under 0.1 of the sum"
    );
    eprintln!(
        "{met} met, {apart} apart, {hard} beyond the sum's search, {tighter} with a bound \
         under 0.1 of the sum"
    );
}

#[test]
fn a_braking_pair_before_a_horizon_is_the_same_contact_to_the_bit() {
    // Random braking pairs near each other (proper speeds to 20, γ to
    // 20, so kicks can precede their contact by several R/c): every
    // horizon at or after the contact's first kick gives the very
    // contact of the full search; an earlier one gives it or nothing.
    let mut rng = crate::physics::gas::Rng::new(0x9e37_79b9_7f4a_7c15);
    let mut next = move || rng.next_f64();
    let (mut kept, mut cut) = (0, 0);
    for _ in 0..4000 {
        let speed = if next() < 0.5 { 3.0 } else { 20.0 };
        let mut u = || DVec3::new(next() - 0.5, next() - 0.5, 0.0) * 2.0 * speed;
        let (ua, ub) = (u(), u());
        let (x, y) = (0.1 * next(), 0.1 * next());
        let wa = braking(1.0, 0.7, ua, 1.962);
        let wb = braking(1.0 + 0.07 + x, 0.7 + y, ub, 1.962);
        let (a, b) = (mover(wa.last()), mover(wb.last()));
        let full = pair(a, b, C, 0.0);
        let first = full.map(|h| h.kicks[0].t.min(h.kicks[1].t).min(h.contact.t));
        for horizon in [0.0, 1e-3, 0.01, 0.03, 0.1, 0.3, 1.0, 3.0, f64::INFINITY] {
            let ours = pair_before(a, b, C, 0.0, horizon);
            match first {
                Some(first) if first <= horizon => {
                    assert_eq!(ours, full, "{ua} {ub} at {horizon}");
                    kept += 1;
                }
                _ => {
                    assert!(ours.is_none() || ours == full, "{ua} {ub} at {horizon}");
                    cut += usize::from(ours.is_none() && full.is_some());
                }
            }
        }
        if let Some(first) = first {
            assert_eq!(pair_before(a, b, C, 0.0, first), full);
        }
    }
    assert!(kept > 1300 && cut > 30, "{kept} kept, {cut} cut");
}

#[test]
fn kicks_are_simultaneous_with_the_contact_in_the_pair_frame() {
    let wa = braking(1.0, 0.7, DVec3::new(5.0, 0.4, 0.0), 1.962);
    let wb = braking(2.0, 0.75, DVec3::new(-1.0, 0.0, 0.0), 1.962);
    let hit = pair(mover(wa.last()), mover(wb.last()), C, 0.0).expect("they meet");
    let to_pair = Boost::into_frame(hit.pair_frame);
    let time = |e: Event| to_pair.apply(FourVector::new(C * e.t, e.position)).ct;
    let tc = time(hit.contact);
    for k in hit.kicks {
        assert!(
            (time(k) - tc).abs() < 1e-12 * tc.abs(),
            "{} vs {tc}",
            time(k)
        );
    }
    // The pair frame is that of the velocities at the kicks: equal and
    // opposite there.
    let ua = to_pair.apply_velocity(wa.proper_velocity_at(hit.kicks[0].t));
    let ub = to_pair.apply_velocity(wb.proper_velocity_at(hit.kicks[1].t));
    assert!(
        (ua.0 + ub.0).length() < 1e-12 * ua.0.length(),
        "{ua:?} {ub:?}"
    );
}

/// The Illinois root keeps bisection's contract (adjacent floats, `f`
/// ≤ 0 at the answer and > 0 just before) on smooth, flat, steep and
/// stepped decreasing functions, and never takes much more than twice
/// bisection's evaluations.
#[test]
fn bisect_ends_at_adjacent_floats_within_twice_the_bisection_count() {
    type Case = (Box<dyn Fn(f64) -> f64>, f64, f64);
    let cases: Vec<Case> = vec![
        (Box::new(|t: f64| 0.7 - t), 0.0, 3.0),
        (Box::new(|t: f64| (1.3 - t).powi(3)), 0.0, 2.0),
        (Box::new(|t: f64| (-50.0 * t).exp() - 1e-10), 0.0, 1.0),
        (
            Box::new(|t: f64| if t < 0.25 { 1.0 } else { -1.0 }),
            0.0,
            1.0,
        ),
        (
            Box::new(|t: f64| 2.0 * (1.0 - t).atan() + 1e-3 * (1.0 - t)),
            -5.0,
            40.0,
        ),
        (Box::new(|t: f64| 1e-300 * (0.1 - t)), 0.0, 1.0),
    ];
    for (k, (f, lo, hi)) in cases.iter().enumerate() {
        let count = std::cell::Cell::new(0usize);
        let counted = |t: f64| {
            count.set(count.get() + 1);
            f(t)
        };
        let root = bisect(counted, *lo, *hi);
        assert!(
            f(root) <= 0.0 && f(root.next_down()) > 0.0,
            "case {k}: {root}"
        );
        assert!(
            count.get() <= 2 * 64 + 4,
            "case {k}: {} evaluations",
            count.get()
        );
    }
}

#[test]
fn shell_exit_inverts_the_braking_law() {
    let w = braking(1.0, 0.7, DVec3::new(2.0, 1.0, 0.0), 1.962);
    let s = w.last();
    let shell = DVec2::new(1.0, 0.7);
    let t = shell_exit(s, shell, 0.05, 0.0);
    assert!(t.is_finite() && t > 0.0);
    let r = (s.position_at(t).truncate() - shell).length();
    assert!((r - 0.05).abs() < 1e-13, "{r}");
    // A margin beyond the stopping point: never.
    assert_eq!(shell_exit(s, shell, 10.0, 0.0), f64::INFINITY);
}
