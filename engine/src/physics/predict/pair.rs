//! The pair-contact policy: when two pucks on their current segments next
//! touch, in the pair frame or on the board, as a function of the two
//! segments alone (the event loop only schedules, applies and records).

use glam::DVec3;

use super::bounds::leaves_reach;
use super::braking;
use super::puck_puck::{self, Mover, PairContact};
use crate::physics::overlap;
use crate::spacetime::{Event, ProperVelocity};
use crate::worldline::Worldline;

/// Proper speed of the pair frame on the board above which a pair-frame
/// contact is checked against the board's first touch (see [`contact`]).
pub const BOARD_FIRST_U: f64 = 3.0;

/// The next contact of pucks `a` and `b` (on their current segments) from
/// board time `now` on, for speed of light `c` (m/s).
///
/// Normally the closed-form prediction ([`puck_puck::predict`]), in the
/// pair frame. But the board slice is not the pair frame's, and a kick
/// (from a cushion or a third puck) changes a puck's contraction at once
/// and begins a new segment whose backward extension the pair-frame
/// solve cannot tell from the real past. So the board picture decides
/// where the pair-frame one is silent:
///
/// * pucks overlapping on the board and closing (the penetration depth
///   grows) are pushed apart at once: a contact at `now`, normal along
///   the penetration direction, both kicks at `now` (the board is the
///   frame in which that overlap is defined); if they are opening, the
///   depth shrinks to nothing with no event (it is concave in time);
/// * pucks apart on the board for which the pair frame finds no contact
///   ahead, but whose board shapes will meet (a concave gap function
///   crossing zero, [`overlap::first_touch`]), meet then, the same way.
///
/// `board_only`: a settled pair (they have collided and nothing has
/// touched either since): the pair frame is
/// not asked (its contact is the one just resolved), only the board, and
/// while the contact's own overlap lasts nothing is predicted.
///
/// Both board searches (an overlap scan per time tried)
/// are skipped for a pair that [`overlap::apart_throughout`] proves
/// apart on the board for as long as their rest discs overlap: they
/// would find nothing. `proofs`: whether such cheap one-sided proofs may
/// skip the searches (the reference loop turns them off, so that the test
/// comparing the two loops checks the proofs).
///
/// `horizon` (s): a braking pair's search may stop there
/// ([`braking::pair_before`]: a contact whose earlier kick is at or before
/// it is found to the same bits; a later one may be missed). Uniform pairs,
/// solved in closed form, ignore it.
#[must_use]
pub fn contact(
    a: Mover,
    b: Mover,
    c: f64,
    now: f64,
    board_only: bool,
    proofs: bool,
    horizon: f64,
) -> Option<PairContact> {
    let (sa, sb) = (a.segment, b.segment);
    let (ra, rb) = (a.radius, b.radius);
    if sa.is_braking() || sb.is_braking() {
        return braking::pair_before(a, b, c, now, horizon);
    }
    let on_board = |t: f64, m: DVec3| PairContact {
        contact: Event::new(t, overlap::contact_point_at(sa, ra, sb, rb, t, m)),
        kicks: [
            Event::new(t, sa.position_at(t)),
            Event::new(t, sb.position_at(t)),
        ],
        normal: m,
        pair_frame: ProperVelocity::ZERO,
        gamma_pair: sa.gamma().max(sb.gamma()),
        on_board: true,
    };
    let v_rel = sb.velocity() - sa.velocity();
    // A closing speed below this is rounding (relative to the speeds).
    let still = 1e-12 * (sa.velocity().length() + sb.velocity().length());
    let d0 = sb.position_at(now) - sa.position_at(now);
    // How long the centres stay within reach of each other (rest discs
    // overlapping), if they are or come so; before and after, the board
    // shapes, inside their rest discs, are apart.
    let leave = leaves_reach(d0, v_rel, ra + rb);
    // Proved apart on the board over that whole window (a cheap
    // one-sided test, made only where a search would follow): the
    // penetration test now and the board's first touch below would find
    // nothing, so neither search is made.
    // (Not on the reference path, which keeps the searches themselves
    // so that the test comparing the two paths checks these proofs.)
    let apart = || {
        proofs
            && leave
                .is_some_and(|leave| overlap::apart_throughout(sa, ra, sb, rb, now, now + leave))
    };
    let mut proved_apart = None;
    if overlap::penetration_needs_scan(sa, ra, sb, rb, d0) {
        // A settled pair proved still overlapping (a cheap one-sided
        // test): the penetration test would find it so, and nothing is
        // predicted.
        if board_only && proofs && overlap::overlap_certain(sa, ra, sb, rb, now) {
            return None;
        }
        let is_apart = *proved_apart.insert(apart());
        if !is_apart && let Some((depth, m)) = overlap::penetration(sa, ra, sb, rb, now) {
            if board_only {
                return None; // a settled pair's own overlap: it only opens
            }
            let m = overlap::contact_normal(sa, ra, sb, rb, now, (depth, m));
            return (m.dot(v_rel) < -still).then(|| on_board(now, m));
        }
    }
    if !board_only && let Some(hit) = puck_puck::predict(a, b, c, now) {
        // The board shapes can meet well before the pair frame's first
        // kick when the pair frame moves fast on the board (a very fast
        // puck crossing a slower one's path: the pair frame's slice is
        // far from the board's). Then the board decides, at its first
        // touch. Checked only for a pair frame faster than
        // `BOARD_FIRST_U` (proper speed; below it the slices differ by
        // a fraction of a contact and the pair frame keeps the contact)
        // whose unperturbed shapes overlap on the board at that kick.
        let first = hit.kicks[0].t.min(hit.kicks[1].t);
        if first > now
            && hit.pair_frame.0.length_squared() > BOARD_FIRST_U * BOARD_FIRST_U
            && overlap::depth(sa, ra, sb, rb, first) > 0.0
            && let Some(t) = overlap::first_touch(sa, ra, sb, rb, now, first)
            && t < first
        {
            let d = sb.position_at(t) - sa.position_at(t);
            let normal =
                overlap::contact_normal(sa, ra, sb, rb, t, overlap::gap(sa, ra, sb, rb, d));
            return Some(on_board(t.max(now), normal));
        }
        return Some(hit);
    }
    // Apart now, and the pair frame sees nothing ahead: will the board
    // shapes meet? Only while the centres are within reach.
    let end = now + leave?;
    if proved_apart.unwrap_or_else(apart) {
        return None;
    }
    // A separating axis along which they do not close: never.
    let (g, m) = overlap::gap(sa, ra, sb, rb, d0);
    if g <= 0.0 && m.dot(v_rel) >= 0.0 {
        return None;
    }
    let t = overlap::first_touch(sa, ra, sb, rb, now, end)?.max(now);
    let d = d0 + v_rel * (t - now);
    let normal = overlap::contact_normal(sa, ra, sb, rb, t, overlap::gap(sa, ra, sb, rb, d));
    Some(on_board(t, normal))
}

/// Whether two pucks leaving the board events `xa`, `xb` (m, s) with
/// proper velocities `ua`, `ub` and rest radii `ra`, `rb` (m), speed of
/// light `c` (m/s), will overlap on the board again while their centres
/// are within reach: the direction (unit, board frame, from `a` towards
/// `b`) along which they then meet, if they do.
#[must_use]
pub fn touch_again(
    xa: Event,
    ra: f64,
    ua: ProperVelocity,
    xb: Event,
    rb: f64,
    ub: ProperVelocity,
    c: f64,
) -> Option<DVec3> {
    let (wa, wb) = (Worldline::new(xa, ua, c), Worldline::new(xb, ub, c));
    let (sa, sb) = (wa.last(), wb.last());
    let d0 = xb.position - xa.position;
    let leave = leaves_reach(d0, sb.velocity() - sa.velocity(), ra + rb)?;
    let t0 = xa.t;
    let t = overlap::first_touch(sa, ra, sb, rb, t0, t0 + leave)?;
    let d = sb.position_at(t) - sa.position_at(t);
    Some(overlap::contact_normal(
        sa,
        ra,
        sb,
        rb,
        t,
        overlap::gap(sa, ra, sb, rb, d),
    ))
}
