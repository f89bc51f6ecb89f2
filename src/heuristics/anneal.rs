//! The paper's stochastic search (Peng et al. 2016, §6 "Stochastic search", Fig. 13), as its
//! baseline:
//!
//! > Beginning at a trivial solution (e.g., every edge is active), the approach iteratively
//! > performs the following types of operations to alter the current solution: (i) deleting a
//! > single edge, (ii) deleting a pair of adjacent edges, (iii) deleting a triple of consecutive
//! > edges, and (iv) adding a single edge. At each iteration, we enumerate all possible feasible
//! > operations, rank them according to the new objective values (the lower the better), and
//! > pick one to perform. We pick operations in a simulated annealing sense (i.e., the higher
//! > ranked the larger chance to be picked, and such tendency becomes more absolute at each
//! > iteration). The approach stops when there are no feasible solutions or a time limit is
//! > reached. […] We run the approach multiple passes and pick the best solution.
//!
//! What this implementation fixes where the text leaves a choice:
//!
//! - **Start.** Every usable edge active (for floor plans and game levels, every edge the
//!   tiling allows — the rooms come from one seeded exact tiling, [`super::tiling`], the same in
//!   every pass).
//! - **Feasible.** The all-active start can break rules of its own: a too-close pair on every
//!   quad where too-close pairs are forbidden, branches where they are forbidden, through-route
//!   vertices of degree 4. The rules the start satisfies (no islands, coverage, dead-ends,
//!   forced elements, point-to-point paths, room rules) are hard: an operation that breaks one is
//!   infeasible. The rules the start breaks are counted, and an operation may not increase that
//!   count; operations are ranked by (count, objective), so the search first works the count
//!   down. Only states with a zero count (and a valid block graph for game levels) are designs;
//!   the best of them is returned and validated like any other.
//! - **Annealing.** The operation of rank `i` (0 = best) is picked with probability
//!   proportional to `exp(−i / T)`, with `T = t0 · cooling^k` at step `k` (defaults `t0 = 10`,
//!   `cooling = 0.99`): nearly uniform over the top ranks at first, greedy after a few hundred
//!   steps.
//! - **Passes.** The time limit is split evenly over the passes (default 4); each pass has its
//!   own seed. A pass ends when no operation is feasible or its time is up.

use super::budget::Deadline;
use super::rng::Rng;
use super::state::{Counts, Rules, State};
use super::TracePoint;
use crate::mesh::{EdgeId, VertexId};
use std::time::Instant;

/// Settings of the stochastic search.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct AnnealOptions {
    /// Total time for all passes, seconds.
    pub time_limit: f64,
    /// Seed of the first pass (pass `k` uses `seed + k`).
    pub seed: u64,
    /// Number of passes.
    pub passes: usize,
    /// Initial temperature, in ranks.
    pub t0: f64,
    /// Factor applied to the temperature after every step.
    pub cooling: f64,
}

impl Default for AnnealOptions {
    fn default() -> Self {
        AnnealOptions { time_limit: 60.0, seed: 0, passes: 4, t0: 10.0, cooling: 0.99 }
    }
}

/// One operation of the paper's move set.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Operation {
    /// (i) Delete one edge.
    Delete1(EdgeId),
    /// (ii) Delete two edges sharing a vertex.
    Delete2(EdgeId, EdgeId),
    /// (iii) Delete three consecutive edges (a path `e1, e2, e3`).
    Delete3(EdgeId, EdgeId, EdgeId),
    /// (iv) Add one edge.
    Add(EdgeId),
}

impl Operation {
    /// The edges it switches.
    pub fn edges(&self) -> Vec<EdgeId> {
        match *self {
            Operation::Delete1(a) | Operation::Add(a) => vec![a],
            Operation::Delete2(a, b) => vec![a, b],
            Operation::Delete3(a, b, c) => vec![a, b, c],
        }
    }
}

/// Every operation of the move set on the active edges `active`: deletions of one active free
/// edge, of two active free edges sharing a vertex, of three consecutive active free edges (a
/// simple path; each path once, named from one end), and additions of one inactive allowed
/// edge. Feasibility is not checked here. Deterministic order.
pub(crate) fn operations(r: &Rules, active: &[bool]) -> Vec<Operation> {
    let mesh = r.mesh;
    let free_on = |e: EdgeId| active[e.index()] && r.free(e);
    let mut out = Vec::new();
    for e in mesh.edges() {
        if free_on(e) {
            out.push(Operation::Delete1(e));
        }
    }
    for v in mesh.vertices() {
        let es: Vec<EdgeId> = mesh.incident_edges(v).filter(|&e| free_on(e)).collect();
        for i in 0..es.len() {
            for j in i + 1..es.len() {
                out.push(Operation::Delete2(es[i].min(es[j]), es[i].max(es[j])));
            }
        }
    }
    for e2 in mesh.edges() {
        if !free_on(e2) {
            continue;
        }
        let (a, b) = mesh.edge_vertices(e2);
        for e1 in mesh.incident_edges(a).filter(|&e| e != e2 && free_on(e)) {
            let far1 = other(mesh, e1, a);
            for e3 in mesh.incident_edges(b).filter(|&e| e != e2 && e != e1 && free_on(e)) {
                let far3 = other(mesh, e3, b);
                if far1 == b || far3 == a {
                    continue;
                }
                // The path e1, e2, e3 read from either end is the same operation.
                if e1 <= e3 {
                    out.push(Operation::Delete3(e1, e2, e3));
                } else {
                    out.push(Operation::Delete3(e3, e2, e1));
                }
            }
        }
    }
    for e in mesh.edges() {
        if !active[e.index()] && r.free(e) {
            out.push(Operation::Add(e));
        }
    }
    out
}

fn other(mesh: &crate::mesh::Mesh, e: EdgeId, v: VertexId) -> VertexId {
    let (a, b) = mesh.edge_vertices(e);
    if a == v {
        b
    } else {
        a
    }
}

/// Which counts the start satisfies (hard) — the rest are worked down (soft).
#[derive(Clone, Copy, Debug)]
struct Split {
    hard: [bool; 10],
}

fn parts(c: &Counts) -> [i64; 10] {
    [
        c.uncovered,
        c.dead_ends,
        c.branches,
        c.configs,
        c.tjunctions,
        c.routes,
        c.forced_vertices,
        c.forced_edges,
        c.pairs,
        c.groups,
    ]
}

impl Split {
    fn of(start: &Counts) -> Split {
        let p = parts(start);
        Split { hard: p.map(|x| x == 0) }
    }
    fn hard_ok(&self, c: &Counts) -> bool {
        parts(c).iter().zip(self.hard).all(|(&x, h)| !h || x == 0)
    }
    fn soft(&self, c: &Counts) -> i64 {
        parts(c).iter().zip(self.hard).filter(|(_, h)| !h).map(|(&x, _)| x).sum()
    }
}

/// Whether the state after `op` (already applied) is feasible — hard rules hold, the soft
/// count (by `soft_of`, `None` when a hard rule breaks) is at most `limit`, no island — and if
/// so its (soft count, objective).
pub(crate) fn judge(
    r: &Rules,
    s: &mut State,
    op: &Operation,
    limit: i64,
    soft_of: &dyn Fn(&Counts) -> Option<i64>,
) -> Option<(i64, f64)> {
    let soft = soft_of(&s.counts)?;
    if soft > limit {
        return None;
    }
    match *op {
        Operation::Add(e) => {
            // An edge between two vertices that had none is an island (unless at a sink).
            let (a, b) = r.mesh.edge_vertices(e);
            if s.deg[a.index()] == 1 && s.deg[b.index()] == 1 && !r.is_sink(a) && !r.is_sink(b) {
                return None;
            }
        }
        _ => {
            for e in op.edges() {
                let (a, b) = r.mesh.edge_vertices(e);
                if !s.reaches_sink(r, a) || !s.reaches_sink(r, b) {
                    return None;
                }
            }
        }
    }
    Some((soft, s.objective(r)))
}

fn set(r: &Rules, s: &mut State, op: &Operation) {
    for e in op.edges() {
        s.toggle(r, e);
    }
}

/// The result of one pass.
pub(crate) struct PassResult {
    pub best: Option<(State, f64)>,
    pub steps: u64,
    pub exhausted: bool,
}

/// One pass from the all-active start until no operation is feasible or `deadline`.
pub(crate) fn pass(
    r: &Rules,
    opts: &AnnealOptions,
    seed: u64,
    deadline: Deadline,
    t_start: Instant,
    trace: &mut Vec<TracePoint>,
    global_best: &mut f64,
) -> PassResult {
    let mut rng = Rng::new(seed);
    let mut s = State::from_active(r, &r.allowed);
    let split = Split::of(&s.counts);
    let soft_of = |c: &Counts| if split.hard_ok(c) { Some(split.soft(c)) } else { None };
    let mut soft = split.soft(&s.counts);
    let mut best: Option<(State, f64)> = None;
    let mut temperature = opts.t0;
    let mut steps = 0u64;
    let record =
        |s: &State, soft: i64, best: &mut Option<(State, f64)>, trace: &mut Vec<TracePoint>, global_best: &mut f64| {
            if soft != 0 || !s.islands(r).is_empty() || !r.shape_ok(s) {
                return;
            }
            let obj = s.objective(r);
            if best.as_ref().is_none_or(|(_, b)| obj < *b - 1e-9) {
                *best = Some((s.clone(), obj));
            }
            if obj < *global_best - 1e-9 {
                *global_best = obj;
                trace.push(TracePoint { seconds: t_start.elapsed().as_secs_f64(), objective: obj });
            }
        };
    record(&s, soft, &mut best, trace, global_best);
    let mut exhausted = false;
    while !deadline.passed() {
        let ops = operations(r, &s.active);
        let mut ranked: Vec<(i64, f64, usize)> = Vec::new();
        for (i, op) in ops.iter().enumerate() {
            if i % 256 == 0 && deadline.passed() {
                break;
            }
            set(r, &mut s, op);
            if let Some((sf, obj)) = judge(r, &mut s, op, soft, &soft_of) {
                ranked.push((sf, obj, i));
            }
            set(r, &mut s, op);
        }
        if deadline.passed() {
            break;
        }
        if ranked.is_empty() {
            exhausted = true;
            break;
        }
        ranked.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.cmp(&b.2)));
        let pick = pick_rank(&mut rng, ranked.len(), temperature);
        let (sf, _, i) = ranked[pick];
        set(r, &mut s, &ops[i]);
        soft = sf;
        steps += 1;
        temperature *= opts.cooling;
        record(&s, soft, &mut best, trace, global_best);
    }
    PassResult { best, steps, exhausted }
}

/// A rank in `0..n`, rank `i` with probability proportional to `exp(−i / T)`.
pub(crate) fn pick_rank(rng: &mut Rng, n: usize, temperature: f64) -> usize {
    if temperature <= 1e-9 || n == 1 {
        return 0;
    }
    let ratio = (-1.0 / temperature).exp();
    // Truncated geometric distribution by inversion.
    let u = rng.unit();
    let total = if ratio < 1.0 { (1.0 - ratio.powi(n as i32)) / (1.0 - ratio) } else { n as f64 };
    let mut acc = 0.0;
    let mut w = 1.0;
    for i in 0..n {
        acc += w / total;
        if u < acc {
            return i;
        }
        w *= ratio;
        if w < 1e-12 {
            return i;
        }
    }
    n - 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{self, EdgeId};
    use crate::spec::Spec;
    use std::path::Path;

    /// A 2×1 grid (two squares side by side), every edge a candidate:
    ///
    /// ```text
    /// 3 --e5-- 4 --e6-- 5        vertex ids 0..5, edge ids as the mesh numbers them
    /// |        |        |
    /// 0 ------ 1 ------ 2
    /// ```
    fn problem() -> crate::spec::Problem {
        let text =
            "name = \"two\"\nboundary = \"candidate\"\n[mesh]\ngrid = { width = 2, height = 1 }\n[sinks]\nvertices = [0]\n[features]\ndead_ends = \"allow\"\n";
        Spec::from_toml(text).unwrap().resolve(Path::new(".")).unwrap()
    }

    fn edge(p: &crate::spec::Problem, a: u32, b: u32) -> EdgeId {
        let m = &p.mesh;
        m.he_edge(m.half_edge_between(mesh::VertexId(a), mesh::VertexId(b)).unwrap())
    }

    #[test]
    fn move_set_on_a_hand_built_network() {
        let p = problem();
        assert_eq!(p.mesh.num_edges(), 7);
        let r = Rules::new(&p, None, None, None);
        // Active: the path 0-1-2-5-4 (four edges); inactive: 0-3, 3-4, 1-4.
        let on = [edge(&p, 0, 1), edge(&p, 1, 2), edge(&p, 2, 5), edge(&p, 5, 4)];
        let mut active = vec![false; 7];
        for e in on {
            active[e.index()] = true;
        }
        let ops = operations(&r, &active);
        let count = |f: fn(&Operation) -> bool| ops.iter().filter(|o| f(o)).count();
        // (i) one deletion per active edge.
        assert_eq!(count(|o| matches!(o, Operation::Delete1(_))), 4);
        // (ii) a pair per vertex where two active edges meet: at 1, 2 and 5.
        assert_eq!(count(|o| matches!(o, Operation::Delete2(..))), 3);
        // (iii) the consecutive triples of the path 0-1-2-5-4: 0-1-2-5 and 1-2-5-4.
        assert_eq!(count(|o| matches!(o, Operation::Delete3(..))), 2);
        // (iv) one addition per inactive edge.
        assert_eq!(count(|o| matches!(o, Operation::Add(_))), 3);
        let triple = |a: EdgeId, b: EdgeId, c: EdgeId| Operation::Delete3(a.min(c), b, a.max(c));
        assert!(ops.contains(&triple(edge(&p, 0, 1), edge(&p, 1, 2), edge(&p, 2, 5))));
        assert!(ops.contains(&triple(edge(&p, 1, 2), edge(&p, 2, 5), edge(&p, 5, 4))));
        assert!(ops.contains(&Operation::Add(edge(&p, 1, 4))));
        assert!(!ops.contains(&Operation::Delete1(edge(&p, 0, 3))));
        // Deterministic: the same list every time.
        assert_eq!(ops, operations(&r, &active));
    }

    #[test]
    fn a_cycle_gives_each_triple_once() {
        let p = problem();
        let r = Rules::new(&p, None, None, None);
        // The square 0-1-4-3: four triples around it, each named once.
        let mut active = vec![false; 7];
        for (a, b) in [(0, 1), (1, 4), (4, 3), (3, 0)] {
            active[edge(&p, a, b).index()] = true;
        }
        let ops = operations(&r, &active);
        let triples: Vec<&Operation> = ops.iter().filter(|o| matches!(o, Operation::Delete3(..))).collect();
        assert_eq!(triples.len(), 4, "{triples:?}");
        assert_eq!(ops.iter().filter(|o| matches!(o, Operation::Delete2(..))).count(), 4);
    }

    #[test]
    fn fixed_edges_are_never_deleted() {
        let text =
            "name = \"two\"\nboundary = \"road\"\n[mesh]\ngrid = { width = 2, height = 1 }\n[sinks]\nall_boundary = true\n[features]\ndead_ends = \"allow\"\n";
        let p = Spec::from_toml(text).unwrap().resolve(Path::new(".")).unwrap();
        let r = Rules::new(&p, None, None, None);
        // Every boundary edge is an existing road; only the middle edge 1-4 is free.
        let active = vec![true; 7];
        let ops = operations(&r, &active);
        assert_eq!(ops, vec![Operation::Delete1(edge(&p, 1, 4))]);
    }

    #[test]
    fn rank_picks_follow_the_temperature() {
        let mut rng = Rng::new(7);
        // Frozen: always the best.
        assert!((0..100).all(|_| pick_rank(&mut rng, 50, 0.0) == 0));
        // Hot: spread over the ranks, better ranks more often.
        let mut hist = [0usize; 10];
        for _ in 0..20_000 {
            hist[pick_rank(&mut rng, 10, 3.0)] += 1;
        }
        assert!(hist.windows(2).all(|w| w[0] > w[1]), "{hist:?}");
        assert!(hist[9] > 0);
    }
}
