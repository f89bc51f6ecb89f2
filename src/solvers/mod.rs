//! MILP backends behind one small trait.
//!
//! Every backend lives in its own file behind a cargo feature named after the solver. A solve
//! returns a [`SolveResult`] that says *why* the solver stopped ([`Termination`]) separately from
//! *whether* it has a solution: infeasible is a result, not an `Err`. An `Err` means the solve
//! could not be attempted (an option the backend cannot honour, a model the backend rejects).

#[cfg(feature = "cbc")]
pub mod cbc;
#[cfg(feature = "good_lp")]
pub mod good_lp_bridge;
#[cfg(feature = "highs")]
pub mod highs;
#[cfg(feature = "microlp")]
pub mod microlp;
#[cfg(feature = "scip")]
pub mod scip;
#[cfg(feature = "scip")]
mod scip_lazy;
#[cfg(feature = "scip")]
mod scip_live;

mod guard;
pub mod lattice;
pub mod lazy;
mod options;
mod result;
pub mod split;
mod stop;

pub use lazy::{LazyMode, LazyReport, LazyRow, LazySolve, Lock, Separator};
pub use options::{
    Capabilities, Interrupt, InvalidOption, LogTarget, PointSink, Progress, ProgressSink, RawParam, SolveOptions,
    MAX_THREADS,
};
pub use result::{
    finished, gap, percent, status_line, within_optimality_tolerance, LimitKind, SolveResult, StartCheck, Termination,
    OPTIMALITY_TOLERANCE,
};

use crate::milp::{check_point, Model, Tolerances};
use serde::{Deserialize, Serialize};
use std::borrow::Cow;
use std::time::Instant;
use stop::StopControl;

/// A MILP backend.
pub trait Solver {
    /// Which backend this is.
    fn kind(&self) -> SolverKind;
    /// The underlying solver's version string (e.g. `1.11.0`).
    fn version(&self) -> String;
    /// What options and results the backend supports.
    fn capabilities(&self) -> Capabilities;
    /// Solves `model`. Returns `Err` only when the solve cannot be attempted: an option the
    /// backend cannot honour ([`SolverErrorKind::Unsupported`]) or a model it rejects.
    fn solve(&self, model: &Model, options: &SolveOptions) -> Result<SolveResult, SolverError>;
    /// Solves `model` together with the rows `separator` produces on demand. Backends with
    /// [`Capabilities::lazy_constraints`] run the separator inside their branch and cut; the
    /// default is the solve–separate–resolve loop [`lazy::solve_loop`].
    fn solve_lazy(
        &self,
        model: &Model,
        separator: &mut dyn Separator,
        options: &SolveOptions,
    ) -> Result<LazySolve, SolverError> {
        lazy::solve_loop(self, model, separator, options)
    }
    /// An LP `model` (every variable continuous) loaded once for repeated solves, rows added
    /// between them and each solve starting from the last one's basis: the cutting-plane
    /// rounds at the root ([`lazy::solve_loop`]) use it. `None` when the backend cannot keep
    /// a basis between solves (the default), or not for this model (HiGHS: one without
    /// columns); the rounds then solve each LP from scratch with
    /// [`Solver::solve`]. Only `threads` of `options` is used.
    fn lp_session(&self, _model: &Model, _options: &SolveOptions) -> Result<Option<Box<dyn LpSession>>, SolverError> {
        Ok(None)
    }
    /// The backend's own parameters for a solve strategy ([`StrategyHints`]): settings measured
    /// to help on netspec's models, handed over before the user's parameters (a parameter the
    /// user sets by the same name replaces its hint). The default: none.
    fn strategy_hints(&self, _hints: &StrategyHints) -> Vec<RawParam> {
        Vec::new()
    }
}

/// What a solve strategy asks of a backend's own settings ([`Solver::strategy_hints`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StrategyHints {
    /// Use the settings measured on the model's recipe.
    pub tuned: bool,
    /// Use the backend's parallel tree search when `threads` ≥ 2.
    pub parallel_search: bool,
    /// The solve's thread count.
    pub threads: Option<u32>,
    /// Keep the model's symmetry visible to the backend (its presolve may break it first).
    pub keep_symmetry: bool,
}

/// An LP kept loaded in a backend between solves ([`Solver::lp_session`]).
pub trait LpSession {
    /// Adds rows (every term on a column of the session's model).
    fn add_rows(&mut self, rows: &[LazyRow]) -> Result<(), SolverError>;
    /// Solves the LP as it stands, from the last basis, within `time_limit` seconds. The
    /// result is the LP's: termination, point and objective (its own bound when optimal).
    fn solve(&mut self, time_limit: Option<f64>) -> Result<SolveResult, SolverError>;
}

/// The backends known to netspec (compiled in or not).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SolverKind {
    /// HiGHS, embedded (built from source by `highs-sys`).
    Highs,
    /// COIN-OR CBC, linked from the Debian package.
    Cbc,
    /// SCIP 10, linked from the pyscipopt wheel's shared library.
    Scip,
    /// microlp, pure Rust.
    Microlp,
    /// good_lp's solver selection (the good_lp bridge).
    GoodLp,
}

impl SolverKind {
    /// Every backend, in a fixed order.
    pub const ALL: [SolverKind; 5] =
        [SolverKind::Highs, SolverKind::Cbc, SolverKind::Scip, SolverKind::Microlp, SolverKind::GoodLp];

    /// The name used on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            SolverKind::Highs => "highs",
            SolverKind::Cbc => "cbc",
            SolverKind::Scip => "scip",
            SolverKind::Microlp => "microlp",
            SolverKind::GoodLp => "good_lp",
        }
    }

    /// The cargo feature that compiles this backend in.
    pub fn feature(self) -> &'static str {
        self.name()
    }

    /// Whether this backend was compiled in.
    pub fn is_compiled(self) -> bool {
        match self {
            SolverKind::Highs => cfg!(feature = "highs"),
            SolverKind::Cbc => cfg!(feature = "cbc"),
            SolverKind::Scip => cfg!(feature = "scip"),
            SolverKind::Microlp => cfg!(feature = "microlp"),
            SolverKind::GoodLp => cfg!(feature = "good_lp"),
        }
    }

    /// The compiled backends, in a fixed order.
    pub fn compiled() -> Vec<SolverKind> {
        Self::ALL.into_iter().filter(|k| k.is_compiled()).collect()
    }

    /// The default backend: HiGHS when compiled in (it is embedded), else the first compiled.
    pub fn default_kind() -> Option<SolverKind> {
        Self::compiled().into_iter().next()
    }

    /// An instance of this backend, or an error if it was not compiled in.
    pub fn instance(self) -> Result<Box<dyn Solver + Send + Sync>, SolverError> {
        let inner: Box<dyn Solver + Send + Sync> = match self {
            #[cfg(feature = "highs")]
            SolverKind::Highs => Box::new(highs::HighsSolver),
            #[cfg(feature = "cbc")]
            SolverKind::Cbc => Box::new(cbc::CbcSolver),
            #[cfg(feature = "scip")]
            SolverKind::Scip => Box::new(scip::ScipSolver),
            #[cfg(feature = "microlp")]
            SolverKind::Microlp => Box::new(microlp::MicrolpSolver),
            #[cfg(feature = "good_lp")]
            SolverKind::GoodLp => Box::new(good_lp_bridge::GoodLpSolver),
            #[allow(unreachable_patterns)]
            other => return Err(SolverError::new(other, SolverErrorKind::NotCompiled)),
        };
        // A panic inside a backend's library becomes an error naming it.
        Ok(Box::new(guard::Guarded(inner)))
    }
}

impl std::fmt::Display for SolverKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for SolverKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL
            .into_iter()
            .find(|k| {
                k.name().eq_ignore_ascii_case(s) || (s.eq_ignore_ascii_case("good-lp") && *k == SolverKind::GoodLp)
            })
            .ok_or_else(|| {
                let names: Vec<_> = Self::ALL.iter().map(|k| k.name()).collect();
                format!("unknown solver `{s}` (known: {})", names.join(", "))
            })
    }
}

/// Why a solve could not be attempted.
#[derive(Debug, thiserror::Error)]
pub enum SolverErrorKind {
    /// The backend was not compiled in.
    #[error("backend not compiled in (enable the cargo feature)")]
    NotCompiled,
    /// The backend cannot honour an option that was set.
    #[error("option `{option}` is not supported: {reason}")]
    Unsupported {
        /// The option's name, as in [`SolveOptions`].
        option: &'static str,
        /// Why, in a few words.
        reason: String,
    },
    /// An option's value is unusable (checked by netspec before any backend sees it).
    #[error("invalid option {0}")]
    InvalidOption(#[from] InvalidOption),
    /// A solver parameter passed through ([`RawParam`]) that the backend does not know, or
    /// whose value it refuses.
    #[error("parameter `{name}`: {reason}")]
    Param {
        /// The parameter as given (`highs.mip_rel_gap`).
        name: String,
        /// The backend's reason.
        reason: String,
    },
    /// The model is invalid (see [`Model::validate`]).
    #[error("invalid model: {0}")]
    InvalidModel(#[from] crate::milp::ModelError),
    /// The model has a feature this backend cannot represent (e.g. integers on an LP-only
    /// solver).
    #[error("model not supported: {0}")]
    ModelUnsupported(String),
    /// The native solver refused the model or an option.
    #[error("solver rejected the input: {0}")]
    Rejected(String),
    /// Writing the log file failed.
    #[error("log file: {0}")]
    Io(#[from] std::io::Error),
    /// A coefficient the backend cannot load ([`crate::milp::numeric`]).
    #[error("{0}")]
    Numeric(String),
    /// The backend's library panicked; netspec caught it.
    #[error("the backend failed inside its library (a panic, caught by netspec): {0}")]
    Panicked(String),
}

/// An error from a backend: which one, and what.
#[derive(Debug, thiserror::Error)]
#[error("{solver}: {kind}")]
pub struct SolverError {
    /// The backend.
    pub solver: SolverKind,
    /// What went wrong.
    #[source]
    pub kind: SolverErrorKind,
}

impl SolverError {
    /// Builds an error.
    pub fn new(solver: SolverKind, kind: impl Into<SolverErrorKind>) -> Self {
        SolverError { solver, kind: kind.into() }
    }
}

/// Validates the model and checks the options against the backend's capabilities.
pub(crate) fn preflight(
    kind: SolverKind,
    caps: &Capabilities,
    model: &Model,
    options: &SolveOptions,
) -> Result<(), SolverError> {
    model.validate().map_err(|e| SolverError::new(kind, e))?;
    caps.check(kind, options).map_err(|k| SolverError::new(kind, k))?;
    if let Some(why) = crate::milp::numeric_screen(model, &caps.numeric, kind.name()).refused {
        return Err(SolverError::new(kind, SolverErrorKind::Numeric(why)));
    }
    if model.is_mip() && !caps.integer_variables {
        return Err(SolverError::new(kind, SolverErrorKind::ModelUnsupported("integer variables".into())));
    }
    if let Some(start) = &options.mip_start {
        if start.len() != model.num_vars() {
            return Err(SolverError::new(
                kind,
                SolverErrorKind::Rejected(format!(
                    "MIP start has {} values for {} variables",
                    start.len(),
                    model.num_vars()
                )),
            ));
        }
        if let Some(j) = start.iter().position(|v| !v.is_finite()) {
            return Err(SolverError::new(
                kind,
                SolverErrorKind::Rejected(format!("MIP start value of `{}` is not finite", model.vars()[j].name)),
            ));
        }
    }
    Ok(())
}

/// Checks a MIP start with netspec's own checker: a start that fails is reported and dropped
/// from the options, never handed to the solver.
fn check_start<'a>(model: &Model, o: &'a SolveOptions) -> (Cow<'a, SolveOptions>, Option<StartCheck>) {
    let Some(start) = &o.mip_start else { return (Cow::Borrowed(o), None) };
    let report = check_point(model, start, &Tolerances::default());
    let check = StartCheck {
        accepted: report.is_feasible(),
        objective: report.objective,
        violations: report.violations.len(),
        first_violation: report.violations.first().map(|v| v.to_string()),
    };
    if check.accepted {
        (Cow::Borrowed(o), Some(check))
    } else {
        (Cow::Owned(SolveOptions { mip_start: None, ..o.clone() }), Some(check))
    }
}

/// The part of a solve every backend shares, around its native solve `native`: validation
/// ([`preflight`]), netspec's own proof of trivial infeasibility ([`crate::milp::screen`]),
/// the check of a MIP start, an interrupt already made, and the time limit as a deadline over
/// the whole call ([`StopControl`]). A solve that the control stopped from outside and that the
/// solver reports as interrupted is reported as stopped by the time limit when that is why.
pub(crate) fn guarded_solve(
    solver: &dyn Solver,
    model: &Model,
    options: &SolveOptions,
    native: impl FnOnce(&SolveOptions, &StopControl) -> Result<SolveResult, SolverError>,
) -> Result<SolveResult, SolverError> {
    let t0 = Instant::now();
    let kind = solver.kind();
    preflight(kind, &solver.capabilities(), model, options)?;
    if let Some(why) = crate::milp::screen(model) {
        let mut r = SolveResult::empty(kind, solver.version(), Termination::Infeasible);
        r.infeasibility = Some(why);
        r.nodes = Some(0);
        r.solver_time = Some(0.0);
        r.wall_time = t0.elapsed().as_secs_f64();
        return Ok(r);
    }
    let caps = solver.capabilities();
    let warnings: Vec<String> = crate::milp::numeric_screen(model, &caps.numeric, kind.name())
        .warning(kind.name(), &caps.numeric)
        .into_iter()
        .collect();
    let (o, start) = check_start(model, options);
    let ctl = StopControl::new(&o, t0);
    let mut r = if ctl.interrupted() {
        SolveResult::empty(kind, solver.version(), Termination::Limit(LimitKind::Interrupt))
    } else if model.num_vars() == 0 {
        // No column: netspec answers itself, the same for every backend (the screen above has
        // refused rows whose sides exclude 0).
        let mut r = SolveResult::empty(kind, solver.version(), Termination::Optimal);
        r.primal = Some(Vec::new());
        r.objective = Some(model.objective_value(&[]));
        r.dual_bound = r.objective;
        r.nodes = Some(0);
        r.solver_time = Some(0.0);
        r.finish(model.sense);
        r
    } else {
        native(&o, &ctl)?
    };
    r.warnings = warnings;
    if r.termination == Termination::Limit(LimitKind::Interrupt) {
        if let Some(why) = ctl.reason() {
            r.termination = Termination::Limit(why);
        }
    }
    r.mip_start = start;
    r.wall_time = t0.elapsed().as_secs_f64();
    Ok(r)
}
