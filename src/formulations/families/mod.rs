//! The constraint families, one file each ([`crate::formulations::Family`]), citing the
//! equations of docs/formulation.md they write (§8 for the strengthened forms). Their order of
//! emission is [`REGISTRY`]'s: a new family is its file here plus its `mod` line and its
//! entry below.

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

use crate::formulations::family::Entry;

/// Every family, in emission order.
pub const REGISTRY: &[Entry] = &[
    edges::Edges::entry,
    no_island::NoIsland::entry,
    label_bounds::LabelBounds::entry,
    coverage::Coverage::entry,
    distance_flow::DistanceFlow::entry,
    travel_flow::TravelFlow::entry,
    connectivity_flow::ConnectivityFlow::entry,
    out_arcs::OutArcs::entry,
    dead_ends::DeadEnds::entry,
    branches::Branches::entry,
    local_configs::LocalConfigs::zigzags,
    local_configs::LocalConfigs::too_close,
    t_junctions::TJunctions::entry,
    paths::PointToPoint::entry,
    rooms::Rooms::entry,
    user::UserSpecs::entry,
    cutset::Cutsets::entry,
];
