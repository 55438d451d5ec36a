//! `import lightcone`: the wheel's extension module. The classes live in the
//! game crate ([`lightcone::python`]) so that the game's embedded lesson
//! host offers exactly the same module.

use pyo3::prelude::*;

/// The Lightcone engine from Python.
#[pymodule]
fn _lightcone(m: &Bound<'_, PyModule>) -> PyResult<()> {
    lightcone::python::register(m)
}
