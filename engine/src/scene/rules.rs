//! The scene rules, stated once: the ranges the engine holds and every
//! check a scene passes, whether it is read from a file
//! (`scene::validate`, which locates each failure at its value) or built
//! in code ([`super::Scene::add_puck`] and its neighbours, Python's
//! `Scene`). Each rule returns a typed [`BuildError`]; its message is the
//! one the file loader prints after `file:line:column: field:`.
//!
//! The ranges: everything a scene gives must lie inside them. Outside them
//! f64 loses the digits the physics and optics need, a figure `lightcone
//! check` prints is no longer finite, or a run cannot finish, so scenes
//! beyond them are refused. The guide (docs/guide/src/scenes.md, "What the engine holds") gives the
//! reasons.

use std::ops::RangeInclusive;

use glam::{DVec2, DVec3};

use super::model::{Color, PuckSpec, TableSpec};
use crate::spacetime::ProperVelocity;

/// Largest proper speed |u| = γ|β| a puck or observer may have. β itself
/// rounds to 1 in f64 from |u| ≈ 10⁸ on; the engine works with u, never
/// with 1 − β², so it holds far beyond that, and γ = √(1 + u²) stays exact
/// to the last digit up to here.
pub const MAX_U: f64 = 1e12;
/// Lengths (table sides, puck radius and height), m.
pub const LENGTH_RANGE: RangeInclusive<f64> = 1e-6..=1e6;
/// Puck rest mass, kg.
pub const MASS_RANGE: RangeInclusive<f64> = 1e-9..=1e9;
/// Speed of light, m/s (the real one, 299 792 458, included).
pub const C_RANGE: RangeInclusive<f64> = 1e-6..=1e9;
/// Largest coefficient of sliding friction a scene may give (`table.friction`).
pub const MAX_FRICTION: f64 = 100.0;
/// Smallest non-zero coefficient of sliding friction (`table.friction` is
/// 0 or from here to [`MAX_FRICTION`]). With the slowest gravity
/// ([`GRAVITY_RANGE`]) the braking deceleration μg is then at least
/// 10⁻¹² m/s², so the braking's Rindler length c²/(μg) is at most 10³⁰ m
/// and a stopping distance (c²/μg)(γ − 1) at most 10⁴² m at the fastest c
/// and |u| a scene holds: finite, as every figure `check` prints. (The
/// smallest double, 5e-324, gives c²/(μg) = ∞.) Below it, braking on any
/// table the engine holds is uniform motion to every printed digit.
pub const MIN_FRICTION: f64 = 1e-6;
/// Range of the gravitational acceleration a scene may give
/// (`table.gravity`), m/s².
pub const GRAVITY_RANGE: RangeInclusive<f64> = 1e-6..=1e6;
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

/// A number as messages and summaries show it: as written (`1.42`,
/// `0.0305`, `2500`) from 10⁻⁴ to below 10⁶, else in exponent form
/// (`1e-300`, `1e6`, `2.5e20`), never hundreds of digits; `inf` and `NaN`
/// as such.
#[must_use]
pub fn number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || !x.is_finite() || (1e-4..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// |v| without overflow: finite for every finite `v` (10²⁰⁰ squared is
/// not).
#[must_use]
pub fn magnitude(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        m
    } else {
        m * (v / m).length()
    }
}

/// A number a scene gives that has a range: which, for the message and the
/// bounds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    /// The speed of light `c`, m/s ([`C_RANGE`]).
    C,
    /// A puck's radius or height, m ([`LENGTH_RANGE`]).
    Length,
    /// A puck's rest mass, kg ([`MASS_RANGE`]).
    Mass,
    /// `table.gravity`, m/s² ([`GRAVITY_RANGE`]).
    Gravity,
    /// `table.friction`: 0, or [`MIN_FRICTION`] to [`MAX_FRICTION`].
    Friction,
    /// A restitution (puck or cushion), [0, 1].
    Restitution,
    /// A body's proper speed |u| = γ|β|, at most [`MAX_U`].
    ProperSpeed,
    /// `[optics] history_frames`, 2 to [`MAX_HISTORY_FRAMES`].
    HistoryFrames,
    /// `[optics] dichotomy_steps`, 0 to [`MAX_DICHOTOMY_STEPS`].
    DichotomySteps,
}

impl Quantity {
    /// Whether `x` is allowed.
    #[must_use]
    pub fn holds(self, x: f64) -> bool {
        match self {
            Quantity::C => C_RANGE.contains(&x),
            Quantity::Length => LENGTH_RANGE.contains(&x),
            Quantity::Mass => MASS_RANGE.contains(&x),
            Quantity::Gravity => GRAVITY_RANGE.contains(&x),
            Quantity::Friction => x == 0.0 || (MIN_FRICTION..=MAX_FRICTION).contains(&x),
            Quantity::Restitution => (0.0..=1.0).contains(&x),
            Quantity::ProperSpeed => (0.0..=MAX_U).contains(&x),
            Quantity::HistoryFrames => (2.0..=MAX_HISTORY_FRAMES as f64).contains(&x),
            Quantity::DichotomySteps => (0.0..=f64::from(MAX_DICHOTOMY_STEPS)).contains(&x),
        }
    }

    /// `x`, or the error saying what is allowed.
    pub fn check(self, x: f64) -> Result<f64, BuildError> {
        if self.holds(x) {
            Ok(x)
        } else {
            Err(BuildError::OutOfRange {
                quantity: self,
                value: x,
            })
        }
    }

    /// What the loader says of `x` outside the range (after the field).
    fn refusal(self, x: f64) -> String {
        let between = |r: &RangeInclusive<f64>, unit: &str| {
            format!(
                "{} must be a positive finite number from {} to {} {unit}",
                number(x),
                number(*r.start()),
                number(*r.end())
            )
        };
        match self {
            Quantity::C => between(&C_RANGE, "m/s"),
            Quantity::Length => between(&LENGTH_RANGE, "m"),
            Quantity::Mass => between(&MASS_RANGE, "kg"),
            Quantity::Gravity => between(&GRAVITY_RANGE, "m/s²"),
            Quantity::Friction if x > 0.0 && x < MIN_FRICTION => format!(
                "{} is too small a friction to brake with: give 0 (frictionless) or from {} \
                 to {MAX_FRICTION} (a carom cloth slides at about 0.2)",
                number(x),
                number(MIN_FRICTION)
            ),
            Quantity::Friction => format!(
                "{} must be a finite number from 0 (frictionless) to {MAX_FRICTION} \
                 (a carom cloth slides at about 0.2)",
                number(x)
            ),
            Quantity::Restitution => format!("{} must lie in [0, 1]", number(x)),
            Quantity::ProperSpeed => format!(
                "|u| = {} is beyond what the engine holds: give |u| = γ|β| ≤ {}",
                number(x),
                number(MAX_U)
            ),
            Quantity::HistoryFrames => {
                format!("{x} must be at least 2 and at most {MAX_HISTORY_FRAMES}")
            }
            Quantity::DichotomySteps => {
                format!("{x} must be 0 (full) or more, at most {MAX_DICHOTOMY_STEPS}")
            }
        }
    }
}

/// A scene rule broken, by a value in a scene file or by a scene built in
/// code. The variants are what a caller tells apart (Python raises
/// `SpeedOfLightError` for [`BuildError::TooFast`], for instance); the
/// message ([`std::fmt::Display`]) says what is wrong and what would be
/// right, on one line. [`BuildError::In`] names the body or field that
/// broke a rule; [`BuildError::rule`] is the rule under it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// A speed at or above `c`: a `beta` of |β| ≥ 1 (an f64 β that rounds
    /// to 1 included), or a `velocity` of |v| ≥ c.
    #[error("{}", too_fast(*.speed, *.c))]
    TooFast {
        /// |β| when `c` is `None`, else |v| in m/s.
        speed: f64,
        /// The speed of light a `velocity` was given against, m/s.
        c: Option<f64>,
    },
    /// A number outside what the engine holds.
    #[error("{}", .quantity.refusal(*.value))]
    OutOfRange {
        /// Which number.
        quantity: Quantity,
        /// The value given.
        value: f64,
    },
    /// A table side outside [`LENGTH_RANGE`] (or not a positive number).
    #[error(
        "[{}, {}]: both sides must be positive, from {} to {} m",
        number(.0.x), number(.0.y), number(*LENGTH_RANGE.start()), number(*LENGTH_RANGE.end())
    )]
    TableSize(DVec2),
    /// A list of numbers with a NaN or an infinity in it.
    #[error("{} has a component that is not a finite number", list(.0))]
    NotFinite(Vec<f64>),
    /// More than one of `beta`, `velocity` and `u` for one body.
    #[error("give at most one of `beta`, `velocity` and `u`")]
    TwoSpeeds,
    /// An observer's eye or `look_at` too far from the board.
    #[error(
        "({}, {}, {}) m is too far: keep each coordinate within ±{} m",
        number(.0.x), number(.0.y), number(.0.z), number(MAX_OBSERVER_DISTANCE)
    )]
    TooFar(DVec3),
    /// An observer looking at its own eye.
    #[error("must differ from `position`")]
    LookAtEye,
    /// A puck reaching outside the table at t = 0 (judged by its contracted
    /// half-extents; touching a cushion is allowed).
    #[error(
        "puck \"{puck}\" at ({}, {}) m reaches outside the table [0, {}] × [0, {}] m \
         (its half-extents are {} × {} m)",
        number(.position.x), number(.position.y), number(.size.x), number(.size.y),
        number(.half.x), number(.half.y)
    )]
    OffTable {
        /// The puck.
        puck: String,
        /// Its centre, m.
        position: DVec2,
        /// The table, m.
        size: DVec2,
        /// Its contracted half-extents along x and y, m.
        half: DVec2,
    },
    /// A puck whose rest disc is wider than the table: once it slows, its
    /// board shape could fit nowhere between the cushions.
    #[error(
        "puck \"{puck}\" is {} m across at rest, wider than the table's {} m side: \
         give a radius of at most half the table's shorter side",
        number(2.0 * *.radius), number(*.side)
    )]
    WiderThanTable {
        /// The puck.
        puck: String,
        /// Its rest radius, m.
        radius: f64,
        /// The table's shorter side, m.
        side: f64,
    },
    /// Two pucks' rest-frame discs overlapping at t = 0.
    #[error(
        "puck \"{puck}\" overlaps puck \"{other}\"{}: centres {} m apart, radii add to {} m",
        .other_line.map(|l| format!(" (line {l})")).unwrap_or_default(),
        number(*.distance), number(*.reach)
    )]
    Overlap {
        /// The puck placed later.
        puck: String,
        /// The puck it overlaps.
        other: String,
        /// The line of `other` in a scene file.
        other_line: Option<usize>,
        /// Distance between the centres, m.
        distance: f64,
        /// Sum of the radii, m.
        reach: f64,
    },
    /// A puck too large to brake rigidly: a Born-rigid body must be shorter
    /// than the braking's Rindler horizon `c²/(μg)` (see
    /// [`crate::worldline::sliding`]).
    #[error(
        "puck \"{puck}\" (radius {} m) cannot brake rigidly: with friction {}, gravity {} m/s² \
         and c = {} m/s a puck must be smaller than c²/(μg) = {} m{}",
        number(*.radius), number(*.friction), number(*.gravity), number(*.c),
        number(.c * .c / (.friction * .gravity)),
        .min_c.map(|m| format!(
            ": on this cloth c must be above {} m/s (or the table frictionless)", number(m)
        )).unwrap_or_default()
    )]
    BeyondHorizon {
        /// The puck.
        puck: String,
        /// Its radius, m.
        radius: f64,
        /// μ.
        friction: f64,
        /// g, m/s².
        gravity: f64,
        /// c, m/s.
        c: f64,
        /// When c was being changed: the slowest light every puck fits
        /// under, `√(R μ g)` of the largest puck, m/s.
        min_c: Option<f64>,
    },
    /// An empty name.
    #[error("a name must not be empty")]
    EmptyName,
    /// A name with spaces or control characters at its ends (" a " would sit
    /// beside "a" and confuse every look-up).
    #[error("name {0:?}: give a name without spaces or control characters at its ends")]
    PaddedName(String),
    /// A name already taken by a body of the same kind.
    #[error("duplicate name \"{0}\": names must be unique")]
    DuplicateName(String),
    /// A colour that is neither `#rrggbb` nor a known name.
    #[error("\"{0}\" is not a colour: use \"#rrggbb\" or a name such as \"red\"")]
    UnknownColor(String),
    /// More bodies than a scene holds.
    #[error("{count} {what}: a scene holds at most {max}")]
    TooMany {
        /// "pucks" or "observers".
        what: &'static str,
        /// How many were given.
        count: usize,
        /// The most a scene holds.
        max: usize,
    },
    /// A scene with no observer (one sent as data).
    #[error("a scene has at least one observer")]
    NoObserver,
    /// A rule broken by `subject` (a puck and its field, `Scene.c`, …).
    #[error("{subject}: {error}")]
    In {
        /// What broke it, e.g. `puck "a" radius`.
        subject: String,
        /// The rule broken.
        error: Box<BuildError>,
    },
}

impl BuildError {
    /// This error as broken by `subject`.
    pub fn of(self, subject: impl Into<String>) -> Self {
        BuildError::In {
            subject: subject.into(),
            error: Box::new(self),
        }
    }

    /// The rule broken, under every [`BuildError::In`].
    #[must_use]
    pub fn rule(&self) -> &BuildError {
        match self {
            BuildError::In { error, .. } => error.rule(),
            other => other,
        }
    }
}

fn too_fast(speed: f64, c: Option<f64>) -> String {
    match c {
        None => format!(
            "speed |β| = {} is not below the speed of light (|β| must be < 1); \
             to state γ beyond ~10⁷ give `u` = γβ instead",
            number(speed)
        ),
        Some(c) => format!(
            "speed {} m/s is not below c = {} m/s",
            number(speed),
            number(c)
        ),
    }
}

/// `[a, b, …]` with each number as [`number`] writes it.
pub(super) fn list(x: &[f64]) -> String {
    let parts: Vec<String> = x.iter().map(|v| number(*v)).collect();
    format!("[{}]", parts.join(", "))
}

/// The numbers, if every one is finite.
pub fn finite(x: &[f64]) -> Result<(), BuildError> {
    if x.iter().all(|c| c.is_finite()) {
        Ok(())
    } else {
        Err(BuildError::NotFinite(x.to_vec()))
    }
}

/// A table of `size` m: both sides in [`LENGTH_RANGE`].
pub fn table_size(size: DVec2) -> Result<DVec2, BuildError> {
    if LENGTH_RANGE.contains(&size.x) && LENGTH_RANGE.contains(&size.y) {
        Ok(size)
    } else {
        Err(BuildError::TableSize(size))
    }
}

/// The proper velocity of a body at `beta` = v/c: finite, |β| < 1.
pub fn from_beta(beta: DVec3) -> Result<ProperVelocity, BuildError> {
    finite(&beta.to_array())?;
    ProperVelocity::try_from_beta(beta).map_err(|_| BuildError::TooFast {
        speed: magnitude(beta),
        c: None,
    })
}

/// The proper velocity of a body at `velocity` m/s under light at `c` m/s:
/// finite, |v| < c.
pub fn from_velocity(velocity: DVec3, c: f64) -> Result<ProperVelocity, BuildError> {
    finite(&velocity.to_array())?;
    ProperVelocity::try_from_velocity(velocity, c).map_err(|_| BuildError::TooFast {
        speed: magnitude(velocity),
        c: Some(c),
    })
}

/// A proper velocity `u` = γβ given as such: finite, |u| ≤ [`MAX_U`].
pub fn proper_velocity(u: DVec3) -> Result<ProperVelocity, BuildError> {
    finite(&u.to_array())?;
    Quantity::ProperSpeed.check(magnitude(u))?;
    Ok(ProperVelocity(u))
}

/// A body's proper velocity from at most one of `beta`, `velocity` (m/s,
/// under light at `c`) and `u`; at rest when none is given.
pub fn motion(
    beta: Option<DVec3>,
    velocity: Option<DVec3>,
    u: Option<DVec3>,
    c: f64,
) -> Result<ProperVelocity, BuildError> {
    match (beta, velocity, u) {
        (Some(b), None, None) => from_beta(b),
        (None, Some(v), None) => from_velocity(v, c),
        (None, None, Some(u)) => proper_velocity(u),
        (None, None, None) => Ok(ProperVelocity::ZERO),
        _ => Err(BuildError::TwoSpeeds),
    }
}

/// A body's name: not empty, no spaces or control characters at its ends,
/// not one of the names `taken` says are used.
pub fn name(name: &str, taken: impl Fn(&str) -> bool) -> Result<(), BuildError> {
    let padded = |c: char| c.is_whitespace() || c.is_control();
    if name.is_empty() {
        Err(BuildError::EmptyName)
    } else if name.starts_with(padded) || name.ends_with(padded) {
        Err(BuildError::PaddedName(name.to_owned()))
    } else if taken(name) {
        Err(BuildError::DuplicateName(name.to_owned()))
    } else {
        Ok(())
    }
}

/// A colour: `#rrggbb` or a name from [`Color::NAMED`].
pub fn color(text: &str) -> Result<Color, BuildError> {
    Color::parse(text).ok_or_else(|| BuildError::UnknownColor(text.to_owned()))
}

/// An observer's eye or `look_at`: each coordinate within
/// ±[`MAX_OBSERVER_DISTANCE`] of the board's origin.
pub fn near(p: DVec3) -> Result<DVec3, BuildError> {
    if p.abs().max_element() > MAX_OBSERVER_DISTANCE {
        Err(BuildError::TooFar(p))
    } else {
        Ok(p)
    }
}

/// The puck fits on the table at t = 0 (judged by its contracted
/// half-extents; touching a cushion is allowed), and its rest disc fits
/// between the cushions (a kick that slows it re-contracts it about a
/// cushion it touches: `physics::billiard`).
pub fn on_table(table: &TableSpec, puck: &PuckSpec) -> Result<(), BuildError> {
    let side = table.size.min_element();
    if 2.0 * puck.radius > side {
        return Err(BuildError::WiderThanTable {
            puck: puck.name.clone(),
            radius: puck.radius,
            side,
        });
    }
    let half = DVec2::new(
        puck.half_extent_along(DVec2::X),
        puck.half_extent_along(DVec2::Y),
    );
    let p = puck.position;
    let hi = table.size - half;
    if p.x < half.x || p.x > hi.x || p.y < half.y || p.y > hi.y {
        Err(BuildError::OffTable {
            puck: puck.name.clone(),
            position: p,
            size: table.size,
            half,
        })
    } else {
        Ok(())
    }
}

/// The first puck of `pucks` that cannot brake rigidly on a table of
/// sliding friction `friction` under `gravity` m/s² with light at `c` m/s
/// (a Born-rigid body must be shorter than the braking's Rindler horizon
/// `c²/(μg)`, see [`crate::worldline::sliding`]): its index and the error;
/// `None` when every puck can (or μ = 0).
#[must_use]
pub fn braking_horizon(
    c: f64,
    friction: f64,
    gravity: f64,
    pucks: &[PuckSpec],
) -> Option<(usize, BuildError)> {
    if friction <= 0.0 {
        return None;
    }
    let horizon = c * c / (friction * gravity);
    let k = pucks.iter().position(|p| p.radius >= horizon)?;
    let p = &pucks[k];
    Some((
        k,
        BuildError::BeyondHorizon {
            puck: p.name.clone(),
            radius: p.radius,
            friction,
            gravity,
            c,
            min_c: None,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rule_under_a_subject_is_the_rule() {
        let e = Quantity::Length
            .check(0.0)
            .unwrap_err()
            .of("puck \"a\" radius");
        assert_eq!(
            e.to_string(),
            "puck \"a\" radius: 0 must be a positive finite number from 1e-6 to 1e6 m"
        );
        assert!(matches!(
            e.rule(),
            BuildError::OutOfRange {
                quantity: Quantity::Length,
                ..
            }
        ));
        assert!(matches!(
            from_beta(DVec3::X).unwrap_err(),
            BuildError::TooFast { c: None, .. }
        ));
        assert_eq!(
            motion(Some(DVec3::ZERO), None, Some(DVec3::ZERO), 1.0),
            Err(BuildError::TwoSpeeds)
        );
    }

    #[test]
    fn names_are_refused_empty_padded_or_taken() {
        assert_eq!(name("", |_| false), Err(BuildError::EmptyName));
        for bad in [" a", "a ", "\ta", "a\n", "\u{1}a"] {
            assert!(
                matches!(name(bad, |_| false), Err(BuildError::PaddedName(_))),
                "{bad:?}"
            );
        }
        assert_eq!(
            name("a", |n| n == "a"),
            Err(BuildError::DuplicateName("a".into()))
        );
        assert_eq!(name("a b", |_| false), Ok(()));
    }
}
