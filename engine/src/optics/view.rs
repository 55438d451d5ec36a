//! The optics kernels, one per effect and one for its absence, with no
//! effect flags: light delay ([`light_delayed`], [`light_delayed_sampled`])
//! or board simultaneity ([`simultaneous`]); aberration ([`aberrated`]) or
//! board directions ([`on_board`]); [`doppler`]; [`searchlight_intensity`].
//! A body's shape is data they take ([`ShapeMaps`]: the kinematics phase's
//! contracted shape, or the rest shape [`Rigid`]), not a switch. The frame
//! schedule (`crate::ecs`) runs each as its own system for the views that
//! have the effect.
//!
//! [`observe`] composes them for one eye and one effect set (building each
//! puck's contracted shape itself when the set has contraction): the
//! engine tests' reference for the schedule's per-view output; [`emissions`]
//! and [`seen`] are its steps, which `lightcone bench optics` times.

use glam::DVec3;
use rayon::prelude::*;

use super::emission::{self, Emission};
use super::eye::{Eye, Seen, searchlight};
use super::history::{SampledHistory, Search};
use crate::physics::Billiard;
use crate::scene::Effects;
use crate::worldline::{ContractedShape, RestShape, Rigid, ShapeMaps, Worldline};

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

/// Light delay (kernel): the emission events of the points at rest-frame
/// `offsets` on a body moving along `worldline` with the shape `shapes`,
/// for light reaching the eye, exactly on the worldline.
pub fn light_delayed(
    worldline: &Worldline,
    offsets: &[DVec3],
    shapes: &impl ShapeMaps,
    eye: &Eye,
    out: &mut Vec<Emission>,
) {
    out.clear();
    super::batch::solve_body(worldline, offsets, DVec3::ZERO, shapes, eye.event, out);
}

/// Light delay (kernel) by the paper's method: emission events of `offsets`
/// on puck `puck` (shape `shapes`) searched in the sampled `history` (the
/// exact solve on `worldline` where the history has no sample yet).
#[allow(clippy::too_many_arguments)]
pub fn light_delayed_sampled(
    history: &SampledHistory,
    search: Search,
    puck: usize,
    worldline: &Worldline,
    offsets: &[DVec3],
    shapes: &impl ShapeMaps,
    eye: &Eye,
    out: &mut Vec<Emission>,
) {
    out.clear();
    let c = worldline.speed_of_light();
    out.extend(offsets.iter().map(|&r| {
        history
            .solve(puck, r, shapes, eye.event, c, search)
            .unwrap_or_else(|| emission::solve(worldline, r, shapes, eye.event))
    }));
}

/// Without light delay (kernel): every point of the body of shape
/// `shapes` where it is at the eye's board time (board-simultaneous, the
/// "truth"). The body's segment at that time is found once for all its
/// points.
pub fn simultaneous(
    worldline: &Worldline,
    offsets: &[DVec3],
    shapes: &impl ShapeMaps,
    eye: &Eye,
    out: &mut Vec<Emission>,
) {
    out.clear();
    let t = eye.event.t;
    let k = worldline.segment_index_at(t);
    out.extend(
        offsets
            .iter()
            .map(|&r| emission::simultaneous_on(worldline, k, r, shapes, t)),
    );
}

/// Aberration (kernel): apparent positions of `emissions` in the eye's
/// rest frame, relative to the eye. Doppler factors left at 1.
pub fn aberrated(eye: &Eye, c: f64, emissions: &[Emission], out: &mut Vec<Seen>) {
    out.clear();
    eye.place_all_in_own_frame(&eye.frame(), emissions, c, out);
}

/// Without aberration (kernel): board-frame offsets of `emissions` from
/// the eye. Doppler factors left at 1.
pub fn on_board(eye: &Eye, emissions: &[Emission], out: &mut Vec<Seen>) {
    out.clear();
    out.extend(emissions.iter().map(|e| eye.place_on_board(e.event)));
}

/// Doppler (kernel): the factor of each emission, into `seen` (same order).
pub fn doppler(eye: &Eye, emissions: &[Emission], seen: &mut [Seen]) {
    for (s, e) in seen.iter_mut().zip(emissions) {
        s.doppler = eye.doppler_of(e.event, e.u);
    }
}

/// Searchlight (kernel): the intensity factor `D⁴` of each emission.
pub fn searchlight_intensity(eye: &Eye, emissions: &[Emission], out: &mut Vec<f64>) {
    out.clear();
    out.extend(
        emissions
            .iter()
            .map(|e| searchlight(eye.doppler_of(e.event, e.u))),
    );
}

/// Emission events with the effects of `effects` (for [`observe`] and
/// `lightcone bench optics`): with contraction, the puck's contracted shape
/// built here ([`ContractedShape::of`]), else its rest shape.
pub fn emissions(
    billiard: &Billiard,
    puck: usize,
    offsets: &[DVec3],
    eye: &Eye,
    effects: &Effects,
    method: Method,
    out: &mut Vec<Emission>,
) {
    let w = billiard.worldline(puck);
    if effects.contraction {
        let shapes = ContractedShape::of(w);
        emissions_with_shape(&shapes, puck, w, offsets, eye, effects, method, out);
    } else {
        emissions_with_shape(&Rigid, puck, w, offsets, eye, effects, method, out);
    }
}

/// [`emissions`] of puck `puck` moving along `w` with the shape `shapes`
/// (light delay, exactly or by `method`, or board-simultaneous, as
/// `effects` asks).
#[allow(clippy::too_many_arguments)]
pub fn emissions_with_shape(
    shapes: &impl ShapeMaps,
    puck: usize,
    w: &Worldline,
    offsets: &[DVec3],
    eye: &Eye,
    effects: &Effects,
    method: Method,
    out: &mut Vec<Emission>,
) {
    match (effects.light_delay, method) {
        (false, _) => simultaneous(w, offsets, shapes, eye, out),
        (true, Method::Exact) => light_delayed(w, offsets, shapes, eye, out),
        (true, Method::Sampled(history, search)) => {
            light_delayed_sampled(history, search, puck, w, offsets, shapes, eye, out)
        }
    }
}

/// Apparent positions with or without aberration (for [`observe`] and the
/// front ends that predate the schedule).
pub fn seen(eye: &Eye, c: f64, effects: &Effects, emissions: &[Emission], out: &mut Vec<Seen>) {
    if effects.aberration {
        aberrated(eye, c, emissions, out);
    } else {
        on_board(eye, emissions, out);
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
#[must_use]
pub fn observe(
    billiard: &Billiard,
    shapes: &[RestShape],
    heights: &[f64],
    eye: Eye,
    effects: Effects,
    method: Method,
    with_vertices: bool,
) -> View {
    let bodies = (0..billiard.len())
        .into_par_iter()
        .map(|puck| {
            let vertices = with_vertices.then_some(shapes[puck].vertices.as_slice());
            let centre = DVec3::new(0.0, 0.0, heights[puck] / 2.0);
            let seen = Observed {
                billiard,
                eye: &eye,
                effects: &effects,
                method,
            };
            if effects.contraction {
                let contracted = ContractedShape::of(billiard.worldline(puck));
                seen.body(puck, &contracted, centre, vertices)
            } else {
                seen.body(puck, &Rigid, centre, vertices)
            }
        })
        .collect();
    View { eye, bodies }
}

/// What [`observe`] looks at.
struct Observed<'a> {
    billiard: &'a Billiard,
    eye: &'a Eye,
    effects: &'a Effects,
    method: Method<'a>,
}

impl Observed<'_> {
    /// Every point of `offsets` on `puck`, of shape `shapes`, as seen.
    fn points(&self, puck: usize, shapes: &impl ShapeMaps, offsets: &[DVec3]) -> Vec<PointView> {
        let (mut e, mut s) = (Vec::new(), Vec::new());
        let w = self.billiard.worldline(puck);
        emissions_with_shape(
            shapes,
            puck,
            w,
            offsets,
            self.eye,
            self.effects,
            self.method,
            &mut e,
        );
        seen(self.eye, self.billiard.c(), self.effects, &e, &mut s);
        doppler(self.eye, &e, &mut s);
        e.iter()
            .zip(&s)
            .map(|(e, s)| point(*e, *s, self.effects))
            .collect()
    }

    /// Puck `puck` (shape `shapes`): its `centre` (rest-frame offset) and
    /// its `vertices` if given.
    fn body(
        &self,
        puck: usize,
        shapes: &impl ShapeMaps,
        centre: DVec3,
        vertices: Option<&[DVec3]>,
    ) -> BodyView {
        let centre = self.points(puck, shapes, &[centre])[0];
        let seen_proper_time = if self.effects.time_dilation {
            self.billiard
                .worldline(puck)
                .proper_time_at(centre.emission.event.t)
        } else {
            centre.emission.event.t
        };
        BodyView {
            puck,
            centre,
            seen_proper_time,
            vertices: vertices.map_or_else(Vec::new, |v| self.points(puck, shapes, v)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spacetime::{Event, ProperVelocity};
    use crate::worldline::ContractedShape;

    /// The board-simultaneous kernel puts every point at the eye's board
    /// time, about the centre where the worldline has it then: the rest
    /// shape keeps each (turned) offset whole; the contracted one, on a
    /// uniform segment, shrinks its component along the motion by `1/γ`
    /// (`r⊥ + n (n·r)/γ`) and, braking (Born-rigid), by no more than that
    /// and no less than nothing, leaving the rest whole. Uniform and
    /// braking worldlines with kinks, at times between kinks, on them and
    /// before the start.
    #[test]
    fn simultaneous_points_are_the_shape_about_the_centre_at_that_time() {
        let c = 1.42;
        let offsets: Vec<DVec3> = (0..50)
            .map(|k| {
                let a = k as f64 * 0.37;
                DVec3::new(a.cos(), a.sin(), 0.01 * (k % 3) as f64) * 0.03
            })
            .collect();
        let start = Event::new(0.0, DVec3::new(0.5, 0.4, 0.0));
        let u = |x: f64, y: f64| ProperVelocity(DVec3::new(x, y, 0.0));
        let mut uniform = Worldline::new(start, u(1.5, -0.4), c);
        let mut braking = Worldline::braking(start, u(2.0, 0.7), c, 1.96);
        for (k, t) in [0.1, 0.25, 0.6].into_iter().enumerate() {
            let v = u(0.3 + k as f64, -0.8 * k as f64);
            uniform.push(t, v).unwrap();
            braking.push(t, v).unwrap();
        }
        for w in [&uniform, &braking] {
            let contracted = ContractedShape::of(w);
            for t in [-0.2, 0.0, 0.05, 0.1, 0.25, 0.3, 0.6, 0.9, 4.0] {
                let eye = Eye {
                    event: Event::new(t, DVec3::new(1.0, -1.0, 0.8)),
                    u: ProperVelocity::ZERO,
                };
                let s = w.segment_at(t);
                let (centre, n) = (w.position_at(t), s.direction());
                let mut rigid = Vec::new();
                simultaneous(w, &offsets, &Rigid, &eye, &mut rigid);
                let mut squeezed = Vec::new();
                simultaneous(w, &offsets, &contracted, &eye, &mut squeezed);
                for ((r, a), b) in offsets.iter().zip(&rigid).zip(&squeezed) {
                    assert!(a.event.t == t && b.event.t == t);
                    let turned = s.rotate(*r);
                    assert!((a.event.position - centre - turned).length() < 1e-12);
                    let q = b.event.position - centre;
                    let along = n.dot(turned);
                    let (q_along, q_across) = (n.dot(q), q - n * n.dot(q));
                    assert!(
                        (q_across - (turned - n * along)).length() < 1e-12,
                        "t = {t}"
                    );
                    if s.is_braking() {
                        assert!(q_along.abs() <= along.abs() + 1e-12, "t = {t}");
                        assert!(q_along * along >= 0.0, "t = {t}");
                    } else {
                        let expect = along / s.gamma();
                        assert!(
                            (q_along - expect).abs() < 1e-12,
                            "t = {t}: {q_along} {expect}"
                        );
                    }
                }
            }
        }
    }
}
