//! Proper velocity `u = γβ`, the engine's way of stating how a body moves.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Why a speed given as `β` or in m/s cannot be turned into a proper velocity.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum SpeedError {
    /// A component is NaN or infinite.
    #[error("velocity has a component that is not a finite number")]
    NotFinite,
    /// `|β| ≥ 1`: a body cannot reach the speed of light.
    #[error("speed |β| = {0} is not below the speed of light (|β| must be < 1)")]
    AtOrAboveLight(f64),
    /// The speed of light itself is not a positive finite number.
    #[error("speed of light c = {0} must be a positive finite number of m/s")]
    BadSpeedOfLight(f64),
}

/// Proper velocity `u = γ v / c` in the board frame (dimensionless).
///
/// This is the engine's exact state of motion: every `u ∈ ℝ³` is a valid
/// sub-luminal velocity, impulses add to it linearly (momentum is `m c u`),
/// and `γ = √(1 + u²)` loses no digits at any speed. `β = u / γ` is derived,
/// for reading only: at γ above about 10⁸ its length rounds to 1.0 in f64,
/// which is why [`ProperVelocity::speed_deficit`] exists.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct ProperVelocity(pub DVec3);

impl ProperVelocity {
    /// At rest.
    pub const ZERO: Self = Self(DVec3::ZERO);

    /// The proper velocity of a body moving at `beta = v / c`.
    ///
    /// Fails if a component is not finite or if `|β| ≥ 1`. Precision: `γ` is
    /// formed as `1 / √((1 − |β|)(1 + |β|))`, exact to a few ulps of the
    /// *input*; but `β` itself cannot state speeds closer to `c` than about
    /// 1e-16, so give `u` directly for γ beyond ~10⁷.
    pub fn try_from_beta(beta: DVec3) -> Result<Self, SpeedError> {
        if !beta.is_finite() {
            return Err(SpeedError::NotFinite);
        }
        let b = beta.length();
        if b >= 1.0 {
            return Err(SpeedError::AtOrAboveLight(b));
        }
        let gamma = 1.0 / ((1.0 - b) * (1.0 + b)).sqrt();
        Ok(Self(beta * gamma))
    }

    /// The proper velocity of a body moving at `velocity` (m/s) when light
    /// travels at `c` (m/s). Fails as [`Self::try_from_beta`] does, or if `c`
    /// is not a positive finite number.
    pub fn try_from_velocity(velocity: DVec3, c: f64) -> Result<Self, SpeedError> {
        if !(c.is_finite() && c > 0.0) {
            return Err(SpeedError::BadSpeedOfLight(c));
        }
        Self::try_from_beta(velocity / c)
    }

    /// A proper velocity of rapidity `eta` along the unit vector `direction`.
    #[must_use]
    pub fn from_rapidity(direction: DVec3, eta: f64) -> Self {
        Self(direction * eta.sinh())
    }

    /// Lorentz factor `γ = √(1 + u²)`, correctly rounded to within an ulp;
    /// beyond |u| = 1e150, where `u²` would overflow, γ = |u| exactly in f64.
    #[inline]
    #[must_use]
    pub fn gamma(self) -> f64 {
        let u_sq = self.0.length_squared();
        if u_sq < 1e300 {
            (1.0 + u_sq).sqrt()
        } else {
            self.0.length()
        }
    }

    /// `γ − 1 = u² / (γ + 1)`, exact also in the classical limit where the
    /// subtraction would leave nothing (β = 1e-9 gives 5e-19, not 0).
    #[inline]
    #[must_use]
    pub fn gamma_minus_one(self) -> f64 {
        self.0.length_squared() / (self.gamma() + 1.0)
    }

    /// `β = v / c = u / γ`. Its length rounds to 1.0 for γ ≳ 10⁸; use
    /// [`Self::speed_deficit`] to tell such speeds apart.
    #[inline]
    #[must_use]
    pub fn beta(self) -> DVec3 {
        self.0 / self.gamma()
    }

    /// Board-frame velocity in m/s for a speed of light `c` in m/s.
    #[inline]
    #[must_use]
    pub fn velocity(self, c: f64) -> DVec3 {
        self.beta() * c
    }

    /// `1 − |β| = 1 / (γ (γ + |u|))`: how far below `c` the body is, with full
    /// relative precision at any γ (1e-18 at γ = 10⁹, where `1 − |β|` in f64
    /// is 0).
    #[inline]
    #[must_use]
    pub fn speed_deficit(self) -> f64 {
        let g = self.gamma();
        1.0 / (g * (g + self.0.length()))
    }

    /// Rapidity `η = asinh |u|`; collinear rapidities add.
    #[inline]
    #[must_use]
    pub fn rapidity(self) -> f64 {
        self.0.length().asinh()
    }

    /// Whether every component is finite.
    #[inline]
    #[must_use]
    pub fn is_finite(self) -> bool {
        self.0.is_finite()
    }
}

impl core::ops::Add for ProperVelocity {
    type Output = Self;
    /// Adding proper velocities is adding momenta per unit mass (an impulse),
    /// not composing velocities: see [`crate::spacetime::Boost`] for that.
    fn add(self, rhs: Self) -> Self {
        Self(self.0 + rhs.0)
    }
}

impl core::ops::Neg for ProperVelocity {
    type Output = Self;
    fn neg(self) -> Self {
        Self(-self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beta_round_trips_and_gamma_matches_textbook() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.6, 0.0, 0.0)).unwrap();
        assert!((u.gamma() - 1.25).abs() < 1e-15);
        assert!((u.0.x - 0.75).abs() < 1e-15);
        assert!((u.beta().x - 0.6).abs() < 1e-15);
    }

    #[test]
    fn light_speed_and_nan_are_refused() {
        assert_eq!(
            ProperVelocity::try_from_beta(DVec3::X),
            Err(SpeedError::AtOrAboveLight(1.0))
        );
        assert!(ProperVelocity::try_from_beta(DVec3::new(0.8, 0.7, 0.0)).is_err());
        assert_eq!(
            ProperVelocity::try_from_beta(DVec3::new(f64::NAN, 0.0, 0.0)),
            Err(SpeedError::NotFinite)
        );
        assert!(ProperVelocity::try_from_velocity(DVec3::X, 0.0).is_err());
        assert!(ProperVelocity::try_from_velocity(DVec3::X * 3.0, 2.0).is_err());
    }

    #[test]
    fn classical_limit_keeps_gamma_minus_one() {
        let u = ProperVelocity(DVec3::new(1e-9, 0.0, 0.0));
        assert_eq!(u.gamma(), 1.0);
        // γ − 1 = u²/2 − u⁴/8 …: 5e-19 to 1e-15 relative.
        assert!((u.gamma_minus_one() / 5e-19 - 1.0).abs() < 1e-15);
    }

    #[test]
    fn ultra_relativistic_speed_deficit_is_resolved() {
        // γ = 10⁹: 1 − β ≈ 1/(2γ²) = 5e-19, invisible in β itself.
        let u = ProperVelocity(DVec3::new(1e9, 0.0, 0.0));
        assert_eq!(u.beta().length(), 1.0);
        assert!((u.speed_deficit() / 5e-19 - 1.0).abs() < 1e-12);
        assert!((u.rapidity() - (2e9f64).ln()).abs() < 1e-12);
    }
}
