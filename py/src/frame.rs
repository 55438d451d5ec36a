//! `lightcone.Frame`: a rendered picture, as PNG bytes (shown inline in
//! Jupyter through `_repr_png_`).

use std::path::PathBuf;

use pyo3::exceptions::{PyOSError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use lightcone_render::headless::Image;

/// A rendered frame: what an observer saw at board time `t`.
#[pyclass(module = "lightcone._lightcone", frozen)]
pub struct Frame {
    /// The picture, PNG-encoded (RGBA, 8 bits).
    pub(crate) png: Vec<u8>,
    width: u32,
    height: u32,
    t: f64,
}

impl Frame {
    /// Encodes `image`, rendered at board time `t`.
    pub(crate) fn from_image(image: &Image, t: f64) -> PyResult<Self> {
        let mut png = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut png, image.width, image.height);
            encoder.set_color(png::ColorType::Rgba);
            encoder.set_depth(png::BitDepth::Eight);
            let mut writer = encoder
                .write_header()
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
            writer
                .write_image_data(&image.rgba)
                .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        }
        Ok(Self {
            png,
            width: image.width,
            height: image.height,
            t,
        })
    }

    /// Writes the PNG to `path`.
    pub(crate) fn save(&self, path: PathBuf) -> PyResult<()> {
        std::fs::write(&path, &self.png)
            .map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))
    }
}

#[pymethods]
impl Frame {
    /// Width, pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.width
    }

    /// Height, pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.height
    }

    /// Board time of the picture, s.
    #[getter]
    fn t(&self) -> f64 {
        self.t
    }

    /// The PNG file's bytes.
    #[getter]
    fn png<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.png)
    }

    /// Saves the picture as a PNG file.
    #[pyo3(name = "save")]
    fn save_py(&self, path: PathBuf) -> PyResult<()> {
        self.save(path)
    }

    /// A frame from its PNG bytes: how a lesson run in its own process
    /// receives `world.diagram(...)` from the game (which made the PNG).
    #[staticmethod]
    fn _from_png(png: &[u8], width: u32, height: u32, t: f64) -> Self {
        Self {
            png: png.to_vec(),
            width,
            height,
            t,
        }
    }

    fn _repr_png_<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, &self.png)
    }

    fn __repr__(&self) -> String {
        format!("Frame({}×{} px, t = {} s)", self.width, self.height, self.t)
    }
}
