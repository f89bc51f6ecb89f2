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

use super::{preflight, Capabilities, LimitKind, LogTarget, SolveOptions, SolveResult, Solver, SolverError, SolverErrorKind, SolverKind, Termination};
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
        SolverError::new(KIND, SolverErrorKind::ModelUnsupported(format!("{n} {what}: too many for CBC's 32-bit indices")))
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

fn apply_options(m: &mut CbcModel, model: &Model, o: &SolveOptions) -> Result<(), SolverError> {
    match &o.log {
        LogTarget::Quiet => set_quiet(m, true)?,
        LogTarget::Stdout => set_quiet(m, false)?,
        // Refused by the capabilities (preflight) before we get here.
        LogTarget::File(_) => return Err(rejected("CBC cannot write a log file")),
    }
    if let Some(t) = o.time_limit {
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
    Ok(())
}

/// CBC's `status()`/`secondaryStatus()` (see `CbcModel.hpp`) to a [`Termination`].
fn termination(m: *mut sys::Cbc_Model, is_mip: bool) -> Termination {
    // SAFETY: `m` is a live, solved model.
    let (status, secondary, optimal, infeasible) =
        unsafe { (sys::Cbc_status(m), sys::Cbc_secondaryStatus(m), sys::Cbc_isProvenOptimal(m), sys::Cbc_isProvenInfeasible(m)) };
    match (status, secondary) {
        // "Linear relaxation not feasible (or worse than cutoff)": also how CBC ends a search
        // that completes without an integer solution.
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
        (0, _) if optimal != 0 => Termination::Optimal,
        (0, _) if infeasible != 0 => Termination::Infeasible,
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
        }
    }

    fn solve(&self, model: &Model, o: &SolveOptions) -> Result<SolveResult, SolverError> {
        let t0 = Instant::now();
        preflight(KIND, &self.capabilities(), model, o)?;
        let _serial = CBC_SOLVES.lock().unwrap_or_else(|e| e.into_inner());
        let mut m = load(model)?;
        apply_options(&mut m, model, o)?;
        let t_solve = Instant::now();
        m.solve();
        let solver_time = t_solve.elapsed().as_secs_f64();
        let ptr = raw_ptr(&m);
        let n = model.num_vars();
        let mut r = SolveResult::empty(KIND, self.version(), termination(ptr, model.is_mip()));
        // SAFETY: live, solved model; a non-null best solution has one value per column (n + 1).
        let best = unsafe {
            let p = ffi::Cbc_bestSolution(ptr);
            (!p.is_null()).then(|| std::slice::from_raw_parts(p, n + 1)[..n].to_vec())
        };
        if let Some(x) = best {
            r.primal = Some(x);
            // SAFETY: live, solved model.
            r.objective = finite_cbc(unsafe { sys::Cbc_getObjValue(ptr) });
        }
        let bound_meaningful =
            !matches!(r.termination, Termination::Infeasible | Termination::Unbounded | Termination::InfeasibleOrUnbounded | Termination::Error(_));
        if bound_meaningful {
            // SAFETY: live, solved model. In the model's own sense, with the constant column.
            r.dual_bound = finite_cbc(unsafe { sys::Cbc_getBestPossibleObjValue(ptr) });
        }
        // SAFETY: live, solved model.
        r.nodes = Some(unsafe { sys::Cbc_getNodeCount(ptr) }.max(0) as u64);
        r.solver_time = Some(solver_time);
        r.finish(model.sense, o.rel_gap.is_some() || o.abs_gap.is_some());
        drop(m);
        r.wall_time = t0.elapsed().as_secs_f64();
        Ok(r)
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
    unsafe { ffi::Cbc_addCol(ptr, c"netspec_fixed_one".as_ptr(), 1.0, 1.0, 0.0, 1, 0, std::ptr::null_mut(), std::ptr::null_mut()) };
    set_quiet(&mut m, true)?;
    m.solve();
    // SAFETY: live model; column indices below Cbc_getNumCols (the last is our fixed column).
    let is_mip = unsafe {
        let ncols = sys::Cbc_getNumCols(ptr);
        (0..ncols - 1).any(|j| sys::Cbc_isInteger(ptr, j) != 0)
    };
    let t = termination(ptr, is_mip);
    // SAFETY: live, solved model.
    let obj = (t == Termination::Optimal).then(|| unsafe { sys::Cbc_getObjValue(ptr) });
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
