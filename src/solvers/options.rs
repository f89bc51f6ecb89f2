//! Solve options and backend capabilities.

use super::SolverErrorKind;
use serde::{Deserialize, Serialize};
use std::path::PathBuf;
use std::sync::Arc;

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
    /// [`SolveOptions::progress`]: reports incumbent, bound and nodes while solving.
    #[serde(default)]
    pub reports_progress: bool,
    /// Lazy rows are separated inside the solver's own branch and cut (a callback); without
    /// it, [`crate::solvers::Solver::solve_lazy`] runs the solve–separate–resolve loop.
    #[serde(default)]
    pub lazy_constraints: bool,
}

fn unsupported(option: &'static str, reason: &str) -> SolverErrorKind {
    SolverErrorKind::Unsupported { option, reason: reason.to_string() }
}

impl Capabilities {
    /// Checks that every option set in `o` is supported; also rejects meaningless values
    /// (negative or NaN limits, zero threads).
    pub fn check(&self, o: &SolveOptions) -> Result<(), SolverErrorKind> {
        if let Some(t) = o.time_limit {
            if !self.time_limit {
                return Err(unsupported("time_limit", "the backend has no time limit"));
            }
            if t.is_nan() || t < 0.0 {
                return Err(SolverErrorKind::Rejected(format!("time_limit must be ≥ 0 seconds, got {t}")));
            }
        }
        for (name, g, ok) in [("rel_gap", o.rel_gap, self.rel_gap), ("abs_gap", o.abs_gap, self.abs_gap)] {
            if let Some(g) = g {
                if !ok {
                    return Err(unsupported(name, "the backend has no such gap limit"));
                }
                if g.is_nan() || g < 0.0 {
                    return Err(SolverErrorKind::Rejected(format!("{name} must be ≥ 0, got {g}")));
                }
            }
        }
        match o.threads {
            Some(0) => return Err(SolverErrorKind::Rejected("threads must be ≥ 1".into())),
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
            LogTarget::Stdout if !self.log_stdout => return Err(unsupported("log", "the backend cannot print its log")),
            LogTarget::File(_) if !self.log_file => return Err(unsupported("log", "the backend cannot write a log file")),
            _ => {}
        }
        if o.progress.is_some() && !self.reports_progress {
            return Err(unsupported("progress", "the backend reports no progress while solving"));
        }
        if o.mip_start.is_some() && !self.mip_start {
            return Err(unsupported("mip_start", "the backend does not accept a starting solution"));
        }
        Ok(())
    }
}
