//! The network IP of the paper's §4, as `shared/FORMULATION.md` §2–§3 state it. Each
//! constraint family is one function citing its equations.
//!
//! Names in the exported `.lp`: `E_e12` (edge active), `H_v3_v7` (half-edge 3→7 active),
//! `D_v3_v7` (distance label), `L_v3_v7_v8` (successor), `V_v5` (vertex active), `nu_v3_v7`
//! (paper dead-end indicator), `P_p2_k` (path), `Z0_e4_1` / `Z1_f4_0` (local configurations),
//! `T_v3_v7` (T-junction). Rows: `noisl1_…`–`noisl4_…`, `cov5a_v5`, `cov6_v5`, `dead_v5`,
//! `branch_v5`, `zz_e4_1`, `close_f4_0`, `tj_v3_v7`, `p2p8_…`, `p2p9_…`, `thru…`.

use super::expr::{Emitter, Expr, FamilyStats, Value};
use super::paths::{enumerate_path_sets, PathSets};
use crate::mesh::{EdgeId, FaceId, HalfEdgeId, Mesh, VertexId};
use crate::milp::{Model, Sense, VarId};
use crate::spec::{Allow, CoverageModel, EdgeRole, FormulationVariant, Problem, Weight};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

/// A local configuration of (13): a set of edges that must not all be active.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LocalConfig {
    /// `0` zig-zag, `1` too close.
    pub k: u8,
    /// The edges.
    pub edges: Vec<EdgeId>,
    /// The indicator, when penalised.
    pub indicator: Option<VarId>,
}

/// A T-junction configuration of (14): `e0` inactive while the other three edges at `vertex`
/// are active.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TConfig {
    /// The interior valence-4 vertex.
    pub vertex: VertexId,
    /// The missing edge (the edge of the half-edge into `vertex`).
    pub e0: EdgeId,
    /// The other three edges.
    pub others: [EdgeId; 3],
    /// The indicator, when penalised.
    pub indicator: Option<VarId>,
}

/// The emitted MILP together with the map from design elements to its variables.
pub struct NetworkModel {
    /// The MILP.
    pub model: Model,
    /// `E_x` for candidate edges.
    pub edge_var: Vec<Option<VarId>>,
    /// `E(i→j)` per half-edge of a candidate edge.
    pub half_edge_var: Vec<Option<VarId>>,
    /// `D(i→j)` per half-edge of a candidate edge.
    pub label_var: Vec<Option<VarId>>,
    /// Activity of each vertex: `V_y`, or a constant.
    pub vertex_value: Vec<Value>,
    /// The big-M used in (2) (Δall for `paper`).
    pub big_m: f64,
    /// Local configurations of (13) that were emitted.
    pub local_configs: Vec<LocalConfig>,
    /// T-junction configurations of (14) that were emitted.
    pub t_configs: Vec<TConfig>,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room placements and their variables, if room tiling is on.
    pub rooms: Option<super::rooms::RoomModel>,
    /// Variables and rows per family.
    pub families: IndexMap<String, FamilyStats>,
}

impl NetworkModel {
    /// The activity of edge `e` (a variable or a constant).
    pub fn edge_value(&self, e: EdgeId, roles: &[EdgeRole]) -> Value {
        match (roles[e.index()], self.edge_var[e.index()]) {
            (_, Some(v)) => Value::Var(v),
            (EdgeRole::Existing, None) => Value::Const(1.0),
            _ => Value::Const(0.0),
        }
    }
}

fn vname(v: VertexId) -> String {
    format!("v{}", v.0)
}

fn he_name(mesh: &Mesh, h: HalfEdgeId) -> String {
    format!("v{}_v{}", mesh.he_tail(h).0, mesh.he_head(h).0)
}

/// Builds the MILP for a resolved problem.
pub fn build(p: &Problem) -> NetworkModel {
    let mesh = &p.mesh;
    let mut em = Emitter::new(&p.spec.name);
    em.model.sense = Sense::Minimize;
    let ne = mesh.num_edges();
    let mut nm = NetworkModel {
        model: Model::new(""),
        edge_var: vec![None; ne],
        half_edge_var: vec![None; 2 * ne],
        label_var: vec![None; 2 * ne],
        vertex_value: vec![Value::Const(0.0); mesh.num_vertices()],
        big_m: 0.0,
        local_configs: Vec::new(),
        t_configs: Vec::new(),
        path_sets: None,
        rooms: None,
        families: IndexMap::new(),
    };
    nm.big_m = big_m(p);
    em.family("edges (4)", |em| edge_variables(p, em, &mut nm));
    em.family("no-island (1)-(3)", |em| no_island(p, em, &nm));
    em.family(if p.rooms.is_some() { "vertices (5)" } else { "coverage (5)-(6)" }, |em| coverage(p, em, &mut nm));
    if p.dead_ends == Allow::Forbid {
        em.family("dead-ends (10)-(11)", |em| dead_ends(p, em, &nm));
    }
    if p.branches == Allow::Forbid {
        em.family("branches (12)", |em| branches(p, em, &nm));
    }
    if p.w_zigzag != Weight::Off {
        em.family("zig-zag (13, k=0)", |em| zigzags(p, em, &mut nm));
    }
    if p.w_too_close != Weight::Off {
        em.family("too-close (13, k=1)", |em| too_close(p, em, &mut nm));
    }
    if p.w_t_junction != Weight::Off {
        em.family("T-junctions (14)", |em| t_junctions(p, em, &mut nm));
    }
    if p.p2p.is_some() {
        em.family("point-to-point (8)-(9)", |em| point_to_point(p, em, &mut nm));
    }
    if let Some(rooms) = &p.rooms {
        let label = match rooms.mode {
            crate::spec::RoomMode::Floorplan => "rooms (16)-(18)",
            crate::spec::RoomMode::Game => "blocks (16), (19)-(20)",
        };
        nm.rooms = Some(em.family(label, |em| super::rooms::rooms(p, rooms, em, &nm)));
    }
    if !p.forced_vertices.is_empty() || !p.through_routes.is_empty() || !p.forced_edges.is_empty() {
        em.family("user specifications", |em| user_specs(p, em, &nm));
    }
    nm.families = std::mem::take(&mut em.families);
    nm.model = em.model;
    nm
}

/// The constant of (2): `Δall` (sum of the lengths of all half-edges of the candidate network)
/// for `paper`; for `tight`, the sum of the `|V_c| − 1` longest candidate edges (a label is the
/// length of a simple path, which has at most `|V_c| − 1` edges).
pub fn big_m(p: &Problem) -> f64 {
    let mesh = &p.mesh;
    let mut lens: Vec<f64> = mesh.edges().filter(|e| p.roles[e.index()] == EdgeRole::Candidate).map(|e| mesh.edge_length(e)).collect();
    match p.variant {
        FormulationVariant::Paper => 2.0 * lens.iter().sum::<f64>(),
        FormulationVariant::Tight => {
            let mut touched = vec![false; mesh.num_vertices()];
            for e in mesh.edges().filter(|e| p.roles[e.index()] == EdgeRole::Candidate) {
                let (a, b) = mesh.edge_vertices(e);
                touched[a.index()] = true;
                touched[b.index()] = true;
            }
            let nv = touched.iter().filter(|&&t| t).count();
            lens.sort_by(|a, b| b.total_cmp(a));
            lens.iter().take(nv.saturating_sub(1)).sum()
        }
    }
}

/// `E_x`, `E(i→j)`, `D(i→j)` for candidate edges, the length term of (15), the distance term of
/// (15), and (4): `−1 ≤ E(i→j) + E(j→i) − 2·E_x ≤ 0`.
fn edge_variables(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    let mesh = &p.mesh;
    let forced: std::collections::HashSet<EdgeId> =
        p.forced_edges.iter().copied().chain(route_edges(p)).collect();
    for e in mesh.edges() {
        if p.roles[e.index()] != EdgeRole::Candidate {
            continue;
        }
        let len = mesh.edge_length(e);
        let x = em.model.add_binary(format!("E_e{}", e.0), p.w_length * len);
        if forced.contains(&e) {
            em.model.var_mut(x).lb = 1.0;
        }
        nm.edge_var[e.index()] = Some(x);
        let [h0, h1] = mesh.edge_half_edges(e);
        for h in [h0, h1] {
            let name = he_name(mesh, h);
            nm.half_edge_var[h.index()] = Some(em.model.add_binary(format!("H_{name}"), 0.0));
            nm.label_var[h.index()] = Some(em.model.add_continuous(format!("D_{name}"), 0.0, nm.big_m, p.w_distance));
        }
        let mut ex = Expr::new();
        ex.add(nm.half_edge_var[h0.index()].unwrap(), 1.0).add(nm.half_edge_var[h1.index()].unwrap(), 1.0).add(x, -2.0);
        em.row(format!("noisl4_e{}", e.0), -1.0, &ex, 0.0);
    }
}

fn route_edges(p: &Problem) -> Vec<EdgeId> {
    p.through_routes
        .iter()
        .flat_map(|r| r.windows(2).map(|w| p.mesh.he_edge(p.mesh.half_edge_between(w[0], w[1]).expect("route follows mesh edges"))))
        .collect()
}

/// (1)–(3): for every candidate half-edge `i→j` whose head is not a sink, and every candidate
/// successor `j→k`, `k ≠ i`:
/// (1) `L ≤ E(j→k)`; (2) `D(j→k) − D(i→j) + M·L ≤ M − Δ(i→j)`; (3) `E(i→j) − Σ_k L ≤ 0`.
fn no_island(p: &Problem, em: &mut Emitter, nm: &NetworkModel) {
    let mesh = &p.mesh;
    let m = nm.big_m;
    for e in mesh.edges() {
        if nm.edge_var[e.index()].is_none() {
            continue;
        }
        for h in mesh.edge_half_edges(e) {
            let (i, j) = (mesh.he_tail(h), mesh.he_head(h));
            if p.is_sink[j.index()] {
                continue;
            }
            let eij = nm.half_edge_var[h.index()].unwrap();
            let dij = nm.label_var[h.index()].unwrap();
            let delta = mesh.edge_length(e);
            let mut three = Expr::new();
            three.add(eij, 1.0);
            for &g in mesh.outgoing(j) {
                let k = mesh.he_head(g);
                let Some(ejk) = nm.half_edge_var[g.index()] else { continue };
                if k == i {
                    continue;
                }
                let djk = nm.label_var[g.index()].unwrap();
                let (i, j, k) = (i.0, j.0, k.0);
                let l = em.model.add_binary(format!("L_v{i}_v{j}_v{k}"), 0.0);
                em.model.add_le(format!("noisl1_v{i}_v{j}_v{k}"), [(l, 1.0), (ejk, -1.0)], 0.0);
                em.model.add_le(format!("noisl2_v{i}_v{j}_v{k}"), [(djk, 1.0), (dij, -1.0), (l, m)], m - delta);
                three.add(l, -1.0);
            }
            em.le(format!("noisl3_{}", he_name(mesh, h)), &three, 0.0);
        }
    }
}

/// (5) `1 − |E_y| ≤ Σ_{x∈E_y} E_x − |E_y|·V_y ≤ 0` for vertices whose incident edges are all
/// candidates or excluded (a vertex with an existing edge is active as a constant), and
/// (6) `Σ_{u ∈ cover(v)} V_u ≥ 1` for every non-obstacle vertex.
fn coverage(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    let mesh = &p.mesh;
    for v in mesh.vertices() {
        if p.is_obstacle_vertex[v.index()] {
            continue;
        }
        let mut cand = Vec::new();
        let mut existing = false;
        for e in mesh.incident_edges(v) {
            match (p.roles[e.index()], nm.edge_var[e.index()]) {
                (EdgeRole::Existing, _) => existing = true,
                (_, Some(x)) => cand.push(x),
                _ => {}
            }
        }
        if existing {
            nm.vertex_value[v.index()] = Value::Const(1.0);
        } else if !cand.is_empty() {
            let y = em.model.add_binary(format!("V_{}", vname(v)), 0.0);
            if p.forced_vertices.contains(&v) {
                em.model.var_mut(y).lb = 1.0;
            }
            let n = cand.len() as f64;
            let mut ex = Expr::new();
            for &x in &cand {
                ex.add(x, 1.0);
            }
            ex.add(y, -n);
            em.row(format!("cov5_{}", vname(v)), 1.0 - n, &ex, 0.0);
            nm.vertex_value[v.index()] = Value::Var(y);
        }
    }
    if p.rooms.is_some() {
        return; // Room tiling replaces coverage (6) (FORMULATION §4).
    }
    for v in mesh.vertices() {
        if p.is_obstacle_vertex[v.index()] {
            continue;
        }
        let cover = cover_set(p, v);
        if cover.iter().any(|u| nm.vertex_value[u.index()] == Value::Const(1.0)) {
            continue;
        }
        let mut ex = Expr::new();
        for u in cover {
            ex.add_value(nm.vertex_value[u.index()], 1.0);
        }
        em.ge(format!("cov6_{}", vname(v)), &ex, 1.0);
    }
}

/// The vertices within the coverage range of `v` (hops on the whole mesh graph, or Euclidean),
/// `v` included, in id order.
pub fn cover_set(p: &Problem, v: VertexId) -> Vec<VertexId> {
    let mesh = &p.mesh;
    let mut out: Vec<VertexId> = match p.coverage_model {
        CoverageModel::Hops => mesh.hop_distances(v, p.coverage_range.floor() as usize).into_iter().map(|(u, _)| u).collect(),
        CoverageModel::Euclidean => {
            let pv = mesh.position(v);
            let r2 = p.coverage_range * p.coverage_range;
            mesh.vertices()
                .filter(|&u| {
                    let pu = mesh.position(u);
                    (pu[0] - pv[0]).powi(2) + (pu[1] - pv[1]).powi(2) <= r2 * (1.0 + 1e-12)
                })
                .collect()
        }
    };
    out.sort();
    out
}

/// Active-degree expression at `v`: `Σ_{x∈E_y} E_x` plus existing incident edges.
fn degree(p: &Problem, nm: &NetworkModel, v: VertexId) -> Expr {
    let mut ex = Expr::new();
    for e in p.mesh.incident_edges(v) {
        ex.add_value(nm.edge_value(e, &p.roles), 1.0);
    }
    ex
}

/// Dead-ends forbidden at non-sinks. `tight`: `Σ E_x ≥ 2·V_y`. `paper`: the ν form (10)–(11),
/// corrected to use `E_x` for both half-edges of `x`: for every candidate half-edge `i→j` with a
/// non-sink head, `ν ≤ Σ_{x∈E_j∖{ij}} E_x ≤ |E_j∖{ij}|·ν` and `E_{ij} ≤ ν`.
fn dead_ends(p: &Problem, em: &mut Emitter, nm: &NetworkModel) {
    let mesh = &p.mesh;
    match p.variant {
        FormulationVariant::Tight => {
            for v in mesh.vertices() {
                if p.is_sink[v.index()] {
                    continue;
                }
                if let Value::Var(y) = nm.vertex_value[v.index()] {
                    let mut ex = degree(p, nm, v);
                    ex.add(y, -2.0);
                    em.ge(format!("dead_{}", vname(v)), &ex, 0.0);
                }
            }
        }
        FormulationVariant::Paper => {
            for e in mesh.edges() {
                let Some(x) = nm.edge_var[e.index()] else { continue };
                for h in mesh.edge_half_edges(e) {
                    let j = mesh.he_head(h);
                    if p.is_sink[j.index()] {
                        continue;
                    }
                    let name = he_name(mesh, h);
                    let mut others = Expr::new();
                    for f in mesh.incident_edges(j).filter(|&f| f != e) {
                        others.add_value(nm.edge_value(f, &p.roles), 1.0);
                    }
                    let n = others.terms.len() as f64;
                    let nu = em.model.add_binary(format!("nu_{name}"), 0.0);
                    let mut a = others.clone();
                    a.add(nu, -1.0);
                    em.ge(format!("dead10a_{name}"), &a, 0.0);
                    let mut b = others;
                    b.add(nu, -n.max(1.0));
                    em.le(format!("dead10b_{name}"), &b, 0.0);
                    em.model.add_le(format!("dead11_{name}"), [(x, 1.0), (nu, -1.0)], 0.0);
                }
            }
        }
    }
}

/// (12): `Σ_{x∈E_y} E_x ≤ 2` at every vertex with more than two usable edges.
fn branches(p: &Problem, em: &mut Emitter, nm: &NetworkModel) {
    for v in p.mesh.vertices() {
        let ex = degree(p, nm, v);
        if ex.terms.len() as f64 + ex.constant > 2.0 {
            em.le(format!("branch_{}", vname(v)), &ex, 2.0);
        }
    }
}

/// Whether the design decides a configuration: at least one of its edges is a candidate. A
/// configuration made only of existing roads (e.g. the staircase boundary of a clipped
/// sub-region, or earlier street levels) is given, not designed: it is neither forbidden nor
/// penalised, and the validator exempts it too.
pub fn designed(p: &Problem, edges: &[EdgeId]) -> bool {
    edges.iter().any(|e| p.roles[e.index()] == EdgeRole::Candidate)
}

/// Emits one local configuration: forbidden → `Σ E ≤ |S| − 1`; penalised →
/// `0 ≤ Σ E − |S|·Z ≤ |S| − 1` with `λ·Z` in the objective.
fn local_config(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel, k: u8, tag: String, edges: Vec<EdgeId>, w: Weight) {
    if edges.iter().any(|e| p.roles[e.index()] == EdgeRole::Excluded) || !designed(p, &edges) {
        return;
    }
    let n = edges.len() as f64;
    let mut ex = Expr::new();
    for &e in &edges {
        ex.add_value(nm.edge_value(e, &p.roles), 1.0);
    }
    let indicator = match w {
        Weight::Forbid => {
            em.le(format!("{}_{tag}", if k == 0 { "zz" } else { "close" }), &ex, n - 1.0);
            None
        }
        Weight::Penalty(lambda) => {
            let z = em.model.add_binary(format!("Z{k}_{tag}"), lambda);
            ex.add(z, -n);
            em.row(format!("{}_{tag}", if k == 0 { "zz" } else { "close" }), 0.0, &ex, n - 1.0);
            Some(z)
        }
        Weight::Off => return,
    };
    nm.local_configs.push(LocalConfig { k, edges, indicator });
}

/// The zig-zag configurations (13, k = 0) of the mesh: for every interior edge `b` with faces
/// `f1`, `f2`, the staircases `a, b, c` with `a` a side of `f1` at one end of `b` and `c` a side of
/// `f2` at the other end. Two per interior edge.
pub fn zigzag_configs(mesh: &Mesh) -> Vec<(String, Vec<EdgeId>)> {
    let mut out = Vec::new();
    for b in mesh.edges() {
        let [h1, h2] = mesh.edge_half_edges(b);
        let (Some(p1), Some(n1), Some(p2), Some(n2)) = (mesh.he_prev(h1), mesh.he_next(h1), mesh.he_prev(h2), mesh.he_next(h2)) else {
            continue;
        };
        out.push((format!("e{}_0", b.0), vec![mesh.he_edge(p1), b, mesh.he_edge(p2)]));
        out.push((format!("e{}_1", b.0), vec![mesh.he_edge(n1), b, mesh.he_edge(n2)]));
    }
    out
}

/// The too-close configurations (13, k = 1): both pairs of opposite edges of every quad face.
pub fn too_close_configs(mesh: &Mesh) -> Vec<(String, Vec<EdgeId>)> {
    let mut out = Vec::new();
    for f in mesh.faces() {
        let es = mesh.face_edges(f);
        if es.len() == 4 {
            out.push((format!("f{}_0", f.0), vec![es[0], es[2]]));
            out.push((format!("f{}_1", f.0), vec![es[1], es[3]]));
        }
    }
    out
}

fn zigzags(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    for (tag, edges) in zigzag_configs(&p.mesh) {
        local_config(p, em, nm, 0, tag, edges, p.w_zigzag);
    }
}

fn too_close(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    for (tag, edges) in too_close_configs(&p.mesh) {
        local_config(p, em, nm, 1, tag, edges, p.w_too_close);
    }
}

/// The T-junction configurations (14): for every half-edge into an interior valence-4 vertex,
/// its edge `E0` and the other three edges.
pub fn t_configs(mesh: &Mesh) -> Vec<(HalfEdgeId, VertexId, EdgeId, [EdgeId; 3])> {
    let mut out = Vec::new();
    for v in mesh.vertices() {
        if mesh.is_boundary_vertex(v) || mesh.valence(v) != 4 {
            continue;
        }
        let edges: Vec<EdgeId> = mesh.incident_edges(v).collect();
        for &g in mesh.outgoing(v) {
            let h = mesh.he_twin(g);
            let e0 = mesh.he_edge(h);
            let others: Vec<EdgeId> = edges.iter().copied().filter(|&e| e != e0).collect();
            out.push((h, v, e0, [others[0], others[1], others[2]]));
        }
    }
    out
}

/// (14): forbidden → `E1 + E2 + E3 + (1 − E0) ≤ 3`; penalised →
/// `0 ≤ E1 + E2 + E3 + (1 − E0) − 4·T ≤ 3` with `λT·T` in the objective.
fn t_junctions(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    let mesh = &p.mesh;
    for (h, v, e0, others) in t_configs(mesh) {
        if !designed(p, &[e0, others[0], others[1], others[2]]) {
            continue;
        }
        let mut ex = Expr::new();
        for &e in &others {
            ex.add_value(nm.edge_value(e, &p.roles), 1.0);
        }
        ex.add_const(1.0).add_value(nm.edge_value(e0, &p.roles), -1.0);
        let name = he_name(mesh, h);
        let indicator = match p.w_t_junction {
            Weight::Forbid => {
                em.le(format!("tj_{name}"), &ex, 3.0);
                None
            }
            Weight::Penalty(lambda) => {
                let t = em.model.add_binary(format!("T_{name}"), lambda);
                ex.add(t, -4.0);
                em.row(format!("tj_{name}"), 0.0, &ex, 3.0);
                Some(t)
            }
            Weight::Off => continue,
        };
        nm.t_configs.push(TConfig { vertex: v, e0, others, indicator });
    }
}

/// (8)–(9) over the enumerated path sets. `paper`: `−N + 1 ≤ N·P − Σ_n E_n ≤ 0`; `tight`:
/// `P ≤ E_n` for each candidate edge of the path. Then `Σ_paths P ≥ 1` per pair of parts.
fn point_to_point(p: &Problem, em: &mut Emitter, nm: &mut NetworkModel) {
    let mut sets = enumerate_path_sets(p);
    for (pi, pair) in sets.pairs.iter_mut().enumerate() {
        let mut nine = Expr::new();
        let mut always = false;
        for (k, path) in pair.paths.iter_mut().enumerate() {
            let cand: Vec<VarId> = path.edges.iter().filter_map(|e| nm.edge_var[e.index()]).collect();
            if cand.is_empty() {
                always = true; // every edge existing: the pair is connected already
                continue;
            }
            let pv = em.model.add_binary(format!("P_p{pi}_{k}"), 0.0);
            path.var = Some(pv);
            let n = cand.len() as f64;
            match p.variant {
                FormulationVariant::Paper => {
                    let mut ex = Expr::new();
                    ex.add(pv, n);
                    for &x in &cand {
                        ex.add(x, -1.0);
                    }
                    em.row(format!("p2p8_p{pi}_{k}"), 1.0 - n, &ex, 0.0);
                }
                FormulationVariant::Tight => {
                    for (t, &x) in cand.iter().enumerate() {
                        em.model.add_le(format!("p2p8_p{pi}_{k}_{t}"), [(pv, 1.0), (x, -1.0)], 0.0);
                    }
                }
            }
            nine.add(pv, 1.0);
        }
        if !always {
            em.ge(format!("p2p9_p{pi}"), &nine, 1.0);
        }
    }
    nm.path_sets = Some(sets);
}

/// Forced vertices (`V_y ≥ 1`, set on the variable's bound), forced edges (bound), and through
/// routes: route edges forced active (bound), inner vertices of active degree exactly 2.
fn user_specs(p: &Problem, em: &mut Emitter, nm: &NetworkModel) {
    for &v in &p.forced_vertices {
        if nm.vertex_value[v.index()] == Value::Const(0.0) {
            em.ge(format!("forced_{}", vname(v)), &Expr::new(), 1.0);
        }
    }
    for (r, route) in p.through_routes.iter().enumerate() {
        for &v in &route[1..route.len() - 1] {
            em.eq(format!("thru{r}_{}", vname(v)), &degree(p, nm, v), 2.0);
        }
    }
}

/// A face's id as a name fragment (used by renderers and reports).
pub fn face_tag(f: FaceId) -> String {
    format!("f{}", f.0)
}
