//! `import lightcone`: thin Python wrappers over the engine. All physics
//! lives in `lightcone-engine`; these classes only convert arguments and
//! results (collision and observation records as the same dictionaries
//! that `lightcone simulate` and `lightcone observe` print as JSON).

use std::path::PathBuf;

use glam::DVec3;
use lightcone_engine::optics::view::{Method, observe};
use lightcone_engine::optics::{Eye, mesh};
use lightcone_engine::physics::Billiard;
use lightcone_engine::report::{CollisionLine, ObserveReport, StateLine};
use lightcone_engine::scene::{self, Effect};
use lightcone_engine::spacetime::{Event, ProperVelocity};
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
#[pyclass(module = "lightcone._lightcone", frozen)]
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

    /// Speed of light, m/s.
    #[getter]
    fn c(&self) -> f64 {
        self.inner.c
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
        let index = match observer {
            None => 0,
            Some(name) => self
                .scene
                .observers
                .iter()
                .position(|o| o.name == name)
                .ok_or_else(|| PyKeyError::new_err(format!("no observer named {name:?}")))?,
        };
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
        let eye = Eye {
            event: Event::new(t, spec.position + spec.u.velocity(self.scene.c) * t),
            u: spec.u,
        };
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
