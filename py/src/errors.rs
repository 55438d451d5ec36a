//! Every exception the `lightcone` module raises beyond Python's own, in
//! one place, one class per kind of error. Each is a subclass of the
//! built-in exception an older caller may already catch.

use lightcone_engine::scene::{BuildError, SceneErrors};
use lightcone_lesson::{ErrorKind, WorldError};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    _lightcone,
    SceneError,
    PyValueError,
    "A scene file, text or element is invalid; the message names the file, line and field (or the puck or observer)."
);

pyo3::create_exception!(
    _lightcone,
    SpeedOfLightError,
    SceneError,
    "A speed at or above the speed of light c was given (β = v/c ≥ 1); no body reaches c."
);

pyo3::create_exception!(
    _lightcone,
    OverlapError,
    SceneError,
    "Two pucks overlap at board time 0 (their rest-frame discs; touching is allowed)."
);

pyo3::create_exception!(
    _lightcone,
    OutOfRangeError,
    SceneError,
    "A number lies outside what the engine holds (the guide, docs/guide/src/scenes.md, \"What the engine holds\"): a length, mass, c, friction, gravity, restitution or |u|."
);

pyo3::create_exception!(
    _lightcone,
    BrakingHorizonError,
    SceneError,
    "A puck cannot brake rigidly on the cloth: its radius reaches the braking's Rindler horizon c²/(μg)."
);

pyo3::create_exception!(
    _lightcone,
    NoAdapterError,
    PyRuntimeError,
    "Rendering needs a graphics adapter and none was found (install Mesa's lavapipe: mesa-vulkan-drivers)."
);

pyo3::create_exception!(
    _lightcone,
    NotComputedError,
    PyValueError,
    "A board time after the one the physics has reached was asked for: run the simulation to it first."
);

/// Adds the exception classes to `m`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SpeedOfLightError", py.get_type::<SpeedOfLightError>())?;
    m.add("OverlapError", py.get_type::<OverlapError>())?;
    m.add("OutOfRangeError", py.get_type::<OutOfRangeError>())?;
    m.add("BrakingHorizonError", py.get_type::<BrakingHorizonError>())?;
    m.add("NoAdapterError", py.get_type::<NoAdapterError>())?;
    m.add("NotComputedError", py.get_type::<NotComputedError>())?;
    Ok(())
}

/// A scene the engine refused, on its way to Python: a broken rule
/// ([`BuildError`], from a scene built in code) or a scene file's located
/// errors ([`SceneErrors`]). `From<BuildError> for PyErr` itself is out of
/// reach (the orphan rule: neither type is this crate's), so this is the
/// bridge, as polars' `PyPolarsErr` is: `.map_err(ScenePyErr::from)?`.
pub enum ScenePyErr {
    /// A rule broken by a scene built in code.
    Rule(BuildError),
    /// Every located problem of a scene file or text.
    File(SceneErrors),
}

impl From<BuildError> for ScenePyErr {
    fn from(e: BuildError) -> Self {
        Self::Rule(e)
    }
}

impl From<SceneErrors> for ScenePyErr {
    fn from(e: SceneErrors) -> Self {
        Self::File(e)
    }
}

/// The exception of class `kind` with `message`.
fn raise_kind(kind: ErrorKind, message: String) -> PyErr {
    match kind {
        ErrorKind::Value => PyValueError::new_err(message),
        ErrorKind::Key => pyo3::exceptions::PyKeyError::new_err(message),
        ErrorKind::Type => pyo3::exceptions::PyTypeError::new_err(message),
        ErrorKind::Runtime => PyRuntimeError::new_err(message),
        ErrorKind::NotComputed => NotComputedError::new_err(message),
        ErrorKind::Scene => SceneError::new_err(message),
        ErrorKind::SpeedOfLight => SpeedOfLightError::new_err(message),
        ErrorKind::Overlap => OverlapError::new_err(message),
        ErrorKind::OutOfRange => OutOfRangeError::new_err(message),
        ErrorKind::BrakingHorizon => BrakingHorizonError::new_err(message),
    }
}

/// A world operation's refusal as the Python exception its kind names.
pub fn world_err(e: WorldError) -> PyErr {
    raise_kind(e.kind, e.message)
}

impl From<ScenePyErr> for PyErr {
    /// A file's errors take the class of the first one that breaks a rule
    /// (`SceneError` when none does: syntax, types, unknown keys); every
    /// class is a `SceneError`.
    fn from(e: ScenePyErr) -> Self {
        match e {
            ScenePyErr::Rule(rule) => world_err(rule.into()),
            ScenePyErr::File(errors) => world_err(errors.into()),
        }
    }
}
