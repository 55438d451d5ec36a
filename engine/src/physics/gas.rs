//! A gas of pucks: many pucks on a grid with random velocities, for the
//! stress tests and the benchmarks.

use glam::{DVec2, DVec3};
use rand_xoshiro::Xoshiro256PlusPlus;
use rand_xoshiro::rand_core::{Rng as _, SeedableRng};

use super::{Billiard, PuckInit};
use crate::spacetime::ProperVelocity;

/// Deterministic pseudo-random numbers: xoshiro256++ (the `rand_xoshiro`
/// crate, value-stable across its versions and every platform), seeded
/// by `SeedableRng::seed_from_u64`, so a gas is the same on every
/// machine. The workspace's one seeded generator: gases, the random scenes
/// of the tests, the property tests' own cases aside (proptest's).
#[derive(Clone, Debug)]
pub struct Rng(Xoshiro256PlusPlus);

impl Rng {
    /// A generator from a seed (any value, 0 included).
    #[must_use]
    pub fn new(seed: u64) -> Self {
        Self(Xoshiro256PlusPlus::seed_from_u64(seed))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// The next number in [0, 1), with 53 random bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// `n` pucks of radius `radius` on a square grid with spacing `spacing`
/// (≥ 2 radius) in a square box just large enough, moving in random
/// directions with speeds uniform in [0, `max_beta`) c. Elastic.
#[must_use]
pub fn dense_box(
    n: usize,
    radius: f64,
    spacing: f64,
    max_beta: f64,
    c: f64,
    seed: u64,
) -> Billiard {
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let size = DVec2::splat(spacing * side as f64);
    let mut rng = Rng::new(seed);
    let pucks = (0..n)
        .map(|i| {
            let (gx, gy) = ((i % side) as f64, (i / side) as f64);
            let phi = std::f64::consts::TAU * rng.next_f64();
            let b = max_beta * rng.next_f64();
            PuckInit {
                name: format!("p{i}"),
                position: DVec2::new(spacing * (gx + 0.5), spacing * (gy + 0.5)),
                u: ProperVelocity::try_from_beta(DVec3::new(b * phi.cos(), b * phi.sin(), 0.0))
                    .unwrap_or(ProperVelocity::ZERO),
                radius,
                mass: 0.21,
            }
        })
        .collect();
    Billiard::new(c, size, 1.0, 1.0, pucks)
}
