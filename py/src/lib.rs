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

use glam::DVec3;
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, StateLine};
use lightcone_engine::scene::{Effect, Effects, Scene as SceneModel};
use pyo3::exceptions::{PyKeyError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pub use errors::{NoAdapterError, NotComputedError, SceneError, SpeedOfLightError};
pub use frame::Frame;
pub use scene::Scene;
pub use simulation::Simulation;
pub use world::{
    Bars, Claim, LessonGame, LessonUi, MAX_BINS, MAX_CHARTS, MAX_CLAIM_BYTES, MAX_CLAIMS, Pictures,
    Question, World, observe_claims,
};

/// Adds the module's classes to `m`: used by the wheel's `_lightcone` and
/// by the module the game embeds alike.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<Scene>()?;
    m.add_class::<Simulation>()?;
    m.add_class::<World>()?;
    m.add_class::<Frame>()?;
    errors::register(m)
}

/// The Lightcone engine from Python (`import lightcone`).
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
/// JSON object the command line prints.
fn to_record<'py, T: serde::Serialize>(
    py: Python<'py>,
    class: &str,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    let data = py.import("json")?.call_method1("loads", (text,))?;
    py.import("lightcone.records")?
        .getattr(class)?
        .call1((data,))
}

/// The effect called `key`, or a ValueError listing the valid names.
fn effect(key: &str) -> PyResult<Effect> {
    Effect::ALL
        .iter()
        .copied()
        .find(|e| e.key() == key)
        .ok_or_else(|| {
            let names: Vec<&str> = Effect::ALL.iter().map(|e| e.key()).collect();
            PyValueError::new_err(format!("unknown effect {key:?}; use one of {names:?}"))
        })
}

/// `None`: the scene's effects; a list: exactly those on.
fn effects_from(scene: Effects, list: Option<Vec<String>>) -> PyResult<Effects> {
    match list {
        None => Ok(scene),
        Some(list) => {
            let mut fx = Effects::NONE;
            for key in list {
                fx.set(effect(&key)?, true);
            }
            Ok(fx)
        }
    }
}

/// Index of puck `name`, or a KeyError listing the pucks.
fn puck_index(billiard: &Billiard, name: &str) -> PyResult<usize> {
    billiard.index_of(name).ok_or_else(|| {
        let names: Vec<&str> = (0..billiard.len()).map(|i| billiard.name(i)).collect();
        PyKeyError::new_err(format!("no puck named {name:?}; the scene has {names:?}"))
    })
}

/// Index of the observer called `name` (the first when `None`).
fn observer_index(scene: &SceneModel, name: Option<&str>) -> PyResult<usize> {
    match name {
        None => Ok(0),
        Some(name) => scene
            .observers
            .iter()
            .position(|o| o.name == name)
            .ok_or_else(|| {
                let names: Vec<&str> = scene.observers.iter().map(|o| o.name.as_str()).collect();
                PyKeyError::new_err(format!(
                    "no observer named {name:?}; the scene has {names:?}"
                ))
            }),
    }
}

/// A finite board time, or a ValueError.
fn finite_time(t: f64) -> PyResult<f64> {
    if t.is_finite() {
        Ok(t)
    } else {
        Err(PyValueError::new_err(format!(
            "t = {t}: give a finite board time"
        )))
    }
}

/// Every collision up to now, as `Collision` records (what `lightcone
/// simulate` prints).
fn collisions<'py>(py: Python<'py>, billiard: &Billiard) -> PyResult<Vec<Bound<'py, PyAny>>> {
    billiard
        .collisions()
        .iter()
        .map(|c| to_record(py, "Collision", &CollisionLine::new(billiard, c)))
        .collect()
}

/// Every puck at board time `t`: a `State` record (the `state` line of
/// `lightcone simulate`).
fn state<'py>(py: Python<'py>, billiard: &Billiard, t: f64) -> PyResult<Bound<'py, PyAny>> {
    to_record(py, "State", &StateLine::new(billiard, t))
}

/// `at` (default `now`) if the physics has reached it, else
/// NotComputedError.
fn past_time(at: Option<f64>, now: f64) -> PyResult<f64> {
    let t = finite_time(at.unwrap_or(now))?;
    if t > now + 1e-12 {
        return Err(NotComputedError::new_err(format!(
            "t = {t} s is after the board time reached ({now} s): the future is not computed yet"
        )));
    }
    Ok(t)
}

/// Strikes puck `name` at board time `t`: its proper velocity grows by `du`.
fn impulse(billiard: &mut Billiard, name: &str, t: f64, du: (f64, f64)) -> PyResult<()> {
    let i = puck_index(billiard, name)?;
    if !(du.0.is_finite() && du.1.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "impulse {du:?} on {name:?}: give finite numbers"
        )));
    }
    billiard
        .apply_impulse(i, t, DVec3::new(du.0, du.1, 0.0))
        .map_err(|e| PyValueError::new_err(e.to_string()))
}

/// The proper velocity γβ of puck `name` at board time `t`, as (x, y).
fn velocity(billiard: &Billiard, name: &str, t: f64) -> PyResult<(f64, f64)> {
    let i = puck_index(billiard, name)?;
    let u = billiard.worldline(i).proper_velocity_at(t);
    Ok((u.0.x, u.0.y))
}

/// What observer `observer` sees at board time `t`, as the dict
/// `lightcone observe` prints.
fn observation<'py>(
    py: Python<'py>,
    scene: &SceneModel,
    billiard: &Billiard,
    t: f64,
    observer: Option<&str>,
    vertices: bool,
    effects: Effects,
) -> PyResult<Bound<'py, PyAny>> {
    let index = observer_index(scene, observer)?;
    let report = lightcone_render::observe::report(scene, billiard, index, t, effects, vertices)
        .ok_or_else(|| PyRuntimeError::new_err(format!("observer {index} saw nothing")))?;
    to_record(py, "Observation", &report)
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
    scene: &SceneModel,
    billiard: &Billiard,
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
    let index = observer_index(scene, observer)?;
    quiet_runtime_dir(py)?;
    let image = py.detach(|| {
        let gpu = gpu().map_err(NoAdapterError::new_err)?;
        lightcone_render::headless::render_billiard(
            gpu, scene, billiard, t, index, kind, size.0, size.1,
        )
        .map_err(PyRuntimeError::new_err)
    })?;
    Frame::from_image(&image, t)
}
