//! `import lightcone`: thin Python wrappers over the engine. All physics
//! lives in `lightcone-engine`; these classes only convert arguments and
//! results (collision and observation records as the same dictionaries
//! that `lightcone simulate` and `lightcone observe` print as JSON).

use std::path::PathBuf;

use glam::DVec3;
use lightcone_engine::optics::mesh;
use lightcone_engine::optics::view::{Method, observe};
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, ObserveReport, StateLine};
use lightcone_engine::scene::{self, Effect};
use lightcone_engine::spacetime::ProperVelocity;
use lightcone_engine::world::PUCK_SEGMENTS;
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

pyo3::create_exception!(
    _lightcone,
    SceneError,
    PyValueError,
    "A scene file or text is invalid; the message names the file, line and field."
);

/// Turns a serialisable report into Python objects via JSON (the same
/// shapes the command line prints).
fn to_python<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A validated scene (see the README's "Scene files").
#[pyclass(module = "lightcone._lightcone")]
#[derive(Clone)]
pub struct Scene {
    inner: scene::Scene,
}

#[pymethods]
impl Scene {
    /// Reads and validates a scene file. Raises SceneError naming the
    /// file, line and field of every problem.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        scene::load(&path)
            .map(|inner| Self { inner })
            .map_err(|e| SceneError::new_err(e.to_string()))
    }

    /// Parses and validates scene TOML text; `name` is used in messages.
    #[staticmethod]
    #[pyo3(signature = (text, name = "<string>"))]
    fn from_toml(text: &str, name: &str) -> PyResult<Self> {
        scene::parse(text, name)
            .map(|inner| Self { inner })
            .map_err(|e| SceneError::new_err(e.to_string()))
    }

    /// An empty scene on a table of `size` metres (default: a match carom
    /// table) with speed of light `c` (default: light crosses the long side
    /// in 2 s).
    #[new]
    #[pyo3(signature = (size = (2.84, 1.42), c = None, title = "scene"))]
    fn new(size: (f64, f64), c: Option<f64>, title: &str) -> PyResult<Self> {
        let mut inner = scene::Scene::empty(glam::DVec2::new(size.0, size.1), c)
            .map_err(SceneError::new_err)?;
        inner.title = title.to_owned();
        Ok(Self { inner })
    }

    /// Adds a puck; give at most one of `beta` (v/c) or `u` (γβ). Raises
    /// SceneError if it would be invalid (speed ≥ c, off the table,
    /// overlapping, duplicate name …).
    #[pyo3(signature = (name, position, beta = None, u = None, radius = 0.0305, height = 0.02, mass = 0.21, color = None))]
    #[allow(clippy::too_many_arguments)]
    fn add_puck(
        &mut self,
        name: &str,
        position: (f64, f64),
        beta: Option<(f64, f64)>,
        u: Option<(f64, f64)>,
        radius: f64,
        height: f64,
        mass: f64,
        color: Option<&str>,
    ) -> PyResult<()> {
        let u = match (beta, u) {
            (Some(_), Some(_)) => {
                return Err(SceneError::new_err("give at most one of beta and u"));
            }
            (Some(b), None) => ProperVelocity::try_from_beta(DVec3::new(b.0, b.1, 0.0))
                .map_err(|e| SceneError::new_err(format!("puck {name:?}: {e}")))?,
            (None, Some(u)) => ProperVelocity(DVec3::new(u.0, u.1, 0.0)),
            (None, None) => ProperVelocity::ZERO,
        };
        let color = match color {
            None => scene::Color::default_for(self.inner.pucks.len()),
            Some(c) => scene::Color::parse(c).ok_or_else(|| {
                SceneError::new_err(format!("{c:?} is not a colour: use \"#rrggbb\" or a name"))
            })?,
        };
        self.inner
            .add_puck(scene::PuckSpec {
                name: name.to_owned(),
                position: glam::DVec2::new(position.0, position.1),
                u,
                radius,
                height,
                mass,
                color,
            })
            .map_err(SceneError::new_err)
    }

    /// Adds an observer (the first replaces the default eye).
    #[pyo3(signature = (name, position, look_at = None, beta = None))]
    fn add_observer(
        &mut self,
        name: &str,
        position: (f64, f64, f64),
        look_at: Option<(f64, f64, f64)>,
        beta: Option<(f64, f64, f64)>,
    ) -> PyResult<()> {
        let size = self.inner.table.size;
        let look_at = look_at.map_or(DVec3::new(size.x / 2.0, size.y / 2.0, 0.0), DVec3::from);
        let u = match beta {
            None => ProperVelocity::ZERO,
            Some(b) => ProperVelocity::try_from_beta(DVec3::from(b))
                .map_err(|e| SceneError::new_err(format!("observer {name:?}: {e}")))?,
        };
        self.inner
            .add_observer(scene::ObserverSpec {
                name: name.to_owned(),
                position: DVec3::from(position),
                look_at,
                u,
            })
            .map_err(SceneError::new_err)
    }

    /// Turns an effect on or off (`contraction`, `light_delay`,
    /// `aberration`, `doppler`, `searchlight`, `time_dilation`).
    fn set_effect(&mut self, name: &str, on: bool) -> PyResult<()> {
        let e = Effect::ALL
            .iter()
            .find(|e| e.key() == name)
            .ok_or_else(|| PyValueError::new_err(format!("unknown effect {name:?}")))?;
        self.inner.effects.set(*e, on);
        Ok(())
    }

    /// Speed of light, m/s.
    #[getter]
    fn c(&self) -> f64 {
        self.inner.c
    }

    /// Sets the speed of light, m/s (positive and finite).
    #[setter]
    fn set_c(&mut self, c: f64) -> PyResult<()> {
        if !(c.is_finite() && c > 0.0) {
            return Err(SceneError::new_err(format!(
                "c = {c} must be a positive finite number of m/s"
            )));
        }
        self.inner.c = c;
        Ok(())
    }

    /// Scene title.
    #[getter]
    fn title(&self) -> String {
        self.inner.title.clone()
    }

    /// Puck names, in file order.
    #[getter]
    fn pucks(&self) -> Vec<String> {
        self.inner.pucks.iter().map(|p| p.name.clone()).collect()
    }

    /// Observer names, in file order.
    #[getter]
    fn observers(&self) -> Vec<String> {
        self.inner
            .observers
            .iter()
            .map(|o| o.name.clone())
            .collect()
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

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, {} pucks, c = {} m/s)",
            self.inner.title,
            self.inner.pucks.len(),
            self.inner.c
        )
    }
}

/// A running simulation of a scene: the event-anticipation physics.
#[pyclass(module = "lightcone._lightcone")]
pub struct Simulation {
    scene: scene::Scene,
    billiard: Billiard,
}

impl Simulation {
    fn puck(&self, name: &str) -> PyResult<usize> {
        self.billiard.index_of(name).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "no puck named {name:?}; the scene has {:?}",
                self.names()
            ))
        })
    }

    /// Index of the observer called `name` (the first when `None`).
    fn observer_index(&self, name: Option<&str>) -> PyResult<usize> {
        match name {
            None => Ok(0),
            Some(name) => self
                .scene
                .observers
                .iter()
                .position(|o| o.name == name)
                .ok_or_else(|| PyKeyError::new_err(format!("no observer named {name:?}"))),
        }
    }

    fn names(&self) -> Vec<String> {
        (0..self.billiard.len())
            .map(|i| self.billiard.name(i).to_owned())
            .collect()
    }
}

#[pymethods]
impl Simulation {
    #[new]
    fn new(scene: &Scene) -> Self {
        Self {
            billiard: Billiard::from_scene(&scene.inner),
            scene: scene.inner.clone(),
        }
    }

    /// Board time reached, s.
    #[getter]
    fn time(&self) -> f64 {
        self.billiard.time()
    }

    /// Runs the physics to board time `t` (s); earlier times do nothing.
    /// Releases the GIL while it runs.
    fn run_until(&mut self, py: Python<'_>, t: f64) -> PyResult<()> {
        if !t.is_finite() {
            return Err(PyValueError::new_err(format!(
                "t = {t}: give a finite board time"
            )));
        }
        let billiard = &mut self.billiard;
        py.detach(|| billiard.advance_to(t));
        Ok(())
    }

    /// Advances by `dt` seconds of board time.
    fn step(&mut self, py: Python<'_>, dt: f64) -> PyResult<()> {
        let t = self.billiard.time() + dt;
        self.run_until(py, t)
    }

    /// Strikes puck `name` now: its proper velocity γβ grows by `du` (a
    /// pair (x, y)); no push reaches c.
    fn impulse(&mut self, name: &str, du: (f64, f64)) -> PyResult<()> {
        let i = self.puck(name)?;
        let t = self.billiard.time();
        self.billiard
            .apply_impulse(i, t, DVec3::new(du.0, du.1, 0.0))
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    /// Every collision so far, as the dicts `lightcone simulate` prints.
    fn collisions<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        self.billiard
            .collisions()
            .iter()
            .map(|c| to_python(py, &CollisionLine::new(&self.billiard, c)))
            .collect()
    }

    /// Every puck now: the `state` dict of `lightcone simulate`.
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &StateLine::new(&self.billiard, self.billiard.time()))
    }

    /// What observer `observer` (default: the first) sees now, as the dict
    /// `lightcone observe` prints. `effects`: None for the scene's, or a
    /// list of effect names to turn on (the others off).
    #[pyo3(signature = (observer = None, vertices = false, effects = None))]
    fn observe<'py>(
        &self,
        py: Python<'py>,
        observer: Option<&str>,
        vertices: bool,
        effects: Option<Vec<String>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let index = self.observer_index(observer)?;
        let fx = match effects {
            None => self.scene.effects,
            Some(list) => {
                let mut fx = lightcone_engine::scene::Effects::NONE;
                for key in list {
                    let e = Effect::ALL
                        .iter()
                        .find(|e| e.key() == key)
                        .ok_or_else(|| PyValueError::new_err(format!("unknown effect {key:?}")))?;
                    fx.set(*e, true);
                }
                fx
            }
        };
        let spec = &self.scene.observers[index];
        let t = self.billiard.time();
        let (eye, _) = lightcone::render::frame::eye_of(&self.scene, index, t);
        let shapes: Vec<_> = self
            .scene
            .pucks
            .iter()
            .map(|p| mesh::puck(p.radius, p.height, PUCK_SEGMENTS))
            .collect();
        let heights: Vec<f64> = self.scene.pucks.iter().map(|p| p.height).collect();
        let view = observe(
            &self.billiard,
            &shapes,
            &heights,
            eye,
            fx,
            Method::Exact,
            vertices,
        );
        let report = ObserveReport::new(
            &self.billiard,
            &view,
            &spec.name,
            t / spec.u.gamma(),
            vertices,
        );
        to_python(py, &report)
    }

    /// The proper velocity γβ of puck `name` now, as (x, y).
    fn velocity(&self, name: &str) -> PyResult<(f64, f64)> {
        let i = self.puck(name)?;
        let u: ProperVelocity = self.billiard.worldline(i).velocity_at(self.billiard.time());
        Ok((u.0.x, u.0.y))
    }

    /// Renders what `observer` (default: the first) sees now to a PNG,
    /// headless; `view` is "seen" or "truth". Raises RuntimeError when
    /// there is no graphics adapter (install mesa-vulkan-drivers).
    #[pyo3(signature = (path, observer = None, size = (1280, 720), view = "seen"))]
    fn render(
        &self,
        py: Python<'_>,
        path: PathBuf,
        observer: Option<&str>,
        size: (u32, u32),
        view: &str,
    ) -> PyResult<()> {
        use lightcone::render::frame::{self, SceneMeshes, ViewKind};
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
        let index = self.observer_index(observer)?;
        let t = self.billiard.time();
        let (scene, billiard) = (&self.scene, &self.billiard);
        py.detach(|| {
            let gpu = lightcone::render::gpu::headless()?;
            let meshes = SceneMeshes::new(scene);
            let (eye, camera) = frame::eye_of(scene, index, t);
            let mut vertices = Vec::new();
            frame::build(
                billiard,
                &meshes,
                &eye,
                kind.effects(scene.effects),
                &mut vertices,
            );
            lightcone::render::headless::draw(&gpu, &vertices, &camera, size.0, size.1)?
                .save_png(&path)
        })
        .map_err(pyo3::exceptions::PyRuntimeError::new_err)
    }

    /// Warnings (e.g. a Zeno sequence ended).
    fn warnings(&self) -> Vec<String> {
        self.billiard.warnings().to_vec()
    }
}

/// The Lightcone engine from Python.
#[pymodule]
fn _lightcone(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Scene>()?;
    m.add_class::<Simulation>()?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    Ok(())
}
