//! Events (board time and place) and 4-vectors.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A point of spacetime in the board frame: board (coordinate) time `t` in
/// seconds and position in metres (origin at a table corner, z up).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Board-frame coordinate time, seconds.
    pub t: f64,
    /// Board-frame position, metres.
    pub position: DVec3,
}

impl Event {
    /// An event at board time `t` and position `position`.
    #[must_use]
    pub const fn new(t: f64, position: DVec3) -> Self {
        Self { t, position }
    }

    /// The displacement from `self` to `later` as a 4-vector `(cΔt, Δx)` in
    /// metres. Differences are taken before scaling, so nearby events keep
    /// their digits whatever their absolute time.
    #[must_use]
    pub fn separation_to(self, later: Event, c: f64) -> FourVector {
        FourVector::new(c * (later.t - self.t), later.position - self.position)
    }

    /// Squared interval `Δs² = c²Δt² − |Δx|²` (time-like positive, the
    /// paper's Eq. 1) to `other`, in m². Zero on a light cone.
    #[must_use]
    pub fn interval_to(self, other: Event, c: f64) -> f64 {
        self.separation_to(other, c).interval()
    }

    /// Whether both coordinates are finite.
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.t.is_finite() && self.position.is_finite()
    }

    /// Whether light sent from `self` has reached `eye` (its event: where
    /// and when it looks): `eye` lies on or inside the future light cone of
    /// `self`, `c (t_eye − t) ≥ |x_eye − x|` (board frame, c in m/s). For
    /// an eye at rest at `x_eye` this holds from `t + |x_eye − x| / c` on;
    /// for a moving eye, from the event where its worldline leaves the
    /// light cone's inside, whatever it did before. Compared without
    /// squaring, so a grazing case is decided to the last few ulps of the
    /// distance.
    #[must_use]
    pub fn light_has_reached(self, eye: Event, c: f64) -> bool {
        let dt = eye.t - self.t;
        dt >= 0.0 && c * dt >= (eye.position - self.position).length()
    }
}

/// A 4-vector `(ct, x)` in metres: a separation of events, or any vector
/// that transforms like one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct FourVector {
    /// Time component times `c`, metres.
    pub ct: f64,
    /// Space components, metres.
    pub space: DVec3,
}

impl FourVector {
    /// The 4-vector `(ct, space)`.
    #[must_use]
    pub const fn new(ct: f64, space: DVec3) -> Self {
        Self { ct, space }
    }

    /// The Minkowski square `ct² − |x|²` (time-like positive).
    ///
    /// Formed as `(ct − |x|)(ct + |x|)`, which is exact on the light cone;
    /// near it the result still carries an absolute error of a few ulps of
    /// `ct² + |x|²`, as any difference of squares must.
    #[must_use]
    pub fn interval(self) -> f64 {
        let r = self.space.length();
        (self.ct - r) * (self.ct + r)
    }

    /// The Euclidean size `ct² + |x|²`, the scale against which the error of
    /// [`Self::interval`] is stated.
    #[must_use]
    pub fn euclidean_norm_squared(self) -> f64 {
        self.ct * self.ct + self.space.length_squared()
    }

    /// The board event reached from `origin` by this separation.
    #[must_use]
    pub fn from_event(self, origin: Event, c: f64) -> Event {
        Event::new(origin.t + self.ct / c, origin.position + self.space)
    }

    /// Whether every component is finite.
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.ct.is_finite() && self.space.is_finite()
    }
}

impl core::ops::Add for FourVector {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self::new(self.ct + rhs.ct, self.space + rhs.space)
    }
}

impl core::ops::Sub for FourVector {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self::new(self.ct - rhs.ct, self.space - rhs.space)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn light_signal_has_zero_interval() {
        let c = 1.42;
        let a = Event::new(1.0, DVec3::ZERO);
        let b = Event::new(3.0, DVec3::new(0.0, 2.0 * c, 0.0));
        assert_eq!(a.interval_to(b, c), 0.0);
        assert!(a.interval_to(Event::new(3.0, DVec3::ZERO), c) > 0.0);
    }

    #[test]
    fn light_reaches_a_resting_eye_after_the_distance_over_c() {
        // An eye 3-4-0 from the event: 5 m, at c = 2 m/s, 2.5 s later.
        let c = 2.0;
        let sent = Event::new(10.0, DVec3::new(1.0, 1.0, 0.0));
        let eye = DVec3::new(4.0, 5.0, 0.0);
        let arrival = 10.0 + 5.0 / c;
        assert!(!sent.light_has_reached(Event::new(arrival - 1e-9, eye), c));
        assert!(sent.light_has_reached(Event::new(arrival, eye), c));
        assert!(sent.light_has_reached(Event::new(arrival + 7.0, eye), c));
        // Never before it was sent, even at the same place.
        assert!(!sent.light_has_reached(Event::new(9.0, sent.position), c));
        assert!(sent.light_has_reached(sent, c));
        // A NaN eye is never reached.
        assert!(!sent.light_has_reached(Event::new(f64::NAN, eye), c));
    }

    #[test]
    fn separation_is_formed_before_scaling() {
        // Times 1 ms apart, a day into the run: the difference is exact.
        let a = Event::new(86_400.0, DVec3::ZERO);
        let b = Event::new(86_400.001, DVec3::X);
        let s = a.separation_to(b, 1e3);
        assert!((s.ct - 1.0).abs() < 1e-8, "{}", s.ct);
        assert_eq!(s.from_event(a, 1e3).t, b.t);
    }
}
