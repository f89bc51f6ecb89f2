//! The connectivity flow (docs/formulation.md §8): the compact form of the cutsets.

use super::flow::{encode_vertex_flow, vertex_flow};
use crate::formulations::encode::{EncodeError, Encoding};
use crate::formulations::family::{Ctx, Family};
use crate::milp::VarId;
use crate::spec::ConnectivityForm;

/// Every active non-sink vertex sends one unit to the sinks over active edges. Rows `ccap_…`,
/// `ccons_…`.
pub struct ConnectivityFlow {
    /// `C` per half-edge.
    flow: Vec<Option<VarId>>,
}

impl ConnectivityFlow {
    /// When the plan ties the network to the sinks by a flow of its own.
    pub fn entry(c: &Ctx) -> Option<Box<dyn Family>> {
        (c.plan.connectivity == Some(ConnectivityForm::Flow))
            .then(|| Box::new(ConnectivityFlow { flow: Vec::new() }) as Box<dyn Family>)
    }
}

impl Family for ConnectivityFlow {
    fn label(&self) -> String {
        "connectivity flow (§8)".into()
    }

    fn emit(&mut self, c: &mut Ctx) {
        self.flow = vertex_flow(c, "C", |_| 0.0);
    }

    fn encode(&self, e: &Encoding, x: &mut [f64]) -> Result<(), EncodeError> {
        encode_vertex_flow(e, x, &self.flow)
    }

    fn lattice_vars(&self) -> Vec<VarId> {
        self.flow.iter().flatten().copied().collect()
    }
}
