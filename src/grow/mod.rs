//! Road networks grown by traffic (Beneš, Wilkie & Křivánek 2014, "Procedural Modelling of
//! Urban Road Networks"): settlements in a landscape with terrain and water, joined to
//! neighbouring cities by trade routes; every time step minor streets grow around growth
//! nuclei, a simple traffic model loads the routes, and where a pair's routes are saturated a
//! new or widened major road is built along a turn-penalised shortest path. docs/grow.md
//! describes the model, the context file and the outputs.
//!
//! One concern per file: [`context`] (the context file), [`terrain`] (heights and classes),
//! [`lattice`] (the implicit pathfinding graph), [`paths`] (shortest paths), [`roads`] (existing
//! roads, placed nuclei and the centre), [`spaces`] (the graphs searched), [`graph`] (the planar road graph), [`blocks`] (faces and the built-up area),
//! [`minor`] (minor-road growth), [`traffic`] (trade routes and capacities), [`step`] (the
//! simulation), [`output`] (files), [`validate`] (an independent check of the output),
//! [`window`] (a window as a city spec and trade flows); [`run`] is the entry point of
//! `netspec grow`.

pub mod blocks;
pub mod context;
pub mod graph;
pub mod lattice;
pub mod minor;
pub mod output;
pub mod paths;
pub mod roads;
pub mod spaces;
pub mod step;
pub mod terrain;
pub mod traffic;
pub mod validate;
pub mod window;

use crate::geometry::P;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why growing failed.
#[derive(Debug, thiserror::Error)]
pub enum GrowError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The context is not TOML.
    #[error("{}: {message}", path.display())]
    Toml {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// A field of the context is wrong.
    #[error("{}: `{field}`: {message}", path.display())]
    Field {
        /// The file.
        path: PathBuf,
        /// The field (`water[1].river`).
        field: String,
        /// What is wrong.
        message: String,
    },
    /// Two cities have no path between them over land, water, harbours and bridges.
    #[error("no path between the cities at ({:.0}, {:.0}) and ({:.0}, {:.0}): water, forbidden areas or slopes cut the map", from[0], from[1], to[0], to[1])]
    Unreachable {
        /// One city.
        from: P,
        /// The other.
        to: P,
    },
    /// A picture could not be made.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// The WGS 84 projection failed.
    #[error(transparent)]
    Site(#[from] crate::geometry::site::SiteError),
    /// The context is a directory (a grown network) and no window of it was asked for.
    #[error("{} is a directory: give a context file to grow, or --window to window a grown network", path.display())]
    NotAContext {
        /// The directory.
        path: PathBuf,
    },
}

impl GrowError {
    /// The same error, naming `path` as its file.
    pub fn in_file(self, path: &Path) -> GrowError {
        match self {
            GrowError::Toml { message, .. } => GrowError::Toml { path: path.to_path_buf(), message },
            GrowError::Field { field, message, .. } => GrowError::Field { path: path.to_path_buf(), field, message },
            e => e,
        }
    }

    /// The field an error is about, if any.
    pub fn field(&self) -> Option<&str> {
        match self {
            GrowError::Field { field, .. } => Some(field),
            _ => None,
        }
    }
}

/// What `netspec grow` is asked to do.
#[derive(Clone, Debug, PartialEq)]
pub struct GrowRequest {
    /// The context file.
    pub context: PathBuf,
    /// The output directory.
    pub out: PathBuf,
    /// Overrides the context's seed.
    pub seed: Option<u64>,
    /// Overrides the context's step count.
    pub steps: Option<u32>,
    /// Writes `step-NNN.svg` every K steps (and at step 0), and `steps.svg`/`.png` with them
    /// side by side.
    pub every: Option<u32>,
    /// Draws every minor road, dead-end stubs too.
    pub all_streets: bool,
    /// Writes `gallery.svg`/`.png`: the initial networks of this many seeds from the run's seed
    /// on (Fig. 10a).
    pub gallery: Option<u32>,
    /// A request to stop early: once triggered, no further step is run; the network grown so
    /// far is checked and written as at the end.
    pub interrupt: Option<crate::solvers::Interrupt>,
}

/// What a `netspec grow` request's context is.
#[derive(Clone, Debug, PartialEq)]
pub enum Source {
    /// A context file: grow it.
    Context,
    /// A grown output directory: only window it.
    Grown(PathBuf),
}

impl GrowRequest {
    /// Whether the context is a file to grow or a grown output directory to window; a
    /// directory without a `window` is refused ([`GrowError::NotAContext`]).
    pub fn source(&self, window: Option<[f64; 4]>) -> Result<Source, GrowError> {
        match (self.context.is_dir(), window) {
            (false, _) => Ok(Source::Context),
            (true, Some(_)) => Ok(Source::Grown(self.context.clone())),
            (true, None) => Err(GrowError::NotAContext { path: self.context.clone() }),
        }
    }

    /// The name the window's city spec is given: the output directory's name (`window` if it
    /// has none).
    pub fn window_name(&self) -> String {
        self.out.file_name().map_or_else(|| "window".to_string(), |n| n.to_string_lossy().into_owned())
    }
}

/// What a run did.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct GrowSummary {
    /// The seed used.
    pub seed: u64,
    /// The last row of the series.
    pub last: step::StepStats,
    /// Seconds for the initial network.
    pub init_seconds: f64,
    /// Seconds for the time steps.
    pub step_seconds: f64,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// What the independent check ([`validate`]) found in the final network, as written to
    /// `network.json`'s `violations` (empty when it is valid).
    pub violations: Vec<validate::Violation>,
    /// The snapshot steps (`--every`) whose network the check found violations in, with their
    /// counts.
    pub snapshot_violations: Vec<(u32, usize)>,
}

/// The independent check of the network `network.json` would hold now.
fn check(sim: &step::Sim) -> Vec<validate::Violation> {
    validate::validate(&validate::Network::of(sim), &sim.ctx)
}

/// `gallery.svg`/`.png`: the initial networks of seeds `seed, seed + 1, …` (`n` of them) on the
/// terrain of `seed`.
fn write_gallery(ctx: &context::Context, seed: u64, n: u32, req: &GrowRequest) -> Result<Vec<PathBuf>, GrowError> {
    let mut scenes = Vec::new();
    for k in 0..n as u64 {
        let sim = step::Sim::with_terrain_seed(ctx, seed + k, seed).map_err(|e| e.in_file(&req.context))?;
        let mut scene = output::scene(&sim, req.all_streets);
        let r = &sim.series[0];
        scene.caption = format!(
            "seed {}: μ {:.2}, {:.1} km of major road, {} bridges, {} ports",
            seed + k,
            sim.mu,
            r.major_km,
            r.bridges,
            r.ports
        );
        scenes.push(scene);
    }
    output::write_strip(&req.out, "gallery", &scenes)
}

/// Runs `netspec grow`: reads the context, builds the initial network, runs the steps (calling
/// `progress(step, steps)` after each), checks the network at every snapshot and at the end
/// ([`validate`]), and writes the outputs into the request's directory. Violations are not an
/// error: they are written to `network.json` and returned in the summary. A triggered
/// interrupt ends the steps early (the summary's `last.step` says how far it grew).
pub fn run(req: &GrowRequest, progress: &mut dyn FnMut(u32, u32)) -> Result<GrowSummary, GrowError> {
    let ctx = context::Context::load(&req.context)?;
    let seed = req.seed.unwrap_or(ctx.seed);
    let steps = req.steps.unwrap_or(ctx.steps);
    let t0 = Instant::now();
    let mut sim = step::Sim::new(&ctx, seed).map_err(|e| e.in_file(&req.context))?;
    let init_seconds = t0.elapsed().as_secs_f64();
    std::fs::create_dir_all(&req.out).map_err(|source| GrowError::Io { path: req.out.clone(), source })?;
    let mut files = Vec::new();
    let every = req.every.filter(|&k| k > 0);
    let mut snapshot_violations = Vec::new();
    let mut strip = Vec::new();
    let mut snapshot = |sim: &step::Sim, files: &mut Vec<PathBuf>| -> Result<(), GrowError> {
        let scene = output::scene(sim, req.all_streets);
        files.push(output::write_snapshot(&req.out, sim.step, &scene)?);
        strip.push(scene);
        let found = check(sim).len();
        if found > 0 {
            snapshot_violations.push((sim.step, found));
        }
        Ok(())
    };
    if every.is_some() {
        snapshot(&sim, &mut files)?;
    }
    progress(0, steps);
    let t1 = Instant::now();
    for k in 1..=steps {
        if req.interrupt.as_ref().is_some_and(crate::solvers::Interrupt::is_triggered) {
            break;
        }
        sim.step();
        if every.is_some_and(|e| k % e == 0) {
            snapshot(&sim, &mut files)?;
        }
        progress(k, steps);
    }
    let step_seconds = t1.elapsed().as_secs_f64();
    let violations = check(&sim);
    files.extend(output::write_all(&req.out, &sim, &violations, req.all_streets)?);
    if !strip.is_empty() {
        files.extend(output::write_strip(&req.out, "steps", &strip)?);
    }
    if let Some(n) = req.gallery.filter(|&n| n > 0) {
        files.extend(write_gallery(&ctx, seed, n, req)?);
    }
    Ok(GrowSummary {
        seed,
        last: sim.series.last().expect("step 0 is always there").clone(),
        init_seconds,
        step_seconds,
        files,
        violations,
        snapshot_violations,
    })
}

/// `x` rounded to the millimetre, as every length and coordinate in the files.
pub(crate) fn mm(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

/// The node ids written: nodes with at least one segment, numbered in order.
pub(crate) fn node_ids(sim: &step::Sim) -> Vec<Option<usize>> {
    let mut ids = vec![None; sim.graph.nodes.len()];
    let mut next = 0;
    for (n, adj) in sim.graph.adj.iter().enumerate() {
        if !adj.is_empty() {
            ids[n] = Some(next);
            next += 1;
        }
    }
    ids
}
