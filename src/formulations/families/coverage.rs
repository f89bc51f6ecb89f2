//! Vertex activity (5), coverage (6), and the edge-coverage rows and ball cuts of
//! docs/formulation.md §8.

use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::expr::{Expr, Value};
use crate::formulations::family::{vname, Ctx, Family};
use crate::rules::cover_set;
use crate::spec::{Allow, CoverageForm, EdgeRole};

/// `V_y` and (5) for every vertex; without room tiling (whose rows replace it) also (6) and its
/// strengthenings.
pub struct Coverage {
    rooms: bool,
}

impl Coverage {
    /// Always in the model.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        Some(Box::new(Coverage { rooms: c.p.rooms.is_some() }))
    }
}

impl Family for Coverage {
    fn label(&self) -> String {
        if self.rooms { "vertices (5)" } else { "coverage (5)-(6)" }.to_string()
    }

    fn emit(&mut self, c: &mut Ctx) {
        vertices(c);
        if !self.rooms {
            coverage(c);
        }
    }

    /// A vertex is active when it has an active edge.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        for v in e.p.mesh.vertices() {
            if let Value::Var(y) = e.vars.vertex[v.index()] {
                x[y.index()] = if e.degree(v) > 0 { 1.0 } else { 0.0 };
            }
        }
        Ok(())
    }
}

/// `V_y` for every vertex whose incident edges are candidates or excluded (a vertex with an
/// existing edge is active as a constant), tied to its edges by (5):
/// `aggregated`: `1 − |E_y| ≤ Σ_{x∈E_y} E_x − |E_y|·V_y ≤ 0`;
/// otherwise `V_y ≤ Σ_{x∈E_y} E_x` and `E_x ≤ V_y` for each incident `x`.
/// Forced vertices get `V_y ≥ 1` on the variable's bound.
fn vertices(c: &mut Ctx) {
    let p = c.p;
    let mesh = &p.mesh;
    for v in mesh.vertices() {
        if p.is_obstacle_vertex[v.index()] {
            continue;
        }
        let mut cand = Vec::new();
        let mut existing = false;
        for e in mesh.incident_edges(v) {
            match (p.roles[e.index()], c.vars.edge[e.index()]) {
                (EdgeRole::Existing, _) => existing = true,
                (_, Some(x)) => cand.push((e, x)),
                _ => {}
            }
        }
        if existing {
            c.vars.vertex[v.index()] = Value::Const(1.0);
            continue;
        }
        if cand.is_empty() {
            continue;
        }
        let y = c.em.model.add_binary(format!("V_{}", vname(v)), 0.0);
        if p.forced_vertices.contains(&v) {
            c.em.model.var_mut(y).lb = 1.0;
        }
        let mut ex = Expr::new();
        for &(_, x) in &cand {
            ex.add(x, 1.0);
        }
        if c.recipe.coverage == CoverageForm::Aggregated {
            let n = cand.len() as f64;
            ex.add(y, -n);
            c.em.row(format!("cov5_{}", vname(v)), 1.0 - n, &ex, 0.0);
        } else {
            ex.add(y, -1.0);
            c.em.ge(format!("cov5a_{}", vname(v)), &ex, 0.0);
            for &(e, x) in &cand {
                c.em.model.add_le(format!("cov5b_{}_e{}", vname(v), e.0), [(x, 1.0), (y, -1.0)], 0.0);
            }
        }
        c.vars.vertex[v.index()] = Value::Var(y);
    }
}

/// (6) `Σ_{u ∈ cover(v)} V_u ≥ 1` for every non-obstacle vertex not already covered by a
/// constant; with the `strong` coverage form also the edge-coverage rows of §8: with `T(v)` the
/// candidate edges with an end in `cover(v)`, `Σ_{x∈T(v)} E_x ≥ 2` when `cover(v)` holds no
/// sink and dead-ends are forbidden (an active non-sink vertex then has two active edges, both
/// in `T(v)`), else `≥ 1`.
fn coverage(c: &mut Ctx) {
    let p = c.p;
    let mesh = &p.mesh;
    let strong = c.recipe.coverage == CoverageForm::Strong;
    let girth = girth(p);
    let mut in_ball = vec![false; mesh.num_vertices()];
    for v in mesh.vertices() {
        if p.is_obstacle_vertex[v.index()] {
            continue;
        }
        let cover = cover_set(p, v);
        if cover.iter().any(|u| c.vars.vertex[u.index()] == Value::Const(1.0)) {
            continue;
        }
        let mut ex = Expr::new();
        for &u in &cover {
            ex.add_value(c.vars.vertex[u.index()], 1.0);
        }
        c.em.ge(format!("cov6_{}", vname(v)), &ex, 1.0);
        if !strong {
            continue;
        }
        for &u in &cover {
            in_ball[u.index()] = true;
        }
        let mut edges = Expr::new();
        for e in mesh.edges() {
            let (a, b) = mesh.edge_vertices(e);
            if (in_ball[a.index()] || in_ball[b.index()]) && c.is_candidate(e) {
                edges.add_value(c.edge_value(e), 1.0);
            }
        }
        for &u in &cover {
            in_ball[u.index()] = false;
        }
        let sink_in_ball = cover.iter().any(|u| p.is_sink[u.index()]);
        let need = if !sink_in_ball && p.dead_ends == Allow::Forbid { 2.0 } else { 1.0 };
        c.em.ge(format!("covedge_{}", vname(v)), &edges, need);
        if !sink_in_ball {
            ball_cut(c, &format!("covball_{}", vname(v)), &cover, girth);
        }
    }
}

/// The ball cut of docs/formulation.md §8 (this project's strengthening): some vertex of `cover(v)` is
/// active and no sink is in the ball, so the network crosses the ball's boundary `δ(C)`, `C =
/// cover(v)`: `Σ_{x∈δ(C)} E_x ≥ 1`. With dead-ends forbidden, a single crossing leaves every
/// active vertex inside with degree ≥ 2, so the active part inside holds a cycle of at least
/// `g` edges (`g` the mesh's girth, 4 on quad meshes): `Σ_{x∈δ(C)} E_x + (1/g)·Σ_{x∈E(C)} E_x ≥ 2`
/// (two crossings, or one and a cycle inside). Unlike a cutset `Σ_{δ(C)} E_x ≥ V_u` it does not
/// weaken when the ball's activity is spread thinly over many vertices.
fn ball_cut(c: &mut Ctx, name: &str, cover: &[crate::mesh::VertexId], girth: f64) {
    let p = c.p;
    let mesh = &p.mesh;
    let mut inside = vec![false; mesh.num_vertices()];
    for &u in cover {
        inside[u.index()] = true;
    }
    let mut edges: Vec<crate::mesh::EdgeId> =
        cover.iter().flat_map(|&u| mesh.incident_edges(u)).filter(|&e| c.is_candidate(e)).collect();
    edges.sort();
    edges.dedup();
    let mut ex = Expr::new();
    let forbid = p.dead_ends == Allow::Forbid;
    for e in edges {
        let (a, b) = mesh.edge_vertices(e);
        let crossing = inside[a.index()] != inside[b.index()];
        let w = if crossing {
            1.0
        } else if forbid {
            1.0 / girth
        } else {
            0.0
        };
        if w > 0.0 {
            ex.add_value(c.edge_value(e), w);
        }
    }
    c.em.ge(name.to_string(), &ex, if forbid { 2.0 } else { 1.0 });
}

/// The shortest cycle a design can hold, as far as the ball cuts need.
/// - 4 when every face is a quadrilateral: a planar graph whose faces are all even is
///   bipartite, and a simple graph has no 2-cycles;
/// - 8 when moreover every vertex off the mesh boundary has valence 4 (the mesh is a piece of
///   the square grid: grids and clipped grids) and too-close pairs are forbidden: a cycle then
///   bounds a polyomino, and a polyomino no cell of which has two opposite sides on its boundary
///   has at least four cells at its corners — the 2×2 block, perimeter 8;
/// - else 3.
pub(crate) fn girth(p: &crate::spec::Problem) -> f64 {
    let mesh = &p.mesh;
    if !mesh.faces().all(|f| mesh.face_size(f) == 4) {
        return 3.0;
    }
    let grid = mesh.vertices().all(|v| mesh.is_boundary_vertex(v) || mesh.valence(v) == 4);
    if grid && p.w_too_close == crate::spec::Weight::Forbid {
        8.0
    } else {
        4.0
    }
}
