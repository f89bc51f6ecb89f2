//! Waiting for a solve outside the GIL: Ctrl-C stops the backend, progress reaches a Python callback.

use crate::errors::py_num;
use netspec::solvers::{Interrupt, Progress, ProgressSink};
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use std::sync::mpsc;
use std::sync::Arc;
use std::time::Duration;

/// How often the waiting thread looks for Ctrl-C and delivers progress.
pub(crate) const POLL: Duration = Duration::from_millis(25);

/// A progress report of a running solve, as the backend gives it.
#[pyclass(module = "netspec", name = "Progress", frozen, get_all)]
#[derive(Clone)]
pub(crate) struct PyProgress {
    /// Seconds since the solver started.
    pub(crate) elapsed: f64,
    /// The best objective found so far (the incumbent), if any.
    pub(crate) incumbent: Option<f64>,
    /// The best proven bound so far, if any.
    pub(crate) bound: Option<f64>,
    /// Branch-and-bound nodes so far.
    pub(crate) nodes: u64,
}

#[pymethods]
impl PyProgress {
    fn __repr__(&self) -> String {
        format!(
            "Progress(elapsed={:.2}, incumbent={}, bound={}, nodes={})",
            self.elapsed,
            py_num(self.incumbent),
            py_num(self.bound),
            self.nodes
        )
    }
}

/// Runs `work` on a thread of its own with the GIL released, and waits for it: every [`POLL`]
/// the waiting (calling) thread takes the GIL to deliver progress reports to `on_progress` and
/// to look for a pending signal. A KeyboardInterrupt (Ctrl-C) triggers the run's interrupt (the
/// backend stops and keeps its best design, which `work` returns); an exception raised by
/// `on_progress` does too, and is raised once `work` has returned.
pub(crate) fn run_blocking<T: Send>(
    py: Python<'_>,
    on_progress: Option<PyObject>,
    work: impl FnOnce(Interrupt, Option<ProgressSink>) -> T + Send,
) -> PyResult<T> {
    run_blocking_with(
        py,
        on_progress,
        |py, cb, p: Progress| {
            let report = PyProgress { elapsed: p.elapsed, incumbent: p.primal, bound: p.dual, nodes: p.nodes };
            cb.call1(py, (report,)).map(drop)
        },
        move |interrupt, report| work(interrupt, report.map(|r| ProgressSink(Arc::new(move |p| r(p))))),
    )
}

/// A report sender handed to the work: called on the working thread, delivered on the calling one.
pub(crate) type Report<P> = Arc<dyn Fn(P) + Send + Sync>;

/// [`run_blocking`] with reports of any kind `P`, each handed to `on_progress` by `deliver`
/// (on the calling thread, with the GIL). The work gets the run's interrupt and, when there is
/// a callback, a sender of reports.
pub(crate) fn run_blocking_with<T: Send, P: Send + 'static>(
    py: Python<'_>,
    on_progress: Option<PyObject>,
    deliver: impl Fn(Python<'_>, &PyObject, P) -> PyResult<()> + Send,
    work: impl FnOnce(Interrupt, Option<Report<P>>) -> T + Send,
) -> PyResult<T> {
    /// What the waiting thread hears from the working one.
    enum Heard<P> {
        Progress(P),
        Done,
    }
    let interrupt = Interrupt::new();
    let (tx, rx) = mpsc::channel::<Heard<P>>();
    let sink = on_progress.as_ref().map(|_| {
        let tx = tx.clone();
        let report: Report<P> = Arc::new(move |p: P| {
            let _ = tx.send(Heard::Progress(p));
        });
        report
    });
    let stop = interrupt.clone();
    let (out, raised) = py.allow_threads(move || {
        let mut raised: Option<PyErr> = None;
        let out = std::thread::scope(|scope| {
            let handle = scope.spawn(move || {
                let out = work(stop, sink);
                let _ = tx.send(Heard::Done);
                out
            });
            let mut finished = false;
            while !finished {
                // Blocks until a report, the end, or the next look for a signal. (A worker that
                // panicked drops its sender: disconnected is the end too.)
                let mut reports = Vec::new();
                let mut hear = |h: Result<Heard<P>, ()>| match h {
                    Ok(Heard::Progress(p)) => reports.push(p),
                    Ok(Heard::Done) | Err(()) => finished = true,
                };
                match rx.recv_timeout(POLL) {
                    Ok(h) => hear(Ok(h)),
                    Err(mpsc::RecvTimeoutError::Timeout) => {}
                    Err(mpsc::RecvTimeoutError::Disconnected) => hear(Err(())),
                }
                rx.try_iter().for_each(|h| hear(Ok(h)));
                if finished && reports.is_empty() {
                    break;
                }
                Python::with_gil(|py| {
                    if let Some(cb) = &on_progress {
                        for p in reports {
                            if let Err(e) = deliver(py, cb, p) {
                                raised.get_or_insert(e);
                                interrupt.trigger();
                            }
                        }
                    }
                    // Only the main thread sees signals; elsewhere this returns Ok.
                    if let Err(e) = py.check_signals() {
                        if !e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                            raised.get_or_insert(e);
                        }
                        interrupt.trigger();
                    }
                });
            }
            handle.join()
        });
        (out, raised)
    });
    match (out, raised) {
        (_, Some(e)) => Err(e),
        (Ok(v), None) => Ok(v),
        (Err(_), None) => Err(PyRuntimeError::new_err("the run panicked")),
    }
}
