//! HiGHS backend (crate `highs`, with `highs-sys` for what the safe crate does not wrap: the
//! objective offset and sense, the MIP dual bound, node count, run time, version and the
//! solver's own file reader and writer).
//!
//! HiGHS is compiled into the binary (vendored source), so it is the default backend.

use super::{preflight, Capabilities, Progress, ProgressSink, LimitKind, LogTarget, SolveOptions, SolveResult, Solver, SolverError, SolverErrorKind, SolverKind, Termination};
use crate::milp::{Model, Sense};
use highs_sys as sys;
use std::ffi::{CStr, CString};
use std::sync::RwLock;
use std::time::Instant;

/// The HiGHS backend.
#[derive(Clone, Copy, Debug, Default)]
pub struct HighsSolver;

const KIND: SolverKind = SolverKind::Highs;

/// HiGHS's version, e.g. `1.11.0`.
pub fn highs_version() -> String {
    // SAFETY: Highs_version returns a static NUL-terminated string.
    unsafe { CStr::from_ptr(sys::Highs_version()) }.to_string_lossy().into_owned()
}

fn rejected(msg: impl Into<String>) -> SolverError {
    SolverError::new(KIND, SolverErrorKind::Rejected(msg.into()))
}

/// Sets a HiGHS option through the safe crate, turning a refusal into a typed error.
fn set<V: highs::HighsOptionValue + Copy + std::fmt::Debug>(m: &mut highs::Model, name: &str, v: V) -> Result<(), SolverError> {
    m.try_set_option(name, v).map_err(|e| rejected(format!("option {name}={v:?}: {e:?}")))
}

/// Loads `model` into a new HiGHS instance (columns with their CSC entries, rows with their
/// sides, sense and offset).
fn load(model: &Model) -> Result<highs::Model, SolverError> {
    let mut problem = highs::ColProblem::default();
    let (lhs, rhs) = model.row_sides();
    let rows: Vec<highs::Row> = lhs.iter().zip(rhs).map(|(&l, &u)| problem.add_row(l..=u)).collect();
    let (start, index, value) = model.to_csc();
    for (j, v) in model.vars().iter().enumerate() {
        let entries = (start[j]..start[j + 1]).map(|k| (rows[index[k] as usize], value[k]));
        problem.add_column_with_integrality(v.obj, v.lb..=v.ub, entries, v.kind.is_integral());
    }
    let mut m = highs::Model::try_new(problem).map_err(|e| rejected(format!("loading the model: {e:?}")))?;
    let sense = match model.sense {
        Sense::Minimize => sys::OBJECTIVE_SENSE_MINIMIZE,
        Sense::Maximize => sys::OBJECTIVE_SENSE_MAXIMIZE,
    };
    // SAFETY: the pointer is a live Highs instance owned by `m`.
    unsafe {
        sys::Highs_changeObjectiveSense(m.as_mut_ptr(), sense);
        sys::Highs_changeObjectiveOffset(m.as_mut_ptr(), model.obj_constant);
    }
    Ok(m)
}

fn apply_options(m: &mut highs::Model, model: &Model, o: &SolveOptions) -> Result<(), SolverError> {
    match &o.log {
        LogTarget::Quiet => m.make_quiet(),
        LogTarget::Stdout => {
            set(m, "output_flag", true)?;
            set(m, "log_to_console", true)?;
        }
        LogTarget::File(path) => {
            set(m, "output_flag", true)?;
            set(m, "log_to_console", false)?;
            let p = path.to_str().ok_or_else(|| rejected("log file path is not UTF-8"))?;
            m.try_set_option("log_file", p).map_err(|e| rejected(format!("log_file: {e:?}")))?;
        }
    }
    if let Some(t) = o.time_limit {
        set(m, "time_limit", t)?;
    }
    if let Some(g) = o.rel_gap {
        set(m, "mip_rel_gap", g)?;
    }
    if let Some(g) = o.abs_gap {
        set(m, "mip_abs_gap", g)?;
    }
    if let Some(t) = o.threads {
        set(m, "threads", t as i32)?;
    }
    if let Some(s) = o.seed {
        set(m, "random_seed", (s % (i32::MAX as u64)) as i32)?;
    }
    if let Some(n) = o.node_limit {
        set(m, "mip_max_nodes", n.min(i32::MAX as u64) as i32)?;
    }
    if let Some(x) = &o.mip_start {
        debug_assert_eq!(x.len(), model.num_vars());
        m.try_set_solution(Some(x), None, None, None).map_err(|e| rejected(format!("MIP start: {e:?}")))?;
    }
    Ok(())
}

/// What the progress callback needs between calls.
struct ProgressState {
    sink: ProgressSink,
    last: f64,
}

/// HiGHS's MIP "interrupt" callback, called often during branch and bound: forwards a
/// [`Progress`] report at most every 0.25 s, and never interrupts.
unsafe extern "C" fn progress_callback(
    _kind: std::os::raw::c_int,
    _message: *const std::os::raw::c_char,
    out: *const sys::HighsCallbackDataOut,
    _in: *mut sys::HighsCallbackDataIn,
    data: *mut std::ffi::c_void,
) {
    if out.is_null() || data.is_null() {
        return;
    }
    // SAFETY: HiGHS passes a valid output block, and `data` is the `ProgressState` registered
    // in `solve`, alive for the whole run and used from this one thread.
    let (out, state) = unsafe { (&*out, &mut *(data as *mut ProgressState)) };
    if out.running_time - state.last < 0.25 {
        return;
    }
    state.last = out.running_time;
    let finite = |v: f64| (v.is_finite() && v.abs() < 1e30).then_some(v);
    (state.sink.0)(Progress {
        elapsed: out.running_time,
        primal: finite(out.mip_primal_bound),
        dual: finite(out.mip_dual_bound),
        nodes: out.mip_node_count.max(0) as u64,
    });
}

/// The thread count HiGHS's process-global task scheduler was last started with (0: never).
static SCHEDULER_THREADS: RwLock<u32> = RwLock::new(0);

/// Runs a solve. HiGHS's task scheduler is global to the process and keeps the thread count of
/// the first solve; a solve that asks for a different count resets it, under an exclusive lock
/// so that no other HiGHS solve is running meanwhile. Solves that keep the count share the lock.
fn run_with_threads(m: highs::Model, threads: Option<u32>) -> Result<highs::SolvedModel, highs::HighsStatus> {
    let current = *SCHEDULER_THREADS.read().unwrap_or_else(|e| e.into_inner());
    match threads {
        Some(t) if t != current => {
            let mut guard = SCHEDULER_THREADS.write().unwrap_or_else(|e| e.into_inner());
            if *guard != t {
                // SAFETY: we hold the exclusive lock, so no HiGHS solve runs in this process.
                unsafe { sys::Highs_resetGlobalScheduler(1) };
                *guard = t;
            }
            m.try_solve()
        }
        _ => {
            let _shared = SCHEDULER_THREADS.read().unwrap_or_else(|e| e.into_inner());
            m.try_solve()
        }
    }
}

fn termination(status: sys::HighsInt, o: &SolveOptions) -> Termination {
    match status {
        sys::MODEL_STATUS_OPTIMAL | sys::MODEL_STATUS_MODEL_EMPTY => Termination::Optimal,
        sys::MODEL_STATUS_INFEASIBLE => Termination::Infeasible,
        sys::MODEL_STATUS_UNBOUNDED => Termination::Unbounded,
        sys::MODEL_STATUS_UNBOUNDED_OR_INFEASIBLE => Termination::InfeasibleOrUnbounded,
        sys::MODEL_STATUS_REACHED_TIME_LIMIT => Termination::Limit(LimitKind::Time),
        // HiGHS reports its node limit (`mip_max_nodes`) as the "solution limit" status; netspec
        // sets no other limit of that family (leaves, improving solutions).
        sys::MODEL_STATUS_REACHED_SOLUTION_LIMIT if o.node_limit.is_some() => Termination::Limit(LimitKind::Node),
        sys::MODEL_STATUS_REACHED_SOLUTION_LIMIT => Termination::Limit(LimitKind::Solution),
        sys::MODEL_STATUS_REACHED_INTERRUPT => Termination::Limit(LimitKind::Interrupt),
        sys::MODEL_STATUS_REACHED_ITERATION_LIMIT | sys::MODEL_STATUS_REACHED_MEMORY_LIMIT => {
            Termination::Limit(LimitKind::Other)
        }
        sys::MODEL_STATUS_OBJECTIVE_BOUND | sys::MODEL_STATUS_OBJECTIVE_TARGET => Termination::Limit(LimitKind::Other),
        sys::MODEL_STATUS_SOLVE_ERROR | sys::MODEL_STATUS_POSTSOLVE_ERROR | sys::MODEL_STATUS_PRESOLVE_ERROR => {
            Termination::NumericalError
        }
        s => Termination::Error(format!("HiGHS model status {s}")),
    }
}

fn info_f64(ptr: *const std::ffi::c_void, name: &CStr) -> Option<f64> {
    let mut v = 0.0;
    // SAFETY: live instance, NUL-terminated name, valid out-pointer.
    let st = unsafe { sys::Highs_getDoubleInfoValue(ptr, name.as_ptr(), &mut v) };
    (st == sys::STATUS_OK).then_some(v)
}

fn info_i64(ptr: *const std::ffi::c_void, name: &CStr) -> Option<i64> {
    let mut v: i64 = 0;
    // SAFETY: as above.
    let st = unsafe { sys::Highs_getInt64InfoValue(ptr, name.as_ptr(), &mut v) };
    (st == sys::STATUS_OK).then_some(v)
}

fn info_int(ptr: *const std::ffi::c_void, name: &CStr) -> Option<i64> {
    let mut v: sys::HighsInt = 0;
    // SAFETY: as above.
    let st = unsafe { sys::Highs_getIntInfoValue(ptr, name.as_ptr(), &mut v) };
    (st == sys::STATUS_OK).then_some(v as i64)
}

impl Solver for HighsSolver {
    fn kind(&self) -> SolverKind {
        KIND
    }

    fn version(&self) -> String {
        highs_version()
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
            lazy_constraints: false,
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        let t0 = Instant::now();
        preflight(KIND, &self.capabilities(), model, o)?;
        let mut m = load(model)?;
        apply_options(&mut m, model, o)?;
        // The state lives on this stack frame for the whole solve; HiGHS only calls back
        // during `Highs_run`.
        let mut progress = o.progress.clone().map(|sink| ProgressState { sink, last: f64::NEG_INFINITY });
        if let Some(state) = progress.as_mut() {
            // SAFETY: live instance; the data pointer outlives the solve (see above).
            unsafe {
                sys::Highs_setCallback(m.as_mut_ptr(), Some(progress_callback), state as *mut ProgressState as *mut std::ffi::c_void);
                sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackMipInterrupt);
            }
        }
        let solved = run_with_threads(m, o.threads).map_err(|e| rejected(format!("Highs_run: {e:?}")));
        let solved = match solved {
            Ok(s) => s,
            Err(e) => {
                let mut r = SolveResult::empty(KIND, self.version(), Termination::Error(e.to_string()));
                r.wall_time = t0.elapsed().as_secs_f64();
                return Ok(r);
            }
        };
        let ptr = solved.as_ptr();
        // SAFETY: live instance.
        let status = unsafe { sys::Highs_getModelStatus(ptr) };
        let mut r = SolveResult::empty(KIND, self.version(), termination(status, o));
        let has_primal = info_int(ptr, c"primal_solution_status") == Some(sys::SOLUTION_STATUS_FEASIBLE as i64);
        if has_primal && model.num_vars() > 0 {
            r.primal = Some(solved.get_solution().columns().to_vec());
            // SAFETY: live instance.
            r.objective = Some(unsafe { sys::Highs_getObjectiveValue(ptr) });
        } else if has_primal || (model.num_vars() == 0 && r.termination == Termination::Optimal) {
            r.primal = Some(Vec::new());
            r.objective = Some(model.obj_constant);
        }
        if model.is_mip() {
            r.dual_bound = info_f64(ptr, c"mip_dual_bound").filter(|b| b.is_finite());
            r.nodes = info_i64(ptr, c"mip_node_count").map(|n| n.max(0) as u64);
        } else if r.termination == Termination::Optimal {
            r.dual_bound = r.objective;
            r.nodes = Some(0);
        }
        // SAFETY: live instance.
        r.solver_time = Some(unsafe { sys::Highs_getRunTime(ptr) });
        r.finish(model.sense, o.rel_gap.is_some() || o.abs_gap.is_some());
        r.wall_time = t0.elapsed().as_secs_f64();
        Ok(r)
    }
}

/// Reads a model file with HiGHS's own reader and solves it (used to check that files netspec
/// writes are read faithfully by HiGHS itself). Returns the termination and objective.
pub fn solve_file_with_native_reader(path: &std::path::Path) -> Result<(Termination, Option<f64>), SolverError> {
    let c = CString::new(path.to_string_lossy().as_bytes()).map_err(|_| rejected("path contains NUL"))?;
    // SAFETY: create/destroy pair; all calls on the live instance.
    unsafe {
        let h = sys::Highs_create();
        sys::Highs_setBoolOptionValue(h, c"output_flag".as_ptr(), 0);
        let st = sys::Highs_readModel(h, c.as_ptr());
        if st == sys::STATUS_ERROR {
            sys::Highs_destroy(h);
            return Err(rejected(format!("HiGHS could not read {}", path.display())));
        }
        sys::Highs_run(h);
        let status = sys::Highs_getModelStatus(h);
        let t = termination(status, &SolveOptions::default());
        let obj = matches!(t, Termination::Optimal).then(|| sys::Highs_getObjectiveValue(h));
        sys::Highs_destroy(h);
        Ok((t, obj))
    }
}

/// A model loaded into HiGHS, for using HiGHS's own writer (the benchmarks compare writers on a
/// model already in memory on both sides).
pub struct LoadedModel(highs::Model);

impl LoadedModel {
    /// Loads `model` into a new HiGHS instance.
    pub fn new(model: &Model) -> Result<Self, SolverError> {
        model.validate().map_err(|e| SolverError::new(KIND, e))?;
        let mut m = load(model)?;
        m.make_quiet();
        Ok(LoadedModel(m))
    }

    /// Writes the model with HiGHS's own writer (`.mps` or `.lp` by extension).
    pub fn write(&mut self, path: &std::path::Path) -> Result<(), SolverError> {
        let c = CString::new(path.to_string_lossy().as_bytes()).map_err(|_| rejected("path contains NUL"))?;
        // SAFETY: live instance, NUL-terminated path.
        let st = unsafe { sys::Highs_writeModel(self.0.as_mut_ptr(), c.as_ptr()) };
        if st == sys::STATUS_ERROR {
            return Err(rejected(format!("HiGHS could not write {}", path.display())));
        }
        Ok(())
    }
}
