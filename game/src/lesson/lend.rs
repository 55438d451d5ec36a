//! The embedded `lightcone` module (the wheel's classes, from
//! `lightcone-py`). How a lesson's world reaches the game is
//! `crate::lesson_game` (on every target: the browser's too).

use pyo3::prelude::*;

/// The module as the game embeds it (registered with `append_to_inittab`
/// before the interpreter starts). Its own name keeps its `PyInit_` symbol
/// apart from the wheel's; the lesson host installs it as
/// `lightcone._lightcone`.
#[pymodule]
pub fn lightcone_embedded(m: &Bound<'_, PyModule>) -> PyResult<()> {
    lightcone_python::register(m)
}
