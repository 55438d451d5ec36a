//! # Lightcone engine
//!
//! The physics and optics of a relativistic carom billiard, with no window
//! and no GPU. The world is a set of **worldlines** in the board's rest
//! frame; everything else is a view of them:
//!
//! * [`camera`]: the one camera model (pinhole, fitted framing);
//! * [`spacetime`]: events, 4-vectors, proper velocities, boosts;
//! * [`worldline`]: each body's history as analytic segments, and its
//!   contracted shape along it, segment by segment;
//! * [`scene`]: scene files, validated with located error messages;
//! * [`physics`]: the event-anticipation billiard that extends worldlines;
//! * [`optics`]: pure kernels for what an observer sees (emission solve,
//!   aberration, Doppler, searchlight);
//! * [`ecs`]: the bevy_ecs world and frame schedule built from a scene:
//!   views (observer + effect set + camera) as entities, each effect's
//!   system running only for the views that have it.
//!
//! Units: SI metres and seconds on the board; `c` is a scene parameter;
//! velocities are proper velocities `u = γβ` (dimensionless).

#![warn(missing_docs)]
// A function whose result is its only point says so (issue 31, item 10):
// ignoring what `Boost::apply` or `puck_cushion::time` returns is a bug.
#![warn(clippy::must_use_candidate)]

pub mod camera;
pub mod ecs;
pub mod optics;
pub mod physics;
pub mod report;
pub mod scene;
pub mod spacetime;
pub mod worldline;
