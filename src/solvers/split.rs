//! The objective split: an exact two-phase solve for objectives whose terms fall in two scales.
//!
//! The paper's floor plans and Fig. 7a weigh length by 1 and the distance term by 1e-4 (its
//! `0*`): `z = P + S` with `P` the large terms (length, zig-zag penalties: integer variables with
//! coefficients on a lattice `q·ℤ`, e.g. edge lengths in multiples of 0.5) and `S` the small
//! ones. A solver that sees `z` cannot round its bound to the lattice — `S` is continuous — so it
//! can sit at a bound of 30.23 below a design of 30.50 that no design with `P = 30` could beat.
//!
//! The split solves instead
//! 1. **phase 1**: `min P` (scaled by `1/q`, so that the backend's objective-integrality test
//!    rounds its bound up to the lattice), giving a design with `P = P₁` and a bound `b₁`
//!    rounded up to the lattice;
//! 2. **phase 2**: `min z` with `b₁ ≤ P ≤ P₁` added, from phase 1's design (its continuous part
//!    re-derived by the caller's `polish`), giving a design and a bound `b₂`.
//!
//! The combined bound is `min(b₂, P₁ + q + S_min)`: a design has `P < b₁` (none exists, by phase
//! 1), `b₁ ≤ P ≤ P₁` (phase 2's bound holds), or `P ≥ P₁ + q` (then `z ≥ P₁ + q + S_min`, with
//! `S_min` the least `S` allowed by the variables' bounds). It proves the design optimal as soon
//! as phase 2 does and the design's `S` is below `q + S_min`, which [`ObjectiveSplit::suits`]
//! asks of the start before the split is tried.

use super::lattice::lattice_step;
use super::{LazyReport, LazyRow, SolveOptions, SolveResult, SolverError, Termination};
use crate::milp::{check_point, Model, Sense, Tolerances, VarId, VarKind};
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// The least ratio between the smallest large and the largest small objective coefficient.
const SCALE_RATIO: f64 = 100.0;
/// Phase 1's share of the time limit (phase 2 gets the rest, and whatever phase 1 leaves).
const PHASE1_SHARE: f64 = 0.85;

/// An objective `P + S + constant` split into large lattice terms `P` and small terms `S`.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjectiveSplit {
    /// The lattice step `q` of `P`: every coefficient of `P` is an integer multiple of it.
    pub quantum: f64,
    /// The terms of `P` (integer variables only).
    pub primary: Vec<(VarId, f64)>,
    /// The least value of `S` over the variables' bounds.
    pub secondary_floor: f64,
}

impl ObjectiveSplit {
    /// The split of a minimisation's objective, if it has one: nonzero coefficients in two
    /// magnitude classes at least [`SCALE_RATIO`] apart (cut at the widest ratio), the large ones
    /// on integer variables and on a lattice `q·ℤ` with `q = g/d`, `d ≤ 1000`, and the small
    /// ones with a finite least value over the bounds.
    pub fn detect(model: &Model) -> Option<ObjectiveSplit> {
        if model.sense != Sense::Minimize {
            return None;
        }
        let terms: Vec<(VarId, f64)> = model
            .vars()
            .iter()
            .enumerate()
            .filter(|(_, v)| v.obj != 0.0)
            .map(|(j, v)| (VarId(j as u32), v.obj))
            .collect();
        let mut mags: Vec<f64> = terms.iter().map(|t| t.1.abs()).collect();
        mags.sort_by(|a, b| b.total_cmp(a));
        mags.dedup();
        let (cut, ratio) = mags.windows(2).map(|w| (w[0], w[0] / w[1])).max_by(|a, b| a.1.total_cmp(&b.1))?;
        if ratio < SCALE_RATIO {
            return None;
        }
        let (primary, secondary): (Vec<_>, Vec<_>) = terms.into_iter().partition(|t| t.1.abs() >= cut);
        if primary.iter().any(|&(v, _)| model.var(v).kind == VarKind::Continuous) {
            return None;
        }
        let quantum = lattice_step(&primary.iter().map(|t| t.1).collect::<Vec<_>>())?;
        let secondary_floor = secondary
            .iter()
            .map(|&(v, c)| {
                let var = model.var(v);
                c * if c > 0.0 { var.lb } else { var.ub }
            })
            .sum::<f64>();
        secondary_floor.is_finite().then_some(ObjectiveSplit { quantum, primary, secondary_floor })
    }

    /// `P` at `x`.
    pub fn primary_value(&self, x: &[f64]) -> f64 {
        self.primary.iter().map(|&(v, c)| c * x[v.index()]).sum()
    }

    /// `S` at `x` (the objective less `P` and the constant).
    pub fn secondary_value(&self, model: &Model, x: &[f64]) -> f64 {
        model.objective_value(x) - model.obj_constant - self.primary_value(x)
    }

    /// Whether the split can prove a design like `start` optimal: its `S` is less than half a
    /// lattice step above `S`'s least value (a design whose `S` reaches `q` above it could be
    /// beaten by one with a larger `P`, which phase 2 does not look at).
    pub fn suits(&self, model: &Model, start: &[f64]) -> bool {
        self.secondary_value(model, start) - self.secondary_floor < 0.5 * self.quantum
    }

    /// `v` rounded up to the lattice (less a relative 1e-6 for the solver's rounding noise; the
    /// whole objective's [`super::lattice::ObjectiveLattice::round_up`] is more cautious, keeping
    /// a bound within 0.005 of a step of a lattice point there).
    fn round_up(&self, v: f64) -> f64 {
        let steps = v / self.quantum;
        self.quantum * (steps - 1e-6 * steps.abs().max(1.0)).ceil()
    }

    /// Phase 1's model: the constraints of `model` with the objective `P / q`.
    fn phase1_model(&self, model: &Model) -> Model {
        let mut m = model.clone();
        for j in 0..m.num_vars() {
            m.var_mut(VarId(j as u32)).obj = 0.0;
        }
        for &(v, c) in &self.primary {
            m.var_mut(v).obj = (c / self.quantum).round();
        }
        m.obj_constant = 0.0;
        m
    }
}

/// One phase's result, for the report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhaseReport {
    /// Why the phase stopped.
    pub termination: Termination,
    /// Its objective (phase 1: `P`, phase 2: the whole objective), if it has a design.
    pub objective: Option<f64>,
    /// Its dual bound (phase 1: rounded up to the lattice).
    pub dual_bound: Option<f64>,
    /// Branch-and-bound nodes.
    pub nodes: Option<u64>,
    /// Wall time, seconds.
    pub wall_time: f64,
}

impl PhaseReport {
    /// The report of a phase that ended with `r`, its objective and bound given in the phase's
    /// own terms.
    fn new(r: &SolveResult, objective: Option<f64>, dual_bound: Option<f64>, since: Instant) -> PhaseReport {
        PhaseReport {
            termination: r.termination.clone(),
            objective,
            dual_bound,
            nodes: r.nodes,
            wall_time: since.elapsed().as_secs_f64(),
        }
    }
}

/// What the split did ([`solve_split`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SplitReport {
    /// The lattice step `q` of the large terms.
    pub quantum: f64,
    /// The least value of the small terms over the bounds.
    pub secondary_floor: f64,
    /// Phase 1 (`min P`).
    pub phase1: PhaseReport,
    /// Phase 2 (`min z` with `P` held between phase 1's bound and design), when it ran.
    pub phase2: Option<PhaseReport>,
}

/// A split solve's result: the combined result for the original model, every lazy row either
/// phase added, the lazy reports merged, and the split's own report.
#[derive(Clone, Debug)]
pub struct SplitSolve {
    /// The result for the original model (its objective, the combined bound).
    pub result: SolveResult,
    /// The lazy rows of both phases.
    pub rows: Vec<LazyRow>,
    /// Both phases' lazy reports, summed.
    pub lazy: Option<LazyReport>,
    /// The phases.
    pub report: SplitReport,
}

/// What one phase's solve returns: the result, the lazy rows it added, its lazy report.
pub type PhaseSolve = (SolveResult, Vec<LazyRow>, Option<LazyReport>);

/// Runs the split ([module docs](self)) with `solve` for each phase (a plain or a lazy solve)
/// and `polish` to re-derive the continuous part of phase 1's design for phase 2's start.
/// Phase 1 gets [`PHASE1_SHARE`] of the time limit; an infeasible phase 1 or one without a
/// design ends the split with phase 1's result (no design; its bound on `P` plus `S_min`).
pub fn solve_split(
    model: &Model,
    split: &ObjectiveSplit,
    o: &SolveOptions,
    mut solve: impl FnMut(&Model, &SolveOptions) -> Result<PhaseSolve, SolverError>,
    polish: impl Fn(&[f64]) -> Option<Vec<f64>>,
) -> Result<SplitSolve, SolverError> {
    let t0 = Instant::now();
    let tol = Tolerances::default();
    let left = |o: &SolveOptions| o.finite_time_limit().map(|l| (l - t0.elapsed().as_secs_f64()).max(0.0));
    let m1 = split.phase1_model(model);
    let mut o1 = o.clone();
    o1.time_limit = o.finite_time_limit().map(|l| PHASE1_SHARE * l);
    let (mut r1, mut rows, mut lazy) = solve(&m1, &o1)?;
    let q = split.quantum;
    let b1 = r1.dual_bound.map(|b| split.round_up(b * q));
    let mut report = SplitReport {
        quantum: q,
        secondary_floor: split.secondary_floor,
        phase1: PhaseReport::new(&r1, r1.primal.as_ref().map(|x| split.primary_value(x)), b1, t0),
        phase2: None,
    };
    let Some(x1) = r1.primal.take() else {
        let mut r = r1;
        r.objective = None;
        // P ≥ b₁ holds for every design, and S ≥ its least value.
        r.dual_bound = b1.map(|b| b + split.secondary_floor);
        r.finish(model.sense);
        r.wall_time = t0.elapsed().as_secs_f64();
        return Ok(SplitSolve { result: r, rows, lazy, report });
    };
    let p1 = split.primary_value(&x1);
    // Phase 2: the original objective with P held in [b₁, P₁], plus the lazy rows phase 1's
    // model held (not the slack root rows it left out).
    let mut m2 = model.clone();
    for r in &rows {
        r.add_to(&mut m2);
    }
    let slack = |v: f64| 1e-7 * v.abs().max(1.0);
    let lo = b1.unwrap_or(f64::NEG_INFINITY).min(p1);
    m2.add_row("split_primary", lo - slack(lo), p1 + slack(p1), split.primary.iter().copied());
    // The start: the best of phase 1's design with its continuous part re-derived, that design,
    // and the original start, among those phase 2's model holds (the first of equals).
    let start = [polish(&x1), Some(x1.clone()), o.mip_start.clone()]
        .into_iter()
        .flatten()
        .filter(|x| check_point(&m2, x, &tol).is_feasible())
        .map(|x| (model.objective_value(&x), x))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or(x1, |(_, x)| x);
    let mut o2 = o.clone();
    o2.time_limit = left(o);
    o2.mip_start = Some(start.clone());
    let t2 = Instant::now();
    let (mut r, rows2, lazy2) = solve(&m2, &o2)?;
    report.phase2 = Some(PhaseReport::new(&r, r.objective, r.dual_bound, t2));
    rows.extend(rows2);
    match (&mut lazy, lazy2) {
        (Some(a), Some(b)) => *a += &b,
        (a, b) => *a = a.take().or(b),
    }
    if r.primal.is_none() || r.objective.is_some_and(|z| z > model.objective_value(&start)) {
        r.objective = Some(model.objective_value(&start));
        r.primal = Some(start);
    }
    // Designs with P ≥ P₁ + q are bounded by the lattice; those with P in [b₁, P₁] by phase 2.
    let beyond = p1 + q + split.secondary_floor;
    // Phase 2 holds P ≥ b₁, so its bound is at least b₁ + S_min even before its solver has one.
    let b2 = r.dual_bound.map_or(lo + split.secondary_floor, |b| b.max(lo + split.secondary_floor));
    r.dual_bound = Some(b2.min(beyond));
    if r.termination == Termination::Infeasible {
        // Phase 1's design is in phase 2's model, so its solver erred; keep the design.
        r.termination = Termination::Limit(super::LimitKind::Other);
    }
    r.nodes = Some(r1.nodes.unwrap_or(0) + r.nodes.unwrap_or(0));
    r.solver_time = match (r1.solver_time, r.solver_time) {
        (Some(a), Some(b)) => Some(a + b),
        (a, b) => a.or(b),
    };
    r.mip_start = r1.mip_start;
    r.finish(model.sense);
    r.wall_time = t0.elapsed().as_secs_f64();
    Ok(SplitSolve { result: r, rows, lazy, report })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattice_step_finds_the_common_step() {
        assert_eq!(lattice_step(&[1.0, 5.0, 0.5]), Some(0.5));
        assert_eq!(lattice_step(&[2.0, 4.0]), Some(2.0));
        assert_eq!(lattice_step(&[0.3, 0.7]), Some(0.1));
        assert_eq!(lattice_step(&[std::f64::consts::PI]), None);
    }

    /// `min x + 5y + 0.5z + 1e-4·(u + 2w)`: x, y, z integer, u, w continuous in [0, 10].
    fn two_scales(z_kind: VarKind) -> Model {
        let mut m = Model::new("two_scales");
        m.add_integer("x", 0.0, 3.0, 1.0);
        m.add_binary("y", 5.0);
        let z = m.add_integer("z", 0.0, 3.0, 0.5);
        m.var_mut(z).kind = z_kind;
        m.add_continuous("u", 0.0, 10.0, 1e-4);
        m.add_continuous("w", 1.0, 10.0, 2e-4);
        m
    }

    #[test]
    fn detect_splits_two_scales_on_a_lattice() {
        let m = two_scales(VarKind::Integer);
        let s = ObjectiveSplit::detect(&m).expect("two scales");
        assert_eq!(s.quantum, 0.5);
        assert_eq!(s.primary.iter().map(|t| t.0 .0).collect::<Vec<_>>(), vec![0, 1, 2]);
        assert!((s.secondary_floor - 2e-4).abs() < 1e-12, "w ≥ 1 costs 2e-4 at least");
        let x = [1.0, 1.0, 2.0, 5.0, 1.0];
        assert!((s.primary_value(&x) - 7.0).abs() < 1e-12);
        assert!((s.secondary_value(&m, &x) - 7e-4).abs() < 1e-12);
        assert!(s.suits(&m, &x));
        // The phase-1 objective is P / q, integral.
        let m1 = s.phase1_model(&m);
        assert_eq!(m1.vars().iter().map(|v| v.obj).collect::<Vec<_>>(), vec![2.0, 10.0, 1.0, 0.0, 0.0]);
    }

    #[test]
    fn detect_refuses_what_it_cannot_prove_with() {
        // A continuous variable among the large terms: no lattice.
        assert_eq!(ObjectiveSplit::detect(&two_scales(VarKind::Continuous)), None);
        // One scale only.
        let mut m = Model::new("one_scale");
        m.add_binary("a", 1.0);
        m.add_binary("b", 5.0);
        assert_eq!(ObjectiveSplit::detect(&m), None);
        // Large terms off any lattice with denominator ≤ 1000.
        let mut m = Model::new("off_lattice");
        m.add_binary("a", std::f64::consts::PI);
        m.add_continuous("u", 0.0, 1.0, 1e-4);
        assert_eq!(ObjectiveSplit::detect(&m), None);
        // Small terms unbounded below.
        let mut m = Model::new("unbounded_small");
        m.add_binary("a", 1.0);
        m.add_continuous("u", f64::NEG_INFINITY, 1.0, 1e-4);
        assert_eq!(ObjectiveSplit::detect(&m), None);
        // A maximisation.
        let mut m = two_scales(VarKind::Integer);
        m.sense = Sense::Maximize;
        assert_eq!(ObjectiveSplit::detect(&m), None);
    }

    #[test]
    fn suits_asks_for_small_terms_below_half_a_step() {
        let m = two_scales(VarKind::Integer);
        let s = ObjectiveSplit::detect(&m).unwrap();
        let mut big = two_scales(VarKind::Integer);
        big.var_mut(VarId(3)).ub = 1e4;
        assert!(s.suits(&m, &[0.0, 0.0, 0.0, 10.0, 10.0]));
        assert!(!s.suits(&big, &[0.0, 0.0, 0.0, 3000.0, 1.0]), "S = 0.3 is more than half of q = 0.5 above its floor");
    }

    /// A scripted solve: phase 1 (the model whose small terms cost nothing) returns `phase1`,
    /// phase 2 returns `phase2`; every model it was given is kept.
    fn scripted(
        phase1: Option<(Vec<f64>, f64)>,
        phase2: Option<(Vec<f64>, f64, Termination)>,
        seen: &mut Vec<Model>,
    ) -> impl FnMut(&Model, &SolveOptions) -> Result<PhaseSolve, SolverError> + '_ {
        move |m: &Model, _: &SolveOptions| {
            seen.push(m.clone());
            let mut r = SolveResult::empty(
                crate::solvers::SolverKind::Microlp,
                "scripted".into(),
                Termination::Limit(crate::solvers::LimitKind::Time),
            );
            if m.var(VarId(3)).obj == 0.0 {
                if let Some((x, bound)) = &phase1 {
                    r.objective = Some(m.objective_value(x));
                    r.primal = Some(x.clone());
                    r.dual_bound = Some(*bound);
                }
            } else if let Some((x, bound, t)) = &phase2 {
                r.termination = t.clone();
                r.objective = Some(m.objective_value(x));
                r.primal = Some(x.clone());
                r.dual_bound = Some(*bound);
            }
            Ok((r, Vec::new(), None))
        }
    }

    #[test]
    fn solve_split_combines_the_phases_bounds() {
        let m = two_scales(VarKind::Integer);
        let s = ObjectiveSplit::detect(&m).unwrap();
        let o = SolveOptions { mip_start: Some(vec![3.0, 1.0, 0.0, 10.0, 10.0]), ..SolveOptions::default() };
        // Phase 1: a design with P = 7 and the scaled bound 13.2 (P ≥ 6.6, so P ≥ 7 on the
        // lattice); its small terms re-derived by `polish` (u = 0, w = 1: S = 2e-4).
        let x1 = vec![1.0, 1.0, 2.0, 10.0, 10.0];
        let polish = |x: &[f64]| Some(vec![x[0], x[1], x[2], 0.0, 1.0]);
        // Phase 2 ends without a design and with a weak bound of its own.
        let mut seen = Vec::new();
        let out = solve_split(&m, &s, &o, scripted(Some((x1.clone(), 13.2)), None, &mut seen), polish).unwrap();
        assert_eq!(out.report.phase1.dual_bound, Some(7.0));
        assert_eq!(out.report.phase1.objective, Some(7.0));
        let m2 = &seen[1];
        let row = m2.row(crate::milp::RowId(m2.num_rows() as u32 - 1));
        assert_eq!(row.name, "split_primary");
        assert!(
            (row.lhs - 7.0).abs() < 1e-6 && (row.rhs - 7.0).abs() < 1e-6,
            "P held at 7: [{}, {}]",
            row.lhs,
            row.rhs
        );
        // The polished design (better than the start, whose P = 8 is outside [7, 7]) is returned,
        // and the bound is P ≥ 7 plus the small terms' floor: the design is proven.
        assert_eq!(out.result.primal.as_deref(), Some(&[1.0, 1.0, 2.0, 0.0, 1.0][..]));
        assert!((out.result.objective.unwrap() - 7.0002).abs() < 1e-12);
        assert!((out.result.dual_bound.unwrap() - 7.0002).abs() < 1e-12);
        // Phase 2's bound holds only for P ≤ P₁: the result's bound is capped at P₁ + q + S_min,
        // all that is known of the designs with P ≥ P₁ + q.
        let costly = vec![1.0, 1.0, 2.0, 10.0, 10.0];
        let mut seen = Vec::new();
        let out = solve_split(
            &m,
            &s,
            &o,
            scripted(Some((x1.clone(), 14.0)), Some((costly.clone(), 9.0, Termination::Optimal)), &mut seen),
            |_: &[f64]| None,
        )
        .unwrap();
        assert!((out.result.dual_bound.unwrap() - 7.5002).abs() < 1e-12, "{:?}", out.result.dual_bound);
        assert_eq!(out.result.primal.as_deref(), Some(&costly[..]));
        // Phase 1 without a design: no phase 2, the bound is phase 1's on P plus S's floor.
        let mut seen = Vec::new();
        let out = solve_split(
            &m,
            &s,
            &o,
            |mm: &Model, oo: &SolveOptions| {
                let mut f = scripted(None, None, &mut seen);
                let (mut r, rows, lazy) = f(mm, oo)?;
                r.dual_bound = Some(12.4);
                Ok((r, rows, lazy))
            },
            |_: &[f64]| None,
        )
        .unwrap();
        assert!(out.report.phase2.is_none());
        assert!(out.result.primal.is_none());
        assert!((out.result.dual_bound.unwrap() - 6.5002).abs() < 1e-12, "{:?}", out.result.dual_bound);
    }

    #[test]
    fn round_up_tolerates_noise() {
        let s = ObjectiveSplit { quantum: 0.5, primary: vec![], secondary_floor: 0.0 };
        assert_eq!(s.round_up(30.23), 30.5);
        assert_eq!(s.round_up(30.5 - 1e-9), 30.5);
        assert_eq!(s.round_up(30.5 + 1e-3), 31.0);
    }
}
