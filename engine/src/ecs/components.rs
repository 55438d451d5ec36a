//! The components of the ECS world: bodies (pucks, fixtures, observers),
//! views and their effect markers, and what the systems write (each
//! body's contracted shape and proper time, and each view's [`Apparent`]
//! output). Plain data:
//! this module imports no system.

use bevy_ecs::prelude::*;
use glam::DVec3;

use crate::camera::{Camera, Framing};
use crate::optics::{Emission, Eye, Seen};
use crate::scene::{Color, Effect, Effects};
use crate::worldline::{ContractedShape, RestShape, Worldline};

// ## Bodies

/// Marks a puck and holds its rest-frame physical properties.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Puck {
    /// Rest-frame radius, m.
    pub radius: f64,
    /// Height, m.
    pub height: f64,
    /// Rest mass, kg.
    pub mass: f64,
}

/// Which puck of the [`crate::ecs::resources::Physics`] this entity is (its
/// worldline lives there, where the event loop extends it).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct PuckIndex(pub usize);

/// Marks a body at rest on the board that is drawn but takes no part in
/// the physics (the cloth and the cushions); its worldline is its
/// [`OwnWorldline`], its index among the fixtures is the number.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct Fixture(pub usize);

/// The worldline of a body the physics does not own: an observer (scene
/// observer, free eye, tracked head), a fixture. Inputs append kinks to
/// it; the past is never rewritten, so a replay is exact.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct OwnWorldline(pub Worldline);

/// A body's name from the scene (pucks and observers).
#[derive(Component, Clone, Debug, PartialEq, Eq)]
pub struct BodyName(pub String);

/// Surface colour.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tint(pub Color);

/// A body's rest-frame mesh, and the points optics follows: every mesh
/// vertex, then one last point, the body's centre (a puck's centre at
/// mid-height) for clocks, picking and `observe`.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// The rest-frame shape.
    pub shape: RestShape,
    /// `shape.vertices`, then the centre (rest-frame offsets, m).
    pub points: Vec<DVec3>,
}

impl Mesh {
    /// The mesh of `shape` with centre `centre` (rest-frame offset from the
    /// reference point, m).
    #[must_use]
    pub fn new(shape: RestShape, centre: DVec3) -> Self {
        let mut points = shape.vertices.clone();
        points.push(centre);
        Self { shape, points }
    }
}

/// Marks an observer (an eye); its motion is its [`OwnWorldline`].
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// Unit viewing direction in the board frame, from the scene.
    pub forward: DVec3,
}

/// A body's Lorentz-contracted shape along its worldline, one map per
/// segment, written by the kinematics phase when some view has
/// [`Contraction`] (extended as the worldline grows, not rebuilt) and
/// applied by the optics systems for the views with [`Contraction`] only.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct BodyContraction(pub ContractedShape);

/// A body's proper time at the clock's board time, s (time dilation),
/// written by the kinematics phase when some view has [`TimeDilation`].
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct ProperTime(pub f64);

// ## Views

/// A view: what one observer sees, with its own effect set (one marker
/// component per effect: [`Contraction`], [`LightDelay`], [`Aberration`],
/// [`Doppler`], [`Searchlight`], [`TimeDilation`]) and its own [`Lens`].
/// Several views run in the same frame; the optics systems write each
/// one's [`Apparent`].
#[derive(Component, Clone, Debug, PartialEq)]
pub struct View {
    /// The observer entity (with [`Observer`] and [`OwnWorldline`]).
    pub observer: Entity,
    /// The view's name ("eye", "eye: truth" …).
    pub name: String,
}

/// The camera of a view: how it is aimed (`framing`, set by the front end)
/// and the camera that framing gave at the last frame (`camera`, written
/// by the optics phase from what the view saw): the one camera model of
/// the window, `render`, Python and the CAVE.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// How the camera is aimed.
    pub framing: Framing,
    /// The camera at the last frame.
    pub camera: Camera,
}

impl Lens {
    /// A lens aimed by `framing` (its camera, until the first frame,
    /// looking along +y with a 60° field).
    #[must_use]
    pub fn new(framing: Framing) -> Self {
        Self {
            framing,
            camera: Camera::looking(DVec3::Y),
        }
    }
}

/// Marks the fixture whose points are what a fitted framing shows (the
/// corners of the playing area and of the cushions' outer top edges); it
/// has no triangles, so nothing draws it.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FramingMarks;

/// Where a view puts its eye at the clock's board time `t`.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub enum Vantage {
    /// On its observer's worldline at `t`: what that observer saw at `t`
    /// (live, and in a replay of `t`).
    #[default]
    OnWorldline,
    /// The paper's "replay and move": watching the light that arrives at
    /// board time `t` from where the observer is at board time `now` (and
    /// with its velocity then), e.g. the live eye looking at a replay.
    ReplayAndMove {
        /// Board time of the observer's state used, s.
        now: f64,
    },
}

/// Effect marker: bodies Lorentz-contracted along their motion.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Contraction;
/// Effect marker: each point seen where it was when its light left.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LightDelay;
/// Effect marker: directions and distances in the observer's frame.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Aberration;
/// Effect marker: colour shifted by the Doppler factor.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Doppler;
/// Effect marker: brightness scaled by `D⁴`.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Searchlight;
/// Effect marker: clocks show proper time.
#[derive(Component, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TimeDilation;

/// Gives the view `entity` the marker of `effect` (`on`) or removes it.
pub fn set_effect_marker(entity: &mut EntityWorldMut, effect: Effect, on: bool) {
    fn put<M: Component + Default>(entity: &mut EntityWorldMut, on: bool) {
        if on {
            entity.insert(M::default());
        } else {
            entity.remove::<M>();
        }
    }
    match effect {
        Effect::Contraction => put::<Contraction>(entity, on),
        Effect::LightDelay => put::<LightDelay>(entity, on),
        Effect::Aberration => put::<Aberration>(entity, on),
        Effect::Doppler => put::<Doppler>(entity, on),
        Effect::Searchlight => put::<Searchlight>(entity, on),
        Effect::TimeDilation => put::<TimeDilation>(entity, on),
    }
}

/// The effect set of a view entity, read off its markers.
#[must_use]
pub fn effects_of(entity: EntityRef) -> Effects {
    Effects {
        contraction: entity.contains::<Contraction>(),
        light_delay: entity.contains::<LightDelay>(),
        aberration: entity.contains::<Aberration>(),
        doppler: entity.contains::<Doppler>(),
        searchlight: entity.contains::<Searchlight>(),
        time_dilation: entity.contains::<TimeDilation>(),
    }
}

// ## What a view sees

/// Which body an [`ApparentBody`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyRef {
    /// Puck number (index in the physics).
    Puck(usize),
    /// Fixture number (the table's cloth and cushions).
    Fixture(usize),
}

impl Default for BodyRef {
    fn default() -> Self {
        Self::Puck(0)
    }
}

/// One body as a view sees it this frame: one entry per point of its
/// [`Mesh`] (every vertex, then the centre).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ApparentBody {
    /// Which body.
    pub body: BodyRef,
    /// Emission event of each point (board-simultaneous without light
    /// delay).
    pub emissions: Vec<Emission>,
    /// Apparent position (relative to the eye; observer's frame with
    /// aberration, board frame without), direction, distance, and Doppler
    /// factor (1 without the doppler effect) of each point.
    pub seen: Vec<Seen>,
    /// Searchlight intensity factor `D⁴` of each point (1 without it).
    pub intensity: Vec<f64>,
    /// The time the body's clock shows in the image, s: its proper time at
    /// the centre's emission event with time dilation, that event's board
    /// time without.
    pub seen_proper_time: f64,
}

impl ApparentBody {
    /// Number of mesh vertices (the points before the centre).
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.emissions.len().saturating_sub(1)
    }

    /// Index of the centre among the points.
    #[must_use]
    pub fn centre(&self) -> usize {
        self.vertex_count()
    }
}

/// What one view sees this frame, written by the optics systems: the one
/// optics output every consumer reads.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct Apparent {
    /// The eye this frame (observation event, observer's proper velocity).
    pub eye: Option<Eye>,
    /// Every puck in index order, then every fixture.
    pub bodies: Vec<ApparentBody>,
    /// The effects whose systems ran for this view this frame.
    pub applied: Effects,
}

impl Apparent {
    /// Every puck's apparent centre (mid-height): its index, emission
    /// event and how it is seen, for clocks, labels and picking.
    pub fn puck_centres(&self) -> impl Iterator<Item = (usize, Emission, Seen)> + '_ {
        self.bodies.iter().filter_map(|b| match b.body {
            BodyRef::Puck(i) => {
                let k = b.centre();
                Some((i, *b.emissions.get(k)?, *b.seen.get(k)?))
            }
            BodyRef::Fixture(_) => None,
        })
    }
}

impl Default for Apparent {
    fn default() -> Self {
        Self {
            eye: None,
            bodies: Vec::new(),
            applied: Effects::NONE,
        }
    }
}
