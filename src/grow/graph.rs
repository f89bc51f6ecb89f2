//! The planar segment graph G = (J, S) of built roads (and, as a layer of its own, waterways):
//! insertion splits at crossings, snaps to nodes within a tolerance and reuses existing
//! segments, so two road segments meet only at shared nodes.

use crate::geometry::index::SegmentIndex;
use crate::geometry::{closest_on_segment, dist, segment_intersection, sub, P};
use std::collections::HashMap;

/// Snap tolerance of insertion (metres): nodes closer than this are one.
pub const SNAP: f64 = 0.5;

/// A segment's class.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Class {
    /// A minor road.
    Minor,
    /// A major road.
    Major,
    /// A bridge (a major road over water).
    Bridge,
    /// A harbour: where a waterway meets the roads.
    Harbour,
    /// A waterway (not a road; its own planar layer).
    Water,
}

impl Class {
    /// The name written in `network.json`.
    pub fn name(self) -> &'static str {
        match self {
            Class::Minor => "minor",
            Class::Major => "major",
            Class::Bridge => "bridge",
            Class::Harbour => "harbour",
            Class::Water => "water",
        }
    }

    /// Part of the road layer (everything but waterways).
    pub fn is_road(self) -> bool {
        self != Class::Water
    }

    /// Carries trade routes (everything but minor roads).
    pub fn is_trade(self) -> bool {
        self != Class::Minor
    }
}

/// A node.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    /// Position (metres).
    pub pos: P,
    /// Whether minor roads have grown from it.
    pub spawned: bool,
}

/// A straight segment.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// One end.
    pub a: u32,
    /// The other end.
    pub b: u32,
    /// Its class.
    pub class: Class,
    /// Lanes.
    pub width: f64,
    /// The step it was built in.
    pub born: u32,
    /// Traffic on it, T(s).
    pub load: f64,
    /// An existing road kept as given (`fixed = true`): never widened or upgraded.
    pub fixed: bool,
}

/// The segment graph.
#[derive(Clone, Debug)]
pub struct Graph {
    /// Nodes.
    pub nodes: Vec<Node>,
    /// Segments (ids are stable; a split keeps the first piece under the old id).
    pub segs: Vec<Segment>,
    /// Segments at each node.
    pub adj: Vec<Vec<u32>>,
    /// Every split so far, `(a, b, x)`: segment `a–b` became `a–x–b`.
    pub splits: Vec<(u32, u32, u32)>,
    index: SegmentIndex,
    by_ends: HashMap<(u32, u32), u32>,
    grid: HashMap<(i64, i64), Vec<u32>>,
    cell: f64,
}

fn key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

impl Graph {
    /// An empty graph over the map `[0, W] × [0, H]`.
    pub fn new(size: [f64; 2]) -> Graph {
        Graph {
            nodes: Vec::new(),
            segs: Vec::new(),
            adj: Vec::new(),
            splits: Vec::new(),
            index: SegmentIndex::with_bounds([0.0, 0.0], size, 50.0),
            by_ends: HashMap::new(),
            grid: HashMap::new(),
            cell: 25.0,
        }
    }

    fn cell_of(&self, p: P) -> (i64, i64) {
        ((p[0] / self.cell).floor() as i64, (p[1] / self.cell).floor() as i64)
    }

    /// Nodes within `r` of `p` (ascending id).
    pub fn nodes_near(&self, p: P, r: f64) -> Vec<u32> {
        let (c0, c1) = (self.cell_of([p[0] - r, p[1] - r]), self.cell_of([p[0] + r, p[1] + r]));
        let mut out = Vec::new();
        for x in c0.0..=c1.0 {
            for y in c0.1..=c1.1 {
                if let Some(v) = self.grid.get(&(x, y)) {
                    out.extend(v.iter().copied().filter(|&n| dist(self.nodes[n as usize].pos, p) <= r));
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// Segment ids whose boxes may come within `r` of `p` (ascending).
    pub fn segs_near(&self, p: P, r: f64) -> Vec<usize> {
        self.index.near(p, r)
    }

    /// A segment's end positions.
    pub fn ends(&self, s: u32) -> (P, P) {
        let g = &self.segs[s as usize];
        (self.nodes[g.a as usize].pos, self.nodes[g.b as usize].pos)
    }

    /// A segment's length.
    pub fn length(&self, s: u32) -> f64 {
        let (a, b) = self.ends(s);
        dist(a, b)
    }

    /// The segment joining two nodes, if any.
    pub fn find(&self, a: u32, b: u32) -> Option<u32> {
        self.by_ends.get(&key(a, b)).copied()
    }

    /// The other end of segment `s` from node `n`.
    pub fn other(&self, s: u32, n: u32) -> u32 {
        let g = &self.segs[s as usize];
        if g.a == n {
            g.b
        } else {
            g.a
        }
    }

    /// Road segments at a node.
    pub fn road_degree(&self, n: u32) -> usize {
        self.adj[n as usize].iter().filter(|&&s| self.segs[s as usize].class.is_road()).count()
    }

    fn add_node(&mut self, p: P) -> u32 {
        let id = self.nodes.len() as u32;
        self.nodes.push(Node { pos: p, spawned: false });
        self.adj.push(Vec::new());
        let c = self.cell_of(p);
        self.grid.entry(c).or_default().push(id);
        id
    }

    fn add_seg(&mut self, a: u32, b: u32, class: Class, width: f64, born: u32, load: f64) -> u32 {
        let id = self.segs.len() as u32;
        let (pa, pb) = (self.nodes[a as usize].pos, self.nodes[b as usize].pos);
        self.segs.push(Segment { a, b, class, width, born, load, fixed: false });
        self.adj[a as usize].push(id);
        self.adj[b as usize].push(id);
        self.by_ends.insert(key(a, b), id);
        let i = self.index.push(pa, pb);
        debug_assert_eq!(i, id as usize);
        id
    }

    /// Splits segment `s` at node `x` (on it): `s` keeps `a–x`, a new segment `x–b` with the same
    /// class, width, age and traffic is returned. Refused (`None`) when `x` is an end or already
    /// joined to one (the pieces would duplicate segments).
    pub fn split(&mut self, s: u32, x: u32) -> Option<u32> {
        let Segment { a, b, class, width, born, load, fixed } = self.segs[s as usize].clone();
        if x == a || x == b || self.find(a, x).is_some() || self.find(x, b).is_some() {
            return None;
        }
        self.by_ends.remove(&key(a, b));
        self.adj[b as usize].retain(|&t| t != s);
        self.segs[s as usize].b = x;
        self.adj[x as usize].push(s);
        self.by_ends.insert(key(a, x), s);
        let (pa, px) = (self.nodes[a as usize].pos, self.nodes[x as usize].pos);
        self.index.shrink(s as usize, pa, px);
        self.splits.push((a, b, x));
        let piece = self.add_seg(x, b, class, width, born, load);
        self.segs[piece as usize].fixed = fixed;
        Some(piece)
    }

    /// The node at `p`: an existing one within [`SNAP`], else a new one (splitting a segment of
    /// the same layer that passes within [`SNAP`]).
    pub fn node_at(&mut self, p: P, road: bool) -> u32 {
        if let Some(&n) = self.nodes_near(p, SNAP).first() {
            return n;
        }
        let on = self.segs_near(p, SNAP).into_iter().find(|&s| {
            let g = &self.segs[s];
            let (a, b) = self.ends(s as u32);
            g.class.is_road() == road && dist(p, closest_on_segment(p, a, b).0) <= SNAP
        });
        let n = self.add_node(p);
        if let Some(s) = on {
            self.split(s as u32, n);
        }
        n
    }

    /// Inserts a straight segment between nodes `a` and `b`, split at every segment of its layer
    /// it crosses or touches; pieces that exist already are upgraded (a higher class, the larger
    /// width). Returns the chain of nodes from `a` to `b`.
    pub fn insert(&mut self, a: u32, b: u32, class: Class, width: f64, born: u32) -> Vec<u32> {
        if a == b {
            return vec![a];
        }
        let (pa, pb) = (self.nodes[a as usize].pos, self.nodes[b as usize].pos);
        let len = dist(pa, pb);
        let mid = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0];
        let road = class.is_road();
        let mut cuts: Vec<(f64, u32)> = vec![(0.0, a), (1.0, b)];
        for s in self.segs_near(mid, len / 2.0 + SNAP) {
            let s = s as u32;
            let g = self.segs[s as usize].clone();
            if g.class.is_road() != road {
                continue;
            }
            let (pc, pd) = (self.nodes[g.a as usize].pos, self.nodes[g.b as usize].pos);
            let shares = g.a == a || g.a == b || g.b == a || g.b == b;
            // Segments sharing an end meet only there, unless (nearly) collinear: then the ends
            // of one lying within the tolerance of the other are cuts or splits.
            let tol = SNAP;
            let mut touched = false;
            for (n, p) in [(g.a, pc), (g.b, pd)] {
                let (q, t) = closest_on_segment(p, pa, pb);
                if n != a
                    && n != b
                    && dist(p, q) <= tol
                    && t > 0.0
                    && t < 1.0
                    && dist(p, pa) > SNAP
                    && dist(p, pb) > SNAP
                {
                    cuts.push((t, n));
                    touched = true;
                }
            }
            for (n, p) in [(a, pa), (b, pb)] {
                let (cur_a, cur_b) = (self.segs[s as usize].a, self.segs[s as usize].b);
                if n == cur_a || n == cur_b {
                    continue;
                }
                let (qc, qd) = self.ends(s);
                let (q, u) = closest_on_segment(p, qc, qd);
                if dist(p, q) <= tol && u > 0.0 && u < 1.0 && dist(p, qc) > SNAP && dist(p, qd) > SNAP {
                    self.split(s, n);
                    touched = true;
                    break;
                }
            }
            if touched || shares {
                continue;
            }
            if let Some((t, _)) = segment_intersection(pa, pb, pc, pd) {
                let x = [pa[0] + (pb[0] - pa[0]) * t, pa[1] + (pb[1] - pa[1]) * t];
                let n = self.nodes_near(x, SNAP).first().copied().unwrap_or_else(|| self.add_node(x));
                if n == a || n == b {
                    continue;
                }
                if n != g.a && n != g.b {
                    self.split(s, n);
                }
                cuts.push((t, n));
            }
        }
        cuts.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        let mut chain: Vec<u32> = Vec::with_capacity(cuts.len());
        for (_, n) in cuts {
            if chain.last() != Some(&n) && !chain.contains(&n) {
                chain.push(n);
            }
        }
        if chain.last() != Some(&b) {
            chain.retain(|&n| n != b);
            chain.push(b);
        }
        for w in chain.windows(2) {
            self.link(w[0], w[1], class, width, born);
        }
        chain
    }

    /// Joins two nodes by one straight segment (no crossing checks), or upgrades the one there
    /// (unless it is fixed).
    fn link(&mut self, u: u32, v: u32, class: Class, width: f64, born: u32) {
        if u == v {
            return;
        }
        match self.find(u, v) {
            Some(s) => {
                let g = &mut self.segs[s as usize];
                if g.fixed {
                    return;
                }
                if class > g.class && g.class != Class::Water {
                    g.class = class;
                }
                g.width = g.width.max(width);
            }
            None => {
                self.add_seg(u, v, class, width, born, 0.0);
            }
        }
    }

    /// The direction of segment `s` leaving node `n` (unit vector).
    pub fn heading(&self, s: u32, n: u32) -> P {
        let o = self.other(s, n);
        let d = sub(self.nodes[o as usize].pos, self.nodes[n as usize].pos);
        let l = crate::geometry::norm(d).max(1e-12);
        [d[0] / l, d[1] / l]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_are_split_and_pieces_reused() {
        let mut g = Graph::new([100.0, 100.0]);
        let (a, b) = (g.node_at([0.0, 50.0], true), g.node_at([100.0, 50.0], true));
        g.insert(a, b, Class::Minor, 1.0, 0);
        let (c, d) = (g.node_at([50.0, 0.0], true), g.node_at([50.0, 100.0], true));
        let chain = g.insert(c, d, Class::Major, 1.0, 1);
        assert_eq!(chain.len(), 3);
        assert_eq!(g.segs.len(), 4);
        assert_eq!(g.road_degree(chain[1]), 4);
        // Re-inserting part of the first road reuses it and upgrades it.
        let e = g.node_at([0.0, 50.0], true);
        let chain = g.insert(e, chain[1], Class::Major, 2.0, 2);
        assert_eq!(chain.len(), 2);
        assert_eq!(g.segs.len(), 4);
        assert_eq!(g.segs[g.find(chain[0], chain[1]).unwrap() as usize].class, Class::Major);
        // A T: an end on a segment's interior splits it.
        let (f, h) = (g.node_at([75.0, 50.0], true), g.node_at([75.0, 80.0], true));
        assert_eq!(g.road_degree(f), 2);
        g.insert(f, h, Class::Minor, 1.0, 3);
        assert_eq!(g.road_degree(f), 3);
    }
}
