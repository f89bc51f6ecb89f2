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

/// Where a command's solves run.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ExecutorKind {
    /// Child processes on this machine.
    #[default]
    Local,
    /// Jobs on a Slurm cluster (see docs/cluster.md).
    Slurm,
}

/// The executor flags `compare` and `city` share.
#[derive(Args, Clone, Default)]
pub struct ExecutorArgs {
    /// Where the solves run: `local` (this machine) or `slurm` (jobs on a Slurm cluster, found
    /// through SLURM_CONF or the site's configuration; see docs/cluster.md).
    #[arg(long, value_enum, default_value_t = ExecutorKind::Local)]
    pub executor: ExecutorKind,
    /// Slurm partition (default: the cluster's).
    #[arg(long, value_name = "NAME")]
    pub slurm_partition: Option<String>,
    /// Slurm account (default: yours).
    #[arg(long, value_name = "NAME")]
    pub slurm_account: Option<String>,
    /// Memory per Slurm job, in Slurm's notation.
    #[arg(long, value_name = "SIZE", default_value = "4G")]
    pub slurm_mem: String,
    /// Seconds added to each Slurm job's time limit for start-up and writing outputs.
    #[arg(long, value_name = "SECONDS", default_value_t = 120.0)]
    pub slurm_startup: f64,
    /// A further sbatch argument, passed as given (repeatable: `--slurm-arg=--qos=long`).
    #[arg(long = "slurm-arg", value_name = "ARG", allow_hyphen_values = true)]
    pub slurm_args: Vec<String>,
}

impl ExecutorArgs {
    /// The Slurm options, or `None` for the local executor; Slurm flags without
    /// `--executor slurm` are an error.
    pub fn slurm(&self) -> anyhow::Result<Option<netspec::slurm::SlurmOptions>> {
        if self.executor == ExecutorKind::Local {
            let given = self.slurm_partition.is_some()
                || self.slurm_account.is_some()
                || !self.slurm_args.is_empty()
                || self.slurm_mem != "4G"
                || self.slurm_startup != 120.0;
            anyhow::ensure!(!given, "the --slurm-* flags need --executor slurm");
            return Ok(None);
        }
        anyhow::ensure!(
            self.slurm_startup.is_finite() && self.slurm_startup >= 0.0,
            "--slurm-startup must be a number of seconds ≥ 0, got {}",
            self.slurm_startup
        );
        Ok(Some(netspec::slurm::SlurmOptions {
            partition: self.slurm_partition.clone(),
            account: self.slurm_account.clone(),
            mem: self.slurm_mem.clone(),
            startup: self.slurm_startup,
            extra: self.slurm_args.clone(),
        }))
    }
}

/// `x0,y0,x1,y1` as four finite numbers with `x0 < x1`, `y0 < y1`.
pub fn parse_window(s: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> =
        s.split(',').map(|x| x.trim().parse::<f64>()).collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    match v[..] {
        [x0, y0, x1, y1] if v.iter().all(|x| x.is_finite()) && x0 < x1 && y0 < y1 => Ok([x0, y0, x1, y1]),
        _ => Err(format!("expected x0,y0,x1,y1 with x0 < x1 and y0 < y1 (metres), got `{s}`")),
    }
}
