//! Head tracking for Lightcone's CAVE mode.
//!
//! A tracker bridge (or the simulator binary `lightcone-tracker-publisher`)
//! publishes [`TrackerSample`]s over zero-copy shared memory
//! ([`transport`], iceoryx2). The game drains them every frame into a
//! [`Follower`] ([`follow`]), which validates, orders and filters them
//! ([`filter`], One-Euro) and always yields a usable head pose plus a status.
//! [`cave`] turns the head pose into per-wall, per-eye off-axis projections.
//! [`motion`] simulates or replays head motion with injectable faults, and
//! [`latency`] summarises the IPC delay. [`dtrack`] and [`vrpn`] read a
//! real tracking system's stream (ART DTrack's UDP output, a VRPN server).
//!
//! ```no_run
//! use lightcone_tracker::{Follower, Subscriber, DEFAULT_SERVICE_NAME};
//! use std::time::Instant;
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let sub = Subscriber::open(DEFAULT_SERVICE_NAME)?;
//! let mut follower = Follower::default();
//! // every frame:
//! let now = Instant::now();
//! follower.extend(sub.drain()?.iter(), now);
//! let out = follower.output(now);
//! println!("{}", out.status_line());
//! # Ok(())
//! # }
//! ```

#![warn(missing_docs)]
#![warn(clippy::must_use_candidate)]

pub mod cave;
pub mod dtrack;
pub mod filter;
pub mod follow;
pub mod latency;
pub mod motion;
// The iceoryx2 transport and the publisher are desktop-only: the browser
// build (wasm32) has CAVE geometry and filters, no shared memory.
#[cfg(not(target_arch = "wasm32"))]
pub mod publish;
pub mod report;
pub mod sample;
#[cfg(not(target_arch = "wasm32"))]
pub mod transport;
pub mod vrpn;

pub use cave::{
    CaveConfig, CaveConfigError, Frustum, Wall, WallProjection, off_axis_projection, stereo_eyes,
};
pub use filter::{OneEuroFilter, OneEuroParams};
pub use follow::{Follower, FollowerConfig, FollowerOutput, HeadPose, TrackerStatus};
pub use latency::{LatencyStats, latency_stats};
pub use motion::{CsvTrack, MotionConfig, MotionGenerator, Path};
pub use sample::{TrackerSample, unix_now_ns};
#[cfg(not(target_arch = "wasm32"))]
pub use transport::{DEFAULT_SERVICE_NAME, Publisher, Subscriber, TransportError};
