//! When a moving (contracted) puck meets a cushion, in the board frame.
//!
//! A puck of rest radius `R` moving with proper velocity `u` is, on the
//! board, an ellipse of semi-axes `R/γ` along its motion and `R` across.
//! Its half-width along a coordinate axis `k` is `R √(1 − βₖ²)`, which is
//! exactly `R √(1 + u⊥²) / γ` with `u⊥` the components of `u` other than
//! `k`: no `1 − β²` is formed. The puck moves in a straight line, so the
//! contact time with an axis-aligned cushion is a single division. The
//! rest-frame construction of the paper (§3.3.2.3: a round puck meeting a
//! tilted, moving cushion) gives the same event; a test shows it.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use crate::spacetime::ProperVelocity;
use crate::worldline::Segment;

/// The four cushions, named by the table edge they lie on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Cushion {
    /// The edge x = 0.
    X0,
    /// The edge x = size.x.
    X1,
    /// The edge y = 0.
    Y0,
    /// The edge y = size.y.
    Y1,
}

impl Cushion {
    /// All four, in the order used to break ties.
    pub const ALL: [Cushion; 4] = [Cushion::X0, Cushion::X1, Cushion::Y0, Cushion::Y1];

    /// `"x0"`, `"x1"`, `"y0"` or `"y1"`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Cushion::X0 => "x0",
            Cushion::X1 => "x1",
            Cushion::Y0 => "y0",
            Cushion::Y1 => "y1",
        }
    }

    /// Coordinate axis of the cushion's normal: 0 for x, 1 for y.
    #[must_use]
    pub fn axis(self) -> usize {
        match self {
            Cushion::X0 | Cushion::X1 => 0,
            Cushion::Y0 | Cushion::Y1 => 1,
        }
    }

    /// +1 if the table lies below the cushion along its axis (x1, y1), −1
    /// otherwise: the sign of the outward normal.
    #[must_use]
    pub fn outward_sign(self) -> f64 {
        match self {
            Cushion::X0 | Cushion::Y0 => -1.0,
            Cushion::X1 | Cushion::Y1 => 1.0,
        }
    }

    /// Outward unit normal (from the table into the cushion), board frame.
    #[must_use]
    pub fn outward(self) -> DVec3 {
        let mut n = DVec3::ZERO;
        n[self.axis()] = self.outward_sign();
        n
    }

    /// The cushion line's coordinate along its axis, m.
    #[must_use]
    pub fn line(self, size: DVec2) -> f64 {
        match self {
            Cushion::X0 | Cushion::Y0 => 0.0,
            Cushion::X1 => size.x,
            Cushion::Y1 => size.y,
        }
    }
}

/// Half-width `R √(1 − βₖ²)` of a puck of rest radius `radius` moving with
/// `u`, along coordinate axis `axis`, m. Exact at any γ.
#[must_use]
pub fn half_width(radius: f64, u: ProperVelocity, axis: usize) -> f64 {
    let across = u.0.length_squared() - u.0[axis] * u.0[axis];
    // length_squared − u_k² can round below zero only when it is ~0.
    radius * (1.0 + across.max(0.0)).sqrt() / u.gamma()
}

/// The point of the contracted puck's rim that touches the cushion,
/// relative to its centre: the ellipse's support point in the direction
/// of the cushion's outward normal.
#[must_use]
pub fn support_offset(radius: f64, u: ProperVelocity, cushion: Cushion) -> DVec3 {
    let k = cushion.axis();
    let s = cushion.outward_sign();
    let gamma = u.gamma();
    let across_sq = (u.0.length_squared() - u.0[k] * u.0[k]).max(0.0);
    let m = (1.0 + across_sq).sqrt();
    // Along the normal: R m / γ. Across: −R u⊥ (u·e) / (γ m) (the support
    // point leans back against the motion).
    let mut u_across = u.0;
    u_across[k] = 0.0;
    let mut offset = -u_across * (radius * (u.0[k] * s) / (gamma * m));
    offset[k] = s * radius * m / gamma;
    offset
}

/// A predicted puck–cushion contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CushionContact {
    /// Board time of contact, s.
    pub t: f64,
    /// Contact point on the cushion, board frame, m.
    pub point: DVec3,
}

/// The next contact, at board time ≥ `now`, of a puck moving along
/// `segment` with the cushion, or `None` if it moves away or parallel.
///
/// A puck already touching (or, after rounding, slightly past) the cushion
/// and still moving into it meets it at `now`.
#[must_use]
pub fn predict(
    segment: &Segment,
    radius: f64,
    table: DVec2,
    cushion: Cushion,
    now: f64,
) -> Option<CushionContact> {
    let t = time(segment, radius, table, cushion, now)?;
    let centre = segment.position_at(t);
    Some(CushionContact {
        t,
        point: centre + support_offset(radius, segment.u, cushion),
    })
}

/// The board time of [`predict`]'s contact alone, s (the same value): what
/// the event loop's calendar needs, without the contact point.
#[must_use]
pub fn time(
    segment: &Segment,
    radius: f64,
    table: DVec2,
    cushion: Cushion,
    now: f64,
) -> Option<f64> {
    let k = cushion.axis();
    let s = cushion.outward_sign();
    let towards = segment.velocity()[k] * s;
    if towards <= 0.0 {
        return None;
    }
    let p = segment.position_at(now);
    let h = half_width(radius, segment.u, k);
    let gap = s * (cushion.line(table) - p[k]) - h;
    let dt = (gap / towards).max(0.0);
    Some(now + dt)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::{Boost, Event, FourVector};
    use crate::worldline::Worldline;

    const C: f64 = 1.42;
    const TABLE: DVec2 = DVec2::new(2.84, 1.42);

    /// The paper's construction (§3.3.2.3), done independently: in the
    /// puck's rest frame the puck is a circle of radius R at the origin, and
    /// the cushion x = W is a moving, tilted line. The circle first touches
    /// it where the line's normal through the centre meets the rim.
    fn rest_frame_contact(start: Event, u: ProperVelocity, radius: f64, w: f64) -> Event {
        let to_rest = Boost::into_frame(u);
        // Events of the cushion line, relative to the puck's start event:
        // board x − x₀ = W − x₀ for any t, y. In rest coordinates a board
        // event is L⁻¹ (ct', x'); its x component is linear:
        // x = A ct' + K·x'. Read A and K off the inverse boost.
        let back = to_rest.inverse();
        let a = back.apply(FourVector::new(1.0, DVec3::ZERO)).space.x;
        let kx = back.apply(FourVector::new(0.0, DVec3::X)).space.x;
        let ky = back.apply(FourVector::new(0.0, DVec3::Y)).space.x;
        let k = DVec3::new(kx, ky, 0.0);
        let rhs = w - start.position.x;
        // Line at rest time t': K·x' = rhs − A ct'. Touches the circle when
        // its distance from the origin, (rhs − A ct')/|K|, equals R.
        let ct = (rhs - radius * k.length()) / a;
        let contact_rest = FourVector::new(ct, k.normalize() * radius);
        back.apply(contact_rest).from_event(start, C)
    }

    #[test]
    fn board_frame_and_puck_rest_frame_agree_at_normal_incidence() {
        for (beta, r) in [(0.95, 0.0305), (0.5, 0.1), (0.999999, 0.05), (1e-4, 0.03)] {
            let u = ProperVelocity::try_from_beta(DVec3::new(beta, 0.0, 0.0)).unwrap();
            let start = Event::new(0.25, DVec3::new(1.0, 0.7, 0.0));
            let w = Worldline::new(start, u, C);
            let ours = predict(w.last(), r, TABLE, Cushion::X1, 0.25).unwrap();
            let theirs = rest_frame_contact(start, u, r, TABLE.x);
            assert!(
                (ours.t - theirs.t).abs() < 1e-12 * ours.t,
                "{beta}: {} vs {}",
                ours.t,
                theirs.t
            );
            // Positions carry the rounding of c·t (t ≈ 10⁴ s at β = 1e-4).
            assert!(
                (ours.point - theirs.position).length() < 1e-12 * (C * ours.t).max(1.0),
                "{beta}"
            );
        }
    }

    /// At oblique incidence the two constructions name different events:
    /// "first contact" of a rigid body is frame-dependent (the worldtube
    /// meets the cushion's hyperplane over a region whose earliest point
    /// depends on the time slicing). The board frame's is the earliest
    /// board time at which the contracted puck touches the cushion, so the
    /// puck never overlaps the cushion on the board; the paper's rest-frame
    /// event lies on the same cushion and the same rim, a little later, by
    /// less than the time light takes to cross the puck.
    #[test]
    fn at_oblique_incidence_the_rest_frame_contact_is_later_by_under_a_light_crossing() {
        for (beta, r) in [
            (DVec3::new(0.7, 0.642, 0.0), 0.0305),
            (DVec3::new(0.3, -0.9, 0.0), 0.1),
            (DVec3::new(0.05, 0.05, 0.0), 0.05),
        ] {
            let u = ProperVelocity::try_from_beta(beta).unwrap();
            let start = Event::new(0.25, DVec3::new(1.0, 0.7, 0.0));
            let w = Worldline::new(start, u, C);
            let ours = predict(w.last(), r, TABLE, Cushion::X1, 0.25).unwrap();
            let theirs = rest_frame_contact(start, u, r, TABLE.x);
            assert!((theirs.position.x - TABLE.x).abs() < 1e-12);
            let late = theirs.t - ours.t;
            assert!(late > 0.0 && late < 2.0 * r / C, "{beta}: {late}");
        }
    }

    #[test]
    fn half_width_at_gamma_1e6_is_exact() {
        let u = ProperVelocity(DVec3::new(1e6, 0.0, 0.0));
        assert!((half_width(0.03, u, 0) / 3e-8 - 1.0).abs() < 1e-12);
        assert!((half_width(0.03, u, 1) - 0.03).abs() < 1e-15);
    }

    #[test]
    fn moving_away_or_along_never_meets() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.0, 0.5, 0.0)).unwrap();
        let w = Worldline::new(Event::new(0.0, DVec3::new(1.0, 0.7, 0.0)), u, C);
        assert!(predict(w.last(), 0.03, TABLE, Cushion::X1, 0.0).is_none());
        assert!(predict(w.last(), 0.03, TABLE, Cushion::X0, 0.0).is_none());
        assert!(predict(w.last(), 0.03, TABLE, Cushion::Y0, 0.0).is_none());
        let hit = predict(w.last(), 0.03, TABLE, Cushion::Y1, 0.0).unwrap();
        // Half-width across the motion along y: R √(1 − 0.25).
        assert!((hit.t - (1.42 - 0.7 - 0.03 * 0.75f64.sqrt()) / (0.5 * C)).abs() < 1e-14);
    }

    #[test]
    fn touching_and_moving_in_meets_now() {
        let u = ProperVelocity(DVec3::new(-1e-9, 0.0, 0.0));
        let w = Worldline::new(Event::new(3.0, DVec3::new(0.0305, 0.5, 0.0)), u, C);
        let hit = predict(w.last(), 0.0305, TABLE, Cushion::X0, 3.0).unwrap();
        assert_eq!(hit.t, 3.0);
        // At rest against it: never.
        let w = Worldline::new(
            Event::new(3.0, DVec3::new(0.0305, 0.5, 0.0)),
            ProperVelocity::ZERO,
            C,
        );
        assert!(predict(w.last(), 0.0305, TABLE, Cushion::X0, 3.0).is_none());
    }
}
