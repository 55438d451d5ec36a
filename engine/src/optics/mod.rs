//! Relativistic optics (the paper's §3.2 and its future work): what an
//! observer sees of the worldlines. Pure kernels, no effect flags, no ECS.
//!
//! * [`emission`]: for an observation event, the event on a vertex's
//!   worldline whose light arrives then (Δs² = 0), exactly, per segment;
//! * [`batch`]: the same for a body's vertices at once, structure of
//!   arrays and vector instructions, the segment search shared;
//! * [`history`]: the paper's method, a sampled per-body history searched
//!   by dichotomy, with optional linear interpolation (the baseline);
//! * [`eye`]: the observer: aberration (the light's direction in the
//!   observer's frame), apparent distance, Doppler factor, searchlight;
//! * [`view`]: one kernel per effect over a body's points, the body's
//!   shape (contracted or at rest) given as data, and the composed
//!   [`observe`], the engine tests' reference for the schedule;
//! * [`solve_rate`]: the workload of the solves-per-second benchmarks.
//!
//! The frame schedule (`crate::ecs`) runs the kernels per view.
//! The rest-frame meshes moved to [`crate::worldline::mesh`] (re-exported
//! here as [`mesh`]).

pub mod batch;
pub mod emission;
pub mod eye;
pub mod history;
pub mod solve_rate;
pub mod view;

pub use crate::worldline::mesh;
pub use emission::Emission;
pub use eye::{Eye, Seen};
pub use history::SampledHistory;
pub use view::{BodyView, View, observe};
