//! Room tiling on the network IP: floor plans (paper §5.2) and game levels (§5.3), as
//! `shared/FORMULATION.md` §4–§5 state them. One binary `R` per enumerated placement.

use super::cutset::GroupOrigin;
use super::Ctx;
use crate::formulations::expr::{Expr, Value};
use crate::mesh::{EdgeId, VertexId};
use crate::milp::VarId;
use crate::rules::placements::{enumerate_placements, Placement, PlacementReport};
use crate::spec::{Allow, CoverageForm, LevelType, Problem, RoomMode, Rooms};
use std::time::Duration;

/// Time cap on placement enumeration.
const PLACEMENT_TIME_CAP: Duration = Duration::from_secs(20);

/// Whether a traversed block has at least two active inner edges in every valid design: dead-ends
/// are forbidden, every inner edge has an end off the block's boundary (true of rectangles at
/// least two faces wide), and no sink lies off the boundary. Then an active inner edge has an
/// end `u` strictly inside the block; `u` is not a sink, so it has a second active edge, and every
/// edge at `u` is an inner edge of the block.
fn traversal_needs_two(p: &Problem, pl: &Placement) -> bool {
    if p.dead_ends != Allow::Forbid {
        return false;
    }
    let mesh = &p.mesh;
    let border = pl.border_vertices(mesh);
    let inside = |v: VertexId| border.binary_search(&v).is_err();
    pl.inner_edges.iter().all(|&e| {
        let (a, b) = mesh.edge_vertices(e);
        (inside(a) || inside(b)) && !(inside(a) && p.is_sink[a.index()]) && !(inside(b) && p.is_sink[b.index()])
    })
}

/// Emits `R` per placement and (16) exact cover, then (17)–(18) for floor plans or (19)–(20)
/// for game levels, then the room-type counts. Returns the enumerated placements (their `R` go
/// to the variable map).
pub fn rooms(c: &mut Ctx, rooms: &Rooms) -> PlacementReport {
    let p = c.p;
    let mesh = &p.mesh;
    // The rows that replace coverage (5)–(6) on tilings are strengthened with it.
    let strong = c.recipe.coverage == CoverageForm::Strong;
    let report =
        enumerate_placements(mesh, &rooms.templates, &p.is_obstacle_face, rooms.max_placements, PLACEMENT_TIME_CAP);
    let mut vars = Vec::with_capacity(report.placements.len());
    let mut covering: Vec<Vec<VarId>> = vec![Vec::new(); mesh.num_faces()];
    for (k, pl) in report.placements.iter().enumerate() {
        let r = c.em.model.add_binary(format!("R_t{}_{k}", pl.template), 0.0);
        vars.push(r);
        for f in &pl.faces {
            covering[f.index()].push(r);
        }

        match rooms.mode {
            RoomMode::Floorplan => {
                // (17) |inner|·R − Σ (1 − E_i) ≤ 0: no corridor inside a room.
                if !pl.inner_edges.is_empty() {
                    let n = pl.inner_edges.len() as f64;
                    let mut ex = Expr::new();
                    ex.add(r, n).add_const(-n);
                    for e in &pl.inner_edges {
                        ex.add_value(c.edge_value(*e), 1.0);
                    }
                    c.em.le(format!("room17_{k}"), &ex, 0.0);
                }
                // (18) R − Σ_bnd E_j ≤ 0: a room touches a corridor.
                let mut ex = Expr::new();
                ex.add(r, 1.0);
                for e in &pl.boundary_edges {
                    ex.add_value(c.edge_value(*e), -1.0);
                }
                c.em.le(format!("room18_{k}"), &ex, 0.0);
            }
            RoomMode::Game => {
                // (19) R − Σ_inner E_i ≤ 0: a block is traversed; strengthened to 2R where
                // two inner edges are implied (see `traversal_needs_two`).
                let need = if strong && traversal_needs_two(p, pl) { 2.0 } else { 1.0 };
                let mut ex = Expr::new();
                ex.add(r, need);
                for e in &pl.inner_edges {
                    ex.add_value(c.edge_value(*e), -1.0);
                }
                c.em.le(format!("room19_{k}"), &ex, 0.0);
                // (20) |bnd|·R − Σ_bnd (1 − E_j) ≤ 0: nothing runs along a block's boundary.
                let n = pl.boundary_edges.len() as f64;
                let mut ex = Expr::new();
                ex.add(r, n).add_const(-n);
                for e in &pl.boundary_edges {
                    ex.add_value(c.edge_value(*e), 1.0);
                }
                c.em.le(format!("room20_{k}"), &ex, 0.0);
            }
        }
    }
    // (16) exact cover of every non-obstacle face.
    for f in mesh.faces() {
        if p.is_obstacle_face[f.index()] {
            continue;
        }
        let mut ex = Expr::new();
        for &r in &covering[f.index()] {
            ex.add(r, 1.0);
        }
        c.em.eq(format!("room16_f{}", f.0), &ex, 1.0);
    }
    // Room-type counts.
    for (t, &(lo, hi)) in rooms.counts.iter().enumerate() {
        if lo.is_none() && hi.is_none() {
            continue;
        }
        let mut ex = Expr::new();
        for (pl, &r) in report.placements.iter().zip(&vars) {
            if pl.template == t {
                ex.add(r, 1.0);
            }
        }
        let lo = lo.map_or(f64::NEG_INFINITY, f64::from);
        let hi = hi.map_or(f64::INFINITY, f64::from);
        c.em.row(format!("roomcount_t{t}"), lo, &ex, hi);
    }
    if rooms.mode == RoomMode::Game && matches!(rooms.level, Some(LevelType::Linear | LevelType::Circular)) {
        level_shape(c, rooms, &report, &vars, strong);
    }
    c.vars.rooms = vars;
    report
}

/// Per face, the candidate edges one of which is active in every valid tiling with the face's
/// room or block: the union over the placements covering the face of their boundary edges for
/// floor plans (18: the room touches a corridor) or of their inner edges for game levels (19: the
/// block is traversed). Ascending; empty for a face no placement covers, and for a face one of
/// whose edges is active as a constant (nothing to ask).
fn serving_edges(c: &Ctx, mode: RoomMode, report: &PlacementReport) -> Vec<Vec<EdgeId>> {
    let mesh = &c.p.mesh;
    let mut serving: Vec<Vec<EdgeId>> = vec![Vec::new(); mesh.num_faces()];
    for pl in &report.placements {
        let edges = match mode {
            RoomMode::Floorplan => &pl.boundary_edges,
            RoomMode::Game => &pl.inner_edges,
        };
        for f in &pl.faces {
            serving[f.index()].extend(edges.iter().copied().filter(|&e| c.edge_value(e) != Value::Const(0.0)));
        }
    }
    for edges in &mut serving {
        edges.sort();
        edges.dedup();
        if edges.iter().any(|&e| c.edge_value(e) == Value::Const(1.0)) {
            edges.clear();
        }
    }
    serving
}

/// The served faces (this project's strengthening, opt-in): exactly one placement covers a
/// face (16) and it needs an active edge among its own (18, 19), so `Σ_{x∈U(f)} E_x ≥ 1` over
/// the [`serving_edges`] `U(f)` of each face `f` — `≥ 2` for a game level's face all of whose
/// blocks need two (see `traversal_needs_two`). Summing (18) over the placements at `f` counts
/// an edge once per placement that has it; this row counts it once, so fractional rooms can no
/// longer share one corridor edge. Returns the ends of each `U(f)`, the cover groups of the
/// cutset separator (one of them is active in every valid design).
pub fn served_faces(c: &mut Ctx, mode: RoomMode, report: &PlacementReport) -> Vec<(GroupOrigin, Vec<VertexId>)> {
    let p = c.p;
    let serving = serving_edges(c, mode, report);
    let mut two = vec![mode == RoomMode::Game; p.mesh.num_faces()];
    if mode == RoomMode::Game {
        for pl in report.placements.iter().filter(|pl| !traversal_needs_two(p, pl)) {
            for f in &pl.faces {
                two[f.index()] = false;
            }
        }
    }
    for f in p.mesh.faces() {
        let edges = &serving[f.index()];
        if edges.is_empty() {
            continue;
        }
        let mut ex = Expr::new();
        for &e in edges {
            ex.add_value(c.edge_value(e), 1.0);
        }
        c.em.ge(format!("roomserved_f{}", f.0), &ex, if two[f.index()] { 2.0 } else { 1.0 });
    }
    let mesh = &p.mesh;
    mesh.faces()
        .filter(|f| !serving[f.index()].is_empty())
        .map(|f| {
            let mut ends: Vec<VertexId> =
                serving[f.index()].iter().flat_map(|&e| <[VertexId; 2]>::from(mesh.edge_vertices(e))).collect();
            ends.sort();
            ends.dedup();
            (GroupOrigin::Face(f.0), ends)
        })
        .collect()
}

/// What a linear or circular level means, as rows (docs/spec.md "Game level types"). With
/// branches and dead-ends forbidden (the spec resolution insists), the network is paths between
/// sinks and cycles through sinks; then:
/// - **linear**: each of the two sinks has degree exactly 1, so the network is one path from one
///   to the other; **circular**: the sink has degree exactly 2, so the network is one cycle
///   through it;
/// - **every block is entered once**: the network crosses the boundary of a chosen block at most
///   twice (counting a sink end as a crossing), `Σ_{v∈∂R} crossings(v) ≤ 2 + K·(1 − R)`. For a
///   boundary vertex with one inner edge of the block the crossing is that edge's `E` (the
///   vertex has degree 2, and its other active edge lies outside the block by (20)); where a
///   vertex has several inner edges (a reflex corner) a continuous `X ≥ inner + outer − 1` (and
///   `X ≥ inner − outer` at a sink) counts it.
///
/// A path (cycle) that enters every traversed block once gives a path (cycle) block graph. A
/// circular level also needs at least three blocks (two blocks joined twice form a path), unless
/// one placement covers the whole footprint.
///
/// With `strong`, a block that holds no sink (inside or on its boundary) is also crossed at least
/// twice, `Σ crossings ≥ 2R` (`levelenter_…`): its active inner edges are paths (no branches)
/// with no end inside (no dead-ends) and no cycle (a cycle inside would hold no sink), so each
/// path has both ends on the boundary.
fn level_shape(c: &mut Ctx, rooms: &Rooms, report: &PlacementReport, vars: &[VarId], strong: bool) {
    let p = c.p;
    let mesh = &p.mesh;
    let circular = rooms.level == Some(LevelType::Circular);
    for v in mesh.vertices().filter(|v| p.is_sink[v.index()]) {
        let d = c.degree(v);
        c.em.eq(format!("levelsink_v{}", v.0), &d, if circular { 2.0 } else { 1.0 });
    }
    for (k, (pl, &r)) in report.placements.iter().zip(vars).enumerate() {
        let inner: std::collections::BTreeSet<EdgeId> = pl.inner_edges.iter().copied().collect();
        let own: std::collections::BTreeSet<EdgeId> =
            pl.inner_edges.iter().chain(&pl.boundary_edges).copied().collect();
        let border = pl.border_vertices(mesh);
        let mut ex = Expr::new();
        let mut big = 0.0;
        for &v in &border {
            let ins: Vec<EdgeId> = mesh.incident_edges(v).filter(|e| inner.contains(e)).collect();
            match ins.len() {
                0 => {}
                1 => {
                    ex.add_value(c.edge_value(ins[0]), 1.0);
                    big += 1.0;
                }
                _ => {
                    let outs: Vec<EdgeId> = mesh.incident_edges(v).filter(|e| !own.contains(e)).collect();
                    let x = c.em.model.add_continuous(format!("X_{k}_v{}", v.0), 0.0, 2.0, 0.0);
                    let mut cross = Expr::new();
                    cross.add(x, 1.0);
                    for &e in &ins {
                        cross.add_value(c.edge_value(e), -1.0);
                    }
                    for &e in &outs {
                        cross.add_value(c.edge_value(e), -1.0);
                    }
                    c.em.ge(format!("levelx_{k}_v{}", v.0), &cross, -1.0);
                    if p.is_sink[v.index()] {
                        let mut end = Expr::new();
                        end.add(x, 1.0);
                        for &e in &ins {
                            end.add_value(c.edge_value(e), -1.0);
                        }
                        for &e in &outs {
                            end.add_value(c.edge_value(e), 1.0);
                        }
                        c.em.ge(format!("levelend_{k}_v{}", v.0), &end, 0.0);
                    }
                    ex.add(x, 1.0);
                    big += 2.0;
                }
            }
        }
        let holds_sink = border.iter().any(|v| p.is_sink[v.index()])
            || pl.inner_edges.iter().any(|&e| {
                let (a, b) = mesh.edge_vertices(e);
                p.is_sink[a.index()] || p.is_sink[b.index()]
            });
        if strong && !holds_sink && !ex.is_constant() {
            let mut enter = ex.clone();
            enter.add(r, -2.0);
            c.em.ge(format!("levelenter_{k}"), &enter, 0.0);
        }
        if big > 2.0 {
            ex.add(r, big - 2.0);
            c.em.le(format!("levelvisit_{k}"), &ex, big);
        }
    }
    let faces = mesh.faces().filter(|f| !p.is_obstacle_face[f.index()]).count();
    if circular && !report.placements.iter().any(|pl| pl.faces.len() == faces) {
        let mut ex = Expr::new();
        for &r in vars {
            ex.add(r, 1.0);
        }
        c.em.ge("levelblocks".to_string(), &ex, 3.0);
    }
}
