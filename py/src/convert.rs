//! Arguments as Python code gives them: wherever a vector goes, any
//! sequence of numbers (a tuple, a list, a numpy array). A wrong one raises
//! a `TypeError` that pyo3 prefixes with the argument's name
//! (`argument 'position': give 2 numbers …`).

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyString};

/// `N` numbers from any sequence of numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vector<const N: usize>(pub [f64; N]);

/// A short description of `obj` for messages.
fn describe(obj: &Bound<'_, PyAny>) -> String {
    let text = obj
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "?".to_owned());
    let short: String = text.chars().take(60).collect();
    if short.len() < text.len() {
        format!("{short}…")
    } else {
        short
    }
}

impl<'a, 'py, const N: usize> FromPyObject<'a, 'py> for Vector<N> {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let obj: &Bound<'py, PyAny> = &obj;
        let bad = |why: &str| {
            PyTypeError::new_err(format!(
                "give {N} numbers (a tuple, list or array){why}, not {}",
                describe(obj)
            ))
        };
        if obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>() {
            return Err(bad(""));
        }
        let n = obj.len().map_err(|_| bad(""))?;
        if n != N {
            return Err(bad(&format!("; got {n}")));
        }
        let mut v = [0.0; N];
        for (slot, item) in v.iter_mut().zip(obj.try_iter().map_err(|_| bad(""))?) {
            *slot = item?.extract::<f64>().map_err(|_| bad(""))?;
        }
        Ok(Self(v))
    }
}

impl Vector<2> {
    /// As a pair.
    pub fn pair(self) -> (f64, f64) {
        (self.0[0], self.0[1])
    }
}

impl Vector<3> {
    /// As a triple.
    pub fn triple(self) -> (f64, f64, f64) {
        (self.0[0], self.0[1], self.0[2])
    }
}

/// An optional vector argument called `name`: None, or `N` numbers; the
/// error names the argument as pyo3 does for required ones.
pub fn optional<const N: usize>(
    name: &str,
    value: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<Vector<N>>> {
    match value {
        None => Ok(None),
        Some(v) if v.is_none() => Ok(None),
        Some(v) => v
            .extract::<Vector<N>>()
            .map(Some)
            .map_err(|e| PyTypeError::new_err(format!("argument '{name}': {}", e.value(v.py())))),
    }
}
