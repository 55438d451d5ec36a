//! The collision convention on braking worldlines: each puck's velocity
//! changes at the event on its centre's worldline simultaneous with the
//! contact in the pair frame, the frame of the two 4-velocities there (a
//! fixed point: the kicks move the velocities, which move the frame); the
//! normal is the pair frame's ([`super::braking`]'s module doc).

use glam::DVec3;

use super::braking_motion::Motion;
use super::isolation::bisect;
use super::puck_puck::PairContact;
use crate::spacetime::{Boost, Event, FourVector, ProperVelocity};

/// The pair frame of two proper velocities: the normalised sum of their
/// 4-velocities.
fn pair_frame(ua: ProperVelocity, ub: ProperVelocity) -> ProperVelocity {
    let gamma_rel = Boost::into_frame(ua).apply_velocity(ub).gamma();
    ProperVelocity((ua.0 + ub.0) / (2.0 + 2.0 * gamma_rel).sqrt())
}

/// The event on `segment` simultaneous with `contact` in the frame moving
/// with `frame`: the first float `t` with `φ(t) ≥ 0`, `φ(t) = c (t − t_c)
/// − β·(x(t) − x_c)`, which increases (`φ′ = c − β·v > 0`). Newton's
/// method from `guess` (the last round's kick, or the contact's time),
/// then a walk of a few ulps to that float; where Newton does not settle
/// (never met), doubling steps bracket the root and it is bisected to
/// adjacent floats.
fn simultaneous(
    motion: &Motion,
    contact: Event,
    frame: ProperVelocity,
    c: f64,
    guess: f64,
) -> Event {
    let beta = frame.beta();
    let phi = |t: f64| c * (t - contact.t) - beta.dot(motion.position_at(t) - contact.position);
    let floor = simultaneity_floor(
        guess,
        motion.position_at(guess),
        contact,
        beta,
        c,
        c - beta.dot(motion.velocity_at(guess)),
    );
    let t = newton_first_float(phi, |t| c - beta.dot(motion.velocity_at(t)), guess, floor)
        .unwrap_or_else(|| simultaneous_bracketed(motion, contact, &phi, frame, c));
    Event::new(t, motion.position_at(t))
}

/// How far (s) Newton's steps on `φ(t) = c (t − t_c) − β·(x(t) − x_c)`
/// can wander from its root by rounding alone, at a step from board time
/// `t` with the centre at `x` and `φ`'s slope `rate` (`c − β·v`): `φ` is
/// formed from terms of size `c |t|` and `|β| |x|`, each rounded by `ε`,
/// and a step divides by the slope; four times that. A step below it has
/// settled (far from the origin of the table's coordinates the terms are
/// larger than the step's own time's ulps: a strict `4 ε |t|` is then
/// never met, found on a mirror image of a scene that settled).
fn simultaneity_floor(t: f64, x: DVec3, contact: Event, beta: DVec3, c: f64, rate: f64) -> f64 {
    let terms =
        c * (t.abs() + contact.t.abs()) + beta.length() * (x.length() + contact.position.length());
    4.0 * f64::EPSILON * terms / rate.max(f64::MIN_POSITIVE)
}

/// [`simultaneous`]'s time to rounding only: Newton's method from `guess`
/// until a step is down to its rounding ([`simultaneity_floor`]); `None`
/// if it does not settle.
fn simultaneous_near(
    motion: &Motion,
    contact: Event,
    frame: ProperVelocity,
    c: f64,
    guess: f64,
) -> Option<f64> {
    let beta = frame.beta();
    let mut t = guess;
    let mut floor = None;
    for _ in 0..16 {
        let (next, settled) = newton_step(motion, contact, beta, c, t, &mut floor)?;
        t = next;
        if settled {
            return Some(t);
        }
    }
    None
}

/// One Newton step on the simultaneity `φ(t) = c (t − t_c) − β·(x(t) −
/// x_c)` of the centre on `motion` with `contact` in the frame moving at
/// `beta` (`c` m/s) from board time `t`: the next time, and whether the
/// step was down to its rounding ([`simultaneity_floor`], worked out into
/// `floor` from the first step's own values, or a few ulps of `t`).
/// Settled only when the step itself is that small: a guess taken as
/// settled because the next step would be (Newton's quadratic error) is
/// wrong across the braking's stop, where `φ′` jumps, and left a frame that
/// was not the pair's (energy off by 1.6e-3 in `engine/tests/friction.rs`'s
/// random scenes). `None` where the slope is not positive or the step not
/// finite.
fn newton_step(
    motion: &Motion,
    contact: Event,
    beta: DVec3,
    c: f64,
    t: f64,
    floor: &mut Option<f64>,
) -> Option<(f64, bool)> {
    let x = motion.position_at(t);
    let value = c * (t - contact.t) - beta.dot(x - contact.position);
    let rate = c - beta.dot(motion.velocity_at(t));
    if rate.is_nan() || rate <= 0.0 {
        return None;
    }
    let floor = *floor.get_or_insert_with(|| simultaneity_floor(t, x, contact, beta, c, rate));
    let next = t - value / rate;
    if !next.is_finite() {
        return None;
    }
    Some((
        next,
        (next - t).abs() <= floor.max(4.0 * f64::EPSILON * t.abs()),
    ))
}

/// Whether the pair frame `next` worked out from a round's kicks is
/// `frame`, the round's own, to rounding (under 1e-15 of its size): the
/// rounds' fixed point.
fn frame_settled(next: ProperVelocity, frame: ProperVelocity) -> bool {
    (next.0 - frame.0).length() <= 1e-15 * (1.0 + frame.0.length())
}

/// The first float at which an increasing `f` (slope `slope`, > 0) is ≥ 0,
/// by Newton's method from `t` until a step is below `floor` (s, what
/// rounding alone moves it) or a few ulps of `t`, then a walk to the float
/// (at most 64 ulps each way); `None` if either does not settle.
fn newton_first_float(
    f: impl Fn(f64) -> f64,
    slope: impl Fn(f64) -> f64,
    mut t: f64,
    floor: f64,
) -> Option<f64> {
    for _ in 0..16 {
        let (value, rate) = (f(t), slope(t));
        if rate.is_nan() || rate <= 0.0 || !value.is_finite() {
            return None;
        }
        let next = t - value / rate;
        if !next.is_finite() {
            return None;
        }
        let settled = (next - t).abs() <= floor.max(4.0 * f64::EPSILON * t.abs());
        t = next;
        if settled {
            if f(t) >= 0.0 {
                for _ in 0..64 {
                    if f(t.next_down()) < 0.0 {
                        return Some(t);
                    }
                    t = t.next_down();
                }
            } else {
                for _ in 0..64 {
                    t = t.next_up();
                    if f(t) >= 0.0 {
                        return Some(t);
                    }
                }
            }
            return None;
        }
    }
    None
}

/// [`simultaneous`]'s fallback: the root of `phi` bracketed by doubling
/// steps from the contact's time and bisected to adjacent floats.
fn simultaneous_bracketed(
    motion: &Motion,
    contact: Event,
    phi: &impl Fn(f64) -> f64,
    frame: ProperVelocity,
    c: f64,
) -> f64 {
    let scale = (motion.position_at(contact.t) - contact.position).length() / c;
    let first = scale.max(1e-300) * frame.gamma() * frame.gamma() + f64::EPSILON * contact.t.abs();
    let (mut lo, mut hi) = (contact.t, contact.t);
    let mut step = first;
    for _ in 0..2100 {
        if phi(lo) <= 0.0 {
            break;
        }
        lo = contact.t - step;
        step *= 2.0;
    }
    step = first;
    for _ in 0..2100 {
        if phi(hi) >= 0.0 {
            break;
        }
        hi = contact.t + step;
        step *= 2.0;
    }
    if phi(lo) == 0.0 {
        lo
    } else {
        bisect(|t| -phi(t), lo, hi)
    }
}

/// The pair frame's fixed point with one Newton step a kick a round: each
/// kick moves towards the simultaneity of the frame it is in while the
/// frame moves with the kicks, until in one round both steps are down to
/// their rounding ([`simultaneity_floor`]) and the frame moves by under
/// 1e-15 of itself (the plain rounds' test, [`plain_rounds`]): then the
/// kicks are on the frame's simultaneity to rounding and the frame is the
/// pair frame of their velocities, as the plain rounds end. The plain
/// rounds solve each kick to rounding every round (2.3 Newton steps a
/// kick a round in a dense gas); this takes one. `None` where a step
/// fails (a slope not positive, a value not finite: across a braking's
/// stop) or 64 rounds do not settle: the plain rounds then.
fn interleaved_rounds(
    sa: &Motion,
    sb: &Motion,
    contact: Event,
    c: f64,
    mut frame: ProperVelocity,
) -> Option<(ProperVelocity, [f64; 2])> {
    let mut guesses = [contact.t; 2];
    let mut floors = [None; 2];
    for _ in 0..64 {
        let beta = frame.beta();
        let mut settled = true;
        for (k, s) in [sa, sb].into_iter().enumerate() {
            let (next, step_settled) =
                newton_step(s, contact, beta, c, guesses[k], &mut floors[k])?;
            settled &= step_settled;
            guesses[k] = next;
        }
        let next = pair_frame(sa.u_at(guesses[0]), sb.u_at(guesses[1]));
        if settled && frame_settled(next, frame) {
            return Some((frame, guesses));
        }
        frame = next;
    }
    None
}

/// The pair frame's fixed point, each round's kicks solved to rounding
/// ([`simultaneous_near`]) in the last round's frame (at most 32 rounds).
fn plain_rounds(
    sa: &Motion,
    sb: &Motion,
    contact: Event,
    c: f64,
    mut frame: ProperVelocity,
) -> (ProperVelocity, [f64; 2]) {
    // The rounds need the kicks only to rounding (Newton's method alone);
    // the kicks kept are then found to the float in the last frame.
    let mut guesses = [contact.t; 2];
    let mut rounds = 0;
    loop {
        for (guess, s) in guesses.iter_mut().zip([sa, sb]) {
            // Where Newton's method alone does not settle, the search
            // that always does (a guess left where it was would end the
            // rounds in a frame that is not the pair's).
            *guess = simultaneous_near(s, contact, frame, c, *guess)
                .unwrap_or_else(|| simultaneous(s, contact, frame, c, *guess).t);
        }
        let next = pair_frame(sa.u_at(guesses[0]), sb.u_at(guesses[1]));
        rounds += 1;
        if frame_settled(next, frame) || rounds == 32 {
            return (frame, guesses);
        }
        frame = next;
    }
}

/// The kicks, normal and pair frame of a contact at `contact` (board) of the
/// pucks on `sa`, `sb` (module doc, "The collision convention").
pub(super) fn in_pair_frame(sa: &Motion, sb: &Motion, contact: Event, c: f64) -> PairContact {
    // The kicks in a frame, then the pair frame of the velocities there,
    // until it no longer moves beyond rounding (each round shrinks the
    // change by a factor ~ a R/c², 0.03 on the paper's table). Not
    // extrapolated: Aitken's δ² every second round saved a fifth of the
    // rounds in a dense gas, but with another search's contact in a
    // random scene on the cloth at γ ≈ 50 it ended on a frame that was not
    // the pair's (energy off by 6e-4 in `engine/tests/friction.rs`), so
    // the rounds are the plain fixed point.
    let start = pair_frame(sa.u_at(contact.t), sb.u_at(contact.t));
    let (frame, guesses) = interleaved_rounds(sa, sb, contact, c, start)
        .unwrap_or_else(|| plain_rounds(sa, sb, contact, c, start));
    let kicks = [
        simultaneous(sa, contact, frame, c, guesses[0]),
        simultaneous(sb, contact, frame, c, guesses[1]),
    ];
    let to_pair = Boost::into_frame(frame);
    let (ua, ub) = (
        to_pair.apply_velocity(sa.u_at(kicks[0].t)),
        to_pair.apply_velocity(sb.u_at(kicks[1].t)),
    );
    let w = 0.5 * (ua.0 - ub.0);
    let w_len = w.length();
    let gamma = 1.0f64.hypot(w_len);
    let rel = |e: Event| {
        to_pair
            .apply(FourVector::new(
                c * (e.t - contact.t),
                e.position - contact.position,
            ))
            .space
    };
    let r = rel(kicks[1]) - rel(kicks[0]);
    let normal = if w_len > 0.0 {
        let n = w / w_len;
        let along = r.dot(n);
        (n * (gamma * gamma * along) + (r - n * along)).normalize()
    } else {
        r.normalize()
    };
    PairContact {
        contact,
        kicks,
        gamma_pair: gamma,
        on_board: false,
        normal,
        pair_frame: frame,
    }
}
