//! Recipes: which form each part of the network IP takes, and which strengthenings are on
//! (docs/formulation.md, "Recipes").

use crate::spec::{
    BigMForm, ConnectivityForm, CoverageForm, DeadEndForm, DistanceForm, FormulationSpec, PathForm, Problem,
    RecipeName, Switch, SWITCHES,
};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A recipe resolved into one choice per part and a value for every switch (docs/spec.md
/// "Formulations"). It says what the model is, never how it is solved (that is the pipeline's
/// solve strategy).
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
    /// Every switch of [`SWITCHES`], on or off.
    pub switches: BTreeMap<String, bool>,
}

/// The least order of a problem's symmetry group at which the `symmetric_flow` switch applies:
/// with one reflection (order 2) the cutsets were worth more than the symmetry (Fig. 2f: 21.5 s
/// with them, 47.3 s without), with the whole group of the square (order 8) the symmetry more
/// (Fig. 2b: proven in 30 s instead of a 14 % gap at 35 s; docs/benchmarks.md).
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
        let (connectivity, distance, coverage, dead_ends, paths, big_m) = match name {
            RecipeName::Paper => (
                C::Labels,
                DistanceForm::Labels,
                CoverageForm::Aggregated,
                DeadEndForm::Nu,
                PathForm::Paper,
                BigMForm::Paper,
            ),
            RecipeName::Tight => (
                C::Labels,
                DistanceForm::Labels,
                CoverageForm::Strong,
                DeadEndForm::Degree,
                PathForm::Tight,
                BigMForm::Tight,
            ),
            RecipeName::Strong => (
                C::Cutset,
                DistanceForm::Flow,
                CoverageForm::Strong,
                DeadEndForm::Degree,
                PathForm::Select,
                BigMForm::Tight,
            ),
        };
        Recipe {
            name,
            label: name.name().to_string(),
            connectivity,
            rooms_connectivity: (name == RecipeName::Strong).then_some(C::Flow),
            distance,
            coverage,
            dead_ends,
            paths,
            big_m,
            switches: SWITCHES.iter().map(|s| (s.key.to_string(), s.default_in(name))).collect(),
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
        for (key, &on) in &parts.switches {
            r.switches.insert(key.clone(), on);
        }
        r
    }

    /// The recipe of a problem.
    pub fn of(p: &Problem) -> Recipe {
        Recipe::from_spec(&p.formulation)
    }

    /// Whether a switch is on.
    pub fn on(&self, s: &Switch) -> bool {
        self.switches.get(s.key).copied().unwrap_or_else(|| s.default_in(self.name))
    }

    /// The same recipe with a switch set (the label is kept: this is for experiments in code).
    pub fn with(&self, s: &Switch, on: bool) -> Recipe {
        let mut r = self.clone();
        r.switches.insert(s.key.to_string(), on);
        r
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
        let symmetry_order = (self.on(&crate::spec::switch::SYMMETRIC_FLOW)
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
    /// The order of the problem's symmetry group when the `symmetric_flow` switch applies (the
    /// cutsets are then left to the distance flow); `None` otherwise.
    pub symmetry_order: Option<usize>,
}

impl Plan {
    /// Whether connectivity is separated lazily (cutsets).
    pub fn lazy_cutsets(&self) -> bool {
        self.connectivity == Some(ConnectivityForm::Cutset)
    }
}
