//! The phases of a frame and the run conditions that gate effect systems.
//! Plain data: this module imports no system.

use bevy_ecs::prelude::*;

use super::components::View;
use super::resources::OpticsMethod;

/// The phases of one frame, in the order they run. The physics is not one
/// of them: it runs first, to the frame's board time, outside the schedule
/// (`Simulation::advance_to`), and input is kinks put on worldlines
/// between frames, so a frame only reads worldlines.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Phase {
    /// Proper time and contracted shapes (the design's
    /// *relativistic-transform*).
    Kinematics,
    /// The sampled per-vertex history, when a scene asks for it (the
    /// design's *history*).
    History,
    /// Per view: emission solve, aberration, Doppler, searchlight (the
    /// design's *retarded-render*).
    Optics,
}

/// Run condition: some view has the effect marker `M`.
#[must_use]
pub fn any_view_with<M: Component>(views: Query<(), (With<View>, With<M>)>) -> bool {
    !views.is_empty()
}

/// Run condition: some view lacks the effect marker `M`.
#[must_use]
pub fn any_view_without<M: Component>(views: Query<(), (With<View>, Without<M>)>) -> bool {
    !views.is_empty()
}

/// Run condition: the scene asks for the paper's sampled history.
#[must_use]
pub fn sampled_history(method: Option<Res<OpticsMethod>>) -> bool {
    method.is_some_and(|m| m.0.sampled)
}
