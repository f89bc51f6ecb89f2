//! Comparing backends on a set of specs (`netspec compare`): every (instance, backend, seed) is
//! solved in its own child process (`netspec solve`), killed at the time limit plus a grace
//! period, and recorded in its own `run.json` as soon as it ends, so an interrupted comparison
//! resumes where it stopped. Tables (Markdown, CSV) and a per-backend summary follow.
//!
//! Instances are named by their paths (the shortest trailing part that tells them apart:
//! `fig1b/L2/spec` and `fig7e/L2/spec`), so no two share records. Every record carries the
//! settings that produced it ([`RunSettings`]); a rerun reuses a record only when they match.
//! On Linux a child dies with the comparison (`PR_SET_PDEATHSIG`), so killing the parent never
//! leaves a solve running.
//!
//! The files, in the order data flows through them (each imports only files before it):
//! [`manifest`] (the instances), [`record`] (one run's record), [`plan`] (settings and the
//! runs), [`child`] (one run as a child process), [`cluster`] and [`executor`] (where the runs
//! execute), [`summary`] (per-backend statistics), [`merge`] (combining comparisons),
//! [`makespan`] and [`report`] (tables and charts). This file only names them.

pub mod child;
pub mod cluster;
pub mod error;
pub mod executor;
pub mod makespan;
pub mod manifest;
pub mod merge;
pub mod plan;
pub mod record;
pub mod report;
pub mod summary;

pub use child::solve_and_record;
pub use error::CompareError;
pub use executor::run_all;
pub use manifest::{glob_match, instance_ids, paper_seconds, Manifest, ManifestError, ManifestRow, PaperRow};
pub use merge::{merge, MergeError, Merged};
pub use plan::{plan, CompareSettings, Event, Executor, PlannedRun, RunSource};
pub use record::{record_from_dir, RunRecord, RunSettings};
pub use report::{bar_chart_svg, csv, markdown, performance_profile_svg, write_report, Report, ReportError};
pub use summary::{shifted_geometric_mean, summarize, BackendSummary, PROVEN_GAP};
