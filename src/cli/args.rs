//! The flags every command that solves shares, as a [`Settings`] layer.

use clap::Args;
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::solvers::{LogTarget, RawParam};
use std::path::PathBuf;

/// Options shared by every command that solves.
#[derive(Args, Clone, Default)]
pub struct SolveArgs {
    /// Backend: highs, cbc, scip, microlp or good_lp (default: the embedded HiGHS); for `solve`,
    /// also a search without a solver: heuristic (construction and local search) or anneal (the
    /// paper's stochastic search).
    #[arg(long, value_name = "NAME")]
    pub solver: Option<Method>,
    /// Wall-clock time limit in seconds.
    #[arg(long, value_name = "SECONDS")]
    pub time_limit: Option<f64>,
    /// Relative MIP gap at which to stop.
    #[arg(long, value_name = "REL")]
    pub gap: Option<f64>,
    /// Absolute MIP gap at which to stop.
    #[arg(long, value_name = "ABS")]
    pub abs_gap: Option<f64>,
    /// Number of threads.
    #[arg(long)]
    pub threads: Option<u32>,
    /// Random seed.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Branch-and-bound node limit.
    #[arg(long)]
    pub node_limit: Option<u64>,
    /// Show the solver's own log on stdout.
    #[arg(long, conflicts_with = "log_file")]
    pub verbose: bool,
    /// Write the solver's own log to this file.
    #[arg(long, value_name = "PATH")]
    pub log_file: Option<PathBuf>,
    /// A solver's own parameter, passed through: `highs.mip_heuristic_effort=0.3`,
    /// `scip.limits/nodes=1000`, `cbc.cuts=off` (repeatable; each backend takes its own).
    #[arg(long = "param", value_name = "BACKEND.NAME=VALUE")]
    pub params: Vec<RawParam>,
    /// Write the solution found (`name value` per variable) to this file; with `solve --relax`,
    /// the LP relaxation's point after the cut rounds.
    #[arg(long, value_name = "FILE.sol")]
    pub sol: Option<PathBuf>,
}

impl SolveArgs {
    /// The flags as a settings layer (checked by the library with the flags' names).
    pub fn settings(&self) -> Settings {
        Settings {
            method: self.solver,
            time_limit: self.time_limit,
            gap: self.gap,
            abs_gap: self.abs_gap,
            threads: self.threads,
            seed: self.seed,
            node_limit: self.node_limit,
            log: match (&self.log_file, self.verbose) {
                (Some(p), _) => Some(LogTarget::File(p.clone())),
                (None, true) => Some(LogTarget::Stdout),
                (None, false) => None,
            },
            params: self.params.clone(),
        }
    }
}
