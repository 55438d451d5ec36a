//! The space-time diagram and a puck frame's line of simultaneity, from
//! Python: `Simulation.diagram(...)` / `World.diagram(...)` return the same
//! [`Frame`] `render` returns (drawn on the CPU: no graphics adapter
//! needed), `simultaneity(frame, at)` the line the diagram draws, as a dict.

use std::path::PathBuf;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::Scene as SceneModel;
use lightcone_engine::spacetime::simultaneity_slope;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::Frame;
use lightcone_render::diagram::{self, Axis, Options};

/// The diagram of `scene` for `observer` (default: the first) at board
/// time `t`, `size` px, along `axis` ("x" or "y"), with puck `frame`'s
/// lines of simultaneity; saved to `path` when given.
#[allow(clippy::too_many_arguments)]
pub(crate) fn diagram_frame(
    scene: &SceneModel,
    billiard: &Billiard,
    t: f64,
    observer: Option<&str>,
    size: (u32, u32),
    axis: &str,
    frame: Option<&str>,
    path: Option<PathBuf>,
) -> PyResult<Frame> {
    let axis = Axis::parse(axis).map_err(PyValueError::new_err)?;
    if size.0 == 0 || size.1 == 0 || size.0 > 16384 || size.1 > 16384 {
        return Err(PyValueError::new_err(format!(
            "size {size:?}: 1 to 16384 pixels a side"
        )));
    }
    let index = super::observer_index(scene, observer)?;
    let frame = frame.map(|f| super::puck_index(billiard, f)).transpose()?;
    let drawn = diagram::draw_with(scene, billiard, index, t, size, Options { axis, frame });
    let picture = Frame::from_image(&drawn.image, t)?;
    if let Some(path) = path {
        picture.save(path)?;
    }
    Ok(picture)
}

/// The line of simultaneity of puck `name`'s rest frame through its event
/// at board time `t`: `{"puck", "event": {"t", "position"}, "slope"}`,
/// `slope` = (dt/dx, dt/dy) in s/m (`v / c²`): the board events its frame
/// calls simultaneous with `event` are those with
/// `t = event.t + slope · (position − event.position)`.
pub(crate) fn simultaneity<'py>(
    py: Python<'py>,
    scene: &SceneModel,
    billiard: &Billiard,
    name: &str,
    t: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let i = super::puck_index(billiard, name)?;
    let w = billiard.worldline(i);
    let e = w.event_at(t);
    let slope = simultaneity_slope(w.proper_velocity_at(t), scene.c);
    let event = PyDict::new(py);
    event.set_item("t", e.t)?;
    event.set_item("position", vec![e.position.x, e.position.y])?;
    let out = PyDict::new(py);
    out.set_item("puck", name)?;
    out.set_item("event", event)?;
    out.set_item("slope", vec![slope.x, slope.y])?;
    Ok(out)
}
