//! One run's record (`run.json`): what it produced, read from the files its process left
//! ([`record_from_dir`]), and the settings that produced it ([`RunSettings`]).

use crate::pipeline::Outcome;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// One (instance, backend, seed) run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Instance name (the spec's file stem).
    pub instance: String,
    /// Backend name.
    pub solver: String,
    /// Seed (`None`: the solver's default).
    pub seed: Option<u64>,
    /// Mesh edges.
    pub edges: Option<usize>,
    /// MILP variables, rows and nonzeros.
    pub vars: Option<usize>,
    /// Rows.
    pub rows: Option<usize>,
    /// Nonzeros.
    pub nonzeros: Option<usize>,
    /// Termination label (`optimal`, `limit(time)`, …), `killed` or `failed`.
    pub status: String,
    /// Objective.
    pub objective: Option<f64>,
    /// Dual bound.
    pub dual_bound: Option<f64>,
    /// netspec's gap.
    pub gap: Option<f64>,
    /// Nodes.
    pub nodes: Option<u64>,
    /// Solver time, seconds.
    pub solver_time: Option<f64>,
    /// Wall time of the child process, seconds.
    pub wall_time: f64,
    /// The independent validity verdict.
    pub valid: bool,
    /// Whether the child was killed at limit + grace.
    pub killed: bool,
    /// The solver's version.
    pub solver_version: Option<String>,
    /// The child's exit code.
    pub exit_code: Option<i32>,
    /// The time limit this run had, seconds (with `--paper-limits`, the row's own).
    #[serde(default)]
    pub time_limit: Option<f64>,
    /// Why the run failed (`failed`: the child's error message, from its `stderr.txt`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Everything that produced this record; a rerun with other settings solves again.
    /// (`None` in records written before settings were recorded: they are always solved again.)
    #[serde(default)]
    pub settings: Option<RunSettings>,
    /// Digest of the netspec binary that ran it, for runs on a cluster (the staged copy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub binary_digest: Option<String>,
    /// The Slurm state of a cluster task that ended without a record (`TIMEOUT`, `NODE_FAIL`,
    /// `OUT_OF_MEMORY`, `CANCELLED`, `PREEMPTED`, …); such a run is solved again on resume.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slurm_state: Option<String>,
}

impl RunRecord {
    /// The record of a run that produced nothing (yet): status `failed`, no model, no outcome.
    pub fn failed(solver: &str, seed: Option<u64>, limit: f64) -> RunRecord {
        RunRecord {
            instance: String::new(),
            solver: solver.to_string(),
            seed,
            edges: None,
            vars: None,
            rows: None,
            nonzeros: None,
            status: "failed".into(),
            objective: None,
            dual_bound: None,
            gap: None,
            nodes: None,
            solver_time: None,
            wall_time: 0.0,
            valid: false,
            killed: false,
            solver_version: None,
            exit_code: None,
            time_limit: Some(limit),
            error: None,
            settings: None,
            binary_digest: None,
            slurm_state: None,
        }
    }

    /// Takes what a design run produced: the mesh's edges, the model's size, its outcome
    /// ([`RunRecord::take_outcome`]) and the independent validity verdict.
    pub fn take_design(&mut self, edges: usize, model: &crate::milp::ModelStats, outcome: &Outcome, valid: bool) {
        self.edges = Some(edges);
        self.vars = Some(model.vars);
        self.rows = Some(model.rows);
        self.nonzeros = Some(model.nonzeros);
        self.take_outcome(outcome);
        self.valid = valid;
    }

    /// Takes the run's outcome: its termination label as `status`, objective, bound, gap,
    /// nodes, solver time and the solver's version (the wall time stays the process's).
    pub fn take_outcome(&mut self, o: &Outcome) {
        self.status = o.termination.label();
        self.objective = o.objective;
        self.dual_bound = o.dual_bound;
        self.gap = o.gap;
        self.nodes = o.nodes;
        self.solver_time = o.solver_time;
        self.solver_version = Some(o.solver_version.clone());
    }
}

/// The settings that produced a run: a record is reused only when all of them are the same.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSettings {
    /// The spec file, as given.
    pub spec: PathBuf,
    /// Digest of the spec file's bytes (and of its mesh file's, if it names one).
    pub spec_digest: String,
    /// The spec's `formulation` (its TOML/JSON value as text), if it sets one.
    pub formulation: Option<String>,
    /// Backend.
    pub solver: String,
    /// Seed (`None`: the solver's default).
    pub seed: Option<u64>,
    /// Threads (`None`: the solver's default).
    pub threads: Option<u32>,
    /// Time limit, seconds.
    pub time_limit: f64,
    /// The netspec version that ran it.
    pub netspec_version: String,
    /// A MILP backend's MIP start: `heuristic` (the default) or `none` (`--no-start`); `None`
    /// for the searches, and in records made before starts existed (they run again).
    #[serde(default)]
    pub start: Option<String>,
}

impl RunSettings {
    /// The settings of one run of `spec`. A spec that cannot be read gets an empty digest (its
    /// run fails, and is tried again next time).
    pub fn new(spec: &Path, solver: &str, seed: Option<u64>, threads: Option<u32>, time_limit: f64) -> RunSettings {
        let bytes = std::fs::read(spec).unwrap_or_default();
        let text = String::from_utf8_lossy(&bytes);
        let value: Option<serde_json::Value> = if spec.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
            serde_json::from_str(&text).ok()
        } else {
            toml::from_str::<toml::Value>(&text).ok().and_then(|v| serde_json::to_value(v).ok())
        };
        let field = |path: &[&str]| path.iter().try_fold(value.as_ref()?, |v, k| v.get(*k));
        let formulation = field(&["formulation"]).map(|v| v.as_str().map_or_else(|| v.to_string(), str::to_string));
        let mesh_bytes = field(&["mesh", "file"])
            .and_then(|f| f.as_str())
            .and_then(|f| std::fs::read(spec.parent().unwrap_or(Path::new(".")).join(f)).ok())
            .unwrap_or_default();
        RunSettings {
            spec: spec.to_path_buf(),
            spec_digest: if bytes.is_empty() { String::new() } else { crate::io::digest(&[&bytes, &mesh_bytes]) },
            formulation,
            solver: solver.to_string(),
            seed,
            threads,
            time_limit,
            netspec_version: env!("CARGO_PKG_VERSION").into(),
            start: None,
        }
    }

    /// What differs from `other`, as `name old → new` phrases (empty when they match).
    pub fn changes_from(&self, other: &RunSettings) -> Vec<String> {
        let mut out = Vec::new();
        let mut diff = |name: &str, a: String, b: String| {
            if a != b {
                out.push(format!("{name} {b} → {a}"));
            }
        };
        let opt = |v: Option<String>| v.unwrap_or_else(|| "default".into());
        diff("spec", self.spec.display().to_string(), other.spec.display().to_string());
        diff("spec digest", self.spec_digest.clone(), other.spec_digest.clone());
        diff("formulation", opt(self.formulation.clone()), opt(other.formulation.clone()));
        diff("solver", self.solver.clone(), other.solver.clone());
        diff("seed", opt(self.seed.map(|s| s.to_string())), opt(other.seed.map(|s| s.to_string())));
        diff("threads", opt(self.threads.map(|s| s.to_string())), opt(other.threads.map(|s| s.to_string())));
        diff("time limit", format!("{} s", self.time_limit), format!("{} s", other.time_limit));
        diff("netspec", self.netspec_version.clone(), other.netspec_version.clone());
        diff("start", opt(self.start.clone()), opt(other.start.clone()));
        out
    }
}

/// The record of a finished run from what its process left in `dir` (`result.json`, and
/// `stderr.txt` when it failed), whoever ran it.
pub fn record_from_dir(
    dir: &Path,
    solver: &str,
    seed: Option<u64>,
    limit: f64,
    wall_time: f64,
    exit_code: Option<i32>,
    killed: bool,
) -> RunRecord {
    let result: Option<ResultView> =
        std::fs::read_to_string(dir.join("result.json")).ok().and_then(|t| serde_json::from_str(&t).ok());
    let status = if killed { "killed" } else { "failed" }.to_string();
    let mut r = RunRecord { status, wall_time, killed, exit_code, ..RunRecord::failed(solver, seed, limit) };
    match (result, killed) {
        (Some(res), false) => r.take_design(res.mesh.num_edges(), &res.model_stats, &res.solve, res.validity.valid),
        (None, false) => r.error = Some(failure_cause(dir, exit_code)),
        _ => {}
    }
    r
}

/// Why a run left no result: its `error:` line and the causes under it, from `stderr.txt`.
fn failure_cause(dir: &Path, exit_code: Option<i32>) -> String {
    let text = std::fs::read_to_string(dir.join("stderr.txt")).unwrap_or_default();
    let lines: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("error:"))
        .take_while(|l| l.starts_with("error:") || l.starts_with("  caused by:"))
        .map(|l| l.trim_start_matches("error:").trim_start_matches("  caused by:").trim())
        .collect();
    if lines.is_empty() {
        let tail = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
        format!("exit code {}: {tail}", exit_code.map_or("none".into(), |c| c.to_string()))
    } else {
        lines.join(": ")
    }
}

/// What a run record needs from a `result.json` of a MILP solve or a search.
#[derive(Deserialize)]
struct ResultView {
    mesh: crate::mesh::Mesh,
    model_stats: crate::milp::ModelStats,
    solve: Outcome,
    validity: ValidityView,
}

#[derive(Deserialize)]
struct ValidityView {
    valid: bool,
}
