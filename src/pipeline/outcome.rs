//! One design run's outcome, the same type for a MILP solve and for a search: why it stopped
//! (apart from whether there is a design, MathOptInterface's principle), the objective, the
//! bound and gap, nodes, times, the solver and its version, and what only one kind of run has
//! (a MILP solve's screen verdict, MIP start check and warnings; a search's seed, trace and
//! counters). It is the `solve` object of `result.json`, whose two layouts (a MILP solve's and a
//! search's) it writes field for field as they have always been, and reads back either.

use crate::heuristics::{SearchStats, TracePoint};
use crate::milp::{Infeasibility, Sense};
use crate::solvers::{LimitKind, SolveResult, StartCheck, Termination};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One design run's outcome (`result.json`'s `solve`).
#[derive(Clone, Debug, PartialEq)]
pub struct Outcome {
    /// Why the run stopped. Says nothing about whether a design exists.
    pub termination: Termination,
    /// The objective of the best design or point found, if any.
    pub objective: Option<f64>,
    /// The best proven bound on the optimum, if known (never for a search).
    pub dual_bound: Option<f64>,
    /// netspec's relative gap ([`crate::solvers::gap`]) from `objective` and `dual_bound`.
    pub gap: Option<f64>,
    /// Branch-and-bound nodes, if the backend reports them (never for a search).
    pub nodes: Option<u64>,
    /// The backend's own run time (a search's time searching), seconds.
    pub solver_time: Option<f64>,
    /// Wall-clock time of the whole solve or search (with its checks), seconds.
    pub wall_time: f64,
    /// The backend (`highs`) or the search (`heuristic`, `anneal`).
    pub solver: String,
    /// The backend's version, or netspec's for a search.
    pub solver_version: String,
    /// A MILP solve's model proven infeasible by netspec without a solver
    /// ([`crate::milp::screen`]): the variable or row, and why.
    pub infeasibility: Option<Infeasibility>,
    /// A MILP solve's MIP start as netspec's checker saw it, when one was given.
    pub mip_start: Option<StartCheck>,
    /// What netspec noticed about a MILP's input before the solve.
    pub warnings: Vec<String>,
    /// What only a search has (`None` for a MILP solve).
    pub search: Option<SearchDetails>,
}

/// What only a search's outcome has.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SearchDetails {
    /// Why no design exists, with `infeasible` (a plain reason the search found).
    pub infeasible_because: Option<String>,
    /// The seed.
    pub seed: u64,
    /// Seconds until the first valid design, if any.
    pub first_design_seconds: Option<f64>,
    /// The best objective over time.
    pub trace: Vec<TracePoint>,
    /// Counters.
    pub stats: SearchStats,
}

impl Outcome {
    /// The outcome of a backend's solve; its primal point is the caller's to keep.
    pub fn of_solve(r: SolveResult) -> Outcome {
        Outcome {
            termination: r.termination,
            objective: r.objective,
            dual_bound: r.dual_bound,
            gap: r.gap,
            nodes: r.nodes,
            solver_time: r.solver_time,
            wall_time: r.wall_time,
            solver: r.solver.name().to_string(),
            solver_version: r.solver_version,
            infeasibility: r.infeasibility,
            mip_start: r.mip_start,
            warnings: r.warnings,
            search: None,
        }
    }

    /// A search's outcome: no bound, no gap, no nodes.
    pub fn of_search(
        method: &str,
        termination: Termination,
        objective: Option<f64>,
        times: (f64, f64),
        details: SearchDetails,
    ) -> Outcome {
        Outcome {
            termination,
            objective,
            dual_bound: None,
            gap: None,
            nodes: None,
            solver_time: Some(times.0),
            wall_time: times.1,
            solver: method.to_string(),
            solver_version: env!("CARGO_PKG_VERSION").into(),
            infeasibility: None,
            mip_start: None,
            warnings: Vec::new(),
            search: Some(details),
        }
    }

    /// Whether a search (not a MILP backend) produced it.
    pub fn is_search(&self) -> bool {
        self.search.is_some()
    }

    /// The solver as a caption names it: `highs 1.15.0`, `netspec heuristic 0.1.0`.
    pub fn solver_label(&self) -> String {
        match self.is_search() {
            true => format!("netspec {} {}", self.solver, self.solver_version),
            false => format!("{} {}", self.solver, self.solver_version),
        }
    }

    /// Whether the run was stopped by an interrupt.
    pub fn interrupted(&self) -> bool {
        self.termination == Termination::Limit(LimitKind::Interrupt)
    }

    /// Fills in `gap` from the bounds and turns an "optimal" whose bound is not within
    /// [`crate::solvers::OPTIMALITY_TOLERANCE`] into a gap limit, as
    /// [`SolveResult::finish`] does.
    pub fn finish(&mut self, sense: Sense) {
        let (gap, termination) = crate::solvers::finished(&self.termination, self.objective, self.dual_bound, sense);
        self.gap = gap;
        self.termination = termination;
    }

    /// One line that says apart why it stopped and whether there is a solution, as
    /// [`SolveResult::status_line`] says it.
    pub fn status_line(&self) -> String {
        crate::solvers::status_line(&self.termination, self.infeasibility.as_ref(), self.objective, self.gap, false)
    }
}

/// A MILP solve's `solve` object, in its field order.
#[derive(Serialize, Deserialize)]
struct MilpWire<T, P, S, I, M, W> {
    termination: T,
    /// Always `null` in `result.json` (the point is written with `--sol`).
    #[serde(default = "Option::default")]
    primal: Option<P>,
    objective: Option<f64>,
    dual_bound: Option<f64>,
    gap: Option<f64>,
    nodes: Option<u64>,
    solver_time: Option<f64>,
    wall_time: f64,
    solver: S,
    solver_version: S,
    #[serde(default = "Option::default", skip_serializing_if = "Option::is_none")]
    infeasibility: Option<I>,
    #[serde(default = "Option::default", skip_serializing_if = "Option::is_none")]
    mip_start: Option<M>,
    #[serde(default = "Vec::new", skip_serializing_if = "Vec::is_empty")]
    warnings: Vec<W>,
}

/// A search's `solve` object, in its field order.
#[derive(Serialize, Deserialize)]
struct SearchWire<T, S, D, St> {
    solver: S,
    solver_version: S,
    termination: T,
    #[serde(default = "Option::default", skip_serializing_if = "Option::is_none")]
    infeasible_because: Option<S>,
    objective: Option<f64>,
    dual_bound: Option<f64>,
    gap: Option<f64>,
    nodes: Option<u64>,
    solver_time: Option<f64>,
    wall_time: f64,
    seed: u64,
    first_design_seconds: Option<f64>,
    trace: D,
    stats: St,
}

impl Serialize for Outcome {
    fn serialize<Z: Serializer>(&self, s: Z) -> Result<Z::Ok, Z::Error> {
        match &self.search {
            Some(d) => SearchWire {
                solver: &self.solver,
                solver_version: &self.solver_version,
                termination: &self.termination,
                infeasible_because: d.infeasible_because.as_ref(),
                objective: self.objective,
                dual_bound: self.dual_bound,
                gap: self.gap,
                nodes: self.nodes,
                solver_time: self.solver_time,
                wall_time: self.wall_time,
                seed: d.seed,
                first_design_seconds: d.first_design_seconds,
                trace: &d.trace,
                stats: &d.stats,
            }
            .serialize(s),
            None => MilpWire {
                termination: &self.termination,
                primal: None::<()>,
                objective: self.objective,
                dual_bound: self.dual_bound,
                gap: self.gap,
                nodes: self.nodes,
                solver_time: self.solver_time,
                wall_time: self.wall_time,
                solver: &self.solver,
                solver_version: &self.solver_version,
                infeasibility: self.infeasibility.as_ref(),
                mip_start: self.mip_start.as_ref(),
                warnings: self.warnings.iter().collect(),
            }
            .serialize(s),
        }
    }
}

/// Either layout, read back.
#[derive(Deserialize)]
#[serde(untagged)]
enum Wire {
    Search(SearchWire<Termination, String, Vec<TracePoint>, SearchStats>),
    Milp(MilpWire<Termination, serde::de::IgnoredAny, String, Infeasibility, StartCheck, String>),
}

impl<'de> Deserialize<'de> for Outcome {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Ok(match Wire::deserialize(d)? {
            Wire::Search(w) => Outcome {
                termination: w.termination,
                objective: w.objective,
                dual_bound: w.dual_bound,
                gap: w.gap,
                nodes: w.nodes,
                solver_time: w.solver_time,
                wall_time: w.wall_time,
                solver: w.solver,
                solver_version: w.solver_version,
                infeasibility: None,
                mip_start: None,
                warnings: Vec::new(),
                search: Some(SearchDetails {
                    infeasible_because: w.infeasible_because,
                    seed: w.seed,
                    first_design_seconds: w.first_design_seconds,
                    trace: w.trace,
                    stats: w.stats,
                }),
            },
            Wire::Milp(w) => Outcome {
                termination: w.termination,
                objective: w.objective,
                dual_bound: w.dual_bound,
                gap: w.gap,
                nodes: w.nodes,
                solver_time: w.solver_time,
                wall_time: w.wall_time,
                solver: w.solver,
                solver_version: w.solver_version,
                infeasibility: w.infeasibility,
                mip_start: w.mip_start,
                warnings: w.warnings,
                search: None,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solvers::SolverKind;

    fn search_outcome() -> Outcome {
        let details = SearchDetails {
            infeasible_because: None,
            seed: 3,
            first_design_seconds: Some(0.5),
            trace: vec![TracePoint { seconds: 0.5, objective: 12.0 }],
            stats: SearchStats::default(),
        };
        Outcome::of_search("heuristic", Termination::Limit(LimitKind::Time), Some(12.0), (1.0, 1.5), details)
    }

    #[test]
    fn a_search_writes_its_own_layout_and_reads_back() {
        let o = search_outcome();
        let text = serde_json::to_string(&o).unwrap();
        assert!(text.starts_with(r#"{"solver":"heuristic","solver_version":"#), "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert!(v.get("primal").is_none() && v.get("warnings").is_none());
        let back: Outcome = serde_json::from_value(v).unwrap();
        assert_eq!(back, o);
    }

    #[test]
    fn a_milp_solve_writes_its_own_layout_and_reads_back() {
        let mut r = SolveResult::empty(SolverKind::Highs, "1.0".into(), Termination::Optimal);
        r.objective = Some(4.0);
        r.dual_bound = Some(4.0);
        r.finish(Sense::Minimize);
        let o = Outcome::of_solve(r.clone());
        let text = serde_json::to_string(&o).unwrap();
        assert!(text.starts_with(r#"{"termination":{"reason":"optimal"},"primal":null,"#), "{text}");
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["solver"], "highs");
        assert_eq!(serde_json::to_value(&r).unwrap(), v, "the backend's layout, point omitted");
        let back: Outcome = serde_json::from_value(v).unwrap();
        assert_eq!(back, o);
        assert_eq!(o.status_line(), r.status_line());
    }
}
