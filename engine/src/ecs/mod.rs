//! The ECS world (bevy_ecs): the one path from worldlines to anything a
//! user gets. The only module that imports bevy_ecs.
//!
//! * [`components`], [`resources`], [`phase`]: the types, importing no
//!   system;
//! * [`systems`]: one module per phase (kinematics, history, optics), over
//!   those types, and the input kinks of observers' worldlines;
//! * [`schedule`]: the frame schedule on top; [`simulation`]: a world
//!   built from a scene, and the one way to advance and observe it.
//!
//! **Physics runs first, outside the schedule.** Board time advances in one
//! place, [`crate::physics::Billiard::advance_to`] (the event loop), which
//! every front end reaches through [`Simulation::advance_to`] or, running
//! ahead of any picture, the billiard itself; a frame then only reads the
//! worldlines at its board time, which may be in the past (a replay). Cue
//! strokes, flight and tracked heads are kinks put on worldlines between
//! frames, at the live board time, whichever time a frame shows.
//!
//! A **view** is an entity: an observer (whose motion is its worldline),
//! an effect set (one marker component per effect) and a camera. Several
//! views run in the same frame; each effect's system runs only for the
//! views that have it. The output is each view's [`Apparent`].

pub mod components;
pub mod frame_cost;
pub mod phase;
pub mod resources;
pub mod schedule;
pub mod simulation;
pub mod systems;

pub use crate::camera::{Camera, Framing};
pub use bevy_ecs::entity::Entity;
pub use components::{
    Aberration, Apparent, ApparentBody, BodyRef, Contraction, Doppler, Lens, LightDelay, Observer,
    Searchlight, TimeDilation, Vantage, View,
};
pub use phase::Phase;
pub use schedule::frame_schedule;
pub use simulation::{ObserverError, SeenThen, Simulation};
