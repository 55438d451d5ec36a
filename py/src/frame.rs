//! `lightcone.Frame`: a rendered picture, as PNG bytes (shown inline in
//! Jupyter through `_repr_png_`) or, with numpy, as an array of pixels.

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

    /// The pixels, RGBA 8 bits, row by row from the top: decoded from the
    /// PNG (a frame received from the game holds only that).
    fn rgba(&self) -> PyResult<Vec<u8>> {
        let bad = |e: png::DecodingError| PyRuntimeError::new_err(format!("the frame's PNG: {e}"));
        let mut reader = png::Decoder::new(std::io::Cursor::new(&self.png))
            .read_info()
            .map_err(bad)?;
        let size = reader
            .output_buffer_size()
            .ok_or_else(|| PyRuntimeError::new_err("the frame's PNG is too large to decode"))?;
        let mut pixels = vec![0; size];
        let info = reader.next_frame(&mut pixels).map_err(bad)?;
        if (info.width, info.height) != (self.width, self.height)
            || info.color_type != png::ColorType::Rgba
            || info.bit_depth != png::BitDepth::Eight
        {
            return Err(PyRuntimeError::new_err(format!(
                "the frame's PNG is {}×{} {:?} {:?}, not {}×{} RGBA 8 bits",
                info.width, info.height, info.color_type, info.bit_depth, self.width, self.height
            )));
        }
        pixels.truncate(info.buffer_size());
        Ok(pixels)
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

    /// The picture as a numpy array of shape (height, width, 4), dtype
    /// uint8: RGBA, row 0 at the top (as `matplotlib.pyplot.imshow` takes
    /// it). Needs numpy (`ImportError` naming it otherwise); the rest of
    /// the module does not.
    fn to_numpy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let numpy = super::numpy(py, "Frame.to_numpy")?;
        let pixels = PyBytes::new(py, &self.rgba()?);
        numpy
            .call_method1("frombuffer", (pixels, "uint8"))?
            .call_method1("reshape", (self.height, self.width, 4))?
            .call_method0("copy")
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
