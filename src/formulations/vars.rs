//! A recipe's variable map: which MILP variable stands for which design element.

use super::expr::Value;
use crate::mesh::{EdgeId, HalfEdgeId, VertexId};
use crate::milp::VarId;
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

/// A successor variable `L(i→j; j→k)` of (1)–(3).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Successor {
    /// `i→j`.
    pub from: HalfEdgeId,
    /// `j→k`.
    pub to: HalfEdgeId,
    /// The variable.
    pub var: VarId,
}

/// The paper's dead-end indicator `ν(i→j)` of (10)–(11): 1 when the head of `i→j` has another
/// active edge.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct DeadEndIndicator {
    /// The half-edge `i→j`.
    pub half_edge: HalfEdgeId,
    /// The variable.
    pub var: VarId,
}

/// Every variable of a formulation, by the design element it stands for. `None` (or a
/// [`Value::Const`]) where the element is fixed or the recipe has no such variable.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct VarMap {
    /// `E_x` per edge.
    pub edge: Vec<Option<VarId>>,
    /// `E(i→j)` per half-edge: the direction toward a sink (labels and the distance flow).
    pub half_edge: Vec<Option<VarId>>,
    /// `D(i→j)` per half-edge (labels).
    pub label: Vec<Option<VarId>>,
    /// `L(i→j; j→k)` (labels).
    pub successors: Vec<Successor>,
    /// `ν(i→j)` (the paper's dead-end rows).
    pub dead_end_indicators: Vec<DeadEndIndicator>,
    /// Flow of the distance family per half-edge.
    pub distance_flow: Vec<Option<VarId>>,
    /// Flow of the travel family per half-edge.
    pub travel_flow: Vec<Option<VarId>>,
    /// Flow of the connectivity family per half-edge.
    pub connect_flow: Vec<Option<VarId>>,
    /// Parent arc `P(i→j) ∈ [0, 1]` per half-edge (the out-arc rows without direction binaries).
    pub parent: Vec<Option<VarId>>,
    /// `V_y` per vertex, or its constant activity.
    pub vertex: Vec<Value>,
    /// `P` per enumerated point-to-point path (per pair, per path; `None` when every edge of
    /// the path is existing).
    pub paths: Vec<Vec<Option<VarId>>>,
    /// Local configurations of (13) that were emitted.
    pub local_configs: Vec<LocalConfig>,
    /// T-junction configurations of (14) that were emitted.
    pub t_configs: Vec<TConfig>,
    /// `R` per room placement (parallel to the placements).
    pub rooms: Vec<VarId>,
}

impl VarMap {
    /// An empty map for a mesh of this size.
    pub fn new(vertices: usize, edges: usize) -> VarMap {
        VarMap {
            edge: vec![None; edges],
            half_edge: vec![None; 2 * edges],
            label: vec![None; 2 * edges],
            distance_flow: vec![None; 2 * edges],
            travel_flow: vec![None; 2 * edges],
            connect_flow: vec![None; 2 * edges],
            parent: vec![None; 2 * edges],
            vertex: vec![Value::Const(0.0); vertices],
            ..VarMap::default()
        }
    }
}
