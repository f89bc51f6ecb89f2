//! netspec designs networks (street layouts, building corridors, game levels) from functional
//! specifications by integer programming, after Peng et al., "Computational Network Design from
//! Functional Specifications" (SIGGRAPH 2016).
//!
//! Layers: [`milp`] (the solver-neutral model and its independent checker), [`io`] (MPS and
//! LP files), [`solvers`] (HiGHS, CBC, SCIP, microlp and a good_lp bridge behind one trait).
#![deny(missing_docs)]

pub mod io;
pub mod milp;
pub mod report;
pub mod solvers;
