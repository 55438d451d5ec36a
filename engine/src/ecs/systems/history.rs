//! The history phase (the design's *history* system).

use bevy_ecs::prelude::*;

use crate::ecs::resources::{Clock, History, Physics};

/// Records every puck's state at the clock's board time in the paper's
/// sampled history, as the paper's loop does each frame.
pub fn record_history(clock: Res<Clock>, physics: Res<Physics>, mut history: ResMut<History>) {
    let b = &physics.0;
    history
        .0
        .record(clock.t, (0..b.len()).map(|i| b.worldline(i)));
}
