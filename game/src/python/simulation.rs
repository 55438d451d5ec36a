//! `lightcone.Simulation`: a scene's physics run from Python, headless.

use std::path::PathBuf;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene;
use pyo3::prelude::*;

use super::Scene;

/// A running simulation of a scene: the event-anticipation physics.
#[pyclass(module = "lightcone._lightcone")]
pub struct Simulation {
    scene: scene::Scene,
    billiard: Billiard,
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
        let t = super::finite_time(t)?;
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
        let t = self.billiard.time();
        super::impulse(&mut self.billiard, name, t, du)
    }

    /// Every collision so far, as the dicts `lightcone simulate` prints.
    fn collisions<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        super::collisions(py, &self.billiard)
    }

    /// Every puck now: the `state` dict of `lightcone simulate`.
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        super::state(py, &self.billiard, self.billiard.time())
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
        let fx = super::effects_from(self.scene.effects, effects)?;
        super::observation(
            py,
            &self.scene,
            &self.billiard,
            self.billiard.time(),
            observer,
            vertices,
            fx,
        )
    }

    /// The proper velocity γβ of puck `name` now, as (x, y).
    fn velocity(&self, name: &str) -> PyResult<(f64, f64)> {
        super::velocity(&self.billiard, name, self.billiard.time())
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
        super::render_png(
            py,
            &self.scene,
            &self.billiard,
            self.billiard.time(),
            &path,
            observer,
            size,
            view,
        )
    }

    /// Warnings (e.g. a Zeno sequence ended).
    fn warnings(&self) -> Vec<String> {
        self.billiard.warnings().to_vec()
    }
}
