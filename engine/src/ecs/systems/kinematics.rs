//! The kinematics phase (the design's *relativistic-transform*): each
//! puck's Lorentz-contracted board-frame shape and its proper time at the
//! clock's board time, each run only when some view has the effect.

use bevy_ecs::prelude::*;

use crate::ecs::components::{BoardShape, Mesh, OwnWorldline, ProperTime, PuckIndex};
use crate::ecs::resources::{Clock, Physics};

/// Effect `contraction`: each puck's board-frame shape, its rest shape
/// contracted by `1/γ` along its velocity (the paper's §3.2.2).
pub fn contraction(
    clock: Res<Clock>,
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &Mesh, &mut BoardShape)>,
) {
    for (index, mesh, mut out) in &mut pucks {
        let worldline = physics.0.worldline(index.0);
        out.0.clear();
        out.0
            .extend(mesh.shape.board_vertices_at(worldline, clock.t, true));
    }
}

/// Effect `time_dilation`: each body's proper time, `dτ = dt / γ` along
/// its worldline (exact per segment, not accumulated per frame).
pub fn time_dilation(
    clock: Res<Clock>,
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &mut ProperTime)>,
    mut others: Query<(&OwnWorldline, &mut ProperTime), Without<PuckIndex>>,
) {
    for (index, mut tau) in &mut pucks {
        tau.0 = physics.0.worldline(index.0).proper_time_at(clock.t);
    }
    for (worldline, mut tau) in &mut others {
        tau.0 = worldline.0.proper_time_at(clock.t);
    }
}
