//! A formulation: the MILP a recipe emits for a problem, its variable map, and what it needs
//! beyond the rows (a separator for lazily separated families).

use super::expr::{Emitter, FamilyStats};
use super::families::{self, cutset, Ctx};
use super::recipe::Recipe;
use super::vars::VarMap;
use crate::design::Network;
use crate::milp::{Model, Sense};
use crate::rules::paths::PathSets;
use crate::rules::placements::PlacementReport;
use crate::solvers::lattice::ObjectiveLattice;
use crate::spec::{Allow, ConnectivityForm, EdgeRole, Problem, RoomMode, Weight};
use indexmap::IndexMap;

/// The emitted MILP of one problem under one recipe, with the map from design elements to its
/// variables.
pub struct Formulation {
    /// The recipe, resolved.
    pub recipe: Recipe,
    /// The MILP (without lazily separated rows).
    pub model: Model,
    /// Which variable stands for what.
    pub vars: VarMap,
    /// Variables and rows per family, in emission order.
    pub families: IndexMap<String, FamilyStats>,
    /// The big-M of the label rows (2), when the recipe has labels.
    pub big_m: Option<f64>,
    /// Point-to-point path sets, if on.
    pub path_sets: Option<PathSets>,
    /// Room placements, if room tiling is on (their `R` are `vars.rooms`).
    pub placements: Option<PlacementReport>,
    /// The graph of the lazily separated cutsets, when the recipe has them; on tilings with
    /// served faces, of the cover cutsets separated as cuts ([`cutset::CutsetGraph::cuts_only`]).
    pub cutsets: Option<cutset::CutsetGraph>,
    /// The lattice every design's objective lies on, when there is one
    /// ([`crate::solvers::lattice`]); the pipeline uses it when the recipe says so.
    pub objective_lattice: Option<ObjectiveLattice>,
    /// The order of the problem's symmetry group when the recipe left connectivity to the
    /// distance flow for it ([`Recipe::symmetric_flow`]); `None` otherwise.
    pub symmetry_order: Option<usize>,
}

/// Builds the formulation the problem's spec asks for.
pub fn build(p: &Problem) -> Formulation {
    build_with(p, &Recipe::of(p))
}

/// Builds the problem under the same recipe with every lazily separated family in its compact
/// form (cutsets written as a flow): the whole model in one file.
pub fn build_compact(p: &Problem) -> Formulation {
    build_with(p, &Recipe::of(p).compact())
}

/// Builds a problem under a given recipe. Families are emitted in a fixed order, so the same
/// problem and recipe give the same model, byte for byte (the `paper` recipe's rows, names and
/// order are the paper's model as this project has always written it).
pub fn build_with(p: &Problem, recipe: &Recipe) -> Formulation {
    let mesh = &p.mesh;
    let mut em = Emitter::new(&p.spec.name);
    em.model.sense = Sense::Minimize;
    let plan = recipe.plan(p);
    let mut c = Ctx { p, recipe, plan, em, vars: VarMap::new(mesh.num_vertices(), mesh.num_edges()) };
    let big_m = plan.labels.then(|| families::edges::big_m(p, recipe.big_m));
    let m = big_m.unwrap_or(0.0);
    fam(&mut c, if plan.labels { "edges (4)" } else { "edges" }, |c| families::edges::edges(c, m));
    if plan.labels {
        fam(&mut c, "no-island (1)-(3)", |c| families::edges::no_island_labels(c, m));
        if recipe.label_bounds {
            fam(&mut c, "label bounds (§8)", |c| families::edges::label_bounds(c, m));
        }
    }
    let coverage_label = if p.rooms.is_some() { "vertices (5)" } else { "coverage (5)-(6)" };
    fam(&mut c, coverage_label, |c| {
        families::coverage::vertices(c);
        if p.rooms.is_none() {
            families::coverage::coverage(c);
        }
    });
    if plan.distance_flow {
        fam(&mut c, "distance flow (§8)", families::connectivity::distance_flow);
    }
    if plan.travel_flow {
        fam(&mut c, "travel flow (§8)", families::connectivity::travel_flow);
    }
    if plan.connectivity == Some(ConnectivityForm::Flow) {
        fam(&mut c, "connectivity flow (§8)", families::connectivity::connectivity_flow);
    }
    // Cutsets are separated on streets (lazily) and, with served faces, on tilings (as cuts);
    // without direction binaries the directed ones count the parent arcs, which need writing.
    let lazy = plan.connectivity == Some(ConnectivityForm::Cutset);
    let separates_cutsets = lazy || (p.rooms.is_some() && recipe.served_faces);
    let parent_cutsets = recipe.directed_cutsets && !plan.distance_flow && separates_cutsets;
    if (recipe.out_arcs && p.dead_ends == Allow::Allow) || parent_cutsets {
        fam(&mut c, "out-arcs (§8)", families::connectivity::out_arcs);
    }
    if p.dead_ends == Allow::Forbid {
        fam(&mut c, "dead-ends (10)-(11)", families::local::dead_ends);
    }
    if p.branches == Allow::Forbid {
        fam(&mut c, "branches (12)", families::local::branches);
    }
    if p.w_zigzag != Weight::Off {
        fam(&mut c, "zig-zag (13, k=0)", families::local::zigzags);
    }
    if p.w_too_close != Weight::Off {
        fam(&mut c, "too-close (13, k=1)", families::local::too_close);
    }
    if p.w_t_junction != Weight::Off {
        fam(&mut c, "T-junctions (14)", families::local::t_junctions);
    }
    let path_sets = p.p2p.is_some().then(|| fam(&mut c, "point-to-point (8)-(9)", families::paths::point_to_point));
    let placements = p.rooms.as_ref().map(|rooms| {
        let label = match rooms.mode {
            RoomMode::Floorplan => "rooms (16)-(18)",
            RoomMode::Game => "blocks (16), (19)-(20)",
        };
        fam(&mut c, label, |c| families::rooms::rooms(c, rooms))
    });
    // With served faces, a tiling's faces give cover groups (their serving edges' ends), whose
    // cutsets are separated as cuts beside the compact flow.
    let room_groups = match (&p.rooms, &placements) {
        (Some(rooms), Some(report)) if recipe.served_faces => {
            Some(fam(&mut c, "served faces", |c| families::rooms::served_faces(c, rooms.mode, report)))
        }
        _ => None,
    };
    if !p.forced_vertices.is_empty() || !p.through_routes.is_empty() || !p.forced_edges.is_empty() {
        fam(&mut c, "user specifications", families::user::user_specs);
    }
    let cutsets = (lazy || room_groups.is_some()).then(|| {
        let directions = if plan.distance_flow {
            Some(c.vars.half_edge.as_slice())
        } else {
            parent_cutsets.then_some(c.vars.parent.as_slice())
        };
        let mut g = cutset::CutsetGraph::new(p, &c.vars.edge, &c.vars.vertex, directions);
        g.cuts_only = !lazy;
        let girth = (p.dead_ends == Allow::Forbid).then(|| families::coverage::girth(p));
        // Coverage (6) is in the model only without rooms; its balls give the cover cutsets.
        match room_groups {
            None => g.with_cover_groups(p, &c.vars.vertex, girth),
            Some(groups) => g.with_groups(p, &c.vars.vertex, girth, groups),
        }
    });
    if cutsets.is_some() {
        let label = if lazy { "cutsets (§8, lazy)" } else { "cover cutsets (§8, cuts)" };
        c.em.families.entry(label.to_string()).or_default();
    }
    let Ctx { em, vars, plan, .. } = c;
    let objective_lattice = objective_lattice(&em.model, &vars);
    let symmetry_order = plan.symmetry_order;
    Formulation {
        recipe: recipe.clone(),
        model: em.model,
        vars,
        families: em.families,
        big_m,
        path_sets,
        placements,
        cutsets,
        objective_lattice,
        symmetry_order,
    }
}

/// The objective's lattice ([`crate::solvers::lattice`]). Besides integer variables, the
/// continuous variables with a cost that keep the optimum on the lattice are the flows
/// (distance, travel, connectivity: at integral direction binaries and vertex activities a
/// min-cost flow with integral supplies and capacities on a network matrix, whose optimum is
/// integral) and the continuous indicators of penalised configurations (`Z = max(0, Σ E −
/// (n − 1))` at an optimum). The paper's labels `D` are not: their rows hold the big-M.
fn objective_lattice(model: &Model, vars: &VarMap) -> Option<ObjectiveLattice> {
    let mut certified = vec![false; model.num_vars()];
    let flows = vars.distance_flow.iter().chain(&vars.travel_flow).chain(&vars.connect_flow).flatten();
    let indicators =
        vars.local_configs.iter().filter_map(|c| c.indicator).chain(vars.t_configs.iter().filter_map(|t| t.indicator));
    for v in flows.copied().chain(indicators) {
        certified[v.index()] = true;
    }
    ObjectiveLattice::of_model(model, |v| certified[v.index()])
}

/// Runs one family, charging what it adds to `label`.
fn fam<T>(c: &mut Ctx, label: &str, f: impl FnOnce(&mut Ctx) -> T) -> T {
    let (v0, r0, n0) = (c.em.model.num_vars(), c.em.model.num_rows(), c.em.model.num_nonzeros());
    let out = f(c);
    let s = c.em.families.entry(label.to_string()).or_default();
    s.vars += c.em.model.num_vars() - v0;
    s.rows += c.em.model.num_rows() - r0;
    s.nonzeros += c.em.model.num_nonzeros() - n0;
    out
}

impl Formulation {
    /// Solver settings for this model on the backend `kind`: the recipe's
    /// ([`Recipe::solver_hints`]) and, where the recipe kept the model symmetric for a symmetric
    /// problem ([`Recipe::symmetric_flow`]), `presolve=off` on HiGHS (its presolve's reductions
    /// break the symmetry before HiGHS looks for it).
    pub fn solver_hints(
        &self,
        kind: crate::solvers::SolverKind,
        threads: Option<u32>,
    ) -> Vec<crate::solvers::RawParam> {
        let mut hints = self.recipe.solver_hints(kind, threads);
        if kind == crate::solvers::SolverKind::Highs && self.symmetry_order.is_some() {
            hints.push(crate::solvers::RawParam { solver: kind, name: "presolve".into(), value: "off".into() });
        }
        hints
    }

    /// Whether the model holds every row (no lazily separated family).
    pub fn is_complete(&self) -> bool {
        self.cutsets.as_ref().map_or(true, |g| g.cuts_only)
    }

    /// A separator for the lazily separated rows, if any.
    pub fn separator<'a>(&self) -> Option<cutset::CutsetSeparator<'a>> {
        self.cutsets.clone().map(cutset::CutsetSeparator::new)
    }

    /// Decodes a point into a network (binaries rounded at ½): active edges, directions and
    /// labels where the recipe has them, chosen rooms.
    pub fn decode(&self, p: &Problem, x: &[f64]) -> Network {
        let mesh = &p.mesh;
        let active = mesh
            .edges()
            .map(|e| match self.vars.edge[e.index()] {
                Some(v) => x[v.index()] > 0.5,
                None => p.roles[e.index()] == EdgeRole::Existing,
            })
            .collect();
        let mut directions = Vec::new();
        let mut labels = Vec::new();
        for e in mesh.edges() {
            for h in mesh.edge_half_edges(e) {
                if let Some(v) = self.vars.half_edge[h.index()] {
                    if x[v.index()] > 0.5 {
                        directions.push((mesh.he_tail(h), mesh.he_head(h)));
                        if let Some(d) = self.vars.label[h.index()] {
                            labels.push((mesh.he_tail(h), mesh.he_head(h), x[d.index()]));
                        }
                    }
                }
            }
        }
        let rooms = self.vars.rooms.iter().enumerate().filter(|(_, v)| x[v.index()] > 0.5).map(|(k, _)| k).collect();
        Network { active, directions, labels, rooms }
    }
}
