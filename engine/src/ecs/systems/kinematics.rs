//! The kinematics phase (the design's *relativistic-transform*): each
//! body's Lorentz-contracted shape along its worldline and its proper time
//! at the clock's board time, each run only when some view has the effect.

use bevy_ecs::prelude::*;
use rayon::prelude::*;

use crate::ecs::components::{BodyContraction, OwnWorldline, ProperTime, PuckIndex};
use crate::ecs::resources::{Clock, Physics};

/// Effect `contraction`: each body's shape along its worldline, its rest
/// shape contracted by `1/γ` along each segment's velocity (the paper's
/// §3.2.2; Born-rigid on a braking segment), one map per segment
/// ([`crate::worldline::SegmentShape::contracted`]). Only the maps of
/// segments added or changed since the last frame are computed; pucks in
/// parallel.
pub fn contraction(
    physics: Res<Physics>,
    mut pucks: Query<(&PuckIndex, &mut BodyContraction)>,
    mut others: Query<(&OwnWorldline, &mut BodyContraction), Without<PuckIndex>>,
) {
    let mut pucks: Vec<_> = pucks.iter_mut().collect();
    pucks
        .par_iter_mut()
        .for_each(|(index, shape)| shape.0.update(physics.0.worldline(index.0)));
    for (worldline, mut shape) in &mut others {
        shape.0.update(&worldline.0);
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
