//! Where and along what two touching shapes meet: the contact point
//! (midway between the two rims) and the contact normal (the gap
//! function's minimiser, the line of centres for mirror images), the same
//! whichever puck is named first.

use glam::DVec3;

use super::{Outline, gap_along};
use crate::worldline::Segment;

/// The contact point of two touching shapes centred at `xa`, `xb` (m,
/// board) whose contact normal is the unit `m` (from `a` towards `b`): the
/// midpoint of `a`'s farthest point along `m` and `b`'s farthest along
/// `−m`, which coincide when they touch exactly. The same bits with `a`
/// and `b` exchanged (and `m` negated), so the point does not depend on
/// which of the pair the loop holds first.
#[must_use]
pub fn contact_point(oa: &Outline, ob: &Outline, xa: DVec3, xb: DVec3, m: DVec3) -> DVec3 {
    let on_a = xa + oa.support_point(m.x, m.y);
    let on_b = xb - ob.support_point(m.x, m.y);
    (on_a + on_b) * 0.5
}

/// [`contact_point`] of two pucks on segments `a`, `b` (rest radii m) at
/// board time `t` (s).
#[must_use]
pub fn contact_point_at(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    t: f64,
    m: DVec3,
) -> DVec3 {
    contact_point(
        &Outline::of(&a.tangent_at(t), radius_a),
        &Outline::of(&b.tangent_at(t), radius_b),
        a.position_at(t),
        b.position_at(t),
        m,
    )
}

/// The contact normal of two pucks on segments `a`, `b` at board time `t`
/// (s) whose gap function has its minimum `found` (value, unit direction),
/// as [`super::gap`] or [`super::penetration`] give it: that direction, unless its mirror
/// image across the line of centres is a minimum of the same value (to
/// 1e-9 of the radii, the search's precision) but another direction. The two shapes are then
/// mirror images of each other about the perpendicular bisector of their
/// centres (two mirror-image pucks meeting), the gap function is
/// symmetric across the line of centres, and which of the two minima the
/// search returns is decided by rounding; symmetry gives the line of
/// centres itself, which is returned (pointing the way `found` does).
#[must_use]
pub fn contact_normal(
    a: &Segment,
    radius_a: f64,
    b: &Segment,
    radius_b: f64,
    t: f64,
    found: (f64, DVec3),
) -> DVec3 {
    let (g, m) = found;
    let (a, b) = (a.tangent_at(t), b.tangent_at(t));
    let d = b.position_at(t) - a.position_at(t);
    let length = d.length();
    if length == 0.0 {
        return m;
    }
    let line = d / length;
    let along = m.dot(line);
    let twin = line * (2.0 * along) - m;
    if (twin - m).length() <= 1e-9 {
        return m; // the minimum is on the line of centres
    }
    let (oa, ob) = (Outline::of(&a, radius_a), Outline::of(&b, radius_b));
    let other = gap_along(&oa, &ob, twin.x, twin.y, d);
    // (To 1e-9 of the radii: `g` is a search's minimum, found to about
    // 1e-11 of them in a deep overlap, seed 71 of the mirror test.)
    if (other - g).abs() <= 1e-9 * (radius_a + radius_b) {
        line * along.signum()
    } else {
        m
    }
}
