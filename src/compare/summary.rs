//! Per-backend statistics of a comparison: runs proven, shifted geometric mean of time, wins.

use super::record::RunRecord;
use serde::{Deserialize, Serialize};

/// Shifted geometric mean `exp(mean(ln(t + shift))) − shift` (the MIPLIB convention).
pub fn shifted_geometric_mean(times: &[f64], shift: f64) -> f64 {
    if times.is_empty() {
        return 0.0;
    }
    (times.iter().map(|t| (t + shift).ln()).sum::<f64>() / times.len() as f64).exp() - shift
}

/// Per-backend summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BackendSummary {
    /// Backend name.
    pub solver: String,
    /// Shifted geometric mean of time (shift 10 s; runs not proven optimal charged the limit).
    pub sgm_time: f64,
    /// Runs proven optimal (gap ≤ [`PROVEN_GAP`]) or infeasible, with a valid answer where there
    /// is one.
    pub solved: usize,
    /// Runs.
    pub runs: usize,
    /// Instances where this backend was the fastest to solve.
    pub wins: usize,
}

/// The relative gap at which a run with a valid design counts as proven optimal although its
/// solver went on (the gap Table 1's target names; Gurobi's default `MIPGap`). netspec's own
/// `optimal` is stricter (see [`crate::solvers::OPTIMALITY_TOLERANCE`]).
pub const PROVEN_GAP: f64 = 1e-4;

/// Proven: infeasible, or a valid design that is optimal or within [`PROVEN_GAP`] of its bound.
pub(crate) fn solved(r: &RunRecord) -> bool {
    r.status == "infeasible" || (r.valid && (r.status == "optimal" || r.gap.is_some_and(|g| g <= PROVEN_GAP)))
}

/// Summaries per backend, in the order of `solvers`.
pub fn summarize(records: &[RunRecord], solvers: &[String], limit: f64) -> Vec<BackendSummary> {
    // Each instance once, in first-seen order (merged comparisons list a row once per source).
    let mut seen = std::collections::BTreeSet::new();
    let instances: Vec<&str> = records.iter().map(|r| r.instance.as_str()).filter(|i| seen.insert(*i)).collect();
    solvers
        .iter()
        .map(|s| {
            let mine: Vec<&RunRecord> = records.iter().filter(|r| &r.solver == s).collect();
            let times: Vec<f64> = mine
                .iter()
                .map(|r| {
                    let limit = r.time_limit.unwrap_or(limit);
                    if solved(r) {
                        r.wall_time.min(limit)
                    } else {
                        limit
                    }
                })
                .collect();
            let wins = instances
                .iter()
                .filter(|i| {
                    let best = records
                        .iter()
                        .filter(|r| r.instance == **i && solved(r))
                        .min_by(|a, b| a.wall_time.total_cmp(&b.wall_time));
                    best.is_some_and(|b| &b.solver == s)
                })
                .count();
            BackendSummary {
                solver: s.clone(),
                sgm_time: shifted_geometric_mean(&times, 10.0),
                solved: mine.iter().filter(|r| solved(r)).count(),
                runs: mine.len(),
                wins,
            }
        })
        .collect()
}
