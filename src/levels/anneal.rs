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
//! the chains. Every layout returned has passed [`super::validate::validate`].

use super::cspace::{clip_out, intersect, CSpaces, Segment};
use super::geometry::{self, norm, sub, Pt, AREA_TOL, LEN_TOL};
use super::spec::{BlockId, Level, NodeId};
use super::validate::{shared_wall, validate};
use super::{Layout, Placement};
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use serde::Serialize;
use std::collections::{BTreeSet, VecDeque};
use std::time::Instant;

/// Settings of the annealer (defaults: the paper's).
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
    /// Partial layouts kept per chain extension.
    pub partial_variations: usize,
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
        }
    }
}

/// What the annealer found.
#[derive(Clone, Debug, Default, Serialize)]
pub struct AnnealReport {
    /// Distinct full layouts, each validated.
    #[serde(skip)]
    pub layouts: Vec<Layout>,
    /// The chains, in processing order (node names).
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
    /// Why the search stopped: `count`, `exhausted` (the stack ran empty) or `time limit`.
    pub stopped: String,
}

/// The shortest cycle through edge `(a, b)` (a path from `b` back to `a` avoiding the edge).
fn shortest_cycle(adj: &[Vec<NodeId>], a: NodeId, b: NodeId) -> Option<Vec<NodeId>> {
    let mut prev = vec![None; adj.len()];
    prev[b.0 as usize] = Some(b);
    let mut q = VecDeque::from([b]);
    while let Some(u) = q.pop_front() {
        for &v in &adj[u.0 as usize] {
            if (u == b && v == a) || prev[v.0 as usize].is_some() {
                continue;
            }
            prev[v.0 as usize] = Some(u);
            if v == a {
                let mut path = vec![a];
                let mut x = a;
                while x != b {
                    x = prev[x.0 as usize]?;
                    path.push(x);
                }
                return Some(path);
            }
            q.push_back(v);
        }
    }
    None
}

/// The chains: node sets in processing order. The first is the shortest cycle; each next one
/// is the shortest cycle touching the laid-out nodes that brings new nodes (its new nodes);
/// the nodes left come in breadth-first order, grouped into paths. Fixed nodes, if any, come
/// before all of them as a chain of their own (their blocks are chosen before anything is laid
/// out where they must go), and every later chain then touches what is laid out.
pub fn chains(level: &Level) -> Vec<Vec<NodeId>> {
    let adj = level.adjacency(&level.all_edges());
    let mut cycles: Vec<Vec<NodeId>> = level
        .edges
        .iter()
        .filter_map(|&(a, b)| shortest_cycle(&adj, a, b))
        .map(|mut c| {
            // One representative per cycle: rotated to its least node, that node's smaller neighbour next.
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
    // Trees: breadth-first from what is placed (or from the first node), as paths.
    if out.is_empty() {
        placed[0] = true;
        out.push(vec![NodeId(0)]);
    }
    loop {
        let start = (0..level.nodes.len())
            .filter(|&i| placed[i])
            .flat_map(|i| adj[i].iter().copied())
            .find(|n| !placed[n.0 as usize]);
        let Some(mut n) = start else { break };
        let mut path = Vec::new();
        loop {
            placed[n.0 as usize] = true;
            path.push(n);
            match adj[n.0 as usize].iter().copied().find(|m| !placed[m.0 as usize]) {
                Some(m) => n = m,
                None => break,
            }
        }
        out.push(path);
    }
    out
}

/// Per-block data the energy needs.
struct Shapes {
    tris: Vec<Vec<[Pt; 3]>>,
    centre: Vec<Pt>,
    boxes: Vec<[f64; 4]>,
    /// Obstacles: triangles and bounding box (absolute coordinates).
    obstacles: Vec<(Vec<[Pt; 3]>, [f64; 4])>,
    sigma: f64,
    threshold: f64,
}

impl Shapes {
    fn new(level: &Level) -> Shapes {
        let tris = level.blocks.iter().map(|b| geometry::triangulate(&b.polygon)).collect();
        let centre = level
            .blocks
            .iter()
            .map(|b| {
                let n = b.polygon.len() as f64;
                b.polygon.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n])
            })
            .collect();
        let boxes = level.blocks.iter().map(|b| bounding_box(&b.polygon)).collect();
        let obstacles =
            level.obstacles.iter().map(|o| (geometry::triangulate(&o.polygon), bounding_box(&o.polygon))).collect();
        let mean_area =
            level.blocks.iter().map(|b| geometry::signed_area(&b.polygon)).sum::<f64>() / level.blocks.len() as f64;
        // The paper's σ: a hundred times the average block area. Two layouts differ when their
        // centred block centres move by more than a tenth of that area in all (squared).
        Shapes { tris, centre, boxes, obstacles, sigma: 100.0 * mean_area, threshold: 0.1 * mean_area }
    }
}

/// `[xmin, xmax, ymin, ymax]` of a polygon.
fn bounding_box(poly: &[Pt]) -> [f64; 4] {
    let f = |axis: usize, max: bool| {
        let it = poly.iter().map(|p| p[axis]);
        if max {
            it.fold(f64::NEG_INFINITY, f64::max)
        } else {
            it.fold(f64::INFINITY, f64::min)
        }
    };
    [f(0, false), f(0, true), f(1, false), f(1, true)]
}

/// Whether two boxes are apart (touching counts as apart).
fn boxes_apart(a: [f64; 4], b: [f64; 4]) -> bool {
    a[1] <= b[0] || b[1] <= a[0] || a[3] <= b[2] || b[3] <= a[2]
}

type Slot = Option<(BlockId, Pt)>;

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
    shapes: Shapes,
    adj: Vec<Vec<NodeId>>,
    rng: Xoshiro256PlusPlus,
    o: &'a AnnealOptions,
    t0: Instant,
    trials: u64,
}

impl Search<'_> {
    fn overlap(&self, a: (BlockId, Pt), b: (BlockId, Pt)) -> f64 {
        if boxes_apart(self.placed_box(a), self.placed_box(b)) {
            return 0.0;
        }
        geometry::overlap_area(&self.placed_tris(a), &self.placed_tris(b))
    }

    fn placed_box(&self, a: (BlockId, Pt)) -> [f64; 4] {
        let b = self.shapes.boxes[a.0 .0 as usize];
        [b[0] + a.1[0], b[1] + a.1[0], b[2] + a.1[1], b[3] + a.1[1]]
    }

    fn placed_tris(&self, a: (BlockId, Pt)) -> Vec<[Pt; 3]> {
        self.shapes.tris[a.0 .0 as usize].iter().map(|t| t.map(|p| geometry::add(p, a.1))).collect()
    }

    /// The area of a placed block inside obstacles (each overlap above [`AREA_TOL`]).
    fn obstacle_area(&self, a: (BlockId, Pt)) -> f64 {
        let bx = self.placed_box(a);
        let mut tris = None;
        let mut area = 0.0;
        for (ot, ob) in &self.shapes.obstacles {
            if boxes_apart(bx, *ob) {
                continue;
            }
            let ta = tris.get_or_insert_with(|| self.placed_tris(a));
            let x = geometry::overlap_area(ta, ot);
            if x > AREA_TOL {
                area += x;
            }
        }
        area
    }

    fn in_contact(&self, a: (BlockId, Pt), b: (BlockId, Pt)) -> bool {
        let pa = geometry::translate(&self.level.blocks[a.0 .0 as usize].polygon, a.1);
        let pb = geometry::translate(&self.level.blocks[b.0 .0 as usize].polygon, b.1);
        shared_wall(&pa, &pb).is_some_and(|w| norm(sub(w[1], w[0])) >= self.level.door_width - LEN_TOL)
    }

    fn centre(&self, a: (BlockId, Pt)) -> Pt {
        geometry::add(self.shapes.centre[a.0 .0 as usize], a.1)
    }

    /// Node `i`'s share of the energy terms: overlap area with every placed block and every
    /// obstacle, squared centre distance to every placed neighbour not in door contact.
    fn node_terms(&self, s: &[Slot], i: usize, at: (BlockId, Pt)) -> (f64, f64) {
        let mut area = self.obstacle_area(at);
        for (j, sj) in s.iter().enumerate() {
            if let (true, Some(b)) = (j != i, sj) {
                let x = self.overlap(at, *b);
                if x > AREA_TOL {
                    area += x;
                }
            }
        }
        let mut dist = 0.0;
        for n in &self.adj[i] {
            if let Some(b) = s[n.0 as usize] {
                if !self.in_contact(at, b) {
                    let d = sub(self.centre(at), self.centre(b));
                    dist += geometry::dot(d, d);
                }
            }
        }
        (area, dist)
    }

    fn totals(&self, s: &[Slot]) -> (f64, f64) {
        let (mut a, mut d) = (0.0, 0.0);
        for (i, si) in s.iter().enumerate() {
            if let Some(x) = si {
                let (ai, di) = self.node_terms(s, i, *x);
                // Block pairs are counted from both ends, obstacles once.
                let ob = self.obstacle_area(*x);
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
    fn sample(&mut self, s: &[Slot], i: usize, b: BlockId) -> Option<Pt> {
        if let Some(p) = self.level.nodes[i].position {
            return Some(p);
        }
        let mut nbs: Vec<(BlockId, Pt)> = self.adj[i].iter().filter_map(|n| s[n.0 as usize]).collect();
        if nbs.is_empty() {
            return Some(self.clear_start(b));
        }
        // Random order; the greedy intersection keeps every neighbour it can.
        for k in (1..nbs.len()).rev() {
            let j = ((self.rng.random::<f64>() * (k + 1) as f64) as usize).min(k);
            nbs.swap(k, j);
        }
        let space = |(nb, p): (BlockId, Pt)| -> Vec<Segment> {
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
        let placed: Vec<(BlockId, Pt, BlockId, Pt)> = x
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

    fn out_of_time(&self) -> bool {
        self.t0.elapsed().as_secs_f64() >= self.o.time_limit
    }

    /// Breadth-first placement of the chain's nodes, each at the lowest-energy sample.
    fn initialise(&mut self, s: &mut [Slot], chain: &[NodeId]) {
        let mut order: Vec<NodeId> = Vec::new();
        let mut q: VecDeque<NodeId> = chain
            .iter()
            .copied()
            .filter(|n| self.adj[n.0 as usize].iter().any(|m| s[m.0 as usize].is_some()))
            .collect();
        if q.is_empty() {
            q.push_back(self.pick(chain));
        }
        let members: BTreeSet<NodeId> = chain.iter().copied().collect();
        let mut seen: BTreeSet<NodeId> = q.iter().copied().collect();
        while let Some(n) = q.pop_front() {
            order.push(n);
            for &m in &self.adj[n.0 as usize] {
                if members.contains(&m) && seen.insert(m) {
                    q.push_back(m);
                }
            }
        }
        // Members the search did not reach (fixed nodes apart from each other) come last.
        order.extend(chain.iter().copied().filter(|n| !seen.contains(n)));
        for n in order {
            let i = n.0 as usize;
            let mut best: Option<((BlockId, Pt), f64)> = None;
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
    fn clear_start(&self, b: BlockId) -> Pt {
        if self.obstacle_area((b, [0.0, 0.0])) <= AREA_TOL {
            return [0.0, 0.0];
        }
        let right = self.shapes.obstacles.iter().map(|o| o.1[1]).fold(f64::NEG_INFINITY, f64::max);
        [right - self.shapes.boxes[b.0 as usize][0] + 1.0, 0.0]
    }

    /// A move's new position: a sample clear of every obstacle (a few tries; none when every
    /// try lands in one, and the move is rejected).
    fn sample_clear(&mut self, s: &[Slot], i: usize, b: BlockId) -> Option<Pt> {
        for _ in 0..4 {
            let p = self.sample(s, i, b)?;
            if self.shapes.obstacles.is_empty() || self.obstacle_area((b, p)) <= AREA_TOL {
                return Some(p);
            }
        }
        None
    }

    /// A position beside everything placed (for a node whose neighbours give no contact).
    fn far(&self, s: &[Slot], b: BlockId) -> Pt {
        let right = s.iter().flatten().map(|(k, p)| self.shapes.boxes[k.0 as usize][1] + p[0]).fold(0.0, f64::max);
        [right - self.shapes.boxes[b.0 as usize][0] + 1.0, 0.0]
    }

    /// Extends the partial layout `s` by `chain` (Pseudocode 2): valid extensions that differ,
    /// up to `want`, each with the seconds and trials at which it was found.
    fn add_chain(&mut self, s0: &[Slot], chain: &[NodeId], want: usize) -> Vec<Found> {
        let mut s = s0.to_vec();
        self.initialise(&mut s, chain);
        let (mut a, mut d) = self.totals(&s);
        let mut found: Vec<Found> = Vec::new();
        let members: BTreeSet<NodeId> = chain.iter().copied().collect();
        let ratio = (self.o.t1 / self.o.t0).powf(1.0 / (self.o.cycles.max(2) - 1) as f64);
        let (mut t, mut k_sum, mut k_n) = (self.o.t0, 0.0, 0usize);
        if a <= AREA_TOL && d == 0.0 {
            found.push(self.found(&s));
            if found.len() >= want {
                return found;
            }
        }
        for _ in 0..self.o.cycles {
            for _ in 0..self.o.trials {
                self.trials += 1;
                if self.trials.is_multiple_of(256) && self.out_of_time() {
                    return found;
                }
                // A chain node, or an earlier node with energy of its own.
                let movable: Vec<usize> = (0..s.len())
                    .filter(|&i| {
                        s[i].is_some()
                            && (members.contains(&NodeId(i as u32)) || {
                                let (x, y) = self.node_terms(&s, i, s[i].unwrap_or((BlockId(0), [0.0, 0.0])));
                                x + y > 0.0
                            })
                    })
                    .collect();
                if movable.is_empty() {
                    break;
                }
                let i = self.pick(&movable);
                let Some(old) = s[i] else { continue };
                let blocks = self.level.nodes[i].blocks.clone();
                // Positions 7 : block changes 3.
                let b = if blocks.len() > 1 && self.rng.random::<f64>() < 0.3 { self.pick(&blocks) } else { old.0 };
                let Some(p) = self.sample_clear(&s, i, b) else { continue };
                let (ao, dold) = self.node_terms(&s, i, old);
                let (an, dn) = self.node_terms(&s, i, (b, p));
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
                (a, d) = (a2, d2);
                if a2 <= AREA_TOL && dn == 0.0 && d2 < 1e-12 {
                    // Recount to be sure (the running sums drift).
                    let (ac, dc) = self.totals(&s);
                    (a, d) = (ac, dc);
                    if ac <= AREA_TOL && dc == 0.0 && found.iter().all(|f| self.distinct(&f.slots, &s)) {
                        found.push(self.found(&s));
                        if found.len() >= want {
                            return found;
                        }
                    }
                }
            }
            t *= ratio;
        }
        found
    }
}

/// Lays out `level` with the paper's method.
pub fn anneal(level: &Level, cs: &CSpaces, o: &AnnealOptions) -> AnnealReport {
    let mut search = Search {
        level,
        cs,
        shapes: Shapes::new(level),
        adj: level.adjacency(&level.all_edges()),
        rng: Xoshiro256PlusPlus::seed_from_u64(o.seed),
        o,
        t0: Instant::now(),
        trials: 0,
    };
    let chains = chains(level);
    let mut rep = AnnealReport {
        chains: chains.iter().map(|c| c.iter().map(|&n| level.node_name(n).to_string()).collect()).collect(),
        ..AnnealReport::default()
    };
    let mut full: Vec<Vec<Slot>> = Vec::new();
    let mut stack: Vec<(Vec<Slot>, usize)> = vec![(vec![None; level.nodes.len()], 0)];
    rep.stopped = "exhausted".into();
    while let Some((s, k)) = stack.pop() {
        if search.out_of_time() {
            rep.stopped = "time limit".into();
            break;
        }
        rep.extensions += 1;
        let last = k + 1 == chains.len();
        let want = if last { o.count - full.len() } else { o.partial_variations };
        let ext = search.add_chain(&s, &chains[k], want);
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
                rep.stopped = "count".into();
                break;
            }
        } else {
            stack.extend(ext.into_iter().rev().map(|e| (e.slots, k + 1)));
        }
    }
    rep.trials = search.trials;
    rep
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
