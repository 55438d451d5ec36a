//! The validated scene: what the engine builds a world from.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::effects::Effects;
use super::overlap::overlap;
use super::rules::{self, BuildError, MAX_OBSERVERS, MAX_PUCKS, Quantity};
use crate::spacetime::ProperVelocity;

/// Default puck radius, m: a carom ball's 61.5 mm diameter.
pub const DEFAULT_RADIUS: f64 = 0.0305;
/// Default puck height, m.
pub const DEFAULT_HEIGHT: f64 = 0.02;
/// Default puck mass, kg (a carom ball).
pub const DEFAULT_MASS: f64 = 0.21;
/// Default playing area of a match carom table, m.
pub const DEFAULT_TABLE: [f64; 2] = [2.84, 1.42];

/// A validated scene. Every number is finite, every speed below `c`, every
/// puck on the table and clear of the others.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Scene {
    /// Short title for menus and window titles.
    pub title: String,
    /// Free text shown to the player.
    pub description: String,
    /// Speed of light, m/s.
    pub c: f64,
    /// The table.
    pub table: TableSpec,
    /// Puck–puck restitution in [0, 1]: the fraction of kinetic energy kept
    /// in the centre-of-momentum frame (1 elastic, 0 perfectly inelastic).
    pub restitution: f64,
    /// Which effects the views show.
    pub effects: Effects,
    /// How emission events are found (`[optics]`).
    #[serde(default)]
    pub optics: OpticsSpec,
    /// What the pucks did before board time 0 (`before_start`).
    #[serde(default)]
    pub before_start: BeforeStart,
    /// Pucks, in file order.
    pub pucks: Vec<PuckSpec>,
    /// Observers, in file order (never empty: a default one is added).
    pub observers: Vec<ObserverSpec>,
}

/// What the pucks did before board time 0, which an observer sees while
/// light from then is still arriving.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum BeforeStart {
    /// Each puck rested at its start position and was struck at t = 0
    /// (the default): the student sees each one start late, by its light
    /// delay.
    #[default]
    Rest,
    /// Each puck's initial motion extends back to t = −∞ (it was already
    /// moving: through the cushions, in the past).
    Moving,
}

impl BeforeStart {
    /// The value in a scene file.
    pub fn key(self) -> &'static str {
        match self {
            BeforeStart::Rest => "rest",
            BeforeStart::Moving => "moving",
        }
    }
}

/// The billiard table: the board is the rectangle `[0, size.x] × [0, size.y]`
/// in the plane z = 0, z up; cushions are its four sides.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TableSpec {
    /// Playing area, m.
    pub size: DVec2,
    /// Puck–cushion restitution in [0, 1].
    pub cushion_restitution: f64,
    /// Coefficient of sliding friction between pucks and cloth, `μ ≥ 0`
    /// (dimensionless; 0 is a frictionless table). A scene file without
    /// `[table] friction` gets [`Self::CAROM_CLOTH_FRICTION`]; a scene
    /// built in code ([`Scene::empty`]) starts frictionless. A sliding
    /// puck feels `dp/dt = −μ m g v̂` in the board frame: constant proper
    /// deceleration `μ g` (see [`crate::worldline::sliding`]). A carom
    /// cloth's sliding value is about [`Self::CAROM_CLOTH_FRICTION`].
    #[serde(default)]
    pub friction: f64,
    /// Gravitational acceleration pressing the pucks on the cloth, m/s²
    /// (default [`Self::STANDARD_GRAVITY`]).
    #[serde(default = "TableSpec::standard_gravity")]
    pub gravity: f64,
}

/// One puck at board time 0.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PuckSpec {
    /// Unique name.
    pub name: String,
    /// Centre on the board at t = 0, m.
    pub position: DVec2,
    /// Proper velocity γβ (z = 0).
    pub u: ProperVelocity,
    /// Rest-frame radius, m.
    pub radius: f64,
    /// Height, m.
    pub height: f64,
    /// Rest mass, kg.
    pub mass: f64,
    /// Surface colour.
    pub color: Color,
}

/// One observer: an eye with a position at board time 0 and a constant
/// velocity until something moves it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObserverSpec {
    /// Unique name.
    pub name: String,
    /// Eye position at board time 0, m.
    pub position: DVec3,
    /// The point it looks at, m, when the scene names one (`look_at`): its
    /// views then look there with a 60° field. `None` (the default): its
    /// views are framed to show the whole table with a margin
    /// ([`ObserverSpec::framing`]).
    pub look_at: Option<DVec3>,
    /// Proper velocity γβ.
    pub u: ProperVelocity,
}

impl ObserverSpec {
    /// The point the eye faces at t = 0: its `look_at`, else the centre of
    /// a table of `size` (m) on the board.
    pub fn target(&self, size: DVec2) -> DVec3 {
        self.look_at
            .unwrap_or_else(|| DVec3::new(size.x / 2.0, size.y / 2.0, 0.0))
    }

    /// How a view of this observer is aimed unless told otherwise: along
    /// its `look_at` with a 60° vertical field when the scene names one,
    /// else turned and widened to show the whole table (cushions included)
    /// with [`crate::camera::FIT_MARGIN`] in a viewport of `aspect` =
    /// width / height: the window's default framing.
    pub fn framing(&self, aspect: f64) -> crate::camera::Framing {
        match self.look_at {
            Some(p) => crate::camera::Framing::Look {
                forward: (p - self.position).normalize_or(DVec3::Y),
                fovy: std::f64::consts::FRAC_PI_3,
                zoom: 1.0,
            },
            None => crate::camera::Framing::Fit {
                aspect,
                zoom: 1.0,
                follow: None,
            },
        }
    }
}

/// The `[optics]` table: how the light-delay view finds emission events.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct OpticsSpec {
    /// `false` (default): exactly, on the worldlines. `true`: the paper's
    /// sampled history, recorded every frame and searched by dichotomy.
    pub sampled: bool,
    /// Frames the sampled history keeps (default 1 000, as in the paper).
    pub history_frames: usize,
    /// Dichotomy steps (0 = until one frame apart; the default).
    pub dichotomy_steps: u32,
    /// Interpolate between the two frames around the light cone (default on).
    pub interpolate: bool,
}

impl Default for OpticsSpec {
    fn default() -> Self {
        Self {
            sampled: false,
            history_frames: 1000,
            dichotomy_steps: 0,
            interpolate: true,
        }
    }
}

/// An sRGB colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Color {
    /// Red, 0–255.
    pub r: u8,
    /// Green, 0–255.
    pub g: u8,
    /// Blue, 0–255.
    pub b: u8,
}

impl Color {
    /// Named colours a scene may use, besides `#rrggbb`.
    pub const NAMED: [(&'static str, Color); 12] = [
        ("white", Color::rgb(0xf2, 0xf0, 0xe6)),
        ("yellow", Color::rgb(0xf5, 0xc5, 0x18)),
        ("red", Color::rgb(0xd0, 0x21, 0x2a)),
        ("blue", Color::rgb(0x1f, 0x5f, 0xd1)),
        ("green", Color::rgb(0x2e, 0xa0, 0x43)),
        ("orange", Color::rgb(0xf0, 0x7c, 0x1e)),
        ("purple", Color::rgb(0x7b, 0x3f, 0xb5)),
        ("cyan", Color::rgb(0x1c, 0xb5, 0xc9)),
        ("magenta", Color::rgb(0xc9, 0x2c, 0xa0)),
        ("black", Color::rgb(0x18, 0x18, 0x18)),
        ("grey", Color::rgb(0x80, 0x80, 0x80)),
        ("gray", Color::rgb(0x80, 0x80, 0x80)),
    ];

    /// A colour from its components.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// Parses `#rrggbb` or a name from [`Color::NAMED`].
    pub fn parse(s: &str) -> Option<Self> {
        if let Some(hex) = s.strip_prefix('#') {
            if hex.len() != 6 || !hex.is_ascii() {
                return None;
            }
            let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
            return Some(Self::rgb(byte(0)?, byte(2)?, byte(4)?));
        }
        let lower = s.to_ascii_lowercase();
        Self::NAMED
            .iter()
            .find(|(name, _)| *name == lower)
            .map(|(_, c)| *c)
    }

    /// The default colour of the `i`-th puck: white, yellow, red (carom), …
    pub fn default_for(i: usize) -> Self {
        Self::NAMED[i % 10].1
    }

    /// `#rrggbb`.
    pub fn to_hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

impl PuckSpec {
    /// Half-width of the contracted puck along the unit axis `axis`, m:
    /// the support of an ellipse of semi-axes `R/γ` (along the motion) and
    /// `R`, which is `R √(1 − (axis·β)²)`, formed as `R √((1 − a)(1 + a))`.
    pub fn half_extent_along(&self, axis: DVec2) -> f64 {
        let a = axis.dot(self.u.beta().truncate()).abs();
        self.radius * ((1.0 - a) * (1.0 + a)).sqrt()
    }
}

impl TableSpec {
    /// Sliding friction coefficient of a carom cloth (ball on new woollen
    /// cloth, sliding phase: about 0.2; the rolling value is ~100× smaller).
    pub const CAROM_CLOTH_FRICTION: f64 = 0.2;
    /// Standard gravity, m/s².
    pub const STANDARD_GRAVITY: f64 = 9.806_65;

    fn standard_gravity() -> f64 {
        Self::STANDARD_GRAVITY
    }

    /// A frictionless table of `size` metres, cushions of restitution
    /// `cushion_restitution`.
    pub fn frictionless(size: DVec2, cushion_restitution: f64) -> Self {
        Self {
            size,
            cushion_restitution,
            friction: 0.0,
            gravity: Self::STANDARD_GRAVITY,
        }
    }

    /// The proper deceleration of a sliding puck, `μ g`, m/s².
    pub fn deceleration(&self) -> f64 {
        self.friction * self.gravity
    }
}

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

    /// Speed of light for a table: light crosses the long side in 2 s, as in
    /// the paper's experiments.
    pub fn default_c(size: DVec2) -> f64 {
        size.x.max(size.y) / 2.0
    }

    /// The observer used when a scene names none: standing at rest beside
    /// the long side, 1.25 m back and 1.6 m above the board (high enough
    /// that the table, seen whole, is not a sliver), its views framed to
    /// show the whole table.
    pub fn default_observer(size: DVec2) -> ObserverSpec {
        ObserverSpec {
            name: "eye".to_owned(),
            position: DVec3::new(size.x / 2.0, -1.25, 1.6),
            look_at: None,
            u: ProperVelocity::ZERO,
        }
    }

    /// The puck called `name`.
    pub fn puck(&self, name: &str) -> Option<&PuckSpec> {
        self.pucks.iter().find(|p| p.name == name)
    }

    /// The observer called `name`.
    pub fn observer(&self, name: &str) -> Option<&ObserverSpec> {
        self.observers.iter().find(|o| o.name == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_parse() {
        assert_eq!(Color::parse("#ff0080"), Some(Color::rgb(255, 0, 128)));
        assert_eq!(Color::parse("Red"), Color::parse("red"));
        assert_eq!(Color::parse("#ff00"), None);
        assert_eq!(Color::parse("#ééé"), None);
        assert_eq!(Color::parse("mauve"), None);
        assert_eq!(Color::rgb(1, 2, 255).to_hex(), "#0102ff");
    }

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
