//! Kinematics phase, the design's *relativistic-transform* systems: each
//! body's contracted shape and proper time at the clock's board time.

use bevy_ecs::prelude::*;

use crate::world::{BoardShape, Clock, ProperTime};
use crate::worldline::{RestShape, Worldline};

/// Effect `contraction`: each body drawn contracted by `1/γ` along its
/// velocity of the moment (§3.2.2).
pub fn contraction(
    clock: Res<Clock>,
    mut bodies: Query<(&Worldline, &RestShape, &mut BoardShape)>,
) {
    for (worldline, shape, mut out) in &mut bodies {
        out.0.clear();
        out.0
            .extend(shape.board_vertices_at(worldline, clock.t, true));
    }
}

/// With `contraction` off: each body drawn with its rest shape.
pub fn rigid_shape(
    clock: Res<Clock>,
    mut bodies: Query<(&Worldline, &RestShape, &mut BoardShape)>,
) {
    for (worldline, shape, mut out) in &mut bodies {
        out.0.clear();
        out.0
            .extend(shape.board_vertices_at(worldline, clock.t, false));
    }
}

/// Effect `time_dilation`: each body's proper time, `dτ = dt / γ` along
/// its worldline (exact per segment, not accumulated per frame).
pub fn time_dilation(clock: Res<Clock>, mut bodies: Query<(&Worldline, &mut ProperTime)>) {
    for (worldline, mut tau) in &mut bodies {
        tau.0 = worldline.proper_time_at(clock.t);
    }
}
