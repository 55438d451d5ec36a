//! The workload of BENCHMARKS.md's "Exact emission solves per second", in
//! one place for `lightcone bench optics`, the `optics_rate` example and
//! the criterion bench: a gas of 1 000 pucks (β < 0.8, pucks 3R apart) run
//! for 2 s of board time, so worldlines have kinks, seen from beside its
//! box by an eye at rest; every vertex of every puck solved (emission
//! event, then apparent position with aberration), each puck's contracted
//! shape built once, as the schedule's kinematics phase keeps it.

use glam::DVec3;
use rayon::prelude::*;

use super::eye::{Eye, Seen};
use super::view::{self, Method};
use super::{Emission, mesh};
use crate::physics::Billiard;
use crate::physics::gas::dense_box;
use crate::scene::Effects;
use crate::spacetime::{Event, ProperVelocity};
use crate::worldline::{ContractedShape, RestShape};

/// Output arrays of one body: its points' emission events and how they
/// are seen.
pub type BodyOutput = (Vec<Emission>, Vec<Seen>);

/// The gas, its meshes, the eye and each puck's contracted shape.
pub struct SolveRate {
    billiard: Billiard,
    shape: RestShape,
    eye: Eye,
    contracted: Vec<ContractedShape>,
}

impl SolveRate {
    /// `pucks` pucks of radius 3.05 cm, each a puck mesh of `segments`
    /// around (`2 × segments` vertices).
    #[must_use]
    pub fn gas(pucks: usize, segments: u32) -> Self {
        Self::gas_on_cloth(pucks, segments, 0.0)
    }

    /// [`Self::gas`] on a cloth of sliding friction `mu_g` (μg, m/s²; 0
    /// for none): every worldline brakes, so every emission lies on a
    /// braking segment (or after a puck's stop). At `mu_g` = 0.3 a puck
    /// at 0.8 c is still moving at the observation (t = 2 s).
    #[must_use]
    pub fn gas_on_cloth(pucks: usize, segments: u32, mu_g: f64) -> Self {
        let r = 0.0305;
        let mut billiard = dense_box(pucks, r, 3.0 * r, 0.8, 1.42, 11);
        if mu_g > 0.0 {
            billiard.set_sliding_friction(mu_g);
        }
        billiard.advance_to(2.0);
        let size = billiard.table();
        let eye = Eye {
            event: Event::new(2.0, DVec3::new(size.x / 2.0, -1.0, 0.8)),
            u: ProperVelocity::ZERO,
        };
        let contracted = (0..pucks)
            .map(|i| ContractedShape::of(billiard.worldline(i)))
            .collect();
        Self {
            billiard,
            shape: mesh::puck(r, 0.02, segments),
            eye,
            contracted,
        }
    }

    /// Number of pucks.
    #[must_use]
    pub fn pucks(&self) -> usize {
        self.contracted.len()
    }

    /// Vertices per puck.
    #[must_use]
    pub fn vertices_per_puck(&self) -> usize {
        self.shape.vertices.len()
    }

    /// Vertices of all pucks: what one [`Self::per_thread`] or
    /// [`Self::per_body`] solves.
    #[must_use]
    pub fn vertices(&self) -> usize {
        self.pucks() * self.vertices_per_puck()
    }

    /// Solves every vertex of puck `puck` into `out` (emission events, then
    /// apparent positions); returns the number solved.
    pub fn solve(&self, puck: usize, out: &mut BodyOutput) -> usize {
        let (emissions, seen) = out;
        let effects = Effects::default();
        view::emissions_with_shape(
            &self.contracted[puck],
            puck,
            self.billiard.worldline(puck),
            &self.shape.vertices,
            &self.eye,
            &effects,
            Method::Exact,
            emissions,
        );
        view::seen(&self.eye, self.billiard.c(), &effects, emissions, seen);
        seen.len()
    }

    /// Every puck solved on the current rayon pool, each thread reusing
    /// its own output arrays from one body to the next (in cache); returns
    /// the vertices solved.
    pub fn per_thread(&self) -> usize {
        (0..self.pucks())
            .into_par_iter()
            .map_init(BodyOutput::default, |out, puck| self.solve(puck, out))
            .sum()
    }

    /// Every puck solved on the current rayon pool into its own arrays of
    /// `kept` (one per puck, kept from frame to frame as the pipeline's
    /// `Apparent` keeps them: every call writes all of them); returns the
    /// vertices solved.
    pub fn per_body(&self, kept: &mut [BodyOutput]) -> usize {
        kept.par_iter_mut()
            .enumerate()
            .take(self.pucks())
            .map(|(puck, out)| self.solve(puck, out))
            .sum()
    }
}
