//! The paper's method (§3.2.3), kept as the honest baseline: each frame the
//! state of every body is stored in a history table; the emission event of
//! a vertex is found by dichotomy over that table, optionally refined by
//! linear interpolation between the two samples around the light cone.
//!
//! The paper stores every vertex's contracted position each frame (its
//! Table 1: 94.6 MB for 10 pucks of 496 vertices × 1 000 frames). Here each
//! frame stores a body's centre and velocity, and a vertex's position is
//! rebuilt from its rest-frame offset, exactly as the paper's table would
//! hold it: the same positions, the same search, less memory. Both figures
//! are in BENCHMARKS.md.

use glam::DVec3;

use super::emission::Emission;
use crate::spacetime::{Event, ProperVelocity, rotate_about_normal};
use crate::worldline::{ShapeMaps, Worldline};

/// How the sampled history is searched.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Search {
    /// Bisection steps; fewer than log₂(samples) stops at a coarser bracket
    /// (its earlier end is taken). `u32::MAX`: until the bracket is one
    /// sample wide.
    pub iterations: u32,
    /// Interpolate linearly between the two bracketing samples.
    pub interpolate: bool,
}

impl Default for Search {
    fn default() -> Self {
        Self {
            iterations: u32::MAX,
            interpolate: true,
        }
    }
}

/// One body's samples: board time, centre and proper velocity.
#[derive(Clone, Debug, Default)]
struct Track {
    centre: Vec<DVec3>,
    u: Vec<ProperVelocity>,
    /// Rest-frame orientation (Thomas–Wigner rotation), rad.
    orientation: Vec<f64>,
}

/// The history table: one sample per body per recorded frame, the newest
/// `capacity` kept.
#[derive(Clone, Debug)]
pub struct SampledHistory {
    capacity: usize,
    times: Vec<f64>,
    tracks: Vec<Track>,
}

impl SampledHistory {
    /// A table for `bodies` bodies keeping the newest `capacity` frames.
    #[must_use]
    pub fn new(bodies: usize, capacity: usize) -> Self {
        Self {
            capacity: capacity.max(2),
            times: Vec::with_capacity(capacity),
            tracks: vec![Track::default(); bodies],
        }
    }

    /// Forgets every frame, keeping the bodies and the capacity.
    pub fn clear(&mut self) {
        self.times.clear();
        for track in &mut self.tracks {
            *track = Track::default();
        }
    }

    /// Frames held.
    #[must_use]
    pub fn len(&self) -> usize {
        self.times.len()
    }

    /// Whether no frame is held.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }

    /// Bytes of sample data held (times, centres, velocities, orientations).
    #[must_use]
    pub fn memory_bytes(&self) -> usize {
        self.times.len() * (8 + self.tracks.len() * (24 + 24 + 8))
    }

    /// Records every body's state at board time `t` (later than the last
    /// recorded; an earlier or equal time is ignored), read off the
    /// worldlines, as the paper's simulation loop does each frame.
    pub fn record<'a>(&mut self, t: f64, worldlines: impl IntoIterator<Item = &'a Worldline>) {
        if self.times.last().is_some_and(|&last| t <= last) {
            return;
        }
        let full = self.times.len() == self.capacity;
        if full {
            self.times.remove(0);
        }
        self.times.push(t);
        for (track, w) in self.tracks.iter_mut().zip(worldlines) {
            if full {
                track.centre.remove(0);
                track.u.remove(0);
                track.orientation.remove(0);
            }
            let s = w.state_at(t);
            track.centre.push(s.position);
            track.u.push(s.u);
            track.orientation.push(s.orientation);
        }
    }

    /// Sample `i` of the point at rest-frame `offset` of `body`, of shape
    /// `shapes` at the sample's velocity.
    fn position(&self, body: usize, i: usize, offset: DVec3, shapes: &impl ShapeMaps) -> DVec3 {
        let track = &self.tracks[body];
        let turned = rotate_about_normal(offset, track.orientation[i]);
        track.centre[i] + shapes.moving_with(track.u[i]).apply(turned)
    }

    /// The emission event of the point at `offset` on `body` (of shape
    /// `shapes`: contracted at each sample's velocity, or the rest shape)
    /// for light reaching `observation`, by dichotomy over the table.
    /// Before the oldest sample the oldest is used; after the newest, the
    /// newest. `None` if the table is empty.
    pub fn solve(
        &self,
        body: usize,
        offset: DVec3,
        shapes: &impl ShapeMaps,
        observation: Event,
        c: f64,
        search: Search,
    ) -> Option<Emission> {
        let n = self.times.len();
        if n == 0 {
            return None;
        }
        // f ≥ 0: the sample is inside (or on) the past light cone.
        let f = |i: usize| {
            c * (observation.t - self.times[i])
                - (observation.position - self.position(body, i, offset, shapes)).length()
        };
        let sample = |i: usize| Emission {
            event: Event::new(self.times[i], self.position(body, i, offset, shapes)),
            u: self.tracks[body].u[i],
        };
        if f(0) < 0.0 {
            return Some(sample(0));
        }
        // Invariant: f(lo) ≥ 0; f(hi) < 0 or hi = n.
        let (mut lo, mut hi) = (0usize, n);
        let mut steps = 0;
        while hi - lo > 1 && steps < search.iterations {
            let mid = lo + (hi - lo) / 2;
            if f(mid) >= 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
            steps += 1;
        }
        if !search.interpolate || hi == n || hi - lo > 1 {
            return Some(sample(lo));
        }
        let (f0, f1) = (f(lo), f(hi));
        let s = f0 / (f0 - f1);
        let (a, b) = (sample(lo), sample(hi));
        Some(Emission {
            event: Event::new(
                a.event.t + s * (b.event.t - a.event.t),
                a.event.position + s * (b.event.position - a.event.position),
            ),
            u: a.u,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::emission;
    use crate::worldline::ContractedShape;

    const C: f64 = 1.42;

    #[test]
    fn converges_to_the_exact_solve() {
        let u = ProperVelocity::try_from_beta(DVec3::new(0.8, 0.3, 0.0)).unwrap();
        let mut w = Worldline::new(Event::new(0.0, DVec3::new(0.3, 0.3, 0.0)), u, C);
        w.push(
            1.0,
            ProperVelocity::try_from_beta(DVec3::new(-0.5, 0.2, 0.0)).unwrap(),
        )
        .unwrap();
        let obs = Event::new(2.5, DVec3::new(1.4, -1.0, 0.9));
        let offset = DVec3::new(0.03, 0.0, 0.01);
        let shapes = ContractedShape::of(&w);
        let exact = emission::solve(&w, offset, &shapes, obs);
        let mut last_err = f64::INFINITY;
        for fps in [30.0, 120.0, 480.0] {
            let mut h = SampledHistory::new(1, 100_000);
            let mut t = 0.0;
            while t <= 2.5 {
                h.record(t, [&w]);
                t += 1.0 / fps;
            }
            let with = h
                .solve(0, offset, &shapes, obs, C, Search::default())
                .unwrap();
            let without = h
                .solve(
                    0,
                    offset,
                    &shapes,
                    obs,
                    C,
                    Search {
                        iterations: u32::MAX,
                        interpolate: false,
                    },
                )
                .unwrap();
            let err = (with.event.position - exact.event.position).length();
            let err_raw = (without.event.position - exact.event.position).length();
            assert!(
                err <= err_raw + 1e-15,
                "interpolation helps: {err} vs {err_raw}"
            );
            assert!(err < last_err || err < 1e-12);
            last_err = err;
            // Without interpolation the error is at most a frame of motion.
            assert!(err_raw <= u.velocity(C).length() / fps * 1.01 + 1e-12);
        }
    }

    #[test]
    fn capacity_drops_the_oldest() {
        let w = Worldline::new(Event::default(), ProperVelocity::ZERO, C);
        let mut h = SampledHistory::new(1, 3);
        for t in 0..10 {
            h.record(f64::from(t), [&w]);
        }
        assert_eq!(h.len(), 3);
        assert_eq!(h.memory_bytes(), 3 * (8 + 56));
    }
}
