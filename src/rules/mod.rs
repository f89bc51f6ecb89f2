//! What a spec's rules mean on a mesh, enumerated: local configurations (zig-zags, too-close
//! pairs, T-junctions) and coverage balls ([`local`]), point-to-point path sets ([`paths`]) and
//! room-template placements ([`placements`]).
//!
//! This layer sits below both [`crate::formulations`] (which emits rows over these sets) and
//! [`crate::design`] (which validates and measures designs against them): the checker never
//! reads a formulation's variables, and a formulation's variables never define what the checker
//! accepts.

pub mod local;
pub mod paths;
pub mod placements;

pub use local::{cover_set, designed, t_configs, too_close_configs, zigzag_configs, LocalConfig};
