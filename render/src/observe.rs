//! What an observer sees, as the report `lightcone observe` prints and
//! Python's `observe` returns.

use lightcone_engine::ecs::Simulation;
use lightcone_engine::optics::mesh;
use lightcone_engine::optics::view::{Method, observe};
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{self, Effect, Effects};
use lightcone_engine::world::PUCK_SEGMENTS;

/// What observer `index` of `scene` sees at board time `t`: the report
/// `lightcone observe` prints (and the Python `observe` returns).
pub fn report(
    scene: &scene::Scene,
    billiard: &Billiard,
    index: usize,
    t: f64,
    effects: Effects,
    vertices: bool,
) -> ObserveReport {
    let spec = &scene.observers[index];
    let (eye, _) = crate::frame::eye_of(scene, index, t);
    let shapes: Vec<_> = scene
        .pucks
        .iter()
        .map(|p| mesh::puck(p.radius, p.height, PUCK_SEGMENTS))
        .collect();
    let heights: Vec<f64> = scene.pucks.iter().map(|p| p.height).collect();
    let view = observe(
        billiard,
        &shapes,
        &heights,
        eye,
        effects,
        Method::Exact,
        vertices,
    );
    ObserveReport::new(billiard, &view, &spec.name, t / spec.u.gamma(), vertices)
}

/// What observer `index` of `scene` sees at board time `t` with `effects`,
/// read off its view of the frame schedule (the one optics output, the one
/// the headless frame path draws): the report `lightcone observe` prints.
/// `None` if `scene` has no observer `index`.
pub fn report_at(
    scene: &scene::Scene,
    index: usize,
    t: f64,
    effects: Effects,
    vertices: bool,
) -> Option<ObserveReport> {
    let mut sim = Simulation::new(scene);
    let view = *sim.views().get(index)?;
    for e in Effect::ALL {
        sim.set_view_effect(view, e, effects.is_on(e));
    }
    sim.advance_to(t);
    ObserveReport::of_view(&sim, view, vertices)
}
