//! From a resolved problem to a checked design: build the MILP, solve it, check every row and
//! bound with the MILP checker, decode the network, validate it independently, measure it.

use crate::design::{self, Metrics, Network, Violation};
use crate::formulations::expr::FamilyStats;
use crate::formulations::network::{self, NetworkModel};
use crate::formulations::paths::PathSets;
use crate::mesh::Mesh;
use crate::milp::{check_point, objectives_agree, CheckReport, ModelStats, Tolerances};
use crate::solvers::{SolveOptions, SolveResult, SolverError, SolverKind};
use crate::spec::{Problem, Spec};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

/// Version of the design result schema (`result.json`).
pub const DESIGN_SCHEMA_VERSION: u32 = 1;

/// The verdict of every independent check.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Validity {
    /// `true` when a network exists and every check below passed.
    pub valid: bool,
    /// FORMULATION §6 items 1–5, from plain graph code.
    pub design_violations: Vec<Violation>,
    /// §6 item 7: every row and bound of the emitted MILP at the returned point.
    pub milp_check: Option<CheckReport>,
    /// §6 item 7: the objective recomputed from the decoded design.
    pub objective_recomputed: Option<f64>,
    /// Whether it agrees with the solver's objective (1e-6 relative).
    pub objective_agrees: Option<bool>,
}

/// The room part of a design result.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RoomsResult {
    /// Placements enumerated, per template.
    pub enumerated_per_template: Vec<usize>,
    /// Whether enumeration hit its count or time cap.
    pub truncated: bool,
    /// Seconds spent enumerating.
    pub seconds: f64,
    /// Game levels: the block connectivity graph (also written as `blocks.dot`).
    pub block_graph: Option<crate::design::BlockGraph>,
    /// The chosen placements (faces, inner and boundary edges), in placement order; the
    /// network's `rooms` indices refer to the model's full list, these are the rooms themselves.
    pub chosen: Vec<crate::formulations::placements::Placement>,
}

/// Everything about one design run (`result.json`).
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct DesignResult {
    /// Always `netspec.design`.
    pub schema: String,
    /// [`DESIGN_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The netspec version.
    pub netspec_version: String,
    /// The spec, echoed.
    pub spec: Spec,
    /// The mesh.
    pub mesh: Mesh,
    /// Sink vertex ids.
    pub sinks: Vec<u32>,
    /// Active edges as vertex pairs (existing edges included), in edge-id order.
    pub active_edges: Vec<[u32; 2]>,
    /// The decoded network (active flags, directions, labels), if there is a solution.
    pub network: Option<Network>,
    /// Whether a design exists (apart from why the solver stopped, `solve.termination`).
    #[serde(default)]
    pub design_found: bool,
    /// Metrics of the network.
    pub metrics: Option<Metrics>,
    /// The independent checks.
    pub validity: Validity,
    /// The solver's result (the primal point is omitted here; see `--export` for the model).
    pub solve: SolveResult,
    /// Size of the MILP.
    pub model_stats: ModelStats,
    /// Variables and rows per constraint family.
    pub families: IndexMap<String, FamilyStats>,
    /// The big-M of (2).
    pub big_m: f64,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room tiling, if on.
    pub rooms: Option<RoomsResult>,
    /// The solver's point, one value per MILP variable (not in `result.json`; for `--sol`).
    #[serde(skip)]
    pub primal_point: Option<Vec<f64>>,
}

/// Builds the MILP of a problem (no solve).
pub fn build(p: &Problem) -> NetworkModel {
    network::build(p)
}

/// Solves a built model and checks the answer.
pub fn solve_built(p: &Problem, nm: &NetworkModel, kind: SolverKind, options: &SolveOptions) -> Result<DesignResult, SolverError> {
    let solver = kind.instance()?;
    let mut result = solver.solve(&nm.model, options)?;
    let mut validity = Validity { valid: false, design_violations: Vec::new(), milp_check: None, objective_recomputed: None, objective_agrees: None };
    let mut net = None;
    let mut metrics = None;
    if let Some(x) = &result.primal {
        let check = check_point(&nm.model, x, &Tolerances::default());
        let n = design::decode(p, nm, x);
        validity.design_violations = design::validate(p, &n, nm.path_sets.as_ref());
        if let Some(rm) = &nm.rooms {
            validity.design_violations.extend(design::validate_rooms(p, &n, &rm.report.placements, &n.rooms));
        }
        let recomputed = design::recompute_objective(p, nm, &n, x);
        validity.objective_recomputed = Some(recomputed);
        validity.objective_agrees = result.objective.map(|o| objectives_agree(o, recomputed, 1e-6));
        validity.valid = check.is_feasible() && validity.design_violations.is_empty() && validity.objective_agrees == Some(true);
        validity.milp_check = Some(check);
        metrics = Some(Metrics::of(p, &n));
        net = Some(n);
    }
    let active_edges = net.as_ref().map_or(Vec::new(), |n: &Network| {
        n.active_edges()
            .into_iter()
            .map(|e| {
                let (a, b) = p.mesh.edge_vertices(e);
                [a.0, b.0]
            })
            .collect()
    });
    let primal_point = result.primal.take();
    let rooms = nm.rooms.as_ref().map(|rm| RoomsResult {
        enumerated_per_template: rm.report.per_template.clone(),
        truncated: rm.report.truncated,
        seconds: rm.report.seconds,
        block_graph: match (&p.rooms, &net) {
            (Some(r), Some(n)) if r.mode == crate::spec::RoomMode::Game => Some(design::block_graph(p, n, &rm.report.placements)),
            _ => None,
        },
        chosen: net.as_ref().map_or(Vec::new(), |n| n.rooms.iter().map(|&k| rm.report.placements[k].clone()).collect()),
    });
    Ok(DesignResult {
        schema: "netspec.design".into(),
        schema_version: DESIGN_SCHEMA_VERSION,
        netspec_version: env!("CARGO_PKG_VERSION").into(),
        spec: p.spec.clone(),
        mesh: p.mesh.clone(),
        sinks: p.mesh.vertices().filter(|v| p.is_sink[v.index()]).map(|v| v.0).collect(),
        active_edges,
        design_found: net.is_some(),
        network: net,
        metrics,
        validity,
        solve: result,
        model_stats: nm.model.stats(),
        families: nm.families.clone(),
        big_m: nm.big_m,
        path_sets: nm.path_sets.clone(),
        rooms,
        primal_point,
    })
}
