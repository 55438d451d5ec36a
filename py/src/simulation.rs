//! `lightcone.Simulation`: a scene's physics run from Python, headless.
//!
//! The state sits behind a mutex inside the (frozen) Python object, so a
//! call from another thread while `run_until` runs waits for it (without
//! holding the GIL) instead of raising "Already borrowed". `run_until`
//! advances in chunks of board time, releasing the lock and checking for
//! Ctrl-C (`KeyboardInterrupt`) between them: other threads see a
//! consistent state at a chunk boundary, and a long run stops promptly.

use std::path::PathBuf;
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};

use lightcone_lesson::simulation::SimulationCore;
use pyo3::prelude::*;

use super::convert::Vector;
use super::{Frame, Scene};

/// A running simulation of a scene: the event-anticipation physics.
#[pyclass(module = "lightcone._lightcone", frozen)]
pub struct Simulation {
    state: Mutex<SimulationCore>,
}

impl Simulation {
    /// The state, waiting without the GIL while another thread holds it.
    fn lock(&self, py: Python<'_>) -> MutexGuard<'_, SimulationCore> {
        loop {
            match self.state.try_lock() {
                Ok(guard) => return guard,
                Err(std::sync::TryLockError::Poisoned(p)) => return p.into_inner(),
                Err(std::sync::TryLockError::WouldBlock) => {
                    // Wait for the holder to let go, then try again with
                    // the GIL (a guard cannot leave `detach`).
                    py.detach(|| drop(self.state.lock()));
                }
            }
        }
    }
}

/// Wall-clock time a chunk of `run_until` aims at between two checks for
/// Ctrl-C and two chances for other threads.
const CHUNK: Duration = Duration::from_millis(20);

#[pymethods]
impl Simulation {
    /// `history`: how far back (board seconds) worldlines and collision
    /// records are kept; `None` keeps the whole run. With a horizon, memory
    /// stays bounded however long the run, and `forgotten_before` says from
    /// when the past is gone.
    #[new]
    #[pyo3(signature = (scene, history = None))]
    fn new(scene: &Scene, history: Option<f64>) -> PyResult<Self> {
        let core = SimulationCore::new(&scene.inner, history).map_err(super::errors::world_err)?;
        Ok(Self {
            state: Mutex::new(core),
        })
    }

    /// The history horizon, s (`None`: the whole run is kept).
    #[getter]
    fn history(&self, py: Python<'_>) -> Option<f64> {
        self.lock(py).billiard().history()
    }

    /// Board time before which worldlines and collisions have been
    /// forgotten (`None` while nothing has), s.
    #[getter]
    fn forgotten_before(&self, py: Python<'_>) -> Option<f64> {
        self.lock(py).billiard().forgotten_before()
    }

    /// The scene simulated (a copy).
    #[getter]
    fn scene(&self, py: Python<'_>) -> Scene {
        Scene {
            inner: self.lock(py).scene().clone(),
        }
    }

    /// Board time reached, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> f64 {
        self.lock(py).billiard().time()
    }

    /// Runs the physics to board time `t` (s); earlier times do nothing.
    /// Releases the GIL while it runs; Ctrl-C (KeyboardInterrupt) stops it
    /// within about 20 ms, at a consistent state.
    fn run_until(&self, py: Python<'_>, t: f64) -> PyResult<()> {
        let t = super::finite_time(t)?;
        // Board seconds a chunk, adapted to take about CHUNK of wall time.
        let mut dt = 1e-3_f64;
        loop {
            let (next, took) = py.detach(|| {
                let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
                let now = s.time();
                let next = if now + dt < t { now + dt } else { t };
                let start = Instant::now();
                s.advance_to(next);
                (next, start.elapsed())
            });
            py.check_signals()?;
            if next >= t {
                // `collisions()` then holds only the history horizon.
                self.lock(py).forget_old_records();
                return Ok(());
            }
            if took < CHUNK / 2 {
                dt *= 2.0;
            } else if took > CHUNK * 2 {
                dt = (dt / 2.0).max(1e-9);
            }
        }
    }

    /// Advances by `dt` seconds of board time.
    fn step(&self, py: Python<'_>, dt: f64) -> PyResult<()> {
        let t = self.time(py) + dt;
        self.run_until(py, t)
    }

    /// Strikes puck `name` now: its proper velocity γβ (dimensionless)
    /// grows by `du` (any two numbers: tuple, list, array); no push
    /// reaches c.
    fn impulse(&self, py: Python<'_>, name: &str, du: Vector<2>) -> PyResult<()> {
        let mut s = self.lock(py);
        let t = s.time();
        super::impulse(s.billiard_mut(), name, t, du.pair())
    }

    /// Every collision so far, as the dicts `lightcone simulate` prints.
    fn collisions<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyAny>>> {
        let s = self.lock(py);
        super::collisions(py, s.billiard())
    }

    /// Every puck now: the `state` dict of `lightcone simulate`.
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let s = self.lock(py);
        super::state(py, s.billiard(), s.time())
    }

    /// What observer `observer` (default: the first) sees at board time
    /// `at` (default: now; any time already computed), as the dict
    /// `lightcone observe` prints. `effects`: None for the scene's, or a
    /// list of effect names to turn on (the others off).
    #[pyo3(signature = (observer = None, vertices = false, effects = None, at = None))]
    fn observe<'py>(
        &self,
        py: Python<'py>,
        observer: Option<&str>,
        vertices: bool,
        effects: Option<Vec<String>>,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let report = {
            let mut s = self.lock(py);
            let t = super::past_time(at, s.time())?;
            let fx = super::effects_from(s.scene().effects, effects)?;
            s.observe(observer, t, vertices, fx)
                .map_err(super::errors::world_err)?
        };
        super::to_record(py, "Observation", &report)
    }

    /// The proper velocity γβ (dimensionless) of puck `name` now, as (x, y).
    fn velocity(&self, py: Python<'_>, name: &str) -> PyResult<(f64, f64)> {
        let s = self.lock(py);
        super::velocity(s.billiard(), name, s.time())
    }

    /// Every puck's centre on the board at board time `at` (default: now;
    /// any time already computed), m, as a numpy array of shape (N, 2),
    /// dtype float64, in scene order (`scene.pucks`): the positions of
    /// `state()` as one array, for plotting. Needs numpy.
    #[pyo3(signature = (at = None))]
    fn positions<'py>(&self, py: Python<'py>, at: Option<f64>) -> PyResult<Bound<'py, PyAny>> {
        let rows = {
            let s = self.lock(py);
            let t = super::past_time(at, s.time())?;
            (0..s.billiard().len())
                .map(|i| {
                    let p = s.billiard().worldline(i).position_at(t);
                    [p.x, p.y]
                })
                .collect()
        };
        super::array(py, "Simulation.positions", rows)
    }

    /// Every puck's proper velocity u = γβ (dimensionless) at board time
    /// `at` (default: now), as a numpy array of shape (N, 2), dtype
    /// float64, in scene order: `velocity(name)` for all at once. Needs
    /// numpy.
    #[pyo3(signature = (at = None))]
    fn velocities<'py>(&self, py: Python<'py>, at: Option<f64>) -> PyResult<Bound<'py, PyAny>> {
        let rows = {
            let s = self.lock(py);
            let t = super::past_time(at, s.time())?;
            (0..s.billiard().len())
                .map(|i| {
                    let u = s.billiard().worldline(i).proper_velocity_at(t);
                    [u.0.x, u.0.y]
                })
                .collect()
        };
        super::array(py, "Simulation.velocities", rows)
    }

    /// Renders what `observer` (default: the first) sees at board time `at`
    /// (default: now) headless, and returns the frame (shown inline in
    /// Jupyter); with `path`, also saves it as a PNG. `view` is "seen" or
    /// "truth"; `size` is (width, height) in pixels. Framed as
    /// `lightcone render` frames it: the whole table with a margin, unless
    /// the observer has a `look_at`. Raises NoAdapterError
    /// when there is no graphics adapter (install mesa-vulkan-drivers).
    #[pyo3(signature = (path = None, observer = None, size = (1280, 720), view = "seen", at = None))]
    fn render(
        &self,
        py: Python<'_>,
        path: Option<PathBuf>,
        observer: Option<&str>,
        size: (u32, u32),
        view: &str,
        at: Option<f64>,
    ) -> PyResult<Frame> {
        let mut s = self.lock(py);
        let t = super::past_time(at, s.time())?;
        let frame = super::render_frame(py, &mut s, t, observer, size, view)?;
        if let Some(path) = path {
            frame.save(path)?;
        }
        Ok(frame)
    }

    /// The space-time diagram (board `axis` "x" or "y" across, board time
    /// up) for `observer` (default: the first) at board time `at` (default:
    /// now), as the `Frame` `render` returns; drawn on the CPU (no graphics
    /// adapter needed). `frame`: a puck whose lines of simultaneity to draw
    /// (default: none). With `path`, also saved as a PNG.
    #[pyo3(signature = (path = None, observer = None, size = (1000, 700), at = None, axis = "x", frame = None))]
    #[allow(clippy::too_many_arguments)]
    fn diagram(
        &self,
        py: Python<'_>,
        path: Option<PathBuf>,
        observer: Option<&str>,
        size: (u32, u32),
        at: Option<f64>,
        axis: &str,
        frame: Option<&str>,
    ) -> PyResult<Frame> {
        let s = self.lock(py);
        let t = super::past_time(at, s.time())?;
        super::diagram::diagram_frame(
            s.scene(),
            s.billiard(),
            t,
            observer,
            size,
            axis,
            frame,
            path,
        )
    }

    /// The line of simultaneity of puck `frame`'s rest frame through its
    /// event at board time `at` (default: now): `{"puck", "event": {"t",
    /// "position"}, "slope": [dt/dx, dt/dy]}` (s, m, s/m); the diagram
    /// draws it.
    #[pyo3(signature = (frame, at = None))]
    fn simultaneity<'py>(
        &self,
        py: Python<'py>,
        frame: &str,
        at: Option<f64>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let s = self.lock(py);
        let t = super::past_time(at, s.time())?;
        super::diagram::simultaneity(py, s.scene(), s.billiard(), frame, t)
    }

    /// Warnings (e.g. a Zeno sequence ended).
    fn warnings(&self, py: Python<'_>) -> Vec<String> {
        self.lock(py).billiard().warnings().to_vec()
    }

    /// The current view as PNG bytes, for Jupyter; None without a graphics
    /// adapter.
    fn _repr_png_(&self, py: Python<'_>) -> Option<Vec<u8>> {
        let mut s = self.lock(py);
        let t = s.time();
        super::render_frame(py, &mut s, t, None, (640, 360), "seen")
            .ok()
            .map(|f| f.png)
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let s = self.lock(py);
        format!(
            "Simulation({:?}, t = {} s, {} pucks, {} collisions)",
            s.scene().title,
            s.time(),
            s.billiard().len(),
            s.billiard().collisions().len()
        )
    }
}
