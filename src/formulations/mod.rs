//! Formulations: the network IP of the paper's §4 ([`network`]), its point-to-point path sets
//! ([`paths`]), and the expression helpers they share ([`expr`]).

pub mod expr;
pub mod network;
pub mod paths;
pub mod placements;
pub mod rooms;
