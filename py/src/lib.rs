//! `import lightcone`: thin Python wrappers over the engine. All physics
//! lives in `lightcone-engine`; these classes only convert arguments and
//! results (collision and observation records as the same dictionaries
//! that `lightcone simulate` and `lightcone observe` print as JSON).
//!
//! This crate (`lightcone-py`) is the wheel's extension module
//! (`lightcone._lightcone`, built with maturin) and depends on the engine
//! and the renderer only. The game depends on it and embeds the same
//! classes for its lessons ([`register`]): one set of classes, two ways in.
//! The game lends its running state to a lesson's [`World`] through
//! [`LessonGame`].

mod convert;
mod diagram;
pub mod errors;
mod frame;
mod scene;
mod simulation;
mod world;

use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, StateLine};
use lightcone_engine::scene::{Effect, Effects};
use lightcone_lesson::query;
use lightcone_lesson::simulation::SimulationCore;
use pyo3::exceptions::{PyRuntimeError, PyValueError};

use errors::world_err;
use pyo3::prelude::*;

pub use errors::{NoAdapterError, NotComputedError, SceneError, SpeedOfLightError};
pub use frame::Frame;
pub use lightcone_lesson::{
    Bars, Claim, LessonGame, LessonUi, MAX_BINS, MAX_CHARTS, MAX_CLAIM_BYTES, MAX_CLAIMS, Pictures,
    Question,
};
pub use scene::Scene;
pub use simulation::Simulation;
pub use world::{World, observe_claims};

/// Adds the module's classes to `m`: used by the wheel's `_lightcone` and
/// by the module the game embeds alike.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Scene>()?;
    m.add_class::<Simulation>()?;
    m.add_class::<World>()?;
    m.add_class::<Frame>()?;
    m.add_function(wrap_pyfunction!(standin_call, m)?)?;
    errors::register(m)
}

/// The Lightcone engine from Python (`import lightcone`).
/// The browser's `Scene` and `Simulation` stand-ins' one call
/// (`lightcone_lesson::standin`), here too, so that the stand-ins
/// (web/python/_lightcone.py) are tested against this module's classes
/// on the desktop. Not part of the module's API.
#[pyfunction]
#[pyo3(name = "_standin_call")]
fn standin_call(request: &str) -> String {
    static OBJECTS: std::sync::Mutex<Option<lightcone_lesson::standin::Objects>> =
        std::sync::Mutex::new(None);
    let mut objects = OBJECTS.lock().unwrap_or_else(|e| e.into_inner());
    objects.get_or_insert_with(Default::default).call(request)
}

#[pymodule]
fn _lightcone(m: &Bound<'_, PyModule>) -> PyResult<()> {
    register(m)
}

/// numpy, imported for `what` (numpy is optional: only the calls that
/// return arrays need it), or an `ImportError` saying so.
fn numpy<'py>(py: Python<'py>, what: &str) -> PyResult<Bound<'py, PyModule>> {
    py.import("numpy").map_err(|e| {
        pyo3::exceptions::PyImportError::new_err(format!(
            "{what} returns a numpy array and needs numpy: pip install numpy ({})",
            e.value(py)
        ))
    })
}

/// `rows` as a numpy array of shape (len, N), dtype float64.
fn array<'py, const N: usize>(
    py: Python<'py>,
    what: &str,
    rows: Vec<[f64; N]>,
) -> PyResult<Bound<'py, PyAny>> {
    let numpy = numpy(py, what)?;
    let n = rows.len();
    numpy
        .call_method1("array", (rows, "float64"))?
        .call_method1("reshape", (n, N))
}

/// Turns a serialisable report into the record class `class` of
/// `lightcone.records` (`Collision`, `State`, `Observation`), built from the
/// JSON object the command line prints (through its `serde_json` value, no
/// JSON text). Also what the
/// game's in-process lesson host gives `on_collision`.
///
/// # Errors
/// A value that does not serialize (a map with non-string keys), or a
/// record class that cannot be built from it.
pub fn to_record<'py, T: serde::Serialize>(
    py: Python<'py>,
    class: &str,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let data = to_plain(py, value)?;
    py.import("lightcone.records")?
        .getattr(class)?
        .call1((data,))
}

/// A serialisable value as plain Python data (dicts, lists, numbers,
/// strings, `None`): what the command line's JSON of it reads as in
/// Python. Through `serde_json::Value`, so that it is that JSON's data
/// exactly (fixed-size arrays as lists, not tuples; a non-finite number as
/// `None`, as JSON writes it), then `pythonize` (no JSON text is written
/// or parsed). For the records' types (f64, u64, strings) this is exactly
/// what `json.loads` of the printed text gives; an f32 field would show
/// its binary value's digits (0.10000000149011612), and a u128 beyond
/// u64 would not convert.
fn to_plain<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let json = serde_json::to_value(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    pythonize::pythonize(py, &json).map_err(|e| PyValueError::new_err(e.to_string()))
}

fn effect(key: &str) -> PyResult<Effect> {
    query::effect(key).map_err(world_err)
}

fn effects_from(shown: Effects, list: Option<Vec<String>>) -> PyResult<Effects> {
    query::effects_from(shown, list).map_err(world_err)
}

fn finite_time(t: f64) -> PyResult<f64> {
    query::finite_time(t).map_err(world_err)
}

fn collisions<'py>(py: Python<'py>, billiard: &Billiard) -> PyResult<Vec<Bound<'py, PyAny>>> {
    billiard
        .collisions()
        .iter()
        .map(|c| to_record(py, "Collision", &CollisionLine::new(billiard, c)))
        .collect()
}

fn state<'py>(py: Python<'py>, billiard: &Billiard, t: f64) -> PyResult<Bound<'py, PyAny>> {
    to_record(py, "State", &StateLine::new(billiard, t))
}

fn past_time(at: Option<f64>, now: f64) -> PyResult<f64> {
    query::past_time(at, now).map_err(world_err)
}

fn impulse(billiard: &mut Billiard, name: &str, t: f64, du: (f64, f64)) -> PyResult<()> {
    query::impulse(billiard, name, t, du).map_err(world_err)
}

fn velocity(billiard: &Billiard, name: &str, t: f64) -> PyResult<(f64, f64)> {
    query::velocity(billiard, name, t).map_err(world_err)
}

/// Before the first graphics device opens: gives Mesa's device-select layer
/// a private `XDG_RUNTIME_DIR` when the environment has no valid one
/// ([`lightcone_render::gpu::private_runtime_dir`]), so rendering prints no
/// libwayland `XDG_RUNTIME_DIR is invalid` warning, as the `lightcone`
/// command does. Set through Python's `os.environ`, holding the GIL, as any
/// Python code sets a variable: `os.environ` and the process environment
/// (and so child processes) agree.
fn quiet_runtime_dir(py: Python<'_>) -> PyResult<()> {
    use std::sync::atomic::{AtomicBool, Ordering};
    static DONE: AtomicBool = AtomicBool::new(false);
    if DONE.swap(true, Ordering::Relaxed) {
        return Ok(());
    }
    if let Some(dir) = lightcone_render::gpu::private_runtime_dir()
        && let Some(dir) = dir.to_str()
    {
        py.import("os")?
            .getattr("environ")?
            .set_item("XDG_RUNTIME_DIR", dir)?;
    }
    Ok(())
}

/// The headless graphics device, opened once per process.
fn gpu() -> Result<&'static lightcone_render::gpu::Gpu, String> {
    static GPU: std::sync::OnceLock<Result<lightcone_render::gpu::Gpu, String>> =
        std::sync::OnceLock::new();
    GPU.get_or_init(lightcone_render::gpu::headless)
        .as_ref()
        .map_err(Clone::clone)
}

/// Renders what `observer` sees at board time `t`, headless.
fn render_frame(
    py: Python<'_>,
    core: &mut SimulationCore,
    t: f64,
    observer: Option<&str>,
    size: (u32, u32),
    view: &str,
) -> PyResult<Frame> {
    use lightcone_render::frame::ViewKind;
    let kind = match view {
        "seen" => ViewKind::Seen,
        "truth" => ViewKind::Truth,
        other => {
            return Err(PyValueError::new_err(format!(
                "view {other:?}: use \"seen\" or \"truth\""
            )));
        }
    };
    if size.0 == 0 || size.1 == 0 || size.0 > 16384 || size.1 > 16384 {
        return Err(PyValueError::new_err(format!(
            "size {size:?}: 1 to 16384 pixels a side"
        )));
    }
    let aspect = f64::from(size.0) / f64::from(size.1);
    // The observer is checked before the graphics device, as before.
    query::observer_index(core.scene(), observer).map_err(world_err)?;
    quiet_runtime_dir(py)?;
    let image = py.detach(|| {
        let gpu = gpu().map_err(NoAdapterError::new_err)?;
        // The frame itself runs without the GIL, after the device is found.
        let (sim, view) = core.picture(observer, t, kind, aspect).map_err(world_err)?;
        lightcone_render::headless::render_view(gpu, sim, view, size.0, size.1)
            .map_err(PyRuntimeError::new_err)
    })?;
    Frame::from_image(&image, t)
}
