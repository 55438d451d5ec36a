//! One-Euro filter (Casiez, Roussel & Vogel, CHI 2012) on 3-vectors.
//!
//! Why this filter: head-tracker noise is visible as jitter of the whole
//! CAVE image when the head is still, while any lag is felt as "swimming"
//! when the head moves. The One-Euro filter is a first-order low-pass whose
//! cutoff rises with speed: `cutoff = min_cutoff + beta * |velocity|`, so it
//! smooths hard at rest and follows closely in motion. It needs no fixed
//! sample rate, which matters because IPC samples arrive with jitter.
//!
//! Vector form: the derivative is filtered per component, but the adaptive
//! cutoff uses the *norm* of the filtered derivative, so the smoothing does
//! not depend on how the tracker axes are oriented.
//!
//! The derivative is computed from successive *raw* inputs (as in the
//! authors' reference implementation), which makes the filtered derivative
//! an unbiased velocity estimate for a ramp: it is exposed as
//! [`FilterOutput::velocity`].

use glam::DVec3;
use std::f64::consts::TAU;

/// Filter tuning. Units: cutoffs in Hz, `beta` in Hz per (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OneEuroParams {
    /// Cutoff at rest (Hz). Lower = less jitter when still, more lag.
    pub min_cutoff: f64,
    /// Speed coefficient (Hz per m/s). Higher = less lag when moving.
    pub beta: f64,
    /// Cutoff used to smooth the derivative (Hz); also the bandwidth of the
    /// velocity estimate.
    pub d_cutoff: f64,
}

impl Default for OneEuroParams {
    /// Starting point for a head tracker in metres: 1 Hz at rest,
    /// +4 Hz per m/s, derivative smoothed at 1 Hz.
    fn default() -> Self {
        Self {
            min_cutoff: 1.0,
            beta: 4.0,
            d_cutoff: 1.0,
        }
    }
}

impl OneEuroParams {
    /// Replaces unusable values (non-finite, cutoffs <= 0, beta < 0) by the
    /// defaults, so a bad config file cannot produce NaN poses.
    #[must_use]
    pub fn sanitized(self) -> Self {
        let d = Self::default();
        let pos = |v: f64, dflt: f64| if v.is_finite() && v > 0.0 { v } else { dflt };
        Self {
            min_cutoff: pos(self.min_cutoff, d.min_cutoff),
            beta: if self.beta.is_finite() && self.beta >= 0.0 {
                self.beta
            } else {
                d.beta
            },
            d_cutoff: pos(self.d_cutoff, d.d_cutoff),
        }
    }
}

/// Smoothing factor of a first-order low-pass with the given cutoff (Hz) for
/// a step of `dt` seconds (both > 0).
fn alpha(cutoff_hz: f64, dt: f64) -> f64 {
    let tau = 1.0 / (TAU * cutoff_hz);
    1.0 / (1.0 + tau / dt)
}

/// Filtered position and velocity after an update.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterOutput {
    /// Filtered position (same units as the input).
    pub position: DVec3,
    /// Filtered derivative (input units per second).
    pub velocity: DVec3,
}

#[derive(Debug, Clone, Copy)]
struct State {
    x_hat: DVec3,
    dx_hat: DVec3,
    x_prev_raw: DVec3,
}

/// One-Euro filter state for a 3-vector signal.
#[derive(Debug, Clone)]
pub struct OneEuroFilter {
    params: OneEuroParams,
    state: Option<State>,
}

impl OneEuroFilter {
    /// A filter with the given (sanitised) parameters and no history.
    #[must_use]
    pub fn new(params: OneEuroParams) -> Self {
        Self {
            params: params.sanitized(),
            state: None,
        }
    }

    /// The parameters in use (after sanitising).
    #[must_use]
    pub fn params(&self) -> OneEuroParams {
        self.params
    }

    /// Forgets all history; the next update passes its input through.
    pub fn reset(&mut self) {
        self.state = None;
    }

    /// The last output, if any input has been accepted.
    #[must_use]
    pub fn current(&self) -> Option<FilterOutput> {
        self.state.map(|s| FilterOutput {
            position: s.x_hat,
            velocity: s.dx_hat,
        })
    }

    /// Feeds `x` measured `dt` seconds after the previous input.
    ///
    /// * First input: passed through, velocity zero.
    /// * `x` not finite: ignored (state unchanged).
    /// * `dt` not finite or `dt <= 0` (duplicate or reordered timestamps):
    ///   ignored, because a derivative over zero or negative time is
    ///   meaningless and would blow up the velocity.
    ///
    /// Returns the current output, or `None` while nothing usable has been
    /// fed yet.
    pub fn update(&mut self, x: DVec3, dt: f64) -> Option<FilterOutput> {
        if !x.is_finite() {
            return self.current();
        }
        let Some(s) = self.state else {
            self.state = Some(State {
                x_hat: x,
                dx_hat: DVec3::ZERO,
                x_prev_raw: x,
            });
            return self.current();
        };
        if !dt.is_finite() || dt <= 0.0 {
            return self.current();
        }
        let p = self.params;
        let dx = (x - s.x_prev_raw) / dt;
        let a_d = alpha(p.d_cutoff, dt);
        let dx_hat = s.dx_hat + a_d * (dx - s.dx_hat);
        let cutoff = p.min_cutoff + p.beta * dx_hat.length();
        let a = alpha(cutoff, dt);
        let x_hat = s.x_hat + a * (x - s.x_hat);
        if !(x_hat.is_finite() && dx_hat.is_finite()) {
            // Only reachable with absurd dt/inputs (overflow): restart there.
            self.state = Some(State {
                x_hat: x,
                dx_hat: DVec3::ZERO,
                x_prev_raw: x,
            });
            return self.current();
        }
        self.state = Some(State {
            x_hat,
            dx_hat,
            x_prev_raw: x,
        });
        self.current()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Prng;

    fn variance(v: &[f64]) -> f64 {
        let n = v.len() as f64;
        let m = v.iter().sum::<f64>() / n;
        v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / n
    }

    #[test]
    fn noise_variance_is_much_lower() {
        let mut rng = Prng::new(42);
        let mut f = OneEuroFilter::new(OneEuroParams::default());
        let dt = 1e-3;
        let c = DVec3::new(0.1, 1.7, -0.3);
        let sigma = 1e-3;
        let (mut raw, mut out) = (Vec::new(), Vec::new());
        for i in 0..5000 {
            let n = DVec3::new(rng.gaussian(), rng.gaussian(), rng.gaussian()) * sigma;
            let o = f.update(c + n, dt).expect("output");
            if i >= 1000 {
                raw.push(n.x);
                out.push(o.position.x - c.x);
            }
        }
        let (vr, vo) = (variance(&raw), variance(&out));
        assert!(vo < vr / 20.0, "raw {vr:e} filtered {vo:e}");
    }

    #[test]
    fn step_is_followed_with_bounded_lag() {
        let mut f = OneEuroFilter::new(OneEuroParams::default());
        let dt = 1e-3;
        for _ in 0..100 {
            f.update(DVec3::ZERO, dt);
        }
        let target = DVec3::new(0.5, 0.0, 0.0);
        let mut t_90 = None;
        for i in 1..=2000 {
            let o = f.update(target, dt).expect("output");
            assert!(o.position.x <= 0.5 + 1e-12, "no overshoot");
            if t_90.is_none() && o.position.x >= 0.45 {
                t_90 = Some(i as f64 * dt);
            }
        }
        let t_90 = t_90.expect("reaches 90%");
        // At rest alone (1 Hz) 90% would take ln(10)/(2π) ≈ 0.37 s; the speed
        // term must make it much faster.
        assert!(t_90 < 0.1, "90% rise time {t_90} s");
        let end = f.current().expect("state").position.x;
        assert!((end - 0.5).abs() < 1e-6);
    }

    #[test]
    fn ramp_velocity_is_recovered() {
        let mut f = OneEuroFilter::new(OneEuroParams::default());
        let v = DVec3::new(0.3, -0.1, 0.05);
        let mut rng = Prng::new(7);
        let mut last = None;
        let mut t = 0.0;
        for _ in 0..4000 {
            // Irregular dt between 0.5 and 1.5 ms.
            let dt = 1e-3 * (0.5 + rng.next_f64());
            t += dt;
            last = f.update(v * t, dt);
        }
        let o = last.expect("output");
        assert!((o.velocity - v).length() < 1e-3, "{:?}", o.velocity);
        // Lag of the position is bounded by the speed-dependent cutoff.
        assert!((o.position - v * t).length() < 0.05);
    }

    #[test]
    fn bad_dt_and_inputs_are_ignored() {
        let mut f = OneEuroFilter::new(OneEuroParams::default());
        assert!(f.update(DVec3::NAN, 0.01).is_none());
        let first = f.update(DVec3::ONE, 0.0).expect("first input passes");
        assert_eq!(first.position, DVec3::ONE);
        assert_eq!(first.velocity, DVec3::ZERO);
        for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let o = f.update(DVec3::splat(5.0), dt).expect("state");
            assert_eq!(o, first, "dt {dt} must not change the state");
        }
        let o = f.update(DVec3::splat(f64::INFINITY), 0.01).expect("state");
        assert_eq!(o, first);
        f.reset();
        assert!(f.current().is_none());
    }

    #[test]
    fn huge_gap_snaps_without_nan() {
        let mut f = OneEuroFilter::new(OneEuroParams::default());
        f.update(DVec3::ZERO, 0.01);
        let o = f.update(DVec3::X, 1e300).expect("output");
        assert!(o.position.is_finite() && o.velocity.is_finite());
        assert!((o.position.x - 1.0).abs() < 1e-9);
    }

    #[test]
    fn params_are_sanitized() {
        let p = OneEuroParams {
            min_cutoff: f64::NAN,
            beta: -1.0,
            d_cutoff: 0.0,
        }
        .sanitized();
        assert_eq!(p, OneEuroParams::default());
        let ok = OneEuroParams {
            min_cutoff: 2.0,
            beta: 0.0,
            d_cutoff: 3.0,
        };
        assert_eq!(ok.sanitized(), ok);
    }
}
