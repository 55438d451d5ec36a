//! The observer: light arriving at an event, seen in the observer's frame.
//!
//! * **Aberration.** The past-directed null vector from the observation
//!   event to the emission event, `(c(tₑ − t₀), xₑ − x₀)`, is boosted into the
//!   observer's rest frame; its space part is where the observer sees the
//!   point: its direction, and its length, the *apparent distance* (how far
//!   the light travelled in the observer's frame).
//! * **Doppler.** `D = ν_observed / ν_emitted = (γₒ − uₒ·n) / (γₑ − uₑ·n)`
//!   with `n` the light's direction of travel (board frame), both terms in
//!   the cancellation-free form `(1 + u⊥²) / (γ + u·n)` when `u·n > 0`.
//!   `D > 1`: the source approaches (blue shift).
//! * **Searchlight.** The intensity factor is `D⁴`: a surface radiating as
//!   a black body at temperature `T` in its rest frame is seen as a black
//!   body at `D T`, whose total (bolometric) brightness scales as `D⁴`
//!   (Stefan–Boltzmann). This is the convention the renderer uses.

use glam::DVec3;

use super::batch::{LANES, LaneWork, vectorised};
use super::emission::Emission;
use crate::spacetime::{Boost, Event, FourVector, ProperVelocity};

/// An observer at one event: where and when, and how fast.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Eye {
    /// The observation event (board frame).
    pub event: Event,
    /// The observer's proper velocity.
    pub u: ProperVelocity,
}

/// What the observer sees of one emission. (Its direction is not stored:
/// [`Self::direction`] derives it. One is written for every vertex of
/// every view each frame, so it is kept to 40 bytes.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Seen {
    /// Where the point appears, relative to the eye, in the observer's rest
    /// frame (axes parallel to the board's), m. With aberration off, the
    /// board-frame offset.
    pub position: DVec3,
    /// Apparent distance, m.
    pub distance: f64,
    /// Doppler factor, observed / emitted frequency.
    pub doppler: f64,
}

impl Seen {
    /// Unit vector from the eye towards the point (observer's frame; zero
    /// for a point at the eye).
    #[inline]
    #[must_use]
    pub fn direction(&self) -> DVec3 {
        if self.distance > 0.0 {
            self.position / self.distance
        } else {
            DVec3::ZERO
        }
    }
}

/// `γ − u·n`, without cancellation when `u` is nearly along `n` at large γ.
#[inline]
fn gamma_minus_along(u: ProperVelocity, n: DVec3) -> f64 {
    let along = u.0.dot(n);
    let g = u.gamma();
    if along > 0.0 {
        let across_sq = (u.0 - n * along).length_squared();
        (1.0 + across_sq) / (g + along)
    } else {
        g - along
    }
}

/// Doppler factor for light travelling along unit `n` (board frame) from an
/// emitter moving with `emitter` to an observer moving with `observer`.
#[must_use]
pub fn doppler(n: DVec3, emitter: ProperVelocity, observer: ProperVelocity) -> f64 {
    gamma_minus_along(observer, n) / gamma_minus_along(emitter, n)
}

impl Eye {
    /// What this eye sees of light from `emission` sent by a point moving
    /// with `emitter`. `aberration` off keeps board-frame directions and
    /// distances (as if the eye were at rest).
    #[must_use]
    pub fn see(&self, emission: Event, emitter: ProperVelocity, c: f64, aberration: bool) -> Seen {
        let placed = if aberration {
            self.place_in_own_frame(&self.frame(), emission, c)
        } else {
            self.place_on_board(emission)
        };
        Seen {
            doppler: self.doppler_of(emission, emitter),
            ..placed
        }
    }

    /// The boost into this eye's rest frame (compute once per frame, pass to
    /// [`Self::place_in_own_frame`] for every vertex).
    #[must_use]
    pub fn frame(&self) -> Boost {
        Boost::into_frame(self.u)
    }

    /// Where the light from `emission` appears with aberration: the
    /// past-directed null vector to the emission boosted into this eye's
    /// rest frame (`frame`, from [`Self::frame`]; compute it once per
    /// frame). Doppler factor left at 1.
    #[must_use]
    pub fn place_in_own_frame(&self, frame: &Boost, emission: Event, c: f64) -> Seen {
        let to_source = emission.position - self.event.position;
        let ray = FourVector::new(c * (emission.t - self.event.t), to_source);
        Self::seen_at(frame.apply(ray).space)
    }

    /// [`Self::place_in_own_frame`] for each of `emissions`, appended to
    /// `out` in order: the same operations per emission, on arrays of
    /// [`super::batch::LANES`] at a time (vectorised).
    pub fn place_all_in_own_frame(
        &self,
        frame: &Boost,
        emissions: &[Emission],
        c: f64,
        out: &mut Vec<Seen>,
    ) {
        const N: usize = LANES;
        let (t0, o) = (self.event.t, self.event.position);
        out.reserve(emissions.len());
        let (mut ct, mut x, mut y, mut z) = ([0.0; N], [0.0; N], [0.0; N], [0.0; N]);
        let mut dist = [0.0; N];
        for chunk in emissions.chunks(N) {
            let n = chunk.len().min(N); // no bounds checks: the loops vectorise
            for (i, e) in chunk.iter().enumerate().take(N) {
                ct[i] = c * (e.event.t - t0);
                x[i] = e.event.position.x - o.x;
                y[i] = e.event.position.y - o.y;
                z[i] = e.event.position.z - o.z;
            }
            vectorised(Aberrated {
                frame,
                n,
                ray: (&mut ct, &mut x, &mut y, &mut z),
                distance: &mut dist,
            });
            out.extend((0..n).map(|i| Seen {
                position: DVec3::new(x[i], y[i], z[i]),
                distance: dist[i],
                doppler: 1.0,
            }));
        }
    }

    /// Where the light from `emission` appears without aberration: the
    /// board-frame offset from the eye (as if the eye were at rest).
    /// Doppler factor left at 1.
    #[must_use]
    pub fn place_on_board(&self, emission: Event) -> Seen {
        Self::seen_at(emission.position - self.event.position)
    }

    fn seen_at(position: DVec3) -> Seen {
        Seen {
            position,
            distance: position.length(),
            doppler: 1.0,
        }
    }

    /// What this eye sees of a point at rest on the board at `point` (the
    /// table, the cushions): its light left `|point − eye| / c` ago.
    #[must_use]
    pub fn see_static(&self, point: DVec3, c: f64, aberration: bool) -> Seen {
        let back = (point - self.event.position).length() / c;
        let emission = Event::new(self.event.t - back, point);
        self.see(emission, ProperVelocity::ZERO, c, aberration)
    }

    /// The Doppler factor of light from `emission`, sent by a point moving
    /// with `emitter` (1 if the emission is at the eye).
    #[must_use]
    pub fn doppler_of(&self, emission: Event, emitter: ProperVelocity) -> f64 {
        let travel = self.event.position - emission.position;
        let len = travel.length();
        if len > 0.0 {
            doppler(travel / len, emitter, self.u)
        } else {
            1.0
        }
    }
}

/// Lanes of [`Eye::place_all_in_own_frame`]: the rays (`ct`, `x`, `y`, `z`,
/// first `n`) boosted in place, then each one's apparent distance, as
/// `seen_at` computes it.
struct Aberrated<'a> {
    frame: &'a Boost,
    n: usize,
    ray: (
        &'a mut [f64; LANES],
        &'a mut [f64; LANES],
        &'a mut [f64; LANES],
        &'a mut [f64; LANES],
    ),
    distance: &'a mut [f64; LANES],
}

impl LaneWork for Aberrated<'_> {
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // arrays in step: the form that vectorises
    fn run(self) {
        let n = self.n.min(LANES);
        let (ct, x, y, z) = self.ray;
        self.frame
            .apply_all(&mut ct[..n], &mut x[..n], &mut y[..n], &mut z[..n]);
        for i in 0..n {
            self.distance[i] = (x[i] * x[i] + y[i] * y[i] + z[i] * z[i]).sqrt();
        }
    }
}

/// Searchlight intensity factor for a Doppler factor: `D⁴` (see module doc).
#[inline]
#[must_use]
pub fn searchlight(doppler: f64) -> f64 {
    let d2 = doppler * doppler;
    d2 * d2
}

#[cfg(test)]
mod tests {
    use super::*;

    const C: f64 = 1.42;

    #[test]
    fn textbook_doppler() {
        // Source approaching head-on at β: D = √((1+β)/(1−β)).
        for beta in [0.1, 0.5, 0.9, 0.999] {
            let u = ProperVelocity::try_from_beta(DVec3::new(beta, 0.0, 0.0)).unwrap();
            let d = doppler(DVec3::X, u, ProperVelocity::ZERO);
            let expected = ((1.0 + beta) / (1.0 - beta)).sqrt();
            assert!(
                (d / expected - 1.0).abs() < 1e-12,
                "{beta}: {d} vs {expected}"
            );
            // Receding: the inverse. Transverse (seen at 90° in the board
            // frame): 1/γ, the transverse Doppler effect.
            assert!((doppler(-DVec3::X, u, ProperVelocity::ZERO) * expected - 1.0).abs() < 1e-12);
            assert!((doppler(DVec3::Y, u, ProperVelocity::ZERO) * u.gamma() - 1.0).abs() < 1e-12);
            // A moving observer and a resting source, head-on: same D.
            let o = ProperVelocity(-u.0);
            assert!((doppler(DVec3::X, ProperVelocity::ZERO, o) / expected - 1.0).abs() < 1e-12);
        }
        // γ = 10⁸ head-on: D = γ(1 + β) ≈ 2γ, no cancellation.
        let u = ProperVelocity(DVec3::new(1e8, 0.0, 0.0));
        let d = doppler(DVec3::X, u, ProperVelocity::ZERO);
        assert!((d / 2e8 - 1.0).abs() < 1e-12, "{d}");
        assert!((doppler(-DVec3::X, u, ProperVelocity::ZERO) * 2e8 - 1.0).abs() < 1e-12);
    }

    #[test]
    fn aberration_formula_for_a_moving_observer() {
        // A star at rest straight "above" (along +y, board frame) is seen by
        // an observer moving along +x tilted forwards: cos θ' = β (angle to
        // the motion), the textbook aberration at 90°.
        for beta in [0.1, 0.6, 0.99] {
            let u = ProperVelocity::try_from_beta(DVec3::new(beta, 0.0, 0.0)).unwrap();
            let eye = Eye {
                event: Event::new(5.0, DVec3::ZERO),
                u,
            };
            let far = 1e3;
            let emission = Event::new(5.0 - far / C, DVec3::new(0.0, far, 0.0));
            let seen = eye.see(emission, ProperVelocity::ZERO, C, true);
            assert!(
                (seen.direction().x - beta).abs() < 1e-12,
                "{beta}: {}",
                seen.direction()
            );
            // General angle: cos θ' = (cos θ + β)/(1 + β cos θ).
            for theta in [0.3f64, 1.0, 2.0, 3.0] {
                let dir = DVec3::new(theta.cos(), theta.sin(), 0.0);
                let emission = Event::new(5.0 - far / C, dir * far);
                let seen = eye.see(emission, ProperVelocity::ZERO, C, true);
                let expected = (theta.cos() + beta) / (1.0 + beta * theta.cos());
                assert!((seen.direction().x - expected).abs() < 1e-12);
                // Apparent distance: the light path in the observer's frame,
                // the null vector's time part, scaled by D = γ(1 − β·n).
                let d = doppler(-dir, ProperVelocity::ZERO, u);
                assert!((seen.distance / (far * d) - 1.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn at_rest_nothing_changes() {
        let eye = Eye {
            event: Event::new(1.0, DVec3::new(1.0, 1.0, 1.0)),
            u: ProperVelocity::ZERO,
        };
        let e = Event::new(1.0 - 2.0 / C, DVec3::new(1.0, 3.0, 1.0));
        let seen = eye.see(e, ProperVelocity::ZERO, C, true);
        assert!((seen.position - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-15);
        assert_eq!(seen.doppler, 1.0);
        assert_eq!(searchlight(2.0), 16.0);
    }

    #[test]
    fn placed_in_batches_equals_placed_one_by_one() {
        // Observers at rest, slow (textbook boost) and fast (light-cone
        // form), 150 emissions (batches of 64, 64 and 22), one at the eye:
        // the same bits as `place_in_own_frame`.
        let emissions: Vec<Emission> = (0..150)
            .map(|i| {
                let x = f64::from(i);
                let position = if i == 7 {
                    DVec3::new(0.3, -0.2, 1.0)
                } else {
                    DVec3::new((0.37 * x).sin() * 2.0, (0.11 * x).cos(), 0.01 * x)
                };
                Emission {
                    event: Event::new(2.0 - 0.013 * x, position),
                    u: ProperVelocity::ZERO,
                }
            })
            .collect();
        for u in [
            DVec3::ZERO,
            DVec3::new(0.4, -0.3, 0.0),
            DVec3::new(-2.5, 1.0, 0.2),
        ] {
            let eye = Eye {
                event: Event::new(2.0 - 0.013 * 7.0, DVec3::new(0.3, -0.2, 1.0)),
                u: ProperVelocity(u),
            };
            let frame = eye.frame();
            let mut out = Vec::new();
            eye.place_all_in_own_frame(&frame, &emissions, C, &mut out);
            assert_eq!(out.len(), emissions.len());
            for (e, s) in emissions.iter().zip(&out) {
                assert_eq!(*s, eye.place_in_own_frame(&frame, e.event, C));
            }
            assert_eq!(out[7].distance, 0.0);
        }
    }
}
