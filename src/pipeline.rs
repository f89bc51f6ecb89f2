//! From a resolved problem to a checked design: build the MILP, solve it, check every row and
//! bound with the MILP checker, decode the network, validate it independently, measure it.

use crate::design::{self, Metrics, Network, Objective, Violation};
use crate::formulations::expr::FamilyStats;
use crate::formulations::{self, Formulation};
use crate::heuristics::{self, Inputs};
use crate::mesh::Mesh;
use crate::milp::{check_point, objectives_agree, CheckReport, Model, ModelStats, Tolerances};
use crate::rules::paths::PathSets;
use crate::solvers::lattice::LatticeReport;
use crate::solvers::split::{solve_split, ObjectiveSplit, PhaseSolve, SplitReport};
use crate::solvers::{LazyReport, LazyRow, RawParam, Separator, SolveOptions, SolveResult, SolverError, SolverKind};
use crate::spec::{Problem, Spec};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

/// Version of the design result schema (`result.json`).
pub const DESIGN_SCHEMA_VERSION: u32 = 2;

/// The verdict of every independent check.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Validity {
    /// `true` when a network exists and every check below passed.
    pub valid: bool,
    /// FORMULATION §6 items 1–5, from plain graph code.
    pub design_violations: Vec<Violation>,
    /// §6 item 7: every row and bound of the emitted MILP at the returned point.
    pub milp_check: Option<CheckReport>,
    /// §6 item 7: the objective recomputed from the decoded design alone (see
    /// [`crate::design::Objective`]).
    pub objective_recomputed: Option<f64>,
    /// Whether the solver's objective equals the model's objective at its point (the
    /// formulation's surrogate, 1e-6 relative) and the design's own objective is not above it.
    pub objective_agrees: Option<bool>,
}

/// The room part of a design result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RoomsResult {
    /// Placements enumerated, per template.
    pub enumerated_per_template: Vec<usize>,
    /// Whether enumeration hit its count or time cap.
    pub truncated: bool,
    /// Seconds spent enumerating.
    pub seconds: f64,
    /// Game levels: the block connectivity graph (also written as `blocks.dot`).
    pub block_graph: Option<crate::design::BlockGraph>,
    /// The chosen placements (faces, inner and boundary edges), in placement order; the
    /// network's `rooms` indices refer to the model's full list, these are the rooms themselves.
    pub chosen: Vec<crate::rules::placements::Placement>,
}

/// Everything about one design run (`result.json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DesignResult {
    /// Always `netspec.design`.
    pub schema: String,
    /// [`DESIGN_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The netspec version.
    pub netspec_version: String,
    /// The spec, echoed.
    pub spec: Spec,
    /// The mesh.
    pub mesh: Mesh,
    /// Sink vertex ids.
    pub sinks: Vec<u32>,
    /// Active edges as vertex pairs (existing edges included), in edge-id order.
    pub active_edges: Vec<[u32; 2]>,
    /// The decoded network (active flags, directions, labels), if there is a solution.
    pub network: Option<Network>,
    /// Whether a design exists (apart from why the solver stopped, `solve.termination`).
    #[serde(default)]
    pub design_found: bool,
    /// Metrics of the network.
    pub metrics: Option<Metrics>,
    /// The objective recomputed from the design alone, term by term (the paper's distance term,
    /// total travel, counts of penalised features).
    pub objective: Option<Objective>,
    /// The independent checks.
    pub validity: Validity,
    /// The solver's result (the primal point is omitted here; see `--export` for the model).
    pub solve: SolveResult,
    /// Size of the MILP.
    pub model_stats: ModelStats,
    /// Variables and rows per constraint family.
    pub families: IndexMap<String, FamilyStats>,
    /// The recipe, with its overrides (`strong`, `paper(coverage=strong)`).
    pub formulation: String,
    /// The big-M of the label rows (2), when the recipe has labels.
    pub big_m: Option<f64>,
    /// Lazily separated rows: how they were handled and how many were added.
    #[serde(default)]
    pub lazy: Option<LazyReport>,
    /// The two-phase solve, when the objective's two scales called for it
    /// ([`crate::solvers::split`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split: Option<SplitReport>,
    /// The objective's lattice, when the recipe used it, with the backend's bound before it was
    /// rounded up to the lattice ([`crate::solvers::lattice`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lattice: Option<LatticeReport>,
    /// The recipe's solver settings handed to the backend (`highs.mip_pscost_minreliable=0`;
    /// [`crate::formulations::Recipe::solver_hints`]), beside the user's own.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub solver_hints: Vec<String>,
    /// The MIP start handed to the solver (or refused), if one was prepared.
    #[serde(default)]
    pub start: Option<StartReport>,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room tiling, if on.
    pub rooms: Option<RoomsResult>,
    /// The solver's point, one value per MILP variable (not in `result.json`; for `--sol`).
    #[serde(skip)]
    pub primal_point: Option<Vec<f64>>,
}

/// A MIP start: where it came from, what it is worth, and whether the checker let it through.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StartReport {
    /// Where the design came from (`heuristic`, a file name).
    pub source: String,
    /// The design's own objective.
    pub objective: Option<f64>,
    /// Whether the point passed the MILP checker (every emitted row and bound, and every lazy
    /// row) and was handed to the solver.
    pub accepted: bool,
    /// Why it was refused.
    pub reason: Option<String>,
    /// Seconds spent finding and checking it (counted against the solve's time limit).
    #[serde(default)]
    pub seconds: Option<f64>,
    /// Whether the returned design is the start itself: the solver found nothing better (or
    /// nothing at all) before it stopped.
    #[serde(default)]
    pub returned: bool,
}

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

/// The heuristic's budget for a solve with this time limit: a twentieth of it, at most 1 s (1 s
/// without a limit), so the solver has its incumbent by the first second.
pub fn default_start_budget(time_limit: Option<f64>) -> f64 {
    share_of_limit(time_limit, 0.05, 1.0)
}

/// `share` of a finite time limit, at most `cap` (`cap` without one).
fn share_of_limit(time_limit: Option<f64>, share: f64, cap: f64) -> f64 {
    time_limit.filter(|t| t.is_finite()).map_or(cap, |t| (share * t).min(cap))
}

/// How long the heuristic may go on while it has no design: a fifth of the time limit, at most
/// 60 s (60 s without a limit), never less than [`default_start_budget`]. Where the heuristic
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

/// Builds the MILP of a problem under the recipe its spec asks for (no solve).
pub fn build(p: &Problem) -> Formulation {
    formulations::build(p)
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

/// A design as a point of a formulation, with the MILP checker's report on it.
pub(crate) struct DesignPoint {
    /// The point.
    pub x: Vec<f64>,
    /// Every emitted row and bound, checked.
    pub check: CheckReport,
    /// Lazily separated rows the point violates (0 without a separator).
    pub lazy_violations: usize,
}

/// Encodes `net` for `f` and checks the point against every row, bound and lazy row.
pub(crate) fn design_point(f: &Formulation, p: &Problem, net: &Network) -> Result<DesignPoint, String> {
    let x = f.encode(p, net).map_err(|e| e.to_string())?;
    let check = check_point(&f.model, &x, &Tolerances::default());
    let lazy_violations = f.separator().map_or(0, |mut sep| sep.separate_integral(&x).len());
    Ok(DesignPoint { x, check, lazy_violations })
}

/// The validator's verdict on a design of `f`: §6 items 1–5, and the room rules when tiling.
pub(crate) fn design_violations(p: &Problem, f: &Formulation, net: &Network) -> Vec<Violation> {
    let mut v = design::validate(p, net, f.path_sets.as_ref());
    if let Some(pl) = &f.placements {
        v.extend(design::validate_rooms(p, net, &pl.placements, &net.rooms));
    }
    v
}

/// A design's active edges as vertex pairs, in edge-id order (empty without a design).
pub(crate) fn active_edge_pairs(p: &Problem, net: Option<&Network>) -> Vec<[u32; 2]> {
    net.map_or(Vec::new(), |n| {
        n.active_edges()
            .into_iter()
            .map(|e| {
                let (a, b) = p.mesh.edge_vertices(e);
                [a.0, b.0]
            })
            .collect()
    })
}

/// The room part of a result, when `f` tiles rooms.
pub(crate) fn rooms_result(p: &Problem, f: &Formulation, net: Option<&Network>) -> Option<RoomsResult> {
    f.placements.as_ref().map(|pl| RoomsResult {
        enumerated_per_template: pl.per_template.clone(),
        truncated: pl.truncated,
        seconds: pl.seconds,
        block_graph: match (&p.rooms, net) {
            (Some(r), Some(n)) if r.mode == crate::spec::RoomMode::Game => {
                Some(design::block_graph(p, n, &pl.placements))
            }
            _ => None,
        },
        chosen: net.map_or(Vec::new(), |n| n.rooms.iter().map(|&k| pl.placements[k].clone()).collect()),
    })
}

/// The formulation's point for a repaired version of a disconnected integral point: islands
/// (components without a sink) are dropped, and the rest encoded. `None` when the rest is not a
/// valid design (e.g. coverage needed an island).
fn repair_point(p: &Problem, f: &Formulation, x: &[f64]) -> Option<Vec<f64>> {
    let mut net = f.decode(p, x);
    for v in design::validate(p, &net, f.path_sets.as_ref()) {
        if let Violation::Island { edges } = v {
            for e in edges {
                net.active[e.index()] = false;
            }
        }
    }
    if f.placements.is_none() && design::validate(p, &net, f.path_sets.as_ref()).is_empty() {
        return f.encode(p, &net).ok();
    }
    // Dropping the islands broke a rule (coverage, rooms, …): the heuristic's rule steps mend it.
    let inputs =
        Inputs { paths: f.path_sets.as_ref(), placements: f.placements.as_ref().map(|r| r.placements.as_slice()) };
    let fixed = heuristics::repair_within(p, &inputs, &net, REPAIR_BUDGET)?;
    f.encode(p, &fixed).ok()
}

/// Seconds the solve–cut–resolve loop gives [`heuristics::repair_within`] per broken point.
const REPAIR_BUDGET: f64 = 0.2;

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

/// [`solve_built`] from a MIP start: the start is prepared ([`start_for`]) within the time
/// limit, handed to the backend when the checker accepts it and the backend takes starts, and
/// returned as the design when the solver ends with nothing better (so a solve never ends worse
/// than its start). The report is in [`DesignResult::start`].
pub fn solve_from(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
    from: &StartFrom,
) -> Result<DesignResult, SolverError> {
    let takes_starts = kind.instance()?.capabilities().mip_start;
    let prepared =
        if takes_starts { start_for(p, f, from, options.seed.unwrap_or(0), options.heuristic_threads()) } else { None };
    let Some((x, mut report)) = prepared else {
        let mut res = solve_built(p, f, kind, options)?;
        if !takes_starts && !matches!(from, StartFrom::Nothing) {
            res.start = Some(StartReport {
                source: "none".into(),
                objective: None,
                accepted: false,
                reason: Some(format!("{kind} does not accept a starting solution")),
                seconds: None,
                returned: false,
            });
        }
        return Ok(res);
    };
    let mut o = options.clone();
    if let (Some(limit), Some(spent)) = (o.finite_time_limit(), report.seconds) {
        o.time_limit = Some((limit - spent).max(0.0));
    }
    o.mip_start = x.clone();
    let mut res = solve_built(p, f, kind, &o)?;
    if let (Some(x), Some(start_obj)) = (x, report.objective) {
        let infeasible = res.solve.termination == crate::solvers::Termination::Infeasible;
        let worse = match res.objective.as_ref().filter(|_| res.validity.valid) {
            None => true,
            Some(o) => match f.model.sense {
                crate::milp::Sense::Minimize => o.total > start_obj + 1e-9 * start_obj.abs().max(1.0),
                crate::milp::Sense::Maximize => o.total < start_obj - 1e-9 * start_obj.abs().max(1.0),
            },
        };
        if worse && !infeasible {
            let mut solve = res.solve.clone();
            solve.objective = Some(f.model.objective_value(&x));
            solve.primal = Some(x);
            solve.finish(f.model.sense);
            let reports = Reports {
                lazy: res.lazy.clone(),
                split: res.split.clone(),
                solver_hints: res.solver_hints.clone(),
                lattice: res.lattice.clone(),
            };
            let mut again = checked_result(p, f, solve, reports, &[])?;
            again.solve.wall_time = res.solve.wall_time;
            report.returned = true;
            res = again;
        }
    }
    res.start = Some(report);
    Ok(res)
}

/// Solves a built formulation and checks the answer: lazily separated rows go through the
/// backend's `solve_lazy` (its callback, or the solve–cut–resolve loop), every row and bound of
/// the model and every separated row is checked at the returned point, the network is decoded,
/// validated and measured, and its objective recomputed from the design alone.
pub fn solve_built(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    options: &SolveOptions,
) -> Result<DesignResult, SolverError> {
    let solver = kind.instance()?;
    let (tuned, solver_hints) = with_solver_hints(options, &f.solver_hints(kind, options.threads));
    let options = &tuned;
    let mut sep = f.separator().map(|sep| sep.with_repair(Box::new(|x: &[f64]| repair_point(p, f, x))));
    // Root-round rows no phase's model kept: checked at the answer with the others.
    let mut left_out = Vec::new();
    let mut solve = |m: &Model, o: &SolveOptions| -> Result<PhaseSolve, SolverError> {
        Ok(match sep.as_mut() {
            Some(sep) => {
                let ls = solver.solve_lazy(m, sep, o)?;
                left_out.extend(ls.left_out);
                (ls.result, ls.rows, Some(ls.report))
            }
            None => (solver.solve(m, o)?, Vec::new(), None),
        })
    };
    let split = options
        .mip_start
        .as_ref()
        .filter(|_| f.recipe.split_objective)
        .and_then(|x| ObjectiveSplit::detect(&f.model).filter(|s| s.suits(&f.model, x)));
    let (mut result, mut lazy_rows, lazy, split) = match split {
        Some(split) => {
            let polish = |x: &[f64]| f.encode(p, &f.decode(p, x)).ok();
            let s = solve_split(&f.model, &split, options, &mut solve, polish)?;
            (s.result, s.rows, s.lazy, Some(s.report))
        }
        None => {
            let (r, rows, lazy) = solve(&f.model, options)?;
            (r, rows, lazy, None)
        }
    };
    lazy_rows.extend(left_out);
    let lattice = f
        .objective_lattice
        .filter(|_| f.recipe.objective_lattice)
        .map(|lattice| LatticeReport { lattice, solver_bound: lattice.settle(&mut result, f.model.sense) });
    checked_result(p, f, result, Reports { lazy, split, solver_hints, lattice }, &lazy_rows)
}

/// `options` with the recipe's solver `hints` put before the user's parameters, leaving out a
/// hint whose parameter the user sets (theirs wins); and the hints used, as `highs.name=value`.
fn with_solver_hints(options: &SolveOptions, hints: &[RawParam]) -> (SolveOptions, Vec<String>) {
    let used: Vec<RawParam> = hints
        .iter()
        .filter(|h| !options.params.iter().any(|p| p.solver == h.solver && p.name == h.name))
        .cloned()
        .collect();
    let names = used.iter().map(|h| h.to_string()).collect();
    let mut o = options.clone();
    o.params = used.into_iter().chain(options.params.iter().cloned()).collect();
    (o, names)
}

/// What a solve did besides its result, carried into the design result.
struct Reports {
    lazy: Option<LazyReport>,
    split: Option<SplitReport>,
    solver_hints: Vec<String>,
    lattice: Option<LatticeReport>,
}

/// Checks a solver's result and builds the design result: every row and bound of the model
/// and every separated row at the point, the decoded network validated and measured, its
/// objective recomputed from the design alone.
fn checked_result(
    p: &Problem,
    f: &Formulation,
    mut result: SolveResult,
    reports: Reports,
    lazy_rows: &[LazyRow],
) -> Result<DesignResult, SolverError> {
    let Reports { lazy, split, solver_hints, lattice } = reports;
    let mut validity = Validity {
        valid: false,
        design_violations: Vec::new(),
        milp_check: None,
        objective_recomputed: None,
        objective_agrees: None,
    };
    let mut net = None;
    let mut metrics = None;
    let mut objective = None;
    if let Some(x) = &result.primal {
        let check = if lazy_rows.is_empty() {
            check_point(&f.model, x, &Tolerances::default())
        } else {
            let mut full: Model = f.model.clone();
            for r in lazy_rows {
                r.add_to(&mut full);
            }
            check_point(&full, x, &Tolerances::default())
        };
        let n = f.decode(p, x);
        validity.design_violations = design_violations(p, f, &n);
        // The solver's objective must be the model's objective at its point (the checker
        // recomputes it), and the design's own objective can only be lower: a formulation's
        // surrogate (labels, flows, indicators) overestimates off the optimum, never under.
        let design_objective = Objective::of(p, &n);
        let surrogate = check.objective;
        validity.objective_recomputed = Some(design_objective.total);
        validity.objective_agrees = result.objective.map(|o| {
            objectives_agree(o, surrogate, 1e-6)
                && design_objective.total <= surrogate + 1e-6 * surrogate.abs().max(1.0)
        });
        validity.valid =
            check.is_feasible() && validity.design_violations.is_empty() && validity.objective_agrees == Some(true);
        validity.milp_check = Some(check);
        metrics = Some(Metrics::of(p, &n));
        objective = Some(design_objective);
        net = Some(n);
    }
    let active_edges = active_edge_pairs(p, net.as_ref());
    let primal_point = result.primal.take();
    let rooms = rooms_result(p, f, net.as_ref());
    Ok(DesignResult {
        schema: "netspec.design".into(),
        schema_version: DESIGN_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        spec: p.spec.clone(),
        mesh: p.mesh.clone(),
        sinks: p.mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| v.0).collect(),
        active_edges,
        design_found: net.is_some(),
        network: net,
        metrics,
        objective,
        validity,
        solve: result,
        model_stats: f.model.stats(),
        families: f.families.clone(),
        formulation: f.recipe.label.clone(),
        big_m: f.big_m,
        lazy,
        split,
        lattice,
        solver_hints,
        start: None,
        path_sets: f.path_sets.clone(),
        rooms,
        primal_point,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn param(solver: SolverKind, name: &str, value: &str) -> RawParam {
        RawParam { solver, name: name.into(), value: value.into() }
    }

    /// The hints go first, so a backend that applies parameters in order lets the user's win;
    /// a hint the user sets by name is left out and not reported; another backend's parameter
    /// of the same name does not count.
    #[test]
    fn solver_hints_yield_to_the_users_parameters() {
        let hint = param(SolverKind::Highs, "mip_pscost_minreliable", "0");
        let user = SolveOptions {
            params: vec![param(SolverKind::Highs, "mip_heuristic_effort", "0.1")],
            ..Default::default()
        };
        let (o, used) = with_solver_hints(&user, std::slice::from_ref(&hint));
        assert_eq!(o.params, vec![hint.clone(), user.params[0].clone()]);
        assert_eq!(used, vec!["highs.mip_pscost_minreliable=0".to_string()]);

        let own = SolveOptions {
            params: vec![param(SolverKind::Highs, "mip_pscost_minreliable", "8")],
            ..Default::default()
        };
        let (o, used) = with_solver_hints(&own, std::slice::from_ref(&hint));
        assert_eq!(o.params, own.params);
        assert!(used.is_empty());

        let other =
            SolveOptions { params: vec![param(SolverKind::Scip, "mip_pscost_minreliable", "8")], ..Default::default() };
        let (o, used) = with_solver_hints(&other, std::slice::from_ref(&hint));
        assert_eq!(o.params, vec![hint, other.params[0].clone()]);
        assert_eq!(used.len(), 1);
    }

    /// Only `strong` on HiGHS has hints: the pseudocost setting always, the parallel tree search
    /// from two threads on; `solver_tuning = false` and `parallel_search = false` remove each.
    #[test]
    fn only_the_strong_recipe_on_highs_is_tuned() {
        use crate::formulations::Recipe;
        use crate::spec::RecipeName;
        let strong = Recipe::named(RecipeName::Strong);
        let names = |r: &Recipe, threads: Option<u32>| {
            r.solver_hints(SolverKind::Highs, threads).iter().map(|h| h.to_string()).collect::<Vec<_>>()
        };
        assert_eq!(names(&strong, Some(2)), ["highs.mip_pscost_minreliable=0", "highs.parallel=on"]);
        for threads in [None, Some(1)] {
            assert_eq!(names(&strong, threads), ["highs.mip_pscost_minreliable=0"], "{threads:?}");
        }
        for k in [SolverKind::Scip, SolverKind::Cbc, SolverKind::Microlp] {
            assert!(strong.solver_hints(k, Some(2)).is_empty(), "{k}");
        }
        for name in [RecipeName::Paper, RecipeName::Tight] {
            assert!(Recipe::named(name).solver_hints(SolverKind::Highs, Some(2)).is_empty(), "{name:?}");
        }
        let untuned = Recipe { solver_tuning: false, ..strong.clone() };
        assert_eq!(names(&untuned, Some(2)), ["highs.parallel=on"]);
        let serial = Recipe { parallel_search: false, ..strong.clone() };
        assert_eq!(names(&serial, Some(2)), ["highs.mip_pscost_minreliable=0"]);
        let off = Recipe { solver_tuning: false, parallel_search: false, ..strong };
        assert!(off.solver_hints(SolverKind::Highs, Some(8)).is_empty());
    }
}
