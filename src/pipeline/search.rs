//! The design methods as solver choices: a MILP backend, the heuristic, or the paper's
//! stochastic search ([`Method`]), and for the two searches a result record with the same
//! shape and the same independent checks as a MILP solve's [`super::DesignResult`]:
//! the validator, the objective recomputed from the design, and the MILP checker on the design
//! encoded as a point of the formulation (as a MIP start would be, [`super::prepare_start`]).
//! `netspec solve --solver heuristic|anneal` writes it as `result.json`, and `netspec compare`
//! reads it like any other run.

use super::outcome::{Outcome, SearchDetails};
use super::result::{
    active_edge_pairs, design_point, design_violations, rooms_result, DesignResult, Validity, DESIGN_SCHEMA_VERSION,
};
use crate::design::{Metrics, Objective};
use crate::formulations::Formulation;
use crate::heuristics::{self, AnnealOptions, Inputs, Options, SearchOutput, Stop};
use crate::solvers::{LimitKind, SolverKind, Termination};
use crate::spec::Problem;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// How a design is found: a MILP backend, or one of the searches of [`crate::heuristics`].
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(untagged)]
pub enum Method {
    /// The network IP on a MILP backend.
    Milp(SolverKind),
    /// A search without a solver.
    Search(SearchMethod),
}

/// The searches that are not MILP backends.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SearchMethod {
    /// Construction and local search ([`crate::heuristics::heuristic`]).
    Heuristic,
    /// The paper's stochastic search ([`crate::heuristics::anneal`]).
    Anneal,
}

impl SearchMethod {
    /// The name used on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            SearchMethod::Heuristic => "heuristic",
            SearchMethod::Anneal => "anneal",
        }
    }
}

impl Method {
    /// The name used on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            Method::Milp(k) => k.name(),
            Method::Search(s) => s.name(),
        }
    }

    /// The backend, when this is a MILP method.
    pub fn milp(self) -> Option<SolverKind> {
        match self {
            Method::Milp(k) => Some(k),
            Method::Search(_) => None,
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "heuristic" => Ok(Method::Search(SearchMethod::Heuristic)),
            "anneal" => Ok(Method::Search(SearchMethod::Anneal)),
            _ => s.parse::<SolverKind>().map(Method::Milp).map_err(|e| format!("{e}, or a search: heuristic, anneal")),
        }
    }
}

/// A search's record (`result.json`): a [`DesignResult`] whose `solve` describes the search.
pub type SearchResult = DesignResult;

/// Runs a search on a built formulation (its path sets and placements are the ones the design
/// uses) and checks its design like a solver's. The heuristic runs `threads` searches side by
/// side ([`Options::threads`]); the stochastic search always runs on one thread.
pub fn run_search(
    p: &Problem,
    f: &Formulation,
    method: SearchMethod,
    time_limit: f64,
    seed: u64,
    threads: usize,
) -> SearchResult {
    let t0 = Instant::now();
    let inputs =
        Inputs { paths: f.path_sets.as_ref(), placements: f.placements.as_ref().map(|r| r.placements.as_slice()) };
    let output = match method {
        SearchMethod::Heuristic => {
            heuristics::heuristic(p, &inputs, &Options { time_limit, seed, threads, ..Options::default() })
        }
        SearchMethod::Anneal => {
            heuristics::anneal(p, &inputs, &AnnealOptions { time_limit, seed, ..AnnealOptions::default() })
        }
    };
    record(p, f, method, seed, output, t0)
}

/// The record of a search's output, with the independent checks.
pub fn record(
    p: &Problem,
    f: &Formulation,
    method: SearchMethod,
    seed: u64,
    output: SearchOutput,
    t0: Instant,
) -> SearchResult {
    let mut validity = Validity {
        valid: false,
        design_violations: Vec::new(),
        milp_check: None,
        objective_recomputed: None,
        objective_agrees: None,
    };
    let (mut metrics, mut objective) = (None, None);
    if let Some(net) = &output.network {
        validity.design_violations = design_violations(p, f, net);
        let obj = Objective::of(p, net);
        validity.objective_recomputed = Some(obj.total);
        validity.objective_agrees = output.objective.map(|o| crate::milp::objectives_agree(o, obj.total, 1e-6));
        // The design as a point of the formulation, checked row by row (and against the lazy
        // rows), exactly as a MIP start is.
        let point = design_point(f, p, net).ok();
        let point_ok = point.as_ref().is_some_and(|cp| cp.check.is_feasible() && cp.lazy_violations == 0);
        validity.milp_check = point.map(|cp| cp.check);
        validity.valid = validity.design_violations.is_empty() && point_ok && validity.objective_agrees == Some(true);
        metrics = Some(Metrics::of(p, net));
        objective = Some(obj);
    }
    let active_edges = active_edge_pairs(p, output.network.as_ref());
    let rooms = rooms_result(p, f, output.network.as_ref());
    let termination = match output.stop {
        Stop::TimeLimit => Termination::Limit(LimitKind::Time),
        Stop::Exhausted => Termination::Limit(LimitKind::Other),
        Stop::Infeasible => Termination::Infeasible,
    };
    DesignResult {
        schema: "netspec.design".into(),
        schema_version: DESIGN_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        spec: p.spec.clone(),
        mesh: p.mesh.clone(),
        sinks: p.mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| v.0).collect(),
        active_edges,
        design_found: output.network.is_some(),
        metrics,
        objective,
        validity,
        solve: Outcome::of_search(
            method.name(),
            termination,
            output.objective,
            (output.seconds, t0.elapsed().as_secs_f64()),
            SearchDetails {
                infeasible_because: output.infeasible.clone(),
                seed,
                first_design_seconds: output.trace.first().map(|t| t.seconds),
                trace: output.trace,
                stats: output.stats,
            },
        ),
        network: output.network,
        model_stats: f.model.stats(),
        families: f.families.clone(),
        formulation: f.recipe.label.clone(),
        big_m: f.big_m,
        lazy: None,
        split: None,
        lns: None,
        lattice: None,
        solver_hints: Vec::new(),
        start: None,
        path_sets: f.path_sets.clone(),
        rooms,
        primal_point: None,
    }
}
