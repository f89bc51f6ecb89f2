//! The variables several families share: the network's skeleton.

use super::expr::Value;
use crate::milp::VarId;

/// The variables several families share: the network's skeleton.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VarMap {
    /// `E_x` per edge (`None` for an existing or excluded edge).
    pub edge: Vec<Option<VarId>>,
    /// `E(i→j)` per half-edge: the direction toward a sink (labels and the distance flow).
    pub half_edge: Vec<Option<VarId>>,
    /// `D(i→j)` per half-edge (labels).
    pub label: Vec<Option<VarId>>,
    /// `V_y` per vertex, or its constant activity.
    pub vertex: Vec<Value>,
    /// Parent arc `P(i→j) ∈ [0, 1]` per half-edge (the out-arc rows without direction binaries).
    pub parent: Vec<Option<VarId>>,
}

impl VarMap {
    /// An empty map for a mesh of this size.
    pub fn new(vertices: usize, edges: usize) -> VarMap {
        VarMap {
            edge: vec![None; edges],
            half_edge: vec![None; 2 * edges],
            label: vec![None; 2 * edges],
            vertex: vec![Value::Const(0.0); vertices],
            parent: vec![None; 2 * edges],
        }
    }
}
