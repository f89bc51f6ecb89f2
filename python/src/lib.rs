//! `netspec._netspec`: the Python extension module of netspec, wrapped by the package in
//! `python/netspec/`. Each function calls the library entry point the command line calls
//! (`netspec solve` → [`netspec::run::solve_loaded`], `compare`, `level`, `city`, `solve-file`,
//! `site`, `stats`, `layout`, `field`, `grow`, `traffic`), with the long waits outside the GIL:
//! other Python threads run meanwhile, a Ctrl-C stops the backend (or a layout's variations, a
//! growth's steps) and keeps what it has, and progress reaches a Python callback on the calling
//! thread.

mod blocking;
mod comparison;
mod drawn;
mod errors;
mod methods;
mod model;
mod result;
mod sites;
mod spec;
mod urban;

use blocking::PyProgress;
use errors::{NetspecError, SpecError};
use model::{PyModel, PyModelResult};
use pyo3::prelude::*;
use result::{PyDesign, PyResultObj};
use spec::PySpec;

/// The version of the netspec library this module was built from.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

/// netspec: network design from functional specifications by integer programming, on
/// interchangeable MILP backends.
#[pymodule]
fn _netspec(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("SpecError", py.get_type::<SpecError>())?;
    m.add("NetspecError", py.get_type::<NetspecError>())?;
    m.add_class::<PySpec>()?;
    m.add_class::<PyModel>()?;
    m.add_class::<PyModelResult>()?;
    m.add_class::<PyResultObj>()?;
    m.add_class::<PyDesign>()?;
    m.add_class::<PyProgress>()?;
    m.add_class::<drawn::Drawn>()?;
    m.add_function(wrap_pyfunction!(spec::read_spec, m)?)?;
    m.add_function(wrap_pyfunction!(model::read_model, m)?)?;
    m.add_function(wrap_pyfunction!(model::check, m)?)?;
    m.add_function(wrap_pyfunction!(result::solve, m)?)?;
    m.add_function(wrap_pyfunction!(comparison::compare, m)?)?;
    m.add_function(wrap_pyfunction!(comparison::csv_columns, m)?)?;
    m.add_function(wrap_pyfunction!(comparison::records_csv, m)?)?;
    m.add_function(wrap_pyfunction!(urban::solvers, m)?)?;
    m.add_function(wrap_pyfunction!(urban::level, m)?)?;
    m.add_function(wrap_pyfunction!(urban::city, m)?)?;
    m.add_function(wrap_pyfunction!(sites::site, m)?)?;
    m.add_function(wrap_pyfunction!(sites::stats, m)?)?;
    m.add_function(wrap_pyfunction!(methods::layout, m)?)?;
    m.add_function(wrap_pyfunction!(methods::field, m)?)?;
    m.add_function(wrap_pyfunction!(methods::grow, m)?)?;
    m.add_function(wrap_pyfunction!(methods::traffic, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
