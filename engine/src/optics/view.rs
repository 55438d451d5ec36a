//! Everything an observer sees at one event: every puck's vertices (and its
//! centre at mid-height) with emission event, apparent position, Doppler
//! factor and searchlight intensity, and the clocks. The stages are plain
//! functions so that the frame schedule can run each effect as its own
//! system under a run condition; [`observe`] runs them all in order.

use glam::DVec3;
use rayon::prelude::*;

use super::emission::{self, Emission};
use super::eye::{Eye, Seen, searchlight};
use super::history::{SampledHistory, Search};
use crate::physics::Billiard;
use crate::scene::Effects;
use crate::worldline::RestShape;

/// How emission events are found.
#[derive(Clone, Copy, Debug)]
pub enum Method<'a> {
    /// Exactly, on the worldlines (the engine's default).
    Exact,
    /// The paper's sampled history, searched by dichotomy.
    Sampled(&'a SampledHistory, Search),
}

/// One point as seen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointView {
    /// Emission event and emitter velocity.
    pub emission: Emission,
    /// Where it appears, Doppler factor (1 when the effect is off).
    pub seen: Seen,
    /// Searchlight intensity factor (1 when the effect is off).
    pub intensity: f64,
}

/// One puck as seen.
#[derive(Clone, Debug, PartialEq)]
pub struct BodyView {
    /// Index of the puck.
    pub puck: usize,
    /// Its centre at mid-height.
    pub centre: PointView,
    /// Proper time the puck's clock shows in the image (at the centre's
    /// emission event); board time of emission when time dilation is off.
    pub seen_proper_time: f64,
    /// Every vertex of its mesh (empty unless asked for).
    pub vertices: Vec<PointView>,
}

/// What one observer sees.
#[derive(Clone, Debug, PartialEq)]
pub struct View {
    /// The observer.
    pub eye: Eye,
    /// Every puck, in index order.
    pub bodies: Vec<BodyView>,
}

/// Finds the emission events of `offsets` on puck `puck` (light delay on),
/// or their board-simultaneous positions (off).
pub fn emissions(
    billiard: &Billiard,
    puck: usize,
    offsets: &[DVec3],
    eye: &Eye,
    effects: &Effects,
    method: Method,
    out: &mut Vec<Emission>,
) {
    out.clear();
    let w = billiard.worldline(puck);
    let contracted = effects.contraction;
    if !effects.light_delay {
        out.extend(
            offsets
                .iter()
                .map(|&r| emission::simultaneous(w, r, contracted, eye.event.t)),
        );
        return;
    }
    match method {
        Method::Exact => emission::solve_body(w, offsets, DVec3::ZERO, contracted, eye.event, out),
        Method::Sampled(history, search) => out.extend(offsets.iter().map(|&r| {
            history
                .solve(puck, r, contracted, eye.event, billiard.c(), search)
                .unwrap_or_else(|| emission::solve(w, r, contracted, eye.event))
        })),
    }
}

/// Apparent positions of emissions, in the observer's frame with
/// aberration on, in the board frame with it off. Doppler factors are left
/// at 1 (see [`doppler`]).
pub fn seen(eye: &Eye, c: f64, effects: &Effects, emissions: &[Emission], out: &mut Vec<Seen>) {
    out.clear();
    let frame = eye.frame();
    out.extend(
        emissions
            .iter()
            .map(|e| eye.place(&frame, e.event, c, effects.aberration)),
    );
}

/// Doppler factors of emissions, into `seen` (same order).
pub fn doppler(eye: &Eye, emissions: &[Emission], seen: &mut [Seen]) {
    for (s, e) in seen.iter_mut().zip(emissions) {
        s.doppler = eye.doppler_of(e.event, e.u);
    }
}

fn point(e: Emission, s: Seen, effects: &Effects) -> PointView {
    PointView {
        emission: e,
        seen: Seen {
            doppler: if effects.doppler { s.doppler } else { 1.0 },
            ..s
        },
        intensity: if effects.searchlight {
            searchlight(s.doppler)
        } else {
            1.0
        },
    }
}

/// Everything `eye` sees of the pucks, each with the rest shape in
/// `shapes[puck]` (vertices listed only if `with_vertices`). Pucks are
/// solved in parallel.
pub fn observe(
    billiard: &Billiard,
    shapes: &[RestShape],
    heights: &[f64],
    eye: Eye,
    effects: Effects,
    method: Method,
    with_vertices: bool,
) -> View {
    let c = billiard.c();
    // Every point of `offsets` on `puck`, as seen.
    let points = |puck: usize, offsets: &[DVec3]| -> Vec<PointView> {
        let (mut e, mut s) = (Vec::new(), Vec::new());
        emissions(billiard, puck, offsets, &eye, &effects, method, &mut e);
        seen(&eye, c, &effects, &e, &mut s);
        doppler(&eye, &e, &mut s);
        e.iter()
            .zip(&s)
            .map(|(e, s)| point(*e, *s, &effects))
            .collect()
    };
    let bodies = (0..billiard.len())
        .into_par_iter()
        .map(|puck| {
            let centre = points(puck, &[DVec3::new(0.0, 0.0, heights[puck] / 2.0)])[0];
            let w = billiard.worldline(puck);
            let seen_proper_time = if effects.time_dilation {
                w.proper_time_at(centre.emission.event.t)
            } else {
                centre.emission.event.t
            };
            let vertices = if with_vertices {
                points(puck, &shapes[puck].vertices)
            } else {
                Vec::new()
            };
            BodyView {
                puck,
                centre,
                seen_proper_time,
                vertices,
            }
        })
        .collect();
    View { eye, bodies }
}
