//! A scene's physics run headless, seen through the engine's own views:
//! what Python's `lightcone.Simulation` (lightcone-py) and the browser
//! worker's stand-in of it (`crate::standin`) hold. One implementation of
//! both: each wraps a [`SimulationCore`] and only converts arguments and
//! results.
//!
//! The core is the engine's `ecs::Simulation` (the frame schedule every
//! front end runs: the window, `lightcone observe`, the CAVE), built once
//! for the scene with one view per scene observer, at the first question
//! about what an observer sees (until then only the physics is held, so
//! a simulation run for its collisions costs no more than its billiard).
//! Board time is advanced on its physics; a question about what an
//! observer sees runs one frame of the schedule at the time asked and
//! reads that observer's view, so an `observe` builds no world and copies
//! no billiard. With the paper's sampled optics the samples are taken
//! afresh for each question (at 0 and at the time asked, as a new
//! simulation would), so answers never depend on earlier questions.

use lightcone_engine::camera::DEFAULT_ASPECT;
use lightcone_engine::ecs::{Entity, Simulation};
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::ObserveReport;
use lightcone_engine::scene::{Effects, Scene};
use lightcone_render::frame::ViewKind;

use crate::error::{ErrorKind, WorldError, WorldResult};
use crate::query;

/// A running simulation of a scene and every observer's view of it.
pub struct SimulationCore {
    /// The scene simulated (as given).
    scene: Scene,
    /// Its physics, and once asked what an observer sees, its world.
    held: Held,
}

/// What a [`SimulationCore`] holds.
enum Held {
    /// The physics alone (nothing has been observed yet).
    Physics(Box<Billiard>),
    /// The world: physics (`Billiard`), bodies, observers and views.
    World(Box<Simulation>),
}

impl SimulationCore {
    /// Builds the simulation of `scene` at board time 0. `history`: how
    /// far back (board seconds, finite, ≥ 0) worldlines and collision
    /// records are kept; `None` keeps the whole run.
    pub fn new(scene: &Scene, history: Option<f64>) -> WorldResult<Self> {
        let history = query::history_horizon(history)?;
        let mut billiard = Billiard::from_scene(scene);
        if history.is_some() {
            billiard.set_history(history);
        }
        Ok(Self {
            scene: scene.clone(),
            held: Held::Physics(Box::new(billiard)),
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
        match &self.held {
            Held::Physics(b) => b,
            Held::World(sim) => sim.physics(),
        }
    }

    /// The physics, to strike a puck.
    pub fn billiard_mut(&mut self) -> &mut Billiard {
        match &mut self.held {
            Held::Physics(b) => b,
            Held::World(sim) => sim.physics_mut(),
        }
    }

    /// The world with its views, built at the first call (the physics
    /// moved into it).
    fn world(&mut self) -> &mut Simulation {
        if matches!(self.held, Held::Physics(_)) {
            let built = Held::World(Box::new(Simulation::new(&self.scene)));
            if let Held::Physics(b) = std::mem::replace(&mut self.held, built)
                && let Held::World(sim) = &mut self.held
            {
                sim.replace_physics(*b);
            }
        }
        match &mut self.held {
            Held::World(sim) => sim,
            Held::Physics(_) => unreachable!("the world was built just above"),
        }
    }

    /// Board time the physics has reached, s.
    #[must_use]
    pub fn time(&self) -> f64 {
        self.billiard().time()
    }

    /// Runs the physics to board time `t`, s (earlier times do nothing).
    /// The views are not drawn on the way: they are asked at one time
    /// ([`Self::observe`]), as `ecs::Simulation::run_far_to` runs.
    pub fn advance_to(&mut self, t: f64) {
        self.billiard_mut().advance_to(t);
    }

    /// Forgets collision records older than the history horizon.
    pub fn forget_old_records(&mut self) {
        self.billiard_mut().forget_old_records();
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
        ObserveReport::of_view(self.world(), view, vertices)
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
        Ok((self.world(), view))
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
        let framing = self.scene.observers[index].framing(aspect);
        let sampled = self.scene.optics.sampled;
        let sim = self.world();
        let view = *sim.views().get(index).ok_or_else(|| {
            WorldError::new(ErrorKind::Runtime, format!("observer {index} has no view"))
        })?;
        sim.set_view_effects(view, effects);
        sim.set_framing(view, framing);
        if sampled {
            // Samples at 0 and at `t` only, as a new simulation takes them.
            sim.restart_sampled_history();
            sim.advance_to(0.0);
        }
        sim.advance_to(t);
        Ok(view)
    }
}
