//! Collision outcomes: what each body's momentum becomes.
//!
//! **Puck–puck.** Worked in the centre-of-momentum (CM) frame, where the two
//! momenta are `p` and `−p`. The pucks are smooth, so the impulse is along
//! the contact normal (taken from the pair frame, where the shapes are
//! congruent; for equal masses the two frames coincide). The restitution
//! `e` is the fraction of the CM kinetic energy that stays kinetic:
//!
//! * `e = 1` (elastic): the normal component of `p` is reversed, so both
//!   pucks keep their CM speeds, as the paper's Appendix describes;
//! * `e < 1`: the lost kinetic energy `Q = (1 − e) K` becomes heat, which in
//!   relativity is rest mass: each puck's rest mass grows by its share of
//!   `Q / c²` (shared in proportion to mass). So 4-momentum is conserved
//!   exactly in every collision, elastic or not. The tangential momentum is
//!   kept when the remaining energy allows, else it shrinks too; `e = 0`
//!   leaves the pair at rest in the CM frame, moving together.
//!
//! **Puck–cushion.** The cushion is infinitely massive and at rest on the
//! board, so the board is its CM frame: the normal component of `u` is
//! reversed (elastic: angle of reflection = angle of incidence, the paper's
//! §3.3.2.3 claim), and for `e < 1` the puck's kinetic energy is scaled by
//! `e` (the cushion takes the heat; the puck's mass is unchanged).
//!
//! **Several contacts at one board time** (two strikers meeting a third
//! at once, twins meeting each other and a third): [`simultaneous::on_graph`]
//! ([`simultaneous::on_one_puck`] for a star).

use glam::DVec3;

use crate::spacetime::{Boost, FourMomentum, FourVector, ProperVelocity};

pub mod simultaneous;

/// A body's rest mass (kg) and proper velocity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body {
    /// Rest mass, kg.
    pub mass: f64,
    /// Proper velocity, board frame.
    pub u: ProperVelocity,
}

impl Body {
    /// 4-momentum in mass units.
    #[must_use]
    pub fn momentum(self) -> FourMomentum {
        FourMomentum::of_body(self.mass, self.u)
    }
}

/// Kinetic energy `m (γ − 1)` of a body in mass units, exact for slow bodies.
fn kinetic(mass: f64, u: ProperVelocity) -> f64 {
    mass * u.gamma_minus_one()
}

/// The momentum magnitude² `q` at which two bodies of masses `m1`, `m2` with
/// momenta ±p have kinetic energy `k`: solves
/// `Σ q / (√(mᵢ² + q) + mᵢ) = k`, a form that keeps its digits when `k` is
/// tiny. The left side is increasing in `q`, so bisection on `[0, hi]`
/// until the bracket stops shrinking (at most 200 halvings) finds it to
/// the last bit; `hi` itself if even `hi` has too little energy.
fn momentum_sq_for_kinetic(m1: f64, m2: f64, k: f64, hi: f64) -> f64 {
    let f = |q: f64| q / ((m1 * m1 + q).sqrt() + m1) + q / ((m2 * m2 + q).sqrt() + m2) - k;
    let (mut lo, mut hi) = (0.0f64, hi.max(0.0));
    if f(hi) <= 0.0 {
        return hi;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if f(mid) > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Outcome of a puck–puck collision. `normal` is the unit contact normal
/// from `a` towards `b` in the pair frame (moving with `pair_frame`);
/// `restitution` in [0, 1]. Returns the two bodies after the collision
/// (new proper velocities, and rest masses grown by the heat if
/// `restitution < 1`). If the pucks are not approaching along the normal,
/// nothing changes.
#[must_use]
pub fn puck_puck(
    a: Body,
    b: Body,
    normal: DVec3,
    pair_frame: ProperVelocity,
    restitution: f64,
) -> [Body; 2] {
    // The normal, a spatial vector in the pair frame, seen on the board.
    let n_board = Boost::into_frame(pair_frame)
        .inverse()
        .apply(FourVector::new(0.0, normal));
    in_cm_frame(a, b, n_board, restitution)
}

/// [`puck_puck`]'s outcome with the normal given as a board-frame 4-vector
/// `n_board` whose spatial part in the CM frame is the contact normal (its
/// time part there is ignored; its length does not matter).
fn in_cm_frame(a: Body, b: Body, n_board: FourVector, restitution: f64) -> [Body; 2] {
    let total_mass = FourMomentum::pair_invariant_mass(a.mass, a.u, b.mass, b.u);
    let total = a.momentum() + b.momentum();
    let to_cm = Boost::into_frame(total.centre_of_momentum_velocity(total_mass));
    let n = to_cm.apply(n_board).space.normalize();

    let ua = to_cm.apply_velocity(a.u);
    let ub = to_cm.apply_velocity(b.u);
    // ±p in the CM frame; symmetrise away the rounding.
    let p = 0.5 * (ua.0 * a.mass - ub.0 * b.mass);
    let p_n = p.dot(n);
    if p_n.is_nan() || p_n <= 0.0 {
        return [a, b];
    }

    let (p_after, mass_a, mass_b) = if restitution >= 1.0 {
        (p - n * (2.0 * p_n), a.mass, b.mass)
    } else {
        let k = kinetic(a.mass, ua) + kinetic(b.mass, ub);
        let heat = (1.0 - restitution) * k;
        let share = a.mass / (a.mass + b.mass);
        let (ma, mb) = (a.mass + heat * share, b.mass + heat * (1.0 - share));
        let q = momentum_sq_for_kinetic(ma, mb, restitution * k, p.length_squared());
        let tangential = p - n * p_n;
        let t_sq = tangential.length_squared();
        let p_after = if q >= t_sq {
            tangential - n * (q - t_sq).sqrt()
        } else if t_sq > 0.0 {
            tangential * (q / t_sq).sqrt()
        } else {
            DVec3::ZERO
        };
        (p_after, ma, mb)
    };

    let to_board = to_cm.inverse();
    [
        Body {
            mass: mass_a,
            u: to_board.apply_velocity(ProperVelocity(p_after / mass_a)),
        },
        Body {
            mass: mass_b,
            u: to_board.apply_velocity(ProperVelocity(-p_after / mass_b)),
        },
    ]
}

/// Outcome of a contact found on the board (two pucks that overlap on the
/// board and are closing there, see `Billiard`): the impulse is along the
/// board-frame unit direction `normal` (from `a` towards `b`), and
/// `restitution` is, as in [`puck_puck`], the fraction of the CM kinetic
/// energy kept (the guide, docs/guide/src/collisions.md).
///
/// Worked in the frame that moves along `normal` with the pair's velocity
/// component along it (`β = (P·n) / E`), where the pair's momentum along
/// `normal` is zero. A boost along `normal` keeps the order of the two
/// velocities' components along it (`v′ₙ = (vₙ − β)/(1 − β vₙ)` depends on
/// `vₙ` alone), so "closing along `normal`" means the same there and on the
/// board. Elastic: there the normal momenta `±p` become `∓p` with the
/// energies unchanged. That frame is a CM frame boosted across `normal`, a
/// boost that keeps every 4-vector's component along `normal` and the sign
/// of every velocity's: the elastic outcome is the CM normal momentum
/// reversed, and [`puck_puck`]'s CM rule, with the board 4-vector
/// `(β, normal)` (unit along `normal` in that frame) as its normal, gives
/// the outcome for `e < 1` (heat `(1 − e) K` as rest mass in proportion
/// to mass, the tangential momentum kept when the energy allows). The CM
/// normal momenta stay opposite, so the pair leaves opening along `normal`
/// on the board, or (all the energy taken from the tangential motion too)
/// moving alike along it. For `e = 0` the pair moves together, as
/// [`together`]. 4-momentum is conserved exactly. Not closing: unchanged.
#[must_use]
pub fn puck_puck_board(a: Body, b: Body, normal: DVec3, restitution: f64) -> [Body; 2] {
    // Elastic, in closed form on the board: an impulse `J n` to `a` (`−J n`
    // to `b`) carries energy `J k`, `k = (P·n)/E`, the frame's β along `n`.
    // The root is `J = 2 E (E_a p_b·n − E_b p_a·n) / (E² − (P·n)²)`, with
    // `E² − (P·n)² = M² + |P⊥|²` formed without cancellation (`M` the pair's
    // invariant mass, exact).
    let (pa, pb) = (a.momentum(), b.momentum());
    let total = pa + pb;
    let along = total.momentum.dot(normal);
    let across = (total.momentum - normal * along).length_squared();
    let invariant = FourMomentum::pair_invariant_mass(a.mass, a.u, b.mass, b.u);
    let denom = invariant * invariant + across;
    // E_a p_b·n − E_b p_a·n = E_a E_b (β_b − β_a)·n: closing when negative.
    let closing = pa.energy * pb.energy * (b.u.beta() - a.u.beta()).dot(normal);
    if closing.is_nan() || closing >= 0.0 || denom <= 0.0 {
        return [a, b];
    }
    if restitution < 1.0 {
        return in_cm_frame(
            a,
            b,
            FourVector::new(along / total.energy, normal),
            restitution.max(0.0),
        );
    }
    let j = 2.0 * total.energy * closing / denom;
    let out = |p: FourMomentum, impulse: f64, mass: f64| Body {
        mass,
        u: ProperVelocity((p.momentum + normal * impulse) / mass),
    };
    [out(pa, j, a.mass), out(pb, -j, b.mass)]
}

/// The perfectly inelastic outcome, whatever the geometry: both bodies
/// move together at the pair's centre-of-momentum velocity `P/M` (`P` the
/// total 4-momentum, `M` its invariant mass), and all the kinetic energy
/// of the relative motion becomes rest mass, shared in proportion to the
/// rest masses (`mᵢ′ = M mᵢ / (m_a + m_b)`). This is [`puck_puck`] with
/// restitution 0 for an approaching pair, in closed form and without its
/// approach test: a pair already moving together is unchanged (to
/// rounding). 4-momentum is conserved exactly: `Σ mᵢ′ u = M (P/M) = P` and
/// `Σ mᵢ′ γ = M γ_cm = E`.
#[must_use]
pub fn together(a: Body, b: Body) -> [Body; 2] {
    let total = a.momentum() + b.momentum();
    let invariant = FourMomentum::pair_invariant_mass(a.mass, a.u, b.mass, b.u);
    let u = ProperVelocity(total.momentum / invariant);
    let sum = a.mass + b.mass;
    [
        Body {
            mass: invariant * (a.mass / sum),
            u,
        },
        Body {
            mass: invariant * (b.mass / sum),
            u,
        },
    ]
}

/// [`together`] for any number of bodies (an inelastic collapse of a
/// cluster, which pairwise contacts would only approach, for ever): all move
/// at the cluster's centre-of-momentum velocity `P/M`, rest masses
/// `mᵢ′ = M mᵢ / Σ m`. `M` is built pair by pair with
/// [`FourMomentum::pair_invariant_mass`] (each step combines the bodies so
/// far, as one body of mass `M` at `P/M`, with the next), which keeps its
/// digits when the relative motion is slow. 4-momentum conserved exactly,
/// as for two. Empty in, empty out.
#[must_use]
pub fn together_all(bodies: &[Body]) -> Vec<Body> {
    if let &[a, b] = bodies {
        return together(a, b).to_vec();
    }
    let Some((&first, rest)) = bodies.split_first() else {
        return Vec::new();
    };
    let whole = rest.iter().fold(first, |acc, &next| {
        let [x, y] = together(acc, next);
        Body {
            mass: x.mass + y.mass,
            u: x.u,
        }
    });
    let sum: f64 = bodies.iter().map(|b| b.mass).sum();
    bodies
        .iter()
        .map(|b| Body {
            mass: whole.mass * (b.mass / sum),
            u: whole.u,
        })
        .collect()
}

/// Outcome of a puck meeting a cushion whose outward unit normal (from the
/// table into the cushion) is `outward`, board frame.
#[must_use]
pub fn puck_cushion(u: ProperVelocity, outward: DVec3, restitution: f64) -> ProperVelocity {
    let u_n = u.0.dot(outward);
    if u_n.is_nan() || u_n <= 0.0 {
        return u;
    }
    if restitution >= 1.0 {
        return ProperVelocity(u.0 - outward * (2.0 * u_n));
    }
    // Kinetic energy scaled by e: γ' − 1 = e (γ − 1); |u'|² = (γ' − 1)(γ' + 1).
    let g1 = restitution * u.gamma_minus_one();
    let speed_sq = g1 * (g1 + 2.0);
    let tangential = u.0 - outward * u_n;
    let t_sq = tangential.length_squared();
    if speed_sq >= t_sq {
        ProperVelocity(tangential - outward * (speed_sq - t_sq).sqrt())
    } else {
        ProperVelocity(tangential * (speed_sq / t_sq).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(m: f64, bx: f64, by: f64) -> Body {
        Body {
            mass: m,
            u: ProperVelocity::try_from_beta(DVec3::new(bx, by, 0.0)).unwrap(),
        }
    }

    fn conserved(before: [Body; 2], after: [Body; 2]) {
        let p0 = before[0].momentum() + before[1].momentum();
        let p1 = after[0].momentum() + after[1].momentum();
        let scale = p0.energy;
        assert!(
            (p0.energy - p1.energy).abs() <= 1e-12 * scale,
            "{p0:?} {p1:?}"
        );
        assert!(
            (p0.momentum - p1.momentum).length() <= 1e-12 * scale,
            "{p0:?} {p1:?}"
        );
    }

    #[test]
    fn head_on_equal_masses_exchange_velocities() {
        let (a, b) = (body(1.0, 0.9, 0.0), body(1.0, 0.0, 0.0));
        let out = puck_puck(
            a,
            b,
            DVec3::X,
            ProperVelocity((a.u.0) / (2.0 + 2.0 * a.u.gamma()).sqrt()),
            1.0,
        );
        assert!(out[0].u.0.length() < 1e-14);
        assert!((out[1].u.0 - a.u.0).length() < 1e-14);
        conserved([a, b], out);
    }

    #[test]
    fn elastic_and_inelastic_conserve_four_momentum() {
        let (a, b) = (body(0.2, 0.8, 0.3), body(0.5, -0.4, 0.1));
        let normal = DVec3::new(0.6, -0.8, 0.0);
        for e in [1.0, 0.7, 0.3, 0.0] {
            let out = puck_puck(a, b, normal, ProperVelocity(DVec3::new(0.1, 0.2, 0.0)), e);
            conserved([a, b], out);
            if e < 1.0 {
                assert!(out[0].mass > a.mass && out[1].mass > b.mass);
            }
        }
    }

    #[test]
    fn perfectly_inelastic_head_on_moves_together() {
        let (a, b) = (body(1.0, 0.6, 0.0), body(1.0, -0.2, 0.0));
        let out = puck_puck(a, b, DVec3::X, ProperVelocity::ZERO, 0.0);
        assert!((out[0].u.0 - out[1].u.0).length() < 1e-12);
        conserved([a, b], out);
        // Invariant mass is now all rest mass.
        let m = FourMomentum::pair_invariant_mass(a.mass, a.u, b.mass, b.u);
        assert!((out[0].mass + out[1].mass - m).abs() < 1e-12);
    }

    #[test]
    fn cushion_reflects_at_the_angle_of_incidence() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.7, 0.642, 0.0)).unwrap();
        let out = puck_cushion(u, DVec3::X, 1.0);
        assert_eq!(out.0, DVec3::new(-u.0.x, u.0.y, 0.0));
        let (bi, bo) = (u.beta(), out.beta());
        assert!(((bi.y / bi.x).atan() + (bo.y / bo.x).atan()).abs() < 1e-15);
        // Inelastic: energy fraction e of the kinetic energy, tangential kept.
        let most = puck_cushion(u, DVec3::X, 0.9);
        assert!((most.gamma_minus_one() / u.gamma_minus_one() - 0.9).abs() < 1e-12);
        assert_eq!(most.0.y, u.0.y);
        assert!(most.0.x < 0.0);
        // So little energy left that even the tangential motion must slow:
        // it slides along the cushion.
        let little = puck_cushion(u, DVec3::X, 0.5);
        assert!((little.gamma_minus_one() / u.gamma_minus_one() - 0.5).abs() < 1e-12);
        assert!(little.0.x.abs() < 1e-15 && little.0.y > 0.0);
        // Moving away: untouched.
        assert_eq!(puck_cushion(out, DVec3::X, 1.0), out);
    }

    #[test]
    fn a_board_contact_conserves_and_opens_along_its_normal() {
        let (a, b) = (body(0.2, 0.8, 0.3), body(0.5, -0.4, 0.1));
        let n = DVec3::new(0.6, -0.8, 0.0);
        let v = |x: Body| x.u.beta();
        assert!(v(b).dot(n) < v(a).dot(n)); // closing along n
        for e in [1.0, 0.5, 0.0] {
            let out = puck_puck_board(a, b, n, e);
            conserved([a, b], out);
            let opening = (v(out[1]) - v(out[0])).dot(n);
            // Elastic: opening. `e` is the CM kinetic-energy fraction kept:
            // at 0.5 too little is left for the tangential motion, so the
            // normal motion stops and the tangential shrinks (as in
            // `puck_puck`); at 0 they move together.
            if e == 1.0 {
                assert!(opening > 0.0, "{e}: {opening}");
            } else {
                assert!(opening.abs() < 1e-12, "{e}: {opening}");
            }
            if e == 1.0 {
                assert_eq!((out[0].mass, out[1].mass), (a.mass, b.mass));
            }
        }
        // Opening already: unchanged.
        assert_eq!(puck_puck_board(a, b, -n, 1.0), [a, b]);
    }

    #[test]
    fn together_is_the_pair_frame_outcome_of_restitution_zero() {
        let (a, b) = (body(0.2, 0.8, 0.3), body(0.5, -0.4, 0.1));
        let out = together(a, b);
        conserved([a, b], out);
        assert_eq!(out[0].u, out[1].u);
        // The same as a restitution-0 pair-frame contact (any normal along
        // which they approach).
        let pair = puck_puck(a, b, DVec3::X, ProperVelocity::ZERO, 0.0);
        let near = |x: [Body; 2], y: [Body; 2]| {
            x.iter()
                .zip(&y)
                .all(|(p, q)| (p.u.0 - q.u.0).length() < 1e-12 && (p.mass - q.mass).abs() < 1e-12)
        };
        assert!(near(pair, out), "{pair:?} {out:?}");
        // Already together: unchanged, to rounding.
        assert!(near(together(out[0], out[1]), out));
        // At γ ≈ 5·10³ onto γ ≈ 4 (the seed-15 case): still exact.
        let fast = Body {
            mass: 0.2,
            u: ProperVelocity(DVec3::new(4734.0, -551.0, 0.0)),
        };
        let slow = Body {
            mass: 0.2,
            u: ProperVelocity(DVec3::new(3.4, -1.9, 0.0)),
        };
        let out = together(fast, slow);
        conserved([fast, slow], out);
        assert_eq!(out[0].u, out[1].u);
    }

    #[test]
    fn together_all_conserves_4_momentum_and_is_together_for_two() {
        let (a, b, c) = (
            body(0.2, 0.8, 0.3),
            body(0.5, -0.4, 0.1),
            body(0.3, 0.0, -0.9),
        );
        let two = together_all(&[a, b]);
        assert_eq!(two, together(a, b).to_vec());
        let three = together_all(&[a, b, c]);
        let sum = |x: &[Body]| {
            x.iter()
                .fold(FourMomentum::default(), |s, b| s + b.momentum())
        };
        let (p0, p1) = (sum(&[a, b, c]), sum(&three));
        assert!((p0.energy - p1.energy).abs() <= 1e-12 * p0.energy);
        assert!((p0.momentum - p1.momentum).length() <= 1e-12 * p0.energy);
        assert!(three.iter().all(|x| x.u == three[0].u));
        // Heat: the rest masses grow, in proportion.
        assert!((three[0].mass / three[1].mass - 0.2 / 0.5).abs() < 1e-12);
        assert!(three[0].mass > 0.2);
        assert!(together_all(&[]).is_empty());
    }

    #[test]
    fn kinetic_solve_keeps_digits_in_the_classical_limit() {
        let q = momentum_sq_for_kinetic(1.0, 1.0, 1e-20, 1.0);
        // Classically K = 2 · q / 2 → q = 1e-20.
        assert!((q / 1e-20 - 1.0).abs() < 1e-9, "{q}");
    }
}
