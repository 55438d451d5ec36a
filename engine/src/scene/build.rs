//! Building a scene in code (Python lessons, the game's placeholders, a
//! scene sent as data): the checks a scene file gets, from [`super::rules`],
//! each refusal a typed [`BuildError`] naming the body or field.

use glam::DVec2;

use super::effects::Effects;
use super::model::{BeforeStart, ObserverSpec, OpticsSpec, PuckSpec, Scene, TableSpec};
use super::overlap::overlap;
use super::rules::{self, BuildError, MAX_OBSERVERS, MAX_PUCKS, Quantity};

/// Building a scene in code (Python lessons, the game's placeholders): the
/// checks a scene file gets, from [`super::rules`], each refusal a typed
/// [`BuildError`] naming the body or field.
impl Scene {
    /// An empty scene on a table of `size` metres, with `c` (default: light
    /// crosses the long side in 2 s), default effects and no pucks; one
    /// default observer until one is added.
    pub fn empty(size: DVec2, c: Option<f64>) -> Result<Self, BuildError> {
        rules::table_size(size).map_err(|e| e.of("table size"))?;
        let c = Quantity::C
            .check(c.unwrap_or(Self::default_c(size)))
            .map_err(|e| e.of("c"))?;
        Ok(Self {
            title: "scene".to_owned(),
            description: String::new(),
            c,
            table: TableSpec::frictionless(size, 1.0),
            restitution: 1.0,
            effects: Effects::default(),
            optics: OpticsSpec::default(),
            before_start: BeforeStart::default(),
            pucks: Vec::new(),
            observers: vec![Self::default_observer(size)],
        })
    }

    /// Adds a puck after the same checks a scene file gets (a unique name
    /// without padding, finite numbers, |u| ≤ [`rules::MAX_U`], radius, height and
    /// mass in range, on the table, inside the braking's Rindler horizon,
    /// clear of the other pucks). Nothing changes if it fails.
    pub fn add_puck(&mut self, puck: PuckSpec) -> Result<(), BuildError> {
        let name = puck.name.as_str();
        rules::name(name, |n| self.puck(n).is_some()).map_err(|e| e.of("puck"))?;
        let of = |what: &str| format!("puck \"{name}\" {what}");
        rules::finite(&puck.position.to_array()).map_err(|e| e.of(of("position")))?;
        rules::proper_velocity(puck.u.0).map_err(|e| e.of(of("u")))?;
        for (what, v, quantity) in [
            ("radius", puck.radius, Quantity::Length),
            ("height", puck.height, Quantity::Length),
            ("mass", puck.mass, Quantity::Mass),
        ] {
            quantity.check(v).map_err(|e| e.of(of(what)))?;
        }
        if self.pucks.len() >= MAX_PUCKS {
            return Err(BuildError::TooMany {
                what: "pucks",
                count: self.pucks.len() + 1,
                max: MAX_PUCKS,
            });
        }
        rules::on_table(&self.table, &puck)?;
        let t = &self.table;
        if let Some((_, e)) =
            rules::braking_horizon(self.c, t.friction, t.gravity, std::slice::from_ref(&puck))
        {
            return Err(e);
        }
        // One pass over the others: O(N) per puck added.
        if let Some(other) = self.pucks.iter().find(|o| overlap(o, &puck)) {
            return Err(BuildError::Overlap {
                puck: puck.name.clone(),
                other: other.name.clone(),
                other_line: None,
                distance: other.position.distance(puck.position),
                reach: other.radius + puck.radius,
            });
        }
        self.pucks.push(puck);
        Ok(())
    }

    /// Sets the table's sliding friction `friction` (μ: 0, or
    /// [`rules::MIN_FRICTION`] to [`rules::MAX_FRICTION`]) and `gravity` (m/s², in
    /// [`rules::GRAVITY_RANGE`]), after the checks a scene file's `[table]
    /// friction`/`gravity` get, including that every puck is smaller than
    /// the braking's Rindler horizon `c²/(μg)`. Nothing changes if it fails.
    pub fn set_friction(&mut self, friction: f64, gravity: f64) -> Result<(), BuildError> {
        Quantity::Friction
            .check(friction)
            .map_err(|e| e.of("friction"))?;
        Quantity::Gravity
            .check(gravity)
            .map_err(|e| e.of("gravity"))?;
        if let Some((_, e)) = rules::braking_horizon(self.c, friction, gravity, &self.pucks) {
            return Err(e);
        }
        self.table.friction = friction;
        self.table.gravity = gravity;
        Ok(())
    }

    /// Adds an observer (the first one added replaces the default eye)
    /// after the checks a scene file's `[[observer]]` gets. Nothing changes
    /// if it fails.
    pub fn add_observer(&mut self, observer: ObserverSpec) -> Result<(), BuildError> {
        let name = observer.name.as_str();
        let default_only = self.observers.len() == 1
            && self.observers[0] == Self::default_observer(self.table.size);
        rules::name(name, |n| !default_only && self.observer(n).is_some())
            .map_err(|e| e.of("observer"))?;
        let of = |what: &str| format!("observer \"{name}\" {what}");
        rules::finite(&observer.position.to_array()).map_err(|e| e.of(of("position")))?;
        rules::near(observer.position).map_err(|e| e.of(of("position")))?;
        if let Some(p) = observer.look_at {
            rules::finite(&p.to_array()).map_err(|e| e.of(of("look_at")))?;
            rules::near(p).map_err(|e| e.of(of("look_at")))?;
            if p == observer.position {
                return Err(BuildError::LookAtEye.of(of("look_at")));
            }
        }
        rules::proper_velocity(observer.u.0).map_err(|e| e.of(of("u")))?;
        if !default_only && self.observers.len() >= MAX_OBSERVERS {
            return Err(BuildError::TooMany {
                what: "observers",
                count: self.observers.len() + 1,
                max: MAX_OBSERVERS,
            });
        }
        if default_only {
            self.observers.clear();
        }
        self.observers.push(observer);
        Ok(())
    }

    /// The same scene rebuilt through the checks a scene built in code
    /// gets ([`Self::empty`], [`Self::add_puck`], [`Self::set_friction`],
    /// [`Self::add_observer`]) plus the ranges of the fields those leave
    /// (restitutions in [0, 1], the `[optics]` limits): for a scene that
    /// arrives as data from a process the game does not trust (a lesson
    /// run in its own process sends `world.start(scene)` as JSON). Errors
    /// name the first problem.
    pub fn rebuilt(&self) -> Result<Self, BuildError> {
        let mut scene = Self::empty(self.table.size, Some(self.c))?;
        for p in &self.pucks {
            scene.add_puck(p.clone())?;
        }
        scene.set_friction(self.table.friction, self.table.gravity)?;
        if self.observers.is_empty() {
            return Err(BuildError::NoObserver);
        }
        for o in &self.observers {
            scene.add_observer(o.clone())?;
        }
        for (what, r) in [
            ("restitution", self.restitution),
            ("cushion_restitution", self.table.cushion_restitution),
        ] {
            Quantity::Restitution.check(r).map_err(|e| e.of(what))?;
        }
        Quantity::HistoryFrames
            .check(self.optics.history_frames as f64)
            .map_err(|e| e.of("optics.history_frames"))?;
        Quantity::DichotomySteps
            .check(f64::from(self.optics.dichotomy_steps))
            .map_err(|e| e.of("optics.dichotomy_steps"))?;
        scene.title = self.title.clone();
        scene.description = self.description.clone();
        scene.restitution = self.restitution;
        scene.table.cushion_restitution = self.table.cushion_restitution;
        scene.effects = self.effects;
        scene.optics = self.optics;
        scene.before_start = self.before_start;
        Ok(scene)
    }

    /// The same scene under another speed of light `c` (m/s), every
    /// body keeping its proper velocity in m/s (`γ v`, its momentum per unit
    /// mass): its `u = γβ` scales by `c_old / c`. Raising `c` thus tends to
    /// the Newtonian scene with velocities `γ v`; lowering it never brings a
    /// body to `c`. Errors on a `c` outside [`rules::C_RANGE`] (as a scene file's),
    /// on a body whose `u` would leave what the engine holds ([`rules::MAX_U`]),
    /// and, on a cloth, on a puck that would not fit inside the braking's
    /// Rindler horizon ([`BuildError::BeyondHorizon`], saying how slow `c`
    /// may go); the scene is then unchanged.
    pub fn with_c(&self, c: f64) -> Result<Self, BuildError> {
        Quantity::C.check(c)?;
        let t = &self.table;
        if let Some((_, mut e)) = rules::braking_horizon(c, t.friction, t.gravity, &self.pucks) {
            if let BuildError::BeyondHorizon { min_c, .. } = &mut e {
                let slowest = self
                    .pucks
                    .iter()
                    .map(|p| (p.radius * t.deceleration()).sqrt())
                    .fold(0.0, f64::max);
                *min_c = Some(slowest);
            }
            return Err(e);
        }
        let k = self.c / c;
        let mut scene = self.clone();
        scene.c = c;
        let bodies = scene
            .pucks
            .iter_mut()
            .map(|p| (format!("puck \"{}\" u", p.name), &mut p.u))
            .chain(
                scene
                    .observers
                    .iter_mut()
                    .map(|o| (format!("observer \"{}\" u", o.name), &mut o.u)),
            );
        for (subject, u) in bodies {
            *u = rules::proper_velocity(u.0 * k).map_err(|e| e.of(subject))?;
        }
        Ok(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Color;
    use crate::spacetime::ProperVelocity;
    use glam::DVec3;

    #[test]
    fn every_shipped_scene_rebuilds_to_itself_and_a_bad_one_does_not() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes");
        let mut n = 0;
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let scene = crate::scene::load(&path).unwrap();
                assert_eq!(scene.rebuilt().as_ref(), Ok(&scene), "{}", path.display());
                n += 1;
            }
        }
        assert!(n >= 5);
        let mut scene = Scene::empty(DVec2::new(2.0, 1.0), None).unwrap();
        let puck = |name: &str, x: f64| PuckSpec {
            name: name.to_owned(),
            position: DVec2::new(x, 0.5),
            u: ProperVelocity(DVec3::ZERO),
            radius: 0.1,
            height: 0.02,
            mass: 0.2,
            color: Color::rgb(1, 2, 3),
        };
        scene.add_puck(puck("a", 0.5)).unwrap();
        // What a scene sent as data can hold and a built one cannot.
        let mut overlapping = scene.clone();
        overlapping.pucks.push(puck("b", 0.55));
        assert!(matches!(
            overlapping.rebuilt(),
            Err(BuildError::Overlap { ref puck, ref other, .. }) if puck == "b" && other == "a"
        ));
        let mut fast = scene.clone();
        fast.pucks[0].u = ProperVelocity(DVec3::new(f64::INFINITY, 0.0, 0.0));
        assert!(matches!(
            fast.rebuilt().unwrap_err().rule(),
            BuildError::NotFinite(_)
        ));
        let mut bouncy = scene.clone();
        bouncy.restitution = 1.5;
        let e = bouncy.rebuilt().unwrap_err();
        assert_eq!(e.to_string(), "restitution: 1.5 must lie in [0, 1]");
        assert!(matches!(
            e.rule(),
            BuildError::OutOfRange {
                quantity: Quantity::Restitution,
                ..
            }
        ));
        let mut blind = scene;
        blind.observers.clear();
        assert_eq!(blind.rebuilt(), Err(BuildError::NoObserver));
    }
}
