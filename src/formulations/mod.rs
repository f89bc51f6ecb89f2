//! Formulations: recipes of constraint families (docs/formulation.md).
//!
//! A [`Recipe`] (`paper`, `tight`, `strong`, or one of them with parts overridden and switches
//! set) chooses the form of each part of the network IP: connectivity (the paper's labels
//! (1)–(3), a flow, or lazily separated cutsets), the distance term (labels or a flow with the
//! same value), coverage (5)–(6) aggregated or strengthened, dead-ends, point-to-point, rooms.
//! Each constraint family is one file under `families/` behind the [`Family`] trait: its rows,
//! its variables, its start encoding and its decoding. [`build`] emits the families of the
//! [`REGISTRY`] that a problem's model has into a [`Formulation`], which decodes a point into a
//! [`crate::design::Network`] ([`Formulation::decode`]), turns a design back into a point for a
//! MIP start ([`Formulation::encode`]), and gives a separator for its lazy rows
//! ([`Formulation::separator`]). How a model is solved is not part of it (the pipeline's solve
//! strategy).
//!
//! The enumerations the families emit rows over (local configurations, path sets, placements)
//! live in [`crate::rules`], below both this layer and [`crate::design`].

mod build;
mod encode;
pub mod expr;
pub mod families;
mod family;
mod recipe;
mod vars;

pub use build::{build, build_compact, build_with};
pub use encode::{EncodeError, Encoding};
pub use families::cutset::{CoverGroup, CutsetGraph, CutsetSeparator};
pub use families::REGISTRY;
pub use family::{he_name, vname, Ctx, Entry, Family};
pub use recipe::{Plan, Recipe, SYMMETRIC_FLOW_MIN_ORDER};
pub use vars::VarMap;

use crate::milp::Model;
use crate::rules::paths::PathSets;
use crate::rules::placements::PlacementReport;
use crate::solvers::lattice::ObjectiveLattice;
use expr::FamilyStats;
use indexmap::IndexMap;

/// The emitted MILP of one problem under one recipe, with the map from design elements to its
/// variables.
pub struct Formulation {
    /// The recipe, resolved.
    pub recipe: Recipe,
    /// The MILP (without lazily separated rows).
    pub model: Model,
    /// The variables several families share (edges, directions, labels, vertices, parent arcs).
    pub vars: VarMap,
    /// Variables and rows per family, in emission order.
    pub families: IndexMap<String, FamilyStats>,
    /// The families of the model, in emission order.
    pub parts: Vec<Box<dyn Family>>,
    /// The big-M of the label rows (2), when the recipe has labels.
    pub big_m: Option<f64>,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room placements, if room tiling is on.
    pub placements: Option<PlacementReport>,
    /// The graph of the lazily separated cutsets, when the recipe has them.
    pub cutsets: Option<CutsetGraph>,
    /// The lattice every design's objective lies on, when there is one
    /// ([`crate::solvers::lattice`]); the solve strategy decides whether to use it.
    pub objective_lattice: Option<ObjectiveLattice>,
    /// The order of the problem's symmetry group when the recipe left connectivity to the
    /// distance flow for it (the `symmetric_flow` switch); `None` otherwise.
    pub symmetry_order: Option<usize>,
}
