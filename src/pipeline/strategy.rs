//! The solve strategy: how a built model is solved, apart from what the model is. None of these
//! switches changes a row; each defaults to what was measured best for the recipe and can be
//! set in a spec's `[solver]` section.

use crate::formulations::Formulation;
use crate::solvers::{RawParam, SolveOptions, Solver, StrategyHints};
use crate::spec::{RecipeName, SolverSpec};
use serde::{Deserialize, Serialize};

/// How the pipeline solves a built formulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Strategy {
    /// Solve in two phases when the objective has two scales and a start is given
    /// ([`crate::solvers::split`]).
    pub split_objective: bool,
    /// Round the backend's bound up to the objective's lattice when the formulation has one
    /// ([`crate::solvers::lattice`]).
    pub objective_lattice: bool,
    /// Hand the backend the settings measured on the recipe's models
    /// ([`Solver::strategy_hints`]).
    pub solver_tuning: bool,
    /// The backend's parallel tree search when the solve has two threads or more.
    pub parallel_search: bool,
    /// A large-neighbourhood search from the start before the full MILP
    /// ([`crate::pipeline::lns`]); by default on `strong` models of at least
    /// [`LNS_FROM_NONZEROS`] nonzeros.
    pub lns: bool,
}

/// The model size (nonzeros) from which `strong` starts with a large-neighbourhood search unless
/// the spec says otherwise. On Table 1's open rows of this size or more the search returns a
/// better design at the paper's limit on most rows, below it on a few (docs/benchmarks.md,
/// "Large-neighbourhood search"); on fig7b's city the level-3 model (105k nonzeros) leaves its
/// start with it at 20 s, the level-2 model (26k) does better without it.
pub const LNS_FROM_NONZEROS: usize = 60_000;

impl Strategy {
    /// What was measured best for a recipe's model of `nonzeros` nonzeros: everything for
    /// `strong` (the search from [`LNS_FROM_NONZEROS`]); nothing for `paper` and `tight`, which
    /// stay the models and the solves they always were.
    pub fn default_for(recipe: RecipeName, nonzeros: usize) -> Strategy {
        let on = recipe == RecipeName::Strong;
        Strategy {
            split_objective: on,
            objective_lattice: on,
            solver_tuning: on,
            parallel_search: on,
            lns: on && nonzeros >= LNS_FROM_NONZEROS,
        }
    }

    /// The strategy of a solve of a model of `nonzeros` nonzeros: the recipe's defaults with the
    /// spec's `[solver]` switches over them.
    pub fn of(recipe: RecipeName, solver: &SolverSpec, nonzeros: usize) -> Strategy {
        let d = Strategy::default_for(recipe, nonzeros);
        Strategy {
            split_objective: solver.split_objective.unwrap_or(d.split_objective),
            objective_lattice: solver.objective_lattice.unwrap_or(d.objective_lattice),
            solver_tuning: solver.solver_tuning.unwrap_or(d.solver_tuning),
            parallel_search: solver.parallel_search.unwrap_or(d.parallel_search),
            lns: solver.lns.unwrap_or(d.lns),
        }
    }

    /// The strategy of a problem's solve under formulation `f`.
    pub fn for_problem(p: &crate::spec::Problem, f: &Formulation) -> Strategy {
        Strategy::of(f.recipe.name, &p.spec.solver, f.model.num_nonzeros())
    }

    /// What this strategy asks of the backend's own settings for `f`, solved with `threads`.
    pub fn hints(&self, f: &Formulation, threads: Option<u32>) -> StrategyHints {
        StrategyHints {
            tuned: self.solver_tuning,
            parallel_search: self.parallel_search,
            threads,
            // The recipe kept the model symmetric for a symmetric problem: let the backend see it.
            keep_symmetry: f.symmetry_order.is_some(),
        }
    }
}

/// `options` with the backend's strategy `hints` put before the user's parameters, leaving out a
/// hint whose parameter the user sets (theirs wins); and the hints used, as `highs.name=value`.
pub fn with_hints(options: &SolveOptions, hints: &[RawParam]) -> (SolveOptions, Vec<String>) {
    let used: Vec<RawParam> = hints
        .iter()
        .filter(|h| !options.params.iter().any(|p| p.solver == h.solver && p.name == h.name))
        .cloned()
        .collect();
    let names = used.iter().map(|h| h.to_string()).collect();
    let mut o = options.clone();
    o.params = used.into_iter().chain(options.params.iter().cloned()).collect();
    (o, names)
}

/// The backend's hints for `f` under `strategy`, merged into `options` ([`with_hints`]).
pub fn tuned_options(
    solver: &dyn Solver,
    f: &Formulation,
    strategy: &Strategy,
    options: &SolveOptions,
) -> (SolveOptions, Vec<String>) {
    with_hints(options, &solver.strategy_hints(&strategy.hints(f, options.threads)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::SolverKind;

    fn param(solver: SolverKind, name: &str, value: &str) -> RawParam {
        RawParam { solver, name: name.into(), value: value.into() }
    }

    /// The hints go first, so a backend that applies parameters in order lets the user's win;
    /// a hint the user sets by name is left out and not reported; another backend's parameter
    /// of the same name does not count.
    #[test]
    fn hints_yield_to_the_users_parameters() {
        let hint = param(SolverKind::Highs, "mip_pscost_minreliable", "0");
        let user = SolveOptions {
            params: vec![param(SolverKind::Highs, "mip_heuristic_effort", "0.1")],
            ..Default::default()
        };
        let (o, used) = with_hints(&user, std::slice::from_ref(&hint));
        assert_eq!(o.params, vec![hint.clone(), user.params[0].clone()]);
        assert_eq!(used, vec!["highs.mip_pscost_minreliable=0".to_string()]);

        let own = SolveOptions {
            params: vec![param(SolverKind::Highs, "mip_pscost_minreliable", "8")],
            ..Default::default()
        };
        let (o, used) = with_hints(&own, std::slice::from_ref(&hint));
        assert_eq!(o.params, own.params);
        assert!(used.is_empty());

        let other =
            SolveOptions { params: vec![param(SolverKind::Scip, "mip_pscost_minreliable", "8")], ..Default::default() };
        let (o, used) = with_hints(&other, std::slice::from_ref(&hint));
        assert_eq!(o.params, vec![hint, other.params[0].clone()]);
        assert_eq!(used.len(), 1);
    }

    /// Only `strong` is tuned by default; the `[solver]` switches override each part.
    #[test]
    fn strategy_defaults_follow_the_recipe_and_the_spec_overrides_them() {
        assert_eq!(
            Strategy::default_for(RecipeName::Strong, LNS_FROM_NONZEROS - 1),
            Strategy {
                split_objective: true,
                objective_lattice: true,
                solver_tuning: true,
                parallel_search: true,
                lns: false
            }
        );
        assert!(Strategy::default_for(RecipeName::Strong, LNS_FROM_NONZEROS).lns);
        for name in [RecipeName::Paper, RecipeName::Tight] {
            let s = Strategy::default_for(name, LNS_FROM_NONZEROS);
            assert!(
                !s.split_objective && !s.objective_lattice && !s.solver_tuning && !s.parallel_search && !s.lns,
                "{name}"
            );
        }
        let spec = SolverSpec { solver_tuning: Some(false), split_objective: Some(false), ..Default::default() };
        let s = Strategy::of(RecipeName::Strong, &spec, 0);
        assert!(!s.solver_tuning && !s.split_objective && s.objective_lattice && s.parallel_search);
        let spec = SolverSpec { parallel_search: Some(true), ..Default::default() };
        assert!(Strategy::of(RecipeName::Paper, &spec, 0).parallel_search);
        // The search both ways round its size.
        let off = SolverSpec { lns: Some(false), ..Default::default() };
        assert!(!Strategy::of(RecipeName::Strong, &off, LNS_FROM_NONZEROS).lns);
        let on = SolverSpec { lns: Some(true), ..Default::default() };
        assert!(Strategy::of(RecipeName::Strong, &on, 10).lns);
    }

    /// HiGHS's hints, each from its part of the strategy (the parallel search only from two
    /// threads); every other backend has none.
    #[test]
    fn highs_hints_follow_the_strategy_and_other_backends_have_none() {
        let names = |kind: SolverKind, h: StrategyHints| -> Vec<String> {
            kind.instance().map_or(Vec::new(), |s| s.strategy_hints(&h).iter().map(|p| p.to_string()).collect())
        };
        let all = StrategyHints { tuned: true, parallel_search: true, threads: Some(2), keep_symmetry: true };
        if SolverKind::Highs.is_compiled() {
            assert_eq!(
                names(SolverKind::Highs, all),
                ["highs.mip_pscost_minreliable=0", "highs.parallel=on", "highs.presolve=off"]
            );
            assert_eq!(
                names(SolverKind::Highs, StrategyHints { threads: Some(1), keep_symmetry: false, ..all }),
                ["highs.mip_pscost_minreliable=0"]
            );
            assert!(names(SolverKind::Highs, StrategyHints::default()).is_empty());
        }
        for k in [SolverKind::Scip, SolverKind::Cbc, SolverKind::Microlp] {
            assert!(names(k, all).is_empty(), "{k}");
        }
    }
}
