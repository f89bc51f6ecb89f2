//! The three graphs the searches run on, as implicit [`Space`]s: the initial pathfinding graph 𝒢
//! (the lattice, with the reuse coefficient μ on edges already used), the major-road graph of
//! PROPOSEFROMMAJOR (trade segments with room for the shortfall), and the auxiliary graph 𝒢′ of
//! PROPOSEFROMNEW (the lattice outside the built-up area, plus the segment graph weighted by
//! C₁…C₆, plus stitches between them).

use super::blocks::Blocks;
use super::graph::{Class, Graph};
use super::lattice::{Edge, Lattice};
use super::paths::Space;
use super::terrain::{LAND, WATER};
use super::traffic::capacity;
use crate::geometry::{dist, segment_intersection, P};
use std::collections::{HashMap, HashSet};

/// The initial network's graph: the lattice with reuse (an edge of an earlier initial path
/// weighs μ times as much), plus the road graph's segments (trade segments at μ times their
/// lattice weight: existing roads count as used; minor roads at their length; fixed minor roads
/// closed), joined to the lattice by stitches. States below the lattice size are lattice
/// vertices, the others road-graph nodes. Without existing roads there are no stitches and it is
/// the lattice alone.
pub struct InitialSpace<'a> {
    /// The lattice.
    pub lattice: &'a Lattice,
    /// The road graph.
    pub graph: &'a Graph,
    /// Stitches of the existing roads' nodes.
    pub stitches: &'a Stitches,
    /// Used edges (ends ordered).
    pub used: &'a HashSet<(u32, u32)>,
    /// μ.
    pub mu: f64,
    /// C₁…C₆ (C₃, C₅ weigh harbours and bridges as on the lattice).
    pub c: [f64; 6],
    /// Scratch.
    pub edges: Vec<Edge>,
    /// Scratch.
    pub buf: Vec<u32>,
}

impl InitialSpace<'_> {
    /// A road-graph segment's weight, `None` for a fixed minor road.
    fn segment(&self, s: u32) -> Option<f64> {
        let g = &self.graph.segs[s as usize];
        let len = self.graph.length(s);
        match g.class {
            Class::Minor if g.fixed => None,
            Class::Minor => Some(len),
            Class::Major | Class::Water => Some(len * self.mu),
            Class::Bridge => Some(len * self.mu * self.c[4]),
            Class::Harbour => Some(len * self.mu * self.c[2]),
        }
    }
}

impl Space for InitialSpace<'_> {
    fn len(&self) -> usize {
        self.lattice.len() + self.graph.nodes.len()
    }
    fn pos(&self, v: u32) -> P {
        let n = self.lattice.len() as u32;
        if v < n {
            self.lattice.pos(v)
        } else {
            self.graph.nodes[(v - n) as usize].pos
        }
    }
    fn edges(&mut self, v: u32, settled: &[bool], out: &mut Vec<(u32, f64)>) {
        out.clear();
        let nl = self.lattice.len() as u32;
        if v < nl {
            self.lattice.edges(v, &|_| false, &|u| settled[u as usize], &mut self.edges, &mut self.buf);
            for e in &self.edges {
                let f = if self.used.contains(&(v.min(e.to), v.max(e.to))) { self.mu } else { 1.0 };
                out.push((e.to, e.weight * f));
            }
            for &n in self.stitches.to_nodes.get(&v).into_iter().flatten() {
                if let Some(w) = stitch(self.lattice, self.graph, v, n) {
                    out.push((nl + n, w));
                }
            }
        } else {
            let n = v - nl;
            for &s in &self.graph.adj[n as usize] {
                if let Some(w) = self.segment(s) {
                    out.push((nl + self.graph.other(s, n), w));
                }
            }
            for &u in self.stitches.to_lattice.get(n as usize).into_iter().flatten() {
                if let Some(w) = stitch(self.lattice, self.graph, u, n) {
                    out.push((u, w));
                }
            }
        }
    }
}

/// The weight factors of built segments in the proposal graphs.
#[derive(Clone, Copy, Debug)]
pub struct Costs {
    /// C₁…C₆.
    pub c: [f64; 6],
    /// O₂.
    pub per_lane: f64,
    /// The most lanes widening gives a road.
    pub max_lanes: f64,
    /// The shortfall a segment must have room for (unless it can be widened).
    pub delta: f64,
}

impl Costs {
    /// The weight of a built segment, or `None` when it has no room for the shortfall beside its
    /// traffic and `used` (the pair's own routes saturated, [`super::traffic::Traffic::saturation`]) and
    /// widening to `max_lanes` would not give it (a fixed or non-extendible segment cannot be
    /// widened), or a fixed minor road (which never becomes major).
    pub fn segment(&self, graph: &Graph, blocks: &Blocks, s: u32, trade_only: bool, used: f64) -> Option<f64> {
        let g = &graph.segs[s as usize];
        if trade_only && !g.class.is_trade() {
            return None;
        }
        if g.fixed && g.class == Class::Minor {
            return None;
        }
        let ext = blocks.extendible.get(s as usize).copied().unwrap_or(true);
        let widenable = ext && !g.fixed && matches!(g.class, Class::Major | Class::Minor);
        if g.class != Class::Water && g.class != Class::Minor {
            let room = capacity(graph, s, self.per_lane) - g.load - used;
            let widened = self.per_lane * self.max_lanes.max(g.width) - g.load - used;
            if room < self.delta && (trade_only || !widenable || widened < self.delta) {
                return None;
            }
        }
        let mult = match g.class {
            Class::Major | Class::Bridge => self.c[0],
            Class::Minor => self.c[1],
            Class::Harbour => self.c[3],
            Class::Water => 1.0,
        } * if widenable { self.c[5] } else { 1.0 };
        Some(graph.length(s) * mult)
    }

    /// The smallest weight per metre of any edge (the A* factor).
    pub fn min_factor(&self) -> f64 {
        let c = self.c;
        [1.0, c[0] * c[5], c[1] * c[5], c[0], c[1], c[2], c[3], c[4]].into_iter().fold(f64::INFINITY, f64::min)
    }
}

/// PROPOSEFROMMAJOR's graph: the segment graph's trade segments with room for the shortfall.
pub struct MajorSpace<'a> {
    /// The segment graph.
    pub graph: &'a Graph,
    /// Blocks (extendible segments).
    pub blocks: &'a Blocks,
    /// Weights.
    pub costs: Costs,
    /// The traffic the pair's own routes take per segment when saturated.
    pub used: &'a HashMap<u32, f64>,
}

impl Space for MajorSpace<'_> {
    fn len(&self) -> usize {
        self.graph.nodes.len()
    }
    fn pos(&self, v: u32) -> P {
        self.graph.nodes[v as usize].pos
    }
    fn edges(&mut self, v: u32, _settled: &[bool], out: &mut Vec<(u32, f64)>) {
        out.clear();
        for &s in &self.graph.adj[v as usize] {
            let used = self.used.get(&s).copied().unwrap_or(0.0);
            if let Some(w) = self.costs.segment(self.graph, self.blocks, s, true, used) {
                out.push((self.graph.other(s, v), w));
            }
        }
    }
}

/// Stitches between segment-graph nodes and lattice vertices within the stitch radius.
#[derive(Clone, Debug, Default)]
pub struct Stitches {
    /// Per lattice vertex, the nodes it may stitch to.
    pub to_nodes: HashMap<u32, Vec<u32>>,
    /// Per node, the lattice vertices it may stitch to.
    pub to_lattice: Vec<Vec<u32>>,
    radius: f64,
}

impl Stitches {
    /// Stitches for every node of the graph.
    pub fn new(graph: &Graph, lattice: &Lattice, blocks: &Blocks, radius: f64) -> Stitches {
        let mut s = Stitches { to_nodes: HashMap::new(), to_lattice: Vec::new(), radius };
        s.extend(graph, lattice, blocks);
        s
    }

    /// Adds the stitches of nodes added since the last call.
    pub fn extend(&mut self, graph: &Graph, lattice: &Lattice, blocks: &Blocks) {
        let t = &lattice.terrain;
        let sp = t.spacing;
        let r = self.radius;
        for n in self.to_lattice.len()..graph.nodes.len() {
            let p = graph.nodes[n].pos;
            let mut list = Vec::new();
            let (x0, x1) = (
                ((p[0] - r) / sp).ceil().max(0.0) as usize,
                (((p[0] + r) / sp).floor().max(-1.0) + 1.0).min(t.nx as f64) as usize,
            );
            let (y0, y1) = (
                ((p[1] - r) / sp).ceil().max(0.0) as usize,
                (((p[1] + r) / sp).floor().max(-1.0) + 1.0).min(t.ny as f64) as usize,
            );
            for y in y0..y1 {
                for x in x0..x1 {
                    let v = (y * t.nx + x) as u32;
                    if blocks.built.get(v as usize).copied().unwrap_or(false) || dist(lattice.pos(v), p) > r {
                        continue;
                    }
                    let c = lattice.class(v);
                    if c == LAND || (c == WATER && dist(lattice.pos(v), p) < 1e-6) {
                        list.push(v);
                        self.to_nodes.entry(v).or_default().push(n as u32);
                    }
                }
            }
            self.to_lattice.push(list);
        }
    }
}

/// PROPOSEFROMNEW's graph 𝒢′: states below the lattice size are lattice vertices, the others
/// segment-graph nodes.
pub struct NewSpace<'a> {
    /// The lattice.
    pub lattice: &'a Lattice,
    /// The segment graph.
    pub graph: &'a Graph,
    /// Blocks and the built-up area.
    pub blocks: &'a Blocks,
    /// Stitches.
    pub stitches: &'a Stitches,
    /// Weights.
    pub costs: Costs,
    /// The traffic the pair's own routes take per segment when saturated.
    pub used: &'a HashMap<u32, f64>,
    /// Scratch.
    pub edges: Vec<Edge>,
    /// Scratch.
    pub buf: Vec<u32>,
}

/// The weight of the stitch between lattice vertex `v` and node `n`, if it is usable: over
/// land (or none at all), within the slope cut-off, crossing no road.
fn stitch(lattice: &Lattice, graph: &Graph, v: u32, n: u32) -> Option<f64> {
    let (a, b) = (lattice.pos(v), graph.nodes[n as usize].pos);
    let len = dist(a, b);
    if len < 1e-6 {
        return Some(0.0);
    }
    let t = &lattice.terrain;
    let k = (len / (t.spacing / 2.0)).ceil() as usize;
    for i in 0..=k {
        let f = i as f64 / k as f64;
        if t.class_at([a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f]) != LAND {
            return None;
        }
    }
    let grade = (t.elevation(a) - t.elevation(b)).abs() / len;
    if grade > lattice.slope_cut {
        return None;
    }
    let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    for s in graph.segs_near(mid, len / 2.0 + 1.0) {
        let g = &graph.segs[s];
        if !g.class.is_road() || g.a == n || g.b == n {
            continue;
        }
        let (c, d) = graph.ends(s as u32);
        if segment_intersection(a, b, c, d).is_some() {
            return None;
        }
    }
    Some(len * (lattice.o1 * grade).max(1.0))
}

impl Space for NewSpace<'_> {
    fn len(&self) -> usize {
        self.lattice.len() + self.graph.nodes.len()
    }
    fn pos(&self, v: u32) -> P {
        let n = self.lattice.len() as u32;
        if v < n {
            self.lattice.pos(v)
        } else {
            self.graph.nodes[(v - n) as usize].pos
        }
    }
    fn edges(&mut self, v: u32, settled: &[bool], out: &mut Vec<(u32, f64)>) {
        out.clear();
        let nl = self.lattice.len() as u32;
        if v < nl {
            let built = &self.blocks.built;
            self.lattice.edges(v, &|u| built[u as usize], &|u| settled[u as usize], &mut self.edges, &mut self.buf);
            out.extend(self.edges.iter().map(|e| (e.to, e.weight)));
            if let Some(nodes) = self.stitches.to_nodes.get(&v) {
                for &n in nodes {
                    if let Some(w) = stitch(self.lattice, self.graph, v, n) {
                        out.push((nl + n, w));
                    }
                }
            }
        } else {
            let n = v - nl;
            for &s in &self.graph.adj[n as usize] {
                let used = self.used.get(&s).copied().unwrap_or(0.0);
                if let Some(w) = self.costs.segment(self.graph, self.blocks, s, false, used) {
                    out.push((nl + self.graph.other(s, n), w));
                }
            }
            if let Some(list) = self.stitches.to_lattice.get(n as usize) {
                for &u in list {
                    if let Some(w) = stitch(self.lattice, self.graph, u, n) {
                        out.push((u, w));
                    }
                }
            }
        }
    }
}
