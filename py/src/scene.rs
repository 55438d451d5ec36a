//! `lightcone.Scene`: a validated scene, loaded or built in code.

use lightcone_engine::scene::{self, Effect};
use lightcone_lesson::scene_code;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::convert::{Vector, optional};
use super::effect;
use super::errors::{ScenePyErr, world_err};

/// A validated scene (see the guide, docs/guide/src/scenes.md).
#[pyclass(module = "lightcone._lightcone")]
#[derive(Clone)]
pub struct Scene {
    pub(crate) inner: scene::Scene,
}

#[pymethods]
impl Scene {
    /// Reads and validates a scene file. Raises SceneError naming the
    /// file, line and field of every problem.
    #[staticmethod]
    fn load(path: std::path::PathBuf) -> PyResult<Self> {
        Ok(Self {
            inner: scene::load(&path).map_err(ScenePyErr::from)?,
        })
    }

    /// Parses and validates scene TOML text; `name` is used in messages.
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>"))]
    fn from_toml(text: &str, name: &str) -> PyResult<Self> {
        Ok(Self {
            inner: scene::parse(text, name).map_err(ScenePyErr::from)?,
        })
    }

    /// An empty scene on a table of `size` = (x, y) metres (default: a
    /// match carom table) with speed of light `c` m/s (default: light
    /// crosses the long side in 2 s), sliding `friction` μ (default 0:
    /// frictionless; a carom cloth is about 0.2) under `gravity` m/s², as a
    /// scene file's `[table] friction` and `gravity`; `description`: the
    /// text shown under the title when the scene opens, as a scene file's
    /// `description`. Raises SceneError for a value out of range.
    #[new]
    #[pyo3(signature = (size = Vector([2.84, 1.42]), c = None, title = "scene", friction = 0.0, gravity = 9.80665, description = ""))]
    fn new(
        size: Vector<2>,
        c: Option<f64>,
        title: &str,
        friction: f64,
        gravity: f64,
        description: &str,
    ) -> PyResult<Self> {
        let inner = scene_code::new(size.pair(), c, title, friction, gravity, description)
            .map_err(world_err)?;
        Ok(Self { inner })
    }

    /// Sliding friction μ of the table (0: frictionless). Setting it
    /// checks it as the constructor does (and that every puck can brake
    /// rigidly, see the guide, docs/guide/src/friction.md); raises SceneError.
    #[getter]
    fn friction(&self) -> f64 {
        self.inner.table.friction
    }

    #[setter]
    fn set_friction(&mut self, friction: f64) -> PyResult<()> {
        let gravity = self.inner.table.gravity;
        Ok(self
            .inner
            .set_friction(friction, gravity)
            .map_err(ScenePyErr::from)?)
    }

    /// Gravity under the table, m/s² (with `friction`, the braking
    /// deceleration μg).
    #[getter]
    fn gravity(&self) -> f64 {
        self.inner.table.gravity
    }

    #[setter]
    fn set_gravity(&mut self, gravity: f64) -> PyResult<()> {
        let friction = self.inner.table.friction;
        Ok(self
            .inner
            .set_friction(friction, gravity)
            .map_err(ScenePyErr::from)?)
    }

    /// Adds a puck centred at `position` (x, y) m at board time 0; give at
    /// most one of `beta` (v/c), `velocity` (m/s) or `u` (proper velocity
    /// γβ), each any two numbers (tuple, list, array); `radius`, `height`
    /// in m, `mass` in kg. Raises SpeedOfLightError for a speed ≥ c,
    /// OverlapError, OutOfRangeError, BrakingHorizonError, and SceneError
    /// for anything else invalid (off the table, duplicate or padded
    /// name …): the class by the rule broken (`errors::ScenePyErr`).
    #[pyo3(signature = (name, position, beta = None, u = None, radius = 0.0305, height = 0.02, mass = 0.21, color = None, velocity = None))]
    #[allow(clippy::too_many_arguments)]
    fn add_puck(
        &mut self,
        name: &str,
        position: Vector<2>,
        beta: Option<&Bound<'_, PyAny>>,
        u: Option<&Bound<'_, PyAny>>,
        radius: f64,
        height: f64,
        mass: f64,
        color: Option<&str>,
        velocity: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let pair = |v: Option<Vector<2>>| v.map(Vector::pair);
        let args = scene_code::PuckArgs {
            name,
            position: position.pair(),
            beta: pair(optional::<2>("beta", beta)?),
            u: pair(optional::<2>("u", u)?),
            radius,
            height,
            mass,
            color,
            velocity: pair(optional::<2>("velocity", velocity)?),
        };
        scene_code::add_puck(&mut self.inner, &args).map_err(world_err)
    }

    /// Adds an observer with its eye at `position` (x, y, z) m, looking at
    /// `look_at` with a 60° field (default: none, its views framed to show
    /// the whole table), moving at `beta` (v/c, three numbers); the first
    /// observer replaces the default eye.
    #[pyo3(signature = (name, position, look_at = None, beta = None))]
    fn add_observer(
        &mut self,
        name: &str,
        position: Vector<3>,
        look_at: Option<&Bound<'_, PyAny>>,
        beta: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let look_at = optional::<3>("look_at", look_at)?.map(|v| v.0);
        let beta = optional::<3>("beta", beta)?.map(|v| v.0);
        scene_code::add_observer(&mut self.inner, name, position.0, look_at, beta)
            .map_err(world_err)
    }

    /// Turns an effect on or off (`contraction`, `light_delay`,
    /// `aberration`, `doppler`, `searchlight`, `time_dilation`).
    fn set_effect(&mut self, name: &str, on: bool) -> PyResult<()> {
        self.inner.effects.set(effect(name)?, on);
        Ok(())
    }

    /// Speed of light, m/s.
    #[getter]
    fn c(&self) -> f64 {
        self.inner.c
    }

    /// Sets the speed of light, m/s: from 1e-6 to 1e9, as in a scene file,
    /// each puck and observer keeping its proper velocity in m/s (`γ v`,
    /// its momentum per unit mass), so a large c is Newton's scene (the
    /// engine's `Scene::with_c`, as the game's c slider). On a table with
    /// friction, c must be fast enough that every puck fits inside the
    /// braking's Rindler horizon c²/(μg). `SceneError` otherwise, naming
    /// `Scene.c`; the scene is unchanged.
    #[setter]
    fn set_c(&mut self, c: f64) -> PyResult<()> {
        scene_code::set_c(&mut self.inner, c).map_err(world_err)
    }

    /// Scene title.
    #[getter]
    fn title(&self) -> String {
        self.inner.title.clone()
    }

    /// The scene's description (shown under its title when it opens).
    #[getter]
    fn description(&self) -> String {
        self.inner.description.clone()
    }

    /// Puck names, in file order.
    #[getter]
    fn pucks(&self) -> Vec<String> {
        scene_code::pucks(&self.inner)
    }

    /// Observer names, in file order.
    #[getter]
    fn observers(&self) -> Vec<String> {
        scene_code::observers(&self.inner)
    }

    /// The effects as a dict of flags.
    #[getter]
    fn effects<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for e in Effect::ALL {
            d.set_item(e.key(), self.inner.effects.is_on(e))?;
        }
        Ok(d)
    }

    /// The scene as JSON (the engine's serde form): how a lesson run in
    /// its own process sends `world.start(scene)` to the game.
    fn _to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.inner)
            .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
    }

    /// The scene [`Self::_to_json`] wrote, checked again as a scene built
    /// in code is (`SceneError` otherwise): the game does not trust what a
    /// lesson's process sends.
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<Self> {
        let inner =
            lightcone_lesson::protocol::scene_from_json(text).map_err(super::errors::world_err)?;
        Ok(Self { inner })
    }

    fn __repr__(&self) -> String {
        scene_code::describe(&self.inner)
    }
}
