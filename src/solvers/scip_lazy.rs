//! Lazy rows inside SCIP's branch and cut: a constraint handler, written against SCIP's C API
//! (russcip's safe wrapper has no pseudo-solution enforcement, no separation callback for
//! constraint handlers and no variable locks, which presolving needs to leave the lazy rows
//! alone).
//!
//! The handler needs no constraints (SCIP then calls its LOCK callback once, with no constraint,
//! on the transformed problem) and has:
//! - CHECK: a primal solution is feasible iff the separator finds no violated row on it;
//! - ENFOLP (called for integral LP solutions, priority −1): violated rows are added to the LP
//!   (`SEPARATED`), else `FEASIBLE`;
//! - ENFOPS: a violated pseudo solution is `INFEASIBLE` (SCIP branches);
//! - SEPALP: rows violated by the fractional LP solution are added as cuts;
//! - LOCK: every variable of the lazy rows is locked the way the separator says.
//!
//! Every row added is recorded, so the caller can check the returned point against it.

use super::{LazyRow, Lock, Separator};
use russcip::ffi;
use std::ffi::CString;
use std::os::raw::{c_int, c_uint};
use std::time::Instant;

/// What the callbacks share: the separator, the variables, and what was added.
pub(super) struct Handler<'s> {
    sep: &'s mut dyn Separator,
    /// Original variables, in [`crate::milp::VarId`] order.
    orig: Vec<*mut ffi::SCIP_VAR>,
    /// Transformed variables, filled on first use in the solving stage.
    trans: Vec<*mut ffi::SCIP_VAR>,
    locks: Vec<(usize, Lock)>,
    /// Every row added to SCIP.
    pub rows: Vec<LazyRow>,
    /// Separation calls.
    pub calls: u64,
    /// Seconds in the separator.
    pub seconds: f64,
    /// The first error inside a callback (reported after the solve).
    pub error: Option<String>,
}

impl<'s> Handler<'s> {
    pub(super) fn new(sep: &'s mut dyn Separator, orig: Vec<*mut ffi::SCIP_VAR>) -> Self {
        let locks = sep.locks().into_iter().map(|(v, l)| (v.index(), l)).collect();
        Handler { sep, orig, trans: Vec::new(), locks, rows: Vec::new(), calls: 0, seconds: 0.0, error: None }
    }

    /// Sets the original variables (in [`crate::milp::VarId`] order) once the problem is built.
    pub(super) fn set_vars(&mut self, orig: Vec<*mut ffi::SCIP_VAR>) {
        self.orig = orig;
        self.trans.clear();
    }

    fn transformed(&mut self, scip: *mut ffi::SCIP) -> bool {
        if self.trans.len() == self.orig.len() {
            return true;
        }
        let mut out = Vec::with_capacity(self.orig.len());
        for &v in &self.orig {
            let mut t: *mut ffi::SCIP_VAR = std::ptr::null_mut();
            // SAFETY: live SCIP instance in a transformed stage; `v` is one of its original
            // variables.
            let rc = unsafe { ffi::SCIPgetTransformedVar(scip, v, &mut t) };
            if rc != ffi::SCIP_Retcode_SCIP_OKAY || t.is_null() {
                self.error.get_or_insert_with(|| "SCIPgetTransformedVar failed".into());
                return false;
            }
            out.push(t);
        }
        self.trans = out;
        true
    }

    /// The point of `sol` (NULL: the current LP or pseudo solution) in variable order.
    fn point(&mut self, scip: *mut ffi::SCIP, sol: *mut ffi::SCIP_SOL) -> Option<Vec<f64>> {
        // A solution checked before the solve (a MIP start added in the problem stage) or kept in
        // the original space is read through the original variables.
        // SAFETY: live SCIP instance; `sol` is NULL or one of its solutions.
        let original = unsafe {
            ffi::SCIPgetStage(scip) == ffi::SCIP_Stage_SCIP_STAGE_PROBLEM
                || (!sol.is_null() && ffi::SCIPsolIsOriginal(sol) != 0)
        };
        if original {
            // SAFETY: live instance, original variables of it.
            return Some(self.orig.iter().map(|&v| unsafe { ffi::SCIPgetSolVal(scip, sol, v) }).collect());
        }
        if !self.transformed(scip) {
            return None;
        }
        // SAFETY: live instance in the solving stage, transformed variables of it.
        Some(self.trans.iter().map(|&v| unsafe { ffi::SCIPgetSolVal(scip, sol, v) }).collect())
    }

    /// Adds rows to the LP; returns (added, infeasible).
    fn add_rows(
        &mut self,
        scip: *mut ffi::SCIP,
        conshdlr: *mut ffi::SCIP_CONSHDLR,
        rows: Vec<LazyRow>,
        force: bool,
    ) -> (usize, bool) {
        let inf = unsafe { ffi::SCIPinfinity(scip) };
        let mut added = 0;
        let mut infeasible = false;
        for r in rows {
            let name = CString::new(r.name.replace('\0', "_")).unwrap_or_default();
            let mut row: *mut ffi::SCIP_ROW = std::ptr::null_mut();
            let (lhs, rhs) = (r.lhs.max(-inf), r.rhs.min(inf));
            // SAFETY: live instance in the solving stage; the row is released below.
            unsafe {
                if ffi::SCIPcreateEmptyRowConshdlr(scip, &mut row, conshdlr, name.as_ptr(), lhs, rhs, 0, 0, 1)
                    != ffi::SCIP_Retcode_SCIP_OKAY
                {
                    self.error.get_or_insert_with(|| "SCIPcreateEmptyRowConshdlr failed".into());
                    continue;
                }
                ffi::SCIPcacheRowExtensions(scip, row);
                for &(v, c) in &r.terms {
                    ffi::SCIPaddVarToRow(scip, row, self.trans[v.index()], c);
                }
                ffi::SCIPflushRowExtensions(scip, row);
                let mut inf_flag: c_uint = 0;
                if force || ffi::SCIPisCutEfficacious(scip, std::ptr::null_mut(), row) != 0 {
                    ffi::SCIPaddRow(scip, row, force as c_uint, &mut inf_flag);
                    added += 1;
                    infeasible |= inf_flag != 0;
                    self.rows.push(r);
                }
                ffi::SCIPreleaseRow(scip, &mut row);
            }
        }
        (added, infeasible)
    }
}

/// The handler behind a SCIP constraint handler's data pointer.
///
/// # Safety
/// `conshdlr` is the handler [`install`] created, whose data is a live `Handler`.
unsafe fn handler<'a>(conshdlr: *mut ffi::SCIP_CONSHDLR) -> &'a mut Handler<'static> {
    unsafe { &mut *(ffi::SCIPconshdlrGetData(conshdlr) as *mut Handler<'static>) }
}

/// Runs a callback body, turning a panic into SCIP's error code.
fn guarded(f: impl FnOnce() -> ffi::SCIP_Result, result: *mut ffi::SCIP_RESULT) -> ffi::SCIP_RETCODE {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)) {
        Ok(r) => {
            // SAFETY: SCIP passes a valid result pointer.
            unsafe { *result = r };
            ffi::SCIP_Retcode_SCIP_OKAY
        }
        Err(_) => ffi::SCIP_Retcode_SCIP_ERROR,
    }
}

unsafe extern "C" fn enfolp(
    scip: *mut ffi::SCIP,
    conshdlr: *mut ffi::SCIP_CONSHDLR,
    _conss: *mut *mut ffi::SCIP_CONS,
    _nconss: c_int,
    _nuseful: c_int,
    _solinfeasible: c_uint,
    result: *mut ffi::SCIP_RESULT,
) -> ffi::SCIP_RETCODE {
    guarded(
        || {
            // SAFETY: see `handler`.
            let h = unsafe { handler(conshdlr) };
            let Some(x) = h.point(scip, std::ptr::null_mut()) else { return ffi::SCIP_Result_SCIP_INFEASIBLE };
            let t = Instant::now();
            let rows = h.sep.separate_integral(&x);
            h.calls += 1;
            h.seconds += t.elapsed().as_secs_f64();
            if rows.is_empty() {
                return ffi::SCIP_Result_SCIP_FEASIBLE;
            }
            match h.add_rows(scip, conshdlr, rows, true) {
                (_, true) => ffi::SCIP_Result_SCIP_CUTOFF,
                (0, false) => ffi::SCIP_Result_SCIP_INFEASIBLE,
                _ => ffi::SCIP_Result_SCIP_SEPARATED,
            }
        },
        result,
    )
}

unsafe extern "C" fn enfops(
    scip: *mut ffi::SCIP,
    conshdlr: *mut ffi::SCIP_CONSHDLR,
    _conss: *mut *mut ffi::SCIP_CONS,
    _nconss: c_int,
    _nuseful: c_int,
    _solinfeasible: c_uint,
    _objinfeasible: c_uint,
    result: *mut ffi::SCIP_RESULT,
) -> ffi::SCIP_RETCODE {
    guarded(
        || {
            // SAFETY: see `handler`.
            let h = unsafe { handler(conshdlr) };
            let Some(x) = h.point(scip, std::ptr::null_mut()) else { return ffi::SCIP_Result_SCIP_INFEASIBLE };
            if h.sep.separate_integral(&x).is_empty() {
                ffi::SCIP_Result_SCIP_FEASIBLE
            } else {
                ffi::SCIP_Result_SCIP_INFEASIBLE
            }
        },
        result,
    )
}

unsafe extern "C" fn check(
    scip: *mut ffi::SCIP,
    conshdlr: *mut ffi::SCIP_CONSHDLR,
    _conss: *mut *mut ffi::SCIP_CONS,
    _nconss: c_int,
    sol: *mut ffi::SCIP_SOL,
    _checkintegrality: c_uint,
    _checklprows: c_uint,
    _printreason: c_uint,
    _completely: c_uint,
    result: *mut ffi::SCIP_RESULT,
) -> ffi::SCIP_RETCODE {
    guarded(
        || {
            // SAFETY: see `handler`.
            let h = unsafe { handler(conshdlr) };
            let Some(x) = h.point(scip, sol) else { return ffi::SCIP_Result_SCIP_INFEASIBLE };
            if h.sep.separate_integral(&x).is_empty() {
                ffi::SCIP_Result_SCIP_FEASIBLE
            } else {
                ffi::SCIP_Result_SCIP_INFEASIBLE
            }
        },
        result,
    )
}

unsafe extern "C" fn sepalp(
    scip: *mut ffi::SCIP,
    conshdlr: *mut ffi::SCIP_CONSHDLR,
    _conss: *mut *mut ffi::SCIP_CONS,
    _nconss: c_int,
    _nuseful: c_int,
    result: *mut ffi::SCIP_RESULT,
) -> ffi::SCIP_RETCODE {
    guarded(
        || {
            // SAFETY: see `handler`.
            let h = unsafe { handler(conshdlr) };
            let Some(x) = h.point(scip, std::ptr::null_mut()) else { return ffi::SCIP_Result_SCIP_DIDNOTRUN };
            let t = Instant::now();
            let rows = h.sep.separate_fractional(&x);
            h.calls += 1;
            h.seconds += t.elapsed().as_secs_f64();
            match h.add_rows(scip, conshdlr, rows, false) {
                (_, true) => ffi::SCIP_Result_SCIP_CUTOFF,
                (0, false) => ffi::SCIP_Result_SCIP_DIDNOTFIND,
                _ => ffi::SCIP_Result_SCIP_SEPARATED,
            }
        },
        result,
    )
}

unsafe extern "C" fn lock(
    scip: *mut ffi::SCIP,
    conshdlr: *mut ffi::SCIP_CONSHDLR,
    cons: *mut ffi::SCIP_CONS,
    locktype: ffi::SCIP_LOCKTYPE,
    nlockspos: c_int,
    nlocksneg: c_int,
) -> ffi::SCIP_RETCODE {
    let body = || {
        // SAFETY: see `handler`; `cons` is our constraint.
        let h = unsafe { handler(conshdlr) };
        // A handler that needs no constraints gets its locks with `cons == NULL`, on the
        // transformed problem.
        let transformed = cons.is_null() || unsafe { ffi::SCIPconsIsTransformed(cons) } != 0;
        if transformed && !h.transformed(scip) {
            return ffi::SCIP_Retcode_SCIP_ERROR;
        }
        for &(j, l) in &h.locks {
            let v = if transformed { h.trans[j] } else { h.orig[j] };
            let (down, up) = match l {
                Lock::Down => (nlockspos, nlocksneg),
                Lock::Up => (nlocksneg, nlockspos),
                Lock::Both => (nlockspos + nlocksneg, nlockspos + nlocksneg),
            };
            // SAFETY: live instance, a variable of the matching stage.
            let rc = unsafe { ffi::SCIPaddVarLocksType(scip, v, locktype, down, up) };
            if rc != ffi::SCIP_Retcode_SCIP_OKAY {
                return rc;
            }
        }
        ffi::SCIP_Retcode_SCIP_OKAY
    };
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(body)).unwrap_or(ffi::SCIP_Retcode_SCIP_ERROR)
}

/// Includes the handler and its one constraint in a SCIP instance in the problem stage.
///
/// # Safety
/// `h` must stay alive, and not move, until the SCIP instance is freed; `scip` must be live.
pub(super) unsafe fn install(scip: *mut ffi::SCIP, h: &mut Handler<'_>) -> Result<(), String> {
    let name = c"netspec_lazy";
    let desc = c"netspec lazily separated rows";
    let mut conshdlr: *mut ffi::SCIP_CONSHDLR = std::ptr::null_mut();
    let data = h as *mut Handler<'_> as *mut ffi::SCIP_CONSHDLRDATA;
    let ok = |rc: ffi::SCIP_RETCODE, what: &str| {
        if rc == ffi::SCIP_Retcode_SCIP_OKAY {
            Ok(())
        } else {
            Err(format!("{what}: SCIP returned {rc}"))
        }
    };
    // SAFETY: the caller's contract; callbacks match SCIP's signatures.
    unsafe {
        ok(
            ffi::SCIPincludeConshdlrBasic(
                scip,
                &mut conshdlr,
                name.as_ptr(),
                desc.as_ptr(),
                -1,
                -1,
                1,
                0,
                Some(enfolp),
                Some(enfops),
                Some(check),
                Some(lock),
                data,
            ),
            "SCIPincludeConshdlrBasic",
        )?;
        ok(ffi::SCIPsetConshdlrSepa(scip, conshdlr, Some(sepalp), None, 1, 0, 0), "SCIPsetConshdlrSepa")?;
    }
    Ok(())
}
