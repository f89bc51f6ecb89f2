//! The versioned JSON result of a solve (`netspec solve-file --json`), its one-screen summary,
//! and the listing of compiled backends. The schema is documented in `docs/result-schema.md`.

use crate::milp::{CheckReport, Model, ModelStats, Tolerances};
use crate::pipeline::settings::{resolve, Origin, Settings, SettingsError};
use crate::pipeline::Method;
use crate::solvers::{Capabilities, Interrupt, SolveOptions, SolveResult, SolverError, SolverKind, Termination};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Version of the JSON result schema. Bump on any change that breaks a reader.
pub const SCHEMA_VERSION: u32 = 1;

/// Everything about one solve of one model: input, options, the solver's result and the
/// independent check.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SolveReport {
    /// Always `netspec.solve`.
    pub schema: String,
    /// [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The netspec version that wrote it.
    pub netspec_version: String,
    /// Where the model came from (a file path or a spec name).
    pub source: String,
    /// The model's name.
    pub model_name: String,
    /// Its size.
    pub model_stats: ModelStats,
    /// The options used.
    pub options: SolveOptions,
    /// The solver's result.
    pub result: SolveResult,
    /// Whether a solution exists (apart from why the solver stopped, `result.termination`).
    #[serde(default)]
    pub solution_found: bool,
    /// The independent checker's report on the primal point, if there is one.
    pub check: Option<CheckReport>,
    /// Whether the objective recomputed by the checker agrees with the solver's (1e-6 relative).
    pub objective_agrees: Option<bool>,
    /// `true` when a primal point exists and passed every check.
    pub valid: bool,
}

impl SolveReport {
    /// Runs the independent checker on `result` and bundles everything.
    pub fn new(source: String, model: &Model, options: SolveOptions, result: SolveResult, tol: &Tolerances) -> Self {
        let check = result.check(model, tol);
        let objective_agrees = match (&check, result.objective) {
            (Some(c), Some(obj)) => Some(crate::milp::objectives_agree(c.objective, obj, 1e-6)),
            _ => None,
        };
        let valid = check.as_ref().is_some_and(|c| c.is_feasible()) && objective_agrees != Some(false);
        SolveReport {
            schema: "netspec.solve".into(),
            schema_version: SCHEMA_VERSION,
            netspec_version: env!("CARGO_PKG_VERSION").into(),
            source,
            model_name: model.name.clone(),
            model_stats: model.stats(),
            options,
            solution_found: result.primal.is_some(),
            result,
            check,
            objective_agrees,
            valid,
        }
    }

    /// A one-screen, human-readable summary.
    pub fn summary(&self) -> String {
        use std::fmt::Write;
        let r = &self.result;
        let mut s = String::new();
        let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.10}"));
        let _ = writeln!(s, "model      {} ({})", self.source, self.model_stats);
        let _ = writeln!(s, "solver     {} {}", r.solver, r.solver_version);
        for w in &r.warnings {
            let _ = writeln!(s, "warning    {w}");
        }
        if let Some(st) = &r.mip_start {
            if st.accepted {
                let _ = writeln!(
                    s,
                    "start      passed netspec's check (objective {}) and was handed to the solver",
                    st.objective
                );
            } else {
                let _ = writeln!(
                    s,
                    "start      REJECTED by netspec's check ({} violations; first: {}), not handed to the solver",
                    st.violations,
                    st.first_violation.as_deref().unwrap_or("-")
                );
            }
        }
        let _ = writeln!(s, "status     {}", r.status_line());
        let _ = writeln!(s, "objective  {}", num(r.objective));
        let _ = writeln!(s, "bound      {}", num(r.dual_bound));
        let _ = writeln!(s, "gap        {}", r.gap.map_or("-".into(), |g| format!("{:.4}%", 100.0 * g)));
        let _ = writeln!(s, "nodes      {}", r.nodes.map_or("-".into(), |n| n.to_string()));
        let _ = writeln!(
            s,
            "time       {} solver, {:.3} s wall",
            r.solver_time.map_or("-".into(), |t| format!("{t:.3} s")),
            r.wall_time
        );
        let verdict = match (&self.check, &r.termination) {
            (None, Termination::Infeasible) => "no solution (infeasible)".to_string(),
            (None, t) => format!("no solution to check ({})", t.label()),
            (Some(c), _) if c.is_feasible() && self.objective_agrees != Some(false) => format!(
                "valid: every bound, row and integrality holds (max violations: bound {:.1e}, row {:.1e}, int {:.1e}); objective recomputed {}",
                c.max_bound_violation, c.max_row_violation, c.max_integrality_violation, c.objective
            ),
            (Some(c), _) => {
                let mut t = format!("INVALID: {} violations", c.violations.len());
                for v in c.violations.iter().take(5) {
                    let _ = write!(t, "\n             {v}");
                }
                if self.objective_agrees == Some(false) {
                    let _ = write!(t, "\n             objective recomputed {} differs from the solver's", c.objective);
                }
                t
            }
        };
        let _ = writeln!(s, "check      {verdict}");
        s
    }
}

/// One compiled backend, for `netspec solvers`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct SolverInfo {
    /// Backend name (`--solver` value).
    pub name: String,
    /// The solver's version.
    pub version: String,
    /// What it supports.
    pub capabilities: Capabilities,
}

impl SolverInfo {
    /// The capabilities as one line: supported options, and what is missing.
    pub fn capability_summary(&self) -> String {
        let c = &self.capabilities;
        let flags = [
            ("mip", c.integer_variables),
            (if c.time_limit_whole_seconds { "time(s)" } else { "time" }, c.time_limit),
            ("gap", c.rel_gap),
            ("absgap", c.abs_gap),
            ("threads", c.threads),
            ("seed", c.seed),
            ("nodes", c.node_limit),
            ("logfile", c.log_file),
            ("start", c.mip_start),
            ("bound", c.reports_dual_bound),
            ("nodecount", c.reports_nodes),
            ("interrupt", c.interrupt),
            ("params", c.raw_params),
            ("live", c.reports_progress),
        ];
        flags.iter().map(|(n, ok)| if *ok { n.to_string() } else { format!("-{n}") }).collect::<Vec<_>>().join(" ")
    }
}

/// Every compiled backend with its version and capabilities.
pub fn solver_list() -> Vec<SolverInfo> {
    SolverKind::compiled()
        .into_iter()
        .filter_map(|k| k.instance().ok())
        .map(|s| SolverInfo { name: s.kind().name().into(), version: s.version(), capabilities: s.capabilities() })
        .collect()
}

/// What `netspec solve-file` is asked to do.
#[derive(Clone, Debug, Default)]
pub struct SolveFileRequest {
    /// The model file (`.mps`, `.lp`, either `.gz`).
    pub file: PathBuf,
    /// The command line's settings (the method must be a MILP backend).
    pub settings: Settings,
    /// A `.sol` start, checked before it is handed over.
    pub start: Option<PathBuf>,
    /// Write the solution found here.
    pub sol: Option<PathBuf>,
    /// A request to stop early.
    pub interrupt: Option<Interrupt>,
}

/// Why `solve-file` could not run (a finished solve, whatever its termination, is not one).
#[derive(Debug, thiserror::Error)]
pub enum SolveFileError {
    /// A setting is refused.
    #[error(transparent)]
    Settings(#[from] SettingsError),
    /// The model file is unusable.
    #[error(transparent)]
    File(#[from] crate::io::FileError),
    /// The start or solution file is unusable.
    #[error(transparent)]
    Sol(#[from] crate::io::sol::SolError),
    /// The backend could not attempt the solve.
    #[error("solving {path}: {source}")]
    Solver {
        /// The model file.
        path: PathBuf,
        /// Why.
        #[source]
        source: SolverError,
    },
    /// The method is a design search.
    #[error("`{0}` is a design search, not a MILP backend: it needs a spec (`netspec solve`)")]
    NotABackend(String),
}

/// A warning about an input file, for the caller to show.
pub struct FileWarning<'a> {
    /// The file.
    pub path: &'a Path,
    /// What.
    pub message: String,
}

/// `netspec solve-file`: reads the model (and a start), solves it, writes the solution, and
/// checks the answer independently. Warnings about the files go to `warn`.
pub fn solve_file(req: &SolveFileRequest, warn: &mut dyn FnMut(FileWarning)) -> Result<SolveReport, SolveFileError> {
    let (method, mut options) = resolve(&[(Origin::Flags, req.settings.clone())])?;
    let kind = match method {
        Method::Milp(k) => k,
        m => return Err(SolveFileError::NotABackend(m.to_string())),
    };
    let read = crate::io::read_model_file(&req.file)?;
    for w in &read.warnings {
        warn(FileWarning { path: &req.file, message: w.to_string() });
    }
    if let Some(path) = &req.start {
        let sol = crate::io::sol::read(&read.model, path)?;
        if !sol.missing.is_empty() {
            let message =
                format!("{} variables not in the file start at 0 (first: {})", sol.missing.len(), sol.missing[0]);
            warn(FileWarning { path, message });
        }
        options.mip_start = Some(sol.values);
    }
    options.interrupt = req.interrupt.clone();
    let solver_err = |source| SolveFileError::Solver { path: req.file.clone(), source };
    let solver = kind.instance().map_err(solver_err)?;
    let result = solver.solve(&read.model, &options).map_err(solver_err)?;
    if let (Some(path), Some(x)) = (&req.sol, &result.primal) {
        let header = format!("{} {}, {}", result.solver, result.solver_version, result.termination.label());
        crate::io::sol::write(&read.model, x, result.objective, &header, path)?;
    }
    Ok(SolveReport::new(req.file.display().to_string(), &read.model, options, result, &Tolerances::default()))
}
