//! The physics phase.

use bevy_ecs::prelude::*;

use crate::ecs::resources::{Clock, FrameCollisions, Physics};

/// Extends the worldlines to the clock's board time, resolving every event
/// on the way, and lists this frame's new collisions. A clock moved
/// backwards (replay) changes nothing: the past is in the worldlines.
pub fn advance(
    clock: Res<Clock>,
    mut physics: ResMut<Physics>,
    mut frame: ResMut<FrameCollisions>,
) {
    let before = physics.0.collision_count();
    physics.0.advance_to(clock.t);
    frame.0.clear();
    frame.0.extend_from_slice(physics.0.collisions_from(before));
}
