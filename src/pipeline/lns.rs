//! Large-neighbourhood search (the `lns` strategy switch): before the full MILP, windows of the
//! mesh around seeded random vertices are freed — their edge variables keep their bounds, every
//! other edge is fixed at the incumbent — and each window is solved by the backend under a short
//! limit from the incumbent. The model is built once; a window only changes bounds. A window
//! whose solve improves the incumbent grows the next one, one proven without gain grows it
//! more, one stopped by its limit without gain shrinks it. The best design then starts the full
//! MILP for the rest of the time, and is checked with it.

use crate::milp::Model;
use crate::solvers::split::PhaseSolve;
use crate::solvers::{LogTarget, SolveOptions, SolverError, Termination};
use crate::spec::Problem;
use rand::rngs::Xoshiro256PlusPlus;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::time::Instant;

/// The share of the time limit the search may use before the full MILP.
pub const LNS_SHARE: f64 = 0.75;
/// A window's time limit (seconds).
pub const WINDOW_LIMIT: f64 = 2.5;
/// The first window's size (edges), at most a quarter of the mesh's edges; a window never
/// takes more than half of them (a larger one is the whole MILP again).
pub const FIRST_WINDOW: f64 = 300.0;
/// The smallest window (edges).
pub const MIN_WINDOW: f64 = 30.0;

/// What the search did (`lns` in `result.json`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LnsReport {
    /// Windows solved.
    pub windows: usize,
    /// Windows that improved the incumbent.
    pub improvements: usize,
    /// Seconds spent.
    pub seconds: f64,
    /// The incumbent's objective before the search.
    pub start_objective: f64,
    /// The best objective it found (the full MILP's start).
    pub objective: f64,
    /// Each improvement: (seconds from the search's start, objective).
    pub trace: Vec<(f64, f64)>,
}

/// The edges of a window: breadth first from `v0` over the mesh until `size` edges are taken.
fn window(p: &Problem, v0: crate::mesh::VertexId, size: usize) -> Vec<bool> {
    let mesh = &p.mesh;
    let mut free = vec![false; mesh.num_edges()];
    let mut seen = vec![false; mesh.num_vertices()];
    let mut queue = VecDeque::from([v0]);
    seen[v0.index()] = true;
    let mut count = 0;
    while let Some(v) = queue.pop_front() {
        for e in mesh.incident_edges(v) {
            if !free[e.index()] {
                free[e.index()] = true;
                count += 1;
                if count >= size {
                    return free;
                }
            }
            let (a, b) = mesh.edge_vertices(e);
            let w = if a == v { b } else { a };
            if !seen[w.index()] {
                seen[w.index()] = true;
                queue.push_back(w);
            }
        }
    }
    free
}

/// Improves the start `x0` of `model` by windows solved with `solve` (the pipeline's backend
/// call, lazily separated rows included) until `budget` seconds are spent or `options`'
/// interrupt fires; `edge_vars` are the edge variables by mesh edge. Returns the best point and
/// what the search did.
pub fn improve(
    p: &Problem,
    model: &Model,
    edge_vars: &[Option<crate::milp::VarId>],
    x0: &[f64],
    options: &SolveOptions,
    budget: f64,
    solve: &mut dyn FnMut(&Model, &SolveOptions) -> Result<PhaseSolve, SolverError>,
) -> (Vec<f64>, LnsReport) {
    let t0 = Instant::now();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(p.spec.solver.seed.unwrap_or(1));
    let mut x = x0.to_vec();
    let start_objective = model.objective_value(&x);
    let mut report = LnsReport {
        windows: 0,
        improvements: 0,
        seconds: 0.0,
        start_objective,
        objective: start_objective,
        trace: Vec::new(),
    };
    let edges = p.mesh.num_edges() as f64;
    let mut size = FIRST_WINDOW.min(edges / 4.0).max(1.0);
    let nv = p.mesh.num_vertices();
    // One copy of the model; each window only resets the edge variables' bounds.
    let mut m = model.clone();
    while nv > 0 && options.interrupt.as_ref().is_none_or(|i| !i.is_triggered()) {
        let left = budget - t0.elapsed().as_secs_f64();
        if left <= 0.1 {
            break;
        }
        let free = window(p, crate::mesh::VertexId(rng.random_range(0..nv) as u32), size as usize);
        // Every edge variable gets its window's bounds: the model's own when free, else fixed.
        for (e, var) in edge_vars.iter().enumerate() {
            if let Some(var) = var {
                let own = model.var(*var);
                let at = x[var.index()].round();
                let v = m.var_mut(*var);
                (v.lb, v.ub) = if free[e] { (own.lb, own.ub) } else { (at, at) };
            }
        }
        let o = SolveOptions {
            time_limit: Some(WINDOW_LIMIT.min(left)),
            mip_start: Some(x.clone()),
            log: LogTarget::Quiet,
            ..options.clone()
        };
        report.windows += 1;
        let Ok((r, _, _)) = solve(&m, &o) else { continue };
        let proven = r.termination == Termination::Optimal;
        match (r.primal, r.objective) {
            (Some(y), Some(obj)) if model.sense.improves(obj, report.objective, 1e-6) => {
                x = y;
                report.objective = obj;
                report.improvements += 1;
                report.trace.push((t0.elapsed().as_secs_f64(), obj));
                size *= 1.2;
            }
            _ if proven => size *= 1.3,
            _ => size = (size * 0.8).max(MIN_WINDOW),
        }
        size = size.min(edges / 2.0).max(1.0);
    }
    report.seconds = t0.elapsed().as_secs_f64();
    (x, report)
}
