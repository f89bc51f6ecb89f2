//! The constraint families, one file each ([`crate::formulations::Family`]), citing the
//! equations of docs/formulation.md they write (§8 for the strengthened forms). Their order of
//! emission is the registry's ([`crate::formulations::REGISTRY`]).

pub mod branches;
pub mod connectivity_flow;
pub mod coverage;
pub mod cutset;
pub mod dead_ends;
pub mod distance_flow;
pub mod edges;
mod flow;
pub mod label_bounds;
pub mod local_configs;
pub mod no_island;
pub mod out_arcs;
pub mod paths;
mod penalty;
pub mod rooms;
pub mod t_junctions;
pub mod travel_flow;
pub mod user;
