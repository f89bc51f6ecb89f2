//! The objective lattice: when every design's objective lies on `offset + step·ℤ`, a dual bound
//! may be rounded up to the lattice (what Gurobi calls objective integrality; HiGHS and CBC
//! detect it only when every variable with a cost is an integer).
//!
//! The formulation says whether its objective has a lattice (`Formulation::objective_lattice`):
//! the coefficients must be multiples of one step, and the optimum over the continuous variables
//! at any integral assignment must stay on the lattice — true of integer variables, of flows with
//! integral supplies and capacities (a network matrix), and of indicators that take `max(0, ·)`
//! of integral sums; not of the paper's labels. The solve's bound is then rounded up
//! ([`ObjectiveLattice::round_up`]) before its gap is computed: the search is the backend's own.
//!
//! The backend is not handed an absolute gap of a step (with which HiGHS would also drop every
//! node less than a step below its incumbent): measured on twenty Table 1 rows it proved as many
//! rows, changed the search on each, and on Fig. 2d and 7d-L2 made HiGHS slower per node
//! (docs/benchmarks.md, *Objective lattice*). A user may hand it with `--abs-gap`; a solve that
//! stops on `(1 − 2·ROUNDING_SLACK)` steps rounds to a proof.

use super::result::SolveResult;
use super::{LimitKind, Termination};
use crate::milp::{Model, Sense, VarId, VarKind};
use serde::{Deserialize, Serialize};

/// The largest denominator tried for a lattice step.
const MAX_DENOMINATOR: u64 = 1000;
/// A bound more than this share of a step past a lattice point is rounded up to the next one; a
/// bound closer to it is taken for round-off.
const ROUNDING_SLACK: f64 = 0.005;

/// `offset + step·ℤ`, on which every design's objective lies.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectiveLattice {
    /// The step: every objective coefficient is an integer multiple of it.
    pub step: f64,
    /// The objective's constant.
    pub offset: f64,
}

/// What the lattice did to one solve, for the result.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LatticeReport {
    /// The lattice.
    pub lattice: ObjectiveLattice,
    /// The backend's own dual bound, before rounding.
    pub solver_bound: Option<f64>,
}

impl ObjectiveLattice {
    /// The lattice of `model`'s objective, if every nonzero coefficient is a multiple of one step
    /// `g/d` (`d ≤ 1000`) and every continuous variable with a cost is one `certified` says
    /// stays on the lattice at an optimum (see the module docs); `None` otherwise, or for a
    /// model without costs.
    pub fn of_model(model: &Model, certified: impl Fn(VarId) -> bool) -> Option<ObjectiveLattice> {
        let mut coefs = Vec::new();
        for (j, v) in model.vars().iter().enumerate() {
            if v.obj == 0.0 {
                continue;
            }
            if v.kind == VarKind::Continuous && !certified(VarId(j as u32)) {
                return None;
            }
            coefs.push(v.obj);
        }
        if !model.obj_constant.is_finite() {
            return None;
        }
        lattice_step(&coefs).map(|step| ObjectiveLattice { step, offset: model.obj_constant })
    }

    /// `bound` rounded up to the lattice (down for a maximisation): to the next lattice point
    /// when it is more than `ROUNDING_SLACK` of a step past the one below, so that a bound a
    /// hair above a lattice point through round-off is not taken for a whole step more — and
    /// more than `1e-9·|bound|` (a solver's relative accuracy), so that on an objective of
    /// millions of steps the rounding gives up rather than guesses. Never moves a bound toward
    /// better objectives.
    pub fn round_up(&self, bound: f64, sense: Sense) -> f64 {
        if !bound.is_finite() {
            return bound;
        }
        let steps = (bound - self.offset) / self.step;
        let slack = ROUNDING_SLACK.max(1e-9 * bound.abs() / self.step);
        match sense {
            Sense::Minimize => bound.max(self.offset + self.step * (steps - slack).ceil()),
            Sense::Maximize => bound.min(self.offset + self.step * (steps + slack).floor()),
        }
    }

    /// Rounds `r`'s dual bound to the lattice and settles its gap: a solver that stopped on a
    /// gap ([`LimitKind::Gap`]) has proven its design optimal when the rounded bound meets the
    /// objective. Returns the solver's own bound.
    pub fn settle(&self, r: &mut SolveResult, sense: Sense) -> Option<f64> {
        let raw = r.dual_bound?;
        let mut rounded = self.round_up(raw, sense);
        // An objective a hair off its lattice point (round-off) caps the rounded bound.
        if let Some(p) = r.objective {
            rounded = match sense {
                Sense::Minimize => rounded.min(p).max(raw),
                Sense::Maximize => rounded.max(p).min(raw),
            };
        }
        r.dual_bound = Some(rounded);
        if r.termination == Termination::Limit(LimitKind::Gap) {
            r.termination = Termination::Optimal;
        }
        r.finish(sense);
        Some(raw)
    }
}

/// The largest `q = g/d` (`d ≤ 1000`) of which every coefficient is an integer multiple.
pub(crate) fn lattice_step(coefs: &[f64]) -> Option<f64> {
    (1..=MAX_DENOMINATOR).find_map(|d| {
        // The gcd of the coefficients times d, or None at the first one that is not an integer.
        let g = coefs.iter().try_fold(0, |g, c| {
            let s = (c * d as f64).abs();
            let n = s.round();
            ((s - n).abs() <= 1e-9 * s.max(1.0) && n <= 1e12).then(|| gcd(g, n as u64))
        })?;
        (g > 0).then(|| g as f64 / d as f64)
    })
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::SolverKind;

    fn lattice(step: f64, offset: f64) -> ObjectiveLattice {
        ObjectiveLattice { step, offset }
    }

    /// Integer costs and certified continuous ones give the step of all of them; a continuous
    /// cost that is not certified, or a coefficient off every lattice, gives none.
    #[test]
    fn the_lattice_is_the_common_step_of_certified_costs() {
        let mut m = Model::new("m");
        m.add_binary("e", 1.0);
        m.add_integer("z", 0.0, 3.0, 5.0);
        let f = m.add_continuous("f", 0.0, 9.0, 0.5);
        m.add_continuous("free", 0.0, 9.0, 0.0);
        m.obj_constant = 2.0;
        assert_eq!(ObjectiveLattice::of_model(&m, |v| v == f), Some(lattice(0.5, 2.0)));
        assert_eq!(ObjectiveLattice::of_model(&m, |_| false), None, "an uncertified continuous cost");
        m.add_binary("pi", std::f64::consts::PI);
        assert_eq!(ObjectiveLattice::of_model(&m, |v| v == f), None, "a coefficient on no lattice");
        assert_eq!(ObjectiveLattice::of_model(&Model::new("empty"), |_| true), None, "no costs");
    }

    /// A bound goes up to the next lattice point; one a hair above a point (round-off) stays
    /// there; no bound moves toward better objectives.
    #[test]
    fn bounds_round_up_to_the_lattice() {
        let l = lattice(1.0, 0.0);
        assert_eq!(l.round_up(67.3, Sense::Minimize), 68.0);
        assert_eq!(l.round_up(67.0 - 1e-9, Sense::Minimize), 67.0);
        assert_eq!(l.round_up(67.002, Sense::Minimize), 67.002);
        assert_eq!(l.round_up(67.3, Sense::Maximize), 67.0);
        assert_eq!(l.round_up(f64::NEG_INFINITY, Sense::Minimize), f64::NEG_INFINITY);
        let shifted = lattice(0.5, 0.25);
        assert_eq!(shifted.round_up(1.0, Sense::Minimize), 1.25);
        assert_eq!(shifted.round_up(1.25, Sense::Minimize), 1.25);
        // A solve stopped on an absolute gap of (1 − 2·slack) steps rounds to its incumbent.
        assert_eq!(l.round_up(68.0 - (1.0 - 2.0 * ROUNDING_SLACK), Sense::Minimize), 68.0);
        // Ten million steps: 1e-9 relative is a hundredth of a step, more than the slack.
        assert_eq!(l.round_up(1e7 + 0.008, Sense::Minimize), 1e7 + 0.008);
        assert_eq!(l.round_up(1e7 + 0.3, Sense::Minimize), 1e7 + 1.0);
    }

    fn result(termination: Termination, objective: f64, bound: f64) -> SolveResult {
        let mut r = SolveResult::empty(SolverKind::Microlp, "test".into(), termination);
        r.objective = Some(objective);
        r.dual_bound = Some(bound);
        r.finish(Sense::Minimize);
        r
    }

    /// A solve stopped on the gap is optimal once its rounded bound meets its objective, and
    /// stays gap-limited when it does not; a time-limited one keeps its termination with the
    /// closed gap.
    #[test]
    fn settling_proves_what_the_lattice_proves_and_nothing_more() {
        let l = lattice(1.0, 0.0);
        let mut r = result(Termination::Optimal, 68.0, 67.02);
        assert_eq!(r.termination, Termination::Limit(LimitKind::Gap));
        assert_eq!(l.settle(&mut r, Sense::Minimize), Some(67.02));
        assert_eq!((r.termination.clone(), r.dual_bound, r.gap), (Termination::Optimal, Some(68.0), Some(0.0)));

        let mut r = result(Termination::Optimal, 68.0, 66.5);
        l.settle(&mut r, Sense::Minimize);
        assert_eq!((r.termination.clone(), r.dual_bound), (Termination::Limit(LimitKind::Gap), Some(67.0)));
        assert!(r.gap.unwrap() > 0.01);

        let mut r = result(Termination::Limit(LimitKind::Time), 68.0, 67.5);
        l.settle(&mut r, Sense::Minimize);
        assert_eq!((r.termination.clone(), r.gap), (Termination::Limit(LimitKind::Time), Some(0.0)));

        // Never past the objective, which the solver reached a hair below its lattice point.
        let mut r = result(Termination::Optimal, 68.0 - 1e-10, 67.3);
        l.settle(&mut r, Sense::Minimize);
        assert_eq!((r.termination.clone(), r.dual_bound), (Termination::Optimal, Some(68.0 - 1e-10)));

        let mut r = result(Termination::Limit(LimitKind::Time), 68.0, 67.5);
        r.dual_bound = None;
        assert_eq!(l.settle(&mut r, Sense::Minimize), None);
    }
}
