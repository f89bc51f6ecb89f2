//! Game levels from a connectivity graph, after Ma, Vining, Lefebvre and Sheffer, "Game Level
//! Layout from Design Specification" (Eurographics 2014).
//!
//! A level is a set of block shapes (polygons), a door width and a graph: every node gets a
//! block and a position so that no two blocks overlap and every graph edge is a wall the two
//! blocks share over at least the door width. [`cspace`] computes the configuration spaces of
//! block pairs (the paper's §3.1); [`milp`] and [`exact`] place the blocks exactly, proving when
//! no layout exists; [`validate`] checks every layout with plain geometry. [`run`] is the one
//! entry point of `netspec level`.

pub mod anneal;
pub mod bridge;
pub mod construct;
pub mod cspace;
pub mod exact;
pub mod generate;
pub mod milp;
pub mod output;
pub mod seeds;
pub mod spec;
pub mod validate;

use crate::geometry::P;
use crate::solvers::{Interrupt, SolverError, SolverKind};
use serde::Serialize;
use spec::{BlockId, Level, NodeId};
use std::path::PathBuf;
use std::time::Instant;

/// Why a level could not be laid out (an answer of "no layout" is not an error).
#[derive(Debug, thiserror::Error)]
pub enum LevelError {
    /// The file could not be read.
    #[error("{path}: {reason}")]
    Io {
        /// The file.
        path: String,
        /// The reason.
        reason: String,
    },
    /// The TOML parser's message (with line and column).
    #[error("{0}")]
    Toml(String),
    /// A field's value is unusable.
    #[error("{field}: {reason}")]
    Field {
        /// The field, e.g. `block[2] ("ell").polygon`.
        field: String,
        /// Why.
        reason: String,
    },
    /// An error in a named file.
    #[error("{path}: {source}")]
    InFile {
        /// The file.
        path: String,
        /// The error.
        #[source]
        source: Box<LevelError>,
    },
    /// The solve could not be attempted.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// An answer failed netspec's own checks (a solver bug or a tolerance problem).
    #[error("{0}")]
    Rejected(String),
    /// An export was asked for, but there is no layout to export.
    #[error("{path}: no layout to export (status {status}); the export needs a feasible level")]
    NoLayout {
        /// The level file.
        path: String,
        /// `infeasible` or `unknown`.
        status: String,
    },
    /// Writing an output failed.
    #[error("writing {path}: {reason}")]
    Write {
        /// The file.
        path: String,
        /// The reason.
        reason: String,
    },
}

/// One node's block and position.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Placement {
    /// The node.
    pub node: String,
    /// The block's name.
    pub block_name: String,
    /// The block.
    #[serde(skip)]
    pub block: BlockId,
    /// The translation applied to the block's polygon.
    pub position: P,
}

impl Placement {
    /// Node `n` as block `block` at `position`.
    pub fn new(level: &Level, n: NodeId, block: BlockId, position: P) -> Placement {
        Placement {
            node: level.node_name(n).to_string(),
            block_name: level.blocks[block.0 as usize].name.clone(),
            block,
            position,
        }
    }
}

/// A layout: every node placed, in node order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Layout {
    /// Placements, in node order.
    pub nodes: Vec<Placement>,
}

/// A layout of a level without fixed nodes, moved clear of the obstacles when it overlaps one
/// (translations keep every door and every gap, so the layout stays a layout); any other layout
/// unchanged.
pub fn clear_of_obstacles(level: &Level, layout: Layout) -> Layout {
    if level.has_fixed() || validate::validate(level, &layout).obstacle_overlaps.is_empty() {
        return layout;
    }
    let right = level.obstacles.iter().flat_map(|o| o.polygon.iter().map(|q| q[0])).fold(f64::NEG_INFINITY, f64::max);
    let left = layout
        .nodes
        .iter()
        .flat_map(|n| level.blocks[n.block.0 as usize].polygon.iter().map(|q| q[0] + n.position[0]))
        .fold(f64::INFINITY, f64::min);
    let dx = right - left + level.door_width;
    let nodes =
        layout.nodes.into_iter().map(|n| Placement { position: [n.position[0] + dx, n.position[1]], ..n }).collect();
    Layout { nodes }
}

/// The method(s) to run.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// The paper's incremental simulated annealing.
    Anneal,
    /// The exact model.
    Milp,
    /// The annealer and the exact model side by side; the first to settle the question stops
    /// the other.
    Both,
}

impl std::str::FromStr for Method {
    type Err = String;
    /// `anneal`, `milp` or `both` (any case).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "anneal" => Ok(Method::Anneal),
            "milp" => Ok(Method::Milp),
            "both" => Ok(Method::Both),
            _ => Err(format!("unknown method `{s}` (known: anneal, milp, both)")),
        }
    }
}

/// What `netspec level` asks for.
#[derive(Clone, Debug)]
pub struct LevelRequest {
    /// The level file.
    pub spec: PathBuf,
    /// Method.
    pub method: Method,
    /// Layouts wanted.
    pub count: usize,
    /// Backend of the exact model.
    pub solver: SolverKind,
    /// Seconds for the whole command (configuration spaces, both methods, the checks).
    pub time_limit: f64,
    /// Threads for the backend.
    pub threads: Option<u32>,
    /// Output directory (nothing written when `None`).
    pub out: Option<PathBuf>,
    /// Look for conflicting edges when the level is infeasible.
    pub explain: bool,
    /// Seed of the annealer.
    pub seed: u64,
    /// Export the first layout as a mesh and a network spec into `out` ([`bridge`]).
    pub export: Option<bridge::BridgeOptions>,
    /// Seeds to run the annealer with (`seed`, `seed + 1`, …); above 1, a summary over them.
    pub seeds: usize,
}

/// The overall answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Layouts found (each validated).
    Feasible,
    /// Proven that none exists (the exact model only).
    Infeasible,
    /// Neither.
    Unknown,
}

impl Status {
    /// The name `level.json` gives it.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Feasible => "feasible",
            Status::Infeasible => "infeasible",
            Status::Unknown => "unknown",
        }
    }
}

impl Serialize for Status {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(self.as_str())
    }
}

/// Everything `netspec level` found.
#[derive(Clone, Debug, Serialize)]
pub struct LevelOutcome {
    /// The answer.
    pub status: Status,
    /// The method(s) run.
    pub method: Method,
    /// Door width.
    pub door_width: f64,
    /// Layouts, distinct, each validated.
    pub layouts: Vec<Layout>,
    /// Seconds to build the configuration spaces.
    pub cspace_time: f64,
    /// The annealer, when run.
    pub anneal: Option<anneal::AnnealReport>,
    /// The exact search, when run.
    pub milp: Option<exact::ExactReport>,
    /// The annealer over seeds, when more than one was asked for (`summary.json`).
    #[serde(skip)]
    pub seeds: Option<seeds::SeedsSummary>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Reads the level file, lays it out with the chosen method, validates every layout and
/// writes the outputs.
pub fn run(req: &LevelRequest) -> Result<LevelOutcome, LevelError> {
    let level = Level::read(&req.spec)?;
    if let Some(opts) = &req.export {
        // A bad export is refused before the solve, not after it.
        export_dir(req)?;
        opts.check(&level)
            .map_err(|e| LevelError::InFile { path: req.spec.display().to_string(), source: Box::new(e) })?;
    }
    let mut outcome = solve_level(&level, req)?;
    if let Some(dir) = &req.out {
        outcome.files = output::write(dir, &level, &outcome)?;
    }
    if let Some(opts) = &req.export {
        outcome.files.extend(export(req, &level, &outcome, opts)?);
    }
    Ok(outcome)
}

/// The export of the first layout into the output directory.
fn export(
    req: &LevelRequest,
    level: &Level,
    outcome: &LevelOutcome,
    opts: &bridge::BridgeOptions,
) -> Result<Vec<PathBuf>, LevelError> {
    let path = req.spec.display().to_string();
    let dir = export_dir(req)?;
    let Some(layout) = outcome.layouts.first() else {
        return Err(LevelError::NoLayout { path, status: outcome.status.as_str().into() });
    };
    let name = req.spec.file_stem().map_or("level".into(), |s| s.to_string_lossy().into_owned());
    let b = bridge::bridge(level, layout, &name, opts).map_err(|e| LevelError::InFile { path, source: Box::new(e) })?;
    bridge::write(dir, &b)
}

/// The output directory an export writes into.
fn export_dir(req: &LevelRequest) -> Result<&PathBuf, LevelError> {
    req.out
        .as_ref()
        .ok_or_else(|| LevelError::Field { field: "out".into(), reason: "the export needs an output directory".into() })
}

/// Lays out a checked level (no files). `req.time_limit` bounds the whole call: the
/// configuration spaces, both methods and the checks.
pub fn solve_level(level: &Level, req: &LevelRequest) -> Result<LevelOutcome, LevelError> {
    let t0 = Instant::now();
    check_request(level, req)?;
    let cs = cspace::CSpaces::new(level);
    let cspace_time = t0.elapsed().as_secs_f64();
    let count = req.count.max(1);
    let left = || (req.time_limit - t0.elapsed().as_secs_f64()).max(0.0);
    let anneal_opts = |stop: Option<Interrupt>| anneal::AnnealOptions {
        seed: req.seed,
        count,
        time_limit: left(),
        stop,
        ..Default::default()
    };
    let exact_opts = |interrupt: Option<Interrupt>| exact::ExactOptions {
        solver: req.solver,
        time_limit: left(),
        count,
        threads: req.threads,
        explain: req.explain,
        interrupt,
    };
    let mut summary = None;
    let (annealed, milp) = match req.method {
        Method::Anneal => {
            let o = anneal_opts(None);
            let a = if req.seeds > 1 {
                let (first, s) = seeds::over_seeds(level, &cs, &o, req.seeds);
                summary = Some(s);
                first
            } else {
                anneal::anneal(level, &cs, &o)
            };
            (Some(a), None)
        }
        Method::Milp => (None, Some(exact::solve(level, &cs, &exact_opts(None), &[])?)),
        Method::Both if req.seeds > 1 => {
            let (first, s) = seeds::over_seeds(level, &cs, &anneal_opts(None), req.seeds);
            summary = Some(s);
            (Some(first), None)
        }
        Method::Both => {
            let (a, m) = race(level, &cs, count, anneal_opts(None), exact_opts(None));
            (Some(a), Some(m?))
        }
    };
    let mut layouts: Vec<Layout> = annealed.as_ref().map(|a| a.layouts.clone()).unwrap_or_default();
    if let Some(m) = &milp {
        for l in &m.layouts {
            if layouts.len() < count && !layouts.contains(l) {
                layouts.push(l.clone());
            }
        }
    }
    let status = match (&milp, layouts.is_empty()) {
        (_, false) => Status::Feasible,
        (Some(m), true) if m.status == exact::ExactStatus::Infeasible => Status::Infeasible,
        _ => Status::Unknown,
    };
    Ok(LevelOutcome {
        status,
        method: req.method,
        door_width: level.door_width,
        layouts,
        cspace_time,
        anneal: annealed,
        milp,
        seeds: summary,
        files: Vec::new(),
    })
}

/// Checks what the methods need before anything runs: a planar graph for the annealer, seeds
/// for the annealer only, and a level small enough to be laid out at all.
fn check_request(level: &Level, req: &LevelRequest) -> Result<(), LevelError> {
    if req.method != Method::Milp && !level.is_planar() {
        return Err(LevelError::Field {
            field: "edge".into(),
            reason: format!(
                "the graph is not planar ({} nodes, {} edges), and the annealer lays out planar graphs only \
                 (use --method milp)",
                level.nodes.len(),
                level.edges.len()
            ),
        });
    }
    if req.seeds > 1 && req.method == Method::Milp {
        return Err(LevelError::Field {
            field: "--seeds".into(),
            reason: "seeds are the annealer's: use --method anneal or both".into(),
        });
    }
    if level.nodes.len() > MAX_NODES {
        return Err(LevelError::Field {
            field: "node".into(),
            reason: format!(
                "{} nodes: netspec lays out levels of at most {MAX_NODES} nodes (the configuration spaces and \
                 the checks grow with the square of the block shapes and the nodes near each other)",
                level.nodes.len()
            ),
        });
    }
    let estimate = placement_estimate(level.nodes.len());
    if req.method != Method::Milp && estimate > req.time_limit {
        return Err(LevelError::Field {
            field: "--time-limit".into(),
            reason: format!(
                "{} nodes take about {estimate:.0} s to place once (each placement is checked against every \
                 block placed before it: {PLACEMENT_SECONDS:e} s × nodes², measured on 2 cores), more than the \
                 {} s limit; give a longer --time-limit",
                level.nodes.len(),
                req.time_limit
            ),
        });
    }
    Ok(())
}

/// The most nodes a level may have.
pub const MAX_NODES: usize = 20_000;

/// Seconds per squared node count the annealer's exact placement takes, at least (a path of
/// 5,000 unit squares is placed in 1.6 s, of 20,000 in 23 s).
pub const PLACEMENT_SECONDS: f64 = 6e-8;

/// The least time the annealer needs to place `nodes` nodes once.
pub fn placement_estimate(nodes: usize) -> f64 {
    PLACEMENT_SECONDS * (nodes as f64).powi(2)
}

/// `--method both`: the annealer and the exact search side by side on two threads; whichever
/// settles the question first (the layouts wanted, or a proof that none exists) stops the
/// other.
fn race(
    level: &Level,
    cs: &cspace::CSpaces,
    count: usize,
    mut ao: anneal::AnnealOptions,
    mut eo: exact::ExactOptions,
) -> (anneal::AnnealReport, Result<exact::ExactReport, LevelError>) {
    let (stop_anneal, stop_exact) = (Interrupt::new(), Interrupt::new());
    ao.stop = Some(stop_anneal.clone());
    eo.interrupt = Some(stop_exact.clone());
    std::thread::scope(|sc| {
        let annealer = sc.spawn(|| {
            let r = anneal::anneal(level, cs, &ao);
            if r.layouts.len() >= count {
                stop_exact.trigger();
            }
            r
        });
        let m = exact::solve(level, cs, &eo, &[]);
        let settled =
            m.as_ref().map_or(true, |m| m.status == exact::ExactStatus::Infeasible || m.layouts.len() >= count);
        if settled {
            stop_anneal.trigger();
        }
        let a =
            annealer.join().unwrap_or_else(|_| anneal::AnnealReport { stopped: "failed".into(), ..Default::default() });
        (a, m)
    })
}
