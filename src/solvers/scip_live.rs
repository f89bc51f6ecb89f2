//! Live reports from SCIP: an event handler on SCIP's improving solutions hands every new best
//! point to [`SolveOptions::incumbents`], and on solved nodes reports incumbent, bound and node
//! count to [`SolveOptions::progress`] (at most four times a second).
//!
//! SCIP's concurrent solver (`threads` > 1) runs copies of the problem that do not carry the
//! handler: there, as before, the points and bounds come at the end only.

use super::options::{PointSink, Progress, ProgressSink, SolveOptions};
use russcip::{ffi, EventMask, Eventhdlr, Model, SCIPEventhdlr, Solving};
use std::time::{Duration, Instant};

/// The handler's state: raw variable pointers (no reference back to the SCIP instance that
/// owns the handler), the sinks, and when progress was last reported.
pub(crate) struct Live {
    vars: Vec<*mut ffi::SCIP_VAR>,
    incumbents: Option<PointSink>,
    progress: Option<ProgressSink>,
    start: Instant,
    last: Option<Instant>,
}

impl Live {
    /// A handler for the options' sinks, or `None` when neither is asked for.
    pub(crate) fn new(vars: Vec<*mut ffi::SCIP_VAR>, o: &SolveOptions) -> Option<Live> {
        (o.incumbents.is_some() || o.progress.is_some()).then(|| Live {
            vars,
            incumbents: o.incumbents.clone(),
            progress: o.progress.clone(),
            start: Instant::now(),
            last: None,
        })
    }

    fn report_point(&self, scip: *mut ffi::SCIP, sol: *mut ffi::SCIP_SOL) {
        let Some(sink) = &self.incumbents else { return };
        // SAFETY: a live SCIP instance in the solving stage, its best solution and the
        // problem's own variables (alive as long as the instance).
        let (obj, point): (f64, Vec<f64>) = unsafe {
            (ffi::SCIPgetSolOrigObj(scip, sol), self.vars.iter().map(|&v| ffi::SCIPgetSolVal(scip, sol, v)).collect())
        };
        (sink.0)(obj, &point);
    }

    fn report_progress(&mut self, scip: *mut ffi::SCIP, sol: *mut ffi::SCIP_SOL, force: bool) {
        let Some(sink) = &self.progress else { return };
        let now = Instant::now();
        if !force && self.last.is_some_and(|t| now - t < Duration::from_millis(250)) {
            return;
        }
        self.last = Some(now);
        // SAFETY: a live SCIP instance in the solving stage; `sol` null or its best solution.
        let (primal, dual, nodes, inf) = unsafe {
            let primal = (!sol.is_null()).then(|| ffi::SCIPgetSolOrigObj(scip, sol));
            (primal, ffi::SCIPgetDualbound(scip), ffi::SCIPgetNTotalNodes(scip), ffi::SCIPinfinity(scip))
        };
        (sink.0)(Progress {
            elapsed: self.start.elapsed().as_secs_f64(),
            primal,
            dual: (dual.abs() < inf).then_some(dual),
            nodes: nodes.max(0) as u64,
        });
    }
}

impl Eventhdlr for Live {
    fn get_type(&self) -> EventMask {
        EventMask::BEST_SOL_FOUND | EventMask::NODE_SOLVED
    }

    fn execute(&mut self, model: Model<Solving>, _eventhdlr: SCIPEventhdlr, event: russcip::Event) {
        let scip = model.scip_ptr();
        // SAFETY: a live SCIP instance in the solving stage.
        let sol = unsafe { ffi::SCIPgetBestSol(scip) };
        let best = event.event_type().matches(EventMask::BEST_SOL_FOUND);
        if best && !sol.is_null() {
            self.report_point(scip, sol);
        }
        self.report_progress(scip, sol, best);
    }
}
