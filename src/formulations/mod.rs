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

pub use build::{build, build_compact, build_with, Formulation};
pub use encode::{EncodeError, Encoding};
pub use families::cutset::{CoverGroup, CutsetGraph, CutsetSeparator};
pub use families::REGISTRY;
pub use family::{he_name, vname, Ctx, Entry, Family, VarMap};
pub use recipe::{Plan, Recipe, SYMMETRIC_FLOW_MIN_ORDER};
