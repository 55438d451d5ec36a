//! The validated scene: what the engine builds a world from.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

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
    /// The point it looks at, m.
    pub look_at: DVec3,
    /// Proper velocity γβ.
    pub u: ProperVelocity,
}

/// The `[optics]` table: how the light-delay view finds emission events.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize, bevy_ecs::resource::Resource)]
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

/// A relativistic effect a view can show. Physics (collisions, contraction
/// of the colliding shapes) is always relativistic; these select what the
/// *views* show, and each is implemented by systems that run only when it
/// is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Effect {
    /// Bodies drawn contracted along their motion (§3.2.2).
    Contraction,
    /// Bodies seen where they were when the light left them (§3.2.1).
    LightDelay,
    /// Directions transformed into the moving observer's frame.
    Aberration,
    /// Colours shifted by the Doppler factor.
    Doppler,
    /// Brightness scaled by the Doppler factor (searchlight / beaming).
    Searchlight,
    /// Clocks on bodies show proper time.
    TimeDilation,
}

impl Effect {
    /// Every effect, in the order of the `[effects]` table.
    pub const ALL: [Effect; 6] = [
        Effect::Contraction,
        Effect::LightDelay,
        Effect::Aberration,
        Effect::Doppler,
        Effect::Searchlight,
        Effect::TimeDilation,
    ];

    /// The key in the scene file.
    pub fn key(self) -> &'static str {
        match self {
            Effect::Contraction => "contraction",
            Effect::LightDelay => "light_delay",
            Effect::Aberration => "aberration",
            Effect::Doppler => "doppler",
            Effect::Searchlight => "searchlight",
            Effect::TimeDilation => "time_dilation",
        }
    }
}

/// The `[effects]` flags; also the world's resource that gates each
/// effect's systems.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, bevy_ecs::resource::Resource,
)]
pub struct Effects {
    /// See [`Effect::Contraction`]. Default on.
    pub contraction: bool,
    /// See [`Effect::LightDelay`]. Default on.
    pub light_delay: bool,
    /// See [`Effect::Aberration`]. Default on.
    pub aberration: bool,
    /// See [`Effect::Doppler`]. Default off.
    pub doppler: bool,
    /// See [`Effect::Searchlight`]. Default off.
    pub searchlight: bool,
    /// See [`Effect::TimeDilation`]. Default on.
    pub time_dilation: bool,
}

impl Default for Effects {
    fn default() -> Self {
        Self {
            contraction: true,
            light_delay: true,
            aberration: true,
            doppler: false,
            searchlight: false,
            time_dilation: true,
        }
    }
}

impl Effects {
    /// Every effect off: the Newtonian picture (for comparison views).
    pub const NONE: Self = Self {
        contraction: false,
        light_delay: false,
        aberration: false,
        doppler: false,
        searchlight: false,
        time_dilation: false,
    };

    /// Whether `effect` is on.
    pub fn is_on(&self, effect: Effect) -> bool {
        *self.flag(effect)
    }

    /// Turns `effect` on or off.
    pub fn set(&mut self, effect: Effect, on: bool) {
        *self.flag_mut(effect) = on;
    }

    fn flag(&self, effect: Effect) -> &bool {
        match effect {
            Effect::Contraction => &self.contraction,
            Effect::LightDelay => &self.light_delay,
            Effect::Aberration => &self.aberration,
            Effect::Doppler => &self.doppler,
            Effect::Searchlight => &self.searchlight,
            Effect::TimeDilation => &self.time_dilation,
        }
    }

    fn flag_mut(&mut self, effect: Effect) -> &mut bool {
        match effect {
            Effect::Contraction => &mut self.contraction,
            Effect::LightDelay => &mut self.light_delay,
            Effect::Aberration => &mut self.aberration,
            Effect::Doppler => &mut self.doppler,
            Effect::Searchlight => &mut self.searchlight,
            Effect::TimeDilation => &mut self.time_dilation,
        }
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
    /// Why the puck does not fit on the table at t = 0, if it does not.
    /// Touching a cushion is allowed.
    pub fn misplaced(&self, puck: &PuckSpec) -> Option<String> {
        let hx = puck.half_extent_along(DVec2::X);
        let hy = puck.half_extent_along(DVec2::Y);
        let p = puck.position;
        let (lo, hi) = (DVec2::new(hx, hy), self.size - DVec2::new(hx, hy));
        if p.x < lo.x || p.x > hi.x || p.y < lo.y || p.y > hi.y {
            Some(format!(
                "puck \"{}\" at ({}, {}) m reaches outside the table [0, {}] × [0, {}] m \
                 (its half-extents are {:.6} × {:.6} m)",
                puck.name, p.x, p.y, self.size.x, self.size.y, hx, hy
            ))
        } else {
            None
        }
    }
}

/// Index pairs `(i, j)`, `i < j`, of pucks whose rest-frame discs overlap at
/// t = 0 (touching is allowed). Sweep over x, so near O(N log N) for a
/// spread-out scene.
///
/// The rest-frame disc is conservative: a contracted puck lies inside it.
pub fn overlapping_pairs(pucks: &[PuckSpec]) -> Vec<(usize, usize)> {
    let mut order: Vec<usize> = (0..pucks.len()).collect();
    order.sort_by(|&a, &b| {
        let ka = pucks[a].position.x - pucks[a].radius;
        let kb = pucks[b].position.x - pucks[b].radius;
        ka.total_cmp(&kb)
    });
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        let right = pucks[i].position.x + pucks[i].radius;
        for &j in &order[k + 1..] {
            if pucks[j].position.x - pucks[j].radius >= right {
                break;
            }
            let reach = pucks[i].radius + pucks[j].radius;
            // Relative tolerance so that pucks placed in contact (to the
            // digits of the file) are not called overlapping.
            if pucks[i].position.distance(pucks[j].position) < reach * (1.0 - 1e-12) {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

impl Scene {
    /// An empty scene on a table of `size` metres, with `c` (default: light
    /// crosses the long side in 2 s), default effects and no pucks; one
    /// default observer until one is added. For scenes built in code
    /// (Python lessons).
    pub fn empty(size: DVec2, c: Option<f64>) -> Result<Self, String> {
        if !(size.is_finite() && size.x > 0.0 && size.y > 0.0) {
            return Err(format!(
                "table size {size} must be two positive finite numbers"
            ));
        }
        let c = c.unwrap_or(Self::default_c(size));
        if !(c.is_finite() && c > 0.0) {
            return Err(format!("c = {c} must be a positive finite number of m/s"));
        }
        Ok(Self {
            title: "scene".to_owned(),
            description: String::new(),
            c,
            table: TableSpec {
                size,
                cushion_restitution: 1.0,
            },
            restitution: 1.0,
            effects: Effects::default(),
            optics: OpticsSpec::default(),
            before_start: BeforeStart::default(),
            pucks: Vec::new(),
            observers: vec![Self::default_observer(size)],
        })
    }

    /// Adds a puck after the same checks a scene file gets (unique name,
    /// finite numbers, positive radius, height and mass, on the table, clear
    /// of the other pucks). Nothing changes if it fails.
    pub fn add_puck(&mut self, puck: PuckSpec) -> Result<(), String> {
        let name = puck.name.clone();
        if name.trim().is_empty() || self.puck(&name).is_some() {
            return Err(format!("puck name \"{name}\" must be unique and not empty"));
        }
        if !(puck.position.is_finite() && puck.u.is_finite()) {
            return Err(format!(
                "puck \"{name}\": position and velocity must be finite"
            ));
        }
        for (what, v) in [
            ("radius", puck.radius),
            ("height", puck.height),
            ("mass", puck.mass),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(format!(
                    "puck \"{name}\": {what} {v} must be a positive finite number"
                ));
            }
        }
        if let Some(why) = self.table.misplaced(&puck) {
            return Err(why);
        }
        self.pucks.push(puck);
        if let Some(&(i, j)) = overlapping_pairs(&self.pucks)
            .iter()
            .find(|(i, j)| *i == self.pucks.len() - 1 || *j == self.pucks.len() - 1)
        {
            let other = if i == self.pucks.len() - 1 { j } else { i };
            let msg = format!(
                "puck \"{name}\" overlaps puck \"{}\"",
                self.pucks[other].name
            );
            self.pucks.pop();
            return Err(msg);
        }
        Ok(())
    }

    /// Adds an observer (the first one added replaces the default eye).
    pub fn add_observer(&mut self, observer: ObserverSpec) -> Result<(), String> {
        let name = &observer.name;
        let default_only = self.observers.len() == 1
            && self.observers[0] == Self::default_observer(self.table.size);
        if name.trim().is_empty() || (!default_only && self.observer(name).is_some()) {
            return Err(format!(
                "observer name \"{name}\" must be unique and not empty"
            ));
        }
        if !(observer.position.is_finite()
            && observer.look_at.is_finite()
            && observer.u.is_finite())
        {
            return Err(format!(
                "observer \"{name}\": position, look_at and velocity must be finite"
            ));
        }
        if observer.position == observer.look_at {
            return Err(format!(
                "observer \"{name}\": look_at must differ from position"
            ));
        }
        if default_only {
            self.observers.clear();
        }
        self.observers.push(observer);
        Ok(())
    }

    /// The same scene under another speed of light `c` (m/s), every
    /// body keeping its proper velocity in m/s (`γ v`, its momentum per unit
    /// mass): its `u = γβ` scales by `c_old / c`. Raising `c` thus tends to
    /// the Newtonian scene with velocities `γ v`; lowering it never brings a
    /// body to `c`. Errors on a `c` that is not a positive finite number.
    pub fn with_c(&self, c: f64) -> Result<Self, String> {
        if !(c.is_finite() && c > 0.0) {
            return Err(format!("c = {c} must be a positive finite number of m/s"));
        }
        let k = self.c / c;
        let mut scene = self.clone();
        scene.c = c;
        for p in &mut scene.pucks {
            p.u = ProperVelocity(p.u.0 * k);
        }
        for o in &mut scene.observers {
            o.u = ProperVelocity(o.u.0 * k);
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
    /// that the table, seen whole, is not a sliver), looking at its centre.
    pub fn default_observer(size: DVec2) -> ObserverSpec {
        ObserverSpec {
            name: "eye".to_owned(),
            position: DVec3::new(size.x / 2.0, -1.25, 1.6),
            look_at: DVec3::new(size.x / 2.0, size.y / 2.0, 0.0),
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
    fn effects_flags_round_trip() {
        let mut e = Effects::NONE;
        for effect in Effect::ALL {
            assert!(!e.is_on(effect));
            e.set(effect, true);
            assert!(e.is_on(effect));
        }
    }
}
