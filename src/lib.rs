//! netspec designs networks (street layouts, building corridors, game levels) from functional
//! specifications by integer programming, after Peng et al., "Computational Network Design from
//! Functional Specifications" (SIGGRAPH 2016).
//!
//! Layers, bottom up: [`milp`] (the solver-neutral model and its independent checker), [`io`]
//! (MPS and LP files), [`solvers`] (HiGHS, CBC, SCIP, microlp and a good_lp bridge behind one
//! trait), [`mesh`] (2D half-edge meshes), [`spec`] (functional specifications),
//! [`rules`] (what a spec's rules mean on a mesh, enumerated), [`formulations`] (recipes of
//! constraint families: the paper's integer program and stronger ones), [`design`] (decoding, metrics and the
//! independent validator), [`render`] (pictures), and [`pipeline`] (spec → checked design). [`urban`] lays out cities;
//! [`traffic`] evaluates designed street networks in SUMO; [`serve`] is the browser application
//! over all of it.
#![deny(missing_docs)]

pub mod compare;
pub mod design;
pub mod explain;
pub mod formulations;
pub mod geometry;
pub mod grow;
pub mod heuristics;
pub mod io;
pub mod layout;
pub mod levels;
pub mod measure;
pub mod mesh;
pub mod milp;
pub mod osm;
pub mod pipeline;
pub mod render;
pub mod report;
pub mod rules;
pub mod run;
pub mod serve;
pub mod slurm;
pub mod solvers;
pub mod spec;
pub mod stats;
pub mod traffic;
pub mod urban;

/// The README's code examples, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;

#[cfg(test)]
mod layers;
