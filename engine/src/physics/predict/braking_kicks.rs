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
/// − β·(x(t) − x_c)`, which increases (`φ′ = c − β·v > 0`). A walk of
/// at most 4 ulps from `guess` (the rounds' kick, on the simultaneity to
/// rounding) where it is that near; else Newton's method from `guess`,
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
    // The rounds leave the guess on the simultaneity to rounding: most
    // often a few ulps from the float, reached by walking alone.
    if let Some(t) = first_float_from(&phi, guess, 4) {
        return Event::new(t, motion.position_at(t));
    }
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
        let step = newton_step(motion, contact, beta, c, t, &mut floor)?;
        t = step.next;
        if step.settled {
            return Some(t);
        }
    }
    None
}

/// One Newton step on the simultaneity `φ(t) = c (t − t_c) − β·(x(t) −
/// x_c)` of the centre on `motion` with `contact` in the frame moving at
/// `beta` (`c` m/s) from board time `t` ([`Step`]), whether the step was
/// down to its rounding ([`simultaneity_floor`], worked out into `floor`
/// from the first step's own values, or a few ulps of `t`).
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
) -> Option<Step> {
    let x = motion.position_at(t);
    let offset = x - contact.position;
    let value = c * (t - contact.t) - beta.dot(offset);
    let slope = c - beta.dot(motion.velocity_at(t));
    if slope.is_nan() || slope <= 0.0 {
        return None;
    }
    let floor = *floor.get_or_insert_with(|| simultaneity_floor(t, x, contact, beta, c, slope));
    let next = t - value / slope;
    if !next.is_finite() {
        return None;
    }
    Some(Step {
        next,
        settled: (next - t).abs() <= floor.max(4.0 * f64::EPSILON * t.abs()),
        value,
        slope,
        offset,
    })
}

/// What [`newton_step`] finds at a kick's time `t`.
struct Step {
    /// The next time, s.
    next: f64,
    /// Whether the step was down to its rounding.
    settled: bool,
    /// `φ(t)`, m.
    value: f64,
    /// `φ′(t) = c − β·v`, m/s (> 0).
    slope: f64,
    /// The centre less the contact point, `x(t) − x_c`, m.
    offset: DVec3,
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
            return first_float_from(&f, t, 64);
        }
    }
    None
}

/// The first float at which an increasing `f` is ≥ 0, walked to from `t`
/// one ulp at a time (at most `most` ulps): the float with `f ≥ 0` whose
/// predecessor has `f < 0`. `None` if it is farther.
fn first_float_from(f: &impl Fn(f64) -> f64, mut t: f64, most: u32) -> Option<f64> {
    if f(t) >= 0.0 {
        for _ in 0..most {
            if f(t.next_down()) < 0.0 {
                return Some(t);
            }
            t = t.next_down();
        }
    } else {
        for _ in 0..most {
            t = t.next_up();
            if f(t) >= 0.0 {
                return Some(t);
            }
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

/// The pair frame's fixed point by Newton's method on both kicks at once:
/// the kick times `t = (t_a, t_b)` solve `φ_k(t) = c (t_k − t_c) − β(t)·(x_k(t_k)
/// − x_c) = 0`, where `β(t) = (u_a + u_b)/(γ_a + γ_b)` is the pair frame of
/// the proper velocities at the kicks (the velocity of [`pair_frame`]). The
/// frame's dependence on the kicks is in the Jacobian,
///
/// ```text
/// ∂φ_k/∂t_l = δ_kl (c − β·v_k) − (∂β/∂t_l)·(x_k − x_c),
/// ∂β/∂t_l = (u̇_l − β (u_l·u̇_l)/γ_l)/(γ_a + γ_b),
/// ```
///
/// `u̇ = du/dt` the braking's linear fall ([`Motion::u_rate_at`]), so the
/// rounds close in quadratically; one kick at a time in a frame that lags
/// a round behind (the plain fixed point) closes in only by the factor
/// `~ a R/c²` a round: eight rounds in a dense gas on the cloth, four
/// this way.
///
/// Each round first tests the fixed point as the plain rounds do: one
/// Newton step of each kick in the round's frame (the pair frame of the
/// kicks as they are), both down to their rounding
/// ([`simultaneity_floor`]), and the pair frame of the stepped kicks
/// within 1e-15 of the round's; then the kicks are on the frame's
/// simultaneity to rounding and the frame is the pair frame of their
/// velocities, whatever steps led there. `None` where a slope is not
/// positive, the Jacobian not invertible with a positive determinant, a
/// step not finite (as across a braking's stop, where `u̇` jumps) or 64
/// rounds do not settle: the plain rounds then.
fn coupled_rounds(
    sa: &Motion,
    sb: &Motion,
    contact: Event,
    c: f64,
) -> Option<(ProperVelocity, [f64; 2])> {
    let motions = [sa, sb];
    let mut t = [contact.t; 2];
    let mut floors = [None; 2];
    for _ in 0..64 {
        let u = [sa.u_at(t[0]), sb.u_at(t[1])];
        let frame = pair_frame(u[0], u[1]);
        let beta = frame.beta();
        let [a, b] = [
            newton_step(sa, contact, beta, c, t[0], &mut floors[0])?,
            newton_step(sb, contact, beta, c, t[1], &mut floors[1])?,
        ];
        if a.settled
            && b.settled
            && frame_settled(pair_frame(sa.u_at(a.next), sb.u_at(b.next)), frame)
        {
            return Some((frame, [a.next, b.next]));
        }
        // The Jacobian: the diagonal slopes, less the frame's turn with
        // each kick.
        let gamma = [u[0].gamma(), u[1].gamma()];
        let sum = gamma[0] + gamma[1];
        let d_beta = [0, 1].map(|l| {
            let du = motions[l].u_rate_at(t[l]);
            (du - beta * (u[l].0.dot(du) / gamma[l])) / sum
        });
        let j00 = a.slope - d_beta[0].dot(a.offset);
        let j01 = -d_beta[1].dot(a.offset);
        let j10 = -d_beta[0].dot(b.offset);
        let j11 = b.slope - d_beta[1].dot(b.offset);
        let det = j00 * j11 - j01 * j10;
        if !(j00 > 0.0 && j11 > 0.0 && det > 0.0) {
            return None;
        }
        t = [
            t[0] - (j11 * a.value - j01 * b.value) / det,
            t[1] - (j00 * b.value - j10 * a.value) / det,
        ];
        if !t.iter().all(|x| x.is_finite()) {
            return None;
        }
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
    // The fixed point by Newton's method on both kicks with the frame's
    // turn in the Jacobian (four rounds in a dense gas, where the plain
    // fixed point, shrinking the change by ~ a R/c² a round, took eight),
    // each round ending only on the plain rounds' own test. (Aitken's δ²
    // on the plain rounds was tried before and taken back: it ended on its
    // extrapolated frame, not on that test, and once on a frame that was
    // not the pair's: energy off by 6e-4 in `engine/tests/friction.rs`.)
    let (frame, guesses) = coupled_rounds(sa, sb, contact, c).unwrap_or_else(|| {
        plain_rounds(
            sa,
            sb,
            contact,
            c,
            pair_frame(sa.u_at(contact.t), sb.u_at(contact.t)),
        )
    });
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
