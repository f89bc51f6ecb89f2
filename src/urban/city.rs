//! Running a city: sub-regions from the planar arrangement, the level hierarchy per sub-region
//! (each level one network IP), in parallel under a thread budget, with every finished level
//! written to disk at once so that an interrupted run resumes without solving it again.

use super::spec::{CitySpec, CitySpecErrorKind, LevelSpec};
use crate::geometry::planar::{self, Region};
use crate::mesh::{self, Mesh};
use crate::pipeline::settings::{resolve, Origin, Settings, SettingsError};
use crate::pipeline::{self, DesignResult, Method};
use crate::solvers::{Interrupt, ProgressSink, SolveOptions, SolverKind};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// Why a city could not be run at all (a sub-region's failure is an report, not this).
#[derive(Debug, thiserror::Error)]
pub enum CityError {
    /// The spec is unusable.
    #[error(transparent)]
    Spec(#[from] CitySpecErrorKind),
    /// The domain and major roads do not form sub-regions.
    #[error("the domain and major roads: {0}")]
    Arrangement(String),
    /// Writing outputs failed.
    #[error("{path}: {source}")]
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A level's saved state (`state.json`) is unreadable.
    #[error("{}: {message}", path.display())]
    State {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The thread pool could not be created.
    #[error("thread pool: {0}")]
    Threads(String),
    /// The streets could not be placed on the Earth (`geo_origin` is no WGS 84 position).
    #[error("{}: {source}", path.display())]
    GeoJson {
        /// The file.
        path: PathBuf,
        /// Why.
        source: crate::geometry::site::SiteError,
    },
}

fn io_err(path: &Path) -> impl FnOnce(std::io::Error) -> CityError + '_ {
    move |source| CityError::Io { path: path.to_path_buf(), source }
}

/// How to run a city.
#[derive(Clone)]
pub struct CityRunOptions {
    /// The backend.
    pub solver: SolverKind,
    /// Overrides every level's time limit (seconds).
    pub time_limit: Option<f64>,
    /// Total thread budget (sub-regions at once = `threads / threads_per_solve`).
    pub threads: u32,
    /// Threads per solve.
    pub threads_per_solve: u32,
    /// Relative gap.
    pub gap: Option<f64>,
    /// Seed.
    pub seed: Option<u64>,
    /// Reuse finished levels found in the output directory (same inputs only).
    pub resume: bool,
    /// Receives events as the run goes (from worker threads).
    pub observer: Option<CityObserver>,
    /// A request to stop (Ctrl-C): running levels stop and keep their best network, levels
    /// not yet started are skipped; finished levels stay on disk for a rerun to reuse.
    pub interrupt: Option<Interrupt>,
    /// Run one level only, as a cluster job does: `(region, level)`; the region's earlier levels
    /// are reused from their saved state (solved first only when it is missing).
    pub only: Option<(usize, u8)>,
    /// Solve nothing: levels without a saved state of the same inputs are skipped (the
    /// assembly after cluster jobs).
    pub reuse_only: bool,
    /// When the whole city's time runs out: no level starts after it, and a running level's
    /// limit ends at it (it keeps its best network). `None`: no overall limit.
    pub deadline: Option<Instant>,
}

/// A receiver of [`CityEvent`]s, called from the worker threads.
pub type CityObserver = Arc<dyn Fn(&CityEvent) + Send + Sync>;

impl CityRunOptions {
    /// Options from the command line's settings over a city spec's `[solver]` section (through
    /// [`crate::pipeline::settings::resolve`], errors naming the flag or the file and field):
    /// `flags.time_limit` replaces every level's own; `threads` and `threads_per_solve` replace
    /// the spec's budget; a city whose level meshes could exceed `max_cells` cells is refused.
    pub fn resolve(
        spec: &CitySpec,
        spec_path: &Path,
        flags: &Settings,
        threads: Option<u32>,
        threads_per_solve: Option<u32>,
        max_cells: usize,
    ) -> Result<CityRunOptions, SettingsError> {
        let own = Settings {
            method: spec.solver.name.map(Method::Milp),
            gap: spec.solver.gap,
            seed: spec.solver.seed,
            ..Settings::default()
        };
        let (method, o) = resolve(&[(Origin::Flags, flags.clone()), (Origin::City(spec_path.to_path_buf()), own)])?;
        let solver = method.milp().ok_or_else(|| SettingsError {
            place: "--solver".into(),
            reason: format!("`{method}` is a design search: a city's levels need a MILP backend"),
        })?;
        let cells = spec.estimated_cells();
        if cells > max_cells as f64 {
            return Err(SettingsError {
                place: format!("{}: mesh.spacing", spec_path.display()),
                reason: format!(
                    "{} gives up to about {cells:.0} cells per level mesh, above the limit of {max_cells} (raise it with --max-cells if the machine can take it)",
                    spec.mesh.spacing
                ),
            });
        }
        for (flag, v) in [("--threads", threads), ("--threads-per-solve", threads_per_solve)] {
            if v == Some(0) {
                return Err(SettingsError { place: flag.into(), reason: "must be ≥ 1, got 0".into() });
            }
        }
        Ok(CityRunOptions {
            solver,
            time_limit: o.time_limit,
            threads: threads.unwrap_or(spec.solver.threads).max(1),
            threads_per_solve: threads_per_solve.unwrap_or(spec.solver.threads_per_solve).max(1),
            gap: o.rel_gap,
            seed: o.seed,
            resume: true,
            observer: None,
            interrupt: None,
            only: None,
            reuse_only: false,
            deadline: None,
        })
    }

    /// Options from a city spec's `[solver]` section, with the embedded default backend.
    pub fn from_spec(spec: &CitySpec) -> Option<CityRunOptions> {
        Some(CityRunOptions {
            solver: spec.solver.name.or_else(SolverKind::default_kind)?,
            time_limit: None,
            threads: spec.solver.threads,
            threads_per_solve: spec.solver.threads_per_solve,
            gap: spec.solver.gap,
            seed: spec.solver.seed,
            resume: true,
            observer: None,
            interrupt: None,
            only: None,
            reuse_only: false,
            deadline: None,
        })
    }
}

/// What happens during a run.
#[derive(Clone, Debug)]
pub enum CityEvent {
    /// A level of a region starts solving.
    LevelStarted {
        /// Region index.
        region: usize,
        /// Level.
        level: u8,
        /// Its time limit.
        time_limit: Option<f64>,
    },
    /// Solver progress (backends that report it).
    LevelProgress {
        /// Region index.
        region: usize,
        /// Level.
        level: u8,
        /// The report.
        progress: crate::solvers::Progress,
    },
    /// A level ended (solved, reused, failed or skipped).
    LevelDone {
        /// Region index.
        region: usize,
        /// The report.
        report: LevelReport,
    },
}

/// How one level of one region ended.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LevelReport {
    /// The level.
    pub level: u8,
    /// `solved` (a network was found), `reused` (from an earlier run), `no_network`, `error`
    /// or `skipped`.
    pub state: String,
    /// The solver's termination label (`optimal`, `limit(time)`, `infeasible`, …).
    pub termination: Option<String>,
    /// Objective.
    pub objective: Option<f64>,
    /// Dual bound.
    pub dual_bound: Option<f64>,
    /// netspec's gap.
    pub gap: Option<f64>,
    /// Solver time, seconds.
    pub solver_time: Option<f64>,
    /// Wall time of the solve call, seconds.
    pub wall_time: Option<f64>,
    /// The independent validity verdict.
    pub valid: Option<bool>,
    /// Mesh size at this level: vertices, edges, faces.
    pub mesh: Option<[usize; 3]>,
    /// MILP variables, rows, nonzeros.
    pub model: Option<[usize; 3]>,
    /// Roads added at this level (mesh edges).
    pub new_edges: Option<usize>,
    /// Why the level failed or was skipped.
    pub message: Option<String>,
}

impl LevelReport {
    fn bare(level: u8, state: &str, message: impl Into<String>) -> LevelReport {
        LevelReport {
            level,
            state: state.into(),
            termination: None,
            objective: None,
            dual_bound: None,
            gap: None,
            solver_time: None,
            wall_time: None,
            valid: None,
            mesh: None,
            model: None,
            new_edges: None,
            message: Some(message.into()),
        }
    }

    /// Whether this level produced a network (solved now or reused).
    pub fn has_network(&self) -> bool {
        self.state == "solved" || self.state == "reused"
    }

    /// Whether the solver proved this level's network optimal.
    pub fn proven_optimal(&self) -> bool {
        self.has_network() && self.termination.as_deref() == Some("optimal")
    }

    /// The level in words that say apart why the solver stopped and whether there is a
    /// network: `optimal`, `limit(time), network found (gap 100 %)`, `limit(time), no network`,
    /// `reused: optimal`, `error: …`, `skipped: …`.
    pub fn verdict(&self) -> String {
        let stopped = self.termination.clone().unwrap_or_default();
        let found = |s: &str| match self.gap {
            _ if s == "optimal" => "optimal".to_string(),
            Some(g) => format!("{s}, network found (gap {})", crate::solvers::percent(g)),
            None => format!("{s}, network found"),
        };
        match self.state.as_str() {
            "solved" => found(&stopped),
            "reused" => format!("reused: {}", found(&stopped)),
            "no_network" => format!("{stopped}, no network"),
            other => format!("{other}: {}", self.message.clone().unwrap_or_default()),
        }
    }
}

/// One line over every level of every region: how many have a network, how many of those are
/// proven optimal, and how far from it the others stopped: `3/3 levels with a network (1 proven
/// optimal; 2 stopped early, gap up to 100 %)`.
pub fn levels_summary(regions: &[RegionReport]) -> String {
    let levels: Vec<&LevelReport> = regions.iter().flat_map(|r| &r.levels).collect();
    let with = levels.iter().filter(|l| l.has_network()).count();
    let optimal = levels.iter().filter(|l| l.proven_optimal()).count();
    let early: Vec<&&LevelReport> = levels.iter().filter(|l| l.has_network() && !l.proven_optimal()).collect();
    let mut s = format!("{with}/{} levels with a network ({optimal} proven optimal", levels.len());
    if !early.is_empty() {
        let worst = early.iter().filter_map(|l| l.gap).fold(None, |m: Option<f64>, g| Some(m.map_or(g, |m| m.max(g))));
        s.push_str(&format!("; {} stopped early", early.len()));
        if let Some(g) = worst {
            s.push_str(&format!(", gap up to {}", crate::solvers::percent(g)));
        }
    }
    s.push(')');
    s
}

/// A region's roads after its last successful level: the mesh and each edge's level
/// (0: no road; 1: the sub-region's boundary, a major road; 2–4: the level that chose it).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionRoads {
    /// The mesh of the last level.
    pub mesh: Mesh,
    /// Level per edge.
    pub edge_level: Vec<u8>,
    /// Per vertex: whether streets may join the major road there (a sink at the last level; on
    /// a `wall` boundary only the given sinks). Empty until a level has found a network.
    pub joins_major: Vec<bool>,
}

impl RegionRoads {
    /// A sub-region's mesh before any level: its boundary edges are level 1, nothing else is a
    /// road.
    pub fn boundary_only(mesh: Mesh) -> RegionRoads {
        let edge_level = mesh.edges().map(|e| u8::from(mesh.is_boundary_edge(e))).collect();
        RegionRoads { mesh, edge_level, joins_major: Vec::new() }
    }
}

/// Everything about one sub-region.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RegionReport {
    /// Index (regions sorted by their lowest, then leftmost corner).
    pub index: usize,
    /// Name (from `[[region]]`, or `region-N`).
    pub name: String,
    /// Which `[[region]]` entry applies, if any.
    pub spec_entry: Option<usize>,
    /// The sub-region polygon.
    pub outer: Vec<[f64; 2]>,
    /// Its holes.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Area in model units².
    pub area: f64,
    /// A point inside (for labels).
    pub label_point: [f64; 2],
    /// One entry per level run (or attempted).
    pub levels: Vec<LevelReport>,
    /// The roads after the last level with a network (`None` if the region could not be
    /// meshed). Not in `city.json`: each level's `state.json` has them.
    #[serde(skip)]
    pub roads: Option<RegionRoads>,
}

/// What one finished level leaves on disk (`state.json`): enough to go on without solving again.
#[derive(Clone, Debug, Serialize, Deserialize)]
struct LevelState {
    /// Digest of every input of this level.
    fingerprint: String,
    report: LevelReport,
    roads: Option<RegionRoads>,
}

/// The roads a finished run left in a region ([`RegionReport::roads`], which `city.json`
/// omits), read back from the output directory `out`: those of the `state.json` of its last
/// level with a network, or the sub-region's boundary alone (meshed again, as the run did) when
/// no level found one. `None` if the sub-region cannot be meshed.
pub fn saved_roads(spec: &CitySpec, out: &Path, region: &RegionReport) -> Result<Option<RegionRoads>, CityError> {
    if let Some(last) = region.levels.iter().rev().find(|l| l.has_network()) {
        let path = region_dir(out, region.index, &region.name).join(format!("L{}", last.level)).join("state.json");
        let text = crate::io::read_utf8(&path).map_err(io_err(&path))?;
        let state: LevelState =
            serde_json::from_str(&text).map_err(|e| CityError::State { path: path.clone(), message: e.to_string() })?;
        return match state.roads {
            Some(r) => Ok(Some(r)),
            None => Err(CityError::State {
                path,
                message: format!("level {} is recorded with a network but has no roads", last.level),
            }),
        };
    }
    let origin = spec.domain_bounds().0;
    Ok(mesh::clipped_grid_on_lattice(&region.outer, &region.holes, spec.mesh.spacing, origin)
        .ok()
        .map(RegionRoads::boundary_only))
}

/// The sub-regions of a city, each matched to its `[[region]]` entry.
pub fn regions(spec: &CitySpec) -> Result<Vec<(Region, Option<usize>)>, CityError> {
    let roads: Vec<Vec<[f64; 2]>> = spec.roads.iter().map(|r| r.points.clone()).collect();
    let tol = spec.mesh.spacing * 1e-6;
    let arr =
        planar::arrangement(&spec.domain.outer, &roads, tol).map_err(|e| CityError::Arrangement(e.to_string()))?;
    let mut entries: Vec<Option<usize>> = vec![None; arr.regions.len()];
    for (i, r) in spec.regions.iter().enumerate() {
        let hit = arr.regions.iter().position(|reg| point_in_region(r.at, reg));
        let Some(k) = hit else {
            return Err(CitySpecErrorKind::Field {
                field: format!("region[{i}].at"),
                message: format!("point {:?} is in no sub-region", r.at),
            }
            .into());
        };
        if let Some(j) = entries[k] {
            return Err(CitySpecErrorKind::Field {
                field: format!("region[{i}].at"),
                message: format!("names the same sub-region as region[{j}]"),
            }
            .into());
        }
        entries[k] = Some(i);
    }
    Ok(arr.regions.into_iter().zip(entries).collect())
}

/// Whether `p` is inside a sub-region: in its outer ring and in none of its holes.
pub fn point_in_region(p: [f64; 2], r: &Region) -> bool {
    crate::geometry::ring_contains(&r.outer, p) && !r.holes.iter().any(|h| crate::geometry::ring_contains(h, p))
}

/// The directory of one region's files.
pub fn region_dir(out: &Path, index: usize, name: &str) -> PathBuf {
    let safe: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '-' || c == '_' { c } else { '_' }).collect();
    out.join("regions").join(format!("{index:02}-{safe}"))
}

fn write_atomic(path: &Path, text: &str) -> Result<(), CityError> {
    crate::io::write_atomic(path, text).map_err(io_err(path))
}

/// Runs every sub-region's levels (in parallel) and returns the reports in region order;
/// `regs` are the city's sub-regions from [`regions`].
/// Finished levels are written under `out/regions/` as they end.
pub fn run_regions(
    spec: &CitySpec,
    regs: Vec<(Region, Option<usize>)>,
    out: &Path,
    opts: &CityRunOptions,
) -> Result<Vec<RegionReport>, CityError> {
    // One lattice for the whole city, through the domain's lower-left corner.
    let origin = spec.domain_bounds().0;
    let workers = (opts.threads / opts.threads_per_solve.max(1)).max(1) as usize;
    let pool =
        rayon::ThreadPoolBuilder::new().num_threads(workers).build().map_err(|e| CityError::Threads(e.to_string()))?;
    use rayon::prelude::*;
    pool.install(|| {
        regs.into_par_iter()
            .enumerate()
            .filter(|(i, _)| opts.only.is_none_or(|(r, _)| r == *i))
            .map(|(i, (reg, entry))| run_region(spec, out, opts, origin, i, reg, entry))
            .collect()
    })
}

#[allow(clippy::too_many_arguments)]
fn run_region(
    spec: &CitySpec,
    out: &Path,
    opts: &CityRunOptions,
    origin: [f64; 2],
    index: usize,
    reg: Region,
    entry: Option<usize>,
) -> Result<RegionReport, CityError> {
    let name = spec.region_name(index, entry);
    let dir = region_dir(out, index, &name);
    std::fs::create_dir_all(&dir).map_err(io_err(&dir))?;
    let mut report = RegionReport {
        index,
        name: name.clone(),
        spec_entry: entry,
        outer: reg.outer.clone(),
        holes: reg.holes.clone(),
        area: reg.area,
        label_point: reg.label_point,
        levels: Vec::new(),
        roads: None,
    };
    let emit = |e: CityEvent| {
        if let Some(o) = &opts.observer {
            o(&e)
        }
    };
    let levels = spec.region_levels(entry);
    let mesh0 = match mesh::clipped_grid_on_lattice(&reg.outer, &reg.holes, spec.mesh.spacing, origin) {
        Ok(m) => m,
        Err(e) => {
            for &n in &levels {
                let o = LevelReport::bare(
                    n,
                    "error",
                    format!("the sub-region cannot be meshed at spacing {}: {e}", spec.mesh.spacing),
                );
                emit(CityEvent::LevelDone { region: index, report: o.clone() });
                report.levels.push(o);
            }
            return Ok(report);
        }
    };
    let mut roads = RegionRoads::boundary_only(mesh0);
    let mut blocked: Option<String> = None;
    for &n in &levels {
        if opts.only.is_some_and(|(_, last)| n > last) {
            break;
        }
        if blocked.is_none() && opts.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            blocked = Some("interrupted".into());
        }
        if blocked.is_none() && opts.deadline.is_some_and(|d| Instant::now() >= d) {
            blocked = Some("the city's total time limit ran out".into());
        }
        if let Some(why) = &blocked {
            let o = LevelReport::bare(n, "skipped", why.clone());
            emit(CityEvent::LevelDone { region: index, report: o.clone() });
            report.levels.push(o);
            continue;
        }
        let level = spec.level(entry, n)?;
        let (o, next) = run_level(spec, &dir, opts, index, &name, n, &level, &roads, &emit)?;
        emit(CityEvent::LevelDone { region: index, report: o.clone() });
        if let Some(r) = next {
            roads = r;
        } else {
            blocked = Some(format!(
                "level {n} ended without a network ({})",
                o.termination.clone().or(o.message.clone()).unwrap_or_default()
            ));
        }
        if o.termination.as_deref() == Some("interrupted") {
            blocked = Some("interrupted".into());
        }
        report.levels.push(o);
    }
    report.roads = Some(roads);
    Ok(report)
}

/// The solver's limit of a level that started at `started`: what is left of the level's limit and
/// of the city's, less the time kept for the level's outputs ([`crate::run::output_reserve`]).
fn level_solve_limit(started: Instant, limit: Option<f64>, city: Option<Instant>) -> Option<f64> {
    let limit = limit.filter(|t| t.is_finite());
    let own = limit.map(|t| started + std::time::Duration::from_secs_f64(t));
    let end = match (own, city) {
        (Some(a), Some(b)) => a.min(b),
        (a, b) => a.or(b)?,
    };
    let left = end.saturating_duration_since(Instant::now()).as_secs_f64();
    Some((left - crate::run::output_reserve(limit.unwrap_or(left))).max(0.0))
}

/// The input of one level: the mesh (subdivided if asked) with earlier roads, and its spec.
pub struct LevelInput {
    /// The level's mesh and the levels of the roads already on it.
    pub roads: RegionRoads,
    /// The functional spec (earlier levels' roads as `user.existing_edges`).
    pub spec: crate::spec::Spec,
}

/// Prepares level `n` from the previous roads: subdivides when the level asks, and carries
/// every earlier road (level ≥ 2) over as an existing edge whose vertices are sinks.
pub fn level_input(city: &str, region: &str, n: u8, level: &LevelSpec, prev: &RegionRoads) -> LevelInput {
    let roads = if level.subdivide {
        let sub = mesh::subdivide(&prev.mesh);
        let mut edge_level = vec![0u8; sub.mesh.num_edges()];
        for (e, children) in sub.edge_children.iter().enumerate() {
            for c in children {
                edge_level[c.index()] = prev.edge_level[e];
            }
        }
        RegionRoads { mesh: sub.mesh, edge_level, joins_major: Vec::new() }
    } else {
        prev.clone()
    };
    let mut spec =
        level.to_spec(format!("{city}-{region}-L{n}"), format!("city {city}, sub-region {region}, level {n}"));
    for e in roads.mesh.edges() {
        if roads.edge_level[e.index()] >= 2 {
            let (a, b) = roads.mesh.edge_vertices(e);
            spec.user.existing_edges.push([a.0, b.0]);
        }
    }
    LevelInput { roads, spec }
}

#[allow(clippy::too_many_arguments)]
fn run_level(
    city: &CitySpec,
    dir: &Path,
    opts: &CityRunOptions,
    region: usize,
    name: &str,
    n: u8,
    level: &LevelSpec,
    prev: &RegionRoads,
    emit: &dyn Fn(CityEvent),
) -> Result<(LevelReport, Option<RegionRoads>), CityError> {
    // The level's time limit bounds all of its work, from here: input, model, start, solve, outputs.
    let started = Instant::now();
    let mut input = level_input(&city.name, name, n, level, prev);
    input.spec.solver.lns = city.solver.lns;
    let time_limit = opts.time_limit.or(level.time_limit);
    let solve_opts = SolveOptions {
        time_limit,
        rel_gap: opts.gap,
        threads: Some(opts.threads_per_solve),
        seed: opts.seed,
        ..SolveOptions::default()
    };
    let spec_json = serde_json::to_string(&input.spec).expect("specs serialise");
    let mesh_json = serde_json::to_string(&input.roads.mesh).expect("meshes serialise");
    let opts_json = serde_json::to_string(&(opts.solver, &solve_opts)).expect("options serialise");
    let fingerprint = crate::io::digest(&[spec_json.as_bytes(), mesh_json.as_bytes(), opts_json.as_bytes()]);
    let ldir = dir.join(format!("L{n}"));
    let state_path = ldir.join("state.json");
    // A cluster job for a later level reuses this one (its own job solved it).
    if opts.resume || opts.reuse_only || opts.only.is_some_and(|(_, last)| n < last) {
        if let Some(state) =
            std::fs::read_to_string(&state_path).ok().and_then(|t| serde_json::from_str::<LevelState>(&t).ok())
        {
            if state.fingerprint == fingerprint {
                let mut o = state.report;
                // Assembled after cluster jobs, a level keeps the state its job gave it.
                if o.has_network() && !opts.reuse_only {
                    o.state = "reused".into();
                }
                return Ok((o, state.roads));
            }
        }
    }
    if opts.reuse_only {
        return Ok((
            LevelReport::bare(n, "skipped", "no finished state of these inputs (its cluster job did not finish it)"),
            None,
        ));
    }
    std::fs::create_dir_all(&ldir).map_err(io_err(&ldir))?;
    let _ = std::fs::remove_file(&state_path);
    // The level as a standalone instance: `netspec solve L<n>/spec.json` rebuilds the same model.
    write_atomic(&ldir.join("mesh.json"), &mesh_json)?;
    write_atomic(
        &ldir.join("spec.json"),
        &(serde_json::to_string_pretty(&input.spec).expect("specs serialise") + "\n"),
    )?;
    emit(CityEvent::LevelStarted { region, level: n, time_limit });
    let problem = match input.spec.resolve_on_mesh(input.roads.mesh.clone()) {
        Ok(p) => p,
        Err(e) => return Ok((LevelReport::bare(n, "error", format!("level {n} spec: {e}")), None)),
    };
    let nm = pipeline::build(&problem);
    let mut solve_opts = solve_opts;
    solve_opts.time_limit = level_solve_limit(started, time_limit, opts.deadline);
    solve_opts.interrupt = opts.interrupt.clone();
    if opts.observer.is_some() && opts.solver.instance().is_ok_and(|s| s.capabilities().reports_progress) {
        let observer = opts.observer.clone().expect("checked");
        solve_opts.progress = Some(ProgressSink(Arc::new(move |progress| {
            observer(&CityEvent::LevelProgress { region, level: n, progress })
        })));
    }
    // Every level starts from the construction heuristic's design (checked before it is used),
    // and is solved and written like `netspec solve` (result.json, network.svg/png, .geojson).
    // A level that an earlier run left unfinished (killed) goes on from the design it wrote,
    // checked like any start.
    let start = match crate::run::left_design(&ldir).filter(|l| l.network.active.len() == problem.mesh.num_edges()) {
        Some(left) => pipeline::StartFrom::Design { network: left.network, source: left.path.display().to_string() },
        // The start's budget is work (module `heuristics::budget`), from the level's limit as
        // asked, not from what is left of it, so that a seed gives the same start every run.
        None => pipeline::default_start(time_limit.filter(|t| t.is_finite())),
    };
    let run = crate::run::Run {
        method: Method::Milp(opts.solver),
        start,
        options: solve_opts,
        explain: None,
        sol: None,
        deadline: None,
    };
    let res: DesignResult = match crate::run::solve_problem(&problem, &nm, &run, &ldir, &mut |_| {}) {
        Ok(crate::run::Solved { design: Some(r), .. }) => r,
        Ok(_) => unreachable!("a design run gives a design result"),
        Err(e) => return Ok((LevelReport::bare(n, "error", e.to_string()), None)),
    };
    let stats = res.model_stats;
    let mut o = LevelReport {
        level: n,
        state: "no_network".into(),
        termination: Some(res.solve.termination.label()),
        objective: res.solve.objective,
        dual_bound: res.solve.dual_bound,
        gap: res.solve.gap,
        solver_time: res.solve.solver_time,
        wall_time: Some(res.solve.wall_time),
        valid: res.network.as_ref().map(|_| res.validity.valid),
        mesh: Some([problem.mesh.num_vertices(), problem.mesh.num_edges(), problem.mesh.num_faces()]),
        model: Some([stats.vars, stats.rows, stats.nonzeros]),
        new_edges: None,
        message: None,
    };
    let next = res.network.as_ref().map(|net| {
        let mut roads = input.roads.clone();
        let mut added = 0;
        for e in net.active_edges() {
            if roads.edge_level[e.index()] == 0 {
                roads.edge_level[e.index()] = n;
                added += 1;
            }
        }
        roads.joins_major = problem.is_sink.clone();
        o.new_edges = Some(added);
        o.state = "solved".into();
        roads
    });
    if res.solve.termination == crate::solvers::Termination::Limit(crate::solvers::LimitKind::Interrupt) {
        // Not finished: no state, so a rerun solves it again; the levels after it are skipped.
        return Ok((o, next));
    }
    let state = LevelState { fingerprint, report: o.clone(), roads: next.clone() };
    write_atomic(&state_path, &serde_json::to_string(&state).expect("states serialise"))?;
    Ok((o, next))
}
