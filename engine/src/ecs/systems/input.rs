//! Input: how an observer's moves become kinks on its worldline (flight
//! thrust, tracker samples), as cue strokes become kinks on a puck's. The
//! past is never rewritten, so a replay shows the observer where it was.

use glam::DVec3;

use crate::spacetime::ProperVelocity;
use crate::worldline::{Worldline, WorldlineError};

/// Fastest an observer is steered by [`follow`], as a fraction of c.
pub const MAX_FOLLOW_BETA: f64 = 0.99;

/// Flight: from board time `t` on the observer moves with proper velocity
/// `u` (a kink at `t`; a second kink at the same `t` replaces the first).
pub fn steer(worldline: &mut Worldline, t: f64, u: ProperVelocity) -> Result<(), WorldlineError> {
    worldline.push(t, u)
}

/// A tracked head: at board time `t` a sample says the eye is at `target`
/// (board frame, m). The worldline gets a kink at `t` whose velocity
/// reaches `target` `lag` seconds later (one sample interval), so the eye
/// follows the samples one interval behind without drifting, and never
/// faster than [`MAX_FOLLOW_BETA`]·c.
pub fn follow(
    worldline: &mut Worldline,
    t: f64,
    target: DVec3,
    lag: f64,
) -> Result<(), WorldlineError> {
    if !(lag.is_finite() && lag > 0.0 && target.is_finite()) {
        return Err(WorldlineError::NotFinite);
    }
    let c = worldline.speed_of_light();
    let mut beta = (target - worldline.position_at(t)) / (lag * c);
    if beta.length() > MAX_FOLLOW_BETA {
        beta = beta.normalize() * MAX_FOLLOW_BETA;
    }
    let u = ProperVelocity::try_from_beta(beta).map_err(|_| WorldlineError::NotFinite)?;
    worldline.push(t, u)
}
