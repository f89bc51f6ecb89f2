//! HiGHS backend (crate `highs`, with `highs-sys` for what the safe crate does not wrap: the
//! objective offset and sense, the MIP dual bound, node count, run time, version and the
//! solver's own file reader and writer).
//!
//! HiGHS is compiled into the binary (vendored source), so it is the default backend.

use super::stop::StopControl;
use super::{
    guarded_solve, Capabilities, LazyRow, LimitKind, LogTarget, LpSession, PointSink, Progress, ProgressSink, RawParam,
    SolveOptions, SolveResult, Solver, SolverError, SolverErrorKind, SolverKind, StrategyHints, Termination,
};
use crate::milp::NumericLimits;
use crate::milp::{Model, Sense};
use highs_sys as sys;
use std::ffi::{CStr, CString};
use std::sync::RwLock;

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
fn set<V: highs::HighsOptionValue + Copy + std::fmt::Debug>(
    m: &mut highs::Model,
    name: &str,
    v: V,
) -> Result<(), SolverError> {
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

fn apply_options(m: &mut highs::Model, model: &Model, o: &SolveOptions, ctl: &StopControl) -> Result<(), SolverError> {
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
    // The time left of the limit, so that it bounds the whole solve call.
    if let Some(t) = ctl.remaining() {
        set(m, "time_limit", t)?;
    }
    // HiGHS's default relative gap (1e-4) would stop short of netspec's "optimal"
    // (`OPTIMALITY_TOLERANCE`): without a gap from the user, HiGHS must close the gap.
    set(m, "mip_rel_gap", o.rel_gap.unwrap_or(0.0))?;
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
    if let (Some(x), false) = (&o.mip_start, model.is_mip()) {
        // An LP has no use for a start but its values as a hint; a MIP's start goes in through
        // the user-solution callback at the end of the root (see `native`).
        debug_assert_eq!(x.len(), model.num_vars());
        m.try_set_solution(Some(x), None, None, None).map_err(|e| rejected(format!("MIP start: {e:?}")))?;
    }
    for p in o.params_for(KIND) {
        set_raw_param(m, &p.name, &p.value).map_err(|reason| {
            SolverError::new(KIND, SolverErrorKind::Param { name: format!("{KIND}.{}", p.name), reason })
        })?;
    }
    Ok(())
}

/// Sets one of HiGHS's own options by name, parsing the value by the option's type.
fn set_raw_param(m: &mut highs::Model, name: &str, value: &str) -> Result<(), String> {
    let c_name = CString::new(name).map_err(|_| "the name contains NUL".to_string())?;
    let mut ty: sys::HighsInt = -1;
    // SAFETY: live instance, NUL-terminated name, valid out-pointer.
    if unsafe { sys::Highs_getOptionType(m.as_mut_ptr(), c_name.as_ptr(), &mut ty) } != sys::STATUS_OK {
        return Err("HiGHS has no such option (see HiGHS's documentation for the list)".into());
    }
    let bad = |what: &str| format!("HiGHS option of type {what}: cannot use `{value}`");
    // SAFETY (each call): live instance, NUL-terminated name and value.
    let status = match ty {
        sys::kHighsOptionTypeBool => {
            let v = match value.to_ascii_lowercase().as_str() {
                "true" | "on" | "1" => 1,
                "false" | "off" | "0" => 0,
                _ => return Err(bad("bool")),
            };
            unsafe { sys::Highs_setBoolOptionValue(m.as_mut_ptr(), c_name.as_ptr(), v) }
        }
        sys::kHighsOptionTypeInt => {
            let v: sys::HighsInt = value.parse().map_err(|_| bad("int"))?;
            unsafe { sys::Highs_setIntOptionValue(m.as_mut_ptr(), c_name.as_ptr(), v) }
        }
        sys::kHighsOptionTypeDouble => {
            let v: f64 = value.parse().map_err(|_| bad("double"))?;
            unsafe { sys::Highs_setDoubleOptionValue(m.as_mut_ptr(), c_name.as_ptr(), v) }
        }
        _ => {
            let v = CString::new(value).map_err(|_| "the value contains NUL".to_string())?;
            unsafe { sys::Highs_setStringOptionValue(m.as_mut_ptr(), c_name.as_ptr(), v.as_ptr()) }
        }
    };
    if status == sys::STATUS_ERROR {
        return Err(format!("HiGHS refused the value `{value}` (out of range or not allowed)"));
    }
    Ok(())
}

/// Where HiGHS asks for a user solution (`ExternalMipSolutionQueryOrigin`): before a dive, and
/// at the end of the root node. A MIP start is handed over at the first of these, not before the
/// solve: an incumbent present while HiGHS processes its root changes the root (its heuristics and
/// cut loop), and on the paper's Fig. 2e and 2f that made the proof 2–3 times slower (2e: 377
/// nodes and 30 s instead of 35 nodes and 12 s, with the optimum as the start), while at the end
/// of the root the solve is the start-free one with the incumbent added.
const START_QUERY_ORIGINS: [i32; 2] = [1, 6];

/// What the callback needs between calls: where progress goes, when to stop, and a MIP start
/// still to hand over.
struct CallbackState<'a> {
    sink: Option<ProgressSink>,
    incumbents: Option<PointSink>,
    last: f64,
    stop: &'a StopControl,
    start: Option<&'a [f64]>,
}

/// HiGHS's interrupt callbacks (MIP, simplex, IPM), called often while it solves: forwards a
/// [`Progress`] report at most every 0.25 s (MIP), and interrupts HiGHS when the solve should
/// stop (the user's interrupt, or the deadline passed by the watchdog's grace).
unsafe extern "C" fn callback(
    kind: std::os::raw::c_int,
    _message: *const std::os::raw::c_char,
    out: *const sys::HighsCallbackDataOut,
    data_in: *mut sys::HighsCallbackDataIn,
    data: *mut std::ffi::c_void,
) {
    if out.is_null() || data.is_null() {
        return;
    }
    // SAFETY: HiGHS passes a valid output block, and `data` is the `CallbackState` registered
    // in `native`, alive for the whole run and used from the solving threads one at a time
    // (HiGHS calls back from its main search thread).
    let (out, state) = unsafe { (&*out, &mut *(data as *mut CallbackState)) };
    if kind == sys::kHighsCallbackCallbackMipUserSolution as std::os::raw::c_int {
        if START_QUERY_ORIGINS.contains(&{ out.external_solution_query_origin }) {
            if let (Some(x), false) = (state.start.take(), data_in.is_null()) {
                // SAFETY: a valid input block in a user-solution callback; `x` has one value per column.
                // The C wrapper copies the C block back into HiGHS's input after the call, so the
                // flag must be set there too (the API call sets it on the C++ side only).
                unsafe {
                    if sys::Highs_setCallbackSolution(data_in, x.len() as sys::HighsInt, x.as_ptr())
                        == sys::kHighsStatusOk
                    {
                        (*data_in).user_has_solution = 1;
                    }
                }
            }
        }
        return;
    }
    if kind == sys::kHighsCallbackMipImprovingSolution as std::os::raw::c_int {
        if let (Some(sink), false) = (&state.incumbents, out.mip_solution.is_null()) {
            // SAFETY: in an improving-solution callback HiGHS points `mip_solution` at the new
            // incumbent, one value per column of the original model, alive during the call.
            let x = unsafe { std::slice::from_raw_parts(out.mip_solution, out.mip_solution_size.max(0) as usize) };
            (sink.0)(out.objective_function_value, x);
        }
        return;
    }
    if state.stop.should_stop() && !data_in.is_null() {
        // SAFETY: HiGHS passes a valid input block with interrupt callbacks.
        unsafe { (*data_in).user_interrupt = 1 };
    }
    if kind != sys::kHighsCallbackMipInterrupt as std::os::raw::c_int || out.running_time - state.last < 0.25 {
        return;
    }
    let Some(sink) = &state.sink else { return };
    state.last = out.running_time;
    let finite = |v: f64| (v.is_finite() && v.abs() < 1e30).then_some(v);
    (sink.0)(Progress {
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
    with_scheduler(threads, || m.try_solve())
}

/// Runs `run` (a HiGHS solve) under the scheduler lock, resetting HiGHS's global scheduler
/// first when `threads` differs from its count (see [`run_with_threads`]).
fn with_scheduler<R>(threads: Option<u32>, run: impl FnOnce() -> R) -> R {
    let current = *SCHEDULER_THREADS.read().unwrap_or_else(|e| e.into_inner());
    match threads {
        Some(t) if t != current => {
            let mut guard = SCHEDULER_THREADS.write().unwrap_or_else(|e| e.into_inner());
            if *guard != t {
                // SAFETY: we hold the exclusive lock, so no HiGHS solve runs in this process.
                unsafe { sys::Highs_resetGlobalScheduler(1) };
                *guard = t;
            }
            run()
        }
        _ => {
            let _shared = SCHEDULER_THREADS.read().unwrap_or_else(|e| e.into_inner());
            run()
        }
    }
}

/// HiGHS reports a model without columns as "empty" without looking at its rows: it is optimal
/// (at the empty point) only when every row admits an activity of 0.
fn empty_model_termination(model: &Model) -> Termination {
    let excludes_zero = |l: f64, u: f64| l > 1e-9 || u < -1e-9;
    let (lhs, rhs) = model.row_sides();
    if lhs.iter().zip(rhs).any(|(&l, &u)| excludes_zero(l, u)) {
        Termination::Infeasible
    } else {
        Termination::Optimal
    }
}

fn termination(status: sys::HighsInt, o: &SolveOptions) -> Termination {
    match status {
        sys::MODEL_STATUS_OPTIMAL => Termination::Optimal,
        // Callers with the model at hand use `empty_model_termination` instead.
        sys::MODEL_STATUS_MODEL_EMPTY => Termination::Optimal,
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
            interrupt: true,
            raw_params: true,
            numeric: NumericLimits { max_matrix: 1e15, max_objective: 1e20, infinity: Some(1e20) },
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        guarded_solve(self, model, o, |o, ctl| native(model, o, ctl))
    }

    /// - `tuned`: `mip_pscost_minreliable=0` (HiGHS's default 8). HiGHS then branches on
    ///   pseudocosts from the first node instead of strong-branching every candidate until it has
    ///   eight observations; on Fig. 7d-L2 strong branching took 100,088 of the solve's 124,262 LP
    ///   iterations. Measured on the `strong` recipe's Table 1 rows (docs/benchmarks.md): 7d-L2
    ///   proven in 9.6 s instead of a 4.7 % gap at 12 s, 2f in 21.7 s instead of 38.4 s, no row lost.
    /// - `parallel_search` with two threads or more: `parallel=on`. HiGHS 1.15 otherwise runs its
    ///   tree search on one worker whatever the thread count; with it, on ⌈1.7·threads⌉ workers
    ///   (Fig. 7b-L2 proven in 128 s of its 174 instead of an 11.8 % gap, 8-L2 in 113 s instead
    ///   of 189 s, no row lost).
    /// - `keep_symmetry`: `presolve=off`. HiGHS finds a model's symmetry only without its
    ///   presolve, whose reductions break it first (Fig. 2b proven in about 30 s instead of a
    ///   14 % gap).
    fn strategy_hints(&self, h: &StrategyHints) -> Vec<RawParam> {
        let hint = |name: &str, value: &str| RawParam { solver: KIND, name: name.into(), value: value.into() };
        let mut out = Vec::new();
        if h.tuned {
            out.push(hint("mip_pscost_minreliable", "0"));
        }
        if h.parallel_search && h.threads.is_some_and(|t| t >= 2) {
            out.push(hint("parallel", "on"));
        }
        if h.keep_symmetry {
            out.push(hint("presolve", "off"));
        }
        out
    }

    fn lp_session(&self, model: &Model, o: &SolveOptions) -> Result<Option<Box<dyn LpSession>>, SolverError> {
        model.validate().map_err(|e| SolverError::new(KIND, e))?;
        if model.is_mip() {
            return Err(rejected("an LP session needs a model without integer variables"));
        }
        if model.num_vars() == 0 {
            // HiGHS calls a model without columns empty without reading its rows;
            // `Solver::solve` judges those (`empty_model_termination`).
            return Ok(None);
        }
        let mut m = load(model)?;
        m.make_quiet();
        if let Some(t) = o.threads {
            set(&mut m, "threads", t as i32)?;
        }
        Ok(Some(Box::new(HighsLp { m, threads: o.threads, cols: model.num_vars() })))
    }
}

/// An LP kept in a HiGHS instance between solves ([`Solver::lp_session`]): rows added with
/// `Highs_addRows` leave the basis valid (the new rows' slacks enter it), so the next
/// `Highs_run` goes on with the dual simplex from there instead of presolving and solving anew.
struct HighsLp {
    m: highs::Model,
    threads: Option<u32>,
    cols: usize,
}

impl LpSession for HighsLp {
    fn add_rows(&mut self, rows: &[LazyRow]) -> Result<(), SolverError> {
        let (mut lower, mut upper, mut starts, mut index, mut value) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for r in rows {
            starts.push(index.len() as sys::HighsInt);
            lower.push(r.lhs);
            upper.push(r.rhs);
            for &(v, c) in &r.terms {
                if v.index() >= self.cols {
                    return Err(rejected(format!(
                        "row `{}` names column {} of a session with {}",
                        r.name,
                        v.index(),
                        self.cols
                    )));
                }
                index.push(v.index() as sys::HighsInt);
                value.push(c);
            }
        }
        // SAFETY: live instance; the arrays hold `rows.len()` sides and starts and `index.len()`
        // entries, every index a column of the instance.
        let st = unsafe {
            sys::Highs_addRows(
                self.m.as_mut_ptr(),
                rows.len() as sys::HighsInt,
                lower.as_ptr(),
                upper.as_ptr(),
                index.len() as sys::HighsInt,
                starts.as_ptr(),
                index.as_ptr(),
                value.as_ptr(),
            )
        };
        if st == sys::STATUS_ERROR {
            return Err(rejected("Highs_addRows refused the rows"));
        }
        Ok(())
    }

    fn solve(&mut self, time_limit: Option<f64>) -> Result<SolveResult, SolverError> {
        let ptr = self.m.as_mut_ptr();
        // HiGHS's run clock accumulates over runs and its time limit is read against it: zero
        // it so that the limit is this solve's.
        // SAFETY: live instance.
        unsafe { sys::Highs_zeroAllClocks(ptr) };
        set(&mut self.m, "time_limit", time_limit.unwrap_or(f64::INFINITY))?;
        // SAFETY: live instance; the scheduler lock is held by `with_scheduler`.
        let st = with_scheduler(self.threads, || unsafe { sys::Highs_run(ptr) });
        let version = highs_version();
        if st == sys::STATUS_ERROR {
            return Ok(SolveResult::empty(KIND, version, Termination::Error("Highs_run failed on the LP".into())));
        }
        // SAFETY: live instance.
        let status = unsafe { sys::Highs_getModelStatus(ptr) };
        let mut r = SolveResult::empty(KIND, version, termination(status, &SolveOptions::default()));
        if info_int(ptr, c"primal_solution_status") == Some(sys::SOLUTION_STATUS_FEASIBLE as i64) {
            let mut x = vec![0.0; self.cols];
            // SAFETY: live instance; `x` has one slot per column, the other outputs are null.
            unsafe {
                sys::Highs_getSolution(
                    ptr,
                    x.as_mut_ptr(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                    std::ptr::null_mut(),
                )
            };
            r.primal = Some(x);
            // SAFETY: live instance.
            r.objective = Some(unsafe { sys::Highs_getObjectiveValue(ptr) });
        }
        if r.termination == Termination::Optimal {
            r.dual_bound = r.objective;
        }
        r.nodes = Some(0);
        // SAFETY: live instance.
        r.solver_time = Some(unsafe { sys::Highs_getRunTime(ptr) });
        Ok(r)
    }
}

/// The solve itself, after netspec's common checks (`guarded_solve`).
fn native(model: &Model, o: &SolveOptions, ctl: &StopControl) -> Result<SolveResult, SolverError> {
    let mut m = load(model)?;
    apply_options(&mut m, model, o, ctl)?;
    // The state lives on this stack frame for the whole solve; HiGHS only calls back during
    // `Highs_run`.
    let start = o.mip_start.as_deref().filter(|_| model.is_mip());
    let incumbents = o.incumbents.clone().filter(|_| model.is_mip());
    let mut state = CallbackState { sink: o.progress.clone(), incumbents, last: f64::NEG_INFINITY, stop: ctl, start };
    if state.sink.is_some() || state.incumbents.is_some() || ctl.is_armed() || state.start.is_some() {
        // SAFETY: live instance; the data pointer outlives the solve (see above).
        unsafe {
            sys::Highs_setCallback(
                m.as_mut_ptr(),
                Some(callback),
                &mut state as *mut CallbackState as *mut std::ffi::c_void,
            );
            sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackMipInterrupt);
            if state.incumbents.is_some() {
                sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackMipImprovingSolution);
            }
            if state.start.is_some() {
                sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackCallbackMipUserSolution);
            }
            if ctl.is_armed() {
                sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackSimplexInterrupt);
                sys::Highs_startCallback(m.as_mut_ptr(), sys::kHighsCallbackIpmInterrupt);
            }
        }
    }
    let solved = run_with_threads(m, o.threads).map_err(|e| rejected(format!("Highs_run: {e:?}")));
    let version = highs_version();
    let solved = match solved {
        Ok(s) => s,
        Err(e) => return Ok(SolveResult::empty(KIND, version, Termination::Error(e.to_string()))),
    };
    let ptr = solved.as_ptr();
    // SAFETY: live instance.
    let status = unsafe { sys::Highs_getModelStatus(ptr) };
    let termination =
        if status == sys::MODEL_STATUS_MODEL_EMPTY { empty_model_termination(model) } else { termination(status, o) };
    let mut r = SolveResult::empty(KIND, version, termination);
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
    // A start HiGHS never asked for (it stopped, or solved the problem, before the end of its
    // root) is still the best point known when HiGHS has none better.
    if let (Some(x), false) = (state.start, matches!(r.termination, Termination::Infeasible | Termination::Error(_))) {
        let start_objective = model.objective_value(x);
        let better = match (r.objective, model.sense) {
            (None, _) => true,
            (Some(o), crate::milp::Sense::Minimize) => start_objective < o,
            (Some(o), crate::milp::Sense::Maximize) => start_objective > o,
        };
        if better {
            r.primal = Some(x.to_vec());
            r.objective = Some(start_objective);
        }
    }
    // SAFETY: live instance.
    r.solver_time = Some(unsafe { sys::Highs_getRunTime(ptr) });
    r.finish(model.sense);
    Ok(r)
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Instant;

    /// HiGHS itself, without netspec's screen: a model without columns whose empty row excludes
    /// 0 is infeasible, not "optimal" (HiGHS reports such a model as empty).
    #[test]
    fn empty_row_without_columns_is_infeasible() {
        let mut m = Model::new("empty_row");
        m.add_ge("c", [], 1.0);
        let o = SolveOptions::default();
        let r = native(&m, &o, &StopControl::new(&o, Instant::now())).unwrap();
        assert_eq!(r.termination, Termination::Infeasible);
        assert!(r.primal.is_none());
        m.set_row_sides(crate::milp::RowId(0), -1.0, 1.0);
        let r = native(&m, &o, &StopControl::new(&o, Instant::now())).unwrap();
        assert_eq!(r.termination, Termination::Optimal);
    }

    /// The same with columns: HiGHS's presolve sees the empty row.
    #[test]
    fn empty_row_with_columns_is_infeasible() {
        let mut m = Model::new("empty_row_cols");
        let x = m.add_binary("x", 1.0);
        m.add_ge("c", [], 1.0);
        m.add_le("d", [(x, 1.0)], 1.0);
        let o = SolveOptions::default();
        let r = native(&m, &o, &StopControl::new(&o, Instant::now())).unwrap();
        assert_eq!(r.termination, Termination::Infeasible);
    }

    #[test]
    fn raw_params_are_typed_and_checked() {
        let mut m = load(&Model::new("p")).unwrap();
        set_raw_param(&mut m, "mip_heuristic_effort", "0.3").unwrap();
        set_raw_param(&mut m, "presolve", "off").unwrap();
        set_raw_param(&mut m, "mip_max_leaves", "10").unwrap();
        set_raw_param(&mut m, "output_flag", "false").unwrap();
        assert!(set_raw_param(&mut m, "no_such_option", "1").unwrap_err().contains("no such option"));
        assert!(set_raw_param(&mut m, "mip_max_leaves", "ten").unwrap_err().contains("int"));
        assert!(set_raw_param(&mut m, "mip_rel_gap", "-1").unwrap_err().contains("refused"));
    }
}
