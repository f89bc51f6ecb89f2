//! `Drawn`: a dict (what a command's JSON file holds) that draws itself in notebooks, for the
//! urban methods' results.

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A dict, equal to the JSON file the command writes, with its picture: Jupyter shows the SVG
/// (`_repr_svg_`); `svg` gives it as text.
#[pyclass(extends = PyDict, module = "netspec", name = "Drawn")]
pub(crate) struct Drawn {
    svg: String,
}

#[pymethods]
impl Drawn {
    /// The picture, an SVG document.
    #[getter]
    fn svg(&self) -> &str {
        &self.svg
    }

    fn _repr_svg_(&self) -> &str {
        &self.svg
    }
}

/// `data` (a dict) as a [`Drawn`] with picture `svg`.
pub(crate) fn drawn(py: Python<'_>, data: PyObject, svg: String) -> PyResult<PyObject> {
    let obj = Bound::new(py, Drawn { svg })?;
    obj.as_any().downcast::<PyDict>()?.update(data.bind(py).downcast::<pyo3::types::PyMapping>()?)?;
    Ok(obj.into_any().unbind())
}
