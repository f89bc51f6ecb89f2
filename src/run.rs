//! Designing from a spec and writing the outputs: the one library entry point behind
//! `netspec solve` ([`solve_spec`]) and every level of `netspec city` ([`solve_problem`]).
//!
//! A run loads and resolves the spec, applies a command-line variant of its formulation,
//! builds the model, optionally exports it or solves its relaxation, then designs — on a MILP
//! backend from a checked MIP start, or by a search — explains an infeasible spec, and writes
//! `result.json`, `network.svg`/`.png`, `network.geojson` and, for game levels, `blocks.dot` into
//! the output folder. What happens on the way is told to the caller as [`Event`]s; printing is
//! the caller's.

use crate::design::picture::network_svg;
use crate::design::Network;
use crate::explain::{conflict_svg, explain, ExplainOptions, Explanation};
use crate::formulations::Formulation;
use crate::pipeline::search::{run_search, SearchMethod};
use crate::pipeline::settings::{resolve, Origin, Settings, SettingsError};
use crate::pipeline::{self, DesignResult, Method, StartFrom, StartReport, Validity};
use crate::render::Caption;
use crate::solvers::lazy::LpBound;
use crate::solvers::{Interrupt, PointSink, ProgressSink, SolveOptions, SolverError, SolverKind, Termination};
use crate::spec::{Problem, Spec, SpecError, Variant};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

pub mod running;
pub use running::{left_design, write_atomic, LeftDesign};

/// Default time limits of the searches, seconds.
const HEURISTIC_SECONDS: f64 = 10.0;
const ANNEAL_SECONDS: f64 = 60.0;
/// The explanation's budget when the command has no time limit, seconds.
const EXPLAIN_SECONDS: f64 = 60.0;

/// How long explaining an infeasible spec may take.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ExplainBudget {
    /// What is left of the command's time limit (60 s without one): the limit bounds the whole
    /// command.
    Remaining,
    /// Its own budget, in seconds from when the explanation starts: it may run past the
    /// command's limit, which the run says up front ([`Event::LimitExtended`]).
    Seconds(f64),
}

/// The time kept from a command's limit for writing its outputs (pictures, GeoJSON, results): a
/// twentieth of the limit, at most 1 s.
pub fn output_reserve(limit: f64) -> f64 {
    (0.05 * limit).min(1.0)
}

/// Why a run could not be made (a finished solve, whatever its termination, is not an error).
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// The spec file is unusable.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// A setting is refused (names the flag, or the file and field).
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The backend could not attempt the solve.
    #[error(transparent)]
    Solver(#[from] SolverError),
    /// A model file could not be written.
    #[error(transparent)]
    File(#[from] crate::io::FileError),
    /// A solution file could not be read or written.
    #[error(transparent)]
    Sol(#[from] crate::io::sol::SolError),
    /// The `--start` file is unusable.
    #[error("{path}: {message}")]
    Start {
        /// The file.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// An output could not be written.
    #[error("writing {path}: {source}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A picture could not be rendered.
    #[error("rendering {path}: {message}")]
    Render {
        /// The picture's file.
        path: PathBuf,
        /// Why.
        message: String,
    },
    /// An option the chosen method cannot honour.
    #[error("{0}")]
    Unsupported(String),
}

/// Where a MILP solve's start comes from.
#[derive(Clone, Debug, Default)]
pub enum StartChoice {
    /// No start.
    Nothing,
    /// The construction heuristic (the default).
    #[default]
    Heuristic,
    /// An earlier `result.json` of the same spec, or a `.sol` point of the model.
    File(PathBuf),
}

/// What [`solve_spec`] is asked to do (the flags of `netspec solve`).
#[derive(Clone, Default)]
pub struct SolveRequest {
    /// The spec file.
    pub spec: PathBuf,
    /// The formulation (and strategy switches) in place of the spec's.
    pub variant: Option<Variant>,
    /// Settings given on the command line (over the spec's `[solver]` section).
    pub flags: Settings,
    /// Output folder (default: [`default_out_dir`] of the spec file).
    pub out: Option<PathBuf>,
    /// Also write the model (`.lp`/`.mps`, by extension).
    pub export: Option<PathBuf>,
    /// Build (and export) without solving.
    pub no_solve: bool,
    /// Solve the LP relaxation (with the recipe's cut rounds) instead of designing.
    pub relax: bool,
    /// Write the solution (or, with `relax`, the LP point) as a `.sol` file.
    pub sol: Option<PathBuf>,
    /// Explaining an infeasible spec, and its budget (`None`: do not explain).
    pub explain: Option<ExplainBudget>,
    /// The MIP start.
    pub start: StartChoice,
    /// A request to stop early, keeping the best design.
    pub interrupt: Option<Interrupt>,
    /// Receives the backend's progress while it solves.
    pub progress: Option<ProgressSink>,
    /// The cap on the mesh's cells (default [`crate::spec::DEFAULT_MAX_CELLS`]).
    pub max_cells: Option<usize>,
    /// Receives the designs found on the way: the checked MIP start, then every improving
    /// incumbent of a backend that reports progress.
    pub incumbents: Option<IncumbentSink>,
}

/// A design found on the way to the answer, as its active edges: the checked MIP start, or a
/// backend's improving incumbent (which the independent checks have not seen yet).
#[derive(Clone, Debug, PartialEq)]
pub struct Incumbent {
    /// Whether each edge of the mesh is active.
    pub active: Vec<bool>,
    /// The objective the solver (or the start's check) gives it.
    pub objective: Option<f64>,
}

/// Receives [`Incumbent`]s, from whichever thread finds them.
#[derive(Clone)]
pub struct IncumbentSink(pub Arc<dyn Fn(Incumbent) + Send + Sync>);

/// The backend's point sink that turns points into [`Incumbent`]s by the formulation's edge
/// variables (an edge without one is active when it is an existing road).
fn point_sink(p: &Problem, f: &Formulation, sink: IncumbentSink) -> PointSink {
    let edges: Vec<Result<usize, bool>> = p
        .mesh
        .edges()
        .map(|e| match f.vars.edge[e.index()] {
            Some(v) => Ok(v.index()),
            None => Err(p.roles[e.index()] == crate::spec::EdgeRole::Existing),
        })
        .collect();
    PointSink(Arc::new(move |objective: f64, x: &[f64]| {
        let active =
            edges.iter().map(|e| e.map_or_else(|fixed| fixed, |i| x.get(i).is_some_and(|&v| v > 0.5))).collect();
        (sink.0)(Incumbent { active, objective: objective.is_finite().then_some(objective) })
    }))
}

/// What happens during a run, in order.
pub enum Event<'a> {
    /// The spec is loaded and resolved, and its model built.
    Built {
        /// The problem.
        problem: &'a Problem,
        /// Its formulation.
        formulation: &'a Formulation,
        /// Milliseconds the build took.
        millis: f64,
    },
    /// The model was written to a file; `compact` when its lazily separated rows were written
    /// in their compact form.
    Exported {
        /// The file.
        path: &'a Path,
        /// Whether the lazily separated rows were replaced by a compact equivalent.
        compact: bool,
    },
    /// The LP relaxation's bound.
    Relaxed {
        /// The backend.
        kind: SolverKind,
        /// The bound.
        bound: &'a LpBound,
    },
    /// A search starts.
    SearchStarted {
        /// Which.
        method: SearchMethod,
        /// Its time limit, seconds.
        limit: f64,
        /// Its seed.
        seed: u64,
        /// Independent searches side by side.
        threads: usize,
        /// Threads asked for.
        asked: u32,
    },
    /// A MILP solve starts, with its prepared start (if the backend takes one).
    SolveStarted {
        /// The backend.
        kind: SolverKind,
        /// Its time limit.
        time_limit: Option<f64>,
        /// The start, checked.
        start: Option<&'a StartReport>,
    },
    /// Work with its own budget will run past the command's time limit (said before any work).
    LimitExtended {
        /// What: `explain`.
        what: &'static str,
        /// Its budget, seconds.
        seconds: f64,
        /// The command's time limit, seconds.
        limit: f64,
    },
    /// The design (or the verdict that there is none) is ready, checked.
    Designed(&'a Design),
    /// Explaining an infeasible spec starts.
    Explaining,
    /// Which requirements conflict.
    Explained(&'a Explanation),
    /// A file was written.
    Wrote {
        /// What it holds (`result`, `picture`, `geojson`, `blocks`, `solution`).
        what: &'static str,
        /// Where.
        path: &'a Path,
    },
}

/// A checked design run, a MILP solve's or a search's: one record, whose `solve` (its
/// [`crate::pipeline::Outcome`]) says which.
pub type Design = DesignResult;

impl DesignResult {
    /// The validity line: `valid`, `INVALID (n violations)`, or `none` without a design.
    pub fn verdict(&self, none: &str) -> String {
        verdict_line(self.network.is_some(), &self.validity, none)
    }

    /// The status line `netspec solve` prints: [`milp_status_line`] or [`search_status_line`].
    pub fn status_line(&self) -> String {
        match self.solve.is_search() {
            true => search_status_line(self),
            false => milp_status_line(self),
        }
    }

    /// Whether a design exists and failed an independent check.
    pub fn is_invalid(&self) -> bool {
        self.network.is_some() && !self.validity.valid
    }
}

/// Why the solver stopped and whether a design exists: `optimal, design found (47 edges)`,
/// `limit(time), design found (47 edges, gap 12 %)`, `limit(time), no design`.
pub fn milp_status_line(r: &DesignResult) -> String {
    let s = &r.solve;
    if let (Termination::Infeasible, Some(why)) = (&s.termination, &s.infeasibility) {
        return format!("infeasible (found by netspec before solving): {why}");
    }
    let design = match &r.metrics {
        Some(m) => {
            let gap = match (&s.termination, s.gap) {
                (Termination::Optimal, _) | (_, None) => String::new(),
                (_, Some(g)) => format!(", gap {}", crate::solvers::percent(g)),
            };
            format!("design found ({} edges{gap})", m.edges)
        }
        None => "no design".to_string(),
    };
    format!("{}, {design}", s.termination)
}

/// A search's status line: `optimal`, `limit(time)`, or with ` (no design)` when it found none.
pub fn search_status_line(r: &DesignResult) -> String {
    let label = r.solve.termination.label();
    if r.network.is_some() {
        label
    } else {
        format!("{label} (no design)")
    }
}

/// The validity line: `none` without a design, else `valid` or how many violations.
pub fn verdict_line(has_design: bool, v: &Validity, none: &str) -> String {
    match (has_design, v.valid) {
        (false, _) => none.into(),
        (true, true) => "valid".into(),
        (true, false) => {
            let n = v.design_violations.len() + v.milp_check.as_ref().map_or(0, |c| c.violations.len());
            format!("INVALID ({n} violations)")
        }
    }
}

/// What [`solve_spec`] produced.
pub struct Solved {
    /// The design run, unless only the model was built (`no_solve`, `relax`).
    pub design: Option<Design>,
    /// Which requirements conflict, when the spec was infeasible and explained.
    pub explanation: Option<Explanation>,
}

/// The default output folder of a spec file: `out/<file stem>`, with every character but
/// letters, digits, `-`, `_` and `.` replaced by `_` (a spec's own `name` is a label, never a
/// path: a spec file from elsewhere cannot choose where files go).
pub fn default_out_dir(spec_file: &Path) -> PathBuf {
    let stem = spec_file.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    PathBuf::from("out").join(safe_component(&stem))
}

/// `name` as one safe path component: letters, digits, `-`, `_`, `.` kept, everything else `_`;
/// never empty, `.` or `..`.
pub fn safe_component(name: &str) -> String {
    let s: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') { c } else { '_' }).collect();
    let s = s.trim_start_matches('.').to_string();
    if s.is_empty() {
        "spec".into()
    } else {
        s
    }
}

/// Loads a spec file, applies a variant, and resolves it against its mesh (of at most
/// `max_cells` cells).
pub fn load(path: &Path, variant: Option<&Variant>, max_cells: usize) -> Result<Problem, SpecError> {
    let mut spec = Spec::load(path)?;
    if let Some(v) = variant {
        v.apply(&mut spec.formulation, &mut spec.solver);
    }
    let base = path.parent().unwrap_or(Path::new("."));
    spec.resolve_within(base, max_cells).map_err(|kind| SpecError { path: path.to_path_buf(), kind })
}

/// `netspec solve`: loads, builds, and (unless told only to build) designs, explains an
/// infeasible spec, and writes the outputs. Events go to `on` as they happen.
pub fn solve_spec(req: &SolveRequest, on: &mut dyn FnMut(Event)) -> Result<Solved, RunError> {
    // The time limit covers loading the spec, building the mesh and the model.
    let t0 = Instant::now();
    let problem = load(&req.spec, req.variant.as_ref(), req.max_cells.unwrap_or(crate::spec::DEFAULT_MAX_CELLS))?;
    let out = req.out.clone().unwrap_or_else(|| default_out_dir(&req.spec));
    Ok(solve_loaded(&problem, req, t0, Some(&out), on)?.1)
}

/// [`solve_spec`] on a problem already loaded (with `req.variant` applied; `req.spec` names its
/// `[solver]` section in errors), timed from `t0`. The outputs go into `out`; with `None`
/// nothing is written (the library callers that keep the design in memory, such as the Python
/// package). Returns the formulation built with what was solved.
pub fn solve_loaded(
    problem: &Problem,
    req: &SolveRequest,
    t0: Instant,
    out: Option<&Path>,
    on: &mut dyn FnMut(Event),
) -> Result<(Formulation, Solved), RunError> {
    // Every setting is checked before any work: the flags over the spec's [solver] section.
    let layers =
        [(Origin::Flags, req.flags.clone()), (Origin::Spec(req.spec.clone()), Settings::of_spec(&problem.spec.solver))];
    let (method, mut options) = resolve(&layers)?;
    if let Some(ExplainBudget::Seconds(s)) = req.explain {
        if !(s.is_finite() && s >= 0.0) {
            return Err(RunError::Unsupported(format!("--explain-time must be a number of seconds ≥ 0, got {s}")));
        }
    }
    let deadline = options.finite_time_limit().map(|limit| t0 + Duration::from_secs_f64(limit));
    if let (Some(ExplainBudget::Seconds(seconds)), Some(limit)) = (req.explain, options.finite_time_limit()) {
        if !req.no_solve && !req.relax && method.milp().is_some() {
            on(Event::LimitExtended { what: "explain", seconds, limit });
        }
    }
    let f = pipeline::build(problem);
    on(Event::Built { problem, formulation: &f, millis: t0.elapsed().as_secs_f64() * 1e3 });
    if let Some(path) = &req.export {
        let compact = export(problem, &f, path)?;
        on(Event::Exported { path, compact });
    }
    if req.relax {
        let kind = method.milp().ok_or_else(|| {
            RunError::Unsupported(format!("`{method}` is a design search: --relax needs a MILP backend"))
        })?;
        let bound = relax(&f, kind, &options)?;
        on(Event::Relaxed { kind, bound: &bound });
        if let (Some(sol), Some(x)) = (&req.sol, &bound.point) {
            let header = format!("LP relaxation after {} cut rounds ({kind})", bound.rounds);
            crate::io::sol::write(&f.model, x, bound.with_cuts, &header, sol)?;
            on(Event::Wrote { what: "solution", path: sol });
        }
    }
    if req.no_solve || req.relax {
        return Ok((f, Solved { design: None, explanation: None }));
    }
    options.interrupt = req.interrupt.clone();
    options.progress = req.progress.clone();
    options.incumbents = req.incumbents.clone().map(|sink| point_sink(problem, &f, sink));
    // The searches (`--solver heuristic` or `anneal`, and the heuristic's MIP start) budget work,
    // not time (module `heuristics::budget`): their budgets come from the limit asked for, not
    // from what the model's build left of it, so that a seed gives the same design every run.
    let asked = options.finite_time_limit().map(|limit| limit - output_reserve(limit));
    if let Some(limit) = asked {
        let built = if method.milp().is_some() { t0.elapsed().as_secs_f64() } else { 0.0 };
        options.time_limit = Some((limit - built).max(0.0));
    }
    let start = match &req.start {
        StartChoice::Nothing => StartFrom::Nothing,
        StartChoice::Heuristic => pipeline::default_start(asked),
        StartChoice::File(file) => {
            StartFrom::Design { network: start_design(file, problem, &f)?, source: file.display().to_string() }
        }
    };
    let run = Run { method, options, start, explain: req.explain, sol: req.sol.clone(), deadline };
    let solved = match out {
        Some(out) => solve_problem(problem, &f, &run, out, on),
        None => design_problem(problem, &f, &run, on),
    };
    Ok((f, solved.map_err(|e| name_origin(e, &layers))?))
}

/// An option a backend refuses, named as the layer that set it gives it (`--seed`, or the spec
/// file and `solver.seed`).
fn name_origin(e: RunError, layers: &[(Origin, Settings)]) -> RunError {
    match e {
        RunError::Solver(SolverError {
            solver,
            kind: crate::solvers::SolverErrorKind::Unsupported { option, reason },
        }) => match crate::pipeline::settings::provenance(layers, option) {
            Some(place) => RunError::Unsupported(format!("{place}: {solver} does not support it: {reason}")),
            None => RunError::Solver(SolverError::new(
                solver,
                crate::solvers::SolverErrorKind::Unsupported { option, reason },
            )),
        },
        other => other,
    }
}

/// How [`solve_problem`] designs.
#[derive(Clone)]
pub struct Run {
    /// A MILP backend or a search.
    pub method: Method,
    /// The solve options (checked).
    pub options: SolveOptions,
    /// The MIP start of a MILP solve.
    pub start: StartFrom,
    /// Explaining an infeasible spec, and its budget (`None`: do not explain).
    pub explain: Option<ExplainBudget>,
    /// Write the solution found as a `.sol` file here.
    pub sol: Option<PathBuf>,
    /// When the command's time limit runs out (`None`: no limit); what is left of it after the
    /// solve is the explanation's [`ExplainBudget::Remaining`].
    pub deadline: Option<Instant>,
}

impl Run {
    /// Seconds the explanation may take, when it is asked for.
    fn explain_seconds(&self) -> Option<f64> {
        match self.explain? {
            ExplainBudget::Seconds(s) => Some(s),
            ExplainBudget::Remaining => Some(self.deadline.map_or(EXPLAIN_SECONDS, |d| {
                let left = d.saturating_duration_since(Instant::now()).as_secs_f64();
                (left - output_reserve(left)).max(0.0)
            })),
        }
    }
}

/// Designs a built problem, explains it if infeasible, and writes the outputs into `out`.
pub fn solve_problem(
    p: &Problem,
    f: &Formulation,
    run: &Run,
    out: &Path,
    on: &mut dyn FnMut(Event),
) -> Result<Solved, RunError> {
    let solved = design_into(p, f, run, Some(out), on)?;
    let design = solved.design.as_ref().expect("a design run");
    write_outputs(out, p, f, design, solved.explanation.as_ref(), on)?;
    Ok(solved)
}

/// Designs a built problem and explains it if infeasible, writing nothing (a `.sol` file only
/// when `run.sol` asks for one): [`solve_problem`] for callers that keep the design in memory
/// and write it later, if at all, with [`write_outputs`].
pub fn design_problem(p: &Problem, f: &Formulation, run: &Run, on: &mut dyn FnMut(Event)) -> Result<Solved, RunError> {
    design_into(p, f, run, None, on)
}

/// The design run of [`solve_problem`]; a MILP solve's designs found on the way are written
/// into `out` as they arrive when it is given.
fn design_into(
    p: &Problem,
    f: &Formulation,
    run: &Run,
    out: Option<&Path>,
    on: &mut dyn FnMut(Event),
) -> Result<Solved, RunError> {
    let design = match (run.method, out) {
        (Method::Search(m), _) => search(p, f, m, &run.options, on)?,
        (Method::Milp(kind), Some(out)) => milp_writing(p, f, kind, run, out, on)?,
        (Method::Milp(kind), None) => milp(p, f, kind, run, on)?,
    };
    on(Event::Designed(&design));
    if let Some(path) = &run.sol {
        if let Some(x) = &design.primal_point {
            let s = &design.solve;
            let header = format!("{} {}, {}", s.solver, s.solver_version, s.termination.label());
            crate::io::sol::write(&f.model, x, s.objective, &header, path)?;
            on(Event::Wrote { what: "solution", path });
        }
    }
    let milp_infeasible = !design.outcome().is_search() && *design.termination() == Termination::Infeasible;
    let explanation = match run.explain_seconds() {
        Some(budget) if milp_infeasible => {
            on(Event::Explaining);
            let opts = ExplainOptions {
                time_budget: budget,
                check_time_limit: budget.min(5.0),
                threads: run.options.threads,
                known_infeasible: true,
                ..ExplainOptions::default()
            };
            let kind = run.method.milp().expect("a MILP run");
            let e = explain(p, kind, &opts);
            on(Event::Explained(&e));
            Some(e)
        }
        _ => None,
    };
    Ok(Solved { design: Some(design), explanation })
}

/// A MILP solve that writes every design it finds on the way into `out` as it arrives
/// ([`running`]), the writer finished before the answer is returned.
fn milp_writing(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    run: &Run,
    out: &Path,
    on: &mut dyn FnMut(Event),
) -> Result<DesignResult, RunError> {
    std::thread::scope(|scope| {
        let (sink, writer) = running::spawn(scope, out, p, f);
        let mut run = run.clone();
        run.options.incumbents = Some(sink.point_sink(run.options.incumbents.take()));
        let r = milp(p, f, kind, &run, on);
        sink.close();
        let _ = writer.join();
        r
    })
}

/// A MILP solve from the run's start: the start is prepared first (so the caller can show it),
/// then the backend solves, and the answer is checked.
fn milp(
    p: &Problem,
    f: &Formulation,
    kind: SolverKind,
    run: &Run,
    on: &mut dyn FnMut(Event),
) -> Result<DesignResult, RunError> {
    let caps = kind.instance()?.capabilities();
    let mut o = run.options.clone();
    if !caps.reports_progress {
        o.progress = None;
        o.incumbents = None;
    }
    let o = &o;
    let from = match caps.mip_start {
        true => match pipeline::start_for(p, f, &run.start, o.seed.unwrap_or(0), o.heuristic_threads()) {
            Some((point, report)) => StartFrom::Prepared { point, report },
            None => run.start.clone(),
        },
        false => run.start.clone(),
    };
    let report = match &from {
        StartFrom::Prepared { report, .. } => Some(report),
        _ => None,
    };
    if let (Some(sink), StartFrom::Prepared { point: Some(x), report }) = (&run.options.incumbents, &from) {
        (sink.0)(report.objective.unwrap_or(f64::NAN), x);
    }
    on(Event::SolveStarted { kind, time_limit: o.time_limit, start: report });
    Ok(pipeline::solve_from(p, f, kind, o, &from)?)
}

/// A design search: the heuristic (one search per thread) or the stochastic search (one).
fn search(
    p: &Problem,
    f: &Formulation,
    method: SearchMethod,
    o: &SolveOptions,
    on: &mut dyn FnMut(Event),
) -> Result<DesignResult, RunError> {
    for (set, name) in
        [(o.rel_gap.is_some(), "gap"), (o.abs_gap.is_some(), "abs_gap"), (o.node_limit.is_some(), "node_limit")]
    {
        if set {
            return Err(RunError::Unsupported(format!(
                "option `--{}` is not supported by the {} search (nor `solver.{name}` in a spec): it has no bound and no nodes",
                name.replace('_', "-"),
                method.name()
            )));
        }
    }
    let limit = o.time_limit.unwrap_or(match method {
        SearchMethod::Heuristic => HEURISTIC_SECONDS,
        SearchMethod::Anneal => ANNEAL_SECONDS,
    });
    let seed = o.seed.unwrap_or(0);
    let asked = o.threads.unwrap_or(1);
    let threads = match method {
        SearchMethod::Heuristic => asked as usize,
        SearchMethod::Anneal => 1,
    };
    on(Event::SearchStarted { method, limit, seed, threads, asked });
    Ok(run_search(p, f, method, limit, seed, threads))
}

/// Writes the model to `path` (`.lp`/`.mps`, by extension); a model with lazily separated rows
/// is written with them in their compact form (returns `true` then), the same optimum.
pub fn export(p: &Problem, f: &Formulation, path: &Path) -> Result<bool, RunError> {
    if f.is_complete() {
        // No comment: the `paper` recipe's files stay byte for byte what they always were.
        crate::io::write_model_file(&f.model, path)?;
        return Ok(false);
    }
    let compact = crate::formulations::build_compact(p);
    let note = format!(
        "netspec formulation: {} — written complete: its lazily separated cutset rows are\nreplaced by the equivalent single-commodity flow ({}); same optimum.",
        f.recipe.label, compact.recipe.label
    );
    crate::io::write_model_file_with_comments(&compact.model, path, &[note])?;
    Ok(true)
}

/// The LP relaxation's bound, as written and after the recipe's cut rounds.
pub fn relax(f: &Formulation, kind: SolverKind, o: &SolveOptions) -> Result<LpBound, RunError> {
    let solver = kind.instance()?;
    let mut sep = f.separator();
    Ok(crate::solvers::lazy::lp_bound(
        solver.as_ref(),
        &f.model,
        sep.as_mut().map(|s| s as &mut dyn crate::solvers::Separator),
        o,
    )?)
}

/// Reads `--start FILE`: the network of an earlier `result.json` (its mesh must be this spec's),
/// or a `.sol` point of this model, decoded.
pub fn start_design(file: &Path, problem: &Problem, f: &Formulation) -> Result<Network, RunError> {
    let err = |message: String| RunError::Start { path: file.to_path_buf(), message };
    if file.extension().is_some_and(|e| e.eq_ignore_ascii_case("sol")) {
        let sol = crate::io::sol::read(&f.model, file)?;
        return Ok(f.decode(problem, &sol.values));
    }
    #[derive(serde::Deserialize)]
    struct View {
        schema: Option<String>,
        network: Option<Network>,
    }
    let text = crate::io::read_utf8(file).map_err(|e| err(format!("reading the start: {e}")))?;
    let view: View = serde_json::from_str(&text).map_err(|e| err(format!("not a netspec result.json: {e}")))?;
    if view.schema.as_deref() != Some("netspec.design") {
        return Err(err("not a netspec result.json (no `\"schema\": \"netspec.design\"`)".into()));
    }
    let net = view.network.ok_or_else(|| err("the result has no network (`network` is null)".into()))?;
    if net.active.len() != problem.mesh.num_edges() {
        return Err(err(format!(
            "the start's network has {} edges, this spec's mesh {} — is it a result of another spec?",
            net.active.len(),
            problem.mesh.num_edges()
        )));
    }
    Ok(net)
}

/// Writes a design run's outputs into `dir`: `result.json` (with `infeasibility` when the spec
/// was explained), `network.svg`/`.png` (the design, or the conflicting requirements),
/// `network.geojson`, and `blocks.dot` for a game level's block graph.
pub fn write_outputs(
    dir: &Path,
    p: &Problem,
    f: &Formulation,
    design: &Design,
    explanation: Option<&Explanation>,
    on: &mut dyn FnMut(Event),
) -> Result<(), RunError> {
    let write = |path: &Path, bytes: &[u8]| {
        write_atomic(path, bytes).map_err(|source| RunError::Write { path: path.to_path_buf(), source })
    };
    std::fs::create_dir_all(dir).map_err(|source| RunError::Write { path: dir.to_path_buf(), source })?;
    let json = dir.join("result.json");
    // result.json: the design result, plus `infeasibility` when the spec was explained.
    #[derive(serde::Serialize)]
    struct Written<'a> {
        #[serde(flatten)]
        result: &'a DesignResult,
        status: &'static str,
        #[serde(skip_serializing_if = "Option::is_none")]
        infeasibility: Option<&'a Explanation>,
    }
    let text = serde_json::to_string_pretty(&Written {
        result: design,
        status: running::FINISHED,
        infeasibility: explanation,
    })
    .expect("results serialise");
    let spec = &p.spec;
    if let Some(svg) = picture(p, f, design, explanation) {
        let svg_path = dir.join("network.svg");
        write(&svg_path, svg.as_bytes())?;
        let png_path = dir.join("network.png");
        let png = crate::render::png(&svg)
            .map_err(|e| RunError::Render { path: png_path.clone(), message: e.to_string() })?;
        write(&png_path, &png)?;
        on(Event::Wrote { what: "picture", path: &png_path });
    }
    if design.network().is_some() && !design.outcome().is_search() {
        let geo = dir.join("network.geojson");
        let level = crate::design::streets::DEFAULT_SOLVE_LEVEL;
        let text = crate::design::streets::design_geojson(&design.mesh, &design.active_edges, &design.spec.name, level)
            .map_err(|e| RunError::Render { path: geo.clone(), message: e.to_string() })?;
        write(&geo, text.as_bytes())?;
        on(Event::Wrote { what: "geojson", path: &geo });
    }
    if let Some(g) = design.rooms().and_then(|r| r.block_graph.as_ref()) {
        let dot = dir.join("blocks.dot");
        write(&dot, g.to_dot(&spec.name).as_bytes())?;
        on(Event::Wrote { what: "blocks", path: &dot });
    }
    // Last, so that a finished result.json never stands beside a picture of an earlier design.
    write(&json, (text + "\n").as_bytes())?;
    on(Event::Wrote { what: "result", path: &json });
    Ok(())
}

/// The picture `network.svg` holds: the design with its caption, or without one the conflicting
/// requirements of an explained infeasible spec (`None` when there is neither).
pub fn picture(p: &Problem, f: &Formulation, design: &Design, explanation: Option<&Explanation>) -> Option<String> {
    let caption = caption(&p.spec, design);
    match design.network() {
        Some(net) => {
            let placements = f.placements.as_ref().map(|r| r.placements.as_slice());
            Some(network_svg(p, net, f.path_sets.as_ref(), placements, &caption))
        }
        None => explanation.filter(|e| !e.conflicts.is_empty()).map(|e| conflict_svg(p, e, &caption)),
    }
}

/// The picture's title: spec, solver, status, objective, gap, verdict.
fn caption(spec: &Spec, design: &Design) -> Caption {
    let name =
        if spec.description.is_empty() { spec.name.clone() } else { format!("{} — {}", spec.name, spec.description) };
    let o = design.outcome();
    Caption {
        name,
        solver: o.solver_label(),
        status: o.termination.label(),
        objective: o.objective,
        gap: o.gap,
        verdict: design.verdict(if o.is_search() { "no design" } else { "no network" }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_folders_come_from_the_file_name_made_safe() {
        assert_eq!(default_out_dir(Path::new("models/fig2b.toml")), PathBuf::from("out/fig2b"));
        assert_eq!(default_out_dir(Path::new("/tmp/../x y.toml")), PathBuf::from("out/x_y"));
        assert_eq!(safe_component("../../escaped"), "_.._escaped");
        assert_eq!(safe_component(".."), "spec");
        assert_eq!(safe_component("."), "spec");
        assert_eq!(safe_component("/abs/path"), "_abs_path");
        assert_eq!(safe_component("a\0b"), "a_b");
        assert_eq!(safe_component(""), "spec");
    }
}
