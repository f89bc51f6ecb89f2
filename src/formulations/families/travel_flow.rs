//! The travel flow (docs/formulation.md §8): the per-vertex travel term.

use super::flow::{encode_vertex_flow, vertex_flow};
use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::family::{Ctx, Family};
use crate::milp::VarId;

/// Its cost is `λtravel·Σ_{active non-sink v} d(v)`, `d` the network distance to the nearest
/// sink (an uncapacitated min-cost flow in which every active vertex supplies one unit). Rows
/// `gcap_…`, `gcons_…`.
pub struct TravelFlow {
    /// `G` per half-edge.
    flow: Vec<Option<VarId>>,
}

impl TravelFlow {
    /// When the problem weighs travel.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        c.plan.travel_flow.then(|| Box::new(TravelFlow { flow: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for TravelFlow {
    fn label(&self) -> String {
        "travel flow (§8)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        let lambda = c.p.w_travel;
        self.flow = vertex_flow(c, "G", |len| lambda * len);
    }

    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        encode_vertex_flow(e, x, &self.flow)
    }

    fn lattice_vars(&self) -> Vec<VarId> {
        self.flow.iter().flatten().copied().collect()
    }
}
