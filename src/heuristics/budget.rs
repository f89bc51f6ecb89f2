//! The heuristics' budget: counted work, not the clock, so that the same spec and seed give the
//! same design on any machine and under any load.
//!
//! A search's limit in seconds becomes a number of *work units* at the fixed rate
//! [`UNITS_PER_SECOND`]. A unit is one step of the inner loops: a vertex settled or a half-edge
//! scanned by a path search, a vertex visited by a connectivity walk, an edge switched, a node of
//! the tiling search, a vertex of a full scan (chains, islands, the objective's shortest paths).
//! The steps are counted per thread ([`charge`]); a search reads the count where it used to read
//! the clock ([`Deadline::passed`]). The count of the same search is the same on every run, so
//! where it stops, and what it returns, depends only on the spec and the seed.
//!
//! The wall clock stays as a safety net: a deadline also passes at [`WALL_FACTOR`] times its
//! seconds (plus [`WALL_SLACK`]), so that no search runs past its limit by more than that, on a
//! machine slower or busier than the one the rate was measured on. Only then does timing decide.
//! One wait is on the clock alone ([`Deadline::on_clock`]): a MIP start's search that has no design
//! at its budget goes on for one up to a share of the solve's time limit, which is itself seconds
//! on the clock; where it finds one, the design is the one its work count leads to.

use std::cell::Cell;
use std::time::{Duration, Instant};

/// Work units per second of search. Measured with `netspec search --solver heuristic` on the
/// street, floor-plan and game-level specs of `models/` (work over CPU seconds: see
/// `docs/heuristics.md`, "Budget"), the slowest spec's rate rounded down, so that on such a
/// machine a budget of work ends before its seconds do.
pub const UNITS_PER_SECOND: f64 = 15_000_000.0;

/// The wall-clock net: a deadline of `s` seconds also passes after `WALL_FACTOR · s + WALL_SLACK`
/// seconds.
pub const WALL_FACTOR: f64 = 1.0;

/// See [`WALL_FACTOR`].
pub const WALL_SLACK: f64 = 0.5;

thread_local! {
    static SPENT: Cell<u64> = const { Cell::new(0) };
}

/// Counts `units` of work on this thread.
#[inline]
pub(crate) fn charge(units: u64) {
    SPENT.with(|c| c.set(c.get().wrapping_add(units)));
}

/// Work units for `steps` of a tight loop (a linked-list or array scan, a few nanoseconds each):
/// [`TIGHT_STEPS`] to a unit, rounded up.
#[inline]
pub(crate) fn tight(steps: u64) -> u64 {
    steps.div_ceil(TIGHT_STEPS)
}

/// Counts `steps` of a tight loop ([`tight`]).
#[inline]
pub(crate) fn charge_tight(steps: u64) {
    charge(tight(steps));
}

/// Steps of a tight loop per work unit ([`charge_tight`]).
pub const TIGHT_STEPS: u64 = 8;

/// The work counted on this thread so far.
#[inline]
pub(crate) fn spent() -> u64 {
    SPENT.with(Cell::get)
}

/// Work units for `seconds` (0 for a negative or NaN budget, saturating for a huge one).
pub fn units(seconds: f64) -> u64 {
    let u = seconds * UNITS_PER_SECOND;
    if u.is_nan() || u <= 0.0 {
        0
    } else if u >= u64::MAX as f64 {
        u64::MAX
    } else {
        u as u64
    }
}

/// When a search stops: a work count of this thread, or the wall-clock net.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Deadline {
    /// This thread's count at which the deadline passes.
    work: u64,
    /// The net.
    wall: Instant,
}

/// The instant `seconds` from now: 0 for a negative or NaN time, at most 1e9 s.
fn clock_in(seconds: f64) -> Instant {
    let seconds = if seconds.is_nan() { 0.0 } else { seconds.clamp(0.0, 1e9) };
    Instant::now() + Duration::from_secs_f64(seconds)
}

impl Deadline {
    /// `seconds` of work from now (this thread's count now).
    pub fn after(seconds: f64) -> Deadline {
        let net = WALL_FACTOR * seconds.max(0.0) + WALL_SLACK;
        Deadline { work: spent().saturating_add(units(seconds)), wall: clock_in(net) }
    }

    /// `seconds` on the clock from now, with no work limit: the wait for a first design
    /// ([`crate::heuristics::Options::first_design_limit`]), which decides only whether a search
    /// returns a design, not which.
    pub fn on_clock(seconds: f64) -> Deadline {
        Deadline { work: u64::MAX, wall: clock_in(seconds) }
    }

    /// Whether the deadline has passed: the work is spent, or the net's time is up.
    pub fn passed(&self) -> bool {
        spent() >= self.work || Instant::now() >= self.wall
    }

    /// Work left before the deadline (0 once it has passed by work).
    pub fn work_left(&self) -> u64 {
        self.work.saturating_sub(spent())
    }

    /// The deadline at `1/parts` of what is left of this one, from now: half for `parts = 2`.
    pub fn share(&self, parts: u64) -> Deadline {
        let parts = parts.max(1);
        let now = Instant::now();
        let wall_left = self.wall.saturating_duration_since(now);
        Deadline { work: spent().saturating_add(self.work_left() / parts), wall: now + wall_left / parts as u32 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_passes_a_deadline_and_shares_split_what_is_left() {
        let d = Deadline::after(1.0);
        assert!(!d.passed());
        assert_eq!(d.work_left(), units(1.0));
        let half = d.share(2);
        assert_eq!(half.work_left(), units(1.0) / 2);
        charge(units(1.0) / 2);
        assert!(half.passed());
        assert!(!d.passed());
        charge(units(1.0));
        assert!(d.passed());
        assert_eq!(d.work_left(), 0);
    }

    #[test]
    fn the_wall_clock_net_passes_a_deadline_without_work() {
        let d = Deadline { work: u64::MAX, wall: Instant::now() };
        assert!(d.passed());
    }

    #[test]
    fn a_wait_on_the_clock_ignores_work_and_passes_with_its_time() {
        let d = Deadline::on_clock(60.0);
        charge(units(1e6));
        assert!(!d.passed());
        assert!(Deadline::on_clock(0.0).passed());
        assert!(Deadline::on_clock(f64::NAN).passed());
        assert!(Deadline::on_clock(-3.0).passed());
        assert!(!Deadline::on_clock(f64::INFINITY).passed());
    }

    #[test]
    fn units_of_odd_budgets() {
        assert_eq!(units(-1.0), 0);
        assert_eq!(units(f64::NAN), 0);
        assert_eq!(units(f64::INFINITY), u64::MAX);
        assert_eq!(units(2.0), 2 * units(1.0));
    }
}
