//! The last guard around a backend: a panic inside its library (or in a callback it runs)
//! becomes a [`SolverErrorKind::Panicked`] error naming the backend, instead of ending the
//! process. Every backend [`SolverKind::instance`] returns is wrapped in it; netspec's own checks
//! before a solve (the model's validation, the numeric screen) should leave nothing to catch.

use super::{Capabilities, SolverErrorKind, SolverKind, StrategyHints};
use super::{LazyRow, LazySolve, LpSession, RawParam, Separator, SolveOptions, SolveResult, Solver, SolverError};
use crate::milp::Model;
use std::cell::{Cell, RefCell};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// How deep this thread is inside guarded backend calls.
    static DEPTH: Cell<usize> = const { Cell::new(0) };
    /// Where the last caught panic happened.
    static WHERE: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Installs (once) a panic hook that stays quiet inside guarded calls — their panic becomes an
/// error with the same message — and defers to the previous hook everywhere else.
fn quiet_inside_guards() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if DEPTH.with(Cell::get) > 0 {
                let at = info.location().map(|l| format!("{}:{}", l.file(), l.line()));
                WHERE.with(|w| *w.borrow_mut() = at);
            } else {
                previous(info);
            }
        }));
    });
}

/// Runs `f`, turning a panic into an error naming `kind`.
fn guard<T>(kind: SolverKind, f: impl FnOnce() -> Result<T, SolverError>) -> Result<T, SolverError> {
    quiet_inside_guards();
    DEPTH.with(|d| d.set(d.get() + 1));
    let r = catch_unwind(AssertUnwindSafe(f));
    DEPTH.with(|d| d.set(d.get() - 1));
    r.unwrap_or_else(|payload| {
        let text = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        let at = WHERE.with(|w| w.borrow_mut().take()).map_or(String::new(), |w| format!(" (at {w})"));
        Err(SolverError::new(kind, SolverErrorKind::Panicked(format!("{text}{at}"))))
    })
}

/// A backend behind the guard.
pub(crate) struct Guarded(pub(crate) Box<dyn Solver + Send + Sync>);

impl Solver for Guarded {
    fn kind(&self) -> SolverKind {
        self.0.kind()
    }

    fn version(&self) -> String {
        self.0.version()
    }

    fn capabilities(&self) -> Capabilities {
        self.0.capabilities()
    }

    fn solve(&self, model: &Model, options: &SolveOptions) -> Result<SolveResult, SolverError> {
        guard(self.kind(), || self.0.solve(model, options))
    }

    fn solve_lazy(
        &self,
        model: &Model,
        separator: &mut dyn Separator,
        options: &SolveOptions,
    ) -> Result<LazySolve, SolverError> {
        guard(self.kind(), || self.0.solve_lazy(model, separator, options))
    }

    fn lp_session(&self, model: &Model, options: &SolveOptions) -> Result<Option<Box<dyn LpSession>>, SolverError> {
        let kind = self.kind();
        let inner = guard(kind, || self.0.lp_session(model, options))?;
        Ok(inner.map(|s| Box::new(GuardedLp { kind, inner: s }) as Box<dyn LpSession>))
    }

    fn strategy_hints(&self, hints: &StrategyHints) -> Vec<RawParam> {
        self.0.strategy_hints(hints)
    }
}

/// A backend's loaded LP behind the guard.
struct GuardedLp {
    kind: SolverKind,
    inner: Box<dyn LpSession>,
}

impl LpSession for GuardedLp {
    fn add_rows(&mut self, rows: &[LazyRow]) -> Result<(), SolverError> {
        guard(self.kind, || self.inner.add_rows(rows))
    }

    fn solve(&mut self, time_limit: Option<f64>) -> Result<SolveResult, SolverError> {
        guard(self.kind, || self.inner.solve(time_limit))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A backend whose library panics.
    struct Panics;

    impl Solver for Panics {
        fn kind(&self) -> SolverKind {
            SolverKind::Microlp
        }
        fn version(&self) -> String {
            "0".into()
        }
        fn capabilities(&self) -> Capabilities {
            SolverKind::Microlp.instance().expect("microlp is always compiled").capabilities()
        }
        fn solve(&self, _: &Model, _: &SolveOptions) -> Result<SolveResult, SolverError> {
            panic!("coefficient is infinite")
        }
    }

    #[test]
    fn a_panic_in_a_backend_becomes_an_error_naming_it() {
        let g = Guarded(Box::new(Panics));
        let e = g.solve(&Model::new("m"), &SolveOptions::default()).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("microlp") && text.contains("coefficient is infinite") && text.contains("guard.rs"),
            "{text}"
        );
        // The thread is fine afterwards, and panics outside a guard still reach the old hook.
        assert_eq!(DEPTH.with(Cell::get), 0);
    }
}
