//! Decoding a solution into a network, measuring it, and validating it independently.
//!
//! The validator ([`validate`], [`validate_rooms`]) checks docs/formulation.md §6 items 1–6 in plain
//! graph code that never reads the MILP: it takes the problem and a set of active edges. Item 7
//! is the MILP checker (every row and bound at the returned point) together with
//! [`Objective::of`], the objective recomputed from the design alone. Nothing here imports
//! [`crate::formulations`]: a recipe decodes its point into a [`Network`], and from there on
//! only design code judges it.

mod blocks;
mod metrics;
mod objective;
pub mod picture;
pub mod streets;
mod validate;

pub use blocks::{block_graph, BlockGraph, GraphShape};
pub use metrics::{travel_distances, Metrics};
pub use objective::{label_distances, Objective};
pub use validate::{validate, validate_rooms, Violation};

use crate::mesh::{EdgeId, VertexId};
use crate::spec::{EdgeRole, Problem};
use serde::{Deserialize, Serialize};

/// A decoded network.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Network {
    /// Whether each edge is active (existing edges included).
    pub active: Vec<bool>,
    /// Active half-edges (direction toward a sink), as (tail, head), from `E(i→j)`.
    pub directions: Vec<(VertexId, VertexId)>,
    /// Distance labels of active half-edges as the solver returned them: (tail, head, label).
    pub labels: Vec<(VertexId, VertexId, f64)>,
    /// Chosen room placements (indices into the model's placements), when tiling rooms.
    #[serde(default)]
    pub rooms: Vec<usize>,
}

impl Network {
    /// The active edges, in id order.
    pub fn active_edges(&self) -> Vec<EdgeId> {
        self.active.iter().enumerate().filter(|(_, &a)| a).map(|(i, _)| EdgeId(i as u32)).collect()
    }

    /// Every edge that is not excluded, active: the most a design can use (bounds computed on
    /// it hold for every design).
    pub fn all_usable(p: &Problem) -> Network {
        let active = p.roles.iter().map(|r| *r != EdgeRole::Excluded).collect();
        Network { active, directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() }
    }

    /// A network from a list of active edges (existing edges are added), for hand-built tests.
    pub fn from_edges(p: &Problem, edges: &[EdgeId]) -> Network {
        let mut active: Vec<bool> = p.roles.iter().map(|r| *r == EdgeRole::Existing).collect();
        for e in edges {
            active[e.index()] = true;
        }
        Network { active, directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() }
    }
}
