//! The resources of the ECS world: the clock, the physics that owns the
//! pucks' worldlines, and the paper's sampled history. Plain data: this
//! module imports no system.

use bevy_ecs::prelude::*;

use crate::optics::SampledHistory;
use crate::optics::history::Search;
use crate::physics::Billiard;
use crate::scene::{OpticsSpec, TableSpec};

/// Board (coordinate) time of the frame, s: the time every view observes
/// (a replay sets it to a past time).
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct Clock {
    /// Board time, s.
    pub t: f64,
}

/// Speed of light, m/s.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct SpeedOfLight(pub f64);

/// The table.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Table(pub TableSpec);

/// The event-anticipation physics: owns the pucks' worldlines.
#[derive(Resource)]
pub struct Physics(pub Billiard);

/// How light delay finds emission events (the scene's `[optics]`).
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct OpticsMethod(pub OpticsSpec);

impl OpticsMethod {
    /// The dichotomy search the spec asks for.
    #[must_use]
    pub fn search(&self) -> Search {
        Search {
            iterations: if self.0.dichotomy_steps == 0 {
                u32::MAX
            } else {
                self.0.dichotomy_steps
            },
            interpolate: self.0.interpolate,
        }
    }
}

/// The paper's per-frame history table, kept when the scene's `[optics]`
/// asks for the sampled method.
#[derive(Resource, Clone, Debug)]
pub struct History(pub SampledHistory);
