//! Designs without a solver: construction heuristics, local search, a repair function for
//! broken designs (a solver's disconnected incumbent), and the paper's stochastic search as a
//! baseline (§6, Fig. 13).
//!
//! Plain Rust over [`crate::spec`], [`crate::rules`] and [`crate::design`]; nothing here reads a
//! formulation. Every design a function of this module returns has passed
//! [`crate::design::validate`] (and [`crate::design::validate_rooms`]); when a search finds none
//! it says so (`network: None`), it never returns an invalid one.
//!
//! - [`heuristic`]: construction, then iterated local search, restarted with new seeds (and, for
//!   room problems, new tilings) until the time limit; the best design wins. Networks are built
//!   by the rule steps of `build` (coverage by through-streets from the network to the farthest
//!   uncovered vertex, dead-ends extended or pruned, forbidden configurations broken), every
//!   path rule-aware (`paths`). Floor plans and game levels tile the footprint by exact cover
//!   (`tiling`, dancing links), then build the corridors or the traversal (`rooms`).
//! - [`anneal`]: the paper's stochastic search, exactly its move set and selection rule
//!   (see the module `anneal` for what the text leaves open and how it is fixed).
//! - [`repair`]: a design that breaks connectivity or local rules, made valid when possible.
//! - [`start`]: the heuristic's design within a budget, for a MIP start.
//!
//! Searches return designs only; [`crate::pipeline::search`] runs them as a solver choice and
//! checks their designs like a MILP solve's.

mod anneal;
pub mod budget;
mod build;
mod local;
mod paths;
mod rng;
mod rooms;
mod state;
mod tiling;

pub use anneal::{AnnealOptions, Operation};

use crate::design::{self, Network};
use crate::rules::paths::{enumerate_path_sets, PathSets};
use crate::rules::placements::{enumerate_for, Placement, PlacementReport};
use crate::spec::Problem;
use budget::Deadline;
use build::Builder;
use local::LocalSearch;
use rng::Rng;
use serde::{Deserialize, Serialize};
use state::{Rules, State, Tiling};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// What a search needs besides the problem: the point-to-point path sets and the room
/// placements *the formulation uses* (a design's room indices point into that list, and the
/// validator checks paths against it). Pass the formulation's (`f.path_sets`,
/// `f.placements`), or [`OwnedInputs::enumerate`] them the same way.
#[derive(Clone, Copy, Debug, Default)]
pub struct Inputs<'a> {
    /// Path sets, when point-to-point is on.
    pub paths: Option<&'a PathSets>,
    /// Placements, when the problem tiles rooms.
    pub placements: Option<&'a [Placement]>,
}

/// [`Inputs`] owned: enumerated as the formulation enumerates them.
#[derive(Clone, Debug, Default)]
pub struct OwnedInputs {
    /// Path sets, when point-to-point is on.
    pub paths: Option<PathSets>,
    /// Placements, when the problem tiles rooms.
    pub placements: Option<PlacementReport>,
}

impl OwnedInputs {
    /// Enumerates the path sets and placements of `p` exactly as the formulations do
    /// (deterministic unless an enumeration hits its time cap).
    pub fn enumerate(p: &Problem) -> OwnedInputs {
        OwnedInputs {
            paths: p.p2p.is_some().then(|| enumerate_path_sets(p)),
            placements: p.rooms.as_ref().map(|r| enumerate_for(p, r)),
        }
    }

    /// Borrowed.
    pub fn inputs(&self) -> Inputs<'_> {
        Inputs { paths: self.paths.as_ref(), placements: self.placements.as_ref().map(|r| r.placements.as_slice()) }
    }
}

/// Settings of [`heuristic`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Options {
    /// Budget, in seconds of work ([`budget`]: counted steps at a fixed rate, so the search and
    /// its design do not depend on the machine's speed or load; the wall clock stops it only at
    /// [`budget::WALL_FACTOR`] times this plus [`budget::WALL_SLACK`]).
    pub time_limit: f64,
    /// Seed (the first construction is noise-free; restarts draw from the seed).
    pub seed: u64,
    /// Stop after this many constructions (default: until the time limit).
    pub max_constructions: Option<usize>,
    /// Stop after this many valid constructions (each improved by the local search if on).
    pub max_designs: Option<usize>,
    /// Run the local search on each construction (default true).
    pub local_search: bool,
    /// While no valid design has been found, keep constructing past `time_limit` up to this
    /// many seconds on the clock (default: stop at `time_limit`). Only the search for a first
    /// design is extended; improving it stays within `time_limit`. The wait is timed by the
    /// clock, not by work (a first design may need 11–57 s of one search where work runs fast,
    /// and a share of a solve's time limit is clock seconds); which design is found does not
    /// depend on it, only whether one is found before the clock runs out.
    pub first_design_limit: Option<f64>,
    /// Independent searches run side by side, one per thread (default 1); the best design of
    /// all is kept. The first runs exactly as a single search with `seed` would; the others
    /// draw from seeds derived from it. A search stops waiting for a first design
    /// (`first_design_limit`) once another has found one with less work, and only the designs
    /// found with the least work count (see [`heuristic`]), so the result does not depend on
    /// how the threads were scheduled.
    pub threads: usize,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            time_limit: 10.0,
            seed: 0,
            max_constructions: None,
            max_designs: None,
            local_search: true,
            first_design_limit: None,
            threads: 1,
        }
    }
}

/// The best objective so far, at a time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct TracePoint {
    /// Seconds since the search started.
    pub seconds: f64,
    /// The best design's objective then.
    pub objective: f64,
}

/// Why a search stopped.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stop {
    /// The time limit.
    TimeLimit,
    /// Nothing left to do: the construction count was reached, or (stochastic search) every
    /// pass ended with no feasible operation.
    Exhausted,
    /// No design exists, for a reason plain enough to prove without search (see
    /// [`obvious_infeasibility`]).
    Infeasible,
}

/// Counters of a search.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SearchStats {
    /// Constructions attempted (tilings included).
    pub constructions: u64,
    /// Constructions that gave a valid design.
    pub constructed: u64,
    /// Local-search moves tried.
    pub moves_tried: u64,
    /// Local-search moves kept.
    pub moves_accepted: u64,
    /// Iterated-local-search kicks.
    pub kicks: u64,
    /// Stochastic search: passes run.
    pub passes: u64,
    /// Stochastic search: operations performed, over all passes.
    pub steps: u64,
    /// Work units spent ([`budget`]).
    #[serde(default)]
    pub work: u64,
    /// Designs the final validation rejected (a bug if ever non-zero; they are dropped).
    pub rejected: u64,
}

impl std::ops::AddAssign<&SearchStats> for SearchStats {
    /// Adds every counter of `other` (searches run side by side).
    fn add_assign(&mut self, other: &SearchStats) {
        self.constructions += other.constructions;
        self.constructed += other.constructed;
        self.moves_tried += other.moves_tried;
        self.moves_accepted += other.moves_accepted;
        self.kicks += other.kicks;
        self.passes += other.passes;
        self.steps += other.steps;
        self.work += other.work;
        self.rejected += other.rejected;
    }
}

/// What a search found.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SearchOutput {
    /// The best valid design (validated), if any.
    pub network: Option<Network>,
    /// Its objective, as [`crate::design::Objective::of`] computes it.
    pub objective: Option<f64>,
    /// The best objective each time it improved.
    pub trace: Vec<TracePoint>,
    /// Why the search stopped.
    pub stop: Stop,
    /// With [`Stop::Infeasible`]: why no design exists.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub infeasible: Option<String>,
    /// Counters.
    pub stats: SearchStats,
    /// Seconds spent.
    pub seconds: f64,
}

/// A proof that no design exists, when one is plain: the design cannot be empty (coverage needs
/// an active vertex, rooms a corridor or a traversal, forced elements their edges) and no sink
/// has an edge that is not excluded, so no active edge could reach a sink.
pub fn obvious_infeasibility(p: &Problem) -> Option<String> {
    let mesh = &p.mesh;
    let nonempty = (p.rooms.is_none() && mesh.vertices().any(|v| !p.is_obstacle_vertex[v.index()]))
        || (p.rooms.is_some() && mesh.faces().any(|f| !p.is_obstacle_face[f.index()]))
        || !p.forced_edges.is_empty()
        || !p.forced_vertices.is_empty()
        || !p.through_routes.is_empty();
    let sink_usable = mesh.vertices().any(|v| {
        p.is_sink[v.index()] && mesh.incident_edges(v).any(|e| p.roles[e.index()] != crate::spec::EdgeRole::Excluded)
    });
    (nonempty && !sink_usable).then(|| {
        let sinks: Vec<String> = mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| format!("v{}", v.0)).collect();
        format!("no sink ({}) has an edge that is not a wall or an obstacle, yet the design cannot be empty: nothing could reach a sink", sinks.join(", "))
    })
}

impl SearchOutput {
    fn infeasible(why: String, t0: Instant) -> SearchOutput {
        SearchOutput {
            network: None,
            objective: None,
            trace: Vec::new(),
            stop: Stop::Infeasible,
            infeasible: Some(why),
            stats: SearchStats::default(),
            seconds: t0.elapsed().as_secs_f64(),
        }
    }

    fn none(stop: Stop, stats: SearchStats, t0: Instant) -> SearchOutput {
        SearchOutput {
            network: None,
            objective: None,
            trace: Vec::new(),
            stop,
            infeasible: None,
            stats,
            seconds: t0.elapsed().as_secs_f64(),
        }
    }
}

/// Whether a design passes the independent validator (items 1–6).
pub fn is_valid(p: &Problem, inputs: &Inputs, net: &Network) -> bool {
    if !design::validate(p, net, inputs.paths).is_empty() {
        return false;
    }
    match (&p.rooms, inputs.placements) {
        (Some(_), Some(pl)) => design::validate_rooms(p, net, pl, &net.rooms).is_empty(),
        (Some(_), None) => false,
        _ => true,
    }
}

/// Keeps the best validated design and the trace.
struct Best<'i, 'p> {
    p: &'p Problem,
    inputs: &'i Inputs<'i>,
    t0: Instant,
    network: Option<Network>,
    objective: f64,
    trace: Vec<TracePoint>,
    rejected: u64,
    /// This thread's work count when the search began.
    work0: u64,
    /// The work (since `work0`) at which the first valid design was offered.
    first_at: Option<u64>,
}

impl<'i, 'p> Best<'i, 'p> {
    fn new(p: &'p Problem, inputs: &'i Inputs<'i>, t0: Instant) -> Self {
        Best {
            p,
            inputs,
            t0,
            network: None,
            objective: f64::INFINITY,
            trace: Vec::new(),
            rejected: 0,
            work0: budget::spent(),
            first_at: None,
        }
    }

    /// Work since the search began.
    fn work(&self) -> u64 {
        budget::spent().wrapping_sub(self.work0)
    }

    fn offer(&mut self, net: Network) {
        self.offer_reached(net, Vec::new());
    }

    /// Offers a design that a search reached through the improvements `reached` (when each
    /// objective was first reached, the last being this design's): if the design is valid and
    /// better, the improvements below the previous best join the trace at their own times.
    fn offer_reached(&mut self, net: Network, reached: Vec<TracePoint>) {
        let obj = design::Objective::of(self.p, &net).total;
        if obj >= self.objective - 1e-9 {
            return;
        }
        if !is_valid(self.p, self.inputs, &net) {
            self.rejected += 1;
            return;
        }
        for t in reached {
            if t.objective < self.objective - 1e-9 && t.objective > obj + 1e-9 {
                self.objective = t.objective;
                self.trace.push(t);
            }
        }
        self.objective = obj;
        self.network = Some(net);
        if self.first_at.is_none() {
            self.first_at = Some(self.work());
        }
        self.trace.push(TracePoint { seconds: self.t0.elapsed().as_secs_f64(), objective: obj });
    }
}

/// Construction and local search, restarted until the budget (or the construction count): the
/// best valid design found. With `opts.threads` > 1, that many independent searches run side by
/// side and the best design of all is kept (ties: the lowest-numbered search's).
///
/// The result depends on the spec and `opts` only, not on timing (unless the wall-clock net of
/// [`budget`] stops a search, or the clock ends the wait for a first design). Each search's
/// course is a function of its own work count; one that has no design at the budget waits for
/// its first (up to `first_design_limit`) until another has found one with less work; and a
/// design counts only when its search found its first design within the budget, or, when none
/// did, with the least work of all.
pub fn heuristic(p: &Problem, inputs: &Inputs, opts: &Options) -> SearchOutput {
    let t0 = Instant::now();
    if let Some(why) = obvious_infeasibility(p) {
        return SearchOutput::infeasible(why, t0);
    }
    let found = AtomicU64::new(u64::MAX);
    let outputs: Vec<(SearchOutput, Option<u64>)> = if opts.threads <= 1 {
        vec![search(p, inputs, opts, 0, &found, t0)]
    } else {
        std::thread::scope(|scope| {
            let found = &found;
            let workers: Vec<_> =
                (0..opts.threads).map(|k| scope.spawn(move || search(p, inputs, opts, k, found, t0))).collect();
            workers.into_iter().map(|w| w.join().expect("a heuristic search thread panicked")).collect()
        })
    };
    merge_outputs(outputs, budget::units(opts.time_limit), t0)
}

/// The output of side-by-side searches (each with the work at which it found its first design):
/// the best design (the first search's on ties) among those that count — found first within
/// `budget_work`, or else with the least work of all — every counter summed, the running best
/// over their traces, the first search's reason to stop.
fn merge_outputs(outputs: Vec<(SearchOutput, Option<u64>)>, budget_work: u64, t0: Instant) -> SearchOutput {
    let least = outputs.iter().filter_map(|(_, w)| *w).min().unwrap_or(u64::MAX);
    let cutoff = least.max(budget_work);
    let mut stats = SearchStats::default();
    let mut points: Vec<TracePoint> = Vec::new();
    let mut kept = Vec::new();
    let stop = outputs[0].0.stop;
    for (o, first_at) in outputs {
        stats += &o.stats;
        if first_at.is_some_and(|w| w <= cutoff) {
            points.extend(&o.trace);
            kept.push(o);
        }
    }
    points.sort_by(|a, b| a.seconds.total_cmp(&b.seconds));
    let mut trace: Vec<TracePoint> = Vec::new();
    for pt in points {
        if trace.last().is_none_or(|last| pt.objective < last.objective) {
            trace.push(pt);
        }
    }
    let best = kept
        .into_iter()
        .filter(|o| o.network.is_some())
        .min_by(|a, b| a.objective.unwrap_or(f64::INFINITY).total_cmp(&b.objective.unwrap_or(f64::INFINITY)));
    let (network, objective) = best.map_or((None, None), |o| (o.network, o.objective));
    SearchOutput { network, objective, trace, stop, infeasible: None, stats, seconds: t0.elapsed().as_secs_f64() }
}

/// One search of [`heuristic`]: search `worker` of `opts.threads`. `found` holds the least work
/// at which any search has found its first design; without a design of its own, a search past
/// its budget stops waiting once its work reaches that. Returns the output and the work at which
/// its first design was found.
fn search(
    p: &Problem,
    inputs: &Inputs,
    opts: &Options,
    worker: usize,
    found: &AtomicU64,
    t0: Instant,
) -> (SearchOutput, Option<u64>) {
    let deadline = Deadline::after(opts.time_limit);
    // Without a design yet, constructions may go on until this later deadline.
    let first_deadline = match opts.first_design_limit {
        Some(first) if first > opts.time_limit => Deadline::on_clock(first),
        _ => deadline,
    };
    // Search k > 0 draws from its own seed, and its first construction is noisy too (the
    // noise-free one is search 0's).
    let seed = if worker == 0 { opts.seed } else { opts.seed ^ (worker as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) };
    let mut rng = Rng::new(seed);
    let mut best = Best::new(p, inputs, t0);
    let mut stats = SearchStats::default();
    let network_rules = p.rooms.is_none().then(|| Rules::new(p, inputs.paths, None, None));
    let mut stop = Stop::TimeLimit;
    loop {
        if let Some(w) = best.first_at {
            found.fetch_min(w, Ordering::Relaxed);
        }
        // The limit of this construction depends on this search alone (its course must not
        // depend on the others' timing); whether to wait on does not change what counts.
        let limit = if best.network.is_some() { deadline } else { first_deadline };
        let waited_enough = best.network.is_none() && best.work() >= found.load(Ordering::Relaxed);
        if limit.passed() || (deadline.passed() && waited_enough) {
            break;
        }
        if opts.max_constructions.is_some_and(|m| stats.constructions as usize >= m)
            || opts.max_designs.is_some_and(|m| stats.constructed as usize >= m)
        {
            stop = Stop::Exhausted;
            break;
        }
        stats.constructions += 1;
        let noise = if stats.constructions == 1 && worker == 0 { 0.0 } else { 0.4 };
        let mut sub = rng.fork();
        // Half the budget left goes to improving this construction.
        let slice = deadline.share(2);
        let polish = |rules: &Rules, s: State, sub: &mut Rng, best: &mut Best, stats: &mut SearchStats| {
            stats.constructed += 1;
            best.offer(s.network(rules));
            if !opts.local_search {
                return;
            }
            let b = Builder::new(rules, s, sub.fork(), 0.3, Some(slice));
            let ls = LocalSearch::new(b);
            // When each improvement was reached (the search keeps every rule as it goes; the
            // design it ends with is validated by `offer_reached`).
            let mut reached = Vec::new();
            let (s, _, ls_stats) =
                ls.run(slice, |obj| reached.push(TracePoint { seconds: t0.elapsed().as_secs_f64(), objective: obj }));
            stats.moves_tried += ls_stats.tried;
            stats.moves_accepted += ls_stats.accepted;
            stats.kicks += ls_stats.kicks;
            best.offer_reached(s.network(rules), reached);
        };
        match (&network_rules, inputs.placements) {
            (Some(rules), _) => {
                let mut b = Builder::new(rules, State::new(rules), sub.fork(), noise, Some(limit));
                // Where dead-ends are allowed, every other construction covers by the shortest
                // arms (spurs from the network) instead.
                b.short_arms = !rules.dead_end_forbid && stats.constructions % 2 == 0;
                if b.repair_all() && b.s.feasible(rules) {
                    polish(rules, b.s, &mut sub, &mut best, &mut stats);
                }
            }
            (None, Some(placements)) => {
                if let Some((rules, s)) =
                    rooms::construct(p, placements, inputs.paths, &mut sub, noise, limit, stats.constructions - 1)
                {
                    polish(&rules, s, &mut sub, &mut best, &mut stats);
                }
            }
            (None, None) => {
                stop = Stop::Exhausted;
                break;
            }
        }
    }
    stats.rejected = best.rejected;
    stats.work = best.work();
    let first_at = best.first_at;
    let out = SearchOutput {
        objective: best.network.as_ref().map(|_| best.objective),
        network: best.network,
        trace: best.trace,
        stop,
        infeasible: None,
        stats,
        seconds: t0.elapsed().as_secs_f64(),
    };
    (out, first_at)
}

/// The paper's stochastic search (module `anneal`): several seeded passes from the all-active
/// start, the best valid design over all passes.
pub fn anneal(p: &Problem, inputs: &Inputs, opts: &AnnealOptions) -> SearchOutput {
    let t0 = Instant::now();
    if let Some(why) = obvious_infeasibility(p) {
        return SearchOutput::infeasible(why, t0);
    }
    let deadline = Deadline::after(opts.time_limit);
    let mut best = Best::new(p, inputs, t0);
    let mut stats = SearchStats::default();
    // Room problems: one tiling for every pass, one the construction can build a design on.
    let rules = if p.rooms.is_some() {
        let Some(placements) = inputs.placements else {
            return SearchOutput::none(Stop::Exhausted, stats, t0);
        };
        let mut rng = Rng::new(opts.seed);
        let tiling_deadline = Deadline::after(opts.time_limit * 0.2);
        let mut found = None;
        while found.is_none() && !tiling_deadline.passed() {
            found = rooms::construct(p, placements, inputs.paths, &mut rng, 0.0, tiling_deadline, stats.constructions)
                .map(|(r, _)| r.tiling.expect("tiled").rooms);
            stats.constructions += 1;
        }
        let Some(rooms) = found else {
            return SearchOutput::none(Stop::TimeLimit, stats, t0);
        };
        Rules::new(p, inputs.paths, Some(placements), Some(Tiling { rooms }))
    } else {
        Rules::new(p, inputs.paths, None, None)
    };
    let passes = opts.passes.max(1);
    let mut global = f64::INFINITY;
    let mut trace = Vec::new();
    let mut all_exhausted = true;
    for k in 0..passes {
        if deadline.passed() {
            all_exhausted = false;
            break;
        }
        let pass_deadline = deadline.share((passes - k) as u64);
        let res =
            anneal::pass(&rules, opts, opts.seed.wrapping_add(k as u64), pass_deadline, t0, &mut trace, &mut global);
        stats.passes += 1;
        stats.steps += res.steps;
        all_exhausted &= res.exhausted;
        if let Some((s, _)) = res.best {
            best.offer(s.network(&rules));
        }
    }
    stats.rejected = best.rejected;
    stats.work = best.work();
    // The trace of the passes (every improvement of a zero-count state), restricted to what the
    // validator accepted: the final point is the returned design.
    let mut trace: Vec<TracePoint> = trace.into_iter().filter(|t| t.objective >= best.objective - 1e-9).collect();
    if trace.is_empty() {
        trace = best.trace.clone();
    }
    SearchOutput {
        objective: best.network.as_ref().map(|_| best.objective),
        network: best.network,
        trace,
        stop: if all_exhausted { Stop::Exhausted } else { Stop::TimeLimit },
        infeasible: None,
        stats,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Turns a design that breaks connectivity (islands) or local rules into a valid one when it
/// can: islands are joined to the network or dropped, then coverage, rooms, dead-ends and
/// forbidden configurations are mended by the construction's rule steps (module `build`),
/// within `budget` seconds. A room problem keeps the design's tiling (its `rooms`, indices into
/// `inputs.placements`) and needs it to be an exact tiling with valid counts; otherwise `None`.
/// Returns only validated designs.
pub fn repair_within(p: &Problem, inputs: &Inputs, net: &Network, budget: f64) -> Option<Network> {
    let deadline = Deadline::after(budget);
    if net.active.len() != p.mesh.num_edges() {
        return None;
    }
    let tiling = match (&p.rooms, inputs.placements) {
        (None, _) => None,
        (Some(_), None) => return None,
        (Some(_), Some(pl)) => {
            if net.rooms.iter().any(|&k| k >= pl.len()) {
                return None;
            }
            let tiling_only = design::validate_rooms(
                p,
                &Network { active: vec![false; p.mesh.num_edges()], ..net.clone() },
                pl,
                &net.rooms,
            );
            if tiling_only
                .iter()
                .any(|v| matches!(v, design::Violation::Cover { .. } | design::Violation::RoomCount { .. }))
            {
                return None;
            }
            Some(Tiling { rooms: net.rooms.clone() })
        }
    };
    let rules = Rules::new(p, inputs.paths, inputs.placements, tiling);
    let start: Vec<bool> = net.active.iter().zip(&rules.allowed).map(|(&a, &ok)| a && ok).collect();
    let s = State::from_active(&rules, &start);
    let mut b = Builder::new(&rules, s, Rng::new(0), 0.0, Some(deadline));
    if !b.repair_all() || !b.s.feasible(&rules) || !rules.shape_ok(&b.s) {
        return None;
    }
    let out = b.s.network(&rules);
    is_valid(p, inputs, &out).then_some(out)
}

/// [`repair_within`] with a one-second budget.
pub fn repair(p: &Problem, inputs: &Inputs, net: &Network) -> Option<Network> {
    repair_within(p, inputs, net, 1.0)
}

/// The heuristic's best design within `budget` seconds (construction and local search), for a
/// MIP start (the pipeline encodes and checks it before a solver sees it).
pub fn start(p: &Problem, inputs: &Inputs, budget: f64, seed: u64) -> Option<Network> {
    start_within(p, inputs, budget, budget, seed, 1)
}

/// [`start`] that, while it has no design, goes on past `budget` up to `first_design_budget`
/// seconds on the clock to find one (a hard instance's first design is worth more than the
/// solver's first seconds; once one is found the search stops at `budget`), with `threads`
/// searches side by side ([`Options::threads`]).
pub fn start_within(
    p: &Problem,
    inputs: &Inputs,
    budget: f64,
    first_design_budget: f64,
    seed: u64,
    threads: usize,
) -> Option<Network> {
    heuristic(
        p,
        inputs,
        &Options {
            time_limit: budget,
            seed,
            first_design_limit: Some(first_design_budget),
            threads,
            ..Options::default()
        },
    )
    .network
}
