//! The `formulation` key of a spec: a recipe name, or a table naming a recipe and overriding
//! its parts and switches (docs/formulation.md; docs/spec.md "Formulations").
//!
//! ```toml
//! formulation = "strong"          # paper | tight | strong (default strong)
//! # or
//! [formulation]
//! recipe = "strong"
//! connectivity = "flow"            # labels | flow | cutset
//! out_arcs = false                 # a switch (see SWITCHES)
//! ```
//!
//! On the command line the same is one word, `RECIPE[:KEY=VALUE]…` (`strong:out_arcs=off`,
//! [`Variant`]), which may also set the solve strategy's switches of `[solver]`.

use serde::de::{self, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use std::collections::BTreeMap;

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
    /// `V_y ≤ Σ E_x` and `E_x ≤ V_y` per incident edge, plus the edge-coverage rows and ball
    /// cuts of docs/formulation.md §8.
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
    /// `Σ_{paths through y} P ≤ V_y` (docs/formulation.md §3.4 aggregated; see
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

/// A strengthening a recipe turns on or off: `[formulation] out_arcs = false`. None changes the
/// designs a model allows, only how tight its relaxation is; the families that read one say so.
#[derive(Debug, PartialEq, Eq)]
pub struct Switch {
    /// The key in `[formulation]` and on the command line.
    pub key: &'static str,
    /// What it does, for `--help`-like listings.
    pub about: &'static str,
    /// The recipes it is on in by default.
    pub on_in: &'static [RecipeName],
}

/// The recipe switches, by name.
pub mod switch {
    use super::{RecipeName, Switch};

    /// Label bounds tied to the direction binaries, and `E(i→j) + E(j→i) = E_x` for (4).
    pub const LABEL_BOUNDS: Switch = Switch {
        key: "label_bounds",
        about: "valid label bounds tied to the direction binaries (labels only)",
        on_in: &[RecipeName::Tight, RecipeName::Strong],
    };
    /// Penalised local configurations with a continuous indicator and one row.
    pub const CONTINUOUS_INDICATORS: Switch = Switch {
        key: "continuous_indicators",
        about: "penalised zig-zags, too-close pairs and T-junctions with a continuous indicator and one row",
        on_in: &[RecipeName::Strong],
    };
    /// Every active non-sink vertex has an arc out toward the sinks.
    pub const OUT_ARCS: Switch = Switch {
        key: "out_arcs",
        about: "every active non-sink vertex has an arc out toward the sinks",
        on_in: &[RecipeName::Strong],
    };
    /// Cutsets counted on parent arcs where the recipe has no direction binaries.
    pub const DIRECTED_CUTSETS: Switch = Switch {
        key: "directed_cutsets",
        about: "cutsets counted on parent arcs where the recipe has no direction binaries",
        on_in: &[RecipeName::Strong],
    };
    /// On a problem with four symmetries or more, connectivity from the distance flow alone.
    pub const SYMMETRIC_FLOW: Switch = Switch {
        key: "symmetric_flow",
        about: "on a problem with four symmetries or more, connectivity from the distance flow alone (no cutsets)",
        on_in: &[RecipeName::Strong],
    };
    /// On tilings, one row: the network is at least as long as the chosen rooms' rows need.
    pub const ROOM_LENGTH: Switch = Switch {
        key: "room_length",
        about: "on tilings, one row: the network is at least as long as the chosen rooms' own rows need together",
        on_in: &[RecipeName::Strong],
    };
    /// On floor plans, a row per face: a corridor near it, whichever room covers it. On in no
    /// recipe: it lifts the root LP of the Table 1 floor plans, and the MILP at their time
    /// limits ends worse with it (docs/benchmarks.md).
    pub const ROOM_REACH: Switch = Switch {
        key: "room_reach",
        about: "on floor plans, a row per face: whichever room covers it, a corridor runs along that room's boundary near the face",
        on_in: &[],
    };
}

/// Every recipe switch, in the order labels list them.
pub const SWITCHES: &[&Switch] = &[
    &switch::LABEL_BOUNDS,
    &switch::CONTINUOUS_INDICATORS,
    &switch::OUT_ARCS,
    &switch::DIRECTED_CUTSETS,
    &switch::SYMMETRIC_FLOW,
    &switch::ROOM_LENGTH,
    &switch::ROOM_REACH,
];

/// The keys of `[solver]` that set the solve strategy (they change no row of the model).
pub const STRATEGY_KEYS: &[&str] = &["split_objective", "objective_lattice", "solver_tuning", "parallel_search", "lns"];

/// The part keys of `[formulation]` besides the switches.
const PART_KEYS: &[&str] = &["recipe", "connectivity", "distance", "coverage", "dead_ends", "paths", "big_m"];

impl Switch {
    /// Whether the switch is on in `recipe` unless a spec says otherwise.
    pub fn default_in(&self, recipe: RecipeName) -> bool {
        self.on_in.contains(&recipe)
    }

    /// The switch named `key`.
    pub fn named(key: &str) -> Option<&'static Switch> {
        SWITCHES.iter().copied().find(|s| s.key == key)
    }
}

/// A recipe with some of its parts overridden (the table form of `formulation`).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Default)]
pub struct FormulationParts {
    /// The recipe whose parts are the defaults.
    pub recipe: RecipeName,
    /// No-islands family.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub connectivity: Option<ConnectivityForm>,
    /// Travel-distance family (when `weights.distance` > 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distance: Option<DistanceForm>,
    /// Coverage family.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coverage: Option<CoverageForm>,
    /// Dead-end rows.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dead_ends: Option<DeadEndForm>,
    /// Point-to-point rows (8).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paths: Option<PathForm>,
    /// The big-M of the label rows (2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub big_m: Option<BigMForm>,
    /// Switches set by the spec ([`SWITCHES`]), by key.
    #[serde(flatten)]
    pub switches: BTreeMap<String, bool>,
}

impl FormulationParts {
    /// Sets one key of the table from its text (`connectivity`, `flow`; `out_arcs`, `off`), as
    /// the command line gives it. The error names the key and what it takes.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), String> {
        fn form<T: serde::de::DeserializeOwned>(key: &str, value: &str) -> Result<T, String> {
            serde_json::from_value(serde_json::Value::String(value.to_ascii_lowercase()))
                .map_err(|e| format!("`{key}`: {e}"))
        }
        match key {
            "recipe" => self.recipe = value.parse()?,
            "connectivity" => self.connectivity = Some(form(key, value)?),
            "distance" => self.distance = Some(form(key, value)?),
            "coverage" => self.coverage = Some(form(key, value)?),
            "dead_ends" => self.dead_ends = Some(form(key, value)?),
            "paths" => self.paths = Some(form(key, value)?),
            "big_m" => self.big_m = Some(form(key, value)?),
            _ => {
                let s = switch_key(key)?;
                self.switches.insert(s.key.to_string(), parse_on_off(key, value)?);
            }
        }
        Ok(())
    }
}

/// The switch named `key`, or an error that says what `[formulation]` takes (and where a solve
/// strategy key belongs).
fn switch_key(key: &str) -> Result<&'static Switch, String> {
    if let Some(s) = Switch::named(key) {
        return Ok(s);
    }
    if STRATEGY_KEYS.contains(&key) {
        return Err(format!("`{key}` is a solve setting, not a part of the model: set it in `[solver]`"));
    }
    let known: Vec<&str> = PART_KEYS.iter().copied().chain(SWITCHES.iter().map(|s| s.key)).collect();
    Err(format!("unknown key `{key}` (known: {})", known.join(", ")))
}

/// `on`/`off`/`true`/`false`/`yes`/`no`/`1`/`0`.
pub fn parse_on_off(key: &str, value: &str) -> Result<bool, String> {
    match value.to_ascii_lowercase().as_str() {
        "on" | "true" | "yes" | "1" => Ok(true),
        "off" | "false" | "no" | "0" => Ok(false),
        _ => Err(format!("`{key}` takes on or off, got `{value}`")),
    }
}

impl<'de> Deserialize<'de> for FormulationParts {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = FormulationParts;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a table with `recipe`, part overrides and switches")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<FormulationParts, A::Error> {
                let mut p = FormulationParts::default();
                while let Some(key) = m.next_key::<String>()? {
                    match key.as_str() {
                        "recipe" => p.recipe = m.next_value()?,
                        "connectivity" => p.connectivity = Some(m.next_value()?),
                        "distance" => p.distance = Some(m.next_value()?),
                        "coverage" => p.coverage = Some(m.next_value()?),
                        "dead_ends" => p.dead_ends = Some(m.next_value()?),
                        "paths" => p.paths = Some(m.next_value()?),
                        "big_m" => p.big_m = Some(m.next_value()?),
                        other => {
                            let s = switch_key(other).map_err(de::Error::custom)?;
                            let on: bool = m
                                .next_value()
                                .map_err(|e| de::Error::custom(format!("`{other}` takes true or false: {e}")))?;
                            p.switches.insert(s.key.to_string(), on);
                        }
                    }
                }
                Ok(p)
            }
        }
        d.deserialize_map(V)
    }
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
        for sw in SWITCHES {
            push(sw.key, p.switches.get(sw.key).map(|v| v.to_string()));
        }
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

/// A formulation with its switches, and the solve strategy's switches, in one word as the command
/// line takes it: `strong`, `strong:out_arcs=off`, `paper:coverage=strong:split_objective=on`
/// (`RECIPE[:KEY=VALUE]…`; keys are the `[formulation]` table's and the strategy keys of
/// `[solver]`, [`STRATEGY_KEYS`]).
#[derive(Clone, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct Variant {
    /// The formulation it asks for.
    pub formulation: FormulationSpec,
    /// Strategy switches it sets, in the order given.
    pub strategy: Vec<(String, bool)>,
}

impl Variant {
    /// Puts the variant into a spec's `formulation` and `[solver]` strategy switches.
    pub fn apply(&self, formulation: &mut FormulationSpec, solver: &mut super::SolverSpec) {
        *formulation = self.formulation.clone();
        for (key, on) in &self.strategy {
            let slot = match key.as_str() {
                "split_objective" => &mut solver.split_objective,
                "objective_lattice" => &mut solver.objective_lattice,
                "solver_tuning" => &mut solver.solver_tuning,
                "lns" => &mut solver.lns,
                _ => &mut solver.parallel_search,
            };
            *slot = Some(*on);
        }
    }

    /// The recipe it names.
    pub fn recipe(&self) -> RecipeName {
        self.formulation.recipe()
    }
}

impl From<RecipeName> for Variant {
    fn from(r: RecipeName) -> Self {
        Variant { formulation: FormulationSpec::Named(r), strategy: Vec::new() }
    }
}

impl std::str::FromStr for Variant {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let mut words = s.split(':');
        let recipe: RecipeName = words.next().unwrap_or_default().trim().parse()?;
        let mut parts = FormulationParts { recipe, ..FormulationParts::default() };
        let mut strategy = Vec::new();
        let mut any_part = false;
        for w in words {
            let (key, value) = w
                .split_once('=')
                .ok_or_else(|| format!("`{w}` in `{s}`: expected KEY=VALUE (e.g. `{recipe}:out_arcs=off`)"))?;
            let (key, value) = (key.trim(), value.trim());
            if STRATEGY_KEYS.contains(&key) {
                strategy.retain(|(k, _): &(String, bool)| k != key);
                strategy.push((key.to_string(), parse_on_off(key, value)?));
            } else {
                parts.set(key, value).map_err(|e| format!("`{s}`: {e}"))?;
                any_part = true;
            }
        }
        let formulation = if any_part { FormulationSpec::Parts(parts) } else { FormulationSpec::Named(recipe) };
        Ok(Variant { formulation, strategy })
    }
}

impl std::fmt::Display for Variant {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = self.formulation.parts();
        write!(f, "{}", p.recipe)?;
        let s = |v: &dyn erased::Lower| v.lower();
        let forms = [
            ("connectivity", p.connectivity.map(|v| s(&v))),
            ("distance", p.distance.map(|v| s(&v))),
            ("coverage", p.coverage.map(|v| s(&v))),
            ("dead_ends", p.dead_ends.map(|v| s(&v))),
            ("paths", p.paths.map(|v| s(&v))),
            ("big_m", p.big_m.map(|v| s(&v))),
        ];
        for (k, v) in forms {
            if let Some(v) = v {
                write!(f, ":{k}={v}")?;
            }
        }
        for sw in SWITCHES {
            if let Some(on) = p.switches.get(sw.key) {
                write!(f, ":{}={}", sw.key, if *on { "on" } else { "off" })?;
            }
        }
        for (k, on) in &self.strategy {
            write!(f, ":{k}={}", if *on { "on" } else { "off" })?;
        }
        Ok(())
    }
}

impl TryFrom<String> for Variant {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<Variant> for String {
    fn from(v: Variant) -> String {
        v.to_string()
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

    #[test]
    fn switches_and_variants() {
        let h: Holder = toml::from_str("[formulation]\nrecipe = \"strong\"\nout_arcs = false\n").unwrap();
        assert_eq!(h.formulation.parts().switches.get("out_arcs"), Some(&false));
        assert_eq!(h.formulation.label(), "strong(out_arcs=false)");
        let e = toml::from_str::<Holder>("[formulation]\nsplit_objective = false\n").unwrap_err().to_string();
        assert!(e.contains("`split_objective` is a solve setting") && e.contains("[solver]"), "{e}");
        let e = toml::from_str::<Holder>("[formulation]\nout_arcs = \"no\"\n").unwrap_err().to_string();
        assert!(e.contains("`out_arcs` takes true or false"), "{e}");
        let e = toml::from_str::<Holder>("[formulation]\nserved_faces = true\n").unwrap_err().to_string();
        assert!(e.contains("unknown key `served_faces`") && e.contains("out_arcs"), "{e}");

        let v: Variant = "strong:out_arcs=off:split_objective=off".parse().unwrap();
        assert_eq!(v.formulation.label(), "strong(out_arcs=false)");
        assert_eq!(v.strategy, vec![("split_objective".to_string(), false)]);
        assert_eq!(v.to_string(), "strong:out_arcs=off:split_objective=off");
        let v: Variant = "paper".parse().unwrap();
        assert_eq!(v.formulation, FormulationSpec::Named(RecipeName::Paper));
        let v: Variant = "tight:connectivity=flow".parse().unwrap();
        assert_eq!(v.formulation.parts().connectivity, Some(ConnectivityForm::Flow));
        for (bad, says) in [
            ("fast", "unknown formulation `fast`"),
            ("strong:out_arcs", "expected KEY=VALUE"),
            ("strong:out_arcs=maybe", "takes on or off"),
            ("strong:colour=red", "unknown key `colour`"),
            ("strong:connectivity=rope", "`connectivity`"),
        ] {
            let e = bad.parse::<Variant>().unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
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
