//! Recipes: which family writes each part of the network IP.

use crate::solvers::{RawParam, SolverKind};
use crate::spec::{
    BigMForm, ConnectivityForm, CoverageForm, DeadEndForm, DistanceForm, FormulationSpec, PathForm, Problem, RecipeName,
};
use serde::{Deserialize, Serialize};

/// A recipe resolved into one choice per part (docs/spec.md "Formulations").
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Recipe {
    /// The recipe the parts come from.
    pub name: RecipeName,
    /// `strong`, or `strong(connectivity=flow)` when parts were overridden.
    pub label: String,
    /// No islands: labels (1)–(3), a flow, or lazily separated cutsets.
    pub connectivity: ConnectivityForm,
    /// No islands on problems that tile rooms (floor plans, game levels), where it differs from
    /// `connectivity`: `strong` writes a flow there (see [`Recipe::named`]). `None` once the
    /// spec names a connectivity, which then holds everywhere.
    #[serde(default)]
    pub rooms_connectivity: Option<ConnectivityForm>,
    /// The λD term: labels (1)–(3) or a flow with the same value.
    pub distance: DistanceForm,
    /// Coverage (5)–(6) and the edge-coverage rows.
    pub coverage: CoverageForm,
    /// Forbidden dead-ends.
    pub dead_ends: DeadEndForm,
    /// Point-to-point (8).
    pub paths: PathForm,
    /// The big-M of (2).
    pub big_m: BigMForm,
    /// Label bounds tied to the direction binaries.
    pub label_bounds: bool,
    /// Solve in two phases when the objective has two scales ([`crate::solvers::split`]):
    /// `strong` only.
    #[serde(default)]
    pub split_objective: bool,
    /// Hand the backend the solver settings measured on this recipe's models
    /// ([`Recipe::solver_hints`]): `strong` only.
    #[serde(default)]
    pub solver_tuning: bool,
    /// Penalised local configurations (zig-zags, too-close pairs, T-junctions) get a continuous
    /// indicator `Z ∈ [0, 1]` with `Z ≥ Σ E − (n − 1)` (13)–(14) instead of a binary one with
    /// `0 ≤ Σ E − n·Z ≤ n − 1`: `strong` only. Exact because `Z` has a positive cost and this
    /// one row: at an optimum `Z = max(0, Σ E − (n − 1))`, which is 0 or 1 at integral edges.
    #[serde(default)]
    pub continuous_indicators: bool,
    /// Round the solver's bound up to the objective's lattice, when the formulation's objective
    /// has one ([`crate::solvers::lattice`]): `strong` only.
    #[serde(default)]
    pub objective_lattice: bool,
    /// Every active non-sink vertex has an arc out toward the sinks
    /// ([`crate::formulations::families::connectivity::out_arcs`]): `strong` only.
    #[serde(default)]
    pub out_arcs: bool,
    /// Without the distance flow's direction binaries, the cutsets and cover cutsets count
    /// only the parent arcs leaving a set (the parent arcs of
    /// [`crate::formulations::families::connectivity::out_arcs`], then written whatever the
    /// dead-end rule): `strong` only.
    #[serde(default)]
    pub directed_cutsets: bool,
    /// On tilings, every face's room or block has one of the edges that can serve it, and
    /// their ends reach a sink (the served rows of
    /// [`crate::formulations::families::rooms`] and their cover cutsets, separated as cuts):
    /// off in every recipe, `served_faces = true` in `[formulation]` turns it on.
    #[serde(default)]
    pub served_faces: bool,
    /// Hand HiGHS `parallel=on`, its parallel tree search ([`Recipe::solver_hints`]): `strong`
    /// only; used when the solve has two threads or more (HiGHS runs one search worker
    /// otherwise, and the second core idles once the heuristic's start is handed over).
    #[serde(default)]
    pub parallel_search: bool,
    /// On a problem whose symmetry group ([`crate::spec::symmetries`]) has order
    /// [`SYMMETRIC_FLOW_MIN_ORDER`] or more and which has the distance flow, connectivity comes
    /// from the distance flow alone (no cutsets, so no asymmetric rows from the separator) and
    /// HiGHS gets `presolve=off` ([`crate::formulations::Formulation::solver_hints`]): HiGHS
    /// finds a model's symmetry only without its presolve, and uses it then (orbital fixing).
    /// `strong` only.
    #[serde(default)]
    pub symmetric_flow: bool,
}

/// The least order of a problem's symmetry group at which [`Recipe::symmetric_flow`] applies:
/// with one reflection (order 2) the cutsets were worth more than the symmetry (Fig. 2f: 21.5 s
/// with them, 47.3 s without), with the whole group of the square (order 8) the symmetry more
/// (Fig. 2b: proven in 30 s instead of a 14 % gap at 35 s; docs/benchmarks.md, *Symmetric grids*).
pub const SYMMETRIC_FLOW_MIN_ORDER: usize = 4;

impl Recipe {
    /// The parts of a named recipe.
    ///
    /// `strong` separates cutsets lazily on street networks but writes the single-commodity
    /// flow on tilings: there the solver's first design depends on connectivity being in the
    /// model (measured on Fig. 9b1/9b3, HiGHS: with the flow a first design in 156 s and 18 s,
    /// with cutsets none within the paper's time; the cutset rounds at the root took up to a
    /// fifth of the limit and moved no design closer).
    pub fn named(name: RecipeName) -> Recipe {
        use ConnectivityForm as C;
        let (connectivity, distance, coverage, dead_ends, paths, big_m, label_bounds) = match name {
            RecipeName::Paper => (
                C::Labels,
                DistanceForm::Labels,
                CoverageForm::Aggregated,
                DeadEndForm::Nu,
                PathForm::Paper,
                BigMForm::Paper,
                false,
            ),
            RecipeName::Tight => (
                C::Labels,
                DistanceForm::Labels,
                CoverageForm::Strong,
                DeadEndForm::Degree,
                PathForm::Tight,
                BigMForm::Tight,
                true,
            ),
            RecipeName::Strong => (
                C::Cutset,
                DistanceForm::Flow,
                CoverageForm::Strong,
                DeadEndForm::Degree,
                PathForm::Select,
                BigMForm::Tight,
                true,
            ),
        };
        let rooms_connectivity = (name == RecipeName::Strong).then_some(C::Flow);
        let split_objective = name == RecipeName::Strong;
        let solver_tuning = name == RecipeName::Strong;
        let continuous_indicators = name == RecipeName::Strong;
        let objective_lattice = name == RecipeName::Strong;
        let out_arcs = name == RecipeName::Strong;
        let directed_cutsets = name == RecipeName::Strong;
        let parallel_search = name == RecipeName::Strong;
        let symmetric_flow = name == RecipeName::Strong;
        // Opt-in: measured, it raised every tiling row's bound but cost designs (docs/benchmarks.md).
        let served_faces = false;
        Recipe {
            name,
            label: name.name().to_string(),
            connectivity,
            rooms_connectivity,
            distance,
            coverage,
            dead_ends,
            paths,
            big_m,
            label_bounds,
            split_objective,
            solver_tuning,
            continuous_indicators,
            objective_lattice,
            out_arcs,
            directed_cutsets,
            served_faces,
            parallel_search,
            symmetric_flow,
        }
    }

    /// The recipe a spec asks for, with its overrides.
    pub fn from_spec(f: &FormulationSpec) -> Recipe {
        let parts = f.parts();
        let mut r = Recipe::named(parts.recipe);
        r.label = f.label();
        if let Some(c) = parts.connectivity {
            r.connectivity = c;
            r.rooms_connectivity = None;
        }
        r.distance = parts.distance.unwrap_or(r.distance);
        r.coverage = parts.coverage.unwrap_or(r.coverage);
        r.dead_ends = parts.dead_ends.unwrap_or(r.dead_ends);
        r.paths = parts.paths.unwrap_or(r.paths);
        r.big_m = parts.big_m.unwrap_or(r.big_m);
        r.label_bounds = parts.label_bounds.unwrap_or(r.label_bounds);
        r.split_objective = parts.split_objective.unwrap_or(r.split_objective);
        r.solver_tuning = parts.solver_tuning.unwrap_or(r.solver_tuning);
        r.continuous_indicators = parts.continuous_indicators.unwrap_or(r.continuous_indicators);
        r.objective_lattice = parts.objective_lattice.unwrap_or(r.objective_lattice);
        r.out_arcs = parts.out_arcs.unwrap_or(r.out_arcs);
        r.directed_cutsets = parts.directed_cutsets.unwrap_or(r.directed_cutsets);
        r.served_faces = parts.served_faces.unwrap_or(r.served_faces);
        r.parallel_search = parts.parallel_search.unwrap_or(r.parallel_search);
        r.symmetric_flow = parts.symmetric_flow.unwrap_or(r.symmetric_flow);
        r
    }

    /// Solver settings this recipe's models were measured to need, for the backend `kind`; a
    /// parameter the user sets by the same name replaces its hint (see
    /// `pipeline::with_solver_hints`).
    ///
    /// `strong` on HiGHS: `mip_pscost_minreliable=0` (HiGHS's default 8). HiGHS then branches on
    /// pseudocosts from the first node instead of strong-branching every candidate until it has
    /// eight observations; on Fig. 7d-L2 strong branching took 100,088 of the solve's 124,262 LP
    /// iterations and 7 nodes in 9.5 s. Measured on Table 1 rows (docs/benchmarks.md, *Pseudocost
    /// branching and warm root rounds*): proves 7d-L2 in 9.6 s instead of a 4.7 % gap at 12 s, 2f
    /// in 21.7 s instead of 38.4 s, and no row lost.
    ///
    /// `strong` on HiGHS with `threads` ≥ 2 ([`Recipe::parallel_search`]): `parallel=on`. HiGHS
    /// 1.15 otherwise runs its tree search on one worker whatever the thread count; with it, on
    /// ⌈1.7·threads⌉ workers. Measured on 23 Table 1 rows in one run (docs/benchmarks.md,
    /// *Parallel tree search*): Fig. 7b-L2 proven in 128 s of its 174 (11.8 % gap without), 8-L2
    /// in 113 s instead of 189 s, no row lost.
    pub fn solver_hints(&self, kind: SolverKind, threads: Option<u32>) -> Vec<RawParam> {
        let mut hints = Vec::new();
        if kind != SolverKind::Highs {
            return hints;
        }
        let hint = |name: &str, value: &str| RawParam { solver: kind, name: name.into(), value: value.into() };
        if self.solver_tuning {
            hints.push(hint("mip_pscost_minreliable", "0"));
        }
        if self.parallel_search && threads.is_some_and(|t| t >= 2) {
            hints.push(hint("parallel", "on"));
        }
        hints
    }

    /// The recipe of a problem.
    pub fn of(p: &Problem) -> Recipe {
        Recipe::from_spec(&p.formulation)
    }

    /// The same recipe with every lazily separated family replaced by a compact equivalent
    /// (cutsets by a single-commodity flow), for files that must hold the whole model.
    pub fn compact(&self) -> Recipe {
        let mut r = self.clone();
        if r.rooms_connectivity == Some(ConnectivityForm::Cutset) {
            r.rooms_connectivity = Some(ConnectivityForm::Flow);
        }
        if r.connectivity == ConnectivityForm::Cutset {
            r.connectivity = ConnectivityForm::Flow;
            r.label = format!("{} (cutsets written as a flow)", self.label);
        }
        r
    }

    /// Which families a problem gets from this recipe.
    pub fn plan(&self, p: &Problem) -> Plan {
        let connectivity_form = match (p.rooms.is_some(), self.rooms_connectivity) {
            (true, Some(c)) => c,
            _ => self.connectivity,
        };
        let distance = (p.w_distance > 0.0).then_some(self.distance);
        let symmetry_order = (self.symmetric_flow
            && connectivity_form == ConnectivityForm::Cutset
            && distance == Some(DistanceForm::Flow))
        .then(|| crate::spec::symmetries(p).len() + 1)
        .filter(|&order| order >= SYMMETRIC_FLOW_MIN_ORDER);
        let connectivity_form = if symmetry_order.is_some() { ConnectivityForm::Flow } else { connectivity_form };
        let labels = distance == Some(DistanceForm::Labels)
            || (distance.is_none() && connectivity_form == ConnectivityForm::Labels);
        // A labels or distance-flow family already ties every active edge to a sink; a second
        // connectivity family is added only when asked for explicitly (as a strengthening).
        let connectivity = match (connectivity_form, labels, distance) {
            (ConnectivityForm::Labels, _, _) => None,
            (ConnectivityForm::Flow, _, Some(DistanceForm::Flow)) => None,
            (c, _, _) => Some(c),
        };
        Plan {
            labels,
            distance_flow: distance == Some(DistanceForm::Flow),
            connectivity,
            travel_flow: p.w_travel > 0.0,
            symmetry_order,
        }
    }
}

/// The families a recipe emits for one problem.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Plan {
    /// The paper's labels (1)–(3) (with or without the λD term on them).
    pub labels: bool,
    /// The distance flow (the λD term, and connectivity).
    pub distance_flow: bool,
    /// A separate connectivity family (flow or cutsets), when nothing above gives it.
    pub connectivity: Option<ConnectivityForm>,
    /// The travel flow (the per-vertex travel term).
    pub travel_flow: bool,
    /// The order of the problem's symmetry group when [`Recipe::symmetric_flow`] applies (the
    /// cutsets are then left to the distance flow); `None` otherwise.
    pub symmetry_order: Option<usize>,
}
