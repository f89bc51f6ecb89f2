//! The `formulation` key of a spec: a recipe name, or a table naming a recipe and overriding
//! its parts (FORMULATION.md §3 and §8; docs/spec.md "Formulations").
//!
//! ```toml
//! formulation = "strong"          # paper | tight | strong (default strong)
//! # or
//! [formulation]
//! recipe = "strong"
//! connectivity = "flow"            # labels | flow | cutset
//! ```

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};

/// A named composition of constraint families.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default, PartialOrd, Ord)]
#[serde(rename_all = "lowercase")]
pub enum RecipeName {
    /// Exactly the paper's rows (big-M = Δall, aggregated coverage (5), ν dead-end indicators,
    /// (8) in the paper's form): reproducible byte for byte.
    Paper,
    /// The paper's distance labels with every valid strengthening: a small big-M, label bounds
    /// tied to the direction binaries, compact dead-end rows, `P ≤ E_n`, disaggregated and
    /// edge-coverage rows.
    Tight,
    /// No labels: connectivity by cutsets (separated lazily; a single-commodity flow where the
    /// model must be compact), the distance term by a flow tied to the direction binaries, and
    /// the strengthened coverage.
    #[default]
    Strong,
}

impl RecipeName {
    /// Every recipe, in a fixed order.
    pub const ALL: [RecipeName; 3] = [RecipeName::Paper, RecipeName::Tight, RecipeName::Strong];

    /// The name used in specs, on the command line and in results.
    pub fn name(self) -> &'static str {
        match self {
            RecipeName::Paper => "paper",
            RecipeName::Tight => "tight",
            RecipeName::Strong => "strong",
        }
    }
}

impl std::fmt::Display for RecipeName {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for RecipeName {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        RecipeName::ALL
            .into_iter()
            .find(|r| r.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown formulation `{s}` (known: paper, tight, strong)"))
    }
}

/// How the network is tied to the sinks (no islands).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ConnectivityForm {
    /// The paper's (1)–(3): direction binaries, successors and distance labels.
    Labels,
    /// A single-commodity flow from the sinks to every active vertex (compact).
    Flow,
    /// Cutset rows `Σ_{x∈δ(C)} E_x ≥ V_v`, separated lazily.
    Cutset,
}

/// How the travel-distance term `λD·Σ D(i→j)` is modelled.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DistanceForm {
    /// The paper's labels (1)–(3).
    Labels,
    /// A flow on the active half-edges whose cost equals the paper's term exactly.
    Flow,
}

/// How coverage (5) ties vertices to edges, and whether the edge-coverage rows are added.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CoverageForm {
    /// The paper's aggregated (5): `1 − |E_y| ≤ Σ E_x − |E_y|·V_y ≤ 0`.
    Aggregated,
    /// `V_y ≤ Σ E_x` and `E_x ≤ V_y` per incident edge.
    Disaggregated,
    /// Disaggregated, plus the edge-coverage rows of FORMULATION §8.
    Strong,
}

/// How forbidden dead-ends are written.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DeadEndForm {
    /// The paper's ν indicators (10)–(11), corrected to constrain both ends.
    Nu,
    /// `Σ E_x ≥ 2·V_y` at non-sinks.
    Degree,
}

/// How a point-to-point path variable is tied to its edges (8).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PathForm {
    /// `−N + 1 ≤ N·P − Σ E_n ≤ 0`.
    Paper,
    /// `P ≤ E_n` for each edge.
    Tight,
    /// One path chosen per pair: `Σ_paths P = 1`, and for each candidate edge `e` of the pair's
    /// paths `Σ_{paths through e} P ≤ E_e`, for each of their vertices `y` (where not implied)
    /// `Σ_{paths through y} P ≤ V_y` (FORMULATION §3.4 aggregated; see
    /// `formulations::families::paths`).
    Select,
}

/// The constant of the label rows (2).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BigMForm {
    /// Δall, the sum of the lengths of all candidate half-edges.
    Paper,
    /// The sum of the `|V_c| − 1` longest candidate edges (a label is a simple path's length).
    Tight,
}

/// A recipe with some of its parts overridden (the table form of `formulation`).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields)]
pub struct FormulationParts {
    /// The recipe whose parts are the defaults.
    #[serde(default)]
    pub recipe: RecipeName,
    /// No-islands family.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub connectivity: Option<ConnectivityForm>,
    /// Travel-distance family (when `weights.distance` > 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance: Option<DistanceForm>,
    /// Coverage family.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coverage: Option<CoverageForm>,
    /// Dead-end rows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dead_ends: Option<DeadEndForm>,
    /// Point-to-point rows (8).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub paths: Option<PathForm>,
    /// The big-M of the label rows (2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub big_m: Option<BigMForm>,
    /// Valid label bounds tied to the direction binaries (labels only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label_bounds: Option<bool>,
    /// The two-phase solve for objectives in two scales (`solvers::split`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub split_objective: Option<bool>,
    /// The recipe's measured solver settings (`Recipe::solver_hints`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub solver_tuning: Option<bool>,
    /// Penalised local configurations (zig-zags, too-close pairs, T-junctions) with a continuous
    /// indicator in `[0, 1]` and the one row `Z ≥ Σ E − (n − 1)`, instead of the paper's binary
    /// indicator and its two-sided row.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub continuous_indicators: Option<bool>,
    /// The solve rounds its bound up to the objective's lattice (`solvers::lattice`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub objective_lattice: Option<bool>,
    /// Out-arc rows: every active non-sink vertex has an arc out toward the sinks.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub out_arcs: Option<bool>,
    /// Directed cutsets on parent arcs where the recipe has no direction binaries.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub directed_cutsets: Option<bool>,
    /// Served faces on tilings: each face's room (block) has a serving edge among the union
    /// of its placements', and its ends reach a sink (cutsets separated as cuts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub served_faces: Option<bool>,
    /// HiGHS's parallel tree search (`parallel=on`) when the solve has two threads or more
    /// (`Recipe::solver_hints`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parallel_search: Option<bool>,
    /// On a problem with four symmetries or more, connectivity through the distance flow alone
    /// (no cutsets) and HiGHS's presolve off, so that the model stays symmetric and HiGHS uses
    /// its symmetry (`Recipe::symmetric_flow`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub symmetric_flow: Option<bool>,
}

/// The `formulation` key: a recipe name or a table of parts.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(untagged)]
pub enum FormulationSpec {
    /// `formulation = "strong"`.
    Named(RecipeName),
    /// `[formulation]` with `recipe = …` and part overrides.
    Parts(FormulationParts),
}

impl Default for FormulationSpec {
    fn default() -> Self {
        FormulationSpec::Named(RecipeName::default())
    }
}

impl From<RecipeName> for FormulationSpec {
    fn from(r: RecipeName) -> Self {
        FormulationSpec::Named(r)
    }
}

impl FormulationSpec {
    /// The recipe named (directly or as the table's base).
    pub fn recipe(&self) -> RecipeName {
        match self {
            FormulationSpec::Named(r) => *r,
            FormulationSpec::Parts(p) => p.recipe,
        }
    }

    /// The parts, with `None` for every part the recipe decides.
    pub fn parts(&self) -> FormulationParts {
        match self {
            FormulationSpec::Named(r) => FormulationParts { recipe: *r, ..FormulationParts::default() },
            FormulationSpec::Parts(p) => p.clone(),
        }
    }

    /// A short label for tables: `strong`, or `strong(connectivity=flow)` with overrides.
    pub fn label(&self) -> String {
        let p = self.parts();
        let mut over = Vec::new();
        let mut push = |k: &str, v: Option<String>| {
            if let Some(v) = v {
                over.push(format!("{k}={v}"));
            }
        };
        let s = |v: &dyn erased::Lower| v.lower();
        push("connectivity", p.connectivity.map(|v| s(&v)));
        push("distance", p.distance.map(|v| s(&v)));
        push("coverage", p.coverage.map(|v| s(&v)));
        push("dead_ends", p.dead_ends.map(|v| s(&v)));
        push("paths", p.paths.map(|v| s(&v)));
        push("big_m", p.big_m.map(|v| s(&v)));
        push("label_bounds", p.label_bounds.map(|v| v.to_string()));
        push("split_objective", p.split_objective.map(|v| v.to_string()));
        push("solver_tuning", p.solver_tuning.map(|v| v.to_string()));
        push("continuous_indicators", p.continuous_indicators.map(|v| v.to_string()));
        push("objective_lattice", p.objective_lattice.map(|v| v.to_string()));
        push("out_arcs", p.out_arcs.map(|v| v.to_string()));
        push("directed_cutsets", p.directed_cutsets.map(|v| v.to_string()));
        push("served_faces", p.served_faces.map(|v| v.to_string()));
        push("parallel_search", p.parallel_search.map(|v| v.to_string()));
        push("symmetric_flow", p.symmetric_flow.map(|v| v.to_string()));
        if over.is_empty() {
            p.recipe.name().to_string()
        } else {
            format!("{}({})", p.recipe.name(), over.join(","))
        }
    }
}

mod erased {
    /// The serde name of a unit enum value.
    pub trait Lower {
        fn lower(&self) -> String;
    }
    impl<T: serde::Serialize> Lower for T {
        fn lower(&self) -> String {
            serde_json::to_value(self).ok().and_then(|v| v.as_str().map(str::to_string)).unwrap_or_default()
        }
    }
}

impl<'de> Deserialize<'de> for FormulationSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = FormulationSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(
                    "a recipe name (\"paper\", \"tight\" or \"strong\") or a table with `recipe` and part overrides",
                )
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<FormulationSpec, E> {
                s.parse::<RecipeName>().map(FormulationSpec::Named).map_err(E::custom)
            }
            fn visit_map<A: MapAccess<'de>>(self, m: A) -> Result<FormulationSpec, A::Error> {
                FormulationParts::deserialize(de::value::MapAccessDeserializer::new(m)).map(FormulationSpec::Parts)
            }
        }
        d.deserialize_any(V)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize, Debug)]
    struct Holder {
        formulation: FormulationSpec,
    }

    #[test]
    fn names_tables_and_errors() {
        let h: Holder = toml::from_str("formulation = \"tight\"").unwrap();
        assert_eq!(h.formulation, FormulationSpec::Named(RecipeName::Tight));
        let h: Holder = toml::from_str("[formulation]\nrecipe = \"paper\"\nconnectivity = \"flow\"\n").unwrap();
        assert_eq!(h.formulation.recipe(), RecipeName::Paper);
        assert_eq!(h.formulation.parts().connectivity, Some(ConnectivityForm::Flow));
        assert_eq!(h.formulation.label(), "paper(connectivity=flow)");
        let e = toml::from_str::<Holder>("formulation = \"fast\"").unwrap_err().to_string();
        assert!(e.contains("unknown formulation `fast`"), "{e}");
        let e = toml::from_str::<Holder>("[formulation]\nconectivity = \"flow\"\n").unwrap_err().to_string();
        assert!(e.contains("conectivity"), "{e}");
        // JSON round trip of both forms.
        for f in [FormulationSpec::Named(RecipeName::Strong), h_parts()] {
            let j = serde_json::to_string(&Holder { formulation: f.clone() }).unwrap();
            let back: Holder = serde_json::from_str(&j).unwrap();
            assert_eq!(back.formulation, f);
        }
    }

    fn h_parts() -> FormulationSpec {
        FormulationSpec::Parts(FormulationParts {
            recipe: RecipeName::Tight,
            coverage: Some(CoverageForm::Aggregated),
            ..Default::default()
        })
    }
}
