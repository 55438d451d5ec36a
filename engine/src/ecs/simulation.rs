//! One simulation: a world built from a scene and its frame schedule, the
//! one way to advance the worldlines and to get what each view sees.

use bevy_ecs::prelude::*;
use glam::{DVec2, DVec3};

use super::components::{
    Apparent, BodyContraction, BodyName, BodyRef, Fixture, FramingMarks, Lens, Mesh, Observer,
    OwnWorldline, ProperTime, Puck, PuckIndex, Tint, Vantage, View, effects_of, set_effect_marker,
};
use super::resources::{Clock, History, OpticsMethod, Physics, SpeedOfLight, Table};
use super::schedule::frame_schedule;
use super::systems::input;
use super::systems::optics::eye_at;
use crate::camera::{self, Camera, DEFAULT_ASPECT, Framing};
use crate::optics::view::{self as kernel, Method};
use crate::optics::{Eye, SampledHistory, Seen};
use crate::physics::Billiard;
use crate::scene::{Color, Effect, Effects, Scene};
use crate::spacetime::{Event, ProperVelocity};
use crate::worldline::mesh::{self, CUSHION_HEIGHT, CUSHION_WIDTH, PUCK_SEGMENTS};
use crate::worldline::{ContractedShape, RestShape, Rigid, Worldline, WorldlineError};

/// Why an observer cannot be moved.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ObserverError {
    /// The entity is not an observer (or was removed).
    #[error("no such observer")]
    NoSuchObserver,
    /// The kink does not fit the worldline.
    #[error(transparent)]
    Worldline(#[from] WorldlineError),
}

/// What a view saw of one point at one past board time
/// ([`Simulation::seen_history`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeenThen {
    /// The view's eye then.
    pub eye: Eye,
    /// Where and when the light it received left the point (board frame).
    pub emission: crate::optics::Emission,
    /// The apparent point, relative to that eye.
    pub seen: Seen,
}

/// One simulation: the ECS world and its frame schedule.
pub struct Simulation {
    /// The ECS world (public so front ends can query it).
    pub world: World,
    schedule: Schedule,
    views: Vec<Entity>,
}

/// The least history [`Simulation::history_needed`] asks for, s of board
/// time: as much as the game's replay keeps, so that up to that time a
/// headless run forgets nothing (a picture at t < 600 s is drawn from the
/// whole past, as before).
pub const HEADLESS_HISTORY: f64 = 600.0;

impl Simulation {
    /// Builds the world for `scene`: one entity per puck, per table part
    /// (fixtures at rest) and per observer, each observer with a worldline
    /// starting at board time 0 and one view with the scene's effects,
    /// named after it, its camera aimed by [`ObserverSpec::framing`] (along
    /// the observer's `look_at` if the scene names one, else fitted to the
    /// whole table in a 16:9 viewport: set the view's framing for another
    /// aspect). Runs the frame at board time 0.
    ///
    /// [`ObserverSpec::framing`]: crate::scene::ObserverSpec::framing
    #[must_use]
    pub fn new(scene: &Scene) -> Self {
        let mut world = World::new();
        world.insert_resource(Clock::default());
        world.insert_resource(SpeedOfLight(scene.c));
        world.insert_resource(Table(scene.table));
        world.insert_resource(OpticsMethod(scene.optics));
        if scene.optics.sampled {
            world.insert_resource(History(SampledHistory::new(
                scene.pucks.len(),
                scene.optics.history_frames,
            )));
        }
        world.insert_resource(Physics(Billiard::from_scene(scene)));
        for (i, p) in scene.pucks.iter().enumerate() {
            world.spawn((
                PuckIndex(i),
                Puck {
                    radius: p.radius,
                    height: p.height,
                    mass: p.mass,
                },
                BodyName(p.name.clone()),
                Tint(p.color),
                Mesh::new(
                    RestShape::puck(p.radius, p.height, PUCK_SEGMENTS),
                    DVec3::new(0.0, 0.0, p.height / 2.0),
                ),
                BodyContraction::default(),
                ProperTime::default(),
            ));
        }
        let at_rest = Worldline::new(Event::new(0.0, DVec3::ZERO), ProperVelocity::ZERO, scene.c);
        for (n, part) in mesh::table(scene.table.size, CUSHION_HEIGHT, CUSHION_WIDTH)
            .into_iter()
            .enumerate()
        {
            let centre = part.vertices.iter().sum::<DVec3>() / part.vertices.len().max(1) as f64;
            world.spawn((
                Fixture(n),
                OwnWorldline(at_rest.clone()),
                Mesh::new(part, centre),
                BodyContraction::default(),
            ));
        }
        let marks = RestShape {
            vertices: camera::table_corners(scene.table.size, CUSHION_HEIGHT, CUSHION_WIDTH),
            triangles: Vec::new(),
        };
        let centre = marks.vertices.iter().sum::<DVec3>() / marks.vertices.len() as f64;
        let n = world.query::<&Fixture>().iter(&world).count();
        world.spawn((
            Fixture(n),
            FramingMarks,
            OwnWorldline(at_rest),
            Mesh::new(marks, centre),
            BodyContraction::default(),
        ));
        let mut sim = Self {
            world,
            schedule: frame_schedule(),
            views: Vec::new(),
        };
        for o in &scene.observers {
            let forward = (o.target(scene.table.size) - o.position).normalize_or(DVec3::Y);
            let observer = sim.add_observer(
                &o.name,
                Worldline::new(Event::new(0.0, o.position), o.u, scene.c),
                forward,
            );
            sim.add_view(
                &o.name,
                observer,
                scene.effects,
                o.framing(DEFAULT_ASPECT),
                Vantage::OnWorldline,
            );
        }
        sim.advance_to(0.0);
        sim
    }

    /// Runs the physics to board time `t` (the billiard resolves every
    /// event up to it: [`Billiard::advance_to`], the one place board time
    /// advances), then one frame of the schedule at `t`. A time before the
    /// physics' (a replay) moves nothing: the frame re-reads the
    /// worldlines, where the past is.
    pub fn advance_to(&mut self, t: f64) {
        self.physics_mut().advance_to(t);
        self.world.resource_mut::<Clock>().t = t;
        self.schedule.run(&mut self.world);
    }

    /// Forgets what the paper's sampled optics (`[optics] method =
    /// "sampled"`) has recorded, keeping its capacity: the next frames
    /// sample afresh. For a view asked about past times in any order (the
    /// Python `Simulation`): a frame at 0 then one at `t` samples what a
    /// new simulation run to `t` samples. Nothing for exact optics.
    pub fn restart_sampled_history(&mut self) {
        if let Some(mut history) = self.world.get_resource_mut::<History>() {
            history.0.clear();
        }
    }

    /// Board time of the last frame, s.
    pub fn time(&self) -> f64 {
        self.world.resource::<Clock>().t
    }

    /// How far back, s of board time, the physics must remember for `view`
    /// to be drawn at any board time from `t0` to `t1`: the longest light
    /// delay from the table (pucks and cushions, their heights included)
    /// to its eye then, doubled, plus 1 s, and at least
    /// [`HEADLESS_HISTORY`] (infinite for a view with no observer). A
    /// headless run to a far time gives it to
    /// [`Billiard::set_history`] so that its memory stays bounded (a whole
    /// history of 10⁵ s of ten pucks once took 0.8 GB) while every
    /// emission event it looks for is still held.
    pub fn history_needed(&self, view: Entity, t0: f64, t1: f64) -> f64 {
        let size = self.table_size();
        let (mut reach, mut top) = (CUSHION_WIDTH, CUSHION_HEIGHT);
        let mut pucks = self.world.try_query::<&Puck>();
        if let Some(q) = pucks.as_mut() {
            for p in q.iter(&self.world) {
                reach = reach.max(p.radius);
                top = top.max(p.height);
            }
        }
        // The box every point of the table lies in.
        let low = DVec3::new(-reach, -reach, 0.0);
        let high = DVec3::new(size.x + reach, size.y + reach, top);
        let Some(w) = self
            .observer_of(view)
            .and_then(|o| self.observer_worldline(o))
        else {
            // No eye on a worldline to bound the delay: keep everything.
            return f64::INFINITY;
        };
        // The distance to a point is convex along each straight segment:
        // its largest is at the ends or the kinks; the box's farthest
        // point from the eye is, on each axis, its farther face.
        let kinks = w
            .segments()
            .iter()
            .map(|s| s.start.t)
            .filter(|&t| t > t0 && t < t1);
        let mut delay = 0.0f64;
        for t in [t0, t1].into_iter().chain(kinks) {
            let eye = w.position_at(t);
            let farthest = (eye - low).abs().max((eye - high).abs());
            delay = delay.max(farthest.length() / self.c());
        }
        (2.0 * delay + 1.0).max(HEADLESS_HISTORY)
    }

    /// Runs to board time `t` for a picture of `view` at `t` only (a
    /// headless `observe`, `render`): the physics keeps
    /// [`Self::history_needed`] and is run there in steps of that horizon,
    /// the collision records of each step forgotten before the next, then
    /// one frame at `t`. Memory is bounded however far `t` is; what `view`
    /// sees at `t` is what [`Self::advance_to`] alone gives (other views
    /// may look further back than was kept).
    pub fn run_far_to(&mut self, view: Entity, t: f64) {
        let keep = self.history_needed(view, self.time(), t);
        let physics = self.physics_mut();
        physics.set_history(Some(keep));
        while physics.time() + keep < t {
            let next = physics.time() + keep;
            physics.advance_to(next);
            physics.forget_old_records();
        }
        self.advance_to(t);
        self.physics_mut().forget_old_records();
    }

    /// Speed of light, m/s.
    pub fn c(&self) -> f64 {
        self.world.resource::<SpeedOfLight>().0
    }

    /// The physics (pucks' worldlines, collisions so far).
    pub fn physics(&self) -> &Billiard {
        &self.world.resource::<Physics>().0
    }

    /// The physics, to apply impulses.
    pub fn physics_mut(&mut self) -> &mut Billiard {
        &mut self.world.resource_mut::<Physics>().into_inner().0
    }

    /// Puts `billiard` (of the same scene, run as far as wanted) in place
    /// of the physics: the pucks' worldlines every view then sees. Used to
    /// look at a billiard run elsewhere (the Python `Simulation`, a lesson)
    /// through this world's views. The pucks' contracted shapes are
    /// computed afresh for the new worldlines at the next frame.
    pub fn replace_physics(&mut self, billiard: Billiard) {
        self.world.resource_mut::<Physics>().0 = billiard;
        let mut shapes = self
            .world
            .query_filtered::<&mut BodyContraction, With<PuckIndex>>();
        for mut shape in shapes.iter_mut(&mut self.world) {
            shape.0.clear();
        }
    }

    /// Table size, m.
    pub fn table_size(&self) -> DVec2 {
        self.world.resource::<Table>().0.size
    }

    /// The entity of the body (puck or observer) called `name`.
    pub fn entity(&mut self, name: &str) -> Option<Entity> {
        let mut q = self.world.query::<(Entity, &BodyName)>();
        q.iter(&self.world)
            .find(|(_, n)| n.0 == name)
            .map(|(e, _)| e)
    }

    /// Adds an observer (scene observer, free eye, tracked head) moving
    /// along `worldline`, looking along `forward` (board frame). It sees
    /// nothing until a view uses it ([`Self::add_view`]).
    pub fn add_observer(&mut self, name: &str, worldline: Worldline, forward: DVec3) -> Entity {
        let tau = worldline.proper_time_at(self.world.resource::<Clock>().t);
        self.world
            .spawn((
                Observer {
                    forward: forward.normalize_or(DVec3::Y),
                },
                BodyName(name.to_owned()),
                OwnWorldline(worldline),
                ProperTime(tau),
            ))
            .id()
    }

    /// Adds a view of `observer` with the effect set `effects`, its camera
    /// aimed by `framing`, and the vantage `vantage`; it sees from the next
    /// frame.
    pub fn add_view(
        &mut self,
        name: &str,
        observer: Entity,
        effects: Effects,
        framing: Framing,
        vantage: Vantage,
    ) -> Entity {
        let mut view = self.world.spawn((
            View {
                observer,
                name: name.to_owned(),
            },
            Lens::new(framing),
            vantage,
            Apparent::default(),
        ));
        for effect in Effect::ALL {
            set_effect_marker(&mut view, effect, effects.is_on(effect));
        }
        let id = view.id();
        self.views.push(id);
        id
    }

    /// Removes a view.
    pub fn remove_view(&mut self, view: Entity) {
        self.views.retain(|v| *v != view);
        self.world.despawn(view);
    }

    /// Every view, in the order they were added (the scene's observers
    /// first).
    pub fn views(&self) -> &[Entity] {
        &self.views
    }

    /// The view called `name`.
    pub fn view(&self, name: &str) -> Option<Entity> {
        self.views.iter().copied().find(|&v| {
            self.world
                .get::<View>(v)
                .is_some_and(|view| view.name == name)
        })
    }

    /// What `view` saw at the last frame.
    pub fn apparent(&self, view: Entity) -> Option<&Apparent> {
        self.world.get::<Apparent>(view)
    }

    /// The camera of `view` at the last frame.
    pub fn camera(&self, view: Entity) -> Option<Camera> {
        self.world.get::<Lens>(view).map(|l| l.camera)
    }

    /// How `view`'s camera is aimed.
    pub fn framing(&self, view: Entity) -> Option<Framing> {
        self.world.get::<Lens>(view).map(|l| l.framing)
    }

    /// Sets how `view`'s camera is aimed (from the next frame).
    pub fn set_framing(&mut self, view: Entity, framing: Framing) {
        if let Some(mut l) = self.world.get_mut::<Lens>(view) {
            l.framing = framing;
        }
    }

    /// The observer entity of `view`.
    pub fn observer_of(&self, view: Entity) -> Option<Entity> {
        self.world.get::<View>(view).map(|v| v.observer)
    }

    /// Sets where `view` puts its eye (on its observer's worldline, or the
    /// "replay and move" mode).
    pub fn set_vantage(&mut self, view: Entity, vantage: Vantage) {
        if let Some(mut v) = self.world.get_mut::<Vantage>(view) {
            *v = vantage;
        }
    }

    /// The effect set of `view` (read off its markers).
    pub fn view_effects(&self, view: Entity) -> Option<Effects> {
        self.world.get_entity(view).ok().map(effects_of)
    }

    /// Turns `effect` on or off for `view`; takes hold at the next frame.
    pub fn set_view_effect(&mut self, view: Entity, effect: Effect, on: bool) {
        if let Ok(mut e) = self.world.get_entity_mut(view) {
            set_effect_marker(&mut e, effect, on);
        }
    }

    /// Gives `view` exactly the effects in `effects`; takes hold at the
    /// next frame.
    pub fn set_view_effects(&mut self, view: Entity, effects: Effects) {
        for e in Effect::ALL {
            self.set_view_effect(view, e, effects.is_on(e));
        }
    }

    /// Turns `effect` on or off for every view; takes hold at the next
    /// frame.
    pub fn set_effect(&mut self, effect: Effect, on: bool) {
        for view in self.views.clone() {
            self.set_view_effect(view, effect, on);
        }
    }

    /// Every drawn body's rest-frame mesh, with its colour for a puck
    /// (`None` for a fixture), in no particular order.
    pub fn body_meshes(&mut self) -> Vec<(BodyRef, &Mesh, Option<Color>)> {
        let mut q = self
            .world
            .query::<(Option<&PuckIndex>, Option<&Fixture>, &Mesh, Option<&Tint>)>();
        q.iter(&self.world)
            .filter_map(|(p, f, m, tint)| {
                let body = match (p, f) {
                    (Some(p), _) => BodyRef::Puck(p.0),
                    (None, Some(f)) => BodyRef::Fixture(f.0),
                    (None, None) => return None,
                };
                Some((body, m, tint.map(|t| t.0)))
            })
            .collect()
    }

    /// The worldline of `observer`.
    pub fn observer_worldline(&self, observer: Entity) -> Option<&Worldline> {
        self.world.get::<OwnWorldline>(observer).map(|w| &w.0)
    }

    fn observer_worldline_mut(
        &mut self,
        observer: Entity,
    ) -> Result<&mut Worldline, ObserverError> {
        self.world
            .get_mut::<OwnWorldline>(observer)
            .map(|w| &mut w.into_inner().0)
            .ok_or(ObserverError::NoSuchObserver)
    }

    /// Flight: `observer` moves with proper velocity `u` from board time
    /// `t` on (a kink on its worldline; see [`input::steer`]).
    pub fn steer_observer(
        &mut self,
        observer: Entity,
        t: f64,
        u: ProperVelocity,
    ) -> Result<(), ObserverError> {
        Ok(input::steer(self.observer_worldline_mut(observer)?, t, u)?)
    }

    /// Puts `observer` at `position` at board time `t`, moving with proper
    /// velocity `u` from then on: a jump on its worldline (the free eye
    /// orbited or reset, a tracked pose; see [`Worldline::relocate`]).
    pub fn place_observer(
        &mut self,
        observer: Entity,
        t: f64,
        position: DVec3,
        u: ProperVelocity,
    ) -> Result<(), ObserverError> {
        Ok(self
            .observer_worldline_mut(observer)?
            .relocate(t, position, u)?)
    }

    /// Forgets the part of `observer`'s worldline that ended at or before
    /// board time `t` (a bounded replay window, as the physics keeps).
    pub fn forget_observer_before(&mut self, observer: Entity, t: f64) {
        if let Ok(w) = self.observer_worldline_mut(observer) {
            w.forget_before(t);
        }
    }

    /// The vantage of `view`.
    pub fn vantage(&self, view: Entity) -> Option<Vantage> {
        self.world.get::<Vantage>(view).copied()
    }

    /// What `view` saw of the point `offset` (m, in the rest frame of puck
    /// `puck`, from its reference point) at each board time of `times`: the
    /// view's eye then, per its [`Vantage`] (on its observer's worldline,
    /// or "replay and move"), and the apparent point relative to that eye.
    /// The same kernels, in the same order, as the frame schedule's optics
    /// systems run for this view, chosen by the view's own effect markers
    /// (light delay, exact or from the sampled history as the scene asks,
    /// or board-simultaneous; the puck's contracted shape, built here, or
    /// its rest shape; aberration or board directions).
    /// A history of the view's picture without running a frame per time:
    /// the seen trails. Each entry: the eye then, the emission event (board
    /// frame: where and when the light left the point) and the apparent
    /// point. Every entry is `None` if the view, its observer or the puck
    /// does not exist.
    pub fn seen_history(
        &self,
        view: Entity,
        puck: usize,
        offset: DVec3,
        times: &[f64],
    ) -> Vec<Option<SeenThen>> {
        let gone = || times.iter().map(|_| None).collect();
        let (Some(v), Some(&vantage), Some(effects)) = (
            self.world.get::<View>(view),
            self.world.get::<Vantage>(view),
            self.view_effects(view),
        ) else {
            return gone();
        };
        let Some(eye_line) = self.observer_worldline(v.observer) else {
            return gone();
        };
        if puck >= self.physics().len() {
            return gone();
        }
        let worldline = self.physics().worldline(puck);
        let c = self.c();
        let sampled = match (
            self.world.get_resource::<OpticsMethod>(),
            self.world.get_resource::<History>(),
        ) {
            (Some(m), Some(h)) if m.0.sampled => Some((&h.0, m.search())),
            _ => None,
        };
        let method = match sampled {
            Some((h, search)) => Method::Sampled(h, search),
            None => Method::Exact,
        };
        let contracted = effects.contraction.then(|| ContractedShape::of(worldline));
        let offsets = [offset];
        let (mut emissions, mut seen) = (Vec::new(), Vec::new());
        times
            .iter()
            .map(|&t| {
                let eye = eye_at(eye_line, vantage, t);
                let out = &mut emissions;
                match &contracted {
                    Some(shapes) => kernel::emissions_with_shape(
                        shapes, puck, worldline, &offsets, &eye, &effects, method, out,
                    ),
                    None => kernel::emissions_with_shape(
                        &Rigid, puck, worldline, &offsets, &eye, &effects, method, out,
                    ),
                }
                kernel::seen(&eye, c, &effects, &emissions, &mut seen);
                Some(SeenThen {
                    eye,
                    emission: *emissions.first()?,
                    seen: *seen.first()?,
                })
            })
            .collect()
    }

    /// A tracked head: a sample puts `observer` at `target` at board time
    /// `t`; its worldline follows `lag` seconds behind (see
    /// [`input::follow`]).
    pub fn follow_observer(
        &mut self,
        observer: Entity,
        t: f64,
        target: DVec3,
        lag: f64,
    ) -> Result<(), ObserverError> {
        Ok(input::follow(
            self.observer_worldline_mut(observer)?,
            t,
            target,
            lag,
        )?)
    }
}
