//! 4-momentum of bodies and systems of bodies.

use glam::DVec3;

use super::{Boost, ProperVelocity};

/// 4-momentum in mass units: `energy = γ m` (that is `E / c²`, kg) and
/// `momentum = m u` (that is `p / c`, kg). Multiply by `c²` and `c` for SI.
///
/// Mass units keep `c` out of the engine's state: a scene can change `c`
/// without touching any momentum.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FourMomentum {
    /// `E / c² = γ m`, kg.
    pub energy: f64,
    /// `p / c = m u`, kg.
    pub momentum: DVec3,
}

impl FourMomentum {
    /// The 4-momentum of a body of rest mass `mass` (kg) moving with proper
    /// velocity `u`.
    #[must_use]
    pub fn of_body(mass: f64, u: ProperVelocity) -> Self {
        Self {
            energy: mass * u.gamma(),
            momentum: u.0 * mass,
        }
    }

    /// Invariant (rest) mass `√(E² − p²)`, kg.
    ///
    /// Formed as `√((E − |p|)(E + |p|))`. For a single ultra-relativistic
    /// body `E − |p|` cancels: keep the body's own rest mass instead. For a
    /// pair use [`FourMomentum::pair_invariant_mass`], which is exact.
    #[must_use]
    pub fn invariant_mass(self) -> f64 {
        let p = self.momentum.length();
        ((self.energy - p) * (self.energy + p)).max(0.0).sqrt()
    }

    /// Invariant mass of two bodies, `M² = m₁² + m₂² + 2 m₁ m₂ γ_rel`, with
    /// the relative Lorentz factor `γ_rel` taken from the boosted proper
    /// velocity, so no cancellation happens even when both bodies move at
    /// γ = 10⁹ side by side.
    #[must_use]
    pub fn pair_invariant_mass(m1: f64, u1: ProperVelocity, m2: f64, u2: ProperVelocity) -> f64 {
        let gamma_rel = Boost::into_frame(u1).apply_velocity(u2).gamma();
        (m1 * m1 + m2 * m2 + 2.0 * m1 * m2 * gamma_rel).sqrt()
    }

    /// The proper velocity of the frame in which this total momentum
    /// vanishes (the centre-of-momentum frame), given the system's invariant
    /// mass (`u = p / M`; equal to the paper's Eq. 3 for `β = p / E`).
    #[must_use]
    pub fn centre_of_momentum_velocity(self, invariant_mass: f64) -> ProperVelocity {
        ProperVelocity(self.momentum / invariant_mass)
    }

    /// The same 4-momentum in another frame.
    #[must_use]
    pub fn boosted(self, boost: &Boost) -> Self {
        let f = boost.apply(crate::spacetime::FourVector::new(
            self.energy,
            self.momentum,
        ));
        Self {
            energy: f.ct,
            momentum: f.space,
        }
    }
}

impl core::ops::Sub for FourMomentum {
    type Output = Self;
    fn sub(self, rhs: Self) -> Self {
        Self {
            energy: self.energy - rhs.energy,
            momentum: self.momentum - rhs.momentum,
        }
    }
}

impl core::ops::Add for FourMomentum {
    type Output = Self;
    fn add(self, rhs: Self) -> Self {
        Self {
            energy: self.energy + rhs.energy,
            momentum: self.momentum + rhs.momentum,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_of_momentum_frame_has_zero_momentum() {
        let (m1, m2) = (0.2, 0.3);
        let u1 = ProperVelocity(DVec3::new(3.0, 1.0, 0.0));
        let u2 = ProperVelocity(DVec3::new(-0.5, 2.0, 0.0));
        let total = FourMomentum::of_body(m1, u1) + FourMomentum::of_body(m2, u2);
        let m = FourMomentum::pair_invariant_mass(m1, u1, m2, u2);
        assert!((m - total.invariant_mass()).abs() < 1e-13 * m);
        let boost = Boost::into_frame(total.centre_of_momentum_velocity(m));
        let cm = total.boosted(&boost);
        assert!(cm.momentum.length() < 1e-13 * total.energy);
        assert!((cm.energy - m).abs() < 1e-13 * total.energy);
    }

    #[test]
    fn paper_eq3_is_the_equal_mass_cm_velocity() {
        // Eq. 3: v0 = (γ1 v1 + γ2 v2) / (γ1 + γ2) for equal masses.
        let u1 = ProperVelocity::try_from_beta(DVec3::new(0.9, 0.0, 0.0)).unwrap();
        let u2 = ProperVelocity::try_from_beta(DVec3::new(0.0, -0.5, 0.0)).unwrap();
        let eq3 = (u1.0 + u2.0) / (u1.gamma() + u2.gamma());
        let total = FourMomentum::of_body(1.0, u1) + FourMomentum::of_body(1.0, u2);
        let m = FourMomentum::pair_invariant_mass(1.0, u1, 1.0, u2);
        let ours = total.centre_of_momentum_velocity(m).beta();
        assert!((ours - eq3).length() < 1e-15);
    }

    #[test]
    fn side_by_side_at_gamma_1e9_has_twice_the_rest_mass() {
        let u = ProperVelocity(DVec3::new(1e9, 0.0, 0.0));
        let m = FourMomentum::pair_invariant_mass(1.0, u, 1.0, u);
        assert!((m - 2.0).abs() < 1e-15);
    }
}
