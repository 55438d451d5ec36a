//! What an observer sees, as the report `lightcone observe` prints and
//! Python's `observe` returns.

use lightcone_engine::ecs::Simulation;
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{self, Effects};

/// What observer `index` of `scene` sees at board time `t` of `billiard`
/// (run at least that far elsewhere: the Python `Simulation`, a lesson's
/// world), read off its view of the frame schedule: the report
/// `lightcone observe` prints (and the Python `observe` returns). `None` if
/// `scene` has no observer `index`.
#[must_use]
pub fn report(
    scene: &scene::Scene,
    billiard: &Billiard,
    index: usize,
    t: f64,
    effects: Effects,
    vertices: bool,
) -> Option<ObserveReport> {
    let mut sim = Simulation::new(scene);
    sim.replace_physics(billiard.clone());
    let view = *sim.views().get(index)?;
    sim.set_view_effects(view, effects);
    sim.advance_to(t);
    ObserveReport::of_view(&sim, view, vertices)
}

/// What observer `index` of `scene` sees at board time `t` with `effects`,
/// read off its view of the frame schedule (the one optics output, the one
/// the headless frame path draws): the report `lightcone observe` prints.
/// `None` if `scene` has no observer `index`.
#[must_use]
pub fn report_at(
    scene: &scene::Scene,
    index: usize,
    t: f64,
    effects: Effects,
    vertices: bool,
) -> Option<ObserveReport> {
    let mut sim = Simulation::new(scene);
    let view = *sim.views().get(index)?;
    sim.set_view_effects(view, effects);
    // Only what the views can still see at `t` is kept (bounded memory).
    sim.run_far_to(view, t);
    ObserveReport::of_view(&sim, view, vertices)
}
