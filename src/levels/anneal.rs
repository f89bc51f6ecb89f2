//! The paper's stochastic method (Ma et al. 2014, §3.2–3.3): the graph split into chains
//! (shortest cycles first, each next one touching what is laid out, trees last in breadth-first
//! order), an incremental layout over a stack of partial layouts with backtracking, and
//! simulated annealing per chain with the paper's energy `E = e^{A/σ} e^{D/σ} − 1`, moves
//! sampled from the intersection of the neighbours' configuration spaces, its schedule
//! (n = 50 cycles of m = 500 trials, temperature 0.6 → 0.2) and the rule that keeps only
//! layouts that differ.
//!
//! The planar embedding the paper takes its faces from is replaced by shortest cycles through
//! each edge (on a planar graph, the inner faces are such cycles); the embedding only orders
//! the chains. Three additions make it finish where a layout exists:
//! - a chain is first placed exactly ([`super::construct`]): each node in the intersection of
//!   all its placed neighbours' configuration spaces, clear of every placed block, by a
//!   depth-first search with look-ahead — where a cycle closes, that is the exact point; the
//!   paper's annealing runs from the deepest placement when this fails;
//! - long chains are laid out in pieces of at most [`AnnealOptions::piece`] nodes;
//! - extensions are made when the stack needs them (each popped partial layout is extended
//!   again, with other random choices, up to [`AnnealOptions::partial_variations`] times), and
//!   an exhausted stack restarts with the next cycle first and twice the variations, until
//!   `count` layouts, the time limit, or the stop request.
//!
//! Every layout returned has passed [`super::validate::validate`].

use super::construct::{Placer, Slot};
use super::cspace::{clip_out, intersect, CSpaces, Segment};
use super::spec::{shortest_cycle, BlockId, Level, NodeId};
use super::validate::validate;
use super::{Layout, Placement};
use crate::geometry::convex::{self, length, AREA_TOL};
use crate::geometry::{self, sub, P};
use crate::solvers::Interrupt;
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use serde::Serialize;
use std::collections::{BTreeSet, VecDeque};
use std::time::Instant;

/// Settings of the annealer (defaults: the paper's schedule).
#[derive(Clone, Debug)]
pub struct AnnealOptions {
    /// Seed of every random choice.
    pub seed: u64,
    /// Full layouts wanted.
    pub count: usize,
    /// Seconds for the whole search.
    pub time_limit: f64,
    /// Cooling cycles per chain (n).
    pub cycles: usize,
    /// Trials per cycle (m).
    pub trials: usize,
    /// Initial temperature.
    pub t0: f64,
    /// Final temperature.
    pub t1: f64,
    /// Extensions made of one partial layout before the search backtracks past it.
    pub partial_variations: usize,
    /// Longest piece a chain is laid out in (nodes).
    pub piece: usize,
    /// Placements the exact start may try per chain node.
    pub place_budget: usize,
    /// Restarts once the stack runs empty (each with the next cycle first and twice the
    /// variations); `usize::MAX` for as many as the time limit allows.
    pub restarts: usize,
    /// A request to stop (another method has settled the question).
    pub stop: Option<Interrupt>,
}

impl Default for AnnealOptions {
    fn default() -> Self {
        AnnealOptions {
            seed: 1,
            count: 1,
            time_limit: 60.0,
            cycles: 50,
            trials: 500,
            t0: 0.6,
            t1: 0.2,
            partial_variations: 15,
            piece: 12,
            place_budget: 200,
            restarts: usize::MAX,
            stop: None,
        }
    }
}

/// What the annealer found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct AnnealReport {
    /// Distinct full layouts, each validated.
    #[serde(skip)]
    pub layouts: Vec<Layout>,
    /// The chains (pieces), in processing order (node names), of the last start.
    pub chains: Vec<Vec<String>>,
    /// Seconds to the first layout.
    pub time_to_first: Option<f64>,
    /// Seconds to the last layout found.
    pub time_to_last: Option<f64>,
    /// Perturbation trials made in all.
    pub trials: u64,
    /// Trials made when the last layout was found.
    pub trials_to_last: u64,
    /// Partial layouts popped from the stack (backtracks included).
    pub extensions: usize,
    /// Chain extensions the exact start completed without annealing.
    pub exact_extensions: usize,
    /// Restarts after the stack ran empty.
    pub restarts: usize,
    /// Why the search stopped: `count`, `exhausted` (the stack ran empty and no restart was
    /// left), `time limit` or `stopped` (another method answered).
    pub stopped: String,
}

/// The distinct shortest cycles through the edges, shortest first (each rotated to its least
/// node, that node's smaller neighbour next).
fn cycles(level: &Level, adj: &[Vec<NodeId>]) -> Vec<Vec<NodeId>> {
    let mut cycles: Vec<Vec<NodeId>> = level
        .edges
        .iter()
        .filter_map(|&(a, b)| shortest_cycle(adj, a, b))
        .map(|mut c| {
            let i = c.iter().enumerate().min_by_key(|x| x.1).map_or(0, |x| x.0);
            c.rotate_left(i);
            if c.len() > 2 && c[c.len() - 1] < c[1] {
                c[1..].reverse();
            }
            c
        })
        .collect();
    cycles.sort_by(|x, y| x.len().cmp(&y.len()).then(x.cmp(y)));
    cycles.dedup();
    cycles
}

/// The chains: node sets in processing order. The first is the shortest cycle; each next one
/// is the shortest cycle touching the laid-out nodes that brings new nodes (its new nodes, in
/// cycle order); the nodes left come in breadth-first order from what is laid out. Fixed nodes,
/// if any, come before all of them as a chain of their own (their blocks are chosen before
/// anything is laid out where they must go), and every later chain then touches what is laid
/// out.
pub fn chains(level: &Level) -> Vec<Vec<NodeId>> {
    chains_from(level, 0)
}

/// [`chains`] with the `first`-th cycle (modulo their number) laid out first.
pub fn chains_from(level: &Level, first: usize) -> Vec<Vec<NodeId>> {
    let adj = level.adjacency(&level.all_edges());
    let mut cycles = cycles(level, &adj);
    if !cycles.is_empty() {
        let k = first % cycles.len();
        let c = cycles.remove(k);
        cycles.insert(0, c);
    }
    let mut placed: Vec<bool> = level.nodes.iter().map(|n| n.position.is_some()).collect();
    let fixed: Vec<NodeId> = (0..level.nodes.len() as u32).map(NodeId).filter(|n| placed[n.0 as usize]).collect();
    let mut out: Vec<Vec<NodeId>> = if fixed.is_empty() { Vec::new() } else { vec![fixed] };
    loop {
        let next = cycles.iter().find(|c| {
            let new = c.iter().any(|n| !placed[n.0 as usize]);
            let touches = out.is_empty() || c.iter().any(|n| placed[n.0 as usize]);
            new && touches
        });
        let Some(c) = next else { break };
        let new: Vec<NodeId> = c.iter().copied().filter(|n| !placed[n.0 as usize]).collect();
        for n in &new {
            placed[n.0 as usize] = true;
        }
        out.push(new);
    }
    if out.is_empty() {
        placed[0] = true;
        out.push(vec![NodeId(0)]);
    }
    // Trees: breadth-first from what is placed.
    let mut q: VecDeque<NodeId> = (0..level.nodes.len() as u32).map(NodeId).filter(|n| placed[n.0 as usize]).collect();
    let mut rest = Vec::new();
    while let Some(u) = q.pop_front() {
        for &v in &adj[u.0 as usize] {
            if !placed[v.0 as usize] {
                placed[v.0 as usize] = true;
                rest.push(v);
                q.push_back(v);
            }
        }
    }
    if !rest.is_empty() {
        out.push(rest);
    }
    out
}

/// Chains regrouped into pieces of about `size` nodes: long chains cut into consecutive
/// pieces of at most `size`, short consecutive ones joined while the piece stays within
/// `size` (each piece touches what the pieces before it lay out). The fixed nodes' chain stays
/// a piece of its own.
pub fn pieces(level: &Level, chains: Vec<Vec<NodeId>>, size: usize) -> Vec<Vec<NodeId>> {
    let size = size.max(1);
    let mut out: Vec<Vec<NodeId>> = Vec::new();
    let mut open = false;
    for (k, c) in chains.into_iter().enumerate() {
        let fixed = k == 0 && c.iter().all(|n| level.nodes[n.0 as usize].position.is_some());
        for part in c.chunks(size) {
            match out.last_mut() {
                Some(last) if open && !fixed && last.len() + part.len() <= size => last.extend_from_slice(part),
                _ => out.push(part.to_vec()),
            }
            open = !fixed;
        }
    }
    out
}

/// The energy's scales.
struct Shapes {
    sigma: f64,
    threshold: f64,
    /// The largest distance from a block's origin to one of its vertices.
    extent: f64,
}

impl Shapes {
    fn new(level: &Level) -> Shapes {
        let mean_area =
            level.blocks.iter().map(|b| geometry::signed_area(&b.polygon)).sum::<f64>() / level.blocks.len() as f64;
        let extent = level.blocks.iter().flat_map(|b| b.polygon.iter().map(|&p| length(p))).fold(0.0, f64::max);
        // The paper's σ: a hundred times the average block area. Two layouts differ when their
        // centred block centres move by more than a tenth of that area in all (squared).
        Shapes { sigma: 100.0 * mean_area, threshold: 0.1 * mean_area, extent }
    }
}

/// A valid extension and when it was found.
struct Found {
    slots: Vec<Slot>,
    seconds: f64,
    trials: u64,
}

/// The search's fixed data.
struct Search<'a> {
    level: &'a Level,
    cs: &'a CSpaces,
    placer: Placer<'a>,
    shapes: Shapes,
    adj: Vec<Vec<NodeId>>,
    rng: Xoshiro256PlusPlus,
    o: &'a AnnealOptions,
    t0: Instant,
    trials: u64,
    exact_extensions: usize,
    /// The nodes the current chain's energy is counted over: its members and the placed
    /// nodes near enough to touch them.
    local: Vec<usize>,
}

impl Search<'_> {
    fn overlap(&self, a: (BlockId, P), b: (BlockId, P)) -> f64 {
        if convex::boxes_apart(self.placer.placed_box(a), self.placer.placed_box(b)) {
            return 0.0;
        }
        convex::overlap_area(&self.placer.placed_tris(a), &self.placer.placed_tris(b))
    }

    /// The area of a placed block inside obstacles (each overlap above [`AREA_TOL`]).
    fn obstacle_area(&self, a: (BlockId, P)) -> f64 {
        let bx = self.placer.placed_box(a);
        let mut tris = None;
        let mut area = 0.0;
        for (ot, ob) in &self.placer.obstacles {
            if convex::boxes_apart(bx, *ob) {
                continue;
            }
            let ta = tris.get_or_insert_with(|| self.placer.placed_tris(a));
            let x = convex::overlap_area(ta, ot);
            if x > AREA_TOL {
                area += x;
            }
        }
        area
    }

    fn centre(&self, a: (BlockId, P)) -> P {
        self.placer.centre_of(a)
    }

    /// Node `i`'s share of the energy terms: overlap area with every placed block near the
    /// chain and every obstacle, squared centre distance to every placed neighbour not in
    /// door contact.
    fn node_terms(&self, s: &[Slot], i: usize, at: (BlockId, P)) -> (f64, f64) {
        let mut area = self.obstacle_area(at);
        for &j in &self.local {
            if let (true, Some(b)) = (j != i, s[j]) {
                let x = self.overlap(at, b);
                if x > AREA_TOL {
                    area += x;
                }
            }
        }
        let mut dist = 0.0;
        for n in &self.adj[i] {
            if let Some(b) = s[n.0 as usize] {
                if !self.placer.in_contact(at, b) {
                    let d = sub(self.centre(at), self.centre(b));
                    dist += geometry::dot(d, d);
                }
            }
        }
        (area, dist)
    }

    /// The energy terms over the local nodes (the partial layout the chain extends has none).
    fn totals(&self, s: &[Slot]) -> (f64, f64) {
        let (mut a, mut d) = (0.0, 0.0);
        for &i in &self.local {
            if let Some(x) = s[i] {
                let (ai, di) = self.node_terms(s, i, x);
                // Block pairs are counted from both ends, obstacles once.
                let ob = self.obstacle_area(x);
                a += (ai - ob) / 2.0 + ob;
                d += di / 2.0;
            }
        }
        (a, d)
    }

    fn energy(&self, a: f64, d: f64) -> f64 {
        (a / self.shapes.sigma).exp() * (d / self.shapes.sigma).exp() - 1.0
    }

    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[((self.rng.random::<f64>() * xs.len() as f64) as usize).min(xs.len() - 1)]
    }

    /// A position for node `i` as block `b`: a random point of the intersection of its placed
    /// neighbours' configuration spaces (a maximal non-empty one when all of them do not meet).
    fn sample(&mut self, s: &[Slot], i: usize, b: BlockId) -> Option<P> {
        if let Some(p) = self.level.nodes[i].position {
            return Some(p);
        }
        let mut nbs: Vec<(BlockId, P)> = self.adj[i].iter().filter_map(|n| s[n.0 as usize]).collect();
        if nbs.is_empty() {
            return Some(self.clear_start(b));
        }
        // Random order; the greedy intersection keeps every neighbour it can.
        for k in (1..nbs.len()).rev() {
            let j = ((self.rng.random::<f64>() * (k + 1) as f64) as usize).min(k);
            nbs.swap(k, j);
        }
        let space = |(nb, p): (BlockId, P)| -> Vec<Segment> {
            self.cs
                .segments(nb, b)
                .iter()
                .map(|g| Segment { a: geometry::add(g.a, p), b: geometry::add(g.b, p) })
                .collect()
        };
        let mut acc = space(nbs[0]);
        for &x in &nbs[1..] {
            let inter = intersect(&acc, &space(x));
            if !inter.is_empty() {
                acc = inter;
            }
        }
        // Obstacles are fixed: the pieces of the space clear of them.
        for o in 0..self.level.obstacles.len() {
            acc = acc.iter().flat_map(|g| clip_out(g, self.cs.obstacle_facets(o, b))).collect();
        }
        if acc.is_empty() {
            return None;
        }
        let g = self.pick(&acc);
        Some(g.at(self.rng.random::<f64>()))
    }

    fn distinct(&self, x: &[Slot], y: &[Slot]) -> bool {
        let placed: Vec<(BlockId, P, BlockId, P)> = x
            .iter()
            .zip(y)
            .filter_map(|(a, b)| Some((a.as_ref()?.0, a.as_ref()?.1, b.as_ref()?.0, b.as_ref()?.1)))
            .collect();
        if placed.iter().any(|p| p.0 != p.2) {
            return true;
        }
        let n = placed.len() as f64;
        let (cx, cy) = placed.iter().fold(([0.0, 0.0], [0.0, 0.0]), |(u, v), p| {
            let (a, b) = (self.centre((p.0, p.1)), self.centre((p.2, p.3)));
            ([u[0] + a[0] / n, u[1] + a[1] / n], [v[0] + b[0] / n, v[1] + b[1] / n])
        });
        let ssd: f64 = placed
            .iter()
            .map(|p| {
                let d = sub(sub(self.centre((p.0, p.1)), cx), sub(self.centre((p.2, p.3)), cy));
                geometry::dot(d, d)
            })
            .sum();
        ssd > self.shapes.threshold
    }

    fn found(&self, s: &[Slot]) -> Found {
        Found { slots: s.to_vec(), seconds: self.t0.elapsed().as_secs_f64(), trials: self.trials }
    }

    fn stop_requested(&self) -> bool {
        self.o.stop.as_ref().is_some_and(Interrupt::is_triggered)
    }

    fn out_of_time(&self) -> bool {
        self.t0.elapsed().as_secs_f64() >= self.o.time_limit || self.stop_requested()
    }

    /// The chain's nodes breadth-first from what is placed (members the search does not reach
    /// — fixed nodes apart from each other — last).
    fn order(&mut self, s: &[Slot], chain: &[NodeId]) -> Vec<NodeId> {
        let mut q: VecDeque<NodeId> = chain
            .iter()
            .copied()
            .filter(|n| self.adj[n.0 as usize].iter().any(|m| s[m.0 as usize].is_some()))
            .collect();
        if q.is_empty() {
            q.push_back(chain[0]);
        }
        let members: BTreeSet<NodeId> = chain.iter().copied().collect();
        let mut seen: BTreeSet<NodeId> = q.iter().copied().collect();
        let mut order = Vec::new();
        while let Some(n) = q.pop_front() {
            order.push(n);
            for &m in &self.adj[n.0 as usize] {
                if members.contains(&m) && seen.insert(m) {
                    q.push_back(m);
                }
            }
        }
        order.extend(chain.iter().copied().filter(|n| !seen.contains(n)));
        order
    }

    /// The chain's members and the placed nodes within reach of them: the chain can lay its
    /// nodes at most one contact step per node from its placed neighbours.
    fn set_local(&mut self, s: &[Slot], chain: &[NodeId]) {
        let members: BTreeSet<usize> = chain.iter().map(|n| n.0 as usize).collect();
        let anchors: Vec<P> = chain
            .iter()
            .flat_map(|n| self.adj[n.0 as usize].iter())
            .filter_map(|m| s[m.0 as usize])
            .map(|a| self.centre(a))
            .chain(chain.iter().filter_map(|n| self.level.nodes[n.0 as usize].position))
            .collect();
        let radius = (chain.len() as f64 + 2.0) * (self.placer_step() + 2.0 * self.shapes.extent);
        self.local = (0..s.len())
            .filter(|j| {
                members.contains(j)
                    || s[*j].is_some_and(|a| {
                        let c = self.centre(a);
                        anchors.is_empty() || anchors.iter().any(|&p| length(sub(c, p)) <= radius)
                    })
            })
            .collect();
    }

    fn placer_step(&self) -> f64 {
        self.cs.reach * std::f64::consts::SQRT_2
    }

    /// The paper's start: breadth-first, each node at the lowest-energy of ten samples.
    fn initialise(&mut self, s: &mut [Slot], order: &[NodeId]) {
        for &n in order {
            let i = n.0 as usize;
            if s[i].is_some() {
                continue;
            }
            let mut best: Option<((BlockId, P), f64)> = None;
            for _ in 0..10 {
                let b = self.pick(&self.level.nodes[i].blocks.clone());
                let p = self.sample(s, i, b).unwrap_or_else(|| self.far(s, b));
                let (a, d) = self.node_terms(s, i, (b, p));
                if best.is_none_or(|x| a + d < x.1) {
                    best = Some(((b, p), a + d));
                }
            }
            s[i] = best.map(|x| x.0);
        }
    }

    /// The origin, or beside the obstacles when block `b` would overlap one there.
    fn clear_start(&self, b: BlockId) -> P {
        if self.obstacle_area((b, [0.0, 0.0])) <= AREA_TOL {
            return [0.0, 0.0];
        }
        let right = self.placer.obstacles.iter().map(|o| o.1[1]).fold(f64::NEG_INFINITY, f64::max);
        [right - self.placer.boxes[b.0 as usize][0] + 1.0, 0.0]
    }

    /// A move's new position: a sample clear of every obstacle (a few tries; none when every
    /// try lands in one, and the move is rejected).
    fn sample_clear(&mut self, s: &[Slot], i: usize, b: BlockId) -> Option<P> {
        for _ in 0..4 {
            let p = self.sample(s, i, b)?;
            if self.placer.obstacles.is_empty() || self.obstacle_area((b, p)) <= AREA_TOL {
                return Some(p);
            }
        }
        None
    }

    /// A position beside everything placed (for a node whose neighbours give no contact).
    fn far(&self, s: &[Slot], b: BlockId) -> P {
        let right = s.iter().flatten().map(|(k, p)| self.placer.boxes[k.0 as usize][1] + p[0]).fold(0.0, f64::max);
        [right - self.placer.boxes[b.0 as usize][0] + 1.0, 0.0]
    }

    /// Exact placements of the chain (up to `want` that differ), each a valid extension.
    /// Returns them and the deepest partial placement of the last failed try.
    fn exact_starts(&mut self, s0: &[Slot], order: &[NodeId], want: usize) -> (Vec<Found>, Vec<Slot>) {
        let mut found: Vec<Found> = Vec::new();
        let mut deepest = s0.to_vec();
        let budget = self.o.place_budget.saturating_mul(order.len()).max(1);
        // A few tries per layout wanted: ends, middles and straight-on points repeat often.
        for _ in 0..want.saturating_mul(3).max(2) {
            if self.out_of_time() {
                break;
            }
            let mut s = s0.to_vec();
            let stop = self.o.stop.clone();
            let t0 = self.t0;
            let limit = self.o.time_limit;
            let stop_fn =
                move || stop.as_ref().is_some_and(Interrupt::is_triggered) || t0.elapsed().as_secs_f64() >= limit;
            match self.placer.place(&mut s, order, &mut self.rng, budget, &stop_fn) {
                Ok(()) => {
                    if found.iter().all(|f| self.distinct(&f.slots, &s)) {
                        found.push(self.found(&s));
                        if found.len() >= want {
                            break;
                        }
                    }
                }
                Err(partial) => {
                    deepest = partial;
                    break;
                }
            }
        }
        (found, deepest)
    }

    /// Extends the partial layout `s0` by `chain` (Pseudocode 2): valid extensions that differ,
    /// up to `want`, each with the seconds and trials at which it was found — exact placements
    /// first, then the paper's annealing from the deepest one.
    fn add_chain(&mut self, s0: &[Slot], chain: &[NodeId], want: usize) -> Vec<Found> {
        self.set_local(s0, chain);
        let order = self.order(s0, chain);
        let (mut found, deepest) = self.exact_starts(s0, &order, want);
        if !found.is_empty() {
            self.exact_extensions += 1;
        }
        if found.len() >= want || self.out_of_time() {
            return found;
        }
        let mut s = deepest;
        self.initialise(&mut s, &order);
        self.anneal_chain(&mut s, chain, want, &mut found);
        found
    }

    /// The paper's annealing of the chain from `s`, adding valid extensions that differ to
    /// `found` until `want`.
    fn anneal_chain(&mut self, s: &mut [Slot], chain: &[NodeId], want: usize, found: &mut Vec<Found>) {
        let (mut a, mut d) = self.totals(s);
        let members: BTreeSet<usize> = chain.iter().map(|n| n.0 as usize).collect();
        let ratio = (self.o.t1 / self.o.t0).powf(1.0 / (self.o.cycles.max(2) - 1) as f64);
        let (mut t, mut k_sum, mut k_n) = (self.o.t0, 0.0, 0usize);
        let mut moved_earlier: BTreeSet<usize> = BTreeSet::new();
        if a <= AREA_TOL && d == 0.0 && found.iter().all(|f| self.distinct(&f.slots, s)) {
            found.push(self.found(s));
            if found.len() >= want {
                return;
            }
        }
        let mut movable: Vec<usize> = Vec::new();
        for _ in 0..self.o.cycles {
            for trial in 0..self.o.trials {
                self.trials += 1;
                if self.trials.is_multiple_of(256) && self.out_of_time() {
                    return;
                }
                // A chain node, or an earlier node near the chain with energy of its own.
                if trial % 50 == 0 {
                    movable = self
                        .local
                        .iter()
                        .copied()
                        .filter(|&i| {
                            s[i].is_some()
                                && (members.contains(&i) || {
                                    let (x, y) = self.node_terms(s, i, s[i].unwrap_or((BlockId(0), [0.0, 0.0])));
                                    x + y > 0.0
                                })
                        })
                        .collect();
                }
                if movable.is_empty() {
                    break;
                }
                let i = self.pick(&movable);
                let Some(old) = s[i] else { continue };
                let blocks = self.level.nodes[i].blocks.clone();
                // Positions 7 : block changes 3.
                let b = if blocks.len() > 1 && self.rng.random::<f64>() < 0.3 { self.pick(&blocks) } else { old.0 };
                let Some(p) = self.sample_clear(s, i, b) else { continue };
                let (ao, dold) = self.node_terms(s, i, old);
                let (an, dn) = self.node_terms(s, i, (b, p));
                let (a2, d2) = ((a - ao + an).max(0.0), (d - dold + dn).max(0.0));
                let de = self.energy(a2, d2) - self.energy(a, d);
                let accept = de < 0.0 || {
                    k_sum += de;
                    k_n += 1;
                    let k = (k_sum / k_n as f64).max(1e-12);
                    self.rng.random::<f64>() < (-de / (k * t)).exp()
                };
                if !accept {
                    continue;
                }
                s[i] = Some((b, p));
                if !members.contains(&i) {
                    moved_earlier.insert(i);
                }
                (a, d) = (a2, d2);
                if a2 <= AREA_TOL && dn == 0.0 && d2 < 1e-12 {
                    // Recount to be sure (the running sums drift), and check moved earlier
                    // nodes against every placed block, near the chain or not.
                    let (ac, dc) = self.totals(s);
                    (a, d) = (ac, dc);
                    let clear = moved_earlier.iter().all(|&j| s[j].is_some_and(|x| self.placer.fits(s, j, x)));
                    if ac <= AREA_TOL && dc == 0.0 && clear && found.iter().all(|f| self.distinct(&f.slots, s)) {
                        found.push(self.found(s));
                        if found.len() >= want {
                            return;
                        }
                    }
                }
            }
            t *= ratio;
        }
    }
}

/// Lays out `level` with the paper's method (and the additions of the module docs).
pub fn anneal(level: &Level, cs: &CSpaces, o: &AnnealOptions) -> AnnealReport {
    let placer = Placer::new(level, cs);
    let mut search = Search {
        level,
        cs,
        adj: placer.adjacency().to_vec(),
        placer,
        shapes: Shapes::new(level),
        rng: Xoshiro256PlusPlus::seed_from_u64(o.seed),
        o,
        t0: Instant::now(),
        trials: 0,
        exact_extensions: 0,
        local: Vec::new(),
    };
    let mut rep = AnnealReport::default();
    let mut full: Vec<Vec<Slot>> = Vec::new();
    let mut variations = o.partial_variations.max(1);
    loop {
        let chains = pieces(level, chains_from(level, rep.restarts), o.piece);
        rep.chains = chains.iter().map(|c| c.iter().map(|&n| level.node_name(n).to_string()).collect()).collect();
        rep.stopped = search_stack(&mut search, &chains, variations, &mut full, &mut rep);
        if rep.stopped != "exhausted" || rep.restarts >= o.restarts {
            break;
        }
        rep.restarts += 1;
        variations = variations.saturating_mul(2);
    }
    rep.trials = search.trials;
    rep.exact_extensions = search.exact_extensions;
    rep
}

/// One pass over the stack of partial layouts: each popped layout is extended by its next
/// chain (one extension; the layout goes back on the stack for another until `variations`),
/// full layouts are validated and kept. Returns why it stopped.
fn search_stack(
    search: &mut Search,
    chains: &[Vec<NodeId>],
    variations: usize,
    full: &mut Vec<Vec<Slot>>,
    rep: &mut AnnealReport,
) -> String {
    let level = search.level;
    let o = search.o;
    let mut stack: Vec<(Vec<Slot>, usize, usize)> = vec![(vec![None; level.nodes.len()], 0, 0)];
    while let Some((s, k, tries)) = stack.pop() {
        if search.out_of_time() {
            return if search.stop_requested() { "stopped".into() } else { "time limit".into() };
        }
        rep.extensions += 1;
        let last = k + 1 == chains.len();
        let want = if last { o.count - full.len() } else { 1 };
        let ext = search.add_chain(&s, &chains[k], want);
        if tries + 1 < variations {
            stack.push((s, k, tries + 1));
        }
        if last {
            for e in ext {
                if full.iter().all(|f| search.distinct(f, &e.slots)) {
                    let layout = super::clear_of_obstacles(level, to_layout(level, &e.slots));
                    // Every layout passes the independent validator; one that does not is dropped.
                    if validate(level, &layout).is_valid() {
                        rep.time_to_first.get_or_insert(e.seconds);
                        rep.time_to_last = Some(e.seconds);
                        rep.trials_to_last = e.trials;
                        rep.layouts.push(layout);
                        full.push(e.slots);
                    }
                }
            }
            if full.len() >= o.count {
                return "count".into();
            }
        } else {
            stack.extend(ext.into_iter().rev().map(|e| (e.slots, k + 1, 0)));
        }
    }
    "exhausted".into()
}
fn to_layout(level: &Level, s: &[Slot]) -> Layout {
    Layout {
        nodes: s
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let (b, p) = x.unwrap_or((level.nodes[i].blocks[0], [0.0, 0.0]));
                Placement::new(level, NodeId(i as u32), b, p)
            })
            .collect(),
    }
}
