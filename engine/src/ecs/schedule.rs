//! The frame schedule: the phases chained, each effect's systems gated by
//! whether some view has the effect (and, inside, by their queries'
//! `With<marker>` filters).

use bevy_ecs::prelude::*;

use super::components::{Aberration, Contraction, Doppler, LightDelay, Searchlight, TimeDilation};
use super::phase::{Phase, any_view_with, any_view_without, sampled_history};
use super::systems::{history, kinematics, optics};

/// The frame schedule: Kinematics → History → Optics. It only reads the
/// worldlines: the physics has run to the frame's board time before it
/// (`Simulation::advance_to`), and strokes, flight and tracked heads are
/// kinks put on worldlines between frames (`Billiard::apply_impulse`,
/// `Simulation::steer_observer`, `Simulation::follow_observer`).
pub fn frame_schedule() -> Schedule {
    let mut schedule = Schedule::default();
    schedule.configure_sets((Phase::Kinematics, Phase::History, Phase::Optics).chain());
    schedule.add_systems(
        (
            kinematics::contraction.run_if(any_view_with::<Contraction>),
            kinematics::time_dilation.run_if(any_view_with::<TimeDilation>),
        )
            .in_set(Phase::Kinematics),
    );
    schedule.add_systems(
        history::record_history
            .run_if(sampled_history)
            .in_set(Phase::History),
    );
    schedule.add_systems(
        (
            (
                optics::light_delay.run_if(any_view_with::<LightDelay>),
                optics::simultaneous.run_if(any_view_without::<LightDelay>),
            ),
            (
                optics::aberration.run_if(any_view_with::<Aberration>),
                optics::board_directions.run_if(any_view_without::<Aberration>),
            ),
            optics::doppler.run_if(any_view_with::<Doppler>),
            optics::searchlight.run_if(any_view_with::<Searchlight>),
            optics::time_dilation.run_if(any_view_with::<TimeDilation>),
            optics::frame_cameras,
        )
            .chain()
            .in_set(Phase::Optics),
    );
    schedule
}
