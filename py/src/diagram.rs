//! The space-time diagram and a puck frame's line of simultaneity, from
//! Python: `Simulation.diagram(...)` / `World.diagram(...)` return the same
//! [`Frame`] `render` returns (drawn on the CPU: no graphics adapter
//! needed), `simultaneity(frame, at)` the line the diagram draws, as a dict.

use std::path::PathBuf;

use lightcone_engine::physics::Billiard;
use lightcone_engine::scene::Scene as SceneModel;
use lightcone_lesson::query;
use pyo3::prelude::*;

use super::Frame;
use super::errors::world_err;

/// The diagram of `scene` for `observer` at board time `t` as a [`Frame`]
/// (see `lightcone_lesson::query::diagram`), also saved at `path` if given.
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
    let image =
        query::diagram(scene, billiard, t, observer, size, axis, frame).map_err(world_err)?;
    let picture = Frame::from_image(&image, t)?;
    if let Some(path) = path {
        picture.save(path)?;
    }
    Ok(picture)
}

/// Puck `name`'s line of simultaneity at board time `t`, as a dict
/// `{"puck", "event": {"t", "position"}, "slope"}`.
pub(crate) fn simultaneity<'py>(
    py: Python<'py>,
    scene: &SceneModel,
    billiard: &Billiard,
    name: &str,
    t: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let line = query::simultaneity(scene, billiard, name, t).map_err(world_err)?;
    super::to_plain(py, &line)
}
