//! From a resolved problem to a checked design: build the MILP, prepare a checked MIP start,
//! solve under a strategy, check every row and bound with the MILP checker, decode the network,
//! validate it independently, measure it.
//!
//! - [`outcome`]: one run's outcome (why it stopped, objective, bound, times), the same type
//!   for a MILP solve and a search;
//! - [`result`]: the design result (`result.json`) and the independent checks;
//! - [`start`]: MIP starts, checked before any backend sees them;
//! - [`strategy`]: how a model is solved, apart from what it is (objective split, lattice
//!   rounding, backend hints, parallel search);
//! - [`solve`]: a built formulation solved on a backend and its answer checked;
//! - [`search`]: the heuristic and the stochastic search as solver choices, checked the same way;
//! - [`settings`]: one path from the command line, a spec and a city spec to solve options.

pub mod lns;
pub mod outcome;
pub mod result;
pub mod search;
pub mod settings;
pub mod solve;
pub mod start;
pub mod strategy;

pub use outcome::{Outcome, SearchDetails};
pub use result::{DesignResult, RoomsResult, StartReport, Validity, DESIGN_SCHEMA_VERSION};
pub use search::{Method, SearchMethod};
pub use solve::{solve_built, solve_built_with, solve_from, solve_from_with};
pub use start::{
    default_first_design_budget, default_start, default_start_budget, prepare_start, start_for, StartFrom,
};
pub use strategy::Strategy;

use crate::formulations::{self, Formulation};
use crate::spec::Problem;

/// Builds the MILP of a problem under the recipe its spec asks for (no solve).
pub fn build(p: &Problem) -> Formulation {
    formulations::build(p)
}
