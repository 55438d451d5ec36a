//! Relativistic optics (the paper's §3.2 and its future work): what an
//! observer sees of the worldlines.
//!
//! * [`emission`]: for an observation event, the event on a vertex's
//!   worldline whose light arrives then (Δs² = 0), exactly, per segment;
//! * [`history`]: the paper's method, a sampled per-body history searched
//!   by dichotomy, with optional linear interpolation (the baseline);
//! * [`eye`]: the observer: aberration (the light's direction in the
//!   observer's frame), apparent distance, Doppler factor, searchlight;
//! * [`view`]: all of it for every puck, as the renderer and `observe` use it;
//! * [`mesh`]: the rest-frame meshes (parry): pucks, table, cushions, sphere;
//! * [`systems`]: the optics phase of the frame schedule, one system per
//!   effect, each under a run condition.

pub mod emission;
pub mod eye;
pub mod history;
pub mod mesh;
pub mod systems;
pub mod view;

pub use emission::Emission;
pub use eye::{Eye, Seen};
pub use history::SampledHistory;
pub use view::{BodyView, View, observe};
