//! Hierarchical matching with repetition, per block: for every template, the number of units
//! (parcels per row) and the corner match are tried in order of boundary distortion, the three
//! best warped, the lowest energy kept; a template is acceptable when its energy is below its
//! threshold, every face is within its tolerance, its faces tile the block, and its count
//! (`max_uses`) is not used up. `Selection::Best` takes the lowest energy; `Selection::Random`
//! draws uniformly (seeded) among the acceptable ones within [`SELECT_TOLERANCE`] of the lowest.
//! When a choice fails (its faces fold, or its count is used up) the next is taken; when none is
//! left the block goes to the row parceller.
//!
//! Template streets (the cul-de-sac of a spike) become streets one level below the deepest, at
//! the narrowest street width, extended to the centreline of the street they leave; they are
//! carved out of the template's faces. A residential face without street access is a park, a
//! piece under a quarter of a parcel's area "other", as in the row parceller.

use super::arclength::{matches, Block};
use super::file::{Fill, Template};
use super::instance::{instantiate, Instance};
use super::warp::{face_polygons, simple_ccw, warp, Warp, ROUNDS};
use crate::geometry::polygon::geo_polygon;
use crate::geometry::shape::outer_ring;
use crate::geometry::{closest_on_segment, dist, Shape, P};
use crate::layout::parcels::{parcellate, street_buffer, StreetIndex};
use crate::layout::region::Region;
use crate::layout::split::Selection;
use crate::layout::{Parcel, Street, Use};
use geo::{Area, BooleanOps};
use rand::rngs::Xoshiro256PlusPlus;
use rand::RngExt;
use std::collections::BTreeMap;

/// Candidates within this energy of the best are drawn among in `Selection::Random`.
pub const SELECT_TOLERANCE: f64 = 0.005;
/// Corner matches warped per template (the least distorted).
const WARPED_PER_TEMPLATE: usize = 3;
/// A template is tried on blocks within this factor of its area.
const AREA_SPAN: f64 = 2.0;

/// The parcels of all blocks, the template streets, and how often each template was used.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TemplateParcels {
    /// Parcels in block order (each names its template, or none from the row parceller).
    pub parcels: Vec<Parcel>,
    /// Streets the templates made.
    pub streets: Vec<Street>,
    /// Uses per template name.
    pub uses: BTreeMap<String, usize>,
}

/// A warped candidate for a block.
#[derive(Clone, Debug)]
pub struct Candidate {
    /// The template's index in the library.
    pub template: usize,
    /// The concrete template.
    pub instance: Instance,
    /// The warp.
    pub warp: Warp,
}

/// Concrete templates per (template, units), built once.
pub struct Instances<'a> {
    library: &'a [Template],
    k: f64,
    cache: BTreeMap<(usize, usize), Option<Instance>>,
}

impl<'a> Instances<'a> {
    /// For a library and a region's parcel depth.
    pub fn new(library: &'a [Template], depth: f64) -> Instances<'a> {
        Instances { library, k: depth / 30.0, cache: BTreeMap::new() }
    }

    fn get(&mut self, t: usize, units: usize) -> Option<&Instance> {
        let (lib, k) = (self.library, self.k);
        self.cache.entry((t, units)).or_insert_with(|| instantiate(&lib[t], units, k).ok()).as_ref()
    }
}

/// Every template's best warp onto the block (lowest energy over its least distorted matches),
/// in library order; `rounds` as in [`warp`]. Only templates whose label (`kind`) is `label` and
/// that may be used at all are tried; a repeated one not beyond `max_length` along its axis, and
/// none on a block of more than twice or less than half its area.
pub fn candidates(
    block: &Block,
    instances: &mut Instances,
    rounds: usize,
    max_length: f64,
    label: &str,
) -> Vec<Candidate> {
    let mut out = Vec::new();
    for t in 0..instances.library.len() {
        let tpl = &instances.library[t];
        if tpl.kind != label || tpl.max_uses == Some(0) {
            continue;
        }
        let units = tpl.repeat.map_or(1..=1, |r| r.min..=r.max);
        let mut tried: Vec<(f64, usize, super::arclength::Match)> = Vec::new();
        for u in units {
            let Some(inst) = instances.get(t, u) else { continue };
            if tpl.repeat.is_some_and(|r| extent(inst, r.axis) > max_length) {
                break;
            }
            // A block of more than twice or less than half a template's area is beyond what its
            // faces' tolerances allow.
            if block.area > AREA_SPAN * inst.area || block.area * AREA_SPAN < inst.area {
                continue;
            }
            if let Some(m) = matches(inst, block).into_iter().next() {
                tried.push((m.distortion, u, m));
            }
        }
        tried.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best: Option<Candidate> = None;
        for (_, u, m) in tried.into_iter().take(WARPED_PER_TEMPLATE) {
            let Some(inst) = instances.get(t, u) else { continue };
            let w = warp(tpl, inst, block, &m, rounds);
            if best.as_ref().is_none_or(|b| w.energy < b.warp.energy) {
                best = Some(Candidate { template: t, instance: inst.clone(), warp: w });
            }
        }
        out.extend(best);
    }
    out
}

/// The extent of a concrete template along an axis (metres).
fn extent(inst: &Instance, axis: usize) -> f64 {
    let (lo, hi) =
        inst.verts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[axis]), hi.max(p[axis])));
    hi - lo
}

/// Matches blocks against a library: the templates accepted on a block, and the parcels a chosen
/// one makes.
pub struct Matcher<'a> {
    library: &'a [Template],
    instances: Instances<'a>,
    threshold: f64,
    max_length: f64,
    /// Seconds spent matching so far.
    pub seconds: f64,
}

impl<'a> Matcher<'a> {
    /// For a library and a region's parcel, block size and default threshold.
    pub fn new(library: &'a [Template], region: &Region) -> Matcher<'a> {
        Matcher {
            library,
            instances: Instances::new(library, region.parcel.depth),
            threshold: region.fit.threshold,
            max_length: region.block.max_length,
            seconds: 0.0,
        }
    }

    /// The library.
    pub fn library(&self) -> &'a [Template] {
        self.library
    }

    /// The templates of a label accepted on a block, lowest energy first (ties by library order):
    /// energy below the template's threshold, every face within its tolerance, every face a
    /// simple counter-clockwise polygon (the warp did not fold).
    pub fn acceptable(&mut self, block: &Block, label: &str) -> Vec<Candidate> {
        let t0 = std::time::Instant::now();
        let (lib, threshold) = (self.library, self.threshold);
        let mut out: Vec<Candidate> = candidates(block, &mut self.instances, ROUNDS, self.max_length, label)
            .into_iter()
            .filter(|c| c.warp.energy < lib[c.template].threshold.unwrap_or(threshold) && c.warp.within_tolerance)
            .filter(|c| face_polygons(&c.instance, block, &c.warp).iter().all(|f| simple_ccw(f)))
            .collect();
        out.sort_by(|a, b| a.warp.energy.total_cmp(&b.warp.energy).then(a.template.cmp(&b.template)));
        self.seconds += t0.elapsed().as_secs_f64();
        out
    }
}

/// Parcels every block: templates first, the row parceller where none is accepted (the blocks of
/// another method's streets, parcelled as `netspec layout` parcels a block).
pub fn parcellate_with_templates(
    blocks: &[Shape],
    streets: &[Street],
    region: &Region,
    library: &[Template],
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> TemplateParcels {
    let (depth, width) = (region.parcel.depth, region.parcel.width);
    let index = StreetIndex::new(streets);
    let ctx = PlaceContext::new(streets, region);
    let mut matcher = Matcher::new(library, region);
    let mut out = TemplateParcels::default();
    for b in blocks {
        let mut placed = false;
        if !b.has_holes() {
            let block = Block::new(b.ring(), &index, depth / 3.0);
            let cands = matcher.acceptable(&block, "block");
            if let Some(c) = choose_greedy(cands, library, &out.uses, selection, rng) {
                let (parcels, new_streets) = template_parcels(&block, &c, &library[c.template], &ctx, &index, "");
                out.parcels.extend(parcels);
                out.streets.extend(new_streets);
                *out.uses.entry(library[c.template].name.clone()).or_default() += 1;
                placed = true;
            }
        }
        if !placed {
            out.parcels.extend(parcellate(std::slice::from_ref(b), &index, depth, width));
        }
    }
    out
}

/// The first acceptable candidate whose count is not used up: the lowest energy
/// (`Selection::Best`), or drawn uniformly among those within [`SELECT_TOLERANCE`] of it.
pub fn choose_greedy(
    mut cands: Vec<Candidate>,
    library: &[Template],
    uses: &BTreeMap<String, usize>,
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> Option<Candidate> {
    cands.retain(|c| {
        let t = &library[c.template];
        t.max_uses.is_none_or(|k| uses.get(&t.name).copied().unwrap_or(0) < k)
    });
    if cands.is_empty() {
        return None;
    }
    let pick = match selection {
        Selection::Best => 0,
        Selection::Random => {
            let best = cands[0].warp.energy;
            let near = cands.iter().take_while(|c| c.warp.energy <= best + SELECT_TOLERANCE).count();
            rng.random_range(0..near)
        }
    };
    Some(cands.swap_remove(pick))
}

/// What placing a template needs beyond the block: every street (template streets extend to
/// their centrelines), the level and width template streets get, and the parcel area.
pub struct PlaceContext<'a> {
    /// The layout's streets.
    pub streets: &'a [Street],
    /// The level of template streets: one below the deepest.
    pub level: usize,
    /// Their width: the narrowest street width.
    pub width: f64,
    /// A parcel's area (m²).
    pub parcel_area: f64,
    /// The parcel's depth and width (metres), for the row parceller.
    pub parcel: (f64, f64),
}

impl<'a> PlaceContext<'a> {
    /// For a layout's streets and its region.
    pub fn new(streets: &'a [Street], region: &Region) -> PlaceContext<'a> {
        PlaceContext {
            streets,
            level: streets.iter().map(|s| s.level).max().map_or(0, |l| l + 1),
            width: region.street_widths.iter().copied().fold(f64::INFINITY, f64::min),
            parcel_area: region.parcel.depth * region.parcel.width,
            parcel: (region.parcel.depth, region.parcel.width),
        }
    }
}

/// The parcels and template streets of candidate `c` (of template `t`) on its block, its area
/// faces left out (see [`super::assign::choice_parcels`]); `part` names the part they belong to.
/// Template streets are carved out of the faces; a residential face without street access is a
/// park, a piece under a quarter of a parcel's area "other".
pub fn template_parcels(
    block: &Block,
    c: &Candidate,
    t: &Template,
    ctx: &PlaceContext,
    index: &StreetIndex,
    part: &str,
) -> (Vec<Parcel>, Vec<Street>) {
    let faces = face_polygons(&c.instance, block, &c.warp);
    let new_streets: Vec<Street> = c
        .instance
        .streets
        .iter()
        .map(|chain| Street {
            polyline: extend(chain, c, ctx.streets),
            width: ctx.width,
            level: ctx.level,
            part: part.into(),
        })
        .collect();
    let carve = (!new_streets.is_empty()).then(|| {
        let bufs: Vec<geo::MultiPolygon<f64>> = new_streets.iter().map(street_buffer).collect();
        geo::unary_union(bufs.iter())
    });
    let local = StreetIndex::new(&new_streets);
    let mut out = Vec::new();
    for (fi, ring) in faces.iter().enumerate() {
        let face = &t.faces[c.instance.face_of[fi]];
        let poly = geo_polygon(ring, &[]);
        let pieces = match &carve {
            Some(cut) => poly.difference(cut).0,
            None => vec![poly],
        };
        for piece in pieces {
            let ring = outer_ring(&piece);
            let area = piece.unsigned_area();
            if ring.len() < 3 || area < 1e-3 * ctx.parcel_area {
                continue;
            }
            let use_ = match face.fill {
                Fill::Area => continue,
                _ if area < 0.25 * ctx.parcel_area => Use::Other,
                Fill::Use(Use::Residential) if !(index.fronts(&ring) || local.fronts(&ring)) => Use::Park,
                Fill::Use(u) => u,
            };
            out.push(Parcel {
                template: Some(t.name.clone()),
                part: part.into(),
                registration: Some(c.warp.face_similarity[fi]),
                ideal: Some(ideal_area(&c.instance, fi)),
                ..Parcel::new(ring, use_)
            });
        }
    }
    (out, new_streets)
}

/// The area of a concrete template's face (m²).
pub fn ideal_area(inst: &Instance, face: usize) -> f64 {
    let ring: Vec<P> = inst.faces[face].iter().map(|&v| inst.verts[v]).collect();
    crate::geometry::ring_area2(&ring).abs() / 2.0
}

/// A template street's warped centreline, each end on the block's boundary extended to the
/// nearest point of an existing street's centreline (within that street's half width plus 1 m).
fn extend(chain: &[usize], c: &Candidate, streets: &[Street]) -> Vec<P> {
    let mut line: Vec<P> = chain.iter().map(|&v| c.warp.pos[v]).collect();
    let on_boundary = |v: usize| c.instance.boundary.contains(&v);
    let nearest = |p: P| -> Option<P> {
        streets
            .iter()
            .flat_map(|s| s.polyline.windows(2).map(move |w| (closest_on_segment(p, w[0], w[1]).0, s.width)))
            .filter(|(q, w)| dist(p, *q) <= w / 2.0 + 1.0)
            .min_by(|a, b| dist(p, a.0).total_cmp(&dist(p, b.0)))
            .map(|(q, _)| q)
    };
    if on_boundary(chain[0]) {
        if let Some(q) = nearest(line[0]) {
            line.insert(0, q);
        }
    }
    if chain.len() > 1 && on_boundary(chain[chain.len() - 1]) {
        if let Some(q) = nearest(line[line.len() - 1]) {
            line.push(q);
        }
    }
    line.dedup_by(|a, b| dist(*a, *b) < 1e-6);
    line
}
