//! Exact placement of a chain's nodes, one at a time, for the annealer's start: each node goes
//! to a position in the intersection of *all* its placed neighbours' configuration spaces
//! (where a cycle closes, a point), minus the positions where it would overlap a placed block
//! or an obstacle — so a placement the search makes has no energy at all. A randomised
//! depth-first search with backtracking over the chain's nodes tries, per node, the ends,
//! middles and aligned points of those segments (straight on first, most of the time) and a
//! random point; two look-aheads prune it: every unplaced neighbour must keep a non-empty
//! space, and every placed pair must stay within hop distance × the longest contact step
//! (what lets a long cycle come back to close).

use super::cspace::{clip_out, intersect, CSpaces, Segment};
use super::spec::{BlockId, Level, NodeId};
use super::validate::shared_wall;
use crate::geometry::convex::{self, bounding_box, boxes_apart, length, Facet, AREA_TOL, LEN_TOL};
use crate::geometry::{self, sub, P};
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use std::collections::VecDeque;

/// A node's block and position, if placed.
pub type Slot = Option<(BlockId, P)>;

/// The fixed data of exact placement.
pub struct Placer<'a> {
    level: &'a Level,
    cs: &'a CSpaces,
    adj: Vec<Vec<NodeId>>,
    /// Per block: triangles.
    tris: Vec<Vec<[P; 3]>>,
    /// Per block: `[xmin, xmax, ymin, ymax]`.
    pub boxes: Vec<[f64; 4]>,
    centre: Vec<P>,
    /// Obstacles: triangles and box (absolute coordinates).
    pub obstacles: Vec<(Vec<[P; 3]>, [f64; 4])>,
    /// The longest distance between the centres of two blocks in door contact.
    step: f64,
    /// The largest block dimension (the crowding test's margin).
    margin: f64,
    /// A pace a walk of contacts can keep towards any target: 0.7 × the shortest contact step.
    pace: f64,
}

/// The centre a block is measured by: the mean of its vertices.
fn block_centre(poly: &[P]) -> P {
    let n = poly.len() as f64;
    poly.iter().fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n])
}

/// A placement, how straight on it continues, and its sort key (outside the pace, crowding).
type Candidate = ((BlockId, P), f64, (bool, usize, u64));

/// Targets this many hops away or closer draw a placement towards them (the cycles about to
/// close: a grid's next row above the last, not beside it).
const NEAR_HOPS: u32 = 3;

/// Per-node search state of the depth-first placement.
struct Frame {
    node: usize,
    candidates: Vec<(BlockId, P)>,
    targets: Vec<(usize, u32)>,
    next: usize,
}

impl<'a> Placer<'a> {
    /// Precomputes shapes, hop distances and the longest contact step.
    pub fn new(level: &'a Level, cs: &'a CSpaces) -> Placer<'a> {
        let adj = level.adjacency(&level.all_edges());
        let tris = level.blocks.iter().map(|b| convex::triangulate(&b.polygon)).collect();
        let boxes: Vec<[f64; 4]> = level.blocks.iter().map(|b| bounding_box(&b.polygon)).collect();
        let centre: Vec<P> = level.blocks.iter().map(|b| block_centre(&b.polygon)).collect();
        let obstacles =
            level.obstacles.iter().map(|o| (convex::triangulate(&o.polygon), bounding_box(&o.polygon))).collect();
        let n = level.blocks.len() as u32;
        let mut step: f64 = 0.0;
        for a in 0..n {
            for b in 0..n {
                for g in cs.segments(BlockId(a), BlockId(b)) {
                    for p in [g.a, g.b] {
                        let d = sub(geometry::add(centre[b as usize], p), centre[a as usize]);
                        step = step.max(length(d));
                    }
                }
            }
        }
        let mut min_step = f64::INFINITY;
        for a in 0..n {
            for b in 0..n {
                for g in cs.segments(BlockId(a), BlockId(b)) {
                    min_step = min_step.min(g.project(sub(centre[a as usize], centre[b as usize])).1);
                }
            }
        }
        let pace = if min_step.is_finite() { 0.7 * min_step } else { step };
        let margin = boxes.iter().map(|b| (b[1] - b[0]).max(b[3] - b[2])).fold(0.0, f64::max);
        Placer { level, cs, adj, tris, boxes, centre, obstacles, step, pace, margin }
    }

    /// The graph's adjacency lists.
    pub fn adjacency(&self) -> &[Vec<NodeId>] {
        &self.adj
    }

    /// The box of block `a.0` placed at `a.1`.
    pub fn placed_box(&self, a: (BlockId, P)) -> [f64; 4] {
        let b = self.boxes[a.0 .0 as usize];
        [b[0] + a.1[0], b[1] + a.1[0], b[2] + a.1[1], b[3] + a.1[1]]
    }

    /// The triangles of block `a.0` placed at `a.1`.
    pub fn placed_tris(&self, a: (BlockId, P)) -> Vec<[P; 3]> {
        self.tris[a.0 .0 as usize].iter().map(|t| t.map(|p| geometry::add(p, a.1))).collect()
    }

    /// The centre of block `a.0` placed at `a.1`.
    pub fn centre_of(&self, a: (BlockId, P)) -> P {
        geometry::add(self.centre[a.0 .0 as usize], a.1)
    }

    /// Whether two placed blocks share a wall at least a door wide.
    pub fn in_contact(&self, a: (BlockId, P), b: (BlockId, P)) -> bool {
        let pa = convex::translate(&self.level.blocks[a.0 .0 as usize].polygon, a.1);
        let pb = convex::translate(&self.level.blocks[b.0 .0 as usize].polygon, b.1);
        shared_wall(&pa, &pb).is_some_and(|w| length(sub(w[1], w[0])) >= self.level.door_width - LEN_TOL)
    }

    /// The positions of node `i` as block `b` touching every placed neighbour by a door and
    /// clear of every placed block and obstacle (segments, possibly single points); `None`
    /// when `i` has no placed neighbour.
    pub fn space(&self, s: &[Slot], i: usize, b: BlockId) -> Option<Vec<Segment>> {
        let mut acc: Option<Vec<Segment>> = None;
        for n in &self.adj[i] {
            let Some((nb, p)) = s[n.0 as usize] else { continue };
            let sp: Vec<Segment> = self
                .cs
                .segments(nb, b)
                .iter()
                .map(|g| Segment { a: geometry::add(g.a, p), b: geometry::add(g.b, p) })
                .collect();
            acc = Some(match acc {
                None => sp,
                Some(a) => intersect(&a, &sp),
            });
            if acc.as_ref().is_some_and(|a| a.is_empty()) {
                return Some(Vec::new());
            }
        }
        let acc = acc?;
        Some(self.clear(s, i, b, acc))
    }

    /// The pieces of `segs` at which block `b` overlaps no placed block (but node `i`'s own)
    /// and no obstacle.
    fn clear(&self, s: &[Slot], i: usize, b: BlockId, segs: Vec<Segment>) -> Vec<Segment> {
        if segs.is_empty() {
            return segs;
        }
        // The box of every position on the segments, grown by the block's extent.
        let bb = self.boxes[b.0 as usize];
        let mut reach = [f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY];
        for g in &segs {
            for p in [g.a, g.b] {
                reach = [
                    reach[0].min(p[0] + bb[0]),
                    reach[1].max(p[0] + bb[1]),
                    reach[2].min(p[1] + bb[2]),
                    reach[3].max(p[1] + bb[3]),
                ];
            }
        }
        let mut lists: Vec<Vec<Facet>> = Vec::new();
        for (j, sj) in s.iter().enumerate() {
            let Some((kb, p)) = *sj else { continue };
            if j == i || boxes_apart(reach, self.placed_box((kb, p))) {
                continue;
            }
            for fs in self.cs.facets(kb, b) {
                lists.push(fs.iter().map(|f| Facet { n: f.n, h: f.h + geometry::dot(f.n, p) }).collect());
            }
        }
        for (o, (_, ob)) in self.obstacles.iter().enumerate() {
            if !boxes_apart(reach, *ob) {
                lists.extend(self.cs.obstacle_facets(o, b).iter().cloned());
            }
        }
        if lists.is_empty() {
            return segs;
        }
        segs.iter().flat_map(|g| clip_out(g, &lists)).collect()
    }

    /// Whether node `i` as `at` meets the validator's tests against everything placed:
    /// no overlap above [`AREA_TOL`] with a block or an obstacle, a door to every placed
    /// neighbour.
    pub fn fits(&self, s: &[Slot], i: usize, at: (BlockId, P)) -> bool {
        let bx = self.placed_box(at);
        let mut tris: Option<Vec<[P; 3]>> = None;
        for (j, sj) in s.iter().enumerate() {
            let Some(o) = *sj else { continue };
            if j == i || boxes_apart(bx, self.placed_box(o)) {
                continue;
            }
            let t = tris.get_or_insert_with(|| self.placed_tris(at));
            if convex::overlap_area(t, &self.placed_tris(o)) > AREA_TOL {
                return false;
            }
        }
        for (ot, ob) in &self.obstacles {
            if !boxes_apart(bx, *ob) {
                let t = tris.get_or_insert_with(|| self.placed_tris(at));
                if convex::overlap_area(t, ot) > AREA_TOL {
                    return false;
                }
            }
        }
        self.adj[i].iter().all(|n| s[n.0 as usize].is_none_or(|o| self.in_contact(at, o)))
    }

    /// The placed nodes that node `i` must still be joined to through nodes not yet placed,
    /// with the fewest hops of such a route (breadth-first over unplaced nodes; `i`'s own
    /// placed neighbours, joined by a contact already, are left out).
    fn targets(&self, s: &[Slot], i: usize) -> Vec<(usize, u32)> {
        let mut dist = vec![u32::MAX; s.len()];
        dist[i] = 0;
        let mut q = VecDeque::from([i]);
        let mut out = Vec::new();
        while let Some(u) = q.pop_front() {
            for v in &self.adj[u] {
                let v = v.0 as usize;
                if dist[v] != u32::MAX {
                    continue;
                }
                dist[v] = dist[u] + 1;
                if s[v].is_some() {
                    if u != i {
                        out.push((v, dist[v]));
                    }
                } else {
                    q.push_back(v);
                }
            }
        }
        out
    }

    /// Whether a placement at `at` stays within reach of its targets: centres at most hop
    /// distance × the longest contact step apart (a necessary condition for the nodes between
    /// them to close the gap).
    fn within_reach(&self, targets: &[(usize, u32)], s: &[Slot], at: (BlockId, P)) -> bool {
        let c = self.centre_of(at);
        targets
            .iter()
            .all(|&(j, d)| s[j].is_none_or(|o| length(sub(c, self.centre_of(o))) <= f64::from(d) * self.step + LEN_TOL))
    }

    /// Whether a placement at `at` keeps its targets within the pace a walk can surely keep
    /// (hop distance × [`Placer::pace`] plus two steps): not necessary for a layout, so only a
    /// preference — it turns a long cycle back in time to close.
    fn within_pace(&self, targets: &[(usize, u32)], s: &[Slot], at: (BlockId, P)) -> bool {
        let c = self.centre_of(at);
        targets.iter().all(|&(j, d)| {
            s[j].is_none_or(|o| length(sub(c, self.centre_of(o))) <= f64::from(d) * self.pace + 2.0 * self.step)
        })
    }

    /// Whether every unplaced neighbour of `i` still has somewhere to go.
    fn neighbours_open(&self, s: &[Slot], i: usize) -> bool {
        self.adj[i].iter().all(|u| {
            let u = u.0 as usize;
            s[u].is_some()
                || self.level.nodes[u].position.is_some()
                || self.level.nodes[u].blocks.iter().any(|&b| self.space(s, u, b).is_none_or(|sp| !sp.is_empty()))
        })
    }

    /// Candidate placements of node `i`, best first: for each allowed block, points of its
    /// space (ends, middles, points aligned with a placed neighbour's centre, one random
    /// point per segment). Most of the time ordered by how straight on they continue from
    /// the neighbour they attach to; otherwise shuffled.
    fn candidates(
        &self,
        s: &[Slot],
        i: usize,
        targets: &[(usize, u32)],
        rng: &mut Xoshiro256PlusPlus,
    ) -> Vec<(BlockId, P)> {
        if let Some(p) = self.level.nodes[i].position {
            return self.level.nodes[i].blocks.iter().map(|&b| (b, p)).collect();
        }
        let placed_nbs: Vec<(BlockId, P)> = self.adj[i].iter().filter_map(|n| s[n.0 as usize]).collect();
        let mut out: Vec<Candidate> = Vec::new();
        for &b in &self.level.nodes[i].blocks {
            let segs = match self.space(s, i, b) {
                Some(x) => x,
                None => vec![Segment { a: self.free_start(s, b), b: self.free_start(s, b) }],
            };
            for g in &segs {
                let mut pts = vec![g.a, g.b, g.at(0.5), g.at(rng.random::<f64>())];
                for &nb in &placed_nbs {
                    // The positions where the centres line up across or along the wall.
                    let want = sub(self.centre_of(nb), self.centre[b.0 as usize]);
                    for (axis, &v) in want.iter().enumerate() {
                        if let Some(p) = point_on_axis(g, axis, v) {
                            pts.push(p);
                        }
                    }
                }
                for p in pts {
                    if out.iter().any(|(q, _, _)| q.0 == b && length(sub(q.1, p)) < LEN_TOL) {
                        continue;
                    }
                    let at = (b, p);
                    let key = (
                        !self.within_pace(targets, s, at),
                        self.crowding(s, i, at, targets),
                        self.pull(s, at, targets),
                    );
                    out.push(((b, p), self.straightness(s, i, (b, p)), key));
                }
            }
        }
        // Within pace first, then the least crowded (a walk that keeps clear of what is laid out
        // does not trap itself), then the nearest to the cycles about to close; among those,
        // straight on first, or at random one time in four. A little
        // noise breaks ties so that layouts differ.
        let straight = rng.random::<f64>() < 0.75;
        for x in out.iter_mut() {
            x.1 = if straight { x.1 + 1e-3 * rng.random::<f64>() } else { rng.random::<f64>() };
        }
        out.sort_by(|x, y| x.2.cmp(&y.2).then(y.1.total_cmp(&x.1)));
        out.into_iter().map(|x| x.0).collect()
    }

    /// How many placed blocks other than node `i`'s neighbours and its near targets come within
    /// a block's extent of the placement (boxes grown by the largest block dimension).
    fn crowding(&self, s: &[Slot], i: usize, at: (BlockId, P), targets: &[(usize, u32)]) -> usize {
        let b = self.placed_box(at);
        let m = self.margin;
        let grown = [b[0] - m, b[1] + m, b[2] - m, b[3] + m];
        s.iter()
            .enumerate()
            .filter(|(j, sj)| {
                *j != i
                    && sj.is_some_and(|o| !boxes_apart(grown, self.placed_box(o)))
                    && !self.adj[i].iter().any(|n| n.0 as usize == *j)
                    && !targets.iter().any(|&(t, d)| t == *j && d <= NEAR_HOPS)
            })
            .count()
    }

    /// How far the placement is from the targets a few hops away (the sum of centre distances
    /// over hops, in millionths): nearer is better, 0 when there is none.
    fn pull(&self, s: &[Slot], at: (BlockId, P), targets: &[(usize, u32)]) -> u64 {
        let c = self.centre_of(at);
        let sum: f64 = targets
            .iter()
            .filter(|t| t.1 <= NEAR_HOPS)
            .filter_map(|&(j, d)| s[j].map(|o| length(sub(c, self.centre_of(o))) / f64::from(d)))
            .sum();
        (sum * 1e6).round() as u64
    }

    /// How straight on a placement continues: the cosine between its step from the placed
    /// neighbour it attaches to and that neighbour's own step from its placed neighbour
    /// (1 straight on, 0 when there is no earlier step), plus a bonus for centres on a line.
    fn straightness(&self, s: &[Slot], i: usize, at: (BlockId, P)) -> f64 {
        let c = self.centre_of(at);
        let mut best: f64 = 0.0;
        for n in &self.adj[i] {
            let Some(p) = s[n.0 as usize] else { continue };
            let cp = self.centre_of(p);
            let d1 = sub(c, cp);
            let aligned = if d1[0].abs() < LEN_TOL || d1[1].abs() < LEN_TOL { 0.5 } else { 0.0 };
            let mut cos: f64 = 0.0;
            for m in &self.adj[n.0 as usize] {
                if m.0 as usize == i {
                    continue;
                }
                if let Some(q) = s[m.0 as usize] {
                    let d0 = sub(cp, self.centre_of(q));
                    let l = length(d0) * length(d1);
                    if l > LEN_TOL {
                        cos = cos.max(geometry::dot(d0, d1) / l);
                    }
                }
            }
            best = best.max(cos + aligned);
        }
        best
    }

    /// A position for block `b` right of everything placed (a node with no placed neighbour).
    fn free_start(&self, s: &[Slot], b: BlockId) -> P {
        if s.iter().all(|x| x.is_none()) && self.obstacles.is_empty() {
            return [0.0, 0.0];
        }
        let right = s
            .iter()
            .flatten()
            .map(|a| self.placed_box(*a)[1])
            .chain(self.obstacles.iter().map(|o| o.1[1]))
            .fold(0.0, f64::max);
        [right - self.boxes[b.0 as usize][0] + 1.0, 0.0]
    }

    /// Places the nodes of `order` (in that order) into `s` by a depth-first search with
    /// backtracking, at most `budget` placements tried; `stop` is asked now and then. On
    /// success every node of `order` is placed and `s` has no energy; on failure `s` is as it
    /// was and the nodes placed deepest are returned (for the annealer to start from).
    pub fn place(
        &self,
        s: &mut [Slot],
        order: &[NodeId],
        rng: &mut Xoshiro256PlusPlus,
        budget: usize,
        stop: &dyn Fn() -> bool,
    ) -> Result<(), Vec<Slot>> {
        let original = s.to_vec();
        let mut stack: Vec<Frame> = Vec::new();
        let mut deepest: (usize, Vec<Slot>) = (0, original.clone());
        let mut tried = 0usize;
        let mut depth = 0usize;
        while depth < order.len() {
            if stack.len() == depth {
                let node = order[depth].0 as usize;
                let targets = self.targets(s, node);
                let candidates = self.candidates(s, node, &targets, rng);
                stack.push(Frame { node, candidates, targets, next: 0 });
            }
            let f = stack.last_mut().expect("a frame per depth");
            let node = f.node;
            s[node] = None;
            let mut placed = false;
            while f.next < f.candidates.len() {
                let at = f.candidates[f.next];
                f.next += 1;
                tried += 1;
                s[node] = Some(at);
                if self.fits(s, node, at) && self.within_reach(&f.targets, s, at) && self.neighbours_open(s, node) {
                    placed = true;
                    break;
                }
                s[node] = None;
                if tried >= budget {
                    break;
                }
            }
            if placed {
                depth += 1;
                if depth > deepest.0 {
                    deepest = (depth, s.to_vec());
                }
            } else {
                stack.pop();
                if stack.is_empty() || tried >= budget || (tried.is_multiple_of(64) && stop()) {
                    s.copy_from_slice(&original);
                    return Err(deepest.1);
                }
                depth -= 1;
            }
        }
        Ok(())
    }
}

/// The point of segment `g` whose coordinate `axis` is `v`, if the segment crosses it (a
/// segment along the axis has none unless it is a single point).
fn point_on_axis(g: &Segment, axis: usize, v: f64) -> Option<P> {
    let d = g.b[axis] - g.a[axis];
    if d.abs() < LEN_TOL {
        return None;
    }
    let t = (v - g.a[axis]) / d;
    (-1e-12..=1.0 + 1e-12).contains(&t).then(|| g.at(t.clamp(0.0, 1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::generate::Generated;
    use rand::SeedableRng;

    fn place_all(family: &str, w: f64) -> Option<Vec<Slot>> {
        let level = Generated::parse(family).unwrap().level(w).unwrap();
        let cs = CSpaces::new(&level);
        let p = Placer::new(&level, &cs);
        let mut s = vec![None; level.nodes.len()];
        let order: Vec<NodeId> = (0..level.nodes.len() as u32).map(NodeId).collect();
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        p.place(&mut s, &order, &mut rng, 100_000, &|| false).ok().map(|_| s)
    }

    #[test]
    fn a_grid_of_squares_closes_every_cycle_exactly() {
        let s = place_all("grid:4x4", 0.5).expect("a 4 × 4 grid graph has a layout");
        assert!(s.iter().all(|x| x.is_some()));
    }

    #[test]
    fn a_triangle_of_squares_wider_than_half_has_no_placement() {
        assert!(place_all("cycle:3", 0.55).is_none());
        assert!(place_all("cycle:3", 0.5).is_some());
    }

    #[test]
    fn targets_are_the_placed_nodes_joined_through_unplaced_ones() {
        let level = Generated::parse("cycle:6").unwrap().level(0.5).unwrap();
        let cs = CSpaces::new(&level);
        let p = Placer::new(&level, &cs);
        let mut s: Vec<Slot> = vec![None; 6];
        s[0] = Some((BlockId(0), [0.0, 0.0]));
        s[1] = Some((BlockId(0), [1.0, 0.0]));
        // Node 2 touches 1 directly and reaches 0 the other way round, through 3, 4, 5.
        assert_eq!(p.targets(&s, 2), vec![(0, 4)]);
        let path = Generated::parse("path:4").unwrap().level(0.5).unwrap();
        let cs = CSpaces::new(&path);
        let p = Placer::new(&path, &cs);
        let mut s: Vec<Slot> = vec![None; 4];
        s[0] = Some((BlockId(0), [0.0, 0.0]));
        assert!(p.targets(&s, 1).is_empty(), "a path has nothing to close");
    }
}
