//! Room tiling on the network IP: floor plans (paper §5.2) and game levels (§5.3),
//! docs/formulation.md §4–§5. One binary `R` per enumerated placement.

use crate::design::Network;
use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::expr::Expr;
use crate::formulations::family::{Ctx, Family};
use crate::mesh::{EdgeId, VertexId};
use crate::milp::VarId;
use crate::rules::placements::{Placement, PlacementReport};
use crate::spec::{switch, Allow, CoverageForm, LevelType, Problem, RoomMode, Rooms as RoomsSpec};

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

/// `R` per placement and (16) exact cover, then (17)–(18) for floor plans or (19)–(20) for game
/// levels, then the room-type counts; linear and circular levels get their shape rows.
pub struct Rooms {
    mode: RoomMode,
    /// `R` per placement (parallel to the formulation's placements).
    vars: Vec<VarId>,
    /// The crossing counters of linear and circular levels.
    crossings: Vec<Crossing>,
}

/// A continuous crossing counter `X` at a block's boundary vertex with several inner edges (a
/// reflex corner): `X ≥ inner + outer − 1`, and at a sink `X ≥ inner − outer`.
struct Crossing {
    var: VarId,
    inner: Vec<EdgeId>,
    outer: Vec<EdgeId>,
    sink: bool,
}

impl Rooms {
    /// When the spec tiles rooms.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        let rooms = c.p.rooms.as_ref()?;
        c.placements?;
        Some(Box::new(Rooms { mode: rooms.mode, vars: Vec::new(), crossings: Vec::new() }))
    }
}

impl Family for Rooms {
    fn label(&self) -> String {
        match self.mode {
            RoomMode::Floorplan => "rooms (16)-(18)",
            RoomMode::Game => "blocks (16), (19)-(20)",
        }
        .to_string()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let rooms: &RoomsSpec = c.p.rooms.as_ref().expect("the entry checked");
        let p = c.p;
        let mesh = &p.mesh;
        // The rows that replace coverage (5)–(6) on tilings are strengthened with it.
        let strong = c.recipe.coverage == CoverageForm::Strong;
        let report = c.placements.expect("the entry checked");
        let mut vars = Vec::with_capacity(report.placements.len());
        let mut covering: Vec<Vec<VarId>> = vec![Vec::new(); mesh.num_faces()];
        // The per-room rows summed over the chosen rooms (`room_length`, §8.11).
        let mut length = Expr::new();
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
                    length.add(r, -1.0);
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
                    length.add(r, -need);
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
        if c.recipe.on(&switch::ROOM_LENGTH) {
            room_length(c, rooms.mode, length);
        }
        if c.recipe.on(&switch::ROOM_REACH) && rooms.mode == RoomMode::Floorplan {
            room_reach(c, report);
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
            self.crossings = level_shape(c, rooms, report, &vars, strong);
        }
        self.vars = vars;
    }

    /// The chosen rooms, and each crossing counter at the least value its rows allow.
    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        for &k in &e.net.rooms {
            let v = self.vars.get(k).ok_or(EncodeError::UnknownRoom(k))?;
            x[v.index()] = 1.0;
        }
        for cr in &self.crossings {
            let count = |edges: &[EdgeId]| edges.iter().filter(|&&f| e.on(f)).count() as f64;
            let (inner, outer) = (count(&cr.inner), count(&cr.outer));
            let mut least = (inner + outer - 1.0).max(0.0);
            if cr.sink {
                least = least.max(inner - outer);
            }
            x[cr.var.index()] = least.min(2.0);
        }
        Ok(())
    }

    fn decode(&self, _p: &Problem, x: &[f64], net: &mut Network) {
        net.rooms = self.vars.iter().enumerate().filter(|(_, v)| x[v.index()] > 0.5).map(|(k, _)| k).collect();
    }
}

/// The rooms' rows summed over the chosen rooms, one row for the whole tiling (`roomlen`; the
/// `room_length` switch, docs/formulation.md §8.11): `Σ_e m_e·E_e ≥ Σ_R need(R)·R`, where
/// `row` comes in holding `−Σ_R need(R)·R`.
///
/// - Game levels: chosen blocks share no inner edge (an inner edge has a block's faces on both
///   sides, and the blocks are face-disjoint), so the active edges number at least the chosen
///   blocks' (19) right-hand sides: `m_e = 1`.
/// - Floor plans: an active edge is a boundary edge of at most as many chosen rooms as it has
///   non-obstacle faces, so `m_e` is that count (1 or 2) and each chosen room needs one (18).
///
/// Each placement's own row is met by the edges any overlapping placement uses too; this one is
/// not: a relaxation that spreads the tiling over many overlapping placements needs as many
/// edges as a whole tiling of the fewest rooms.
fn room_length(c: &mut Ctx, mode: RoomMode, mut row: Expr) {
    let p = c.p;
    let mesh = &p.mesh;
    for e in mesh.edges() {
        let m = match mode {
            RoomMode::Game => 1.0,
            RoomMode::Floorplan => {
                mesh.edge_faces(e).iter().flatten().filter(|f| !p.is_obstacle_face[f.index()]).count() as f64
            }
        };
        if m > 0.0 {
            row.add_value(c.edge_value(e), m);
        }
    }
    c.em.ge("roomlen".to_string(), &row, 0.0);
}

/// On floor plans, every face's room, whichever it is, touches a corridor near the face
/// (`roomreach_f…`; the `room_reach` switch, docs/formulation.md §8.11): `Σ_{e∈N(f)} E_e ≥ 1`,
/// where `N(f)` is the union of the boundary edges of the placements covering `f`. The chosen
/// room covering `f` is one of them, and (18) needs one of its boundary edges. (Game levels have
/// the same row with inner edges; it left the root LP of the Table 1 levels where `roomlen` puts
/// it, and is not written.)
fn room_reach(c: &mut Ctx, report: &PlacementReport) {
    let p = c.p;
    let mut near: Vec<Vec<EdgeId>> = vec![Vec::new(); p.mesh.num_faces()];
    for pl in &report.placements {
        for f in &pl.faces {
            near[f.index()].extend_from_slice(&pl.boundary_edges);
        }
    }
    for f in p.mesh.faces() {
        let edges = &mut near[f.index()];
        edges.sort_unstable();
        edges.dedup();
        let mut ex = Expr::new();
        for &e in edges.iter() {
            ex.add_value(c.edge_value(e), 1.0);
        }
        // No placement covers `f` (an obstacle face), or every edge near it is fixed: the
        // rooms' own rows decide.
        if !ex.is_constant() {
            c.em.ge(format!("roomreach_f{}", f.0), &ex, 1.0);
        }
    }
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
fn level_shape(
    c: &mut Ctx,
    rooms: &RoomsSpec,
    report: &PlacementReport,
    vars: &[VarId],
    strong: bool,
) -> Vec<Crossing> {
    let mut crossings = Vec::new();
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
                    crossings.push(Crossing {
                        var: x,
                        inner: ins.clone(),
                        outer: outs.clone(),
                        sink: p.is_sink[v.index()],
                    });
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
    crossings
}
