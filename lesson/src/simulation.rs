//! A scene's physics run headless, seen through the engine's own views:
//! what Python's `lightcone.Simulation` (lightcone-py) and the browser
//! worker's stand-in of it (`crate::standin`) hold. One implementation of
//! both: each wraps a [`SimulationCore`] and only converts arguments and
//! results.
//!
//! The core is the engine's `ecs::Simulation` (the frame schedule every
//! front end runs: the window, `lightcone observe`, the CAVE), built once
//! for the scene with one view per scene observer. Board time is advanced
//! on its physics; a question about what an observer sees runs one frame
//! of the schedule at the time asked and reads that observer's view, so
//! an `observe` builds no world and copies no billiard.

use lightcone_engine::camera::DEFAULT_ASPECT;
use lightcone_engine::ecs::{Entity, Simulation};
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{Effect, Effects, Scene};
use lightcone_render::frame::ViewKind;

use crate::error::{ErrorKind, WorldError, WorldResult};
use crate::query;

/// A running simulation of a scene and every observer's view of it.
pub struct SimulationCore {
    /// The scene simulated (as given).
    scene: Scene,
    /// Its world: physics (`Billiard`), bodies, observers and views.
    sim: Simulation,
}

impl SimulationCore {
    /// Builds the simulation of `scene` at board time 0. `history`: how
    /// far back (board seconds, finite, ≥ 0) worldlines and collision
    /// records are kept; `None` keeps the whole run.
    pub fn new(scene: &Scene, history: Option<f64>) -> WorldResult<Self> {
        let history = query::history_horizon(history)?;
        let mut sim = Simulation::new(scene);
        if history.is_some() {
            sim.physics_mut().set_history(history);
        }
        Ok(Self {
            scene: scene.clone(),
            sim,
        })
    }

    /// The scene simulated.
    #[must_use]
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The physics: worldlines and collisions so far.
    #[must_use]
    pub fn billiard(&self) -> &Billiard {
        self.sim.physics()
    }

    /// The physics, to strike a puck.
    pub fn billiard_mut(&mut self) -> &mut Billiard {
        self.sim.physics_mut()
    }

    /// Board time the physics has reached, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.sim.physics().time()
    }

    /// Runs the physics to board time `t`, s (earlier times do nothing).
    /// The views are not drawn on the way: they are asked at one time
    /// ([`Self::observe`]), as `ecs::Simulation::run_far_to` runs.
    pub fn advance_to(&mut self, t: f64) {
        self.sim.physics_mut().advance_to(t);
    }

    /// Forgets collision records older than the history horizon.
    pub fn forget_old_records(&mut self) {
        self.sim.physics_mut().forget_old_records();
    }

    /// What `observer` (default: the first scene observer) sees at board
    /// time `t` (s, already computed: not after [`Self::time`]) with
    /// `effects` on: the report `lightcone observe` prints, read off the
    /// simulation's own view of that observer.
    pub fn observe(
        &mut self,
        observer: Option<&str>,
        t: f64,
        vertices: bool,
        effects: Effects,
    ) -> WorldResult<ObserveReport> {
        let view = self.frame_view(observer, t, effects, DEFAULT_ASPECT)?;
        ObserveReport::of_view(&self.sim, view, vertices)
            .ok_or_else(|| WorldError::new(ErrorKind::Runtime, "the observer saw nothing"))
    }

    /// `observer`'s view drawn at board time `t` (s, already computed) as
    /// `kind` ("seen": the scene's effects; "truth": the board frame) in a
    /// viewport of `aspect` (width / height), framed as `lightcone render`
    /// frames it: the simulation and the view entity, for the headless
    /// renderer (`lightcone_render::headless::render_view`).
    pub fn picture(
        &mut self,
        observer: Option<&str>,
        t: f64,
        kind: ViewKind,
        aspect: f64,
    ) -> WorldResult<(&mut Simulation, Entity)> {
        let effects = kind.effects(self.scene.effects);
        let view = self.frame_view(observer, t, effects, aspect)?;
        Ok((&mut self.sim, view))
    }

    /// Sets `observer`'s view to `effects` and the framing of an `aspect`
    /// viewport, and runs one frame of the schedule at board time `t`.
    fn frame_view(
        &mut self,
        observer: Option<&str>,
        t: f64,
        effects: Effects,
        aspect: f64,
    ) -> WorldResult<Entity> {
        let index = query::observer_index(&self.scene, observer)?;
        let view = *self.sim.views().get(index).ok_or_else(|| {
            WorldError::new(ErrorKind::Runtime, format!("observer {index} has no view"))
        })?;
        for e in Effect::ALL {
            self.sim.set_view_effect(view, e, effects.is_on(e));
        }
        self.sim
            .set_framing(view, self.scene.observers[index].framing(aspect));
        self.sim.advance_to(t);
        Ok(view)
    }
}
