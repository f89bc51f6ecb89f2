//! Solving the exact model: layouts (distinct ones by no-good cuts, annealed layouts as MIP
//! starts), every answer checked by netspec's MILP checker and by the geometric validator, and
//! for an infeasible level the smallest set of graph edges that cannot hold together (the
//! deletion filter of [`crate::explain`], over graph edges).
//!
//! [`solve`] answers by one of three routes ([`Route`]): a screen of small induced subgraphs
//! ([`subgraphs`]) first, whose first infeasible member proves the level infeasible; then the
//! whole model when the level is small, else an incremental layout ([`incremental`]) that
//! places a few nodes per model with the earlier ones held fixed.

pub mod incremental;
pub mod subgraphs;

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

/// Which route gave the answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Route {
    /// The model of the whole level.
    Whole,
    /// A few nodes per model, the earlier ones fixed ([`incremental`]).
    Incremental,
    /// A small induced subgraph proven infeasible ([`subgraphs`]).
    Subgraph,
}

/// The subgraph screen: what was tried, and the subgraph proven infeasible if one was.
#[derive(Clone, Debug, Serialize)]
pub struct Screen {
    /// Candidate subgraphs there were.
    pub candidates: usize,
    /// Candidates solved (a model built and solved).
    pub tried: usize,
    /// Candidates answered feasible.
    pub feasible: usize,
    /// Of those, candidates answered by an earlier one of the same shape
    /// ([`subgraphs::shape`]) without a solve.
    pub same_shape: usize,
    /// Candidates left unanswered within their time limit.
    pub unknown: usize,
    /// Seconds spent.
    pub seconds: f64,
    /// The subgraph proven infeasible.
    pub proof: Option<SubgraphProof>,
}

/// An induced subgraph without a layout.
#[derive(Clone, Debug, Serialize)]
pub struct SubgraphProof {
    /// Where it comes from.
    pub origin: subgraphs::Origin,
    /// Its nodes.
    pub nodes: Vec<String>,
    /// Its edges (every level edge among the nodes), as node-name pairs.
    pub edges: Vec<[String; 2]>,
    /// Variables, rows of its model.
    pub size: (usize, usize),
}

/// What the exact search found.
#[derive(Clone, Debug, Serialize)]
pub struct ExactReport {
    /// The outcome.
    pub status: ExactStatus,
    /// The backend.
    pub solver: SolverKind,
    /// The route that answered (the one last tried when nothing was found).
    pub route: Route,
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
    /// Model size by family (of the whole model; empty when it was not built).
    pub families: Vec<milp::FamilySize>,
    /// Variables, rows (of the whole model; of the largest step's on the incremental route).
    pub size: (usize, usize),
    /// The subgraph screen, when it ran.
    pub screen: Option<Screen>,
    /// The incremental layout, when it ran.
    pub incremental: Option<incremental::Stats>,
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
    /// Seconds for the whole search (screen, solves and explanation).
    pub time_limit: f64,
    /// Layouts wanted.
    pub count: usize,
    /// Threads for the backend.
    pub threads: Option<u32>,
    /// Look for conflicting edges when infeasible.
    pub explain: bool,
    /// A request to stop early: every solve gets it, and the search returns what it has.
    pub interrupt: Option<Interrupt>,
}

/// Levels of at most this many nodes go to the whole model (when it has at most
/// [`WHOLE_MAX_VARS`] variables); larger ones are laid out incrementally first. Measured
/// (HiGHS, 60 s): the incremental route lays out Fig. 1 (14 nodes) in 2.0 s against the whole
/// model's 4.8 s, Fig. 9 (16) in 4.4 s against 21.6 s, a 4-star with a 20-path (25) in well
/// under a second against no answer.
pub const WHOLE_MAX_NODES: usize = 10;

/// The whole model is solved first only when it has at most this many variables.
pub const WHOLE_MAX_VARS: usize = 12_000;

/// When the incremental route ends without an answer, levels of at most this many nodes get
/// the whole model for the time left.
pub const FALLBACK_MAX_NODES: usize = 40;

/// Share of the time limit the subgraph screen may take.
const SCREEN_SHARE: f64 = 0.25;

/// Seconds for one candidate subgraph of the screen at most.
const CANDIDATE_LIMIT: f64 = 1.0;

/// Biconnected components of more nodes than this are not screened.
const BLOCK_CAP: usize = 12;

/// The deadline over a whole call, and the interrupt.
#[derive(Clone, Debug)]
pub struct Clock {
    t0: Instant,
    limit: f64,
    interrupt: Option<Interrupt>,
}

impl Clock {
    /// Starts now, with `o`'s time limit and interrupt.
    pub fn new(o: &ExactOptions) -> Clock {
        Clock { t0: Instant::now(), limit: o.time_limit, interrupt: o.interrupt.clone() }
    }

    /// Seconds since the start.
    pub fn elapsed(&self) -> f64 {
        self.t0.elapsed().as_secs_f64()
    }

    /// Seconds left.
    pub fn left(&self) -> f64 {
        self.limit - self.elapsed()
    }

    /// Whether the interrupt was triggered.
    pub fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|i| i.is_triggered())
    }

    /// Whether to stop: out of time or interrupted.
    pub fn stopped(&self) -> bool {
        self.left() <= 0.0 || self.interrupted()
    }

    /// Why the search stopped, for a note.
    pub fn why(&self) -> &'static str {
        if self.interrupted() {
            "stopped"
        } else {
            "time limit"
        }
    }
}

/// One solve's answer: the verdict, the checked point when there is one, and whether the MIP
/// start (if any) passed the checker.
pub struct Answer {
    /// Feasible, infeasible or unknown.
    pub verdict: Verdict,
    /// The checked point when feasible.
    pub point: Option<Vec<f64>>,
    /// Whether the MIP start passed the checker, when one was given.
    pub start_accepted: Option<bool>,
}

/// One solve of a model, within `limit` seconds and the options' interrupt.
pub fn solve_once(
    lm: &LevelModel,
    o: &ExactOptions,
    limit: f64,
    start: Option<Vec<f64>>,
) -> Result<Answer, LevelError> {
    solve_gap(lm, o, limit, start, None)
}

/// [`solve_once`] with a relative MIP gap to stop at (for a model with an objective).
pub fn solve_gap(
    lm: &LevelModel,
    o: &ExactOptions,
    limit: f64,
    start: Option<Vec<f64>>,
    rel_gap: Option<f64>,
) -> Result<Answer, LevelError> {
    let kind = o.solver;
    let solver = kind.instance()?;
    let opts = SolveOptions {
        time_limit: Some(limit.max(0.01)),
        threads: o.threads,
        mip_start: start,
        rel_gap,
        interrupt: o.interrupt.clone(),
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

/// A layout of the whole level, moved clear of obstacles and checked by the validator.
pub fn checked(level: &Level, o: &ExactOptions, layout: Layout) -> Result<Layout, LevelError> {
    let layout = super::clear_of_obstacles(level, layout);
    let check = validate(level, &layout);
    if !check.is_valid() {
        return Err(LevelError::Rejected(format!(
            "{}: layout fails the validator: {}",
            o.solver,
            check.problems().join("; ")
        )));
    }
    Ok(layout)
}

/// Edge names as node-name pairs.
fn edge_names(level: &Level, edges: impl IntoIterator<Item = EdgeId>) -> Vec<[String; 2]> {
    edges
        .into_iter()
        .map(|e| {
            let (a, b) = level.edges[e.0 as usize];
            [level.node_name(a).to_string(), level.node_name(b).to_string()]
        })
        .collect()
}

fn empty_report(o: &ExactOptions) -> ExactReport {
    ExactReport {
        status: ExactStatus::Unknown,
        solver: o.solver,
        route: Route::Whole,
        layouts: Vec::new(),
        time_to_first: None,
        time_to_last: None,
        time_to_proof: None,
        solves: 0,
        start_accepted: None,
        families: Vec::new(),
        size: (0, 0),
        screen: None,
        incremental: None,
        conflict: None,
        note: None,
    }
}

/// Solves the level exactly, with `starts` (annealed layouts) tried as MIP starts on the whole
/// model. The subgraph screen runs first (at most a quarter of the time limit); then the whole
/// model for levels of at most [`WHOLE_MAX_NODES`] nodes, the incremental layout for larger
/// ones (and the whole model for the time left when that ends without an answer, up to
/// [`FALLBACK_MAX_NODES`] nodes). The time limit is a deadline over the whole call; on an interrupt the call returns
/// what it has.
pub fn solve(level: &Level, cs: &CSpaces, o: &ExactOptions, starts: &[Layout]) -> Result<ExactReport, LevelError> {
    let clock = Clock::new(o);
    let mut rep = empty_report(o);
    let (screen, proof) = screen(level, cs, o, &clock, o.time_limit * SCREEN_SHARE)?;
    rep.solves += screen.tried;
    rep.screen = Some(screen);
    if let Some(nodes) = proof {
        rep.route = Route::Subgraph;
        rep.status = ExactStatus::Infeasible;
        rep.time_to_proof = Some(clock.elapsed());
        if o.explain {
            let part = Part::induced(level, nodes);
            rep.conflict = Some(conflict(level, cs, o, &part.edges, &clock)?);
        }
        return Ok(rep);
    }
    if clock.stopped() {
        rep.note = Some(clock.why().into());
        return Ok(rep);
    }
    let lm = (level.nodes.len() <= WHOLE_MAX_NODES)
        .then(|| milp::build(level, cs, &Part::whole(level)))
        .filter(|lm| lm.model.num_vars() <= WHOLE_MAX_VARS);
    match lm {
        Some(lm) => whole(level, cs, o, lm, starts, &clock, &mut rep)?,
        None => {
            rep.route = Route::Incremental;
            incremental::solve(level, cs, o, &clock, &mut rep)?;
            let open = rep.layouts.is_empty() && rep.time_to_proof.is_none();
            if open && !clock.stopped() && level.nodes.len() <= FALLBACK_MAX_NODES {
                let lm = milp::build(level, cs, &Part::whole(level));
                let note = rep.note.take();
                whole(level, cs, o, lm, starts, &clock, &mut rep)?;
                if let (Some(a), Some(b)) = (note, rep.note.as_mut()) {
                    *b = format!("incremental: {a}; whole: {b}");
                }
            }
        }
    }
    rep.status = match (rep.layouts.is_empty(), rep.time_to_proof.is_some()) {
        (false, _) => ExactStatus::Feasible,
        (true, true) => ExactStatus::Infeasible,
        (true, false) => ExactStatus::Unknown,
    };
    Ok(rep)
}

/// The subgraph screen: candidates smallest first, each within [`CANDIDATE_LIMIT`] and the
/// screen's `budget`; the nodes of the first one proven infeasible.
fn screen(
    level: &Level,
    cs: &CSpaces,
    o: &ExactOptions,
    clock: &Clock,
    budget: f64,
) -> Result<(Screen, Option<Vec<NodeId>>), LevelError> {
    let t0 = clock.elapsed();
    let cands = subgraphs::candidates(level, BLOCK_CAP);
    let mut s =
        Screen { candidates: cands.len(), tried: 0, feasible: 0, same_shape: 0, unknown: 0, seconds: 0.0, proof: None };
    let mut found = None;
    let mut feasible_shapes: BTreeSet<Vec<u32>> = BTreeSet::new();
    for c in cands {
        let left = (budget - (clock.elapsed() - t0)).min(clock.left());
        if left <= 0.0 || clock.interrupted() {
            break;
        }
        let shape = subgraphs::shape(level, &c.nodes);
        if shape.as_ref().is_some_and(|k| feasible_shapes.contains(k)) {
            s.feasible += 1;
            s.same_shape += 1;
            continue;
        }
        let part = Part::induced(level, c.nodes.clone());
        let lm = milp::build(level, cs, &part);
        s.tried += 1;
        match solve_once(&lm, o, left.min(CANDIDATE_LIMIT), None)?.verdict {
            Verdict::Infeasible => {
                s.proof = Some(SubgraphProof {
                    origin: c.origin,
                    nodes: c.nodes.iter().map(|&n| level.node_name(n).to_string()).collect(),
                    edges: edge_names(level, part.edges.iter().copied()),
                    size: (lm.model.num_vars(), lm.model.num_rows()),
                });
                found = Some(c.nodes);
                break;
            }
            Verdict::Feasible => {
                s.feasible += 1;
                feasible_shapes.extend(shape);
            }
            Verdict::Unknown => s.unknown += 1,
        }
    }
    s.seconds = clock.elapsed() - t0;
    Ok((s, found))
}

/// The whole model `lm`: layouts by no-good cuts, MIP starts from `starts`, the conflict when it
/// is infeasible.
fn whole(
    level: &Level,
    cs: &CSpaces,
    o: &ExactOptions,
    mut lm: LevelModel,
    starts: &[Layout],
    clock: &Clock,
    rep: &mut ExactReport,
) -> Result<(), LevelError> {
    rep.route = Route::Whole;
    rep.families = lm.families.clone();
    rep.size = (lm.model.num_vars(), lm.model.num_rows());
    let mut tried_starts = 0;
    while rep.layouts.len() < o.count {
        if clock.stopped() {
            rep.note = Some(clock.why().into());
            break;
        }
        let start = starts.get(tried_starts).map(|l| lm.encode(level, l));
        tried_starts += 1;
        let Answer { verdict: v, point: x, start_accepted: accepted } = solve_once(&lm, o, clock.left(), start)?;
        rep.solves += 1;
        if rep.start_accepted.is_none() {
            rep.start_accepted = accepted;
        }
        match (v, x) {
            (Verdict::Feasible, Some(x)) => {
                rep.layouts.push(checked(level, o, lm.decode(level, &x))?);
                let t = clock.elapsed();
                rep.time_to_first.get_or_insert(t);
                rep.time_to_last = Some(t);
                if !lm.has_contacts() {
                    break; // one node, no edge: nothing to tell layouts apart by
                }
                let i = rep.layouts.len();
                lm.no_good(&x, i);
            }
            (Verdict::Infeasible, _) => {
                rep.time_to_proof = Some(clock.elapsed());
                if !rep.layouts.is_empty() {
                    rep.note = Some(format!("no further layout exists ({} in all)", rep.layouts.len()));
                }
                break;
            }
            _ => {
                rep.note = Some(clock.why().into());
                break;
            }
        }
    }
    if rep.layouts.is_empty() && rep.time_to_proof.is_some() && o.explain {
        rep.conflict = Some(conflict(level, cs, o, &level.all_edges(), clock)?);
    }
    Ok(())
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
        let lm = milp::build(level, cs, &Part { nodes, edges: part_edges, placed: Vec::new() });
        match solve_once(&lm, o, limit, None)?.verdict {
            Verdict::Infeasible => return Ok(Verdict::Infeasible),
            Verdict::Unknown => verdict = Verdict::Unknown,
            Verdict::Feasible => {}
        }
    }
    Ok(verdict)
}

/// A minimal subset of `edges` (a set that cannot all be doors) that cannot all be doors
/// (deletion filter), within the clock's deadline; not proven minimal when a check went
/// unanswered.
fn conflict(
    level: &Level,
    cs: &CSpaces,
    o: &ExactOptions,
    edges: &[EdgeId],
    clock: &Clock,
) -> Result<EdgeConflict, LevelError> {
    let mut kept: BTreeSet<EdgeId> = edges.iter().copied().collect();
    let members: Vec<EdgeId> = kept.iter().copied().collect();
    let mut checks = 0;
    let mut error = None;
    let mut stopped = false;
    let mut minimal = deletion_filter(&mut kept, members, |s| {
        let left = clock.left();
        if left <= 0.01 || clock.interrupted() || error.is_some() {
            stopped = true;
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
    minimal &= !stopped;
    Ok(EdgeConflict { edges: edge_names(level, kept), minimal, checks })
}
