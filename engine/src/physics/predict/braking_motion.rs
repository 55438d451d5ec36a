//! A puck's motion on one braking, uniform or rest segment, with its
//! braking law worked out once: what the braking pair search's probes and
//! the pair frame's kicks read at many board times
//! ([`super::braking`], [`super::braking_kicks`]).

use glam::DVec3;

use crate::physics::overlap;
use crate::spacetime::ProperVelocity;
use crate::worldline::Segment;

/// A puck's motion on one segment, for the probes of one search: the
/// braking law worked out once, then per board time one square root.
pub(super) struct Motion<'a> {
    pub(super) segment: &'a Segment,
    pub(super) law: crate::worldline::sliding::Braking,
    /// `a/c`, 1/s (0 unless braking).
    rate: f64,
}

/// Where a puck is and how it moves at one board time ([`Motion::at`]).
pub(super) struct MotionState {
    pub(super) position: DVec3,
    pub(super) velocity: DVec3,
    /// Its board shape there (the tangent segment's).
    pub(super) outline: overlap::Outline,
    /// How fast `1/γ` grows there, 1/s: `(a/c) u/γ³` while braking, 0
    /// before the segment begins, at rest or moving uniformly.
    pub(super) inverse_gamma_rate: f64,
}

impl<'a> Motion<'a> {
    pub(super) fn of(segment: &'a Segment) -> Self {
        let braking = segment.is_braking();
        Self {
            segment,
            law: segment.braking_law(),
            rate: if braking {
                segment.deceleration() / segment.speed_of_light()
            } else {
                0.0
            },
        }
    }

    /// [`Segment::stop_time`], to the bit, from the law worked out once.
    pub(super) fn stop_time(&self) -> Option<f64> {
        let s = self.segment;
        s.is_braking().then(|| s.start.t + self.law.stop_time())
    }

    /// [`Segment::position_at`], to the bit, from the law worked out once.
    pub(super) fn position_at(&self, t: f64) -> DVec3 {
        let s = self.segment;
        let dt = t - s.start.t;
        if self.rate == 0.0 || dt <= 0.0 {
            return s.position_at(t);
        }
        s.start.position + s.direction() * self.law.distance_at(dt)
    }

    /// [`Segment::u_at`], to the bit, from the law worked out once.
    pub(super) fn u_at(&self, t: f64) -> ProperVelocity {
        let s = self.segment;
        let dt = t - s.start.t;
        if self.rate == 0.0 || dt <= 0.0 {
            return s.u_at(t);
        }
        ProperVelocity(s.direction() * self.law.proper_speed_at(dt))
    }

    /// How fast the proper velocity changes at board time `t`, 1/s
    /// (`du/dt`, `u` dimensionless): `−(a/c)` along the direction while
    /// braking (the proper speed falls linearly in board time,
    /// [`crate::worldline::sliding`]), zero before the segment begins, from
    /// its stop on, at rest or moving uniformly.
    pub(super) fn u_rate_at(&self, t: f64) -> DVec3 {
        let dt = t - self.segment.start.t;
        if self.rate == 0.0 || dt <= 0.0 || dt >= self.law.stop_time() {
            return DVec3::ZERO;
        }
        -self.segment.direction() * self.rate
    }

    /// [`Segment::velocity_at`], to the bit, from the law worked out once.
    pub(super) fn velocity_at(&self, t: f64) -> DVec3 {
        if self.rate == 0.0 {
            return self.segment.velocity_at(t);
        }
        self.u_at(t).velocity(self.law.c)
    }

    /// The state at board time `t`: the values of [`Segment::position_at`],
    /// [`Segment::velocity_at`] and the tangent's shape, to rounding.
    pub(super) fn at(&self, t: f64, radius: f64) -> MotionState {
        let s = self.segment;
        let dt = t - s.start.t;
        if self.rate == 0.0 || dt <= 0.0 {
            return MotionState {
                position: s.position_at(t),
                velocity: s.velocity(),
                outline: overlap::Outline::along(
                    s.direction(),
                    1.0 / s.gamma(),
                    radius,
                    s.velocity(),
                ),
                inverse_gamma_rate: 0.0,
            };
        }
        let law = &self.law;
        let moving = dt.min(law.stop_time());
        let u = law.proper_speed_at(moving);
        let gamma = (1.0 + u * u).sqrt();
        let distance = law.c * moving * (law.u0 + u) / (law.gamma0() + gamma);
        let velocity = s.direction() * (law.c * u / gamma);
        let inverse_gamma = gamma.recip();
        MotionState {
            position: s.start.position + s.direction() * distance,
            velocity,
            outline: overlap::Outline::along(
                if u > 0.0 { s.direction() } else { DVec3::ZERO },
                inverse_gamma,
                radius,
                velocity,
            ),
            inverse_gamma_rate: self.rate * u * inverse_gamma * inverse_gamma * inverse_gamma,
        }
    }
}
