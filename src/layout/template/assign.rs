//! The choice of a template for every part the templates settle, with the counts of the library
//! met (Yang et al. 2013 §3: "a template should occur a maximum of k1 times or a minimum of k2
//! times … met by randomized search and backtracking").
//!
//! Every part is a slot; a template with area faces opens a slot per area face, which the area
//! templates fill (nesting); a template is taken only where every area face of it is accepted by
//! some area template. A slot's options are its accepted templates ordered by preference,
//! the product of the template's probability and `exp(−energy / E)` with `E` =
//! [`PREFERENCE_ENERGY`] — the best first (`Selection::Best`), or in a random order drawn with
//! those weights (`Selection::Random`, seeded); after them the fallback (the row parceller).
//!
//! The search is depth first over the slots, largest block first: an option whose template is at
//! its maximum count is skipped, and a branch is abandoned as soon as the slots left cannot lift a
//! template to its minimum (each slot counted as one use of every template among its options, and
//! of area templates as many as its options' templates have area faces). Minimums no assignment
//! can reach are lowered to what the slots can hold before the search; when the search runs out
//! of its budget ([`BUDGET`] options tried), the first options within the maximums are taken.
//! Whatever minimum is not met is reported, never dropped silently.

use super::arclength::Block;
use super::file::{Fill, Template};
use super::select::{Candidate, Matcher};
use super::warp::face_polygons;
use crate::geometry::P;
use crate::layout::parcels::StreetIndex;
use crate::layout::split::Selection;
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

/// The energy scale of the preference: a template `PREFERENCE_ENERGY` worse than another is
/// preferred `e` times less, all else equal.
pub const PREFERENCE_ENERGY: f64 = 0.005;
/// The most options the search tries before it settles for the first options within the maximums.
pub const BUDGET: usize = 50_000;
/// Area faces are filled at most this deep (an area template's own area faces, and so on).
const MAX_NESTING: usize = 3;

/// What fills a part or an area face.
#[derive(Clone, Debug)]
pub struct Choice {
    /// The block it is warped onto.
    pub block: Block,
    /// The warped template.
    pub candidate: Candidate,
    /// Its area faces (by index among the concrete template's faces), each filled by a template
    /// or, when `None`, by the row parceller.
    pub areas: Vec<(usize, Option<Box<Choice>>)>,
}

/// A minimum count not met.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Unmet {
    /// The template.
    pub template: String,
    /// Its minimum.
    pub min: usize,
    /// How often it is used.
    pub used: usize,
}

/// The assignment: per part its choice (`None`: the fallback), the uses per template it made, the
/// counts not met (with the uses it started from), and the options the search tried.
#[derive(Clone, Debug)]
pub struct Assigned {
    /// Per part (in the order given).
    pub parts: Vec<Option<Choice>>,
    /// Uses per template name (area templates included).
    pub uses: BTreeMap<String, usize>,
    /// Minimums not met.
    pub unmet: Vec<Unmet>,
    /// Options tried by the search.
    pub steps: usize,
}

/// A slot: a part or an area face, its block and its options in order of preference.
#[derive(Clone, Debug)]
struct Slot {
    /// The part it belongs to.
    part: usize,
    /// Its path: the part, then (option, face) per nesting level.
    key: Vec<usize>,
    block: Block,
    options: Vec<Candidate>,
    /// Per template: how many uses this slot (and the area faces it may open) can give at most.
    potential: Vec<usize>,
}

/// The preference weight of a candidate.
pub fn preference(t: &Template, c: &Candidate) -> f64 {
    t.probability * (-c.warp.energy / PREFERENCE_ENERGY).exp()
}

/// Options ordered: by preference (ties by energy, then library order), or a random order drawn
/// with the preferences as weights (each key `−ln u / w`, ascending).
fn order(
    mut options: Vec<Candidate>,
    lib: &[Template],
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> Vec<Candidate> {
    match selection {
        Selection::Best => {
            options.sort_by(|a, b| {
                let (wa, wb) = (preference(&lib[a.template], a), preference(&lib[b.template], b));
                wb.total_cmp(&wa).then(a.warp.energy.total_cmp(&b.warp.energy)).then(a.template.cmp(&b.template))
            });
            options
        }
        Selection::Random => {
            let mut keyed: Vec<(f64, Candidate)> = options
                .into_iter()
                .map(|c| {
                    let u: f64 = rng.random::<f64>().max(f64::MIN_POSITIVE);
                    (-u.ln() / preference(&lib[c.template], &c).max(1e-300), c)
                })
                .collect();
            keyed.sort_by(|a, b| a.0.total_cmp(&b.0));
            keyed.into_iter().map(|(_, c)| c).collect()
        }
    }
}

/// The search's state.
struct Search<'s, 'm, 'l> {
    matcher: &'m mut Matcher<'l>,
    index: &'s StreetIndex,
    merge: f64,
    selection: Selection,
    rng: &'s mut Xoshiro256PlusPlus,
    slots: Vec<Slot>,
    choice: Vec<Option<usize>>,
    count: Vec<usize>,
    min: Vec<usize>,
    max: Vec<usize>,
    budget: usize,
    steps: usize,
    memo: HashMap<Vec<usize>, Vec<Slot>>,
}

/// Where the assignment starts: the uses of parts it does not choose for (a relayout's kept
/// parts), the streets (for the area faces' street sides), the corner merge distance of blocks.
pub struct Context<'a> {
    /// Uses per template name already made.
    pub used: &'a BTreeMap<String, usize>,
    /// The streets.
    pub index: &'a StreetIndex,
    /// Corners of blocks closer than this merge.
    pub merge: f64,
}

/// Chooses a template for every part: `parts` gives each part's block and accepted templates
/// (any order).
pub fn assign(
    parts: Vec<Option<(Block, Vec<Candidate>)>>,
    matcher: &mut Matcher,
    ctx: &Context,
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> Assigned {
    let (index, merge) = (ctx.index, ctx.merge);
    let lib = matcher.library();
    let n = lib.len();
    let initial: Vec<usize> = lib.iter().map(|t| ctx.used.get(&t.name).copied().unwrap_or(0)).collect();
    let min: Vec<usize> = lib.iter().map(|t| t.min_uses).collect();
    let max: Vec<usize> = lib.iter().map(|t| t.max_uses.unwrap_or(usize::MAX)).collect();
    let mut slots = Vec::new();
    for (k, p) in parts.iter().enumerate() {
        if let Some((block, options)) = p {
            let options = order(options.clone(), lib, selection, rng);
            let potential = potential(&options, lib);
            slots.push(Slot { part: k, key: vec![k], block: block.clone(), options, potential });
        }
    }
    let roots = slots.len();
    let mut s = Search {
        matcher,
        index,
        merge,
        selection,
        rng,
        choice: vec![None; roots],
        slots,
        count: initial.clone(),
        min: min.clone(),
        max,
        budget: BUDGET,
        steps: 0,
        memo: HashMap::new(),
    };
    // Minimums no assignment can reach are lowered to what the slots can hold.
    for (t, &start) in initial.iter().enumerate() {
        let cap: usize = start + s.slots.iter().map(|sl| sl.potential[t]).sum::<usize>();
        s.min[t] = s.min[t].min(cap);
    }
    if !s.dfs(0) {
        // Out of budget (or the lowered minimums still conflict): the first options within the
        // maximums.
        s.slots.truncate(roots);
        s.choice = vec![None; roots];
        s.count = initial.clone();
        s.min = vec![0; n];
        s.budget = usize::MAX;
        s.dfs(0);
    }
    let steps = s.steps;
    let uses: BTreeMap<String, usize> =
        (0..n).filter(|&t| s.count[t] > initial[t]).map(|t| (lib[t].name.clone(), s.count[t] - initial[t])).collect();
    let unmet = (0..n)
        .filter(|&t| s.count[t] < min[t])
        .map(|t| Unmet { template: lib[t].name.clone(), min: min[t], used: s.count[t] })
        .collect();
    let mut out: Vec<Option<Choice>> = vec![None; parts.len()];
    for i in 0..roots {
        out[s.slots[i].part] = s.build(i);
    }
    Assigned { parts: out, uses, unmet, steps }
}

/// Per template, the uses a slot with these options may give: one for each template among them,
/// and for an area template as many as the options' templates have area faces.
fn potential(options: &[Candidate], lib: &[Template]) -> Vec<usize> {
    let mut p = vec![0; lib.len()];
    let areas = options.iter().map(|c| lib[c.template].faces.iter().filter(|f| f.fill == Fill::Area).count()).max();
    for c in options {
        p[c.template] = 1;
    }
    if let Some(a) = areas.filter(|&a| a > 0) {
        for (t, tpl) in lib.iter().enumerate() {
            if tpl.kind == "area" {
                p[t] += a;
            }
        }
    }
    p
}

impl Search<'_, '_, '_> {
    fn dfs(&mut self, i: usize) -> bool {
        if i == self.slots.len() {
            return (0..self.count.len()).all(|t| self.count[t] >= self.min[t]);
        }
        if !self.feasible(i) {
            return false;
        }
        let n = self.slots[i].options.len();
        for o in (0..n).map(Some).chain([None]) {
            if self.budget == 0 {
                return false;
            }
            self.budget -= 1;
            self.steps += 1;
            let before = self.slots.len();
            if let Some(o) = o {
                let t = self.slots[i].options[o].template;
                if self.count[t] >= self.max[t] {
                    continue;
                }
                let children = self.children(i, o);
                if children.iter().any(|c| c.options.is_empty()) {
                    // An area face no area template fills: the option is not taken.
                    continue;
                }
                self.count[t] += 1;
                self.slots.extend(children);
                self.choice.resize(self.slots.len(), None);
            }
            self.choice[i] = o;
            if self.dfs(i + 1) {
                return true;
            }
            if let Some(o) = o {
                self.count[self.slots[i].options[o].template] -= 1;
            }
            self.choice[i] = None;
            self.slots.truncate(before);
            self.choice.truncate(before);
        }
        false
    }

    /// Whether the slots from `i` on can still lift every template to its minimum.
    fn feasible(&self, i: usize) -> bool {
        (0..self.count.len()).all(|t| {
            let need = self.min[t].saturating_sub(self.count[t]);
            need == 0 || self.slots[i..].iter().map(|s| s.potential[t]).sum::<usize>() >= need
        })
    }

    /// The slots of option `o`'s area faces (memoised by the slot's path).
    fn children(&mut self, i: usize, o: usize) -> Vec<Slot> {
        let mut key = self.slots[i].key.clone();
        key.push(o);
        if let Some(c) = self.memo.get(&key) {
            return c.clone();
        }
        let lib = self.matcher.library();
        let slot = &self.slots[i];
        let c = &slot.options[o];
        let mut out = Vec::new();
        if key.len() / 2 < MAX_NESTING {
            let rings = face_polygons(&c.instance, &slot.block, &c.warp);
            let (part, block_key) = (slot.part, key.clone());
            for (fi, ring) in rings.into_iter().enumerate() {
                if lib[c.template].faces[c.instance.face_of[fi]].fill != Fill::Area {
                    continue;
                }
                let block = Block::new(ring, self.index, self.merge);
                let options = self.matcher.acceptable(&block, "area");
                let options = order(options, lib, self.selection, self.rng);
                let potential = potential(&options, lib);
                let mut k = block_key.clone();
                k.push(fi);
                out.push(Slot { part, key: k, block, options, potential });
            }
        }
        self.memo.insert(key, out.clone());
        out
    }

    /// The choice tree of slot `i` as the search left it.
    fn build(&self, i: usize) -> Option<Choice> {
        let o = self.choice[i]?;
        let slot = &self.slots[i];
        let mut key = slot.key.clone();
        key.push(o);
        let areas = (0..self.slots.len())
            .filter(|&j| self.slots[j].key.len() == key.len() + 1 && self.slots[j].key.starts_with(&key))
            .map(|j| (self.slots[j].key[key.len()], self.build(j).map(Box::new)))
            .collect();
        Some(Choice { block: slot.block.clone(), candidate: slot.options[o].clone(), areas })
    }
}

/// The ring of an area face of a choice (for the row parceller when no area template fills it).
pub fn area_ring(c: &Choice, face: usize) -> Vec<P> {
    face_polygons(&c.candidate.instance, &c.block, &c.candidate.warp).swap_remove(face)
}

/// The parcels and template streets of a choice: its template's faces, each area face filled by
/// its area template's parcels or, where none was chosen, by the row parceller.
pub fn choice_parcels(
    ch: &Choice,
    lib: &[Template],
    ctx: &super::select::PlaceContext,
    index: &StreetIndex,
    part: &str,
) -> (Vec<crate::layout::Parcel>, Vec<crate::layout::Street>) {
    let t = &lib[ch.candidate.template];
    let (mut parcels, mut streets) = super::select::template_parcels(&ch.block, &ch.candidate, t, ctx, index, part);
    let inst = &ch.candidate.instance;
    for fi in (0..inst.faces.len()).filter(|&fi| t.faces[inst.face_of[fi]].fill == Fill::Area) {
        match ch.areas.iter().find(|(f, _)| *f == fi).and_then(|(_, c)| c.as_deref()) {
            Some(sub) => {
                let (p, s) = choice_parcels(sub, lib, ctx, index, part);
                parcels.extend(p);
                streets.extend(s);
            }
            None => {
                let ring = area_ring(ch, fi);
                let poly = crate::geometry::Shape::new(&ring, &[]);
                let (depth, width) = ctx.parcel;
                parcels.extend(
                    crate::layout::parcels::parcellate(&[poly], index, depth, width)
                        .into_iter()
                        .map(|p| crate::layout::Parcel { part: part.to_string(), ..p }),
                );
            }
        }
    }
    (parcels, streets)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::parcels::StreetIndex;
    use crate::layout::region::{region_from_toml, Region};
    use crate::layout::Street;
    use rand::SeedableRng;
    use std::path::Path;

    /// Three 180 × 60 m blocks between two streets, and a region with `counts` set.
    fn three_blocks(counts: &str) -> (Region, Vec<Block>, StreetIndex) {
        let text = format!("outer = [[0, 0], [700, 0], [700, 75], [0, 75]]\n[templates.counts]\n{counts}");
        let region = region_from_toml(&text, Path::new("t.toml"), "t").unwrap();
        let streets = [
            Street::new(vec![[-10.0, -7.5], [710.0, -7.5]], 15.0, 0),
            Street::new(vec![[-10.0, 67.5], [710.0, 67.5]], 15.0, 0),
        ];
        let index = StreetIndex::new(&streets);
        let blocks = (0..3)
            .map(|k| {
                let x = 230.0 * k as f64;
                Block::new(vec![[x, 0.0], [x + 180.0, 0.0], [x + 180.0, 60.0], [x, 60.0]], &index, 10.0)
            })
            .collect();
        (region, blocks, index)
    }

    fn run(counts: &str) -> Assigned {
        let (region, blocks, index) = three_blocks(counts);
        let mut m = Matcher::new(&region.templates, &region);
        let parts = blocks
            .into_iter()
            .map(|b| {
                let o = m.acceptable(&b, "block");
                Some((b, o))
            })
            .collect();
        let used = BTreeMap::new();
        let ctx = Context { used: &used, index: &index, merge: 10.0 };
        assign(parts, &mut m, &ctx, Selection::Best, &mut Xoshiro256PlusPlus::seed_from_u64(0))
    }

    #[test]
    fn the_best_template_everywhere_without_counts() {
        let a = run("");
        assert_eq!(a.uses.get("double"), Some(&3), "{:?}", a.uses);
        assert!(a.unmet.is_empty());
    }

    #[test]
    fn a_minimum_is_met_by_backtracking_and_an_impossible_one_reported() {
        let a = run("townhouses = { min = 2 }\n");
        assert_eq!((a.uses.get("townhouses"), a.uses.get("double")), (Some(&2), Some(&1)), "{:?}", a.uses);
        assert!(a.unmet.is_empty() && a.steps > 3, "{a:?}");
        // Three parts cannot hold five: as many as they can, and the rest reported.
        let a = run("townhouses = { min = 5 }\n");
        assert_eq!(a.uses.get("townhouses"), Some(&3));
        assert_eq!(a.unmet, vec![Unmet { template: "townhouses".into(), min: 5, used: 3 }]);
    }

    #[test]
    fn a_maximum_passes_the_part_to_the_next_template() {
        let a = run("double = { max = 1 }\n");
        assert_eq!(a.uses.get("double"), Some(&1));
        assert_eq!(a.parts.iter().filter(|p| p.is_some()).count(), 3, "the others take another template");
    }

    #[test]
    fn area_faces_are_filled_by_area_templates() {
        let a = run("mixed = { probability = 1000 }\n");
        assert_eq!(a.uses.get("mixed"), Some(&3), "{:?}", a.uses);
        let ch = a.parts[0].as_ref().unwrap();
        assert_eq!(ch.areas.len(), 1);
        let area = ch.areas[0].1.as_ref().expect("an area template fills the area face");
        assert!(area.candidate.template != ch.candidate.template);
        let areas: usize = a.uses.iter().filter(|(k, _)| k.starts_with("area-")).map(|(_, v)| v).sum();
        assert_eq!(areas, 3);
    }
}
