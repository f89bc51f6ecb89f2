//! Solving the exact model: layouts (distinct ones by no-good cuts, annealed layouts as MIP
//! starts), every answer checked by netspec's MILP checker and by the geometric validator, and
//! for an infeasible level the smallest set of graph edges that cannot hold together (the
//! deletion filter of [`crate::explain`], over graph edges).

use super::cspace::CSpaces;
use super::milp::{self, LevelModel, Part};
use super::spec::{EdgeId, Level, NodeId};
use super::validate::validate;
use super::{Layout, LevelError};
use crate::explain::{deletion_filter, Verdict};
use crate::milp::Tolerances;
use crate::solvers::{Interrupt, SolveOptions, SolverKind, Termination};
use serde::Serialize;
use std::collections::BTreeSet;
use std::time::Instant;

/// How the exact search ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum ExactStatus {
    /// At least one layout found.
    Feasible,
    /// Proven: no layout exists.
    Infeasible,
    /// Neither, within the limits.
    Unknown,
}

/// Graph edges that cannot all be doors at once.
#[derive(Clone, Debug, Serialize)]
pub struct EdgeConflict {
    /// The edges, as node-name pairs.
    pub edges: Vec<[String; 2]>,
    /// Whether no edge of the set can be dropped (every check answered).
    pub minimal: bool,
    /// Feasibility checks solved.
    pub checks: usize,
}

/// What the exact search found.
#[derive(Clone, Debug, Serialize)]
pub struct ExactReport {
    /// The outcome.
    pub status: ExactStatus,
    /// The backend.
    pub solver: SolverKind,
    /// Layouts found (distinct contact choices), each validated.
    #[serde(skip)]
    pub layouts: Vec<Layout>,
    /// Seconds to the first layout.
    pub time_to_first: Option<f64>,
    /// Seconds to the last layout found.
    pub time_to_last: Option<f64>,
    /// Seconds to the proof of infeasibility (or of no further layout).
    pub time_to_proof: Option<f64>,
    /// Solves made.
    pub solves: usize,
    /// Whether the MIP start was accepted by the checker, when one was given.
    pub start_accepted: Option<bool>,
    /// Model size by family.
    pub families: Vec<milp::FamilySize>,
    /// Variables, rows.
    pub size: (usize, usize),
    /// For an infeasible level: edges that conflict.
    pub conflict: Option<EdgeConflict>,
    /// Why the search stopped early, if it did.
    pub note: Option<String>,
}

/// Settings of the exact search.
#[derive(Clone, Debug)]
pub struct ExactOptions {
    /// The backend.
    pub solver: SolverKind,
    /// Seconds for the whole search.
    pub time_limit: f64,
    /// Layouts wanted.
    pub count: usize,
    /// Threads for the backend.
    pub threads: Option<u32>,
    /// Look for conflicting edges when infeasible.
    pub explain: bool,
    /// A request to stop (another method has settled the question): every solve is handed it.
    pub interrupt: Option<Interrupt>,
}

/// One solve's answer: the verdict, the checked point when there is one, and whether the MIP
/// start (if any) passed the checker.
struct Answer {
    verdict: Verdict,
    point: Option<Vec<f64>>,
    start_accepted: Option<bool>,
}

/// One solve of a model.
fn solve_once(
    lm: &LevelModel,
    kind: SolverKind,
    limit: f64,
    threads: Option<u32>,
    start: Option<Vec<f64>>,
    interrupt: Option<&Interrupt>,
) -> Result<Answer, LevelError> {
    let solver = kind.instance()?;
    let opts = SolveOptions {
        time_limit: Some(limit.max(0.01)),
        threads,
        mip_start: start,
        interrupt: interrupt.cloned(),
        ..SolveOptions::default()
    };
    let r = solver.solve(&lm.model, &opts)?;
    let accepted = r.mip_start.as_ref().map(|s| s.accepted);
    let verdict = match &r.termination {
        // Every variable is bounded, so "infeasible or unbounded" is infeasible.
        Termination::Infeasible | Termination::InfeasibleOrUnbounded => Verdict::Infeasible,
        _ => match (&r.primal, r.check(&lm.model, &Tolerances::default())) {
            (Some(x), Some(c)) if c.is_feasible() => {
                return Ok(Answer { verdict: Verdict::Feasible, point: Some(x.clone()), start_accepted: accepted })
            }
            (Some(_), Some(c)) => {
                let first = c.violations.first().map(|v| v.to_string()).unwrap_or_default();
                return Err(LevelError::Rejected(format!("{kind}: answer fails netspec's MILP check: {first}")));
            }
            _ => Verdict::Unknown,
        },
    };
    Ok(Answer { verdict, point: None, start_accepted: accepted })
}

/// Solves the level exactly, with `starts` (annealed layouts) tried as MIP starts.
pub fn solve(level: &Level, cs: &CSpaces, o: &ExactOptions, starts: &[Layout]) -> Result<ExactReport, LevelError> {
    let t0 = Instant::now();
    let mut lm = milp::build(level, cs, &Part::whole(level));
    let mut rep = ExactReport {
        status: ExactStatus::Unknown,
        solver: o.solver,
        layouts: Vec::new(),
        time_to_first: None,
        time_to_last: None,
        time_to_proof: None,
        solves: 0,
        start_accepted: None,
        families: lm.families.clone(),
        size: (lm.model.num_vars(), lm.model.num_rows()),
        conflict: None,
        note: None,
    };
    while rep.layouts.len() < o.count {
        let left = o.time_limit - t0.elapsed().as_secs_f64();
        if left <= 0.0 {
            rep.note = Some("time limit".into());
            break;
        }
        if o.interrupt.as_ref().is_some_and(Interrupt::is_triggered) {
            rep.note = Some("stopped".into());
            break;
        }
        let start = starts.get(rep.solves).map(|l| lm.encode(level, l));
        let Answer { verdict: v, point: x, start_accepted: accepted } =
            solve_once(&lm, o.solver, left, o.threads, start, o.interrupt.as_ref())?;
        rep.solves += 1;
        if rep.start_accepted.is_none() {
            rep.start_accepted = accepted;
        }
        match (v, x) {
            (Verdict::Feasible, Some(x)) => {
                let layout = super::clear_of_obstacles(level, lm.decode(level, &x));
                let check = validate(level, &layout);
                if !check.is_valid() {
                    return Err(LevelError::Rejected(format!(
                        "{}: layout fails the validator: {}",
                        o.solver,
                        check.problems().join("; ")
                    )));
                }
                rep.layouts.push(layout);
                let t = t0.elapsed().as_secs_f64();
                rep.time_to_first.get_or_insert(t);
                rep.time_to_last = Some(t);
                if !lm.has_contacts() {
                    break; // one node, no edge: nothing to tell layouts apart by
                }
                let i = rep.layouts.len();
                lm.no_good(&x, i);
            }
            (Verdict::Infeasible, _) => {
                rep.time_to_proof = Some(t0.elapsed().as_secs_f64());
                if !rep.layouts.is_empty() {
                    rep.note = Some(format!("no further layout exists ({} in all)", rep.layouts.len()));
                }
                break;
            }
            _ => {
                let stopped = o.interrupt.as_ref().is_some_and(Interrupt::is_triggered);
                rep.note = Some(if stopped { "stopped" } else { "time limit" }.into());
                break;
            }
        }
    }
    rep.status = match (rep.layouts.is_empty(), rep.time_to_proof.is_some()) {
        (false, _) => ExactStatus::Feasible,
        (true, true) => ExactStatus::Infeasible,
        (true, false) => ExactStatus::Unknown,
    };
    if rep.status == ExactStatus::Infeasible && o.explain {
        let left = (o.time_limit - t0.elapsed().as_secs_f64()).max(0.0);
        rep.conflict = Some(conflict(level, cs, o, left)?);
    }
    Ok(rep)
}

/// Whether the edges `kept` can all be doors: each connected piece of them is a level of its
/// own (pieces can be placed far apart, nodes on no kept edge anywhere).
fn check_edges(
    level: &Level,
    cs: &CSpaces,
    o: &ExactOptions,
    kept: &BTreeSet<EdgeId>,
    limit: f64,
) -> Result<Verdict, LevelError> {
    let edges: Vec<EdgeId> = kept.iter().copied().collect();
    let adj = level.adjacency(&edges);
    let mut seen = vec![false; level.nodes.len()];
    let mut verdict = Verdict::Feasible;
    for s in 0..level.nodes.len() {
        if seen[s] || adj[s].is_empty() {
            continue;
        }
        let hops = level.hops(NodeId(s as u32), &edges);
        let nodes: Vec<NodeId> =
            (0..level.nodes.len()).filter(|&i| hops[i] != usize::MAX).map(|i| NodeId(i as u32)).collect();
        for n in &nodes {
            seen[n.0 as usize] = true;
        }
        let part_edges: Vec<EdgeId> =
            edges.iter().copied().filter(|e| nodes.binary_search(&level.edges[e.0 as usize].0).is_ok()).collect();
        let lm = milp::build(level, cs, &Part { nodes, edges: part_edges });
        match solve_once(&lm, o.solver, limit, o.threads, None, o.interrupt.as_ref())?.verdict {
            Verdict::Infeasible => return Ok(Verdict::Infeasible),
            Verdict::Unknown => verdict = Verdict::Unknown,
            Verdict::Feasible => {}
        }
    }
    Ok(verdict)
}

/// A minimal set of graph edges that cannot all be doors (deletion filter).
fn conflict(level: &Level, cs: &CSpaces, o: &ExactOptions, budget: f64) -> Result<EdgeConflict, LevelError> {
    let t0 = Instant::now();
    let mut kept: BTreeSet<EdgeId> = level.all_edges().into_iter().collect();
    let members: Vec<EdgeId> = kept.iter().copied().collect();
    let mut checks = 0;
    let mut error = None;
    let mut minimal = deletion_filter(&mut kept, members, |s| {
        let left = budget - t0.elapsed().as_secs_f64();
        if left <= 0.05 || error.is_some() || o.interrupt.as_ref().is_some_and(Interrupt::is_triggered) {
            return Verdict::Unknown;
        }
        checks += 1;
        check_edges(level, cs, o, s, left).unwrap_or_else(|e| {
            error = Some(e);
            Verdict::Unknown
        })
    });
    if let Some(e) = error {
        return Err(e);
    }
    minimal &= t0.elapsed().as_secs_f64() < budget;
    let edges = kept
        .iter()
        .map(|e| {
            let (a, b) = level.edges[e.0 as usize];
            [level.node_name(a).to_string(), level.node_name(b).to_string()]
        })
        .collect();
    Ok(EdgeConflict { edges, minimal, checks })
}
