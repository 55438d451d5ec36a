//! The optics phase (the design's *retarded-render*): per view, one system
//! per effect and one for its absence. Each effect system's query asks
//! for the view's effect marker (`With<…>`), so it never runs for a view
//! without the effect, and its run condition keeps it out of the frame
//! when no view has it. Each writes its part of the view's [`Apparent`]
//! and records itself in [`Apparent::applied`].
//!
//! Order (chained): emission events (light delay or board-simultaneous),
//! then apparent positions (aberration or board directions), then the
//! Doppler factor, the searchlight and the clocks.

use bevy_ecs::prelude::*;
use glam::DVec3;
use rayon::prelude::*;

use crate::camera::{self, FIT_MARGIN, Framing};
use crate::ecs::components::{
    Aberration, Apparent, ApparentBody, BodyRef, Contraction, Doppler, Fixture, FramingMarks, Lens,
    LightDelay, Mesh, Observer, OwnWorldline, PuckIndex, Searchlight, TimeDilation, Vantage, View,
};
use crate::ecs::resources::{Clock, History, OpticsMethod, Physics, SpeedOfLight};
use crate::optics::Eye;
use crate::optics::view as kernel;
use crate::spacetime::Event;
use crate::worldline::Worldline;

/// The pucks' meshes.
pub type Pucks<'w, 's> = Query<'w, 's, (&'static PuckIndex, &'static Mesh)>;
/// The fixtures: number, worldline, mesh.
pub type Fixtures<'w, 's> = Query<'w, 's, (&'static Fixture, &'static OwnWorldline, &'static Mesh)>;
/// The observers' worldlines.
pub type Observers<'w, 's> = Query<'w, 's, &'static OwnWorldline, With<Observer>>;

/// One body optics follows this frame.
struct Body<'a> {
    id: BodyRef,
    worldline: &'a Worldline,
    points: &'a [DVec3],
}

/// Every puck (index order), then every fixture (number order).
fn bodies<'a>(physics: &'a Physics, pucks: &'a Pucks, fixtures: &'a Fixtures) -> Vec<Body<'a>> {
    let mut p: Vec<(usize, &Mesh)> = pucks.iter().map(|(i, m)| (i.0, m)).collect();
    p.sort_unstable_by_key(|(i, _)| *i);
    let mut f: Vec<(usize, &OwnWorldline, &Mesh)> =
        fixtures.iter().map(|(n, w, m)| (n.0, w, m)).collect();
    f.sort_unstable_by_key(|(n, _, _)| *n);
    p.into_iter()
        .map(|(i, m)| Body {
            id: BodyRef::Puck(i),
            worldline: physics.0.worldline(i),
            points: &m.points,
        })
        .chain(f.into_iter().map(|(n, w, m)| Body {
            id: BodyRef::Fixture(n),
            worldline: &w.0,
            points: &m.points,
        }))
        .collect()
}

/// The eye of a view at board time `t`, per its [`Vantage`].
pub fn eye_at(worldline: &Worldline, vantage: Vantage, t: f64) -> Eye {
    let state = worldline.state_at(match vantage {
        Vantage::OnWorldline => t,
        Vantage::ReplayAndMove { now } => now,
    });
    Eye {
        event: Event::new(t, state.position),
        u: state.u,
    }
}

/// Starts a view's frame: its eye, one entry per body, nothing applied
/// yet. `None` (and an empty output) if its observer is gone.
fn begin(
    view: &View,
    vantage: Vantage,
    t: f64,
    observers: &Observers,
    apparent: &mut Apparent,
    bodies: &[Body],
) -> Option<Eye> {
    apparent.applied = crate::scene::Effects::NONE;
    let Ok(worldline) = observers.get(view.observer) else {
        apparent.eye = None;
        apparent.bodies.clear();
        return None;
    };
    let eye = eye_at(&worldline.0, vantage, t);
    apparent.eye = Some(eye);
    apparent
        .bodies
        .resize_with(bodies.len(), ApparentBody::default);
    for (out, body) in apparent.bodies.iter_mut().zip(bodies) {
        out.body = body.id;
    }
    Some(eye)
}

/// After the emission solve: unit brightness, board-time clocks (the
/// searchlight and time dilation systems replace them for their views).
fn neutral(out: &mut ApparentBody) {
    out.intensity.clear();
    out.intensity.resize(out.emissions.len(), 1.0);
    out.seen_proper_time = out.emissions.last().map_or(0.0, |e| e.event.t);
}

/// Effect `light_delay`: each point seen where it was when its light left,
/// exactly on the worldlines, or from the paper's sampled history when the
/// scene asks for it. Contracted shapes for views with [`Contraction`].
#[allow(clippy::too_many_arguments)]
pub fn light_delay(
    clock: Res<Clock>,
    physics: Res<Physics>,
    method: Option<Res<OpticsMethod>>,
    history: Option<Res<History>>,
    pucks: Pucks,
    fixtures: Fixtures,
    observers: Observers,
    mut views: Query<(&View, &Vantage, &mut Apparent, Has<Contraction>), With<LightDelay>>,
) {
    let sampled = match (&method, &history) {
        (Some(m), Some(h)) if m.0.sampled => Some((&h.0, m.search())),
        _ => None,
    };
    let bodies = bodies(&physics, &pucks, &fixtures);
    for (view, vantage, mut apparent, contracted) in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = begin(view, *vantage, clock.t, &observers, apparent, &bodies) else {
            continue;
        };
        apparent.applied.light_delay = true;
        apparent.applied.contraction = contracted;
        apparent
            .bodies
            .par_iter_mut()
            .zip(bodies.par_iter())
            .for_each(|(out, body)| {
                match (body.id, sampled) {
                    (BodyRef::Puck(i), Some((h, search))) => kernel::light_delayed_sampled(
                        h,
                        search,
                        i,
                        body.worldline,
                        body.points,
                        contracted,
                        &eye,
                        &mut out.emissions,
                    ),
                    _ => kernel::light_delayed(
                        body.worldline,
                        body.points,
                        contracted,
                        &eye,
                        &mut out.emissions,
                    ),
                }
                neutral(out);
            });
    }
}

/// Without `light_delay`: each point where it is at the board time of the
/// observation (the board-frame "truth"). Contracted shapes for views with
/// [`Contraction`].
pub fn simultaneous(
    clock: Res<Clock>,
    physics: Res<Physics>,
    pucks: Pucks,
    fixtures: Fixtures,
    observers: Observers,
    mut views: Query<(&View, &Vantage, &mut Apparent, Has<Contraction>), Without<LightDelay>>,
) {
    let bodies = bodies(&physics, &pucks, &fixtures);
    for (view, vantage, mut apparent, contracted) in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = begin(view, *vantage, clock.t, &observers, apparent, &bodies) else {
            continue;
        };
        apparent.applied.contraction = contracted;
        apparent
            .bodies
            .par_iter_mut()
            .zip(bodies.par_iter())
            .for_each(|(out, body)| {
                kernel::simultaneous(
                    body.worldline,
                    body.points,
                    contracted,
                    &eye,
                    &mut out.emissions,
                );
                neutral(out);
            });
    }
}

/// Effect `aberration`: directions and distances in the observer's frame.
pub fn aberration(
    c: Res<SpeedOfLight>,
    mut views: Query<&mut Apparent, (With<View>, With<Aberration>)>,
) {
    for mut apparent in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = apparent.eye else { continue };
        apparent.applied.aberration = true;
        apparent.bodies.par_iter_mut().for_each(|b| {
            kernel::aberrated(&eye, c.0, &b.emissions, &mut b.seen);
        });
    }
}

/// Without `aberration`: board-frame directions and distances.
pub fn board_directions(mut views: Query<&mut Apparent, (With<View>, Without<Aberration>)>) {
    for mut apparent in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = apparent.eye else { continue };
        apparent.bodies.par_iter_mut().for_each(|b| {
            kernel::on_board(&eye, &b.emissions, &mut b.seen);
        });
    }
}

/// Effect `doppler`: each point's Doppler factor (the colour shift).
pub fn doppler(mut views: Query<&mut Apparent, (With<View>, With<Doppler>)>) {
    for mut apparent in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = apparent.eye else { continue };
        apparent.applied.doppler = true;
        apparent.bodies.par_iter_mut().for_each(|b| {
            kernel::doppler(&eye, &b.emissions, &mut b.seen);
        });
    }
}

/// Effect `searchlight`: each point's brightness factor `D⁴`.
pub fn searchlight(mut views: Query<&mut Apparent, (With<View>, With<Searchlight>)>) {
    for mut apparent in &mut views {
        let apparent = &mut *apparent;
        let Some(eye) = apparent.eye else { continue };
        apparent.applied.searchlight = true;
        apparent.bodies.par_iter_mut().for_each(|b| {
            kernel::searchlight_intensity(&eye, &b.emissions, &mut b.intensity);
        });
    }
}

/// Effect `time_dilation`: each body's clock in the image shows its proper
/// time at the centre's emission event.
pub fn time_dilation(
    physics: Res<Physics>,
    fixtures: Query<(&Fixture, &OwnWorldline)>,
    mut views: Query<&mut Apparent, (With<View>, With<TimeDilation>)>,
) {
    let fixture_lines: Vec<(usize, &Worldline)> =
        fixtures.iter().map(|(n, w)| (n.0, &w.0)).collect();
    for mut apparent in &mut views {
        let apparent = &mut *apparent;
        if apparent.eye.is_none() {
            continue;
        }
        apparent.applied.time_dilation = true;
        for b in &mut apparent.bodies {
            let worldline = match b.body {
                BodyRef::Puck(i) => physics.0.worldline(i),
                BodyRef::Fixture(n) => match fixture_lines.iter().find(|(k, _)| *k == n) {
                    Some((_, w)) => w,
                    None => continue,
                },
            };
            if let Some(centre) = b.emissions.last() {
                b.seen_proper_time = worldline.proper_time_at(centre.event.t);
            }
        }
    }
}

/// Aims every view's camera for this frame: along its direction
/// ([`Framing::Look`]), or fitted to the table as that view sees it, with
/// its own effects ([`Framing::Fit`], following a puck's apparent centre if
/// asked).
pub fn frame_cameras(
    marks: Query<&Fixture, With<FramingMarks>>,
    mut views: Query<(&Apparent, &mut Lens), With<View>>,
) {
    let marks = marks.iter().next().map(|f| BodyRef::Fixture(f.0));
    for (apparent, mut lens) in &mut views {
        lens.camera = match lens.framing {
            Framing::Look {
                forward,
                fovy,
                zoom,
            } => camera::zoomed(forward, fovy, zoom),
            Framing::Fit {
                aspect,
                zoom,
                follow,
            } => {
                let points: Vec<DVec3> = apparent
                    .bodies
                    .iter()
                    .find(|b| Some(b.body) == marks)
                    .map(|b| {
                        b.seen[..b.vertex_count()]
                            .iter()
                            .map(|s| s.position)
                            .collect()
                    })
                    .unwrap_or_default();
                let mut fitted = camera::fit(&points, aspect, FIT_MARGIN, zoom);
                let centre = follow.and_then(|i| {
                    apparent
                        .bodies
                        .iter()
                        .find(|b| b.body == BodyRef::Puck(i))
                        .and_then(|b| b.seen.get(b.centre()))
                });
                if let Some(s) = centre
                    && s.position.length() > 1e-9
                {
                    fitted.forward = s.position.normalize();
                }
                fitted
            }
        };
    }
}
