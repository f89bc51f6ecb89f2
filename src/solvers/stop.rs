//! Stopping a solve: the user's [`Interrupt`] and a watchdog over the time limit.
//!
//! Every backend is given its own time limit as the time *left* of the limit when the model
//! has been loaded, so that the limit bounds the whole `solve` call. Solvers do not always honour
//! it (CBC's preprocessing and root never look at the clock; any solver can sit in a long LP):
//! the [`StopControl`] of a solve says when it should stop — on the user's request, or
//! [`GRACE`] after the deadline — and the backend asks its solver to stop by the solver's own
//! means (HiGHS's interrupt callback, `SCIPinterruptSolve`, a signal to CBC's worker process,
//! microlp between time slices).

use super::{Interrupt, LimitKind, SolveOptions};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How long after the deadline a solver still running is asked to stop.
pub(crate) const GRACE: Duration = Duration::from_millis(250);

/// When one solve should stop.
#[derive(Debug)]
pub(crate) struct StopControl {
    interrupt: Option<Interrupt>,
    deadline: Option<Instant>,
    /// Set once the watchdog (or a poll) found the deadline passed by [`GRACE`].
    overdue: AtomicBool,
}

impl StopControl {
    /// The control for a solve that started at `started` with options `o`.
    pub(crate) fn new(o: &SolveOptions, started: Instant) -> Self {
        let deadline =
            o.finite_time_limit().map(|t| started + Duration::try_from_secs_f64(t).unwrap_or(Duration::MAX / 4));
        StopControl { interrupt: o.interrupt.clone(), deadline, overdue: AtomicBool::new(false) }
    }

    /// Seconds left until the deadline (0 when passed), for the solver's own limit.
    pub(crate) fn remaining(&self) -> Option<f64> {
        self.deadline.map(|d| d.saturating_duration_since(Instant::now()).as_secs_f64())
    }

    /// The deadline, if there is a time limit.
    pub(crate) fn deadline(&self) -> Option<Instant> {
        self.deadline
    }

    /// Whether the user asked to stop.
    pub(crate) fn interrupted(&self) -> bool {
        self.interrupt.as_ref().is_some_and(|i| i.is_triggered())
    }

    /// Whether the solve should stop now: the user asked, or the deadline passed by [`GRACE`].
    pub(crate) fn should_stop(&self) -> bool {
        if self.interrupted() {
            return true;
        }
        if self.overdue.load(Ordering::Relaxed) {
            return true;
        }
        let late = self.deadline.is_some_and(|d| Instant::now() >= d + GRACE);
        if late {
            self.overdue.store(true, Ordering::Relaxed);
        }
        late
    }

    /// Whether anything can ever ask this solve to stop (an interrupt or a time limit).
    pub(crate) fn is_armed(&self) -> bool {
        self.interrupt.is_some() || self.deadline.is_some()
    }

    /// Why a solve that was stopped from outside stopped: the user's interrupt, else the time
    /// limit if it has passed; `None` if neither happened.
    pub(crate) fn reason(&self) -> Option<LimitKind> {
        if self.interrupted() {
            Some(LimitKind::Interrupt)
        } else if self.overdue.load(Ordering::Relaxed) || self.deadline.is_some_and(|d| Instant::now() >= d) {
            Some(LimitKind::Time)
        } else {
            None
        }
    }
}

/// Runs `solve` while a watchdog thread calls `poke` as soon as the solve should stop (see
/// [`StopControl::should_stop`]), and again every 0.1 s until `solve` returns (a solver may
/// not be ready to take it the first time). The watchdog ends with `solve`, so `poke` may use
/// anything that outlives this call. Without an interrupt or a time limit no thread is started.
pub(crate) fn with_watchdog<R>(ctl: &StopControl, poke: impl Fn() + Sync, solve: impl FnOnce() -> R) -> R {
    if !ctl.is_armed() {
        return solve();
    }
    let done = AtomicBool::new(false);
    std::thread::scope(|s| {
        s.spawn(|| {
            let mut last_poke: Option<std::time::Instant> = None;
            while !done.load(Ordering::Acquire) {
                if ctl.should_stop() && last_poke.is_none_or(|t| t.elapsed() >= Duration::from_millis(100)) {
                    poke();
                    last_poke = Some(std::time::Instant::now());
                }
                std::thread::sleep(Duration::from_millis(20));
            }
        });
        let r = solve();
        done.store(true, Ordering::Release);
        r
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interrupt_and_deadline() {
        let i = Interrupt::new();
        let o = SolveOptions { time_limit: Some(0.05), interrupt: Some(i.clone()), ..Default::default() };
        let ctl = StopControl::new(&o, Instant::now());
        assert!(!ctl.should_stop() && ctl.reason().is_none());
        std::thread::sleep(Duration::from_millis(60));
        assert_eq!(ctl.reason(), Some(LimitKind::Time));
        i.trigger();
        assert!(ctl.should_stop());
        assert_eq!(ctl.reason(), Some(LimitKind::Interrupt));
    }

    #[test]
    fn watchdog_pokes_after_the_deadline() {
        let o = SolveOptions { time_limit: Some(0.0), ..Default::default() };
        let ctl = StopControl::new(&o, Instant::now());
        let pokes = std::sync::atomic::AtomicUsize::new(0);
        let out = with_watchdog(
            &ctl,
            || {
                pokes.fetch_add(1, Ordering::SeqCst);
            },
            || {
                while pokes.load(Ordering::SeqCst) == 0 {
                    std::thread::sleep(Duration::from_millis(5));
                }
                7
            },
        );
        assert_eq!(out, 7);
        assert!(pokes.load(Ordering::SeqCst) >= 1);
        assert_eq!(ctl.reason(), Some(LimitKind::Time));
    }

    #[test]
    fn no_thread_without_a_limit() {
        let ctl = StopControl::new(&SolveOptions::default(), Instant::now());
        assert!(!ctl.is_armed());
        assert_eq!(with_watchdog(&ctl, || panic!("poked"), || 3), 3);
    }
}
