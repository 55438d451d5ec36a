//! The optics phase (the design's *retarded-render*): per view, one system
//! per effect and one for its absence. Each effect system's query asks
//! for the view's effect marker (`With<…>`), so it never runs for a view
//! without the effect, and its run condition keeps it out of the frame
//! when no view has it. Each writes its part of the view's [`Apparent`]
//! and records itself in [`Apparent::applied`].
//!
//! Order (chained): emission events (light delay or board-simultaneous),
//! then apparent positions (aberration or board directions), then the
//! Doppler factor, the searchlight and the clocks. The emission systems
//! place each body's points with the kinematics phase's contracted shape
//! ([`BodyContraction`]) for the views with [`Contraction`] (one query) and
//! with the rest shape ([`Rigid`]) for the others (another): the kernels
//! take the shape as data.

use bevy_ecs::prelude::*;
use glam::DVec3;
use rayon::prelude::*;

use crate::camera::{self, FIT_MARGIN, Framing};
use crate::ecs::components::{
    Aberration, Apparent, ApparentBody, BodyContraction, BodyRef, Contraction, Doppler, Fixture,
    FramingMarks, Lens, LightDelay, Mesh, Observer, OwnWorldline, PuckIndex, Searchlight,
    TimeDilation, Vantage, View,
};
use crate::ecs::resources::{Clock, History, OpticsMethod, Physics, SpeedOfLight};
use crate::optics::history::Search;
use crate::optics::view as kernel;
use crate::optics::{Emission, Eye, SampledHistory};
use crate::scene::Effects;
use crate::spacetime::Event;
use crate::worldline::{ContractedShape, Rigid, ShapeMaps, Worldline};

/// The pucks' meshes and contracted shapes.
pub type Pucks<'w, 's> =
    Query<'w, 's, (&'static PuckIndex, &'static Mesh, &'static BodyContraction)>;
/// The fixtures: number, worldline, mesh, contracted shape.
pub type Fixtures<'w, 's> = Query<
    'w,
    's,
    (
        &'static Fixture,
        &'static OwnWorldline,
        &'static Mesh,
        &'static BodyContraction,
    ),
>;
/// The observers' worldlines.
pub type Observers<'w, 's> = Query<'w, 's, &'static OwnWorldline, With<Observer>>;
/// The views with effect marker `M` and with (`C` = `With<Contraction>`)
/// or without (`Without<Contraction>`) contraction.
pub type ViewsWith<'w, 's, M, C> =
    Query<'w, 's, (&'static View, &'static Vantage, &'static mut Apparent), (M, C)>;

/// One body optics follows this frame.
struct Body<'a> {
    id: BodyRef,
    worldline: &'a Worldline,
    points: &'a [DVec3],
    /// Its contracted shape (empty when no view has [`Contraction`]).
    contracted: &'a ContractedShape,
}

/// Every puck (index order), then every fixture (number order).
fn bodies<'a>(physics: &'a Physics, pucks: &'a Pucks, fixtures: &'a Fixtures) -> Vec<Body<'a>> {
    let mut p: Vec<(usize, &Mesh, &BodyContraction)> =
        pucks.iter().map(|(i, m, s)| (i.0, m, s)).collect();
    p.sort_unstable_by_key(|(i, _, _)| *i);
    let mut f: Vec<(usize, &OwnWorldline, &Mesh, &BodyContraction)> =
        fixtures.iter().map(|(n, w, m, s)| (n.0, w, m, s)).collect();
    f.sort_unstable_by_key(|(n, _, _, _)| *n);
    p.into_iter()
        .map(|(i, m, s)| Body {
            id: BodyRef::Puck(i),
            worldline: physics.0.worldline(i),
            points: &m.points,
            contracted: &s.0,
        })
        .chain(f.into_iter().map(|(n, w, m, s)| Body {
            id: BodyRef::Fixture(n),
            worldline: &w.0,
            points: &m.points,
            contracted: &s.0,
        }))
        .collect()
}

/// The eye of a view at board time `t`, per its [`Vantage`].
#[must_use]
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
    apparent.applied = Effects::NONE;
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
    mut contracted: ViewsWith<With<LightDelay>, With<Contraction>>,
    mut rigid: ViewsWith<With<LightDelay>, Without<Contraction>>,
) {
    let sampled = match (&method, &history) {
        (Some(m), Some(h)) if m.0.sampled => Some((&h.0, m.search())),
        _ => None,
    };
    let bodies = bodies(&physics, &pucks, &fixtures);
    let ran = Effects {
        light_delay: true,
        ..Effects::NONE
    };
    let (t, observers) = (clock.t, &observers);
    emit(
        contracted.iter_mut(),
        &bodies,
        |b| b.contracted,
        with_contraction(ran),
        (t, observers),
        |s, b, e, out| light_delayed(sampled, s, b, e, out),
    );
    emit(
        rigid.iter_mut(),
        &bodies,
        |_| &Rigid,
        ran,
        (t, observers),
        |s, b, e, out| light_delayed(sampled, s, b, e, out),
    );
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
    mut contracted: ViewsWith<Without<LightDelay>, With<Contraction>>,
    mut rigid: ViewsWith<Without<LightDelay>, Without<Contraction>>,
) {
    let bodies = bodies(&physics, &pucks, &fixtures);
    let (t, observers) = (clock.t, &observers);
    emit(
        contracted.iter_mut(),
        &bodies,
        |b| b.contracted,
        with_contraction(Effects::NONE),
        (t, observers),
        |s, b, e, out| kernel::simultaneous(b.worldline, b.points, s, e, out),
    );
    emit(
        rigid.iter_mut(),
        &bodies,
        |_| &Rigid,
        Effects::NONE,
        (t, observers),
        |s, b, e, out| kernel::simultaneous(b.worldline, b.points, s, e, out),
    );
}

/// `effects` and contraction.
fn with_contraction(effects: Effects) -> Effects {
    Effects {
        contraction: true,
        ..effects
    }
}

/// The light-delay kernel for `body` of shape `shapes`: from the sampled
/// history for a puck when the scene asks for it, exactly otherwise.
fn light_delayed(
    sampled: Option<(&SampledHistory, Search)>,
    shapes: &impl ShapeMaps,
    body: &Body,
    eye: &Eye,
    out: &mut Vec<Emission>,
) {
    match (body.id, sampled) {
        (BodyRef::Puck(i), Some((h, search))) => kernel::light_delayed_sampled(
            h,
            search,
            i,
            body.worldline,
            body.points,
            shapes,
            eye,
            out,
        ),
        _ => kernel::light_delayed(body.worldline, body.points, shapes, eye, out),
    }
}

/// For each view of `views` (at the frame's board time, with the
/// observers, `frame`): starts its frame, runs the emission `kernel` on
/// every body with the shape `shape_of` picks for it, and records `ran` as
/// what was applied. Which shape is the caller's: the contracted one for
/// the views its query found with [`Contraction`], the rest shape for the
/// others.
fn emit<'a, 'v, S: ShapeMaps + 'a>(
    views: impl Iterator<Item = (&'v View, &'v Vantage, Mut<'v, Apparent>)>,
    bodies: &'a [Body<'a>],
    shape_of: impl Fn(&'a Body<'a>) -> &'a S + Sync,
    ran: Effects,
    frame: (f64, &Observers),
    kernel: impl Fn(&S, &Body, &Eye, &mut Vec<Emission>) + Sync,
) {
    let (t, observers) = frame;
    for (view, vantage, mut apparent) in views {
        let apparent = &mut *apparent;
        let Some(eye) = begin(view, *vantage, t, observers, apparent, bodies) else {
            continue;
        };
        apparent.applied = ran;
        apparent
            .bodies
            .par_iter_mut()
            .zip(bodies.par_iter())
            .for_each(|(out, body)| {
                kernel(shape_of(body), body, &eye, &mut out.emissions);
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
