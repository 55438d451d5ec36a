//! Lorentz boosts in any direction, and velocity composition.

use glam::DVec3;

use super::{FourVector, ProperVelocity};

/// Frames (and, for velocities, bodies) slower than this proper speed
/// (γβ, β ≈ 0.71) are boosted in the textbook form, which keeps the digits
/// of small results; faster ones in light-cone form (see [`Boost::apply`]).
pub const DIRECT_FORM_BELOW: f64 = 1.0;

/// The Lorentz boost *into* the frame that moves with proper velocity
/// `frame` relative to the board (or to whichever frame the inputs are in).
///
/// Applying it to a 4-vector gives that vector's components in the moving
/// frame; [`Boost::inverse`] goes back. The transformation is carried out in
/// light-cone coordinates along the boost direction `n`:
///
/// ```text
/// (ct + x∥)' = e^{-η} (ct + x∥)      (ct − x∥)' = e^{+η} (ct − x∥)      x⊥' = x⊥
/// ```
///
/// with `e^{η} = γ + |u|` and `e^{-η} = 1/(γ + |u|)`, so no large terms are
/// subtracted: boost followed by inverse is the identity to a few ulps of
/// `|ct| + |x|` at any rapidity.
///
/// ```
/// use glam::DVec3;
/// use lightcone_engine::spacetime::{Boost, FourVector, ProperVelocity};
/// let boost = Boost::into_frame(ProperVelocity(DVec3::new(0.75, 0.0, 0.0))); // β = 0.6
/// let x = boost.apply(FourVector::new(1.0, DVec3::ZERO));
/// assert!((x.ct - 1.25).abs() < 1e-15 && (x.space.x + 0.75).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boost {
    /// Proper velocity of the target frame in the source frame.
    frame: ProperVelocity,
    /// Unit boost direction (zero for the identity).
    direction: DVec3,
    /// `e^{η} = γ + |u|`.
    exp_rapidity: f64,
    /// `|u|` and `γ` of the frame (read by every application's choice of
    /// form, so worked out once).
    speed: f64,
    gamma: f64,
}

impl Boost {
    /// The boost into the frame moving with proper velocity `frame`.
    ///
    /// Precondition: `frame` is finite (a non-finite one yields NaN output).
    #[must_use]
    pub fn into_frame(frame: ProperVelocity) -> Self {
        let speed = frame.0.length();
        let direction = if speed > 0.0 {
            frame.0 / speed
        } else {
            DVec3::ZERO
        };
        let gamma = frame.gamma();
        Self {
            frame,
            direction,
            exp_rapidity: gamma + speed,
            speed,
            gamma,
        }
    }

    /// The boost into the frame moving at `beta`; fails at `|β| ≥ 1`.
    pub fn try_into_frame_at_beta(beta: DVec3) -> Result<Self, crate::spacetime::SpeedError> {
        ProperVelocity::try_from_beta(beta).map(Self::into_frame)
    }

    /// The proper velocity of the target frame in the source frame.
    #[must_use]
    pub fn frame(&self) -> ProperVelocity {
        self.frame
    }

    /// The boost back: into the frame moving at `−u`.
    #[must_use]
    pub fn inverse(&self) -> Self {
        Self::into_frame(-self.frame)
    }

    /// Components of the 4-vector `x` in the target frame.
    ///
    /// Below `DIRECT_FORM_BELOW` (|u| < 1) the boost is computed in the
    /// textbook form `ct' = γ ct − |u| x∥`, `x∥' = γ x∥ − |u| ct`: in the
    /// light-cone form the small parallel result would be the difference of
    /// two numbers the size of `ct`, losing `ε |ct|` (10⁻⁷ m at c = 10⁹ m/s
    /// after one second); here `|u| ct` is a product and the result keeps
    /// its digits. Above, the light-cone form keeps them at any rapidity.
    #[must_use]
    pub fn apply(&self, x: FourVector) -> FourVector {
        let (ct, space) = self.form().apply(x.ct, x.space);
        FourVector::new(ct, space)
    }

    /// [`Self::apply`] to many 4-vectors held as arrays (`ct[i]`, `x[i]`,
    /// `y[i]`, `z[i]`; equal lengths), in place: the same operations per
    /// vector, the form chosen once, in a loop the compiler vectorises.
    #[inline(always)]
    pub fn apply_all(&self, ct: &mut [f64], x: &mut [f64], y: &mut [f64], z: &mut [f64]) {
        let form = self.form();
        let n = ct.len().min(x.len()).min(y.len()).min(z.len());
        for i in 0..n {
            let (t, s) = form.apply(ct[i], DVec3::new(x[i], y[i], z[i]));
            ct[i] = t;
            x[i] = s.x;
            y[i] = s.y;
            z[i] = s.z;
        }
    }

    /// The form [`Self::apply`] uses for this boost, with what it needs.
    #[inline(always)]
    fn form(&self) -> BoostForm {
        let speed = self.speed;
        BoostForm {
            direction: self.direction,
            direct: (speed < DIRECT_FORM_BELOW).then_some((self.gamma, speed)),
            exp_rapidity: self.exp_rapidity,
        }
    }

    /// The proper velocity, in the target frame, of a body whose proper
    /// velocity in the source frame is `u`: relativistic velocity
    /// composition (the paper's Eq. 4), stated for proper velocities.
    ///
    /// The 4-velocity `(γ, u)` is boosted in light-cone form, with
    /// `γ − u∥` computed as `(1 + u⊥²)/(γ + u∥)` when `u∥ > 0`, so even a
    /// body co-moving with a frame of γ = 10⁹ comes out at rest to within
    /// 1e-15 — and the result, being a proper velocity, is always below `c`.
    ///
    /// For a slow frame (|u_frame| < `DIRECT_FORM_BELOW`) and a slow body
    /// (|u| < 1) it is `u∥' = γ_f u∥ − |u_f| γ`: the light-cone form would
    /// take the small result as the difference of two numbers near 1,
    /// losing ε in absolute terms (a relative 10⁻⁷ at c = 10⁹ m/s, where
    /// a puck's γβ is 10⁻⁹).
    #[must_use]
    pub fn apply_velocity(&self, u: ProperVelocity) -> ProperVelocity {
        let n = self.direction;
        let parallel = n.dot(u.0);
        let perpendicular = u.0 - n * parallel;
        let gamma = u.gamma();
        let speed = self.speed;
        if speed < DIRECT_FORM_BELOW && u.0.length() < DIRECT_FORM_BELOW {
            let frame_gamma = self.gamma;
            return ProperVelocity(perpendicular + n * (frame_gamma * parallel - speed * gamma));
        }
        let transverse_mass_sq = 1.0 + perpendicular.length_squared();
        let (plus, minus) = if parallel >= 0.0 {
            (gamma + parallel, transverse_mass_sq / (gamma + parallel))
        } else {
            (transverse_mass_sq / (gamma - parallel), gamma - parallel)
        };
        let plus = plus / self.exp_rapidity;
        let minus = minus * self.exp_rapidity;
        ProperVelocity(perpendicular + n * (0.5 * (plus - minus)))
    }
}

/// [`Boost::apply`]'s arithmetic: the textbook form (`direct`: `γ` and
/// `|u|`) or the light-cone form.
#[derive(Clone, Copy)]
struct BoostForm {
    direction: DVec3,
    direct: Option<(f64, f64)>,
    exp_rapidity: f64,
}

impl BoostForm {
    #[inline(always)]
    fn apply(&self, ct: f64, space: DVec3) -> (f64, DVec3) {
        let n = self.direction;
        let parallel = n.dot(space);
        let perpendicular = space - n * parallel;
        if let Some((gamma, speed)) = self.direct {
            return (
                gamma * ct - speed * parallel,
                perpendicular + n * (gamma * parallel - speed * ct),
            );
        }
        let plus = (ct + parallel) / self.exp_rapidity;
        let minus = (ct - parallel) * self.exp_rapidity;
        (
            0.5 * (plus + minus),
            perpendicular + n * (0.5 * (plus - minus)),
        )
    }
}

/// Relativistic velocity composition: the board-frame proper velocity of a
/// body moving with `u_in_frame` inside a frame that itself moves with
/// `frame` relative to the board.
#[must_use]
pub fn compose(frame: ProperVelocity, u_in_frame: ProperVelocity) -> ProperVelocity {
    Boost::into_frame(-frame).apply_velocity(u_in_frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The paper's Eq. 4, in β form: velocity of a body `v` in the frame
    /// moving at `v0` (c = 1). Fine at moderate speeds, the reference here.
    fn paper_eq4(v: DVec3, v0: DVec3) -> DVec3 {
        let v0_sq = v0.length_squared();
        let gamma = 1.0 / (1.0 - v.length_squared()).sqrt();
        let par = v0 * (v.dot(v0) / v0_sq);
        let perp = v - par;
        (par - v0 + perp / gamma) / (1.0 - v.dot(v0))
    }

    #[test]
    fn matches_paper_eq4_at_moderate_speeds() {
        // Eq. 4 as printed divides v⊥ by γ of the body; the textbook form
        // divides by γ of the frame. Check ours against the textbook form
        // and record which one the paper's typesetting lost.
        let v = DVec3::new(0.3, 0.5, 0.0);
        let v0 = DVec3::new(0.6, -0.2, 0.0);
        let u = ProperVelocity::try_from_beta(v).unwrap();
        let frame = ProperVelocity::try_from_beta(v0).unwrap();
        let ours = Boost::into_frame(frame).apply_velocity(u).beta();
        let g0 = frame.gamma();
        let par = v0 * (v.dot(v0) / v0.length_squared());
        let textbook = (par - v0 + (v - par) / g0) / (1.0 - v.dot(v0));
        assert!((ours - textbook).length() < 1e-14, "{ours} vs {textbook}");
        // For the CM frame of equal masses (where Eq. 4 is used) both forms
        // agree only if γ = γ0; in general they differ: the paper's typo.
        assert!((paper_eq4(v, v0) - textbook).length() > 1e-3);
    }

    #[test]
    fn co_moving_body_is_at_rest_at_gamma_1e9() {
        let u = ProperVelocity(DVec3::new(3e8, -8e8, 0.0));
        let rest = Boost::into_frame(u).apply_velocity(u);
        assert!(rest.0.length() < 1e-6, "{:?}", rest);
        assert!(rest.gamma() - 1.0 < 1e-12);
    }

    fn arb_direction() -> impl Strategy<Value = DVec3> {
        (0.0..std::f64::consts::TAU, -1.0f64..1.0).prop_map(|(phi, z)| {
            let r = (1.0 - z * z).sqrt();
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        })
    }

    /// Proper velocities with γ spread log-uniformly over [1, 10⁹].
    fn arb_velocity() -> impl Strategy<Value = ProperVelocity> {
        (arb_direction(), 0.0f64..9.0).prop_map(|(n, log_gamma)| {
            let gamma = 10f64.powf(log_gamma);
            // |u| = √(γ² − 1) = √((γ − 1)(γ + 1)).
            ProperVelocity(n * ((gamma - 1.0) * (gamma + 1.0)).sqrt())
        })
    }

    fn arb_four_vector() -> impl Strategy<Value = FourVector> {
        (-1e3f64..1e3, -1e3f64..1e3, -1e3f64..1e3, -1e3f64..1e3)
            .prop_map(|(t, x, y, z)| FourVector::new(t, DVec3::new(x, y, z)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Boost then inverse is the identity on 4-vectors (events).
        ///
        /// Tolerance: 4 ε κ (|ct| + |x|) with κ = (γ + |u|)² = e^{2η}, the
        /// condition number of the boost. No Cartesian representation of the
        /// boosted event can do better: its light-cone component `ct − x∥`
        /// shrinks by e^{-η} and is then held only to ε of the larger one.
        /// Velocities, which the engine's state is made of, come back exact:
        /// see `velocity_boost_then_inverse_is_identity`.
        #[test]
        fn boost_then_inverse_is_identity(u in arb_velocity(), x in arb_four_vector()) {
            let b = Boost::into_frame(u);
            let back = b.inverse().apply(b.apply(x));
            let kappa = (u.gamma() + u.0.length()).powi(2);
            let tol = 4.0 * f64::EPSILON * kappa * (x.ct.abs() + x.space.length());
            prop_assert!((back.ct - x.ct).abs() <= tol);
            prop_assert!((back.space - x.space).length() <= tol);
        }

        /// Boost then inverse is the identity on proper velocities at every γ
        /// up to 10⁹ (frame and body each), along a coordinate axis: the
        /// 4-velocity is on its mass shell, so its small light-cone component
        /// is recomputed, not carried. Tolerance: 1e-14 relative to γ of the
        /// body, however large the intermediate γ (up to 10¹⁸).
        #[test]
        fn velocity_boost_then_inverse_is_identity(axis in 0usize..3, f in -21.0f64..21.0, e in -21.0f64..21.0, t in -1e3f64..1e3) {
            let n = DVec3::AXES[axis];
            let across = DVec3::AXES[(axis + 1) % 3];
            let b = Boost::into_frame(ProperVelocity::from_rapidity(n, f));
            let u = ProperVelocity(n * e.sinh() + across * t);
            let back = b.inverse().apply_velocity(b.apply_velocity(u));
            prop_assert!((back.0 - u.0).length() <= 1e-14 * u.gamma(), "{:?} vs {:?}", back, u);
        }

        /// The same in any direction. The intermediate velocity u', stored as
        /// Cartesian components, carries a rounding of a few ε |u'| that
        /// is parallel to the boost only to ε; the inverse boost amplifies
        /// its parallel part by up to e^η = γ_f + |u_f| (its condition
        /// number). Tolerance: 1e-14 γ + 16 ε |u'| e^η.
        #[test]
        fn velocity_boost_then_inverse_in_any_direction(f in arb_velocity(), u in arb_velocity()) {
            let b = Boost::into_frame(f);
            let mid = b.apply_velocity(u);
            let back = b.inverse().apply_velocity(mid);
            let amplification = f.gamma() + f.0.length();
            let tol = 1e-14 * u.gamma() + 16.0 * f64::EPSILON * mid.0.length() * amplification;
            prop_assert!((back.0 - u.0).length() <= tol, "{:?} vs {:?}", back, u);
        }

        /// The interval is invariant; tolerance 1e-13 relative to the larger
        /// Euclidean norm ct² + |x|² of the two frames (the interval is a
        /// difference of squares, so that is its natural error scale).
        #[test]
        fn interval_is_invariant(u in arb_velocity(), x in arb_four_vector()) {
            let y = Boost::into_frame(u).apply(x);
            let scale = x.euclidean_norm_squared().max(y.euclidean_norm_squared());
            prop_assert!((y.interval() - x.interval()).abs() <= 1e-13 * scale,
                "{} vs {} (scale {})", y.interval(), x.interval(), scale);
        }

        /// Composition never reaches c, and by how much it stays below is
        /// the closed form's: γ of the composite is `γ_a γ_b + u_a·u_b`
        /// (the product of the two 4-velocities), so with `γ − 1` formed
        /// without cancellation, `(γ_a−1)(γ_b−1) + (γ_a−1) + (γ_b−1) +
        /// u_a·u_b`, 1 − |β| is `1/(γ(γ + √((γ − 1)(γ + 1))))`; for two
        /// velocities each up to γ = 10⁹ (combined γ up to ~10¹⁸).
        /// Tolerance: 1e-13 times the closed form's condition number, the
        /// sum of the magnitudes of its terms over `γ − 1` (1 when the
        /// velocities are not opposed; large only for nearly opposite
        /// ones, where the sum cancels).
        #[test]
        fn composition_never_reaches_c(a in arb_velocity(), b in arb_velocity()) {
            let w = compose(a, b);
            prop_assert!(w.is_finite());
            let (ga, gb) = (a.gamma_minus_one(), b.gamma_minus_one());
            let dot = a.0.dot(b.0);
            let gm1 = ga * gb + ga + gb + dot;
            let condition = (ga * gb + ga + gb + dot.abs()) / gm1.abs();
            let gamma = 1.0 + gm1;
            prop_assert!((w.gamma() / gamma - 1.0).abs() <= 1e-13 * condition,
                "γ {} vs closed form {} (condition {})", w.gamma(), gamma, condition);
            let u = (gm1.max(0.0) * (gamma + 1.0)).sqrt();
            let deficit = 1.0 / (gamma * (gamma + u));
            prop_assert!((w.speed_deficit() / deficit - 1.0).abs() <= 1e-13 * condition,
                "1 − |β| {} vs closed form {} (condition {})", w.speed_deficit(), deficit, condition);
        }

        /// Collinear composition along a coordinate axis adds rapidities;
        /// tolerance 1e-12 relative to the larger rapidity (η ≤ 21 at γ = 10⁹).
        #[test]
        fn collinear_rapidities_add(axis in 0usize..3, e1 in -21.0f64..21.0, e2 in -21.0f64..21.0) {
            let n = DVec3::AXES[axis];
            let w = compose(ProperVelocity::from_rapidity(n, e1), ProperVelocity::from_rapidity(n, e2));
            let signed = w.rapidity() * w.0.dot(n).signum();
            prop_assert!((signed - (e1 + e2)).abs() <= 1e-12 * e1.abs().max(e2.abs()).max(1.0),
                "{} vs {}", signed, e1 + e2);
        }

        /// The same in any direction. A direction off the axes is itself
        /// rounded, by ε, and a transverse error passes through a boost
        /// unreduced, so the tolerance is 1e-12 |w| + 4 ε (|u₁| + |u₂|).
        #[test]
        fn collinear_composition_in_any_direction(n in arb_direction(), e1 in -21.0f64..21.0, e2 in -21.0f64..21.0) {
            let (a, b) = (ProperVelocity::from_rapidity(n, e1), ProperVelocity::from_rapidity(n, e2));
            let w = compose(a, b);
            let expected = n * (e1 + e2).sinh();
            let tol = 1e-12 * expected.length() + 4.0 * f64::EPSILON * (a.0.length() + b.0.length());
            prop_assert!((w.0 - expected).length() <= tol, "{:?} vs {}", w, expected);
        }

        /// The velocity boost agrees with boosting the 4-vector (γ, u) as an
        /// event; tolerance 1e-12 relative to γ γ_frame (the 4-velocity's
        /// size after the boost).
        #[test]
        fn velocity_boost_is_four_vector_boost(u in arb_velocity(), f in arb_velocity()) {
            let b = Boost::into_frame(f);
            let as_event = b.apply(FourVector::new(u.gamma(), u.0));
            let direct = b.apply_velocity(u);
            let scale = u.gamma() * f.gamma();
            prop_assert!((as_event.space - direct.0).length() <= 1e-12 * scale);
        }
    }
}
