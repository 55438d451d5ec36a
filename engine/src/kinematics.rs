//! Kinematics phase, the design's *relativistic-transform* systems: each
//! body's contracted shape and proper time at the clock's board time.

use bevy_ecs::prelude::*;

use crate::world::{BoardShape, Clock, Physics, ProperTime, PuckIndex};
use crate::worldline::{RestShape, Worldline};

/// Effect `contraction`: each puck drawn contracted by `1/γ` along its
/// velocity of the moment (§3.2.2).
pub fn contraction(
    clock: Res<Clock>,
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &RestShape, &mut BoardShape)>,
) {
    board_shapes(clock.t, &physics, &mut pucks, true);
}

/// With `contraction` off: each puck drawn with its rest shape.
pub fn rigid_shape(
    clock: Res<Clock>,
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &RestShape, &mut BoardShape)>,
) {
    board_shapes(clock.t, &physics, &mut pucks, false);
}

fn board_shapes(
    t: f64,
    physics: &Physics,
    pucks: &mut Query<(&PuckIndex, &RestShape, &mut BoardShape)>,
    contracted: bool,
) {
    for (index, shape, mut out) in pucks {
        let worldline = physics.0.worldline(index.0);
        out.0.clear();
        out.0
            .extend(shape.board_vertices_at(worldline, t, contracted));
    }
}

/// Effect `time_dilation`: each body's proper time, `dτ = dt / γ` along
/// its worldline (exact per segment, not accumulated per frame).
pub fn time_dilation(
    clock: Res<Clock>,
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &mut ProperTime)>,
    mut others: Query<(&Worldline, &mut ProperTime), Without<PuckIndex>>,
) {
    for (index, mut tau) in &mut pucks {
        tau.0 = physics.0.worldline(index.0).proper_time_at(clock.t);
    }
    for (worldline, mut tau) in &mut others {
        tau.0 = worldline.proper_time_at(clock.t);
    }
}
