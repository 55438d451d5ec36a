//! The ECS world built from a scene: components, resources and the
//! schedule, in which every effect's systems run only when it is on.
//!
//! Phases run in the order of [`Phase`]: input adds events to worldlines,
//! physics extends them, and the later phases only *read* worldlines to
//! produce views (the design's *relativistic-transform*, *history* and
//! *retarded-render* systems are [`Phase::Kinematics`], [`Phase::History`]
//! and [`Phase::Optics`]).

use bevy_ecs::prelude::*;
use glam::{DVec2, DVec3};

use crate::kinematics;
use crate::optics::systems as optics;
use crate::physics::{Billiard, Collision};
use crate::scene::{Color, Effect, Effects, Scene, TableSpec};
use crate::spacetime::Event;
use crate::worldline::{RestShape, Worldline};

/// Vertices around each rim of a puck mesh.
pub const PUCK_SEGMENTS: u32 = 48;

// ## Components

/// Marks a puck and holds its rest-frame physical properties.
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Puck {
    /// Rest-frame radius, m.
    pub radius: f64,
    /// Height, m.
    pub height: f64,
    /// Rest mass, kg.
    pub mass: f64,
}

/// Which puck of the [`Physics`] this entity is (its worldline lives there,
/// where the event loop extends it).
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct PuckIndex(pub usize);

/// A body's name from the scene (pucks and observers).
#[derive(Component, Clone, Debug, PartialEq, Eq)]
pub struct BodyName(pub String);

/// Surface colour.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tint(pub Color);

/// Marks an observer (an eye); its motion is its [`Worldline`].
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    /// Unit viewing direction in the board frame.
    pub forward: DVec3,
}

/// Board-frame vertex positions of a body at the clock's board time
/// (simultaneous in the board frame: the "truth" view), written by the
/// kinematics phase.
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct BoardShape(pub Vec<DVec3>);

/// A body's proper time at the clock's board time, s (time dilation).
#[derive(Component, Clone, Copy, Debug, Default, PartialEq)]
pub struct ProperTime(pub f64);

// ## Resources

/// Board (coordinate) time of the simulation, s.
#[derive(Resource, Clone, Copy, Debug, Default, PartialEq)]
pub struct Clock {
    /// Board time, s.
    pub t: f64,
}

/// Speed of light, m/s.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct SpeedOfLight(pub f64);

/// The table.
#[derive(Resource, Clone, Copy, Debug, PartialEq)]
pub struct Table(pub TableSpec);

/// The event-anticipation physics: owns the pucks' worldlines.
#[derive(Resource)]
pub struct Physics(pub Billiard);

/// Collisions resolved during the last frame (for the HUD and lessons).
#[derive(Resource, Clone, Debug, Default, PartialEq)]
pub struct FrameCollisions(pub Vec<Collision>);

// ## Schedule

/// The phases of one frame, in the order they run.
#[derive(SystemSet, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Phase {
    /// Cue impulses, script commands, tracker samples.
    Input,
    /// Advance worldlines to the clock: resolve events, re-predict.
    Physics,
    /// Proper time and contracted shapes (relativistic-transform).
    Kinematics,
    /// The sampled per-vertex history, when a scene asks for it.
    History,
    /// Per observer: emission solve, aberration, Doppler (retarded-render).
    Optics,
}

/// Run condition: `effect` is on in the world's [`Effects`].
pub fn effect_on(effect: Effect) -> impl Fn(Res<Effects>) -> bool + Clone {
    move |effects: Res<Effects>| effects.is_on(effect)
}

/// Run condition: any of `effects` is on.
pub fn any_effect_on(effects: &'static [Effect]) -> impl Fn(Res<Effects>) -> bool + Clone {
    move |on: Res<Effects>| effects.iter().any(|e| on.is_on(*e))
}

/// Run condition: `effect` is off.
pub fn effect_off(effect: Effect) -> impl Fn(Res<Effects>) -> bool + Clone {
    move |effects: Res<Effects>| !effects.is_on(effect)
}

/// The frame schedule: phases chained, each effect's systems gated by
/// [`effect_on`].
pub fn frame_schedule() -> Schedule {
    let mut schedule = Schedule::default();
    schedule.configure_sets(
        (
            Phase::Input,
            Phase::Physics,
            Phase::Kinematics,
            Phase::History,
            Phase::Optics,
        )
            .chain(),
    );
    schedule.add_systems(crate::physics::systems::advance.in_set(Phase::Physics));
    schedule.add_systems(
        optics::record_history
            .run_if(optics::sampled_history)
            .in_set(Phase::History),
    );
    schedule.add_systems(
        (
            (
                optics::light_delay.run_if(effect_on(Effect::LightDelay)),
                optics::simultaneous.run_if(effect_off(Effect::LightDelay)),
            ),
            (
                optics::aberration.run_if(effect_on(Effect::Aberration)),
                optics::board_directions.run_if(effect_off(Effect::Aberration)),
            ),
            optics::doppler.run_if(any_effect_on(&[Effect::Doppler, Effect::Searchlight])),
            (
                optics::searchlight.run_if(effect_on(Effect::Searchlight)),
                optics::no_searchlight.run_if(effect_off(Effect::Searchlight)),
            ),
            optics::no_colour_shift.run_if(effect_off(Effect::Doppler)),
        )
            .chain()
            .in_set(Phase::Optics),
    );
    schedule.add_systems(
        (
            kinematics::contraction.run_if(effect_on(Effect::Contraction)),
            kinematics::rigid_shape.run_if(effect_off(Effect::Contraction)),
            kinematics::time_dilation.run_if(effect_on(Effect::TimeDilation)),
        )
            .in_set(Phase::Kinematics),
    );
    schedule
}

/// One simulation: a world built from a scene and its frame schedule.
pub struct Simulation {
    /// The ECS world (public so front ends can query it).
    pub world: World,
    schedule: Schedule,
}

impl Simulation {
    /// Builds the world for `scene`: one entity per puck and per observer,
    /// each with a worldline starting at board time 0.
    pub fn new(scene: &Scene) -> Self {
        let mut world = World::new();
        world.insert_resource(Clock::default());
        world.insert_resource(SpeedOfLight(scene.c));
        world.insert_resource(Table(scene.table));
        world.insert_resource(scene.effects);
        world.insert_resource(scene.optics);
        if scene.optics.sampled {
            world.insert_resource(optics::History(crate::optics::SampledHistory::new(
                scene.pucks.len(),
                scene.optics.history_frames,
            )));
        }
        world.insert_resource(Physics(Billiard::from_scene(scene)));
        world.insert_resource(FrameCollisions::default());
        for (i, p) in scene.pucks.iter().enumerate() {
            world.spawn((
                PuckIndex(i),
                Puck {
                    radius: p.radius,
                    height: p.height,
                    mass: p.mass,
                },
                BodyName(p.name.clone()),
                Tint(p.color),
                RestShape::puck(p.radius, p.height, PUCK_SEGMENTS),
                BoardShape::default(),
                ProperTime::default(),
            ));
        }
        for o in &scene.observers {
            world.spawn((
                Observer {
                    forward: (o.look_at - o.position).normalize_or(DVec3::Y),
                },
                BodyName(o.name.clone()),
                Worldline::new(Event::new(0.0, o.position), o.u, scene.c),
                ProperTime::default(),
                optics::Apparent::default(),
            ));
        }
        let mut sim = Self {
            world,
            schedule: frame_schedule(),
        };
        sim.advance_to(0.0);
        sim
    }

    /// Sets the board time and runs one frame of the schedule.
    pub fn advance_to(&mut self, t: f64) {
        self.world.resource_mut::<Clock>().t = t;
        self.schedule.run(&mut self.world);
    }

    /// Board time, s.
    pub fn time(&self) -> f64 {
        self.world.resource::<Clock>().t
    }

    /// The physics (pucks' worldlines, collisions so far).
    pub fn physics(&self) -> &Billiard {
        &self.world.resource::<Physics>().0
    }

    /// The physics, to apply impulses.
    pub fn physics_mut(&mut self) -> &mut Billiard {
        &mut self.world.resource_mut::<Physics>().into_inner().0
    }

    /// Turns an effect on or off; takes hold at the next frame.
    pub fn set_effect(&mut self, effect: Effect, on: bool) {
        self.world.resource_mut::<Effects>().set(effect, on);
    }

    /// Table size, m.
    pub fn table_size(&self) -> DVec2 {
        self.world.resource::<Table>().0.size
    }

    /// The entity of the body (puck or observer) called `name`.
    pub fn entity(&mut self, name: &str) -> Option<Entity> {
        let mut q = self.world.query::<(Entity, &BodyName)>();
        q.iter(&self.world)
            .find(|(_, n)| n.0 == name)
            .map(|(e, _)| e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene;

    const SCENE: &str = r#"
        [table]
        size = [2.0, 1.0]
        [effects]
        contraction = false
        time_dilation = false
        [[puck]]
        name = "fast"
        position = [0.5, 0.5]
        beta = [0.8, 0.0]
        radius = 0.1
    "#;

    fn fast_puck(sim: &mut Simulation) -> (Vec<DVec3>, f64, DVec3) {
        let e = sim.entity("fast").unwrap();
        let centre = sim.physics().worldline(0).position_at(sim.time());
        let shape = sim.world.get::<BoardShape>(e).unwrap().0.clone();
        let tau = sim.world.get::<ProperTime>(e).unwrap().0;
        (shape, tau, centre)
    }

    fn extent_x(shape: &[DVec3], centre: DVec3) -> f64 {
        shape
            .iter()
            .map(|p| (p.x - centre.x).abs())
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_system_for_an_effect_that_is_off_never_runs() {
        let scene = scene::parse(SCENE, "test.toml").unwrap();
        let mut sim = Simulation::new(&scene);
        for k in 1..=5 {
            sim.advance_to(0.1 * f64::from(k));
        }
        let (shape, tau, centre) = fast_puck(&mut sim);
        // time_dilation never ran: its output is still the initial 0, although
        // the puck has aged 0.5 s / γ = 0.3 s.
        assert_eq!(tau, 0.0);
        // contraction never ran: the drawn puck has its rest radius along x.
        assert!((extent_x(&shape, centre) - 0.1).abs() < 1e-12);

        // Turned on, both run from the next frame on.
        sim.set_effect(Effect::Contraction, true);
        sim.set_effect(Effect::TimeDilation, true);
        sim.advance_to(0.6);
        let (shape, tau, centre) = fast_puck(&mut sim);
        assert!((tau - 0.6 * 0.6).abs() < 1e-12); // t / γ, γ = 5/3
        assert!((extent_x(&shape, centre) - 0.1 * 0.6).abs() < 1e-12);

        // And off again: the rigid shape is drawn, the clock stops updating.
        sim.set_effect(Effect::Contraction, false);
        sim.set_effect(Effect::TimeDilation, false);
        sim.advance_to(1.0);
        let (shape, tau, centre) = fast_puck(&mut sim);
        assert!((tau - 0.36).abs() < 1e-12);
        assert!((extent_x(&shape, centre) - 0.1).abs() < 1e-12);
    }

    #[test]
    fn optics_systems_follow_the_effects() {
        use crate::optics::systems::Apparent;
        let scene = scene::parse(SCENE, "test.toml").unwrap();
        let mut sim = Simulation::new(&scene);
        let eye = sim.entity("eye").unwrap();
        let apparent = |sim: &Simulation| sim.world.get::<Apparent>(eye).unwrap().clone();
        for (light_delay, aberration, doppler, searchlight) in [
            (false, false, false, false),
            (true, false, false, false),
            (true, true, false, false),
            (true, true, true, false),
            (true, true, false, true),
            (false, true, true, true),
        ] {
            sim.set_effect(Effect::LightDelay, light_delay);
            sim.set_effect(Effect::Aberration, aberration);
            sim.set_effect(Effect::Doppler, doppler);
            sim.set_effect(Effect::Searchlight, searchlight);
            sim.advance_to(0.5);
            let a = apparent(&sim);
            let e = a.eye.unwrap();
            let body = &a.bodies[0];
            assert_eq!(body.emissions.len(), body.seen.len());
            assert_eq!(body.seen.len(), body.intensity.len());
            for ((em, seen), intensity) in
                body.emissions.iter().zip(&body.seen).zip(&body.intensity)
            {
                if light_delay {
                    assert!(em.event.t < 0.5);
                } else {
                    assert_eq!(em.event.t, 0.5);
                }
                if !aberration {
                    assert!(
                        (seen.position - (em.event.position - e.event.position)).length() < 1e-12
                    );
                }
                let d = e.doppler_of(em.event, em.u);
                assert_eq!(seen.doppler, if doppler { d } else { 1.0 });
                let expected = if searchlight { d.powi(4) } else { 1.0 };
                assert!((intensity - expected).abs() < 1e-12 * expected);
            }
        }
    }

    #[test]
    fn the_sampled_history_is_recorded_only_when_the_scene_asks() {
        use crate::optics::systems::{Apparent, History};
        let exact = Simulation::new(&scene::parse(SCENE, "test.toml").unwrap());
        assert!(exact.world.get_resource::<History>().is_none());
        let text = format!("{SCENE}\n[optics]\nmethod = \"sampled\"\nhistory_frames = 500\n");
        let text = text.replace("[effects]\n", "[effects]\nlight_delay = true\n");
        let mut sim = Simulation::new(&scene::parse(&text, "test.toml").unwrap());
        for f in 1..=120 {
            sim.advance_to(f64::from(f) / 60.0);
        }
        assert_eq!(sim.world.resource::<History>().0.len(), 121);
        // The sampled view is close to the exact one (interpolated, 60/s).
        let eye = sim.entity("eye").unwrap();
        let sampled = sim.world.get::<Apparent>(eye).unwrap().clone();
        let mut exact =
            Simulation::new(&scene::parse(&text.replace("sampled", "exact"), "t.toml").unwrap());
        exact.advance_to(2.0);
        let eye_exact = exact.entity("eye").unwrap();
        let reference = exact.world.get::<Apparent>(eye_exact).unwrap().clone();
        for (a, b) in sampled.bodies[0]
            .emissions
            .iter()
            .zip(&reference.bodies[0].emissions)
        {
            assert!((a.event.position - b.event.position).length() < 1e-3);
        }
    }

    #[test]
    fn world_holds_the_scene() {
        let scene = scene::parse(SCENE, "test.toml").unwrap();
        let mut sim = Simulation::new(&scene);
        assert_eq!(sim.world.resource::<SpeedOfLight>().0, 1.0); // 2 m in 2 s
        assert!(sim.entity("eye").is_some()); // the default observer
        let mut pucks = sim.world.query::<&Puck>();
        assert_eq!(pucks.iter(&sim.world).count(), 1);
        assert_eq!(sim.table_size(), DVec2::new(2.0, 1.0));
    }
}
