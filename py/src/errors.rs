//! Every exception the `lightcone` module raises beyond Python's own, in
//! one place, one class per kind of error. Each is a subclass of the
//! built-in exception an older caller may already catch.

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
    m.add("NoAdapterError", py.get_type::<NoAdapterError>())?;
    m.add("NotComputedError", py.get_type::<NotComputedError>())?;
    Ok(())
}

/// A scene error: [`SpeedOfLightError`] when the engine's message is about
/// a speed at or above c, else [`SceneError`].
pub fn scene_error(message: impl Into<String>) -> PyErr {
    let message = message.into();
    if message.contains("not below the speed of light") {
        SpeedOfLightError::new_err(message)
    } else {
        SceneError::new_err(message)
    }
}
