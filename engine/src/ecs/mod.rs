//! The ECS world (bevy_ecs): the one path from worldlines to anything a
//! user gets. The only module that imports bevy_ecs.
//!
//! * [`components`], [`resources`], [`phase`]: the types, importing no
//!   system;
//! * [`systems`]: one module per phase (input, physics, kinematics,
//!   history, optics), over those types;
//! * [`schedule`]: the frame schedule on top; [`simulation`]: a world
//!   built from a scene, and the one way to advance and observe it.
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
