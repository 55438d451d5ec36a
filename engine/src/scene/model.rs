//! The validated scene: what the engine builds a world from.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::effects::Effects;
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
    #[must_use]
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
    #[must_use]
    pub fn target(&self, size: DVec2) -> DVec3 {
        self.look_at
            .unwrap_or_else(|| DVec3::new(size.x / 2.0, size.y / 2.0, 0.0))
    }

    /// How a view of this observer is aimed unless told otherwise: along
    /// its `look_at` with a 60° vertical field when the scene names one,
    /// else turned and widened to show the whole table (cushions included)
    /// with [`crate::camera::FIT_MARGIN`] in a viewport of `aspect` =
    /// width / height: the window's default framing.
    #[must_use]
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
    #[must_use]
    pub const fn rgb(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// Parses `#rrggbb` or a name from [`Color::NAMED`].
    #[must_use]
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
    #[must_use]
    pub fn default_for(i: usize) -> Self {
        Self::NAMED[i % 10].1
    }

    /// `#rrggbb`.
    #[must_use]
    pub fn to_hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.r, self.g, self.b)
    }
}

impl PuckSpec {
    /// Half-width of the contracted puck along the unit axis `axis`, m:
    /// the support of an ellipse of semi-axes `R/γ` (along the motion) and
    /// `R`, which is `R √(1 − (axis·β)²)`, formed as `R √((1 − a)(1 + a))`.
    #[must_use]
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
    #[must_use]
    pub fn frictionless(size: DVec2, cushion_restitution: f64) -> Self {
        Self {
            size,
            cushion_restitution,
            friction: 0.0,
            gravity: Self::STANDARD_GRAVITY,
        }
    }

    /// The proper deceleration of a sliding puck, `μ g`, m/s².
    #[must_use]
    pub fn deceleration(&self) -> f64 {
        self.friction * self.gravity
    }
}

impl Scene {
    /// Speed of light for a table: light crosses the long side in 2 s, as in
    /// the paper's experiments.
    #[must_use]
    pub fn default_c(size: DVec2) -> f64 {
        size.x.max(size.y) / 2.0
    }

    /// The observer used when a scene names none: standing at rest beside
    /// the long side, 1.25 m back and 1.6 m above the board (high enough
    /// that the table, seen whole, is not a sliver), its views framed to
    /// show the whole table.
    #[must_use]
    pub fn default_observer(size: DVec2) -> ObserverSpec {
        ObserverSpec {
            name: "eye".to_owned(),
            position: DVec3::new(size.x / 2.0, -1.25, 1.6),
            look_at: None,
            u: ProperVelocity::ZERO,
        }
    }

    /// The puck called `name`.
    #[must_use]
    pub fn puck(&self, name: &str) -> Option<&PuckSpec> {
        self.pucks.iter().find(|p| p.name == name)
    }

    /// The observer called `name`.
    #[must_use]
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
}
