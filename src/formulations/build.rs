//! A formulation: the MILP a recipe emits for a problem, its shared variables, its families,
//! and what it needs beyond the rows (a separator for lazily separated families).

use super::expr::Emitter;
use super::families::cutset;
use super::families::REGISTRY;
use super::family::{Ctx, Family, VarMap};
use super::recipe::Recipe;
use super::Formulation;
use crate::design::Network;
use crate::milp::{Model, Sense};
use crate::rules::paths::enumerate_path_sets;
use crate::rules::placements::enumerate_for;
use crate::solvers::lattice::ObjectiveLattice;
use crate::spec::{EdgeRole, Problem};

/// Builds the formulation the problem's spec asks for.
pub fn build(p: &Problem) -> Formulation {
    build_with(p, &Recipe::of(p))
}

/// Builds the problem under the same recipe with every lazily separated family in its compact
/// form (cutsets written as a flow): the whole model in one file.
pub fn build_compact(p: &Problem) -> Formulation {
    build_with(p, &Recipe::of(p).compact())
}

/// Builds a problem under a given recipe. Families are emitted in the registry's order, so the
/// same problem and recipe give the same model, byte for byte (the `paper` recipe's rows, names
/// and order are the paper's model as this project has always written it).
pub fn build_with(p: &Problem, recipe: &Recipe) -> Formulation {
    let path_sets = p.p2p.is_some().then(|| enumerate_path_sets(p));
    let placements = p.rooms.as_ref().map(|r| enumerate_for(p, r));
    let plan = recipe.plan(p);
    let mut em = Emitter::new(&p.spec.name);
    em.model.sense = Sense::Minimize;
    let big_m = plan.labels.then(|| super::families::edges::big_m(p, recipe.big_m));
    let vars = VarMap::new(p.mesh.num_vertices(), p.mesh.num_edges());
    let mut c =
        Ctx { p, recipe, plan, em, vars, big_m, path_sets: path_sets.as_ref(), placements: placements.as_ref() };
    let mut parts: Vec<Box<dyn Family>> = Vec::new();
    for entry in REGISTRY {
        let Some(mut family) = entry(&c) else { continue };
        let (v0, r0, n0) = (c.em.model.num_vars(), c.em.model.num_rows(), c.em.model.num_nonzeros());
        family.emit(&mut c);
        let s = c.em.families.entry(family.label()).or_default();
        s.vars += c.em.model.num_vars() - v0;
        s.rows += c.em.model.num_rows() - r0;
        s.nonzeros += c.em.model.num_nonzeros() - n0;
        parts.push(family);
    }
    let Ctx { em, vars, plan, .. } = c;
    let objective_lattice = objective_lattice(&em.model, &parts);
    let cutsets = parts
        .iter()
        .find_map(|f| (f.as_ref() as &dyn std::any::Any).downcast_ref::<cutset::Cutsets>()?.graph())
        .cloned();
    Formulation {
        recipe: recipe.clone(),
        model: em.model,
        vars,
        families: em.families,
        parts,
        big_m,
        path_sets,
        placements,
        cutsets,
        objective_lattice,
        symmetry_order: plan.symmetry_order,
    }
}

/// The objective's lattice ([`crate::solvers::lattice`]). Besides integer variables, the
/// continuous variables with a cost that keep the optimum on the lattice are the ones the
/// families vouch for ([`Family::lattice_vars`]): flows on a network matrix with integral
/// supplies and capacities, and exact indicators. The paper's labels `D` are not: their rows
/// hold the big-M.
fn objective_lattice(model: &Model, parts: &[Box<dyn Family>]) -> Option<ObjectiveLattice> {
    let mut certified = vec![false; model.num_vars()];
    for v in parts.iter().flat_map(|f| f.lattice_vars()) {
        certified[v.index()] = true;
    }
    ObjectiveLattice::of_model(model, |v| certified[v.index()])
}

impl Formulation {
    /// Whether the model holds every row (no lazily separated family).
    pub fn is_complete(&self) -> bool {
        self.cutsets.is_none()
    }

    /// A separator for the lazily separated rows, if any.
    pub fn separator<'a>(&self) -> Option<cutset::CutsetSeparator<'a>> {
        self.cutsets.clone().map(cutset::CutsetSeparator::new)
    }

    /// Decodes a point into a network (binaries rounded at ½): active edges and directions, then
    /// each family's own part (labels, chosen rooms).
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
        for e in mesh.edges() {
            for h in mesh.edge_half_edges(e) {
                if self.vars.half_edge[h.index()].is_some_and(|v| x[v.index()] > 0.5) {
                    directions.push((mesh.he_tail(h), mesh.he_head(h)));
                }
            }
        }
        let mut net = Network { active, directions, labels: Vec::new(), rooms: Vec::new() };
        for family in &self.parts {
            family.decode(p, x, &mut net);
        }
        net
    }
}
