//! MIP starts: a design (the construction heuristic's, or one given) encoded as a point of the
//! formulation and checked by the MILP checker before any backend sees it.

use super::result::{design_point, StartReport};
use crate::design::{Network, Objective};
use crate::formulations::Formulation;
use crate::heuristics::{self, Inputs};
use crate::spec::Problem;

/// Where a solve's MIP start comes from.
#[derive(Clone, Debug)]
pub enum StartFrom {
    /// No start.
    Nothing,
    /// The construction heuristic with local search ([`crate::heuristics::start`]), given this
    /// many seconds at most (its time is taken off the solve's time limit).
    Heuristic {
        /// Budget in seconds.
        budget: f64,
        /// While it has found no design, the heuristic goes on up to this many seconds (at
        /// least `budget`); see [`default_first_design_budget`].
        first_design_budget: f64,
    },
    /// A design (e.g. read from an earlier `result.json`).
    Design {
        /// The design.
        network: Network,
        /// Where it came from, for the report.
        source: String,
    },
    /// A start already prepared by [`start_for`] (e.g. to show it before the solve begins).
    Prepared {
        /// The checked point, if the checker accepted it.
        point: Option<Vec<f64>>,
        /// Its report (its `seconds` are taken off the time limit).
        report: StartReport,
    },
}

/// The heuristic's budget for a solve with this time limit: a tenth of it, at most 2 s (2 s
/// without a limit), in work ([`crate::heuristics::budget`]). At the budget's rate (the slowest
/// spec's) that is 0.4–2 s of the clock (about 0.8 s on a city's street levels), so the solver
/// has its incumbent by the first second or two.
pub fn default_start_budget(time_limit: Option<f64>) -> f64 {
    share_of_limit(time_limit, 0.1, 2.0)
}

/// `share` of a finite time limit, at most `cap` (`cap` without one).
fn share_of_limit(time_limit: Option<f64>, share: f64, cap: f64) -> f64 {
    time_limit.filter(|t| t.is_finite()).map_or(cap, |t| (share * t).min(cap))
}

/// How long the heuristic may go on while it has no design: a fifth of the time limit, at most
/// 60 s (60 s without a limit), never less than [`default_start_budget`], on the clock
/// ([`crate::heuristics::Options::first_design_limit`]). Where the heuristic
/// needs more than its first second (floor plans, game levels) the solver alone usually finds
/// nothing either, so these seconds are the solve's best chance of a design; once a design is
/// found the heuristic stops at its ordinary budget. (A tenth and 30 s missed the circular
/// level Fig. 1e about half the time: its first design comes after 11–57 s of one search.)
pub fn default_first_design_budget(time_limit: Option<f64>) -> f64 {
    share_of_limit(time_limit, 0.2, 60.0).max(default_start_budget(time_limit))
}

/// The default start of a solve with this time limit: the heuristic with
/// [`default_start_budget`] and [`default_first_design_budget`].
pub fn default_start(time_limit: Option<f64>) -> StartFrom {
    StartFrom::Heuristic {
        budget: default_start_budget(time_limit),
        first_design_budget: default_first_design_budget(time_limit),
    }
}

/// Turns a design into a checked MIP start for `f`: the point is encoded, then checked by the
/// MILP checker against every row and bound (and the lazy rows); a point that fails is
/// reported and not returned, never passed to a solver.
pub fn prepare_start(p: &Problem, f: &Formulation, net: &Network, source: &str) -> (Option<Vec<f64>>, StartReport) {
    let objective = Some(Objective::of(p, net).total);
    let mut report = StartReport {
        source: source.to_string(),
        objective,
        accepted: false,
        reason: None,
        seconds: None,
        returned: false,
    };
    let cp = match design_point(f, p, net) {
        Ok(cp) => cp,
        Err(e) => {
            report.reason = Some(e);
            return (None, report);
        }
    };
    if !cp.check.is_feasible() {
        let first: Vec<String> = cp.check.violations.iter().take(3).map(|v| v.to_string()).collect();
        report.reason =
            Some(format!("{} violations of the model, e.g. {}", cp.check.violations.len(), first.join("; ")));
        return (None, report);
    }
    if cp.lazy_violations > 0 {
        report.reason = Some(format!("violates {} connectivity rows (an island)", cp.lazy_violations));
        return (None, report);
    }
    report.accepted = true;
    (Some(cp.x), report)
}

/// Prepares the start `from` for `f`: runs the heuristic (or takes the given design), encodes
/// and checks it ([`prepare_start`]). `None` for [`StartFrom::Nothing`]. The heuristic runs
/// `threads` searches side by side: the solve's own threads, idle until the start is handed over.
pub fn start_for(
    p: &Problem,
    f: &Formulation,
    from: &StartFrom,
    seed: u64,
    threads: usize,
) -> Option<(Option<Vec<f64>>, StartReport)> {
    let t0 = std::time::Instant::now();
    let (net, source) = match from {
        StartFrom::Nothing => return None,
        StartFrom::Heuristic { budget, first_design_budget } => {
            let inputs = Inputs {
                paths: f.path_sets.as_ref(),
                placements: f.placements.as_ref().map(|r| r.placements.as_slice()),
            };
            (
                heuristics::start_within(p, &inputs, *budget, *first_design_budget, seed, threads),
                "heuristic".to_string(),
            )
        }
        StartFrom::Design { network, source } => (Some(network.clone()), source.clone()),
        StartFrom::Prepared { point, report } => return Some((point.clone(), report.clone())),
    };
    let (x, mut report) = match net {
        Some(net) => prepare_start(p, f, &net, &source),
        None => (
            None,
            StartReport {
                source,
                objective: None,
                accepted: false,
                reason: Some("the heuristic found no design".into()),
                seconds: None,
                returned: false,
            },
        ),
    };
    report.seconds = Some(t0.elapsed().as_secs_f64());
    Some((x, report))
}
