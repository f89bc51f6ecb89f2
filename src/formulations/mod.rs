//! Formulations: recipes of constraint families (FORMULATION.md §3–§5 and §8).
//!
//! A [`Recipe`] (`paper`, `tight`, `strong`, or one of them with parts overridden) chooses one
//! family per part of the network IP: connectivity (the paper's labels (1)–(3), a flow, or
//! lazily separated cutsets), the distance term (labels or a flow with the same value),
//! coverage (5)–(6) aggregated or strengthened, dead-ends, point-to-point, rooms.
//! [`build`] emits the MILP into a [`Formulation`], which owns the variable map, decodes a point
//! into a [`crate::design::Network`] ([`Formulation::decode`]), turns a design back into a point
//! for a MIP start ([`Formulation::encode`]), and gives a separator for its lazy rows
//! ([`Formulation::separator`]).
//!
//! The enumerations the families emit rows over (local configurations, path sets, placements)
//! live in [`crate::rules`], below both this layer and [`crate::design`].

mod build;
mod encode;
pub mod expr;
pub mod families;
mod recipe;
pub mod vars;

pub use build::{build, build_compact, build_with, Formulation};
pub use encode::EncodeError;
pub use families::cutset::{CoverGroup, CutsetGraph, CutsetSeparator};
pub use recipe::{Plan, Recipe};
