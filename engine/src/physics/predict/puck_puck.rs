//! When and where two moving (contracted) pucks meet: the paper's Appendix,
//! Eq. 3–6, generalised to unequal radii and masses.
//!
//! In the board frame two contracted pucks are ellipses of different shapes
//! and their contact is a quartic. In the frame where the two pucks move
//! with equal and opposite speeds, the *pair frame*, both are contracted by
//! the same `1/γ'` along the same line, so they are similar ellipses; the
//! contact is where their centres' separation meets the ellipse of semi-axes
//! `S/γ'` and `S` (`S = R₁ + R₂`), and that is a quadratic. The pair frame
//! moves with the normalised sum of the two 4-velocities, `(u₁ + u₂)/√(2 +
//! 2γ_rel)`; for equal masses it is the paper's centre-of-momentum frame
//! (Eq. 3), and Eq. 5–6 are what this reduces to:
//!
//! ```text
//! d_min = √(S² − b²) / γ'        Δt' = (D∥ − d_min) / (2 v')
//! ```
//!
//! The contact point divides the line of centres in the ratio `R₁ : R₂`
//! (the two ellipses are similar); the contact normal is the gradient of the
//! summed ellipse there.
//!
//! **When the velocities change.** Each puck's velocity changes at the
//! event on its centre's worldline that is *simultaneous with the contact in
//! the pair frame*: both kicks happen at the contact's pair-frame time, at
//! the two centres. In the pair frame the bodies are then exactly touching
//! and both change at once, so neither moves into the other after the
//! contact. (The paper's Appendix instead waits for light from the contact
//! to reach each centre; at high γ that delay, about γR/2c, lets the rigid
//! shapes pass through each other, and the pair is found "colliding" again
//! and again. See the guide, docs/guide/src/collisions.md.) In the board frame
//! the two kicks are `γ_f (v_f·Δx′)/c²` apart in time (`Δx′` the centres'
//! separation in the pair frame); the contact lies between them.

use glam::DVec3;

use crate::spacetime::{Boost, Event, FourVector, ProperVelocity};
use crate::worldline::Segment;

/// A puck in uniform motion: the segment it is on and its rest radius.
#[derive(Clone, Copy, Debug)]
pub struct Mover<'a> {
    /// Current worldline segment (board frame).
    pub segment: &'a Segment,
    /// Rest-frame radius, m.
    pub radius: f64,
}

/// A predicted puck–puck contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairContact {
    /// The contact event, board frame.
    pub contact: Event,
    /// For each puck, the event at its centre where its velocity changes:
    /// simultaneous with the contact in the pair frame. In the board frame
    /// the contact's time lies between the two kicks' times.
    pub kicks: [Event; 2],
    /// Each puck's Lorentz factor in the pair frame before the contact
    /// (the two are equal there).
    pub gamma_pair: f64,
    /// A contact found on the board rather than in the pair frame (see
    /// `Billiard`): `normal` is then a board-frame direction and both kicks
    /// are at the contact's board time.
    pub on_board: bool,
    /// Unit contact normal from the first puck towards the second, in the
    /// pair frame (spatial).
    pub normal: DVec3,
    /// Proper velocity of the pair frame relative to the board.
    pub pair_frame: ProperVelocity,
}

/// The next contact of two pucks, whose contact event lies at board time
/// ≥ `now`; `None` if they miss, move apart, or have no relative motion.
///
/// Pucks already overlapping at `now` (a contact that rounding or another
/// collision's light delay placed in the past) and still approaching meet
/// at once: the contact is placed at board time `now`.
///
/// Precision: positions are taken relative to the first puck's centre at
/// `now` and times relative to `now` before any boost, so digits are lost
/// only to the pair frame's own γ (a few ε γ_f² of the separation).
#[must_use]
pub fn predict(a: Mover, b: Mover, c: f64, now: f64) -> Option<PairContact> {
    let (ua, ub) = (a.segment.u, b.segment.u);
    let origin = Event::new(now, a.segment.position_at(now));
    let separation = b.segment.position_at(now) - origin.position;
    let reach = a.radius + b.radius;

    // Cheap board-frame rejection. At the contact's board time both
    // contracted shapes contain the contact point, and each lies inside its
    // rest-radius disc, so the centres are then at most R₁ + R₂ apart. If the
    // centres' closest approach from now on is farther, there is no contact.
    let closing = b.segment.velocity() - a.segment.velocity();
    let approach = separation.dot(closing);
    let closest_sq = if approach < 0.0 {
        let cc = closing.length_squared();
        (separation - closing * (approach / cc)).length_squared()
    } else {
        separation.length_squared()
    };
    if closest_sq > reach * reach * (1.0 + 1e-9) {
        return None;
    }

    // Pair frame: normalised sum of the 4-velocities.
    let gamma_rel = Boost::into_frame(ua).apply_velocity(ub).gamma();
    let pair_frame = ProperVelocity((ua.0 + ub.0) / (2.0 + 2.0 * gamma_rel).sqrt());
    let to_pair = Boost::into_frame(pair_frame);
    // Equal and opposite there; symmetrise away the rounding.
    let w = 0.5 * (to_pair.apply_velocity(ua).0 - to_pair.apply_velocity(ub).0);
    let w_len = w.length();
    if w_len == 0.0 {
        return None;
    }
    let n = w / w_len;
    let gamma = 1.0f64.hypot(w_len);
    let v = c * w_len / gamma; // each puck's speed in the pair frame, m/s

    // In the pair frame A is at the origin at t' = 0 and moves +n; B passes
    // through its `now` event and moves −n. r(t') = r0 − 2 v n t'.
    let b0 = to_pair.apply(FourVector::new(0.0, separation));
    let tb = b0.ct / c;
    let r0 = b0.space + n * (v * tb);
    let along = r0.dot(n);
    let across = r0 - n * along;
    let impact = across.length();
    if impact >= reach || along <= 0.0 {
        return None; // they miss, or B is not ahead of A along the approach
    }
    let d_min = ((reach - impact) * (reach + impact)).sqrt() / gamma; // Eq. 5

    let contact_point = |t: f64| -> DVec3 {
        let xa = n * (v * t);
        let r = r0 - n * (2.0 * v * t);
        xa + r * (a.radius / reach)
    };
    let board_time = |t: f64| -> f64 {
        let e = to_pair
            .inverse()
            .apply(FourVector::new(c * t, contact_point(t)));
        e.ct / c
    };

    let mut t_contact = (along - d_min) / (2.0 * v); // Eq. 6
    if board_time(t_contact) < 0.0 {
        // The contact lies in the board past: overlapping now. Meet at
        // once if still approaching: find the pair time whose contact point
        // is at board time `now` (board time grows linearly along it).
        let (t0, t1) = (board_time(0.0), board_time(1.0));
        t_contact = -t0 / (t1 - t0);
        if along - 2.0 * v * t_contact <= 0.0 {
            return None; // already past each other along the approach
        }
    }

    let r_contact = r0 - n * (2.0 * v * t_contact);
    let along_c = r_contact.dot(n);
    let normal = (n * (gamma * gamma * along_c) + (r_contact - n * along_c)).normalize();

    let from_pair = to_pair.inverse();
    let to_board = |t: f64, x: DVec3| -> Event {
        let e = from_pair.apply(FourVector::new(c * t, x));
        Event::new(now + e.ct / c, origin.position + e.space)
    };
    let xc = contact_point(t_contact);
    let centre_a = n * (v * t_contact);
    let centre_b = centre_a + r_contact;
    let mut contact = to_board(t_contact, xc);
    contact.t = contact.t.max(now);
    let kick_a = to_board(t_contact, centre_a);
    let kick_b = to_board(t_contact, centre_b);
    Some(PairContact {
        contact,
        kicks: [kick_a, kick_b],
        normal,
        pair_frame,
        gamma_pair: gamma,
        on_board: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::worldline::Worldline;

    const C: f64 = 1.42;
    const R: f64 = 0.0305;

    fn line(x: f64, y: f64, u: ProperVelocity) -> Worldline {
        Worldline::new(Event::new(0.0, DVec3::new(x, y, 0.0)), u, C)
    }

    fn mover(w: &Worldline) -> Mover<'_> {
        Mover {
            segment: w.last(),
            radius: R,
        }
    }

    #[test]
    fn head_on_on_a_resting_puck_matches_the_board_frame_closed_form() {
        for beta in [1e-4, 0.5, 0.9, 0.999] {
            let u = ProperVelocity::try_from_beta(DVec3::new(beta, 0.0, 0.0)).unwrap();
            let a = line(0.5, 0.7, u);
            let b = line(1.5, 0.7, ProperVelocity::ZERO);
            let hit = predict(mover(&a), mover(&b), C, 0.0).unwrap();
            // The front of A (half-width R/γ) meets the back of B (R).
            let gamma = u.gamma();
            let t = (1.0 - R - R / gamma) / (beta * C);
            assert!(
                (hit.contact.t - t).abs() < 1e-12 * t.max(1.0),
                "{beta}: {} vs {t}",
                hit.contact.t
            );
            // Positions carry the rounding of c·t (t ≈ 6600 s at β = 1e-4).
            assert!((hit.contact.position.x - (1.5 - R)).abs() < 1e-12 * (C * t).max(1.0));
            assert!((hit.normal - DVec3::X).length() < 1e-12);
            // The kicks are simultaneous with the contact in the pair frame,
            // which moves at β_f = u / (γ + 1) (the half rapidity); there the
            // centres are R/γ_f either side of the contact, so on the board
            // A's kick comes β_f R / c before the contact and B's as long after.
            let beta_f = u.0.x / (gamma + 1.0);
            let dt = beta_f * R / C;
            assert!(
                (hit.kicks[1].t - (t + dt)).abs() < 1e-12 * t.max(1.0),
                "{beta}: {} vs {}",
                hit.kicks[1].t,
                t + dt
            );
            assert!(
                (hit.kicks[0].t - (t - dt)).abs() < 1e-12 * t.max(1.0),
                "{beta}"
            );
            // B has not moved; A's centre is on its worldline, 2R from B's.
            assert!(
                (hit.kicks[1].position - DVec3::new(1.5, 0.7, 0.0)).length()
                    < 1e-12 * (C * t).max(1.0)
            );
            let xa = 0.5 + beta * C * hit.kicks[0].t;
            assert!((hit.kicks[0].position.x - xa).abs() < 1e-12 * (C * t).max(1.0));
            assert!(
                (hit.kicks[1].position.x - hit.kicks[0].position.x - 2.0 * R).abs()
                    < 1e-12 * (C * t).max(1.0)
            );
            assert!((hit.gamma_pair - ((gamma + 1.0) / 2.0).sqrt()).abs() < 1e-12 * gamma);
        }
    }

    #[test]
    fn equal_masses_use_the_papers_cm_frame_eq3() {
        let ua = ProperVelocity::try_from_beta(DVec3::new(0.8, 0.1, 0.0)).unwrap();
        let ub = ProperVelocity::try_from_beta(DVec3::new(-0.3, 0.4, 0.0)).unwrap();
        let a = line(0.5, 0.5, ua);
        let b = line(1.2, 0.3, ub);
        let hit = predict(mover(&a), mover(&b), C, 0.0).unwrap();
        let eq3 = (ua.0 + ub.0) / (ua.gamma() + ub.gamma());
        assert!((hit.pair_frame.beta() - eq3).length() < 1e-15);
    }

    #[test]
    fn in_the_pair_frame_the_shapes_touch_at_the_contact() {
        // At the contact event, in the pair frame, both contracted pucks'
        // rims pass through the contact point and neither overlaps the other.
        let ua = ProperVelocity::try_from_beta(DVec3::new(0.9, 0.2, 0.0)).unwrap();
        let ub = ProperVelocity::try_from_beta(DVec3::new(-0.1, 0.6, 0.0)).unwrap();
        // Aimed to meet near (1, 0.6) at t = 1, 0.03 m off centre.
        let meet = DVec3::new(1.0, 0.6, 0.0);
        let pa = meet - ua.velocity(C);
        let pb = meet + DVec3::new(0.0, 0.03, 0.0) - ub.velocity(C);
        let a = line(pa.x, pa.y, ua);
        let b = line(pb.x, pb.y, ub);
        let hit = predict(mover(&a), mover(&b), C, 0.0).unwrap();
        let to_pair = Boost::into_frame(hit.pair_frame);
        let in_pair = |e: Event| to_pair.apply(FourVector::new(C * e.t, e.position));
        let contact = in_pair(hit.contact);
        // Each centre at the contact's pair time.
        for (w, u) in [(&a, ua), (&b, ub)] {
            let start = in_pair(w.segments()[0].start);
            let wp = to_pair.apply_velocity(u);
            let centre = start.space + wp.beta() * (contact.ct - start.ct);
            // Distance from centre to contact, in the puck's rest frame of
            // that pair-frame slice: undo the contraction along wp.
            let rel = contact.space - centre;
            let n = wp.0.normalize();
            let along = rel.dot(n) * wp.gamma();
            let across = rel - n * rel.dot(n);
            let rest = (along * along + across.length_squared()).sqrt();
            assert!((rest - R).abs() < 1e-12, "{rest}");
        }
    }

    #[test]
    fn grazing_and_missing() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.9, 0.0, 0.0)).unwrap();
        let a = line(0.5, 0.7, u);
        // b just under 2R: a grazing hit with a normal nearly across.
        let b = line(1.5, 0.7 + 2.0 * R * (1.0 - 1e-9), ProperVelocity::ZERO);
        let hit = predict(mover(&a), mover(&b), C, 0.0).unwrap();
        assert!(hit.normal.y > 0.999, "{}", hit.normal);
        assert!(hit.contact.t.is_finite() && hit.kicks.iter().all(|k| k.is_finite()));
        // b just over 2R: no contact.
        let b = line(1.5, 0.7 + 2.0 * R + 1e-12, ProperVelocity::ZERO);
        assert!(predict(mover(&a), mover(&b), C, 0.0).is_none());
        // Moving apart: none.
        let b = line(0.3, 0.7, ProperVelocity::ZERO);
        assert!(predict(mover(&a), mover(&b), C, 0.0).is_none());
    }

    #[test]
    fn gamma_1e6_head_on() {
        let u = ProperVelocity(DVec3::new(1e6, 0.0, 0.0));
        let a = line(0.5, 0.7, u);
        let b = line(1.5, 0.7, ProperVelocity::ZERO);
        let hit = predict(mover(&a), mover(&b), C, 0.0).unwrap();
        let v = C * u.beta().x;
        let t = (1.0 - R - R / u.gamma()) / v;
        // Tolerance: a few ε γ_f² |d| / c, with the pair frame's γ_f ≈ 707.
        assert!((hit.contact.t - t).abs() < 1e-9, "{} vs {t}", hit.contact.t);
        let dt = u.0.x / (u.gamma() + 1.0) * R / C;
        assert!((hit.kicks[1].t - (t + dt)).abs() < 1e-9);
        assert!((hit.kicks[0].t - (t - dt)).abs() < 1e-9);
    }

    #[test]
    fn resting_in_contact_never_meets_and_overlap_approaching_meets_now() {
        let a = line(0.5, 0.7, ProperVelocity::ZERO);
        let b = line(0.5 + 2.0 * R, 0.7, ProperVelocity::ZERO);
        assert!(predict(mover(&a), mover(&b), C, 5.0).is_none());
        let a = line(0.5, 0.7, ProperVelocity(DVec3::new(1e-12, 0.0, 0.0)));
        let b = line(0.5 + 2.0 * R * (1.0 - 1e-12), 0.7, ProperVelocity::ZERO);
        let hit = predict(mover(&a), mover(&b), C, 5.0).unwrap();
        assert_eq!(hit.contact.t, 5.0);
    }
}
