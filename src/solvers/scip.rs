//! SCIP backend (crate `russcip`, with `scip-sys` on the model's raw pointer for what the safe
//! crate does not wrap: the objective offset, the raw solve status, the dual bound, the node count
//! over all restarts, the log file, the message handler's quiet flag and the version).
//!
//! SCIP 10 is linked from a shared library (see `scripts/setup.sh`); `russcip` is used without
//! its default features (no bindgen).
//!
//! # Options
//!
//! | option | SCIP parameter |
//! |---|---|
//! | `time_limit` | `limits/time` (fractional seconds, the time left of the limit once the model is loaded; wall clock, since netspec sets `timing/clocktype` = 2); a watchdog calls `SCIPinterruptSolve` if SCIP overruns it |
//! | `rel_gap` / `abs_gap` | `limits/gap` / `limits/absgap` (SCIP's gap is relative to the smaller of the two bounds) |
//! | `threads` | 1: the sequential solver; more: SCIP's *concurrent* solver (`SCIPsolveConcurrent` with `parallel/maxnthreads`), which races differently-seeded/-tuned solvers on the same problem rather than splitting one tree (the linked library is built with SCIP's thread interface, tinycthread) |
//! | `seed` | `randomization/randomseedshift` and, for the concurrent solvers, `concurrent/initseed` (the seed modulo 2^31) |
//! | `node_limit` | `limits/totalnodes` (nodes over all restarts, capped at `i64::MAX`) |
//! | `log` | `display/verblevel` 0 plus a quiet message handler (quiet); verbosity 4 on stdout; or SCIP's own log file (`SCIPsetMessagehdlrLogfile`) with the console quiet |
//! | `mip_start` | an original-space solution checked and added before the solve (an infeasible start is dropped) |
//! | `interrupt` | `SCIPinterruptSolve` from netspec's watchdog thread; SCIP's own Ctrl-C handler is off (`misc/catchctrlc` = false), netspec handles the signal |
//! | `incumbents` / `progress` | an event handler ([`super::scip_live`]) on best solutions (every improving point) and solved nodes (incumbent, bound, nodes, at most four times a second); with one thread only: the concurrent solver's copies do not carry it, and report at the end |
//! | `params` | any SCIP parameter by its name (`limits/nodes`), set by its type |
//!
//! Values of magnitude 1e20 or more are infinite for SCIP; netspec passes infinite bounds and
//! sides as SCIP's infinity.

use super::stop::{with_watchdog, StopControl};
use super::{
    guarded_solve, Capabilities, LazyMode, LazyReport, LazySolve, LimitKind, LogTarget, Separator, SolveOptions,
    SolveResult, Solver, SolverError, SolverErrorKind, SolverKind, Termination,
};
use crate::milp::NumericLimits;
use crate::milp::{Model, Sense, VarKind};
use russcip::{ffi, ObjSense, ProblemOrSolving, VarType, Variable, WithSolutions};
use std::ffi::CString;
use std::path::Path;

/// The SCIP backend.
#[derive(Clone, Copy, Debug, Default)]
pub struct ScipSolver;

const KIND: SolverKind = SolverKind::Scip;

/// SCIP's version, e.g. `10.0.2`.
pub fn scip_version() -> String {
    // SAFETY: pure functions returning compile-time constants of the library.
    let (major, minor, tech) = unsafe { (ffi::SCIPmajorVersion(), ffi::SCIPminorVersion(), ffi::SCIPtechVersion()) };
    format!("{major}.{minor}.{tech}")
}

fn rejected(msg: impl Into<String>) -> SolverError {
    SolverError::new(KIND, SolverErrorKind::Rejected(msg.into()))
}

fn retcode(what: &str, rc: impl std::fmt::Debug) -> SolverError {
    rejected(format!("{what}: SCIP returned {rc:?}"))
}

/// Clamps ±inf (and anything SCIP would treat as infinite) to SCIP's infinity.
fn scip_value(v: f64, inf: f64) -> f64 {
    v.clamp(-inf, inf)
}

/// Calls a raw SCIP function returning a `SCIP_RETCODE` and turns a failure into an error.
fn check(what: &str, rc: ffi::SCIP_RETCODE) -> Result<(), SolverError> {
    if rc == ffi::SCIP_Retcode_SCIP_OKAY {
        Ok(())
    } else {
        Err(retcode(what, rc))
    }
}

type Problem = russcip::Model<russcip::ProblemCreated>;

/// A new SCIP instance with the default plugins and the console quiet (callers turn the output
/// back on when asked).
fn new_scip() -> Result<russcip::Model<russcip::PluginsIncluded>, SolverError> {
    let m = russcip::Model::try_new().map_err(|e| retcode("SCIPcreate", e))?;
    // SAFETY: live SCIP instance; its own default message handler.
    unsafe { ffi::SCIPsetMessagehdlrQuiet(m.scip_ptr(), 1) };
    let m = m.set_int_param("display/verblevel", 0).map_err(|e| retcode("display/verblevel", e))?;
    Ok(m.include_default_plugins())
}

/// Builds the SCIP problem: variables (with their objective), linear constraints, sense and
/// objective offset. Returns the problem and its variables in [`crate::milp::VarId`] order.
fn load(model: &Model) -> Result<(Problem, Vec<Variable>), SolverError> {
    let name = if model.name.is_empty() || model.name.contains('\0') { "netspec" } else { model.name.as_str() };
    let mut p = new_scip()?.create_prob(name);
    let ptr = p.scip_ptr();
    // SAFETY: live SCIP instance.
    let inf = unsafe { ffi::SCIPinfinity(ptr) };
    let vars: Vec<Variable> = model
        .vars()
        .iter()
        .map(|v| {
            let ty = match v.kind {
                VarKind::Continuous => VarType::Continuous,
                VarKind::Integer => VarType::Integer,
                VarKind::Binary => VarType::Binary,
            };
            p.add_var(scip_value(v.lb, inf), scip_value(v.ub, inf), v.obj, &v.name, ty)
        })
        .collect();
    for row in model.rows() {
        let vs: Vec<&Variable> = row.vars.iter().map(|v| &vars[v.index()]).collect();
        p.add_cons(vs, row.coefs, scip_value(row.lhs, inf), scip_value(row.rhs, inf), row.name);
    }
    let sense = match model.sense {
        Sense::Minimize => ObjSense::Minimize,
        Sense::Maximize => ObjSense::Maximize,
    };
    let p = p.set_obj_sense(sense);
    if model.obj_constant != 0.0 {
        // SAFETY: live SCIP instance in the problem stage.
        check("SCIPaddOrigObjoffset", unsafe { ffi::SCIPaddOrigObjoffset(p.scip_ptr(), model.obj_constant) })?;
    }
    Ok((p, vars))
}

/// Sets SCIP parameters for the options (the log is handled by [`LogGuard`]).
fn apply_options(
    mut p: Problem,
    vars: &[Variable],
    o: &SolveOptions,
    ctl: &StopControl,
) -> Result<Problem, SolverError> {
    let real = |p: Problem, name: &str, v: f64| p.set_real_param(name, v).map_err(|e| retcode(name, e));
    // Wall clock for `limits/time` (SCIP's default, set explicitly so it cannot drift).
    p = p.set_int_param("timing/clocktype", 2).map_err(|e| retcode("timing/clocktype", e))?;
    // netspec handles Ctrl-C itself (first press: interrupt; second: exit).
    p = p.set_bool_param("misc/catchctrlc", false).map_err(|e| retcode("misc/catchctrlc", e))?;
    if let Some(t) = ctl.remaining() {
        p = real(p, "limits/time", t)?;
    }
    if let Some(g) = o.rel_gap {
        p = real(p, "limits/gap", g)?;
    }
    if let Some(g) = o.abs_gap {
        p = real(p, "limits/absgap", g)?;
    }
    if let Some(s) = o.seed {
        let shift = (s % (i32::MAX as u64 + 1)) as i32;
        p = p
            .set_int_param("randomization/randomseedshift", shift)
            .map_err(|e| retcode("randomization/randomseedshift", e))?;
        // The concurrent solvers (threads > 1) draw their seeds from their own parameter.
        p = p.set_int_param("concurrent/initseed", shift).map_err(|e| retcode("concurrent/initseed", e))?;
    }
    if let Some(n) = o.node_limit {
        let n = n.min(i64::MAX as u64) as i64;
        p = p.set_longint_param("limits/totalnodes", n).map_err(|e| retcode("limits/totalnodes", e))?;
    }
    if let Some(x) = &o.mip_start {
        let sol = p.create_orig_sol();
        for (v, &val) in vars.iter().zip(x) {
            sol.set_val(v, val);
        }
        // An infeasible start is refused by SCIP's check and freed; the solve goes on without.
        let _accepted = p.add_sol(sol).is_ok();
    }
    for param in o.params_for(KIND) {
        set_raw_param(p.scip_ptr(), &param.name, &param.value).map_err(|reason| {
            SolverError::new(KIND, SolverErrorKind::Param { name: format!("{KIND}.{}", param.name), reason })
        })?;
    }
    Ok(p)
}

/// Sets one of SCIP's parameters by name, parsing the value by the parameter's type.
fn set_raw_param(scip: *mut ffi::SCIP, name: &str, value: &str) -> Result<(), String> {
    let c_name = CString::new(name).map_err(|_| "the name contains NUL".to_string())?;
    // SAFETY: live SCIP instance, NUL-terminated name.
    let param = unsafe { ffi::SCIPgetParam(scip, c_name.as_ptr()) };
    if param.is_null() {
        return Err("SCIP has no such parameter (names look like `limits/nodes`; see SCIP's parameter list)".into());
    }
    let bad = |what: &str| format!("SCIP parameter of type {what}: cannot use `{value}`");
    // SAFETY (each call): live SCIP instance and parameter; NUL-terminated strings.
    let rc = unsafe {
        match ffi::SCIPparamGetType(param) {
            ffi::SCIP_ParamType_SCIP_PARAMTYPE_BOOL => {
                let v = match value.to_ascii_lowercase().as_str() {
                    "true" | "on" | "1" => 1,
                    "false" | "off" | "0" => 0,
                    _ => return Err(bad("bool")),
                };
                ffi::SCIPsetBoolParam(scip, c_name.as_ptr(), v)
            }
            ffi::SCIP_ParamType_SCIP_PARAMTYPE_INT => {
                ffi::SCIPsetIntParam(scip, c_name.as_ptr(), value.parse().map_err(|_| bad("int"))?)
            }
            ffi::SCIP_ParamType_SCIP_PARAMTYPE_LONGINT => {
                ffi::SCIPsetLongintParam(scip, c_name.as_ptr(), value.parse().map_err(|_| bad("longint"))?)
            }
            ffi::SCIP_ParamType_SCIP_PARAMTYPE_REAL => {
                ffi::SCIPsetRealParam(scip, c_name.as_ptr(), value.parse().map_err(|_| bad("real"))?)
            }
            ffi::SCIP_ParamType_SCIP_PARAMTYPE_CHAR => {
                let mut chars = value.chars();
                match (chars.next(), chars.next()) {
                    (Some(c), None) if c.is_ascii() => {
                        ffi::SCIPsetCharParam(scip, c_name.as_ptr(), c as std::os::raw::c_char)
                    }
                    _ => return Err(bad("char")),
                }
            }
            _ => {
                let v = CString::new(value).map_err(|_| "the value contains NUL".to_string())?;
                ffi::SCIPsetStringParam(scip, c_name.as_ptr(), v.as_ptr())
            }
        }
    };
    match rc {
        ffi::SCIP_Retcode_SCIP_OKAY => Ok(()),
        ffi::SCIP_Retcode_SCIP_PARAMETERWRONGVAL => {
            Err(format!("SCIP refused the value `{value}` (out of range or not allowed)"))
        }
        rc => Err(format!("SCIP returned {rc}")),
    }
}

/// A SCIP instance the watchdog may interrupt from its own thread.
struct Interruptible(*mut ffi::SCIP);

// SAFETY: the watchdog only calls `SCIPinterruptSolve`, which sets SCIP's user-interrupt flag (a
// plain flag SCIP polls, as its own Ctrl-C handler sets one from a signal context), and the
// watchdog ends before the instance is freed (`with_watchdog` joins it).
unsafe impl Sync for Interruptible {}

// SCIP's synchronisation store (`scip/syncstore.h`, exported by the library but not in
// russcip's bindings): the flag every solver of a concurrent solve polls.
extern "C" {
    fn SCIPsyncstoreIsInitialized(syncstore: *mut ffi::SCIP_SYNCSTORE) -> std::os::raw::c_uint;
    fn SCIPsyncstoreSetSolveIsStopped(syncstore: *mut ffi::SCIP_SYNCSTORE, stopped: std::os::raw::c_uint);
}

impl Interruptible {
    fn interrupt(&self) {
        // SAFETY: see the `Sync` impl; outside SCIP's solving stages the call is refused with a
        // return code, which is ignored (the solve is ending anyway). A concurrent solve
        // (threads > 1) runs copies of the problem that do not look at this instance's flag but
        // at the shared store's, which is set under the store's own lock once it exists.
        unsafe {
            let _ = ffi::SCIPinterruptSolve(self.0);
            let store = ffi::SCIPgetSyncstore(self.0);
            if !store.is_null() && SCIPsyncstoreIsInitialized(store) != 0 {
                SCIPsyncstoreSetSolveIsStopped(store, 1);
            }
        }
    }
}

/// Routes SCIP's log for one solve; closes the log file when dropped.
struct LogGuard {
    scip: *mut ffi::SCIP,
    file: bool,
}

impl LogGuard {
    fn new(p: Problem, log: &LogTarget) -> Result<(Problem, LogGuard), SolverError> {
        let scip = p.scip_ptr();
        match log {
            LogTarget::Quiet => Ok((p, LogGuard { scip, file: false })),
            LogTarget::Stdout => {
                let p = p.set_int_param("display/verblevel", 4).map_err(|e| retcode("display/verblevel", e))?;
                // SAFETY: live SCIP instance.
                unsafe { ffi::SCIPsetMessagehdlrQuiet(scip, 0) };
                Ok((p, LogGuard { scip, file: false }))
            }
            LogTarget::File(path) => {
                // SCIP only prints an error when it cannot open the file: check first, so that
                // an unusable path is a typed error rather than a silently missing log.
                std::fs::OpenOptions::new()
                    .create(true)
                    .append(true)
                    .open(path)
                    .map_err(|e| SolverError::new(KIND, e))?;
                let c = CString::new(path.to_string_lossy().as_bytes())
                    .map_err(|_| rejected("log file path contains NUL"))?;
                let p = p.set_int_param("display/verblevel", 4).map_err(|e| retcode("display/verblevel", e))?;
                // SAFETY: live SCIP instance; SCIP copies nothing but opens the file by name now.
                unsafe { ffi::SCIPsetMessagehdlrLogfile(scip, c.as_ptr()) };
                Ok((p, LogGuard { scip, file: true }))
            }
        }
    }
}

impl Drop for LogGuard {
    fn drop(&mut self) {
        if self.file {
            // SAFETY: the SCIP instance outlives the guard (the guard is dropped before the
            // model in `solve`); NULL closes the log file.
            unsafe { ffi::SCIPsetMessagehdlrLogfile(self.scip, std::ptr::null()) };
        }
    }
}

fn termination(status: ffi::SCIP_Status) -> Termination {
    match status {
        ffi::SCIP_Status_SCIP_STATUS_OPTIMAL => Termination::Optimal,
        ffi::SCIP_Status_SCIP_STATUS_INFEASIBLE => Termination::Infeasible,
        ffi::SCIP_Status_SCIP_STATUS_UNBOUNDED => Termination::Unbounded,
        ffi::SCIP_Status_SCIP_STATUS_INFORUNBD => Termination::InfeasibleOrUnbounded,
        ffi::SCIP_Status_SCIP_STATUS_TIMELIMIT => Termination::Limit(LimitKind::Time),
        ffi::SCIP_Status_SCIP_STATUS_NODELIMIT | ffi::SCIP_Status_SCIP_STATUS_TOTALNODELIMIT => {
            Termination::Limit(LimitKind::Node)
        }
        // Stopped by the user's gap limit: reported optimal, and `SolveResult::finish` turns it
        // into `Limit(Gap)` when the gap is above the default tolerance.
        ffi::SCIP_Status_SCIP_STATUS_GAPLIMIT => Termination::Optimal,
        ffi::SCIP_Status_SCIP_STATUS_SOLLIMIT | ffi::SCIP_Status_SCIP_STATUS_BESTSOLLIMIT => {
            Termination::Limit(LimitKind::Solution)
        }
        ffi::SCIP_Status_SCIP_STATUS_USERINTERRUPT | ffi::SCIP_Status_SCIP_STATUS_TERMINATE => {
            Termination::Limit(LimitKind::Interrupt)
        }
        ffi::SCIP_Status_SCIP_STATUS_STALLNODELIMIT
        | ffi::SCIP_Status_SCIP_STATUS_MEMLIMIT
        | ffi::SCIP_Status_SCIP_STATUS_PRIMALLIMIT
        | ffi::SCIP_Status_SCIP_STATUS_DUALLIMIT
        | ffi::SCIP_Status_SCIP_STATUS_RESTARTLIMIT => Termination::Limit(LimitKind::Other),
        s => Termination::Error(format!("SCIP status {s}")),
    }
}

/// Whether SCIP's statistics (bounds, nodes) can be queried in the instance's current stage.
fn has_statistics(scip: *mut ffi::SCIP) -> bool {
    // SAFETY: live SCIP instance.
    let stage = unsafe { ffi::SCIPgetStage(scip) };
    (ffi::SCIP_Stage_SCIP_STAGE_TRANSFORMED..=ffi::SCIP_Stage_SCIP_STAGE_SOLVED).contains(&stage)
}

impl Solver for ScipSolver {
    fn kind(&self) -> SolverKind {
        KIND
    }

    fn version(&self) -> String {
        scip_version()
    }

    fn capabilities(&self) -> Capabilities {
        Capabilities {
            integer_variables: true,
            time_limit: true,
            time_limit_whole_seconds: false,
            rel_gap: true,
            abs_gap: true,
            threads: true,
            seed: true,
            node_limit: true,
            log_stdout: true,
            log_file: true,
            mip_start: true,
            reports_dual_bound: true,
            reports_nodes: true,
            reports_solver_time: true,
            reports_progress: true,
            lazy_constraints: true,
            interrupt: true,
            raw_params: true,
            numeric: NumericLimits::uniform(1e20, Some(1e20)),
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        guarded_solve(self, model, o, |o, ctl| native(model, o, ctl, None))
    }

    /// Lazy rows through a constraint handler in SCIP's sequential solver (see
    /// [`super::scip_lazy`]). With more than one thread SCIP's concurrent solver would not copy
    /// the handler, so the solve–cut–resolve loop runs instead, each round on the concurrent
    /// solver (the report's `mode` says which).
    fn solve_lazy(&self, model: &Model, sep: &mut dyn Separator, o: &SolveOptions) -> Result<LazySolve, SolverError> {
        if o.threads.is_some_and(|t| t > 1) {
            return super::lazy::solve_loop(self, model, sep, o);
        }
        let name = sep.name().to_string();
        let mut handler = super::scip_lazy::Handler::new(sep, Vec::new());
        let result = guarded_solve(self, model, o, |o, ctl| native(model, o, ctl, Some(&mut handler)))?;
        if let Some(e) = handler.error.take() {
            return Err(rejected(format!("lazy-row handler: {e}")));
        }
        let report = LazyReport {
            rounds: handler.calls,
            rows_added: handler.rows.len(),
            separation_seconds: handler.seconds,
            ..LazyReport::new(name, LazyMode::Callback)
        };
        Ok(LazySolve { result, rows: std::mem::take(&mut handler.rows), left_out: Vec::new(), report })
    }
}

/// The solve itself, after netspec's common checks (`guarded_solve`), with a lazy-row handler
/// installed when given.
fn native(
    model: &Model,
    o: &SolveOptions,
    ctl: &StopControl,
    handler: Option<&mut super::scip_lazy::Handler<'_>>,
) -> Result<SolveResult, SolverError> {
    let (mut p, vars) = load(model)?;
    if let Some(live) = super::scip_live::Live::new(vars.iter().map(|v| v.inner()).collect(), o) {
        p.include_eventhdlr("netspec_live", "improving points and progress for netspec", Box::new(live));
    }
    if let Some(h) = handler {
        h.set_vars(vars.iter().map(|v| v.inner()).collect());
        // SAFETY: the handler outlives this call, and with it the SCIP instance (dropped before
        // `native` returns); `p` is a live instance in the problem stage.
        unsafe { super::scip_lazy::install(p.scip_ptr(), h) }.map_err(rejected)?;
    }
    let p = apply_options(p, &vars, o, ctl)?;
    let (p, log) = LogGuard::new(p, &o.log)?;
    let scip = Interruptible(p.scip_ptr());
    let solved = with_watchdog(
        ctl,
        || scip.interrupt(),
        || match o.threads {
            Some(t) if t > 1 => p
                .set_int_param("parallel/maxnthreads", t.min(i32::MAX as u32) as i32)
                .map_err(|e| retcode("parallel/maxnthreads", e))
                .map(|p| p.try_solve_concurrent()),
            _ => Ok(p.try_solve()),
        },
    )?;
    let version = scip_version();
    let solved = match solved {
        Ok(s) => s,
        Err(e) => {
            drop(log);
            return Ok(SolveResult::empty(KIND, version, Termination::Error(format!("SCIPsolve returned {e:?}"))));
        }
    };
    drop(log);
    let ptr = solved.scip_ptr();
    // SAFETY: live SCIP instance after SCIPsolve.
    let status = unsafe { ffi::SCIPgetStatus(ptr) };
    let mut termination = termination(status);
    if status == ffi::SCIP_Status_SCIP_STATUS_UNKNOWN && ctl.reason().is_some() {
        // A concurrent solve stopped through the shared store leaves the status unknown.
        termination = Termination::Limit(LimitKind::Interrupt);
    }
    let mut r = SolveResult::empty(KIND, version, termination);
    if let Some(sol) = solved.best_sol() {
        r.primal = Some(vars.iter().map(|v| sol.val(v)).collect());
        r.objective = Some(sol.obj_val());
    }
    if has_statistics(ptr) {
        // SAFETY: live SCIP instance in a stage where these statistics exist.
        let (bound, inf, nodes) =
            unsafe { (ffi::SCIPgetDualbound(ptr), ffi::SCIPinfinity(ptr), ffi::SCIPgetNTotalNodes(ptr)) };
        let meaningful = !matches!(
            r.termination,
            Termination::Infeasible | Termination::Unbounded | Termination::InfeasibleOrUnbounded
        );
        r.dual_bound = (meaningful && bound.abs() < inf).then_some(bound);
        r.nodes = Some(nodes.max(0) as u64);
    }
    r.solver_time = Some(solved.solving_time());
    r.finish(model.sense);
    drop(vars);
    drop(solved);
    Ok(r)
}

/// Reads a model file with SCIP's own readers (chosen by the file's extension: `.mps`, `.lp`,
/// also compressed `.gz`) and solves it quietly (used to check that files netspec writes are read
/// faithfully by SCIP itself). Returns the termination and, when a solution exists, the objective
/// of the best one.
pub fn solve_file_with_native_reader(path: &Path) -> Result<(Termination, Option<f64>), SolverError> {
    let p = path.to_str().ok_or_else(|| rejected("path is not UTF-8"))?;
    if p.contains('\0') {
        return Err(rejected("path contains NUL"));
    }
    std::fs::File::open(path).map_err(|e| SolverError::new(KIND, e))?;
    let m = new_scip()?.read_prob(p).map_err(|e| rejected(format!("SCIP could not read {}: {e:?}", path.display())))?;
    let solved = m.try_solve().map_err(|e| retcode("SCIPsolve", e))?;
    // SAFETY: live SCIP instance after SCIPsolve.
    let t = termination(unsafe { ffi::SCIPgetStatus(solved.scip_ptr()) });
    let obj = solved.best_sol().map(|s| s.obj_val());
    Ok((t, obj))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_params_are_typed_and_checked() {
        let m = new_scip().unwrap();
        let p = m.scip_ptr();
        set_raw_param(p, "limits/nodes", "100").unwrap();
        set_raw_param(p, "limits/gap", "0.01").unwrap();
        set_raw_param(p, "misc/catchctrlc", "false").unwrap();
        set_raw_param(p, "lp/initalgorithm", "d").unwrap();
        assert!(set_raw_param(p, "limits/no_such", "1").unwrap_err().contains("no such parameter"));
        assert!(set_raw_param(p, "limits/nodes", "many").unwrap_err().contains("longint"));
        assert!(set_raw_param(p, "limits/gap", "-1").unwrap_err().contains("refused"));
    }

    #[test]
    fn version_is_ten() {
        assert!(scip_version().starts_with("10."), "{}", scip_version());
    }

    #[test]
    fn native_reader() {
        let dir = tempfile::tempdir().unwrap();
        let (mps, lp) = (dir.path().join("t.mps"), dir.path().join("t.lp"));
        std::fs::write(&mps, TEST_MPS).unwrap();
        std::fs::write(&lp, TEST_LP).unwrap();
        for p in [&mps, &lp] {
            let (t, obj) = solve_file_with_native_reader(p).unwrap();
            assert_eq!(t, Termination::Optimal);
            assert!((obj.unwrap() - 5.0).abs() < 1e-9, "{p:?}: {obj:?}");
        }
        assert!(solve_file_with_native_reader(&dir.path().join("missing.mps")).is_err());
        // A syntax error is a typed error (SCIP also prints it on stderr).
        let bad = dir.path().join("bad.lp");
        std::fs::write(&bad, "Minimize\n obj: 2 x +\nSubject To\n c1: x >= >= 1\nEnd\n").unwrap();
        assert!(solve_file_with_native_reader(&bad).is_err());
    }

    /// min -x - y + 10, 2x + 3y <= 12, x, y integer in [0, 4]: optimum 5.
    const TEST_MPS: &str = "NAME          T1\nROWS\n N  obj\n L  c1\nCOLUMNS\n    MARKER                 'MARKER'                 'INTORG'\n    x         obj       -1.0           c1        2.0\n    y         obj       -1.0           c1        3.0\n    MARKER                 'MARKER'                 'INTEND'\nRHS\n    RHS       c1        12.0           obj       -10.0\nBOUNDS\n UP BND       x         4.0\n UP BND       y         4.0\nENDATA\n";
    const TEST_LP: &str = "Minimize\n obj: - x - y + 10\nSubject To\n c1: 2 x + 3 y <= 12\nBounds\n 0 <= x <= 4\n 0 <= y <= 4\nGeneral\n x y\nEnd\n";
}
