//! The validated scene: what the engine builds a world from.

use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

use super::error::number;
use crate::spacetime::ProperVelocity;

/// Default puck radius, m: a carom ball's 61.5 mm diameter.
pub const DEFAULT_RADIUS: f64 = 0.0305;
/// Default puck height, m.
pub const DEFAULT_HEIGHT: f64 = 0.02;
/// Default puck mass, kg (a carom ball).
pub const DEFAULT_MASS: f64 = 0.21;
/// Default playing area of a match carom table, m.
pub const DEFAULT_TABLE: [f64; 2] = [2.84, 1.42];

// The range the engine holds. Everything a scene gives must lie inside it;
// outside it f64 loses the digits the physics and optics need (or a run
// cannot finish), so scenes beyond it are refused with a located error.
// README, "What the engine holds", gives the reasons.

/// Largest proper speed |u| = γ|β| a puck or observer may have. β itself
/// rounds to 1 in f64 from |u| ≈ 10⁸ on; the engine works with u, never
/// with 1 − β², so it holds far beyond that, and γ = √(1 + u²) stays exact
/// to the last digit up to here.
pub const MAX_U: f64 = 1e12;
/// |v| without overflow: finite for every finite `v` (10²⁰⁰ squared is
/// not).
pub fn magnitude(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        m
    } else {
        m * (v / m).length()
    }
}

/// Lengths (table sides, puck radius and height), m.
pub const LENGTH_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=1e6;
/// Puck rest mass, kg.
pub const MASS_RANGE: std::ops::RangeInclusive<f64> = 1e-9..=1e9;
/// Speed of light, m/s (the real one, 299 792 458, included).
pub const C_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=1e9;
/// Largest coefficient of sliding friction a scene may give (`table.friction`).
pub const MAX_FRICTION: f64 = 100.0;
/// Range of the gravitational acceleration a scene may give
/// (`table.gravity`), m/s².
pub const GRAVITY_RANGE: std::ops::RangeInclusive<f64> = 1e-6..=1e6;
/// Largest coordinate of an observer's eye or `look_at`, m.
pub const MAX_OBSERVER_DISTANCE: f64 = 1e9;
/// Most pucks in one scene.
pub const MAX_PUCKS: usize = 1_000_000;
/// Most observers in one scene.
pub const MAX_OBSERVERS: usize = 1000;
/// Most frames of sampled history (`[optics] history_frames`).
pub const MAX_HISTORY_FRAMES: usize = 100_000;
/// Most dichotomy steps (`[optics] dichotomy_steps`): 64 halvings exhaust
/// an f64 interval.
pub const MAX_DICHOTOMY_STEPS: u32 = 64;

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

/// The `[effects]` flags: a scene's effect set (in the ECS each view
/// carries it as one marker component per effect, see `crate::ecs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
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
                 (its half-extents are {} × {} m)",
                puck.name,
                number(p.x),
                number(p.y),
                number(self.size.x),
                number(self.size.y),
                number(hx),
                number(hy)
            ))
        } else {
            None
        }
    }
}

/// Whether the rest-frame discs of `a` and `b` overlap at t = 0 (touching,
/// to a relative 10⁻¹², is allowed: pucks placed in contact to the digits of
/// the file are not called overlapping).
pub fn overlap(a: &PuckSpec, b: &PuckSpec) -> bool {
    let reach = a.radius + b.radius;
    a.position.distance(b.position) < reach * (1.0 - 1e-12)
}

/// For each puck `j` whose rest-frame disc overlaps that of an earlier puck
/// at t = 0, one pair `(i, j)` with `i < j` (the first such `i` the search
/// meets; touching is allowed), in increasing `j`. At most one pair per
/// puck, so 10⁵ pucks at one point give 10⁵ − 1 pairs, not 5·10⁹.
///
/// A uniform grid of cells twice the median radius: each puck is filed
/// under the cells its bounding square covers and compared only with the
/// pucks filed there, so the cost is O(N) for pucks of similar size
/// however they are laid out (on a line, in a crowd, all at one point). A
/// puck covering more than 16 cells (much larger than the median) is kept
/// on a short list compared with every puck.
///
/// The rest-frame disc is conservative: a contracted puck lies inside it.
pub fn first_overlaps(pucks: &[PuckSpec]) -> Vec<(usize, usize)> {
    use std::collections::HashMap;
    if pucks.len() < 2 {
        return Vec::new();
    }
    let mut radii: Vec<f64> = pucks.iter().map(|p| p.radius).collect();
    let mid = radii.len() / 2;
    let (_, median, _) = radii.select_nth_unstable_by(mid, f64::total_cmp);
    let cell = 2.0 * *median;
    let index = |x: f64| (x / cell).floor() as i64;
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut big: Vec<usize> = Vec::new();
    let mut pairs = Vec::new();
    for (j, p) in pucks.iter().enumerate() {
        let (x0, x1) = (
            index(p.position.x - p.radius),
            index(p.position.x + p.radius),
        );
        let (y0, y1) = (
            index(p.position.y - p.radius),
            index(p.position.y + p.radius),
        );
        let cells = (x1 - x0 + 1).saturating_mul(y1 - y0 + 1);
        let found = if cells > 16 {
            (0..j).find(|&i| overlap(&pucks[i], p))
        } else {
            let mut found = big.iter().copied().find(|&i| overlap(&pucks[i], p));
            'cells: for cx in x0..=x1 {
                for cy in y0..=y1 {
                    if found.is_some() {
                        break 'cells;
                    }
                    if let Some(list) = grid.get(&(cx, cy)) {
                        found = list.iter().copied().find(|&i| overlap(&pucks[i], p));
                    }
                }
            }
            found
        };
        if let Some(i) = found {
            pairs.push((i, j));
        }
        if cells > 16 {
            big.push(j);
        } else {
            for cx in x0..=x1 {
                for cy in y0..=y1 {
                    grid.entry((cx, cy)).or_default().push(j);
                }
            }
        }
    }
    pairs
}

/// Why a puck of `pucks` cannot brake rigidly on a table of sliding
/// friction `friction` under `gravity` m/s² with light at `c` m/s: a
/// Born-rigid body must be shorter than the braking's Rindler horizon
/// `c²/(μg)` (see [`crate::worldline::sliding`]). The index of the first
/// such puck and the reason; `None` when every puck can (or μ = 0).
pub fn braking_horizon_error(
    c: f64,
    friction: f64,
    gravity: f64,
    pucks: &[PuckSpec],
) -> Option<(usize, String)> {
    if friction <= 0.0 {
        return None;
    }
    let horizon = c * c / (friction * gravity);
    let k = pucks.iter().position(|p| p.radius >= horizon)?;
    let p = &pucks[k];
    Some((
        k,
        format!(
            "puck \"{}\" (radius {} m) cannot brake rigidly: with friction {}, gravity {} m/s² \
             and c = {} m/s a puck must be smaller than c²/(μg) = {} m",
            p.name,
            number(p.radius),
            number(friction),
            number(gravity),
            number(c),
            number(horizon)
        ),
    ))
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
        if !(LENGTH_RANGE.contains(&size.x) && LENGTH_RANGE.contains(&size.y)) {
            return Err(format!(
                "table size ({}, {}) m: both sides must be from {} to {} m",
                number(size.x),
                number(size.y),
                number(*LENGTH_RANGE.start()),
                number(*LENGTH_RANGE.end())
            ));
        }
        let c = c.unwrap_or(Self::default_c(size));
        if !C_RANGE.contains(&c) {
            return Err(format!(
                "c = {} m/s must be from {} to {} m/s",
                number(c),
                number(*C_RANGE.start()),
                number(*C_RANGE.end())
            ));
        }
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
        if magnitude(puck.u.0) > MAX_U {
            return Err(format!(
                "puck \"{name}\": |u| = {} is beyond what the engine holds (at most {})",
                number(magnitude(puck.u.0)),
                number(MAX_U)
            ));
        }
        for (what, v, range, unit) in [
            ("radius", puck.radius, LENGTH_RANGE, "m"),
            ("height", puck.height, LENGTH_RANGE, "m"),
            ("mass", puck.mass, MASS_RANGE, "kg"),
        ] {
            if !range.contains(&v) {
                return Err(format!(
                    "puck \"{name}\": {what} {} must be a number from {} to {} {unit}",
                    number(v),
                    number(*range.start()),
                    number(*range.end())
                ));
            }
        }
        if self.pucks.len() >= MAX_PUCKS {
            return Err(format!("a scene holds at most {MAX_PUCKS} pucks"));
        }
        if let Some(why) = self.table.misplaced(&puck) {
            return Err(why);
        }
        if self.table.deceleration() > 0.0
            && puck.radius >= self.c * self.c / self.table.deceleration()
        {
            return Err(format!(
                "puck \"{name}\" (radius {} m) cannot brake rigidly on this table: it must be \
                 smaller than c²/(μg) = {} m",
                number(puck.radius),
                number(self.c * self.c / self.table.deceleration())
            ));
        }
        // One pass over the others: O(N) per puck added.
        if let Some(other) = self.pucks.iter().find(|o| overlap(o, &puck)) {
            return Err(format!("puck \"{name}\" overlaps puck \"{}\"", other.name));
        }
        if let Some((_, why)) = braking_horizon_error(
            self.c,
            self.table.friction,
            self.table.gravity,
            std::slice::from_ref(&puck),
        ) {
            return Err(why);
        }
        self.pucks.push(puck);
        Ok(())
    }

    /// Sets the table's sliding friction `friction` (μ, 0 to
    /// [`MAX_FRICTION`]) and `gravity` (m/s², in [`GRAVITY_RANGE`]), after
    /// the checks a scene file's `[table] friction`/`gravity` get, including
    /// that every puck is smaller than the braking's Rindler horizon
    /// `c²/(μg)`. Nothing changes if it fails.
    pub fn set_friction(&mut self, friction: f64, gravity: f64) -> Result<(), String> {
        if !(0.0..=MAX_FRICTION).contains(&friction) {
            return Err(format!(
                "friction {} must be a finite number from 0 (frictionless) to {MAX_FRICTION} \
                 (a carom cloth slides at about 0.2)",
                number(friction)
            ));
        }
        if !GRAVITY_RANGE.contains(&gravity) {
            return Err(format!(
                "gravity {} must be a number from {} to {} m/s²",
                number(gravity),
                number(*GRAVITY_RANGE.start()),
                number(*GRAVITY_RANGE.end())
            ));
        }
        if let Some((_, why)) = braking_horizon_error(self.c, friction, gravity, &self.pucks) {
            return Err(why);
        }
        self.table.friction = friction;
        self.table.gravity = gravity;
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
            && observer.look_at.is_none_or(|p| p.is_finite())
            && observer.u.is_finite())
        {
            return Err(format!(
                "observer \"{name}\": position, look_at and velocity must be finite"
            ));
        }
        if observer.position.abs().max_element() > MAX_OBSERVER_DISTANCE
            || observer
                .look_at
                .is_some_and(|p| p.abs().max_element() > MAX_OBSERVER_DISTANCE)
        {
            return Err(format!(
                "observer \"{name}\": keep position and look_at within ±{} m",
                number(MAX_OBSERVER_DISTANCE)
            ));
        }
        if magnitude(observer.u.0) > MAX_U {
            return Err(format!(
                "observer \"{name}\": |u| = {} is beyond what the engine holds (at most {})",
                number(magnitude(observer.u.0)),
                number(MAX_U)
            ));
        }
        if !default_only && self.observers.len() >= MAX_OBSERVERS {
            return Err(format!("a scene holds at most {MAX_OBSERVERS} observers"));
        }
        if observer.look_at == Some(observer.position) {
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

    /// The same scene rebuilt through the checks a scene built in code
    /// gets ([`Self::empty`], [`Self::add_puck`], [`Self::set_friction`],
    /// [`Self::add_observer`]) plus the ranges of the fields those leave
    /// (restitutions in [0, 1], the `[optics]` limits): for a scene that
    /// arrives as data from a process the game does not trust (a lesson
    /// run in its own process sends `world.start(scene)` as JSON). Errors
    /// name the first problem.
    pub fn rebuilt(&self) -> Result<Self, String> {
        let mut scene = Self::empty(self.table.size, Some(self.c))?;
        for p in &self.pucks {
            scene.add_puck(p.clone())?;
        }
        scene.set_friction(self.table.friction, self.table.gravity)?;
        if self.observers.is_empty() {
            return Err("a scene has at least one observer".to_owned());
        }
        for o in &self.observers {
            scene.add_observer(o.clone())?;
        }
        for (what, r) in [
            ("restitution", self.restitution),
            ("cushion_restitution", self.table.cushion_restitution),
        ] {
            if !(0.0..=1.0).contains(&r) {
                return Err(format!("{what} {} must be from 0 to 1", number(r)));
            }
        }
        if self.optics.history_frames > MAX_HISTORY_FRAMES
            || self.optics.dichotomy_steps > MAX_DICHOTOMY_STEPS
        {
            return Err(format!(
                "optics: history_frames at most {MAX_HISTORY_FRAMES}, dichotomy_steps at most {MAX_DICHOTOMY_STEPS}"
            ));
        }
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
    /// body to `c`. Errors on a `c` outside [`C_RANGE`] (as a scene file's),
    /// on a body whose `u` would leave what the engine holds ([`MAX_U`]),
    /// and on a puck that would not fit inside the braking's Rindler
    /// horizon; the scene is then unchanged.
    pub fn with_c(&self, c: f64) -> Result<Self, String> {
        if !C_RANGE.contains(&c) {
            return Err(format!(
                "{} must be a positive finite number from {} to {} m/s",
                number(c),
                number(*C_RANGE.start()),
                number(*C_RANGE.end())
            ));
        }
        // On a cloth, slower light brings the braking's Rindler horizon
        // closer: refused (the scene kept) once a puck would not fit.
        if let Some((_, why)) =
            braking_horizon_error(c, self.table.friction, self.table.gravity, &self.pucks)
        {
            let slowest = self
                .pucks
                .iter()
                .map(|p| (p.radius * self.table.deceleration()).sqrt())
                .fold(0.0, f64::max);
            return Err(format!(
                "{why}: on this cloth c must be above {} m/s (or the table frictionless)",
                number(slowest)
            ));
        }
        let k = self.c / c;
        let fastest = self
            .pucks
            .iter()
            .map(|p| magnitude(p.u.0))
            .chain(self.observers.iter().map(|o| magnitude(o.u.0)))
            .fold(0.0, f64::max);
        if fastest * k > MAX_U {
            return Err(format!(
                "c = {} m/s would take a body to |u| = {}, beyond what the engine holds \
                 (at most {}): c must be at least {} m/s",
                number(c),
                number(fastest * k),
                number(MAX_U),
                number(fastest * self.c / MAX_U)
            ));
        }
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
        assert!(overlapping.rebuilt().unwrap_err().contains("overlaps"));
        let mut fast = scene.clone();
        fast.pucks[0].u = ProperVelocity(DVec3::new(f64::INFINITY, 0.0, 0.0));
        assert!(fast.rebuilt().is_err());
        let mut bouncy = scene.clone();
        bouncy.restitution = 1.5;
        assert!(bouncy.rebuilt().unwrap_err().contains("restitution"));
        let mut blind = scene;
        blind.observers.clear();
        assert!(blind.rebuilt().is_err());
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
