//! Room tiling on the network IP: floor plans (paper §5.2) and game levels (§5.3), as
//! `shared/FORMULATION.md` §4–§5 state thc.em. One binary `R` per enumerated placement.

use super::Ctx;
use crate::formulations::expr::Expr;
use crate::milp::VarId;
use crate::rules::placements::{enumerate_placements, PlacementReport};
use crate::spec::{RoomMode, Rooms};
use std::time::Duration;

/// Time cap on placement enumeration.
const PLACEMENT_TIME_CAP: Duration = Duration::from_secs(20);

/// Emits `R` per placement and (16) exact cover, then (17)–(18) for floor plans or (19)–(20)
/// for game levels, then the room-type counts. Returns the enumerated placements (their `R` go
/// to the variable map).
pub fn rooms(c: &mut Ctx, rooms: &Rooms) -> PlacementReport {
    let p = c.p;
    let mesh = &p.mesh;
    let report = enumerate_placements(mesh, &rooms.templates, &p.is_obstacle_face, rooms.max_placements, PLACEMENT_TIME_CAP);
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
                // (19) R − Σ_inner E_i ≤ 0: a block is traversed.
                let mut ex = Expr::new();
                ex.add(r, 1.0);
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
    c.vars.rooms = vars;
    report
}
