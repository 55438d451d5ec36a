//! The optics phase (the design's *retarded-render*): per observer, one
//! system per effect, each under a run condition on the scene's effects.
//! With `light_delay` off the view is board-simultaneous (the "truth").
//! Their output, the observer's [`Apparent`] component, is what a renderer
//! draws without knowing any relativity.

use bevy_ecs::prelude::*;
use rayon::prelude::*;

use super::emission::Emission;
use super::eye::{Eye, Seen, searchlight as searchlight_factor};
use super::history::{SampledHistory, Search};
use super::view::{self, Method};
use crate::scene::{Effects, OpticsSpec};
use crate::world::{Clock, Physics, Puck, PuckIndex};
use crate::worldline::{RestShape, Worldline};

/// One puck as an observer sees it this frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ApparentBody {
    /// Index of the puck.
    pub puck: usize,
    /// Emission event of each vertex (rest-shape order).
    pub emissions: Vec<Emission>,
    /// Apparent position (observer frame, relative to the eye), direction,
    /// distance and Doppler factor of each vertex.
    pub seen: Vec<Seen>,
    /// Searchlight intensity factor of each vertex (1 when off).
    pub intensity: Vec<f64>,
}

/// What one observer sees this frame, written by the optics systems.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct Apparent {
    /// The eye this frame.
    pub eye: Option<Eye>,
    /// Every puck.
    pub bodies: Vec<ApparentBody>,
}

fn eye_of(worldline: &Worldline, t: f64) -> Eye {
    let s = worldline.state_at(t);
    Eye {
        event: crate::spacetime::Event::new(t, s.position),
        u: s.u,
    }
}

/// Makes sure each observer's [`Apparent`] lists every puck, sets its eye,
/// and solves emission events; with `light_delay` off, board-simultaneous.
fn solve_emissions(
    clock: &Clock,
    physics: &Physics,
    effects: &Effects,
    method: Method,
    pucks: &Query<(&PuckIndex, &RestShape), With<Puck>>,
    observers: &mut Query<(&Worldline, &mut Apparent)>,
) {
    let shapes: Vec<(usize, &RestShape)> = pucks.iter().map(|(i, s)| (i.0, s)).collect();
    for (worldline, mut apparent) in observers {
        let eye = eye_of(worldline, clock.t);
        apparent.eye = Some(eye);
        apparent
            .bodies
            .resize_with(shapes.len(), ApparentBody::default);
        apparent
            .bodies
            .par_iter_mut()
            .zip(shapes.par_iter())
            .for_each(|(body, &(puck, shape))| {
                body.puck = puck;
                view::emissions(
                    &physics.0,
                    puck,
                    &shape.vertices,
                    &eye,
                    effects,
                    method,
                    &mut body.emissions,
                );
            });
    }
}

/// The paper's per-frame history table, kept when the scene's `[optics]`
/// asks for the sampled method.
#[derive(Resource, Clone, Debug)]
pub struct History(pub SampledHistory);

/// Run condition: the scene asks for the sampled history.
pub fn sampled_history(spec: Res<OpticsSpec>) -> bool {
    spec.sampled
}

/// History phase (the design's *history* system): records every body's
/// state at the clock's board time, as the paper's loop does each frame.
pub fn record_history(clock: Res<Clock>, physics: Res<Physics>, mut history: ResMut<History>) {
    let b = &physics.0;
    history
        .0
        .record(clock.t, (0..b.len()).map(|i| b.worldline(i)));
}

/// Effect `light_delay`: each vertex seen where it was when its light left,
/// exactly, or from the sampled history when the scene asks for it.
pub fn light_delay(
    clock: Res<Clock>,
    physics: Res<Physics>,
    effects: Res<Effects>,
    spec: Res<OpticsSpec>,
    history: Option<Res<History>>,
    pucks: Query<(&PuckIndex, &RestShape), With<Puck>>,
    mut observers: Query<(&Worldline, &mut Apparent)>,
) {
    let method = match (&history, spec.sampled) {
        (Some(h), true) => Method::Sampled(
            &h.0,
            Search {
                iterations: if spec.dichotomy_steps == 0 {
                    u32::MAX
                } else {
                    spec.dichotomy_steps
                },
                interpolate: spec.interpolate,
            },
        ),
        _ => Method::Exact,
    };
    solve_emissions(&clock, &physics, &effects, method, &pucks, &mut observers);
}

/// With `light_delay` off: each vertex where it is at the board time of
/// the observation (the board-frame "truth" view).
pub fn simultaneous(
    clock: Res<Clock>,
    physics: Res<Physics>,
    effects: Res<Effects>,
    pucks: Query<(&PuckIndex, &RestShape), With<Puck>>,
    mut observers: Query<(&Worldline, &mut Apparent)>,
) {
    solve_emissions(
        &clock,
        &physics,
        &effects,
        Method::Exact,
        &pucks,
        &mut observers,
    );
}

fn place(physics: &Physics, effects: &Effects, observers: &mut Query<&mut Apparent>) {
    let c = physics.0.c();
    for mut apparent in observers {
        let Some(eye) = apparent.eye else { continue };
        apparent.bodies.par_iter_mut().for_each(|body| {
            view::seen(&eye, c, effects, &body.emissions, &mut body.seen);
        });
    }
}

/// Effect `aberration`: directions and distances in the observer's frame.
pub fn aberration(
    physics: Res<Physics>,
    effects: Res<Effects>,
    mut observers: Query<&mut Apparent>,
) {
    place(&physics, &effects, &mut observers);
}

/// With `aberration` off: board-frame directions and distances.
pub fn board_directions(
    physics: Res<Physics>,
    effects: Res<Effects>,
    mut observers: Query<&mut Apparent>,
) {
    place(&physics, &effects, &mut observers);
}

/// Effect `doppler` (and the searchlight, which needs it): each vertex's
/// Doppler factor.
pub fn doppler(mut observers: Query<&mut Apparent>) {
    for mut apparent in &mut observers {
        let Some(eye) = apparent.eye else { continue };
        apparent.bodies.par_iter_mut().for_each(|body| {
            view::doppler(&eye, &body.emissions, &mut body.seen);
        });
    }
}

/// With `doppler` off: no colour shift (the factor computed for the
/// searchlight is kept there, not shown as colour).
pub fn no_colour_shift(mut observers: Query<&mut Apparent>) {
    for mut apparent in &mut observers {
        for body in &mut apparent.bodies {
            for s in &mut body.seen {
                s.doppler = 1.0;
            }
        }
    }
}

/// Effect `searchlight`: brightness scaled by D⁴.
pub fn searchlight(mut observers: Query<&mut Apparent>) {
    for mut apparent in &mut observers {
        for body in &mut apparent.bodies {
            body.intensity.clear();
            let seen = &body.seen;
            body.intensity
                .extend(seen.iter().map(|s| searchlight_factor(s.doppler)));
        }
    }
}

/// With `searchlight` off: unit brightness.
pub fn no_searchlight(mut observers: Query<&mut Apparent>) {
    for mut apparent in &mut observers {
        for body in &mut apparent.bodies {
            let n = body.seen.len();
            body.intensity.clear();
            body.intensity.resize(n, 1.0);
        }
    }
}
