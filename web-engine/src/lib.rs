//! The engine in the browser's lesson worker (`web/static/lesson_worker.js`):
//! the Python stand-ins of `lightcone.Scene` and `lightcone.Simulation`
//! (`web/python/_lightcone.py`) call `lightcone_call` (below), which answers with
//! the same operations as the desktop's pyo3 classes
//! (`lightcone_lesson::standin`). `scripts/web.sh` builds it with
//! wasm-bindgen into `web/dist/lightcone_engine_web.js`. On native targets
//! it is empty.
#![cfg(target_arch = "wasm32")]

use std::cell::RefCell;

use wasm_bindgen::prelude::*;

thread_local! {
    /// The simulations the worker's lesson holds.
    static OBJECTS: RefCell<lightcone_lesson::standin::Objects> = RefCell::default();
}

/// Answers one JSON request of the stand-ins (the format:
/// `lightcone_lesson::standin`), as JSON text.
#[wasm_bindgen]
pub fn lightcone_call(request: &str) -> String {
    OBJECTS.with(|o| o.borrow_mut().call(request))
}
