//! What a design run produces (`result.json`), and the independent checks every design goes
//! through: the validator on the network, the MILP checker on the design as a point of the
//! formulation.

use super::outcome::Outcome;
use crate::design::{self, Metrics, Network, Objective, Violation};
use crate::formulations::expr::FamilyStats;
use crate::formulations::Formulation;
use crate::mesh::Mesh;
use crate::milp::{check_point, CheckReport, ModelStats, Tolerances};
use crate::rules::paths::PathSets;
use crate::solvers::lattice::LatticeReport;
use crate::solvers::split::SplitReport;
use crate::solvers::{LazyReport, Separator};
use crate::spec::{Problem, Spec};
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};

/// Version of the design result schema (`result.json`).
pub const DESIGN_SCHEMA_VERSION: u32 = 2;

/// The verdict of every independent check.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Validity {
    /// `true` when a network exists and every check below passed.
    pub valid: bool,
    /// docs/formulation.md §6 items 1–5, from plain graph code.
    pub design_violations: Vec<Violation>,
    /// §6 item 7: every row and bound of the emitted MILP at the returned point.
    pub milp_check: Option<CheckReport>,
    /// §6 item 7: the objective recomputed from the decoded design alone (see
    /// [`crate::design::Objective`]).
    pub objective_recomputed: Option<f64>,
    /// Whether the solver's objective equals the model's objective at its point (the
    /// formulation's surrogate, 1e-6 relative) and the design's own objective is not above it.
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
    pub chosen: Vec<crate::rules::placements::Placement>,
}

/// Everything about one design run (`result.json`), a MILP solve's or a search's: the search
/// has no `lazy`, `split`, `lattice`, `solver_hints` or `start`, and its `result.json` does not
/// write `design_found`, `lazy` and `start` (see [`DesignResult`]'s `Serialize`).
#[derive(Clone, Debug, Deserialize)]
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
    /// The objective recomputed from the design alone, term by term (the paper's distance term,
    /// total travel, counts of penalised features).
    pub objective: Option<Objective>,
    /// The independent checks.
    pub validity: Validity,
    /// Why the solver stopped, objective, bound, times (the primal point is omitted here; see
    /// `--sol`).
    pub solve: Outcome,
    /// Size of the MILP.
    pub model_stats: ModelStats,
    /// Variables and rows per constraint family.
    pub families: IndexMap<String, FamilyStats>,
    /// The recipe, with its overrides (`strong`, `paper(coverage=strong)`).
    pub formulation: String,
    /// The big-M of the label rows (2), when the recipe has labels.
    pub big_m: Option<f64>,
    /// Lazily separated rows: how they were handled and how many were added.
    #[serde(default)]
    pub lazy: Option<LazyReport>,
    /// The two-phase solve, when the objective's two scales called for it
    /// ([`crate::solvers::split`]).
    #[serde(default)]
    pub split: Option<SplitReport>,
    /// The large-neighbourhood search before the full MILP, when the strategy ran it
    /// ([`crate::pipeline::lns`]).
    #[serde(default)]
    pub lns: Option<super::lns::LnsReport>,
    /// The objective's lattice, when the recipe used it, with the backend's bound before it was
    /// rounded up to the lattice ([`crate::solvers::lattice`]).
    #[serde(default)]
    pub lattice: Option<LatticeReport>,
    /// The solve strategy's settings handed to the backend (`highs.mip_pscost_minreliable=0`;
    /// [`crate::solvers::Solver::strategy_hints`]), beside the user's own.
    #[serde(default)]
    pub solver_hints: Vec<String>,
    /// The MIP start handed to the solver (or refused), if one was prepared.
    #[serde(default)]
    pub start: Option<StartReport>,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room tiling, if on.
    pub rooms: Option<RoomsResult>,
    /// The solver's point, one value per MILP variable (not in `result.json`; for `--sol`).
    #[serde(skip)]
    pub primal_point: Option<Vec<f64>>,
}

impl DesignResult {
    /// The design, if one was found.
    pub fn network(&self) -> Option<&Network> {
        self.network.as_ref()
    }

    /// The independent checks.
    pub fn validity(&self) -> &Validity {
        &self.validity
    }

    /// The run's outcome: why it stopped, objective, bound, gap, nodes, times.
    pub fn outcome(&self) -> &Outcome {
        &self.solve
    }

    /// Why the run stopped.
    pub fn termination(&self) -> &crate::solvers::Termination {
        &self.solve.termination
    }

    /// The objective, if any.
    pub fn objective(&self) -> Option<f64> {
        self.solve.objective
    }

    /// The design's metrics, if there is a design.
    pub fn metrics(&self) -> Option<&Metrics> {
        self.metrics.as_ref()
    }

    /// The room part, if the problem tiles rooms.
    pub fn rooms(&self) -> Option<&RoomsResult> {
        self.rooms.as_ref()
    }

    /// Whether the run was stopped by an interrupt.
    pub fn interrupted(&self) -> bool {
        self.solve.interrupted()
    }
}

/// `result.json`'s layout: every field in declaration order, a search's without `design_found`,
/// `lazy` and `start` (which only a MILP solve has), `split`, `lattice` and `solver_hints` only
/// when set.
impl Serialize for DesignResult {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let milp = !self.solve.is_search();
        let mut st = s.serialize_struct("DesignResult", 23)?;
        st.serialize_field("schema", &self.schema)?;
        st.serialize_field("schema_version", &self.schema_version)?;
        st.serialize_field("netspec_version", &self.netspec_version)?;
        st.serialize_field("spec", &self.spec)?;
        st.serialize_field("mesh", &self.mesh)?;
        st.serialize_field("sinks", &self.sinks)?;
        st.serialize_field("active_edges", &self.active_edges)?;
        st.serialize_field("network", &self.network)?;
        if milp {
            st.serialize_field("design_found", &self.design_found)?;
        }
        st.serialize_field("metrics", &self.metrics)?;
        st.serialize_field("objective", &self.objective)?;
        st.serialize_field("validity", &self.validity)?;
        st.serialize_field("solve", &self.solve)?;
        st.serialize_field("model_stats", &self.model_stats)?;
        st.serialize_field("families", &self.families)?;
        st.serialize_field("formulation", &self.formulation)?;
        st.serialize_field("big_m", &self.big_m)?;
        if milp {
            st.serialize_field("lazy", &self.lazy)?;
        }
        if let Some(split) = &self.split {
            st.serialize_field("split", split)?;
        }
        if let Some(lns) = &self.lns {
            st.serialize_field("lns", lns)?;
        }
        if let Some(lattice) = &self.lattice {
            st.serialize_field("lattice", lattice)?;
        }
        if !self.solver_hints.is_empty() {
            st.serialize_field("solver_hints", &self.solver_hints)?;
        }
        if milp {
            st.serialize_field("start", &self.start)?;
        }
        st.serialize_field("path_sets", &self.path_sets)?;
        st.serialize_field("rooms", &self.rooms)?;
        st.end()
    }
}

/// A design as a point of a formulation, with the MILP checker's report on it.
pub(crate) struct DesignPoint {
    /// The point.
    pub x: Vec<f64>,
    /// Every emitted row and bound, checked.
    pub check: CheckReport,
    /// Lazily separated rows the point violates (0 without a separator).
    pub lazy_violations: usize,
}

/// Encodes `net` for `f` and checks the point against every row, bound and lazy row.
pub(crate) fn design_point(f: &Formulation, p: &Problem, net: &Network) -> Result<DesignPoint, String> {
    let x = f.encode(p, net).map_err(|e| e.to_string())?;
    let check = check_point(&f.model, &x, &Tolerances::default());
    let lazy_violations = f.separator().map_or(0, |mut sep| sep.separate_integral(&x).len());
    Ok(DesignPoint { x, check, lazy_violations })
}

/// The validator's verdict on a design of `f`: §6 items 1–5, and the room rules when tiling.
pub(crate) fn design_violations(p: &Problem, f: &Formulation, net: &Network) -> Vec<Violation> {
    let mut v = design::validate(p, net, f.path_sets.as_ref());
    if let Some(pl) = &f.placements {
        v.extend(design::validate_rooms(p, net, &pl.placements, &net.rooms));
    }
    v
}

/// A design's active edges as vertex pairs, in edge-id order (empty without a design).
pub(crate) fn active_edge_pairs(p: &Problem, net: Option<&Network>) -> Vec<[u32; 2]> {
    net.map_or(Vec::new(), |n| {
        n.active_edges()
            .into_iter()
            .map(|e| {
                let (a, b) = p.mesh.edge_vertices(e);
                [a.0, b.0]
            })
            .collect()
    })
}

/// The room part of a result, when `f` tiles rooms.
pub(crate) fn rooms_result(p: &Problem, f: &Formulation, net: Option<&Network>) -> Option<RoomsResult> {
    f.placements.as_ref().map(|pl| RoomsResult {
        enumerated_per_template: pl.per_template.clone(),
        truncated: pl.truncated,
        seconds: pl.seconds,
        block_graph: match (&p.rooms, net) {
            (Some(r), Some(n)) if r.mode == crate::spec::RoomMode::Game => {
                Some(design::block_graph(p, n, &pl.placements))
            }
            _ => None,
        },
        chosen: net.map_or(Vec::new(), |n| n.rooms.iter().map(|&k| pl.placements[k].clone()).collect()),
    })
}

/// A MIP start: where it came from, what it is worth, and whether the checker let it through.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct StartReport {
    /// Where the design came from (`heuristic`, a file name).
    pub source: String,
    /// The design's own objective.
    pub objective: Option<f64>,
    /// Whether the point passed the MILP checker (every emitted row and bound, and every lazy
    /// row) and was handed to the solver.
    pub accepted: bool,
    /// Why it was refused.
    pub reason: Option<String>,
    /// Seconds spent finding and checking it (counted against the solve's time limit).
    #[serde(default)]
    pub seconds: Option<f64>,
    /// Whether the returned design is the start itself: the solver found nothing better (or
    /// nothing at all) before it stopped.
    #[serde(default)]
    pub returned: bool,
}
