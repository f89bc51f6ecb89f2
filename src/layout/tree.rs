//! The control loop (Yang et al. 2013 §3): the region is cut along its major roads, then every
//! part is matched against the template library first — a part on which some template is
//! accepted (energy below its threshold, every face within its tolerance) is settled by it — and
//! only a part no template matches is split along a streamline of its own cross field
//! ([`super::split`]). A part no template matches that passes the fit test (narrow and short
//! enough for a block, or too small to cut), or that no streamline cuts, is settled by the
//! fallback parceller.
//!
//! With `[templates] first = false` the loop cuts every part until it passes the fit test and
//! matches the templates on the leaves afterwards (templates after splitting).
//!
//! The loop records a tree of parts: every node with how it was split or settled and its score
//! (a streamline's quality with every candidate's scores, a template's energy); `layout.json`
//! writes it as `parts`, and `--relayout` lays a part of it out again.

use super::parcels::{blocks, StreetIndex};
use super::region::Region;
use super::split::{cut_part, fits_block, initial_parts, street_ends, CandidateScore, Split, SplitError, SplitOptions};
use super::template::arclength::Block;
use super::template::select::{Candidate, Matcher};
use super::Street;
use crate::geometry::{Polygon, Shape, P};
use rand::rngs::Xoshiro256PlusPlus;
use serde::{Deserialize, Serialize};

pub use super::{How, BLOCK};

/// Runs the control loop on a region without templates: every part is cut until it passes the
/// fit test ([`fits_block`](super::split::fits_block)) or no streamline cuts it.
pub fn split(region: &Region, opts: &SplitOptions, rng: &mut Xoshiro256PlusPlus) -> Result<Split, SplitError> {
    split_with_progress(region, opts, rng, &mut |_| {})
}

/// [`split`], telling `progress` the share of the region's area settled so far (0 to 1) after
/// every part.
pub fn split_with_progress(
    region: &Region,
    opts: &SplitOptions,
    rng: &mut Xoshiro256PlusPlus,
    progress: &mut dyn FnMut(f64),
) -> Result<Split, SplitError> {
    let g = grow(region, opts, None, rng, progress)?;
    let parts = g.leaves.iter().map(|l| g.nodes[l.node].polygon.clone()).collect();
    Ok(Split { parts, streets: g.streets, candidates: g.candidates, cuts: g.cuts })
}

/// A node of the tree while it grows.
#[derive(Clone, Debug)]
pub struct Node {
    /// Its id: `0` for the region, `p.k` for the `k`-th child of `p`.
    pub id: String,
    /// The level of the street that made it (0: the region and the parts of its major roads).
    pub level: usize,
    /// The label of the region it is (`block`; a zone's use), which templates must agree with.
    pub label: String,
    /// The part.
    pub polygon: Polygon,
    /// How it was split or settled.
    pub how: How,
    /// A streamline's quality, a template's energy.
    pub score: Option<f64>,
    /// The template that settled it.
    pub template: Option<String>,
    /// The area templates that filled its template's area faces.
    pub nested: Vec<String>,
    /// A streamline node's candidates (each one's scores) and the chosen one's index.
    pub candidates: Vec<CandidateScore>,
    /// The chosen candidate.
    pub chosen: Option<usize>,
    /// Its children, by index.
    pub children: Vec<usize>,
}

impl Node {
    /// A node not yet split or settled.
    pub fn new(id: String, level: usize, label: &str, polygon: Polygon) -> Node {
        Node {
            id,
            level,
            label: label.to_string(),
            polygon,
            how: How::Rows,
            score: None,
            template: None,
            nested: Vec::new(),
            candidates: Vec::new(),
            chosen: None,
            children: Vec::new(),
        }
    }
}

/// A leaf of the tree: its blocks (the part less the streets' areas, largest first), the largest
/// prepared for matching (when it has no holes), and the templates accepted on it.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// The node.
    pub node: usize,
    /// Its blocks.
    pub blocks: Vec<Shape>,
    /// The largest block, when templates may match it.
    pub block: Option<Block>,
    /// The templates accepted on it, lowest energy first.
    pub options: Vec<Candidate>,
}

/// The grown tree, its leaves and the streets of its cuts.
#[derive(Clone, Debug)]
pub struct Grown {
    /// The nodes; 0 is the region.
    pub nodes: Vec<Node>,
    /// The leaves, in the order they were settled.
    pub leaves: Vec<Leaf>,
    /// Level 0 (the boundary street, major roads) and every cut.
    pub streets: Vec<Street>,
    /// Streamline candidates traced.
    pub candidates: usize,
    /// Cuts along streamlines.
    pub cuts: usize,
}

/// Grows the tree of a region. With a matcher every part is matched against its templates
/// before it is cut (templates first); without one, parts are cut until they pass the fit test,
/// and [`match_leaves`] matches the leaves afterwards. `progress` hears the share of the region's area
/// settled.
pub fn grow(
    region: &Region,
    opts: &SplitOptions,
    matcher: Option<&mut Matcher>,
    rng: &mut Xoshiro256PlusPlus,
    progress: &mut dyn FnMut(f64),
) -> Result<Grown, SplitError> {
    let (parts, streets) = initial_parts(region);
    let root = Node::new("0".into(), 0, BLOCK, region.polygon.clone());
    grow_from(region, opts, matcher, root, parts, streets, rng, progress)
}

/// Grows the subtree of one part (`--relayout`): the part (node id, level, label and polygon in
/// `root`) among the `streets` kept around it, the region's zones that lie inside it set apart.
#[allow(clippy::too_many_arguments)]
pub fn grow_part(
    region: &Region,
    opts: &SplitOptions,
    matcher: Option<&mut Matcher>,
    root: Node,
    mut streets: Vec<Street>,
    rng: &mut Xoshiro256PlusPlus,
    progress: &mut dyn FnMut(f64),
) -> Result<Grown, SplitError> {
    let parts = if root.label == BLOCK {
        let zones: Vec<_> =
            region.zones.iter().filter(|z| z.ring.iter().all(|&p| root.polygon.covers(p, 1e-6))).cloned().collect();
        streets.extend(super::zone::streets(&region.polygon, &zones, region.street_width(0)));
        let mut parts: Vec<(Polygon, String)> =
            super::zone::carve(&root.polygon, &zones).into_iter().map(|p| (p, BLOCK.to_string())).collect();
        parts.extend(zones.iter().map(|z| (z.polygon(), z.use_.label().to_string())));
        parts
    } else {
        vec![(root.polygon.clone(), root.label.clone())]
    };
    grow_from(region, opts, matcher, root, parts, streets, rng, progress)
}

/// The loop from a root node, its first parts (the root itself when it is the only one) and the
/// streets so far.
#[allow(clippy::too_many_arguments)]
fn grow_from(
    region: &Region,
    opts: &SplitOptions,
    matcher: Option<&mut Matcher>,
    root: Node,
    parts: Vec<(Polygon, String)>,
    streets: Vec<Street>,
    rng: &mut Xoshiro256PlusPlus,
    progress: &mut dyn FnMut(f64),
) -> Result<Grown, SplitError> {
    let total = root.polygon.area();
    let whole = parts.len() == 1 && parts[0].1 == root.label && parts[0].0 == root.polygon;
    let mut g = Grown { nodes: vec![root], leaves: Vec::new(), streets, candidates: 0, cuts: 0 };
    let mut work: Vec<usize> = Vec::new();
    if !whole {
        g.nodes[0].how = How::Given;
        let level = g.nodes[0].level;
        for (k, (poly, label)) in parts.into_iter().enumerate() {
            let child = g.add_child(0, k, level, &label, poly);
            work.insert(0, child);
        }
    } else {
        work.push(0);
    }
    let mut loop_ = Loop { region, matcher, total, settled: 0.0 };
    let mut ends: Vec<(P, P)> = g.streets.iter().flat_map(|s| street_ends(&s.polyline)).collect();
    while let Some(n) = work.pop() {
        let leaf = loop_.match_part(&g, n);
        let zone = g.nodes[n].label != BLOCK;
        let fits = fits_block(&g.nodes[n].polygon, region, opts);
        if zone
            || leaf.as_ref().is_some_and(|l| !l.options.is_empty())
            || (fits && !refine(&g, n, leaf.as_ref(), region))
        {
            loop_.settle(&mut g, n, leaf, progress);
            continue;
        }
        let (cut, traced) = cut_part(&g.nodes[n].polygon, region, opts, &ends, rng)?;
        g.candidates += traced;
        let Some(cut) = cut else {
            loop_.settle(&mut g, n, leaf, progress);
            continue;
        };
        let level = g.nodes[n].level + 1;
        let id = g.nodes[n].id.clone();
        for line in &cut.lines {
            ends.extend(street_ends(line));
            g.streets.push(Street {
                polyline: line.clone(),
                width: region.street_width(level),
                level,
                part: id.clone(),
            });
        }
        g.cuts += 1;
        let node = &mut g.nodes[n];
        node.how = How::Streamline;
        node.score = Some(cut.quality);
        node.candidates = cut.scores;
        node.chosen = Some(cut.chosen);
        let (a, b) = cut.parts;
        let label = g.nodes[n].label.clone();
        let (ca, cb) = (g.add_child(n, 0, level, &label, a), g.add_child(n, 1, level, &label, b));
        // Right part first on the stack, so the left one is settled first.
        work.push(cb);
        work.push(ca);
    }
    Ok(g)
}

/// The loop's settings and running totals.
struct Loop<'r, 'm, 'l> {
    region: &'r Region,
    matcher: Option<&'m mut Matcher<'l>>,
    total: f64,
    settled: f64,
}

impl Loop<'_, '_, '_> {
    /// With templates first: the part as a leaf, its blocks and the templates accepted on it.
    fn match_part(&mut self, g: &Grown, n: usize) -> Option<Leaf> {
        let m = self.matcher.as_deref_mut()?;
        Some(leaf_of(&g.nodes[n], n, &g.streets, self.region, Some(m)))
    }

    /// Settles node `n` as a leaf (its blocks found later, by [`match_leaves`], when not yet), and
    /// reports progress.
    fn settle(&mut self, g: &mut Grown, n: usize, leaf: Option<Leaf>, progress: &mut dyn FnMut(f64)) {
        let leaf = leaf.unwrap_or(Leaf { node: n, blocks: Vec::new(), block: None, options: Vec::new() });
        g.nodes[n].how = fallback_or_template(&g.nodes[n], &leaf);
        g.leaves.push(leaf);
        self.settled += g.nodes[n].polygon.area();
        progress(self.settled / self.total);
    }
}

/// Parts no template takes are cut further, though they pass the fit test, when they hold at
/// least this many parcels.
pub const REFINE_PARCELS: f64 = 12.0;

/// With templates first: whether a part that passes the fit test but that no template takes is
/// cut once more (the paper splits wherever no template matches): when it holds at least
/// [`REFINE_PARCELS`] parcels and the fallback would leave undesirable parcels in its blocks.
fn refine(g: &Grown, n: usize, leaf: Option<&Leaf>, region: &Region) -> bool {
    let Some(leaf) = leaf else { return false };
    let parcel = region.parcel.depth * region.parcel.width;
    if g.nodes[n].polygon.area() < REFINE_PARCELS * parcel {
        return false;
    }
    let index = StreetIndex::new(&streets_near(&g.nodes[n].polygon, &g.streets));
    leaf.blocks.iter().any(|b| {
        let (parcels, _) =
            super::fallback::parcel_block(b, &index, region.parcel.depth, region.parcel.width, &g.nodes[n].id);
        super::fallback::undesirable(&parcels) > 0
    })
}

impl Grown {
    fn add_child(&mut self, parent: usize, k: usize, level: usize, label: &str, polygon: Polygon) -> usize {
        let id = format!("{}.{k}", self.nodes[parent].id);
        self.nodes.push(Node::new(id, level, label, polygon));
        let i = self.nodes.len() - 1;
        self.nodes[parent].children.push(i);
        i
    }
}

/// Every leaf's blocks and accepted templates on `streets`: all of them when `fresh` (the
/// streets moved), else those not matched yet (templates after splitting).
pub fn match_leaves(g: &mut Grown, streets: &[Street], region: &Region, matcher: &mut Matcher, fresh: bool) {
    for k in 0..g.leaves.len() {
        let n = g.leaves[k].node;
        if fresh || g.leaves[k].blocks.is_empty() {
            g.leaves[k] = leaf_of(&g.nodes[n], n, streets, region, Some(matcher));
        }
        g.nodes[n].how = fallback_or_template(&g.nodes[n], &g.leaves[k]);
    }
}

/// How a leaf is settled before the assignment: by a template when one is accepted, else by its
/// fallback (a zone whole, a block by the row parceller).
pub fn fallback_or_template(node: &Node, leaf: &Leaf) -> How {
    if !leaf.options.is_empty() {
        How::Template
    } else if node.label == BLOCK {
        How::Rows
    } else {
        How::Zone
    }
}

/// A leaf of node `n`: the part's blocks on the streets near it and, with a matcher, the
/// templates of its label accepted on its largest block (when that has no holes; smaller pieces
/// are remnants the fallback takes).
pub fn leaf_of(node: &Node, n: usize, streets: &[Street], region: &Region, matcher: Option<&mut Matcher>) -> Leaf {
    let poly = &node.polygon;
    let near = streets_near(poly, streets);
    let bl = blocks(poly, &near);
    let block = bl.first().filter(|b| !b.has_holes() && b.area() > 0.0).map(|b| {
        let index = StreetIndex::new(&near);
        Block::new(b.ring(), &index, region.parcel.depth / 3.0)
    });
    let options = match (&block, matcher) {
        (Some(b), Some(m)) => m.acceptable(b, &node.label),
        _ => Vec::new(),
    };
    Leaf { node: n, blocks: bl, block, options }
}

/// The streets whose buffers may reach the part (their bounding boxes, grown by half their width
/// and a metre, meet the part's).
pub fn streets_near(poly: &Polygon, streets: &[Street]) -> Vec<Street> {
    let [lo, hi] = poly.bounds();
    streets
        .iter()
        .filter(|s| {
            let m = s.width / 2.0 + 1.0;
            let [slo, shi] = crate::geometry::polygon::bounds(&s.polyline);
            slo[0] - m <= hi[0] && shi[0] + m >= lo[0] && slo[1] - m <= hi[1] && shi[1] + m >= lo[1]
        })
        .cloned()
        .collect()
}

/// The tree as `layout.json` writes it: nested, coordinates rounded to the millimetre.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PartTree {
    /// The part's id.
    pub id: String,
    /// How it was split or settled.
    pub how: How,
    /// The level of the street that made it.
    pub level: usize,
    /// The label of the region it is.
    pub label: String,
    /// The template that settled it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub template: Option<String>,
    /// The area templates that filled its template's area faces.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nested: Vec<String>,
    /// A streamline's quality; a template's energy.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub score: Option<f64>,
    /// A streamline node's candidates with their scores.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub candidates: Vec<CandidateScore>,
    /// The index of the chosen candidate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub chosen: Option<usize>,
    /// The part's outer ring.
    pub outer: Vec<P>,
    /// Its holes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub holes: Vec<Vec<P>>,
    /// Its children.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub children: Vec<PartTree>,
}

impl Grown {
    /// The tree from node `n` down, for `layout.json`.
    pub fn tree(&self, n: usize) -> PartTree {
        let node = &self.nodes[n];
        let r3 = |x: f64| (x * 1000.0).round() / 1000.0;
        let ring = |r: &[P]| r.iter().map(|p| [r3(p[0]), r3(p[1])]).collect::<Vec<P>>();
        let round_score = |s: &CandidateScore| CandidateScore {
            divergence: r3(s.divergence),
            boundary: r3(s.boundary),
            singularities: r3(s.singularities),
            continuity: r3(s.continuity),
            quality: r3(s.quality),
        };
        PartTree {
            id: node.id.clone(),
            how: node.how,
            level: node.level,
            label: node.label.clone(),
            template: node.template.clone(),
            nested: node.nested.clone(),
            score: node.score.map(|s| (s * 1e6).round() / 1e6),
            candidates: node.candidates.iter().map(round_score).collect(),
            chosen: node.chosen,
            outer: ring(node.polygon.outer()),
            holes: node.polygon.holes().iter().map(|h| ring(h)).collect(),
            children: node.children.iter().map(|&c| self.tree(c)).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::field::FieldMethod;
    use crate::layout::region::region_from_toml;
    use crate::layout::split::Selection;
    use rand::SeedableRng;
    use std::path::Path;

    fn strip(first: bool) -> (Region, Grown) {
        // A 75 × 330 m strip with a street along its boundary: one double-loaded block of 60 m.
        let text = format!("outer = [[0, 0], [330, 0], [330, 75], [0, 75]]\n[templates]\nfirst = {first}\n");
        let region = region_from_toml(&text, Path::new("t.toml"), "t").unwrap();
        let opts = SplitOptions::for_region(&region, FieldMethod::Distance, Selection::Best);
        let mut matcher = Matcher::new(&region.templates, &region);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
        let m = region.templates_first.then_some(&mut matcher);
        let g = grow(&region, &opts, m, &mut rng, &mut |_| {}).unwrap();
        (region, g)
    }

    #[test]
    fn templates_first_settle_a_part_a_template_fits_without_cutting_it() {
        let (_, g) = strip(true);
        assert_eq!((g.cuts, g.leaves.len(), g.nodes.len()), (0, 1, 1));
        assert_eq!(g.nodes[0].how, How::Template);
        assert!(!g.leaves[0].options.is_empty());
        let tree = g.tree(0);
        assert_eq!((tree.id.as_str(), tree.how), ("0", How::Template));
    }

    #[test]
    fn templates_after_splitting_cut_a_part_longer_than_a_block() {
        // 330 m is longer than the longest block (14 parcel widths, 252 m): the fit test cuts it.
        let (region, mut g) = strip(false);
        assert!(g.cuts >= 1, "{} cuts", g.cuts);
        assert!(g.leaves.iter().all(|l| l.options.is_empty()), "no template matched during the loop");
        let mut matcher = Matcher::new(&region.templates, &region);
        let streets = g.streets.clone();
        match_leaves(&mut g, &streets, &region, &mut matcher, false);
        let tree = g.tree(0);
        assert_eq!(tree.how, How::Streamline);
        assert_eq!(tree.children.len(), 2);
        assert!(tree.score.is_some() && tree.chosen.is_some_and(|c| c < tree.candidates.len()));
        assert!(g.streets.iter().any(|s| s.part == "0" && s.level == 1), "the cut names its part");
    }

    fn ring(round_holes: bool) -> Grown {
        // Land 75 m wide round a round lake: the streamlines across it end on the lake, and the
        // ones along it close on themselves, so no single streamline cuts it.
        let circle = |r: f64| -> String {
            let pts: Vec<String> = (0..32)
                .map(|k| {
                    let a = k as f64 * std::f64::consts::TAU / 32.0;
                    format!("[{:.3}, {:.3}]", r * a.cos(), r * a.sin())
                })
                .collect();
            format!("[{}]", pts.join(", "))
        };
        let text = format!(
            "outer = {}\nholes = [{}]\n[templates]\nfirst = false\n[fit]\nround_holes = {round_holes}\n",
            circle(165.0),
            circle(90.0)
        );
        let region = region_from_toml(&text, Path::new("t.toml"), "t").unwrap();
        let opts = SplitOptions::for_region(&region, FieldMethod::Distance, Selection::Best);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(0);
        grow(&region, &opts, None, &mut rng, &mut |_| {}).unwrap()
    }

    #[test]
    fn two_streamlines_to_a_hole_cut_the_land_round_it_when_asked() {
        let whole = ring(false);
        assert_eq!((whole.cuts, whole.leaves.len()), (0, 1), "no streamline crosses the ring");
        assert_eq!(whole.nodes[0].polygon.holes().len(), 1);
        let cut = ring(true);
        assert!(cut.cuts >= 1, "{} cuts", cut.cuts);
        let first: Vec<&Street> = cut.streets.iter().filter(|s| s.part == "0").collect();
        assert_eq!(first.len(), 2, "the root is cut by two streets");
        let lake = &whole.nodes[0].polygon.holes()[0];
        let on_lake = |p: P| crate::geometry::Polygon::new(lake.clone(), vec![]).unwrap().boundary_distance(p) < 1e-3;
        assert!(first.iter().all(|s| on_lake(s.polyline[0]) || on_lake(*s.polyline.last().unwrap())));
        assert!(cut.leaves.iter().all(|l| cut.nodes[l.node].polygon.holes().is_empty()));
        let area: f64 = cut.leaves.iter().map(|l| cut.nodes[l.node].polygon.area()).sum();
        assert!((area - whole.nodes[0].polygon.area()).abs() < 1.0, "the leaves tile the ring: {area}");
    }
}
