//! # Lightcone engine
//!
//! The physics and optics of a relativistic carom billiard, with no window
//! and no GPU. The world is a set of **worldlines** in the board's rest
//! frame; everything else is a view of them:
//!
//! * [`spacetime`]: events, 4-vectors, proper velocities, boosts;
//! * [`worldline`]: each body's history as analytic segments, and its
//!   contracted shape at any board time;
//! * [`scene`]: scene files, validated with located error messages;
//! * [`world`]: the bevy_ecs world and schedule built from a scene, where
//!   each effect runs only when the scene asks for it.
//!
//! Units: SI metres and seconds on the board; `c` is a scene parameter;
//! velocities are proper velocities `u = γβ` (dimensionless).

pub mod kinematics;
pub mod optics;
pub mod physics;
pub mod report;
pub mod scene;
pub mod spacetime;
pub mod world;
pub mod worldline;
