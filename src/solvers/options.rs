//! Solve options and backend capabilities.

use super::{SolverErrorKind, SolverKind};
use crate::milp::NumericLimits;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

/// A request to stop a running solve early (Ctrl-C, a stop button), shared between the caller
/// and the solve. Cloning gives another handle to the same request. A backend that honours it
/// ([`Capabilities::interrupt`]) stops as soon as it can and returns its best point so far,
/// with termination [`LimitKind::Interrupt`](super::LimitKind::Interrupt); one already triggered
/// when a solve starts makes the solve return at once.
#[derive(Clone, Debug, Default)]
pub struct Interrupt(Arc<AtomicBool>);

impl Interrupt {
    /// A request not yet made.
    pub fn new() -> Self {
        Self::default()
    }

    /// Makes the request (from any thread, or a signal handler's thread).
    pub fn trigger(&self) {
        self.0.store(true, Ordering::SeqCst);
    }

    /// Whether the request was made.
    pub fn is_triggered(&self) -> bool {
        self.0.load(Ordering::SeqCst)
    }
}

impl PartialEq for Interrupt {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// A solver's own parameter, passed through unchanged: `highs.mip_heuristic_effort=0.3`,
/// `scip.limits/nodes=100`, `cbc.cuts=off`. The part before the first `.` names the backend;
/// a backend applies only its own parameters (so one list can serve several backends, as in
/// `compare`) and refuses an unknown name or a bad value with
/// [`SolverErrorKind::Param`].
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct RawParam {
    /// The backend the parameter belongs to.
    pub solver: SolverKind,
    /// The solver's own name for it.
    pub name: String,
    /// Its value, as text (parsed by the backend by the parameter's type).
    pub value: String,
}

impl std::fmt::Display for RawParam {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}.{}={}", self.solver, self.name, self.value)
    }
}

impl std::str::FromStr for RawParam {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let form = "expected BACKEND.NAME=VALUE, e.g. highs.mip_heuristic_effort=0.3";
        let (key, value) = s.split_once('=').ok_or_else(|| format!("`{s}`: {form}"))?;
        let (solver, name) = key.split_once('.').ok_or_else(|| format!("`{s}`: {form}"))?;
        let solver: SolverKind = solver.trim().parse().map_err(|e| format!("`{s}`: {e}"))?;
        let (name, value) = (name.trim(), value.trim());
        if name.is_empty() || name.contains('\0') || value.contains('\0') {
            return Err(format!("`{s}`: {form}"));
        }
        Ok(RawParam { solver, name: name.to_string(), value: value.to_string() })
    }
}

/// The most threads a solve may ask for (a backend given far more threads than cores can spend
/// minutes starting them).
pub const MAX_THREADS: u32 = 256;

/// An option value netspec refuses before any backend sees it: which option, and why.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("`{option}` {reason}")]
pub struct InvalidOption {
    /// The [`SolveOptions`] field.
    pub option: &'static str,
    /// What is wrong, e.g. `must be ≥ 0, got -1`.
    pub reason: String,
}

/// A snapshot of a running solve, for progress displays.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Seconds since the solver started.
    pub elapsed: f64,
    /// Best objective found so far (model sense), if any.
    pub primal: Option<f64>,
    /// Best proven bound so far, if any.
    pub dual: Option<f64>,
    /// Branch-and-bound nodes so far.
    pub nodes: u64,
}

/// Receives [`Progress`] reports during a solve, from the solver's thread, at most about four
/// times a second. Only backends whose [`Capabilities::reports_progress`] is set accept one.
#[derive(Clone)]
pub struct ProgressSink(pub Arc<dyn Fn(Progress) + Send + Sync>);

impl std::fmt::Debug for ProgressSink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("ProgressSink")
    }
}

impl PartialEq for ProgressSink {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Receives every improving point a backend finds while it solves: the point's objective (in
/// the model's sense) and one value per variable, from the solver's thread. Only backends whose
/// [`Capabilities::reports_progress`] is set call it.
#[derive(Clone)]
pub struct PointSink(pub Arc<PointFn>);

/// What a [`PointSink`] calls: objective, then the point.
pub type PointFn = dyn Fn(f64, &[f64]) + Send + Sync;

impl std::fmt::Debug for PointSink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("PointSink")
    }
}

impl PartialEq for PointSink {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

/// Where the solver's own log goes.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LogTarget {
    /// No solver output.
    #[default]
    Quiet,
    /// The solver's log on standard output.
    Stdout,
    /// The solver's log written to a file.
    File(PathBuf),
}

/// Options for one solve. `None` means "the solver's default". Every option that is set must be
/// honoured by the backend, or the solve fails with [`SolverErrorKind::Unsupported`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SolveOptions {
    /// Wall-clock time limit in seconds.
    pub time_limit: Option<f64>,
    /// Relative MIP gap at which to stop (e.g. `1e-4`).
    pub rel_gap: Option<f64>,
    /// Absolute MIP gap at which to stop.
    pub abs_gap: Option<f64>,
    /// Number of threads.
    pub threads: Option<u32>,
    /// Random seed.
    pub seed: Option<u64>,
    /// Branch-and-bound node limit.
    pub node_limit: Option<u64>,
    /// Where the solver's log goes.
    pub log: LogTarget,
    /// A full starting point for the MIP (one value per variable, in [`crate::milp::VarId`]
    /// order). The solver may reject it if infeasible.
    pub mip_start: Option<Vec<f64>>,
    /// Progress reports while the solve runs (not serialised).
    #[serde(skip)]
    pub progress: Option<ProgressSink>,
    /// Every improving point while the solve runs (not serialised).
    #[serde(skip)]
    pub incumbents: Option<PointSink>,
    /// Solver parameters passed through as they are (see [`RawParam`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub params: Vec<RawParam>,
    /// A request to stop early (not serialised).
    #[serde(skip)]
    pub interrupt: Option<Interrupt>,
}

impl SolveOptions {
    /// Checks every value, naming the option: limits and gaps must be numbers ≥ 0 (an infinite
    /// time limit means none), threads ≥ 1.
    pub fn validate(&self) -> Result<(), InvalidOption> {
        let bad = |option, reason: String| Err(InvalidOption { option, reason });
        if let Some(t) = self.time_limit {
            if t.is_nan() || t < 0.0 {
                return bad("time_limit", format!("must be a number of seconds ≥ 0 (or inf for none), got {t}"));
            }
        }
        for (option, g) in [("rel_gap", self.rel_gap), ("abs_gap", self.abs_gap)] {
            if let Some(g) = g {
                if !g.is_finite() || g < 0.0 {
                    return bad(option, format!("must be a finite number ≥ 0, got {g}"));
                }
            }
        }
        match self.threads {
            Some(0) => return bad("threads", "must be ≥ 1, got 0".into()),
            Some(t) if t > MAX_THREADS => return bad("threads", format!("must be at most {MAX_THREADS}, got {t}")),
            _ => {}
        }
        Ok(())
    }

    /// The time limit if it is finite (an infinite one means no limit).
    pub fn finite_time_limit(&self) -> Option<f64> {
        self.time_limit.filter(|t| t.is_finite())
    }

    /// How many searches the construction heuristic runs side by side for this solve's MIP start:
    /// [`SolveOptions::threads`] (the solve's threads are idle until the start is handed over),
    /// one when no thread count is given.
    pub fn heuristic_threads(&self) -> usize {
        self.threads.map_or(1, |t| t.max(1) as usize)
    }

    /// The raw parameters meant for `kind`.
    pub fn params_for(&self, kind: SolverKind) -> impl Iterator<Item = &RawParam> + '_ {
        self.params.iter().filter(move |p| p.solver == kind)
    }
}

/// Whether a backend supports an option, and how.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Capabilities {
    /// Integer and binary variables.
    pub integer_variables: bool,
    /// [`SolveOptions::time_limit`].
    pub time_limit: bool,
    /// The time limit is rounded up to whole seconds by the solver.
    pub time_limit_whole_seconds: bool,
    /// [`SolveOptions::rel_gap`].
    pub rel_gap: bool,
    /// [`SolveOptions::abs_gap`].
    pub abs_gap: bool,
    /// [`SolveOptions::threads`] (more than one thread).
    pub threads: bool,
    /// [`SolveOptions::seed`].
    pub seed: bool,
    /// [`SolveOptions::node_limit`].
    pub node_limit: bool,
    /// [`LogTarget::Stdout`].
    pub log_stdout: bool,
    /// [`LogTarget::File`].
    pub log_file: bool,
    /// [`SolveOptions::mip_start`].
    pub mip_start: bool,
    /// The result carries a dual bound.
    pub reports_dual_bound: bool,
    /// The result carries a node count.
    pub reports_nodes: bool,
    /// The result carries the solver's own run time.
    pub reports_solver_time: bool,
    /// [`SolveOptions::progress`]: reports incumbent, bound and nodes while solving, and
    /// [`SolveOptions::incumbents`]: hands over every improving point.
    #[serde(default)]
    pub reports_progress: bool,
    /// Lazy rows are separated inside the solver's own branch and cut (a callback); without
    /// it, [`crate::solvers::Solver::solve_lazy`] runs the solve–separate–resolve loop.
    #[serde(default)]
    pub lazy_constraints: bool,
    /// [`SolveOptions::interrupt`]: stops early on request, keeping the best point found.
    #[serde(default)]
    pub interrupt: bool,
    /// [`SolveOptions::params`]: the solver's own parameters, passed through.
    #[serde(default)]
    pub raw_params: bool,
    /// The magnitudes it loads ([`crate::milp::numeric`]): coefficients at or above its limits
    /// are refused before it sees the model; finite bounds at or above its infinity are passed
    /// with a warning.
    pub numeric: NumericLimits,
}

fn unsupported(option: &'static str, reason: &str) -> SolverErrorKind {
    SolverErrorKind::Unsupported { option, reason: reason.to_string() }
}

impl Capabilities {
    /// Checks that every option set in `o` is supported by the backend `kind` (values are
    /// checked by [`SolveOptions::validate`] first).
    pub fn check(&self, kind: SolverKind, o: &SolveOptions) -> Result<(), SolverErrorKind> {
        o.validate()?;
        if o.finite_time_limit().is_some() && !self.time_limit {
            return Err(unsupported("time_limit", "the backend has no time limit"));
        }
        for (name, g, ok) in [("rel_gap", o.rel_gap, self.rel_gap), ("abs_gap", o.abs_gap, self.abs_gap)] {
            if g.is_some() && !ok {
                return Err(unsupported(name, "the backend has no such gap limit"));
            }
        }
        match o.threads {
            Some(t) if t > 1 && !self.threads => return Err(unsupported("threads", "the backend is single-threaded")),
            _ => {}
        }
        if o.seed.is_some() && !self.seed {
            return Err(unsupported("seed", "the backend has no random seed"));
        }
        if o.node_limit.is_some() && !self.node_limit {
            return Err(unsupported("node_limit", "the backend has no node limit"));
        }
        match &o.log {
            LogTarget::Stdout if !self.log_stdout => {
                return Err(unsupported("log", "the backend cannot print its log"))
            }
            LogTarget::File(_) if !self.log_file => {
                return Err(unsupported("log", "the backend cannot write a log file"))
            }
            _ => {}
        }
        if o.progress.is_some() && !self.reports_progress {
            return Err(unsupported("progress", "the backend reports no progress while solving"));
        }
        if o.incumbents.is_some() && !self.reports_progress {
            return Err(unsupported("incumbents", "the backend reports no incumbents while solving"));
        }
        if o.mip_start.is_some() && !self.mip_start {
            return Err(unsupported("mip_start", "the backend does not accept a starting solution"));
        }
        if o.interrupt.is_some() && !self.interrupt {
            return Err(unsupported("interrupt", "the backend cannot be stopped while it runs"));
        }
        if o.params_for(kind).next().is_some() && !self.raw_params {
            return Err(unsupported("params", "the backend has no parameters of its own to pass through"));
        }
        Ok(())
    }
}
