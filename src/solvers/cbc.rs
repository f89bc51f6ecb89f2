//! COIN-OR CBC backend (crate `coin_cbc`, with `coin_cbc_sys` and a few declarations of our own
//! for what the safe crate does not wrap: the status codes, the best solution, the best possible
//! bound, the node count, the version and CBC's own file readers).
//!
//! CBC is linked from the Debian package (`coinor-libcbc-dev`, CBC 2.10.8).
//!
//! # How the model is given to CBC
//!
//! CBC's C interface solves a model without integer variables with a bare call to Clp, which
//! ignores every parameter (time limit, log level…) and reports an unbounded LP as "infeasible".
//! So netspec always appends one extra column: an **integer column fixed at 1 whose objective
//! coefficient is the model's constant term**. This sends every solve, LP or MIP, through CBC's
//! full driver (`CbcMain1`), so that all options are honoured and the statuses are CBC's; it also
//! puts the objective constant inside CBC, so that CBC's objective, bound and its gap limits all
//! include it, as netspec's own [`gap`](super::gap) does. The column is removed from the
//! reported solution.
//!
//! # Options
//!
//! | option | CBC parameter |
//! |---|---|
//! | `time_limit` | `timeMode elapsed` + `seconds` (wall clock, fractional seconds honoured) |
//! | `rel_gap` / `abs_gap` | `ratioGap` / `allowableGap` (CBC's own gap definitions) |
//! | `threads` | `threads` (the Debian build has CBC's thread support; at most 99; opportunistic, so a multi-threaded search is not repeatable) |
//! | `seed` | `randomSeed` (Clp) and `randomCbcSeed` (CBC), mapped into `1..=i32::MAX-1` because 0 means "use the time of day" |
//! | `node_limit` | `maxNodes` (capped at `i32::MAX`) |
//! | `log` | `logLevel`/`slogLevel` 0 (quiet) or 1 (stdout); a log **file** is unsupported |
//! | `mip_start` | `Cbc_setInitialSolution` (checked by CBC; an infeasible start is dropped) |
//! | `interrupt` | a solve in a worker process (below) stopped by SIGINT |
//! | `params` | any CBC command-line parameter (`cuts=off` → `-cuts off`); names and values are first tried on a tiny model in a worker whose output is read, and one CBC answers with "No match", "is illegal" or a list of options is refused |
//!
//! # Time limits and interrupts: the worker process
//!
//! CBC does not keep its time limit: its preprocessing and root never look at the clock (on
//! `models/fig9b1.toml` with a 10 s limit it ran 16 s at 0 nodes), and it subtracts the
//! preprocessing time from the limit a second time for the search, so that elsewhere it stops
//! seconds *before* the limit. Nor can it be stopped from outside through its C interface.
//! So a CBC solve with a time limit or an [`Interrupt`](super::Interrupt) runs in a **worker
//! process** (`fork` once the model is loaded), in its own process group and killed if netspec
//! dies (`PR_SET_PDEATHSIG`). The worker switches on CBC's own SIGINT handler (which ends the
//! branch and bound at the next node and keeps the incumbent, as "user event"); netspec sends
//! SIGINT at the deadline (or on the interrupt) and, if the worker has not ended 0.5 s later
//! (CBC was in preprocessing or a long LP, which SIGINT cannot stop), kills it. CBC's own
//! `seconds` is then only a backstop, set well past the deadline. The worker writes its
//! result into memory shared with netspec. A killed worker leaves no solution of CBC's; the
//! result then carries the MIP start, if one was given (it passed netspec's check), as the best
//! point known. CBC's SIGINT handler is reached through the `Cbc_Model` structure of CBC 2.10's
//! C interface (`Coin_C_defines.h`) and the layout of `CbcSolverUsefulData`, checked before use;
//! where the check fails, the worker is only killed (at the deadline plus 0.5 s) and CBC keeps
//! its own limit.
//!
//! CBC does not report its run time through the C interface, so `solver_time` is netspec's own
//! measurement of the native solve (`Cbc_solve`), taken after the process-wide lock below is
//! held: it excludes time spent queueing behind other CBC solves, as a solver-reported time would.
//!
//! # Concurrency
//!
//! CBC 2.10 is not thread-safe: `coin_cbc` (feature `singlethread-cbc`) serialises model
//! creation, solves and deletion behind one process-wide lock, which netspec keeps by going
//! through `coin_cbc::raw::Model`, and holds a lock of its own around each whole solve (load,
//! solve, read back) so that queueing happens in one visible place. Concurrent CBC solves
//! therefore run one after the other; the time spent waiting is in `wall_time` but neither in
//! CBC's time limit nor in `solver_time`.

use super::stop::StopControl;
use super::{
    guarded_solve, Capabilities, LimitKind, LogTarget, SolveOptions, SolveResult, Solver, SolverError, SolverErrorKind,
    SolverKind, Termination,
};
use crate::milp::NumericLimits;
use crate::milp::{Model, Sense};
use coin_cbc::raw::Model as CbcModel;
use coin_cbc_sys as sys;
use std::ffi::{c_char, c_int, CStr, CString};
use std::sync::Mutex;
use std::time::Instant;

/// Serialises netspec's CBC solves (see the module docs).
static CBC_SOLVES: Mutex<()> = Mutex::new(());

/// The CBC backend.
#[derive(Clone, Copy, Debug, Default)]
pub struct CbcSolver;

const KIND: SolverKind = SolverKind::Cbc;

/// Functions of CBC 2.10's C interface (`Cbc_C_Interface.h`, all exported by the Debian
/// `libCbcSolver`) that `coin_cbc_sys` 0.1.3 does not declare.
mod ffi {
    use super::{c_char, c_int, sys};
    #[link(name = "CbcSolver")]
    extern "C" {
        /// The best integer-feasible solution found, or NULL if none.
        pub fn Cbc_bestSolution(model: *mut sys::Cbc_Model) -> *const f64;
        /// Reads an LP file; returns 0 on success.
        pub fn Cbc_readLp(model: *mut sys::Cbc_Model, filename: *const c_char) -> c_int;
        /// Adds a column (buffered until the next solve when `nz` is 0).
        pub fn Cbc_addCol(
            model: *mut sys::Cbc_Model,
            name: *const c_char,
            lb: f64,
            ub: f64,
            obj: f64,
            is_integer: c_char,
            nz: c_int,
            rows: *mut c_int,
            coefs: *mut f64,
        );
    }
}

// `coin_cbc::raw::Model` (pinned at =0.1.9) is a struct whose only field is the
// `*mut Cbc_Model` it owns. This check guarantees the struct is exactly that pointer (same size,
// so the single field sits at offset 0 with no padding), which `raw_ptr` relies on.
const _: () = assert!(std::mem::size_of::<CbcModel>() == std::mem::size_of::<*mut sys::Cbc_Model>());

/// The C model behind a `coin_cbc::raw::Model`, for the functions the safe crate does not wrap.
fn raw_ptr(m: &CbcModel) -> *mut sys::Cbc_Model {
    // SAFETY: `CbcModel` consists of exactly one `*mut Cbc_Model` field (see the size assertion
    // above), so reading the struct's bytes as that pointer yields the live model it owns. The
    // pointer stays valid while `m` is alive; callers only use it within that lifetime.
    unsafe { *(m as *const CbcModel as *const *mut sys::Cbc_Model) }
}

/// CBC's version, e.g. `2.10.8`.
pub fn cbc_version() -> String {
    // SAFETY: Cbc_getVersion returns a static NUL-terminated string.
    unsafe { CStr::from_ptr(sys::Cbc_getVersion()) }.to_string_lossy().into_owned()
}

fn rejected(msg: impl Into<String>) -> SolverError {
    SolverError::new(KIND, SolverErrorKind::Rejected(msg.into()))
}

/// Sets a CBC command-line parameter (`-name value`, applied by `CbcMain1` at solve time).
fn set_param(m: &mut CbcModel, name: &str, value: &str) -> Result<(), SolverError> {
    let n = CString::new(name).map_err(|_| rejected(format!("parameter name {name:?} contains NUL")))?;
    let v = CString::new(value).map_err(|_| rejected(format!("parameter {name}: value contains NUL")))?;
    m.set_parameter(&n, &v);
    Ok(())
}

fn to_c_int(n: usize, what: &str) -> Result<c_int, SolverError> {
    c_int::try_from(n).map_err(|_| {
        SolverError::new(
            KIND,
            SolverErrorKind::ModelUnsupported(format!("{n} {what}: too many for CBC's 32-bit indices")),
        )
    })
}

/// Loads `model` into a new CBC instance: the columns (CSC), the rows with their sides, the
/// integrality, the sense, and the extra integer column fixed at 1 that carries the objective
/// constant (see the module documentation).
fn load(model: &Model) -> Result<CbcModel, SolverError> {
    let n = model.num_vars();
    let ncols = n + 1;
    let nrows = model.num_rows();
    to_c_int(ncols, "columns")?;
    to_c_int(nrows, "rows")?;
    to_c_int(model.num_nonzeros(), "nonzeros")?;
    let (start, index, value) = model.to_csc();
    let mut cstart: Vec<c_int> = start.iter().map(|&s| s as c_int).collect();
    cstart.push(index.len() as c_int); // the extra column has no matrix entries
    let cindex: Vec<c_int> = index.iter().map(|&r| r as c_int).collect();
    let mut lb: Vec<f64> = model.vars().iter().map(|v| v.lb).collect();
    let mut ub: Vec<f64> = model.vars().iter().map(|v| v.ub).collect();
    let mut obj: Vec<f64> = model.vars().iter().map(|v| v.obj).collect();
    lb.push(1.0);
    ub.push(1.0);
    obj.push(model.obj_constant);
    let (rlb, rub) = model.row_sides();
    let mut m = CbcModel::new();
    m.load_problem(ncols, nrows, &cstart, &cindex, &value, Some(&lb), Some(&ub), Some(&obj), Some(rlb), Some(rub));
    for (j, v) in model.vars().iter().enumerate() {
        if v.kind.is_integral() {
            m.set_integer(j);
        }
    }
    m.set_integer(n);
    let sense = match model.sense {
        Sense::Minimize => 1.0,
        Sense::Maximize => -1.0,
    };
    // SAFETY: live model owned by `m`.
    unsafe { sys::Cbc_setObjSense(raw_ptr(&m), sense) };
    Ok(m)
}

/// Maps a seed into `1..=i32::MAX-1`: CBC and Clp read 0 as "seed from the time of day".
fn cbc_seed(seed: u64) -> String {
    (1 + seed % (i32::MAX as u64 - 1)).to_string()
}

fn set_quiet(m: &mut CbcModel, quiet: bool) -> Result<(), SolverError> {
    let level = if quiet { 0 } else { 1 };
    m.set_log_level(level);
    set_param(m, "logLevel", &level.to_string())?;
    set_param(m, "slogLevel", &level.to_string())
}

/// How CBC's own time limit is set: to the time left, or, when netspec stops the worker at the
/// deadline with SIGINT, only as a backstop well past it (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
enum OwnLimit {
    Remaining,
    Backstop,
}

fn apply_options(
    m: &mut CbcModel,
    model: &Model,
    o: &SolveOptions,
    ctl: &StopControl,
    own_limit: OwnLimit,
) -> Result<(), SolverError> {
    match &o.log {
        LogTarget::Quiet => set_quiet(m, true)?,
        LogTarget::Stdout => set_quiet(m, false)?,
        // Refused by the capabilities (preflight) before we get here.
        LogTarget::File(_) => return Err(rejected("CBC cannot write a log file")),
    }
    if let Some(t) = ctl.remaining() {
        let t = match own_limit {
            OwnLimit::Remaining => t,
            OwnLimit::Backstop => 2.0 * t + 10.0,
        };
        set_param(m, "timeMode", "elapsed")?;
        set_param(m, "seconds", &t.to_string())?;
    }
    if let Some(g) = o.rel_gap {
        set_param(m, "ratioGap", &g.to_string())?;
    }
    if let Some(g) = o.abs_gap {
        set_param(m, "allowableGap", &g.to_string())?;
    }
    if let Some(t) = o.threads {
        // CBC's `threads 0` is its plain single-threaded search (`1` would start one worker
        // thread); it reads 100 and more as "repeatable mode + (n - 100) threads".
        if t >= 100 {
            return Err(rejected(format!("CBC takes at most 99 threads, got {t}")));
        }
        let t = if t <= 1 { 0 } else { t };
        set_param(m, "threads", &t.to_string())?;
    }
    if let Some(s) = o.seed {
        set_param(m, "randomSeed", &cbc_seed(s))?;
        set_param(m, "randomCbcSeed", &cbc_seed(s))?;
    }
    if let Some(nodes) = o.node_limit {
        set_param(m, "maxNodes", &nodes.min(i32::MAX as u64).to_string())?;
    }
    if let Some(x) = &o.mip_start {
        let mut start = Vec::with_capacity(model.num_vars() + 1);
        start.extend_from_slice(x);
        start.push(1.0);
        // CBC checks the start with Clp right away, at the model's current log level.
        m.set_initial_solution(&start);
    }
    for p in o.params_for(KIND) {
        set_param(m, &p.name, &p.value)?;
    }
    Ok(())
}

/// What a finished CBC solve reports, read from the model (in netspec's process or in the
/// worker, which writes it into shared memory).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
struct WorkerResult {
    status: c_int,
    secondary: c_int,
    optimal: c_int,
    infeasible: c_int,
    nodes: c_int,
    has_best: c_int,
    objective: f64,
    bound: f64,
}

impl WorkerResult {
    /// Reads the result of a solved model; copies the best solution (all columns) into `best`
    /// when there is one and `best` has room for it.
    ///
    /// # Safety
    /// `m` must be a live model after `Cbc_solve`; `best` is empty or has one slot per column.
    unsafe fn read(m: *mut sys::Cbc_Model, best: &mut [f64]) -> WorkerResult {
        // SAFETY: as the caller promises.
        unsafe {
            let p = ffi::Cbc_bestSolution(m);
            let has_best = !p.is_null() && !best.is_empty();
            if has_best {
                best.copy_from_slice(std::slice::from_raw_parts(p, best.len()));
            }
            WorkerResult {
                status: sys::Cbc_status(m),
                secondary: sys::Cbc_secondaryStatus(m),
                optimal: sys::Cbc_isProvenOptimal(m),
                infeasible: sys::Cbc_isProvenInfeasible(m),
                nodes: sys::Cbc_getNodeCount(m),
                has_best: has_best as c_int,
                objective: sys::Cbc_getObjValue(m),
                bound: sys::Cbc_getBestPossibleObjValue(m),
            }
        }
    }
}

/// CBC's `status()`/`secondaryStatus()` (see `CbcModel.hpp`) to a [`Termination`].
fn termination(o: &WorkerResult, is_mip: bool) -> Termination {
    match (o.status, o.secondary) {
        // "Linear relaxation not feasible (or worse than cutoff)" with an incumbent: the
        // search found nothing better than it (a MIP start that was already optimal), so the
        // incumbent is optimal.
        (0, 1) if o.has_best != 0 => Termination::Optimal,
        // Without one: also how CBC ends a search that completes without an integer solution.
        (_, 1) => Termination::Infeasible,
        // The LP relaxation is unbounded (CBC stops at the root). For an LP that is the answer;
        // a MIP may still have no integer point.
        (_, 7) if is_mip => Termination::InfeasibleOrUnbounded,
        (_, 7) => Termination::Unbounded,
        // Stopped on the gap limit: reported optimal, `SolveResult::finish` turns it into
        // `Limit(Gap)` when the gap is above the default tolerance.
        (0 | 1, 2) => Termination::Optimal,
        (_, 3) => Termination::Limit(LimitKind::Node),
        (_, 4) => Termination::Limit(LimitKind::Time),
        (_, 5) => Termination::Limit(LimitKind::Interrupt),
        (_, 6) => Termination::Limit(LimitKind::Solution),
        (_, 8) => Termination::Limit(LimitKind::Other),
        (2, _) => Termination::NumericalError,
        (5, _) => Termination::Limit(LimitKind::Interrupt),
        (0, _) if o.optimal != 0 => Termination::Optimal,
        (0, _) if o.infeasible != 0 => Termination::Infeasible,
        (1, _) => Termination::Limit(LimitKind::Other),
        (s, s2) => Termination::Error(format!("CBC status {s}, secondary status {s2}")),
    }
}

/// CBC's "infinity" for objective values (it reports 1e50 or DBL_MAX when there is none).
fn finite_cbc(v: f64) -> Option<f64> {
    (v.is_finite() && v.abs() < 1e40).then_some(v)
}

impl Solver for CbcSolver {
    fn kind(&self) -> SolverKind {
        KIND
    }

    fn version(&self) -> String {
        cbc_version()
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
            log_file: false,
            mip_start: true,
            reports_dual_bound: true,
            reports_nodes: true,
            reports_solver_time: true,
            reports_progress: false,
            lazy_constraints: false,
            interrupt: true,
            raw_params: true,
            numeric: NumericLimits::uniform(1e20, Some(1e30)),
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        guarded_solve(self, model, o, |o, ctl| native(model, o, ctl))
    }
}

/// The solve itself, after netspec's common checks (`guarded_solve`): in this process when
/// nothing can stop it early, else in a worker process (see the module docs).
fn native(model: &Model, o: &SolveOptions, ctl: &StopControl) -> Result<SolveResult, SolverError> {
    let _serial = CBC_SOLVES.lock().unwrap_or_else(|e| e.into_inner());
    params::check(o)?;
    let mut m = load(model)?;
    let in_worker = ctl.is_armed();
    let graceful = in_worker && worker::signal_stop_available(raw_ptr(&m));
    apply_options(&mut m, model, o, ctl, if graceful { OwnLimit::Backstop } else { OwnLimit::Remaining })?;
    let n = model.num_vars();
    let mut best = vec![0.0; n + 1];
    let t_solve = Instant::now();
    let ended = if in_worker {
        worker::run(raw_ptr(&m), &mut best, ctl, graceful)?
    } else {
        m.solve();
        // SAFETY: live, solved model; `best` has one slot per column.
        worker::Ended::Finished(unsafe { WorkerResult::read(raw_ptr(&m), &mut best) })
    };
    let solver_time = t_solve.elapsed().as_secs_f64();
    drop(m);
    let mut r = match ended {
        worker::Ended::Finished(out) => {
            let mut r = SolveResult::empty(KIND, cbc_version(), termination(&out, model.is_mip()));
            if out.has_best != 0 {
                best.truncate(n);
                r.primal = Some(best);
                r.objective = finite_cbc(out.objective);
            }
            let bound_meaningful = !matches!(
                r.termination,
                Termination::Infeasible
                    | Termination::Unbounded
                    | Termination::InfeasibleOrUnbounded
                    | Termination::Error(_)
            );
            if bound_meaningful && out.secondary == 1 {
                // Nothing beats the incumbent: its objective is the bound (CBC's own is the
                // cutoff's, or infinite).
                r.dual_bound = r.objective;
            } else if bound_meaningful {
                // In the model's own sense, with the constant column.
                r.dual_bound = finite_cbc(out.bound);
            }
            r.nodes = Some(out.nodes.max(0) as u64);
            r
        }
        worker::Ended::Killed => {
            // CBC's own incumbent died with the worker; the MIP start (checked by netspec
            // before the solve) is the best point known.
            let mut r = SolveResult::empty(KIND, cbc_version(), Termination::Limit(LimitKind::Interrupt));
            if let Some(x) = &o.mip_start {
                r.objective = Some(model.objective_value(x));
                r.primal = Some(x.clone());
            }
            r
        }
        worker::Ended::Died(why) => SolveResult::empty(KIND, cbc_version(), Termination::Error(why)),
    };
    r.solver_time = Some(solver_time);
    r.finish(model.sense);
    Ok(r)
}

/// CBC in a worker process (see the module docs).
mod worker {
    use super::{c_int, sys, WorkerResult, KIND as KIND_CBC};
    use crate::solvers::stop::StopControl;
    use crate::solvers::SolverError;
    use std::time::{Duration, Instant};

    /// How long a worker that was sent SIGINT may take to end before it is killed.
    const HARD_STOP: Duration = Duration::from_millis(500);

    /// How a worker ended.
    pub(super) enum Ended {
        /// CBC finished (on its own or after SIGINT) and wrote its result.
        Finished(WorkerResult),
        /// Killed by netspec (it did not stop in time).
        Killed,
        /// It ended without an result (CBC crashed or aborted).
        Died(String),
    }

    /// Offset of `useSignalHandler_` in CBC 2.10's `CbcSolverUsefulData`
    /// (`double totalTime_; std::vector<CbcOrClpParam> parameters_; bool noPrinting_;
    /// bool useSignalHandler_; …`, libstdc++'s three-pointer vector).
    const USE_SIGNAL_HANDLER: usize = 8 + 3 * 8 + 1;

    /// The `CbcSolverUsefulData` of a model: the third field of CBC 2.10's `Cbc_Model`
    /// (`OsiClpSolverInterface *solver_; CbcModel *model_; CbcSolverUsefulData *cbcData; …`,
    /// `Coin_C_defines.h`), if the data there looks like a fresh one: `totalTime_` 0, a
    /// non-empty parameter vector, both flags false (`Cbc_newModel` sets them so).
    fn solver_data(m: *mut sys::Cbc_Model) -> Option<*mut u8> {
        if !super::cbc_version().starts_with("2.10.") || m.is_null() {
            return None;
        }
        // SAFETY: `m` is a live `Cbc_Model` of CBC 2.10, whose first three fields are pointers
        // (public header); the reads below stay inside the `CbcSolverUsefulData` object up to
        // the two flags, which come before its last field.
        unsafe {
            let data = *(m as *const *mut u8).add(2);
            if data.is_null() || !(data as usize).is_multiple_of(8) {
                return None;
            }
            let total_time = *(data as *const f64);
            let v = data.add(8) as *const usize;
            let (begin, end, cap) = (*v, *v.add(1), *v.add(2));
            let (no_printing, use_signal) = (*data.add(USE_SIGNAL_HANDLER - 1), *data.add(USE_SIGNAL_HANDLER));
            let sane = total_time == 0.0
                && begin != 0
                && begin.is_multiple_of(8)
                && begin < end
                && end <= cap
                && no_printing <= 1
                && use_signal == 0;
            sane.then_some(data)
        }
    }

    /// Whether CBC's own SIGINT handler can be switched on for this model (the layout check
    /// of [`solver_data`] passes).
    pub(super) fn signal_stop_available(m: *mut sys::Cbc_Model) -> bool {
        solver_data(m).is_some()
    }

    /// Shared memory for the worker's result: a flag, the [`WorkerResult`], the best solution.
    struct Shared {
        ptr: *mut u8,
        len: usize,
    }

    const HEADER: usize = 64;
    const _: () = assert!(std::mem::size_of::<WorkerResult>() + 8 <= HEADER);

    impl Shared {
        fn new(columns: usize) -> Result<Shared, SolverError> {
            let len = HEADER + columns * 8;
            // SAFETY: anonymous shared mapping, checked below.
            let ptr = unsafe {
                libc::mmap(
                    std::ptr::null_mut(),
                    len,
                    libc::PROT_READ | libc::PROT_WRITE,
                    libc::MAP_SHARED | libc::MAP_ANONYMOUS,
                    -1,
                    0,
                )
            };
            if ptr == libc::MAP_FAILED {
                return Err(SolverError::new(KIND_CBC, std::io::Error::last_os_error()));
            }
            Ok(Shared { ptr: ptr as *mut u8, len })
        }

        fn done(&self) -> *mut u64 {
            self.ptr as *mut u64
        }

        fn result(&self) -> *mut WorkerResult {
            // SAFETY: inside the mapping (HEADER holds the flag and the result).
            unsafe { self.ptr.add(8) as *mut WorkerResult }
        }

        fn best(&mut self, columns: usize) -> &mut [f64] {
            // SAFETY: the mapping holds `columns` f64 after the header, 8-aligned.
            unsafe { std::slice::from_raw_parts_mut(self.ptr.add(HEADER) as *mut f64, columns) }
        }
    }

    impl Drop for Shared {
        fn drop(&mut self) {
            // SAFETY: our own mapping.
            unsafe { libc::munmap(self.ptr as *mut libc::c_void, self.len) };
        }
    }

    /// Forks a worker that solves `m` (loaded, options set) and waits for it, sending SIGINT at
    /// the deadline or on the interrupt and killing it [`HARD_STOP`] later. Copies the best
    /// solution into `best` when CBC found one.
    pub(super) fn run(
        m: *mut sys::Cbc_Model,
        best: &mut [f64],
        ctl: &StopControl,
        graceful: bool,
    ) -> Result<Ended, SolverError> {
        let mut shared = Shared::new(best.len())?;
        let parent = std::process::id() as libc::pid_t;
        // SIGINT stays blocked across the fork until the child has set its disposition, so
        // that a signal sent at once cannot kill it.
        let old_mask = block_sigint();
        // SAFETY: fork in a multi-threaded process: the child runs only CBC's solve on memory it
        // owns (the copied model), glibc's malloc and stdio (both made fork-safe by glibc), and
        // async-signal-safe calls; it never returns into Rust code that could take a lock held
        // by another thread, and ends with `_exit`.
        let pid = unsafe { libc::fork() };
        if pid == 0 {
            // SAFETY: in the child, see above.
            unsafe { child(m, &mut shared, best.len(), parent, graceful, &old_mask) }
        }
        // SAFETY: restoring this thread's signal mask.
        unsafe { libc::pthread_sigmask(libc::SIG_SETMASK, &old_mask, std::ptr::null_mut()) };
        if pid < 0 {
            return Err(SolverError::new(KIND_CBC, std::io::Error::last_os_error()));
        }
        let mut interrupted_at: Option<Instant> = None;
        let mut last_sigint = Instant::now();
        let mut killed = false;
        let status = loop {
            let mut status: c_int = 0;
            // SAFETY: our own child.
            let r = unsafe { libc::waitpid(pid, &mut status, libc::WNOHANG) };
            if r == pid {
                break status;
            }
            if r < 0 {
                return Err(SolverError::new(KIND_CBC, std::io::Error::last_os_error()));
            }
            let now = Instant::now();
            let due = ctl.interrupted() || ctl.deadline().is_some_and(|d| now >= d);
            match interrupted_at {
                None if due => {
                    // SAFETY: our own child.
                    unsafe { libc::kill(pid, libc::SIGINT) };
                    interrupted_at = Some(now);
                    last_sigint = now;
                }
                None => {}
                Some(t) if !killed && now >= t + HARD_STOP => {
                    // SAFETY: our own child.
                    unsafe { libc::kill(pid, libc::SIGKILL) };
                    killed = true;
                }
                // Again every 0.1 s: a SIGINT that came before CBC's branch and bound (when
                // its handler has nothing to stop yet) is lost.
                Some(_) if !killed && now >= last_sigint + Duration::from_millis(100) => {
                    // SAFETY: our own child.
                    unsafe { libc::kill(pid, libc::SIGINT) };
                    last_sigint = now;
                }
                Some(_) => {}
            }
            std::thread::sleep(Duration::from_millis(5));
        };
        // SAFETY: the child has ended; the flag and result were written before `_exit`.
        let finished = unsafe { std::ptr::read_volatile(shared.done()) } == 1;
        if finished {
            // SAFETY: as above.
            let out = unsafe { std::ptr::read_volatile(shared.result()) };
            if out.has_best != 0 {
                best.copy_from_slice(shared.best(best.len()));
            }
            return Ok(Ended::Finished(out));
        }
        if killed {
            return Ok(Ended::Killed);
        }
        let why = if libc::WIFSIGNALED(status) {
            format!("CBC's worker process died of signal {}", libc::WTERMSIG(status))
        } else {
            format!("CBC's worker process ended with code {} and no result", libc::WEXITSTATUS(status))
        };
        Ok(Ended::Died(why))
    }

    /// Blocks SIGINT for this thread; returns the previous mask.
    fn block_sigint() -> libc::sigset_t {
        // SAFETY: plain signal-set manipulation on this thread's mask.
        unsafe {
            let mut set: libc::sigset_t = std::mem::zeroed();
            let mut old: libc::sigset_t = std::mem::zeroed();
            libc::sigemptyset(&mut set);
            libc::sigaddset(&mut set, libc::SIGINT);
            libc::pthread_sigmask(libc::SIG_BLOCK, &set, &mut old);
            old
        }
    }

    /// The worker: solve, write the result, `_exit`.
    ///
    /// # Safety
    /// Only in the child of `fork`, with `m` the parent's loaded model.
    unsafe fn child(
        m: *mut sys::Cbc_Model,
        shared: &mut Shared,
        columns: usize,
        parent: libc::pid_t,
        graceful: bool,
        mask: &libc::sigset_t,
    ) -> ! {
        // SAFETY: async-signal-safe calls on our own process; the model is ours (a copy).
        unsafe {
            // Its own process group: a Ctrl-C at the terminal reaches netspec only, which then
            // decides; and it dies with netspec.
            libc::setpgid(0, 0);
            libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
            if libc::getppid() != parent {
                libc::_exit(2);
            }
            // Ignore SIGINT until CBC installs its own handler (when switched on below), then
            // let it through (it was blocked across the fork).
            libc::signal(libc::SIGINT, libc::SIG_IGN);
            libc::pthread_sigmask(libc::SIG_SETMASK, mask, std::ptr::null_mut());
            if graceful {
                if let Some(data) = solver_data(m) {
                    *data.add(USE_SIGNAL_HANDLER) = 1;
                }
            }
            sys::Cbc_solve(m);
            let out = WorkerResult::read(m, shared.best(columns));
            std::ptr::write_volatile(shared.result(), out);
            std::ptr::write_volatile(shared.done(), 1);
            libc::fflush(std::ptr::null_mut());
            libc::_exit(0)
        }
    }
}

/// Checking CBC parameters before a solve (see the module docs).
mod params {
    use super::{sys, SolveOptions, KIND as KIND_CBC};
    use crate::solvers::{SolverError, SolverErrorKind};
    use std::ffi::CString;
    use std::io::Read;
    use std::os::fd::FromRawFd;

    /// What CBC prints for a parameter it does not take.
    const REFUSALS: [&str; 5] =
        ["No match for", "Short match for", "Multiple matches for", " is illegal for", "Possible options for"];

    /// Tries every CBC parameter of `o` on a tiny model in a worker process whose standard
    /// output is read: an unknown name or a refused value is an error naming the parameter.
    pub(super) fn check(o: &SolveOptions) -> Result<(), SolverError> {
        for p in o.params_for(KIND_CBC) {
            let output = probe(&p.name, &p.value)?;
            if let Some(line) = output.lines().find(|l| REFUSALS.iter().any(|r| l.contains(r))) {
                return Err(SolverError::new(
                    KIND_CBC,
                    SolverErrorKind::Param {
                        name: format!("cbc.{}", p.name),
                        reason: format!("CBC says: {}", line.trim()),
                    },
                ));
            }
        }
        Ok(())
    }

    /// Runs CBC with `-name value` on `min x, x ≥ 0 integer, x ≤ 1` in a child process and
    /// returns what it printed.
    fn probe(name: &str, value: &str) -> Result<String, SolverError> {
        let io = |e| SolverError::new(KIND_CBC, e);
        let bad = || {
            SolverError::new(
                KIND_CBC,
                SolverErrorKind::Param { name: format!("cbc.{name}"), reason: "contains NUL".into() },
            )
        };
        let (n, v) = (CString::new(name).map_err(|_| bad())?, CString::new(value).map_err(|_| bad())?);
        let mut fds = [0 as libc::c_int; 2];
        // SAFETY: valid out-array.
        if unsafe { libc::pipe(fds.as_mut_ptr()) } != 0 {
            return Err(io(std::io::Error::last_os_error()));
        }
        // SAFETY: as in `worker::run`: the child only calls CBC and async-signal-safe functions.
        let pid = unsafe { libc::fork() };
        if pid < 0 {
            return Err(io(std::io::Error::last_os_error()));
        }
        if pid == 0 {
            // SAFETY: in the child.
            unsafe {
                libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
                libc::dup2(fds[1], 1);
                libc::close(fds[0]);
                let m = sys::Cbc_newModel();
                let (start, index, value, lb, ub, obj, rlb, rub) =
                    ([0, 1], [0], [1.0], [0.0], [1.0], [1.0], [f64::NEG_INFINITY], [1.0]);
                sys::Cbc_loadProblem(
                    m,
                    1,
                    1,
                    start.as_ptr(),
                    index.as_ptr(),
                    value.as_ptr(),
                    lb.as_ptr(),
                    ub.as_ptr(),
                    obj.as_ptr(),
                    rlb.as_ptr(),
                    rub.as_ptr(),
                );
                sys::Cbc_setInteger(m, 0);
                sys::Cbc_setParameter(m, c"logLevel".as_ptr(), c"0".as_ptr());
                sys::Cbc_setParameter(m, n.as_ptr(), v.as_ptr());
                sys::Cbc_solve(m);
                libc::fflush(std::ptr::null_mut());
                libc::_exit(0);
            }
        }
        // SAFETY: our write end, no longer needed; the read end becomes a File we own.
        let mut reader = unsafe {
            libc::close(fds[1]);
            std::fs::File::from_raw_fd(fds[0])
        };
        let mut text = String::new();
        let read = reader.read_to_string(&mut text);
        let mut status = 0;
        // SAFETY: our own child.
        unsafe { libc::waitpid(pid, &mut status, 0) };
        read.map_err(io)?;
        Ok(text)
    }
}

/// Reads a model file with CBC's own readers (`Cbc_readLp` for `.lp`, `Cbc_readMps` otherwise)
/// and solves it quietly. Returns the termination and, when optimal, the objective.
///
/// **Only for files expected to be valid.** CBC 2.10's C interface `assert`s that the read
/// succeeded, and the Debian build keeps assertions: a file CBC cannot read *aborts the process*.
/// This function rejects a path it cannot open, but cannot catch a parse error; run it in a
/// child process when the file may be malformed. Known reader quirks: CBC's MPS reader ignores
/// `OBJSENSE` (the file is minimised), and its LP reader drops a constant term of the objective.
pub fn solve_file_with_native_reader(path: &std::path::Path) -> Result<(Termination, Option<f64>), SolverError> {
    std::fs::File::open(path).map_err(|e| SolverError::new(KIND, e))?;
    let c = CString::new(path.to_string_lossy().as_bytes()).map_err(|_| rejected("path contains NUL"))?;
    let is_lp = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("lp"));
    let mut m = CbcModel::new();
    m.set_log_level(0);
    let ptr = raw_ptr(&m);
    // SAFETY: live model; NUL-terminated path.
    let st = unsafe {
        if is_lp {
            ffi::Cbc_readLp(ptr, c.as_ptr())
        } else {
            sys::Cbc_readMps(ptr, c.as_ptr())
        }
    };
    if st != 0 {
        return Err(rejected(format!("CBC could not read {} (code {st})", path.display())));
    }
    // The same fixed integer column as in `load`, so that the solve runs through CbcMain1.
    // SAFETY: live model; static NUL-terminated name; nz = 0 needs no arrays.
    unsafe {
        ffi::Cbc_addCol(
            ptr,
            c"netspec_fixed_one".as_ptr(),
            1.0,
            1.0,
            0.0,
            1,
            0,
            std::ptr::null_mut(),
            std::ptr::null_mut(),
        )
    };
    set_quiet(&mut m, true)?;
    m.solve();
    // SAFETY: live model; column indices below Cbc_getNumCols (the last is our fixed column).
    let is_mip = unsafe {
        let ncols = sys::Cbc_getNumCols(ptr);
        (0..ncols - 1).any(|j| sys::Cbc_isInteger(ptr, j) != 0)
    };
    // SAFETY: live, solved model; no solution copied.
    let out = unsafe { WorkerResult::read(ptr, &mut []) };
    let t = termination(&out, is_mip);
    let obj = (t == Termination::Optimal).then_some(out.objective);
    Ok((t, obj))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn version_is_two() {
        let v = CbcSolver.version();
        assert!(v.starts_with("2."), "{v}");
    }

    #[test]
    fn native_reader() {
        let dir = tempfile::tempdir().unwrap();
        let (mps, lp) = (dir.path().join("t.mps"), dir.path().join("t.lp"));
        std::fs::write(&mps, TEST_MPS).unwrap();
        std::fs::write(&lp, TEST_LP).unwrap();
        let (t, obj) = solve_file_with_native_reader(&mps).unwrap();
        assert_eq!(t, Termination::Optimal);
        assert!((obj.unwrap() - 5.0).abs() < 1e-9, "{obj:?}");
        // CBC's LP reader drops the objective constant (a known quirk): -5 instead of 5.
        let (t, obj) = solve_file_with_native_reader(&lp).unwrap();
        assert_eq!(t, Termination::Optimal);
        assert!((obj.unwrap() + 5.0).abs() < 1e-9, "{obj:?}");
        assert!(solve_file_with_native_reader(&dir.path().join("missing.mps")).is_err());
    }

    /// min -x - y + 10, 2x + 3y <= 12, x, y integer in [0, 4]: optimum 5.
    const TEST_MPS: &str = "NAME          T1\nROWS\n N  obj\n L  c1\nCOLUMNS\n    MARKER                 'MARKER'                 'INTORG'\n    x         obj       -1.0           c1        2.0\n    y         obj       -1.0           c1        3.0\n    MARKER                 'MARKER'                 'INTEND'\nRHS\n    RHS       c1        12.0           obj       -10.0\nBOUNDS\n UP BND       x         4.0\n UP BND       y         4.0\nENDATA\n";
    const TEST_LP: &str = "Minimize\n obj: - x - y + 10\nSubject To\n c1: 2 x + 3 y <= 12\nBounds\n 0 <= x <= 4\n 0 <= y <= 4\nGeneral\n x y\nEnd\n";
}
