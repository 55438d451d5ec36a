//! A puck sliding on the cloth: constant sliding friction in the board frame,
//! in closed form.
//!
//! The cloth is at rest on the board, so friction is stated there: a puck
//! sliding with velocity `v` feels `dp/dt = −μ m g v̂` (Coulomb friction,
//! normal force `m g` from the board). With `p = m c u` (`u = γβ`, the
//! dimensionless proper velocity) and the force along `−v̂`, the path is a
//! straight line and the proper speed falls linearly in **board** time:
//!
//! ```text
//! u(t) = u₀ − a t / c,      a = μ g   (m/s²),   until t_stop = c u₀ / a.
//! ```
//!
//! For motion along a line `c du/dt = γ³ dv/dt` is the proper acceleration,
//! so the centre has constant proper deceleration `a`: its worldline is a
//! hyperbola in `(t, s)` (board time, distance along the path),
//!
//! ```text
//! (s − s_h)² − c² (t − t_h)² = K²,    K = c²/a,   s_h = K γ₀,   t_h = t_stop,
//! ```
//!
//! whose apex `(t_h, s_h − K)` is where the puck comes to rest. In forms that
//! keep their digits from the Newtonian limit (`a → 0`, `c → ∞`) to γ = 10⁸:
//!
//! ```text
//! s(t) = K (γ₀ − γ)        = c t (u₀ + u) / (γ₀ + γ)           (distance)
//! s_stop = K (γ₀ − 1)      = (c²/a) u₀² / (γ₀ + 1)
//! τ(t) = (c/a) (asinh u₀ − asinh u)  = (c/a) asinh(u₀γ − uγ₀)      (proper time)
//! u₀γ − uγ₀ = δ (1 + (1 + u₀² + u²)/(γ₀γ + u₀u)) / (γ₀ + γ),   δ = a t / c
//! ```
//!
//! (the last from `sinh(A − B)` and `γ₀γ − u₀u = (1 + u₀² + u²)/(γ₀γ + u₀u)`).
//!
//! ## The body: Born-rigid braking
//!
//! A rigid puck cannot have every point decelerate alike (that would stretch
//! it in its own frame: Bell's spaceship paradox). The puck here brakes
//! *Born-rigidly* about its centre: every material point at rest-frame offset
//! `r∥` along the motion follows the hyperbola with the **same** centre
//! `(s_h, t_h)` and `K′ = K − r∥` (the front, nearer the Rindler horizon
//! ahead, brakes harder). So
//!
//! * every point stops at the same board time `t_stop`, and the resting puck
//!   has exactly its rest shape;
//! * a point's offset from the centre along the motion, in the board frame at
//!   board time `t`, is, with `ρ = r∥ a / c²`,
//!
//!   ```text
//!   Δs(t) = r∥ (2 − ρ) / (γ + √((1 − ρ)² + u²)),
//!   ```
//!
//!   which is `r∥/γ`, the Lorentz contraction, when `a → 0`, and `r∥` at rest;
//! * a point's proper speed is `u / (1 − ρ)`, its proper deceleration
//!   `a / (1 − ρ)`: every point moves on a hyperbola of its own, so the
//!   emission event of any vertex is a closed form
//!   ([`Braking::emission_time`]).
//!
//! Born rigidity needs `r∥ < K` for every point: a puck of radius
//! `R ≥ c²/(μ g)` cannot be stopped rigidly by friction
//! ([`RigidityError`]). Offsets across the motion do not change.

use glam::DVec3;

/// A point of a body cannot brake Born-rigidly: it lies at or beyond the
/// Rindler horizon of the braking (`r∥ ≥ c²/a`).
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "a point {offset} m ahead of the centre cannot brake rigidly at {deceleration} m/s² \
     with c = {c} m/s: the body must be shorter than c²/a = {horizon} m"
)]
pub struct RigidityError {
    /// Rest-frame offset of the point along the motion, m.
    pub offset: f64,
    /// The centre's proper deceleration, m/s².
    pub deceleration: f64,
    /// Speed of light, m/s.
    pub c: f64,
    /// `c²/a`, m.
    pub horizon: f64,
}

/// The motion of one material point under constant proper deceleration,
/// along a straight path, from board time 0 (the segment's start, where it
/// has proper speed `u0`) until it rests at [`Self::stop_time`].
///
/// Units: `u0` dimensionless (`γβ`, ≥ 0), `deceleration` m/s² (≥ 0; 0 is
/// uniform motion), `c` m/s; times are board seconds from the segment start,
/// distances metres along the direction of motion.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Braking {
    /// Proper speed at the segment start, `γ₀β₀`.
    pub u0: f64,
    /// Proper deceleration `a` (for the centre, `μ g`), m/s².
    pub deceleration: f64,
    /// Speed of light, m/s.
    pub c: f64,
    gamma0: f64,
}

impl Braking {
    /// The centre's braking: proper speed `u0 ≥ 0`, deceleration `a ≥ 0`.
    #[must_use]
    pub fn new(u0: f64, deceleration: f64, c: f64) -> Self {
        Self {
            u0,
            deceleration,
            c,
            gamma0: (1.0 + u0 * u0).sqrt(),
        }
    }

    /// `γ` at the segment start.
    #[inline]
    #[must_use]
    pub fn gamma0(&self) -> f64 {
        self.gamma0
    }

    /// Board time at which the point comes to rest, `c u₀ / a` (∞ without
    /// friction, 0 for a point already at rest).
    #[must_use]
    pub fn stop_time(&self) -> f64 {
        if self.u0 == 0.0 {
            0.0
        } else if self.deceleration == 0.0 {
            f64::INFINITY
        } else {
            self.c * self.u0 / self.deceleration
        }
    }

    /// Proper speed at board time `t` (clamped to `[0, t_stop]`).
    #[inline]
    #[must_use]
    pub fn proper_speed_at(&self, t: f64) -> f64 {
        (self.u0 - self.deceleration * t.max(0.0) / self.c).max(0.0)
    }

    /// `γ` at board time `t`.
    #[inline]
    #[must_use]
    pub fn gamma_at(&self, t: f64) -> f64 {
        let u = self.proper_speed_at(t);
        (1.0 + u * u).sqrt()
    }

    /// Distance travelled along the path by board time `t`, m:
    /// `c t (u₀ + u)/(γ₀ + γ)`, constant after the stop.
    #[must_use]
    pub fn distance_at(&self, t: f64) -> f64 {
        let t = t.clamp(0.0, self.stop_time());
        if t == 0.0 {
            return 0.0;
        }
        if t.is_infinite() {
            return f64::INFINITY;
        }
        let u = self.proper_speed_at(t);
        let g = (1.0 + u * u).sqrt();
        self.c * t * (self.u0 + u) / (self.gamma0 + g)
    }

    /// Board speed at time `t`, m/s.
    #[must_use]
    pub fn speed_at(&self, t: f64) -> f64 {
        let u = self.proper_speed_at(t);
        self.c * u / (1.0 + u * u).sqrt()
    }

    /// Stopping distance `(c²/a)(γ₀ − 1) = (c²/a) u₀²/(γ₀ + 1)`, m
    /// (∞ without friction).
    #[must_use]
    pub fn stopping_distance(&self) -> f64 {
        self.distance_at(self.stop_time())
    }

    /// The point's proper time elapsed by board time `t` (from the segment
    /// start), s: `(c/a)(asinh u₀ − asinh u)` in its cancellation-free form;
    /// after the stop proper time runs at the board's rate.
    #[must_use]
    pub fn proper_time_at(&self, t: f64) -> f64 {
        let t = t.max(0.0);
        let moving = t.min(self.stop_time());
        let rest = t - moving;
        if moving == 0.0 {
            return rest;
        }
        if self.deceleration == 0.0 {
            return moving / self.gamma0 + rest;
        }
        let u0 = self.u0;
        let u = self.proper_speed_at(moving);
        let g = (1.0 + u * u).sqrt();
        let g0 = self.gamma0;
        let delta = self.deceleration * moving / self.c;
        let cosh_diff = (1.0 + u0 * u0 + u * u) / (g0 * g + u0 * u);
        let sinh_diff = delta * (1.0 + cosh_diff) / (g0 + g);
        // asinh x / x → 1 as the deceleration vanishes: no c/a blow-up.
        let asinh_over = if sinh_diff < 1e-8 {
            1.0 - sinh_diff * sinh_diff / 6.0
        } else {
            sinh_diff.asinh() / sinh_diff
        };
        moving * (1.0 + cosh_diff) / (g0 + g) * asinh_over + rest
    }

    /// The Born-rigid braking of the material point at rest-frame offset
    /// `r_parallel` ahead of the centre (negative: behind), with this braking
    /// as the centre's: its own `Braking` (proper speed `u₀/(1−ρ)`,
    /// deceleration `a/(1−ρ)`, `ρ = r∥ a/c²`) and its board-frame offset
    /// from the centre at the segment start.
    ///
    /// # Errors
    /// [`RigidityError`] if `r∥ ≥ c²/a` (the point is at or beyond the
    /// braking's Rindler horizon).
    pub fn material_point(&self, r_parallel: f64) -> Result<(f64, Braking), RigidityError> {
        let rho = self.horizon_fraction(r_parallel)?;
        let point = Braking::new(
            self.u0 / (1.0 - rho),
            self.deceleration / (1.0 - rho),
            self.c,
        );
        Ok((self.offset_along_at(0.0, rho, r_parallel), point))
    }

    /// `ρ = r∥ a / c²`, the point's offset as a fraction of the distance to
    /// the braking's Rindler horizon; an error unless `ρ < 1`.
    fn horizon_fraction(&self, r_parallel: f64) -> Result<f64, RigidityError> {
        let rho = r_parallel * self.deceleration / (self.c * self.c);
        if rho.is_nan() || rho >= 1.0 {
            return Err(RigidityError {
                offset: r_parallel,
                deceleration: self.deceleration,
                c: self.c,
                horizon: self.c * self.c / self.deceleration,
            });
        }
        Ok(rho)
    }

    /// Board-frame offset from the centre, along the motion, of the point at
    /// rest-frame offset `r∥` (with `ρ = r∥ a/c² < 1`), at board time `t`:
    /// `r∥ (2 − ρ)/(γ + √((1 − ρ)² + u²))`.
    fn offset_along_at(&self, t: f64, rho: f64, r_parallel: f64) -> f64 {
        let u = self.proper_speed_at(t);
        let g = (1.0 + u * u).sqrt();
        let one_minus = 1.0 - rho;
        r_parallel * (2.0 - rho) / (g + (one_minus * one_minus + u * u).sqrt())
    }

    /// Board-frame offset along the motion, at board time `t`, of the point
    /// at rest-frame offset `r_parallel` ahead of the centre (Born-rigid
    /// contraction: `r∥/γ` without friction, `r∥` at rest).
    ///
    /// # Errors
    /// [`RigidityError`] as [`Self::material_point`].
    pub fn contracted_offset_at(&self, t: f64, r_parallel: f64) -> Result<f64, RigidityError> {
        let rho = self.horizon_fraction(r_parallel)?;
        Ok(self.offset_along_at(t, rho, r_parallel))
    }

    /// Board time `t ∈ [0, t_stop]` (from the segment start) at which this
    /// point, starting at `start` and moving along the unit vector
    /// `direction`, emitted the light that reaches `observer` at board time
    /// `t_obs` (same origin). `None` if that light left it before the segment
    /// start or after it stopped (the emission then lies on a neighbouring
    /// segment).
    ///
    /// Closed form: the past light cone `|start + s d̂ − x₀|² = c²(t_obs − t)²`
    /// and the hyperbola `ε(s² − c²t²) = γ₀ s − c u₀ t` (`ε = a/2c²`, the
    /// braking hyperbola through the origin) have the same quadratic part
    /// `s² − c²t²`; subtracting leaves the straight line
    ///
    /// ```text
    /// (γ₀ + 2εb) s + (2εc²t_obs − c u₀) t = ε Q,
    /// b = d̂·(start − x₀),  Q = c²t_obs² − |start − x₀|²,
    /// ```
    ///
    /// which is met with the cone in a quadratic, solved in its stable form
    /// in whichever of `s`, `t` the line's larger coefficient eliminates.
    /// Without friction (`ε = 0`) the line is `s = v₀ t`, the uniform case.
    /// For a far observer the line's coefficients lose digits to
    /// cancellation, so the root is then polished by Newton's method on the
    /// light-cone residual itself (`onto_the_cone`): on the past light cone
    /// to the rounding of its inputs at any distance.
    #[must_use]
    pub fn emission_time(
        &self,
        start: DVec3,
        direction: DVec3,
        observer: DVec3,
        t_obs: f64,
    ) -> Option<f64> {
        let c = self.c;
        let delta = start - observer;
        let dist = delta.length();
        // The segment start must lie in (or on) the observation's past cone:
        // f(t) = c(t_obs − t) − |x(t) − x₀| decreases along a worldline.
        if c * t_obs < dist {
            return None;
        }
        let b = direction.dot(delta);
        let h_sq = (delta - direction * b).length_squared();
        let q_cone = (c * t_obs - dist) * (c * t_obs + dist);
        let eps = self.deceleration / (2.0 * c * c);
        let g0 = self.gamma0;
        let u0 = self.u0;
        // Line: alpha s + beta t = q.
        let alpha = g0 + 2.0 * eps * b;
        let beta = 2.0 * eps * c * c * t_obs - c * u0;
        let q = eps * q_cone;
        let stop = self.stop_time();
        let mut best: Option<f64> = None;
        let mut consider = |t: f64, s: f64| {
            let tol = 1e-12 * (t_obs.abs() + stop.min(t_obs.abs()));
            if !(t.is_finite() && s.is_finite()) || t < -tol || t > stop + tol || t > t_obs + tol {
                return;
            }
            // On the braking branch (s < s_h = γ₀/2ε), not its mirror.
            if 2.0 * eps * s >= g0 {
                return;
            }
            let t = t.clamp(0.0, stop.min(t_obs));
            best = Some(best.map_or(t, |b: f64| b.max(t)));
        };
        if alpha.abs() * c >= beta.abs() {
            // s = m t + n.
            let m = -beta / alpha;
            let n = q / alpha;
            // (m² − c²) t² + 2 (m (n + b) + c² t_obs) t + n (n + 2b) − Q = 0,
            // m − c in a form free of cancellation at high γ.
            let m_minus_c = -c * (1.0 / (g0 + u0) + 2.0 * eps * (c * t_obs + b)) / alpha;
            let qa = m_minus_c * (m + c);
            let qb = m * (n + b) + c * c * t_obs;
            let qc = n * (n + 2.0 * b) - q_cone;
            for t in stable_roots(qa, qb, qc) {
                consider(t, m * t + n);
            }
        } else {
            // t = p s + r.
            let p = -alpha / beta;
            let r = q / beta;
            let tt = t_obs - r;
            // (1 − c²p²) s² + 2 (b + c² p (t_obs − r)) s + b² + h² − c²(t_obs − r)² = 0
            let qa = (1.0 - c * p) * (1.0 + c * p);
            let qb = b + c * c * p * tt;
            let qc = b * b + h_sq - c * c * tt * tt;
            for s in stable_roots(qa, qb, qc) {
                consider(p * s + r, s);
            }
        }
        best.map(|t| self.onto_the_cone(delta, direction, t_obs, t))
    }

    /// Newton's method on the light-cone residual
    /// `f(t) = c (t_obs − t) − |delta + d̂ s(t)|` (`delta` the segment
    /// start relative to the observer, `s(t)` [`Self::distance_at`]) from
    /// the closed form's root `t`, kept in `[0, min(t_stop, t_obs)]`.
    ///
    /// The closed form's line and quadratic have coefficients the size of
    /// `ε |delta| γ₀` (`ε = a/2c²`) whose differences are the root: for an
    /// observer many `c²/a` away they lose digits (6.6e-10 of the light
    /// delay at 10³ table lengths and u₀ = 10⁴, issue 30). The residual is
    /// a difference of two lengths formed directly, exact to the rounding
    /// of its inputs; `f′ = −c − (x̂·d̂) v(t) < 0`, so a step or two from
    /// the closed form's root brings `f` to that floor. A step is kept only
    /// while it shrinks `|f|`.
    fn onto_the_cone(&self, delta: DVec3, direction: DVec3, t_obs: f64, t: f64) -> f64 {
        let c = self.c;
        let hi = self.stop_time().min(t_obs).max(0.0);
        let residual = |t: f64| {
            let x = delta + direction * self.distance_at(t);
            let r = x.length();
            let f = c * (t_obs - t) - r;
            let along = if r > 0.0 { direction.dot(x) / r } else { 0.0 };
            (f, -c - along * self.speed_at(t), r)
        };
        let (mut t, (mut f, mut slope, mut r)) = (t, residual(t));
        for _ in 0..4 {
            // Already at the rounding floor of its two terms.
            if f.abs() <= 4.0 * f64::EPSILON * r.max(c * (t_obs - t).abs()) || slope >= 0.0 {
                break;
            }
            let next = (t - f / slope).clamp(0.0, hi);
            let (fn_, sn, rn) = residual(next);
            if next == t || fn_.abs() >= f.abs() {
                break;
            }
            (t, f, slope, r) = (next, fn_, sn, rn);
        }
        t
    }
}

/// Real roots of `a x² + 2 b x + c = 0` in the cancellation-free form
/// (`q = −(b + sign(b)√(b² − ac))`, roots `q/a` and `c/q`); a vanishing `a`
/// leaves the linear root. None when there is no real root. At most two,
/// without allocating (this runs once per vertex and frame in the optics).
fn stable_roots(a: f64, b: f64, c: f64) -> impl Iterator<Item = f64> {
    let disc = b * b - a * c;
    if disc < 0.0 {
        // A tangency lost to rounding: keep the double root.
        let tangent = disc > -1e-12 * (b * b).max((a * c).abs()) && a != 0.0;
        return [tangent.then(|| -b / a), None].into_iter().flatten();
    }
    let q = -(b + b.signum() * disc.sqrt());
    let first = (a != 0.0 && q != 0.0).then(|| q / a);
    let second = if q != 0.0 {
        Some(c / q)
    } else if a != 0.0 {
        Some(0.0)
    } else {
        None
    };
    [first, second].into_iter().flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bisection on `f(t) = c(t_obs − t) − |x(t) − x₀|` (decreasing along a
    /// worldline), with `x(t)` from the distance closed form: the reference
    /// the closed-form emission is checked against.
    fn bracketed_emission(
        b: &Braking,
        start: DVec3,
        dir: DVec3,
        observer: DVec3,
        t_obs: f64,
    ) -> Option<f64> {
        let f = |t: f64| b.c * (t_obs - t) - (start + dir * b.distance_at(t) - observer).length();
        let hi_end = b.stop_time().min(t_obs);
        if f(0.0) < 0.0 || f(hi_end) > 0.0 {
            return None;
        }
        let (mut lo, mut hi) = (0.0, hi_end);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if f(mid) >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    }

    #[test]
    fn stopping_distance_time_and_proper_time_closed_forms() {
        // (c²/μg)(γ₀ − 1), (c/μg) u₀ and (c/μg) asinh u₀, with the right-hand
        // sides evaluated in the textbook form at moderate γ.
        for (u0, a, c) in [(0.5, 2.0, 1.0), (3.0, 0.3, 2.0), (40.0, 9.81, 10.0)] {
            let b = Braking::new(u0, a, c);
            let g0 = (1.0_f64 + u0 * u0).sqrt();
            let d = c * c / a * (g0 - 1.0);
            assert!((b.stopping_distance() - d).abs() < 1e-13 * d, "{u0}");
            assert!((b.stop_time() - c / a * u0).abs() < 1e-15 * c / a * u0);
            let tau = c / a * u0.asinh();
            assert!((b.proper_time_at(b.stop_time()) - tau).abs() < 1e-13 * tau);
            // Mid-way: the asinh difference.
            let t = 0.37 * b.stop_time();
            let u = u0 - a * t / c;
            let tau_mid = c / a * (u0.asinh() - u.asinh());
            assert!((b.proper_time_at(t) - tau_mid).abs() < 1e-12 * tau_mid);
            assert!((b.distance_at(t) - c * c / a * (g0 - (1.0 + u * u).sqrt())).abs() < 1e-12 * d);
        }
    }

    #[test]
    fn high_gamma_keeps_its_digits() {
        // u₀ = 10⁸: stopping distance ≈ (c²/a) u₀ (1 − 1/u₀ + …), time c u₀/a.
        let b = Braking::new(1e8, 1.0, 1.0);
        let d = b.stopping_distance();
        let exact = 1e16 / ((1.0_f64 + 1e16).sqrt() + 1.0);
        assert!((d - exact).abs() <= 1e-15 * exact);
        assert!(b.proper_time_at(b.stop_time()).is_finite());
        assert!((b.proper_time_at(b.stop_time()) - 1e8_f64.asinh()).abs() < 1e-14 * 20.0);
    }

    #[test]
    fn newtonian_limit() {
        // c → 10⁶ m/s: a carom shot at 2 m/s, μg = 0.2·9.81. Classical
        // stopping distance v²/2μg and time v/μg.
        let c: f64 = 1e6;
        let v: f64 = 2.0;
        let a = 0.2 * 9.81;
        let b = Braking::new(v / c / (1.0 - (v / c) * (v / c)).sqrt(), a, c);
        let d = v * v / (2.0 * a);
        assert!(
            (b.stopping_distance() - d).abs() < 1e-9,
            "{}",
            b.stopping_distance() - d
        );
        assert!((b.stop_time() - v / a).abs() < 1e-9);
        let t = 0.4;
        assert!((b.distance_at(t) - (v * t - 0.5 * a * t * t)).abs() < 1e-9);
        assert!((b.proper_time_at(t) - t).abs() < 1e-9);
    }

    #[test]
    fn born_rigid_points_stop_together_in_their_rest_shape() {
        let b = Braking::new(5.0, 2.0, 1.0); // K = 0.5 m
        for r in [-0.2, -0.03, 0.0, 0.03, 0.2] {
            let (start_offset, p) = b.material_point(r).unwrap();
            assert!((p.stop_time() - b.stop_time()).abs() < 1e-14 * b.stop_time());
            // Where each point ends, relative to the centre: its rest offset.
            let end = start_offset + p.stopping_distance() - b.stopping_distance();
            assert!((end - r).abs() < 1e-13, "{r}: {end}");
            // At any time the point is where the contracted-offset form says.
            let t = 0.3 * b.stop_time();
            let here = start_offset + p.distance_at(t) - b.distance_at(t);
            assert!((here - b.contracted_offset_at(t, r).unwrap()).abs() < 1e-13);
            // Its proper deceleration in its own frame is constant: K′ = K − r.
            assert!((b.c * b.c / p.deceleration - (0.5 - r)).abs() < 1e-14);
        }
        // Without friction the offset is the Lorentz contraction r/γ.
        let free = Braking::new(5.0, 0.0, 1.0);
        let g = (26.0_f64).sqrt();
        assert!((free.contracted_offset_at(1.0, 0.03).unwrap() - 0.03 / g).abs() < 1e-17);
        // A point at the horizon cannot brake rigidly.
        assert!(b.material_point(0.5).is_err());
        assert!(b.contracted_offset_at(0.0, 0.7).is_err());
    }

    #[test]
    fn emission_matches_a_bracketed_root() {
        // Observers in every direction, near and far, at times during and
        // after the braking; γ from 1 to 10⁶; friction from weak to strong.
        let mut checked = 0;
        let mut worst = 0.0_f64;
        for &(u0, a, c) in &[
            (0.3, 2.0, 1.0),
            (3.0, 2.0, 1.0),
            (50.0, 0.5, 1.0),
            (1e6, 1.0, 1.0),
            (0.001, 1.962, 1e3),
            (2.0, 1e-6, 1.0),
        ] {
            let b = Braking::new(u0, a, c);
            let dir = DVec3::new(0.6, 0.8, 0.0);
            let start = DVec3::new(0.1, -0.2, 0.0);
            let horizon_scale = b.stop_time().min(1e3);
            for k in 0..40 {
                let ang = k as f64 * 0.7;
                let r = [0.05, 0.5, 2.0, 7.0][k % 4];
                let observer =
                    start + DVec3::new(r * ang.cos(), r * ang.sin(), 0.3 * (k % 3) as f64);
                for frac in [0.05, 0.4, 0.9, 1.3] {
                    let t_obs = frac * horizon_scale + (observer - start).length() / c;
                    let ours = b.emission_time(start, dir, observer, t_obs);
                    let reference = bracketed_emission(&b, start, dir, observer, t_obs);
                    match (ours, reference) {
                        (Some(x), Some(y)) => {
                            let err = (x - y).abs() / t_obs.abs().max(1e-300);
                            worst = worst.max(err);
                            assert!(
                                err < 1e-12,
                                "u0 {u0} a {a} obs {observer} t {t_obs}: {x} vs {y}"
                            );
                            checked += 1;
                        }
                        (None, None) => {}
                        (x, y) => {
                            // Only at the very ends may one side miss.
                            let t = x.or(y).unwrap_or(0.0);
                            let end = b.stop_time().min(t_obs);
                            assert!(
                                t < 1e-12 * t_obs || (end - t).abs() < 1e-12 * t_obs,
                                "u0 {u0} a {a} obs {observer} t {t_obs}: {x:?} vs {y:?}"
                            );
                        }
                    }
                }
            }
        }
        assert!(checked > 500, "{checked}");
        eprintln!("emission on the braking hyperbola: {checked} cases, worst {worst:e}");
    }
}
