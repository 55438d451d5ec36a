//! Why a world operation refused: the kind of error (the name of the
//! Python exception a lesson catches) and the message.

use lightcone_engine::scene::{BuildError, SceneErrors};

/// The kind of a [`WorldError`]: one Python exception class each (the
/// `lightcone` module's own classes are subclasses of `ValueError` or
/// `RuntimeError`: see `py/src/errors.rs`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// A value out of its range or of the wrong shape.
    Value,
    /// A name (puck, observer) the scene does not have.
    Key,
    /// An argument of the wrong type, or missing.
    Type,
    /// No game (outside a hook, before `world.start`), or nothing seen.
    Runtime,
    /// A board time after the one the physics has reached.
    NotComputed,
    /// A scene that breaks no particular rule (syntax, types, keys).
    Scene,
    /// A speed at or above c.
    SpeedOfLight,
    /// Two pucks overlapping at board time 0.
    Overlap,
    /// A number outside what the engine holds.
    OutOfRange,
    /// A puck wider than its braking's Rindler horizon.
    BrakingHorizon,
}

impl ErrorKind {
    /// The Python exception's name (a builtin, or a `lightcone` class).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Value => "ValueError",
            Self::Key => "KeyError",
            Self::Type => "TypeError",
            Self::Runtime => "RuntimeError",
            Self::NotComputed => "NotComputedError",
            Self::Scene => "SceneError",
            Self::SpeedOfLight => "SpeedOfLightError",
            Self::Overlap => "OverlapError",
            Self::OutOfRange => "OutOfRangeError",
            Self::BrakingHorizon => "BrakingHorizonError",
        }
    }

    /// The kind of a scene error, by the rule it breaks (never by its
    /// text): `Scene` when it breaks none.
    #[must_use]
    pub fn of_rule(rule: Option<&BuildError>) -> Self {
        match rule.map(BuildError::rule) {
            Some(BuildError::TooFast { .. }) => Self::SpeedOfLight,
            Some(BuildError::Overlap { .. }) => Self::Overlap,
            Some(BuildError::OutOfRange { .. } | BuildError::TableSize(_)) => Self::OutOfRange,
            Some(BuildError::BeyondHorizon { .. }) => Self::BrakingHorizon,
            _ => Self::Scene,
        }
    }
}

/// A world operation's refusal: raised in the lesson as the exception
/// `kind` names, with `message`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WorldError {
    /// Which exception.
    pub kind: ErrorKind,
    /// What the lesson's traceback says.
    pub message: String,
}

impl WorldError {
    /// A `ValueError`.
    pub fn value(message: impl Into<String>) -> Self {
        Self::new(ErrorKind::Value, message)
    }

    /// An error of `kind`.
    pub fn new(kind: ErrorKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            message: message.into(),
        }
    }
}

impl std::fmt::Display for WorldError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.kind.name(), self.message)
    }
}

impl std::error::Error for WorldError {}

impl From<BuildError> for WorldError {
    fn from(e: BuildError) -> Self {
        Self::new(ErrorKind::of_rule(Some(&e)), e.to_string())
    }
}

impl From<SceneErrors> for WorldError {
    /// A file's errors take the kind of the first one that breaks a rule.
    fn from(e: SceneErrors) -> Self {
        let rule = e.0.iter().find_map(|e| e.rule.as_ref());
        Self::new(ErrorKind::of_rule(rule), e.to_string())
    }
}

/// What a world operation gives, or why it refused.
pub type WorldResult<T> = Result<T, WorldError>;
