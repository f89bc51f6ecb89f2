//! The exceptions the module raises, and the conversions of library errors and arguments into them.

use netspec::pipeline::Method;
use netspec::solvers::SolverKind;
use netspec::spec::{SpecError as LibSpecError, SpecErrorKind, Variant};
use pyo3::create_exception;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use serde::Serialize;
use std::path::Path;

create_exception!(
    netspec,
    SpecError,
    PyValueError,
    "A spec that cannot be used: the message names the file and field, as `netspec solve` does; \
     `.field` is the dotted field (`sinks.vertices[3]`) or None, `.path` the file or `<inline>`."
);
create_exception!(
    netspec,
    NetspecError,
    PyRuntimeError,
    "A run that could not be made: a refused setting (named as the keyword argument), a backend \
     that cannot attempt the solve, a file that cannot be read or written."
);

pub(crate) fn spec_error(py: Python<'_>, path: &Path, kind: &SpecErrorKind, field: Option<String>) -> PyErr {
    // A field found by reading again is named in the message as the library names its own.
    let message = match (kind.field(), &field) {
        (None, Some(f)) => format!("{}: field `{f}`: {kind}", path.display()),
        _ => format!("{}: {kind}", path.display()),
    };
    new_spec_error(py, message, kind.field().or(field), path)
}

/// A `SpecError` with its `field` and `path` attributes.
pub(crate) fn new_spec_error(py: Python<'_>, message: String, field: Option<String>, path: &Path) -> PyErr {
    let err = SpecError::new_err(message);
    let value = err.value(py);
    // Attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("field", field);
    let _ = value.setattr("path", path.display().to_string());
    err
}

pub(crate) fn lib_spec_error(py: Python<'_>, e: &LibSpecError) -> PyErr {
    // A TOML schema error names the line; the field is found by reading the file again.
    let field = match &e.kind {
        SpecErrorKind::Toml(_) => {
            std::fs::read_to_string(&e.path).ok().and_then(|t| netspec::spec::toml_error_field(&t))
        }
        _ => None,
    };
    spec_error(py, &e.path, &e.kind, field)
}

pub(crate) fn run_error(py: Python<'_>, e: netspec::run::RunError) -> PyErr {
    match e {
        netspec::run::RunError::Spec(s) => lib_spec_error(py, &s),
        // The flags are this function's keyword arguments.
        netspec::run::RunError::Settings(s) => {
            let place = s.place.trim_start_matches("--").replace('-', "_");
            NetspecError::new_err(format!("{place}: {}", s.reason))
        }
        other => NetspecError::new_err(other.to_string()),
    }
}

/// An optional number as Python writes it.
pub(crate) fn py_num(v: Option<f64>) -> String {
    v.map_or("None".to_string(), |v| format!("{v:?}"))
}

pub(crate) fn py_bool(b: bool) -> &'static str {
    if b {
        "True"
    } else {
        "False"
    }
}

pub(crate) fn err<E: std::fmt::Display>(e: E) -> PyErr {
    NetspecError::new_err(e.to_string())
}

/// A serialisable value as Python objects (through JSON: dicts, lists, numbers, strings, None).
pub(crate) fn to_py<T: Serialize>(py: Python<'_>, value: &T) -> PyResult<PyObject> {
    let text = serde_json::to_string(value).map_err(err)?;
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

pub(crate) fn parse_method(solver: Option<&str>) -> PyResult<Option<Method>> {
    solver.map(|s| s.parse::<Method>().map_err(|e| PyValueError::new_err(format!("solver: {e}")))).transpose()
}

pub(crate) fn parse_variant(formulation: Option<&str>) -> PyResult<Option<Variant>> {
    formulation
        .map(|f| f.parse::<Variant>().map_err(|e| PyValueError::new_err(format!("formulation: {e}"))))
        .transpose()
}

pub(crate) fn parse_kind(solver: &str) -> PyResult<SolverKind> {
    solver.parse::<SolverKind>().map_err(|e| PyValueError::new_err(format!("solver: {e}")))
}

/// A library error with its causes, each not already in the message before it (as the command
/// line prints them), as a `NetspecError`.
pub(crate) fn err_chain(e: &(dyn std::error::Error + 'static)) -> PyErr {
    let mut message = e.to_string();
    let mut shown = message.clone();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !shown.contains(&text) {
            message.push_str(": ");
            message.push_str(&text);
        }
        shown = text;
        cause = c.source();
    }
    NetspecError::new_err(message)
}

/// A refused setting, named by the command line's flag (`--time-limit`), as a `ValueError`
/// naming the keyword argument (`time_limit`).
pub(crate) fn setting_error(s: &netspec::pipeline::settings::SettingsError) -> PyErr {
    PyValueError::new_err(format!("{}: {}", s.place.trim_start_matches("--").replace('-', "_"), s.reason))
}
