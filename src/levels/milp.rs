//! The exact placement model, built through the solver-neutral [`Model`] so that every backend
//! solves it.
//!
//! Per node `i`: a binary `z[i,k]` per allowed block `k` (exactly one), and a position
//! `(x_i, y_i)` bounded by hop distance × the longest single contact offset from the fixed
//! nodes (or from the first node, pinned at the origin: translations are symmetric).
//! Per graph edge `(i, j)`: a binary `c[e,k,l,s]` per configuration-space segment `s` of every
//! allowed block pair `(k, l)`, exactly one chosen and consistent with the block choices, and a
//! disaggregated convex combination `λ0 + λ1 = c` of the segment's ends giving
//! `p_j − p_i = Σ λ0 a_s + λ1 b_s` (the convex hull of the disjunction: no big-M).
//! Per non-adjacent pair and block pair and convex-part pair: one binary per facet of the parts'
//! Minkowski difference, at least one chosen when both blocks are, and the chosen facet's
//! half-plane `n · (p_j − p_i) ≥ h` (big-M from the position bounds; a part pair the bounds
//! already keep apart gets nothing). Adjacent pairs need no such rows: a configuration-space
//! segment has no overlap on it.
//! Per node, allowed block and obstacle (when the part has a fixed node; otherwise a layout is
//! moved clear of the obstacles afterwards, see [`super::clear_of_obstacles`]): the same facet
//! disjunction against the obstacle's fixed parts, big-M from the node's own position box.

use super::cspace::{CSpaces, Segment};
use super::spec::{BlockId, EdgeId, Level, NodeId, Objective};
use super::{Layout, Placement};
use crate::geometry::{dot, P};
use crate::milp::{Model, Sense, VarId};
use serde::Serialize;
use std::collections::BTreeSet;

/// A part of a level to model: some nodes and the graph edges among them that must hold.
#[derive(Clone, Debug)]
pub struct Part {
    /// Nodes, ascending (the placed ones included).
    pub nodes: Vec<NodeId>,
    /// Edges that must be doors (both ends in `nodes`; an edge between two placed nodes is
    /// left out of the model, it already holds or not).
    pub edges: Vec<EdgeId>,
    /// Nodes already laid out, ascending, each a node of `nodes` with its block and position
    /// held constant: partners of the other nodes' doors and blocks they must not overlap
    /// (an incremental layout's earlier steps). Empty for a whole level.
    pub placed: Vec<(NodeId, BlockId, P)>,
}

impl Part {
    /// The whole level.
    pub fn whole(level: &Level) -> Part {
        Part {
            nodes: (0..level.nodes.len() as u32).map(NodeId).collect(),
            edges: level.all_edges(),
            placed: Vec::new(),
        }
    }

    /// The nodes of `nodes` (ascending) and the level's edges among them, nothing placed: an
    /// induced subgraph as a level of its own.
    pub fn induced(level: &Level, nodes: Vec<NodeId>) -> Part {
        let edges = (0..level.edges.len() as u32)
            .map(EdgeId)
            .filter(|e| {
                let (a, b) = level.edges[e.0 as usize];
                nodes.binary_search(&a).is_ok() && nodes.binary_search(&b).is_ok()
            })
            .collect();
        Part { nodes, edges, placed: Vec::new() }
    }

    /// The placement of node `n` if it is placed.
    pub fn placement(&self, n: NodeId) -> Option<(BlockId, P)> {
        self.placed.binary_search_by_key(&n, |p| p.0).ok().map(|k| (self.placed[k].1, self.placed[k].2))
    }

    /// Where node `n` must be: its placement's position, else its fixed position in the level.
    fn anchor(&self, level: &Level, n: NodeId) -> Option<P> {
        self.placement(n).map(|p| p.1).or(level.nodes[n.0 as usize].position)
    }
}

/// Variables and rows of one family of the model.
#[derive(Clone, Debug, Default, Serialize)]
pub struct FamilySize {
    /// The family.
    pub family: &'static str,
    /// Variables it adds.
    pub vars: usize,
    /// Rows it adds.
    pub rows: usize,
}

struct ContactVar {
    ka: BlockId,
    kb: BlockId,
    seg: Segment,
    c: VarId,
    l0: VarId,
    l1: VarId,
}

struct ObstacleGroup {
    i: usize,
    k: BlockId,
    facets: Vec<(P, f64, VarId)>,
}

struct SepGroup {
    i: usize,
    j: usize,
    ka: BlockId,
    kb: BlockId,
    facets: Vec<(P, f64, VarId)>,
}

/// The built model and the map from its variables back to a layout.
pub struct LevelModel {
    /// The MILP.
    pub model: Model,
    nodes: Vec<NodeId>,
    pos: Vec<(VarId, VarId)>,
    choice: Vec<Vec<(BlockId, VarId)>>,
    contacts: Vec<(usize, usize, Vec<ContactVar>)>,
    seps: Vec<SepGroup>,
    obstacles: Vec<ObstacleGroup>,
    bbox: Option<[VarId; 4]>,
    /// Whether some node is placed (no translation of a start).
    pinned: bool,
    /// Size by family.
    pub families: Vec<FamilySize>,
}

/// Position bounds per node of the part: `[xlo, xhi, ylo, yhi]`, and the pinned root if no
/// node is fixed or placed (hop distance from each anchor × the longest contact offset).
pub fn bounds(level: &Level, cs: &CSpaces, part: &Part) -> Vec<[f64; 4]> {
    let fixed: Vec<(NodeId, P)> = part.nodes.iter().filter_map(|&n| part.anchor(level, n).map(|p| (n, p))).collect();
    let anchors: Vec<(NodeId, P)> = if fixed.is_empty() { vec![(part.nodes[0], [0.0, 0.0])] } else { fixed };
    let mut b: Vec<[f64; 4]> =
        vec![[f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY]; part.nodes.len()];
    for (root, at) in anchors {
        let hops = level.hops(root, &part.edges);
        for (k, n) in part.nodes.iter().enumerate() {
            let h = hops[n.0 as usize];
            // Every node of a part is connected to its anchors; guard anyway.
            let r = if h == usize::MAX { 1e4 } else { h as f64 * cs.reach };
            b[k] = [b[k][0].max(at[0] - r), b[k][1].min(at[0] + r), b[k][2].max(at[1] - r), b[k][3].min(at[1] + r)];
        }
    }
    b
}

struct Counter {
    vars: usize,
    rows: usize,
}

impl Counter {
    fn start(m: &Model) -> Counter {
        Counter { vars: m.num_vars(), rows: m.num_rows() }
    }
    fn done(self, m: &Model, family: &'static str) -> FamilySize {
        FamilySize { family, vars: m.num_vars() - self.vars, rows: m.num_rows() - self.rows }
    }
}

/// Builds the model of `part` of `level`.
pub fn build(level: &Level, cs: &CSpaces, part: &Part) -> LevelModel {
    let mut m = Model::new("level");
    m.sense = Sense::Minimize;
    let mut families = Vec::new();
    let nname = |k: usize| level.nodes[part.nodes[k].0 as usize].name.clone();
    let local = |n: NodeId| part.nodes.binary_search(&n).expect("edge ends are nodes of the part");

    // Block choice and positions.
    let c = Counter::start(&m);
    let b = bounds(level, cs, part);
    let mut pos = Vec::new();
    let mut choice = Vec::new();
    for (k, n) in part.nodes.iter().enumerate() {
        let name = nname(k);
        let x = m.add_continuous(format!("x_{name}"), b[k][0], b[k][1], 0.0);
        let y = m.add_continuous(format!("y_{name}"), b[k][2], b[k][3], 0.0);
        pos.push((x, y));
        let allowed = match part.placement(*n) {
            Some((bk, _)) => vec![bk],
            None => level.nodes[n.0 as usize].blocks.clone(),
        };
        let zs: Vec<(BlockId, VarId)> = allowed
            .iter()
            .map(|&bk| (bk, m.add_binary(format!("z_{name}_{}", level.blocks[bk.0 as usize].name), 0.0)))
            .collect();
        m.add_eq(format!("choose_{name}"), zs.iter().map(|&(_, v)| (v, 1.0)), 1.0);
        choice.push(zs);
    }
    families.push(c.done(&m, "block choice and positions"));

    // Contacts.
    let c = Counter::start(&m);
    let mut contacts = Vec::new();
    let is_placed: Vec<bool> = part.nodes.iter().map(|&n| part.placement(n).is_some()).collect();
    for &e in &part.edges {
        let (na, nb) = level.edges[e.0 as usize];
        let (i, j) = (local(na), local(nb));
        if is_placed[i] && is_placed[j] {
            continue;
        }
        let tag = format!("{}_{}", nname(i), nname(j));
        let mut vars = Vec::new();
        for &(ka, _) in &choice[i] {
            for &(kb, _) in &choice[j] {
                for (s, seg) in cs.segments(ka, kb).iter().enumerate() {
                    let t = format!("{tag}_{}_{}_{s}", ka.0, kb.0);
                    let cv = m.add_binary(format!("c_{t}"), 0.0);
                    let l0 = m.add_continuous(format!("l0_{t}"), 0.0, 1.0, 0.0);
                    let l1 = m.add_continuous(format!("l1_{t}"), 0.0, 1.0, 0.0);
                    m.add_eq(format!("hull_{t}"), [(l0, 1.0), (l1, 1.0), (cv, -1.0)], 0.0);
                    vars.push(ContactVar { ka, kb, seg: *seg, c: cv, l0, l1 });
                }
            }
        }
        m.add_eq(format!("door_{tag}"), vars.iter().map(|v| (v.c, 1.0)), 1.0);
        for &(ka, z) in &choice[i] {
            let terms = vars.iter().filter(|v| v.ka == ka).map(|v| (v.c, 1.0)).chain([(z, -1.0)]);
            m.add_eq(format!("link_{tag}_a{}", ka.0), terms, 0.0);
        }
        for &(kb, z) in &choice[j] {
            let terms = vars.iter().filter(|v| v.kb == kb).map(|v| (v.c, 1.0)).chain([(z, -1.0)]);
            m.add_eq(format!("link_{tag}_b{}", kb.0), terms, 0.0);
        }
        for axis in 0..2 {
            let (pi, pj) = if axis == 0 { (pos[i].0, pos[j].0) } else { (pos[i].1, pos[j].1) };
            let terms = [(pj, 1.0), (pi, -1.0)]
                .into_iter()
                .chain(vars.iter().flat_map(|v| [(v.l0, -v.seg.a[axis]), (v.l1, -v.seg.b[axis])]));
            m.add_eq(format!("offset{}_{tag}", if axis == 0 { "x" } else { "y" }), terms, 0.0);
        }
        contacts.push((i, j, vars));
    }
    families.push(c.done(&m, "contacts (segment choice, λ)"));

    // Non-overlap of non-adjacent pairs.
    let c = Counter::start(&m);
    let adjacent: BTreeSet<(usize, usize)> = contacts.iter().map(|&(i, j, _)| (i.min(j), i.max(j))).collect();
    let mut seps = Vec::new();
    for i in 0..part.nodes.len() {
        for j in i + 1..part.nodes.len() {
            if adjacent.contains(&(i, j)) || (is_placed[i] && is_placed[j]) {
                continue;
            }
            // Range of p_j − p_i over the bounds.
            let (dxl, dxh, dyl, dyh) = (b[j][0] - b[i][1], b[j][1] - b[i][0], b[j][2] - b[i][3], b[j][3] - b[i][2]);
            let lo = |n: P| n[0] * if n[0] > 0.0 { dxl } else { dxh } + n[1] * if n[1] > 0.0 { dyl } else { dyh };
            let hi = |n: P| n[0] * if n[0] > 0.0 { dxh } else { dxl } + n[1] * if n[1] > 0.0 { dyh } else { dyl };
            for &(ka, za) in &choice[i] {
                for &(kb, zb) in &choice[j] {
                    for (q, fs) in cs.facets(ka, kb).iter().enumerate() {
                        if fs.iter().any(|f| lo(f.n) >= f.h) {
                            continue; // the bounds keep these parts apart
                        }
                        let t = format!("{}_{}_{}_{}_{q}", nname(i), nname(j), ka.0, kb.0);
                        let mut facets = Vec::new();
                        for (fi, f) in fs.iter().enumerate() {
                            if hi(f.n) < f.h {
                                continue; // this side can never separate them
                            }
                            let d = m.add_binary(format!("s_{t}_{fi}"), 0.0);
                            let big = f.h - lo(f.n);
                            let terms = [
                                (pos[j].0, f.n[0]),
                                (pos[i].0, -f.n[0]),
                                (pos[j].1, f.n[1]),
                                (pos[i].1, -f.n[1]),
                                (d, -big),
                            ];
                            m.add_ge(format!("sep_{t}_{fi}"), terms, f.h - big);
                            facets.push((f.n, f.h, d));
                        }
                        let terms = facets.iter().map(|&(_, _, d)| (d, 1.0)).chain([(za, -1.0), (zb, -1.0)]);
                        m.add_ge(format!("apart_{t}"), terms, -1.0);
                        seps.push(SepGroup { i, j, ka, kb, facets });
                    }
                }
            }
        }
    }
    families.push(c.done(&m, "non-overlap (facet disjunctions)"));

    let mut obstacles = Vec::new();
    // Obstacles matter once something is pinned in absolute coordinates: a fixed node of the
    // part, or placed nodes of a level that has fixed nodes.
    let pinned = part.nodes.iter().any(|n| level.nodes[n.0 as usize].position.is_some())
        || (!part.placed.is_empty() && level.has_fixed());
    if !level.obstacles.is_empty() && pinned {
        let c = Counter::start(&m);
        obstacles = obstacle_rows(&mut m, level, cs, &b, &pos, &choice, &nname);
        families.push(c.done(&m, "obstacles (facet disjunctions)"));
    }

    let bbox = (level.objective == Objective::Bbox).then(|| {
        let c = Counter::start(&m);
        let v = bbox_rows(&mut m, level, &b, &pos, &choice);
        families.push(c.done(&m, "bounding box objective"));
        v
    });
    let pinned = !part.placed.is_empty();
    LevelModel { model: m, nodes: part.nodes.clone(), pos, choice, contacts, seps, obstacles, bbox, pinned, families }
}

/// Per node, allowed block, obstacle and convex-part pair: a binary per facet of the parts'
/// Minkowski difference, at least one chosen when the block is, and the chosen facet's
/// half-plane `n · p_i ≥ h` with `M = h − min_{box} n · p` (the node's position box, so `M` is
/// zero in effect for a fixed node). Facets the box can never satisfy get no binary; a part pair
/// the box already keeps apart gets nothing; a block with no facet left is forbidden.
fn obstacle_rows(
    m: &mut Model,
    level: &Level,
    cs: &CSpaces,
    b: &[[f64; 4]],
    pos: &[(VarId, VarId)],
    choice: &[Vec<(BlockId, VarId)>],
    nname: &dyn Fn(usize) -> String,
) -> Vec<ObstacleGroup> {
    let mut out = Vec::new();
    for (i, zs) in choice.iter().enumerate() {
        let lo = |n: P| {
            n[0] * if n[0] > 0.0 { b[i][0] } else { b[i][1] } + n[1] * if n[1] > 0.0 { b[i][2] } else { b[i][3] }
        };
        let hi = |n: P| {
            n[0] * if n[0] > 0.0 { b[i][1] } else { b[i][0] } + n[1] * if n[1] > 0.0 { b[i][3] } else { b[i][2] }
        };
        for &(k, z) in zs {
            for o in 0..level.obstacles.len() {
                for (q, fs) in cs.obstacle_facets(o, k).iter().enumerate() {
                    if fs.iter().any(|f| lo(f.n) >= f.h) {
                        continue;
                    }
                    let t = format!("{}_{}_o{o}_{q}", nname(i), k.0);
                    let mut facets = Vec::new();
                    for (fi, f) in fs.iter().enumerate() {
                        if hi(f.n) < f.h {
                            continue;
                        }
                        let d = m.add_binary(format!("so_{t}_{fi}"), 0.0);
                        let big = f.h - lo(f.n);
                        m.add_ge(
                            format!("clear_{t}_{fi}"),
                            [(pos[i].0, f.n[0]), (pos[i].1, f.n[1]), (d, -big)],
                            f.h - big,
                        );
                        facets.push((f.n, f.h, d));
                    }
                    let terms = facets.iter().map(|&(_, _, d)| (d, 1.0)).chain([(z, -1.0)]);
                    m.add_ge(format!("avoid_{t}"), terms, 0.0);
                    out.push(ObstacleGroup { i, k, facets });
                }
            }
        }
    }
    out
}

/// `xmin ≤ x_i + minx(block)`, `xmax ≥ x_i + maxx(block)` (and in y); minimise the width plus
/// the height.
fn bbox_rows(
    m: &mut Model,
    level: &Level,
    b: &[[f64; 4]],
    pos: &[(VarId, VarId)],
    choice: &[Vec<(BlockId, VarId)>],
) -> [VarId; 4] {
    let ext = |k: BlockId, axis: usize, max: bool| {
        let it = level.blocks[k.0 as usize].polygon.iter().map(|p| p[axis]);
        if max {
            it.fold(f64::NEG_INFINITY, f64::max)
        } else {
            it.fold(f64::INFINITY, f64::min)
        }
    };
    let lo = b.iter().map(|x| x[0].min(x[2])).fold(f64::INFINITY, f64::min) - 1e3;
    let hi = b.iter().map(|x| x[1].max(x[3])).fold(f64::NEG_INFINITY, f64::max) + 1e3;
    let v = [
        m.add_continuous("xmin", lo, hi, -1.0),
        m.add_continuous("xmax", lo, hi, 1.0),
        m.add_continuous("ymin", lo, hi, -1.0),
        m.add_continuous("ymax", lo, hi, 1.0),
    ];
    for (k, (&(x, y), zs)) in pos.iter().zip(choice).enumerate() {
        for (axis, p) in [(0, x), (1, y)] {
            let low = zs.iter().map(|&(bk, z)| (z, ext(bk, axis, false)));
            m.add_le(
                format!("bblo{axis}_{k}"),
                [(v[2 * axis], 1.0), (p, -1.0)].into_iter().chain(low.map(|(z, c)| (z, -c))),
                0.0,
            );
            let high = zs.iter().map(|&(bk, z)| (z, ext(bk, axis, true)));
            m.add_ge(
                format!("bbhi{axis}_{k}"),
                [(v[2 * axis + 1], 1.0), (p, -1.0)].into_iter().chain(high.map(|(z, c)| (z, -c))),
                0.0,
            );
        }
    }
    v
}

impl LevelModel {
    /// The layout of a primal point (the part's nodes only).
    pub fn decode(&self, level: &Level, x: &[f64]) -> Layout {
        let nodes = self
            .nodes
            .iter()
            .enumerate()
            .map(|(k, &n)| {
                let block = self.choice[k]
                    .iter()
                    .max_by(|a, b| x[a.1.index()].total_cmp(&x[b.1.index()]))
                    .map(|&(bk, _)| bk)
                    .unwrap_or(BlockId(0));
                Placement::new(level, n, block, [x[self.pos[k].0.index()], x[self.pos[k].1.index()]])
            })
            .collect();
        Layout { nodes }
    }

    /// The no-good row that cuts off this point's choice of contact segments.
    pub fn no_good(&mut self, x: &[f64], index: usize) {
        let on: Vec<VarId> =
            self.contacts.iter().flat_map(|(_, _, vs)| vs.iter().map(|v| v.c)).filter(|c| x[c.index()] > 0.5).collect();
        let n = on.len() as f64;
        // The row count keeps names unique when a model is cut again after a retry.
        let name = format!("nogood_{index}_{}", self.model.num_rows());
        self.model.add_le(name, on.into_iter().map(|c| (c, 1.0)), n - 1.0);
    }

    /// Minimises `−d · p_i` over the part's nodes (placed ones are constants): the free
    /// nodes pushed as far as they go in direction `d` (an incremental step grown away from
    /// what is placed). Left as it is when the model already minimises the bounding box.
    pub fn push_towards(&mut self, d: P) {
        if self.bbox.is_some() {
            return;
        }
        for &(x, y) in &self.pos {
            self.model.var_mut(x).obj = -d[0];
            self.model.var_mut(y).obj = -d[1];
        }
    }

    /// Whether the model has a contact binary to cut on (a level with edges).
    pub fn has_contacts(&self) -> bool {
        !self.contacts.is_empty()
    }

    /// A layout (of the whole level, translated so the part's anchor sits where the model pins
    /// it) as a point of the model: a MIP start. The solver's start check decides whether it
    /// holds.
    pub fn encode(&self, level: &Level, layout: &Layout) -> Vec<f64> {
        let mut x = vec![0.0; self.model.num_vars()];
        let shift = self.anchor_shift(level, layout);
        let place = |n: NodeId| {
            let p = &layout.nodes[n.0 as usize];
            (p.block, [p.position[0] + shift[0], p.position[1] + shift[1]])
        };
        let at: Vec<(BlockId, P)> = self.nodes.iter().map(|&n| place(n)).collect();
        for (k, &(bk, p)) in at.iter().enumerate() {
            x[self.pos[k].0.index()] = p[0];
            x[self.pos[k].1.index()] = p[1];
            for &(b, z) in &self.choice[k] {
                x[z.index()] = if b == bk { 1.0 } else { 0.0 };
            }
        }
        for (i, j, vars) in &self.contacts {
            let d = [at[*j].1[0] - at[*i].1[0], at[*j].1[1] - at[*i].1[1]];
            let best = vars
                .iter()
                .filter(|v| v.ka == at[*i].0 && v.kb == at[*j].0)
                .map(|v| (v, v.seg.project(d)))
                .min_by(|a, b| a.1 .1.total_cmp(&b.1 .1));
            if let Some((v, (t, _))) = best {
                x[v.c.index()] = 1.0;
                x[v.l0.index()] = 1.0 - t;
                x[v.l1.index()] = t;
            }
        }
        for g in &self.seps {
            if at[g.i].0 != g.ka || at[g.j].0 != g.kb {
                continue;
            }
            let d = [at[g.j].1[0] - at[g.i].1[0], at[g.j].1[1] - at[g.i].1[1]];
            if let Some(&(_, _, v)) = g.facets.iter().max_by(|a, b| (dot(a.0, d) - a.1).total_cmp(&(dot(b.0, d) - b.1)))
            {
                x[v.index()] = 1.0;
            }
        }
        for g in &self.obstacles {
            if at[g.i].0 != g.k {
                continue;
            }
            let p = at[g.i].1;
            if let Some(&(_, _, v)) = g.facets.iter().max_by(|a, b| (dot(a.0, p) - a.1).total_cmp(&(dot(b.0, p) - b.1)))
            {
                x[v.index()] = 1.0;
            }
        }
        if let Some(v) = self.bbox {
            let placed: Vec<Vec<P>> = at
                .iter()
                .map(|&(bk, p)| crate::geometry::convex::translate(&level.blocks[bk.0 as usize].polygon, p))
                .collect();
            let all = placed.iter().flatten();
            x[v[0].index()] = all.clone().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            x[v[1].index()] = all.clone().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
            x[v[2].index()] = all.clone().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            x[v[3].index()] = all.map(|p| p[1]).fold(f64::NEG_INFINITY, f64::max);
        }
        x
    }

    /// The translation that moves a free layout onto the model's pinned anchor (none when
    /// some node is fixed: the layout must already respect it).
    fn anchor_shift(&self, level: &Level, layout: &Layout) -> P {
        if self.pinned || self.nodes.iter().any(|n| level.nodes[n.0 as usize].position.is_some()) {
            return [0.0, 0.0];
        }
        let p = layout.nodes[self.nodes[0].0 as usize].position;
        [-p[0], -p[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levels::generate::Generated;

    #[test]
    fn a_model_cut_twice_with_the_same_index_keeps_its_row_names_unique() {
        let level = Generated::parse("path:3").unwrap().level(0.5).unwrap();
        let cs = CSpaces::new(&level);
        let mut lm = build(&level, &cs, &Part::whole(&level));
        let x: Vec<f64> = vec![1.0; lm.model.num_vars()];
        lm.no_good(&x, 1);
        lm.no_good(&x, 1);
        let names: BTreeSet<&str> = lm.model.rows().map(|r| r.name).collect();
        assert_eq!(names.len(), lm.model.num_rows());
    }
}
