//! The embedded `lightcone` module (the wheel's classes, from
//! `lightcone-py`), and how the game lends itself to a lesson's `World`
//! (`crate::lesson_game`, on every target: the browser lends it too).

use pyo3::prelude::*;

pub use crate::lesson_game::{new_game, taken_back};

/// The module as the game embeds it (registered with `append_to_inittab`
/// before the interpreter starts). Its own name keeps its `PyInit_` symbol
/// apart from the wheel's; the lesson host installs it as
/// `lightcone._lightcone`.
#[pymodule]
pub fn lightcone_embedded(m: &Bound<'_, PyModule>) -> PyResult<()> {
    lightcone_python::register(m)
}
