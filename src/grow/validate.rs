//! An independent check of a grown network, run on what `network.json` holds (node ids, road
//! segments in file order, coordinates rounded to the millimetre) against the context's ground,
//! with geometry of its own rather than the road graph's insertion code:
//!
//! - **References**: every segment's node ids exist, no segment has coincident ends, no two
//!   segments join the same two nodes.
//! - **Planarity**: no two road segments (major, minor, bridge, harbour) cross away from a shared
//!   node, and no node lies within [`ON_SEGMENT`] (0.5 m, the graph's snap) of a road segment
//!   it is not joined to — which also covers touching and nearly meeting segments (two straight
//!   segments that do not cross are closest at an end). A node joined by a segment to one of the
//!   segment's ends meets it there already; it must only not lie on it (within [`OVERLAP`]: the
//!   two segments would overlap). A short segment at a sharp angle puts its far end within 0.5 m
//!   of its neighbour (0.64 m at 37° does on the small river map), which is planar and
//!   connected, so it is not reported. Candidate pairs come from a grid index
//!   ([`SegmentIndex`]), not all pairs.
//! - **Water**: no major or minor road runs over water (bridges and harbours are exempt).
//! - **Forbidden ground**: no road of any class runs over a forbidden area.
//!
//! Water and forbidden ground are decided as the lattice decides them: a point has the class of
//! its nearest lattice vertex, and a vertex is water inside or on a water polygon (even–odd,
//! closed: [`ring_covers`]) or within half a river's width of its centre line (`≤`), forbidden
//! inside or on a forbidden polygon (which wins over water). Roads are only checked at lattice resolution by the generator — a minor
//! road's samples every ≤ ℓ/2 must be land, a major road's lattice edges pass land vertices
//! only — so a legal road may clip the corner of a water vertex's cell between two of its
//! samples, for less than ℓ/2. The check therefore samples each segment every ≤ ℓ/8 and reports
//! a run of consecutive samples on water (or forbidden ground) longer than ℓ/2 ([`tolerance`]):
//! a stretch no road built by the generator's rules can have, while any real crossing of a
//! water body the lattice resolves (at least one vertex wide) is longer.

use super::context::Context;
use super::graph::{Class, SNAP};
use super::step::Sim;
use super::{mm, node_ids};
use crate::geometry::index::SegmentIndex;
use crate::geometry::{closest_on_segment, dist, ring_covers, P};
use serde::Serialize;
use std::collections::{BTreeMap, HashMap};

/// A node closer than this to a road segment that does not end at it lies on it (metres): the
/// road graph's snap tolerance.
pub const ON_SEGMENT: f64 = SNAP;

/// A node closer than this to a segment whose end it is joined to lies on it, the two segments
/// overlapping (metres: the millimetre rounding of the file moves a point by under 1 mm).
pub const OVERLAP: f64 = 0.01;

/// Segments shorter than this have coincident ends (metres: half the millimetre the file is
/// rounded to).
const ZERO_LENGTH: f64 = 5e-4;

/// Sample points per lattice spacing along a segment.
const SAMPLES_PER_SPACING: f64 = 8.0;

/// The longest stretch of a road over water or forbidden ground that is not a violation, for
/// lattice spacing ℓ: ℓ/2, the generator's own sampling step (see the module's doc).
pub fn tolerance(spacing: f64) -> f64 {
    spacing / 2.0
}

/// A road network as `network.json` holds it: node positions by id and the road segments in
/// file order (waterways are not roads and are left out).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Network {
    /// Node positions (metres), indexed by node id.
    pub nodes: Vec<P>,
    /// Road segments, indexed as in `segments`.
    pub segments: Vec<Road>,
}

/// A road segment between two node ids.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Road {
    /// One end's node id.
    pub a: usize,
    /// The other end's node id.
    pub b: usize,
    /// Major, minor, bridge or harbour.
    pub class: Class,
}

impl Network {
    /// What `network.json` holds of `sim`'s roads: the same node ids, segment order and
    /// millimetre rounding (a segment end without an id gets one past the last node).
    pub fn of(sim: &Sim) -> Network {
        let ids = node_ids(sim);
        let g = &sim.graph;
        let nodes = g
            .nodes
            .iter()
            .zip(&ids)
            .filter(|(_, id)| id.is_some())
            .map(|(n, _)| [mm(n.pos[0]), mm(n.pos[1])])
            .collect();
        let missing = g.nodes.len();
        let id = |n: u32| ids[n as usize].unwrap_or(missing);
        let segments = g
            .segs
            .iter()
            .filter(|s| s.class.is_road())
            .map(|s| Road { a: id(s.a), b: id(s.b), class: s.class })
            .collect();
        Network { nodes, segments }
    }
}

/// One way a network breaks its invariants; segments and nodes are indices into
/// `network.json`'s `segments` and node ids, positions metres (to the millimetre).
#[derive(Clone, Debug, PartialEq, Serialize, thiserror::Error)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Violation {
    /// A segment names a node id that `nodes` does not have.
    #[error("segment {segment}: node {node} is not in `nodes`")]
    MissingNode {
        /// The segment.
        segment: usize,
        /// The missing id.
        node: usize,
    },
    /// A segment whose ends coincide (the same node, or the same position).
    #[error("segment {segment} has length zero (nodes {a} and {b})")]
    ZeroLength {
        /// The segment.
        segment: usize,
        /// One end.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// Two segments join the same two nodes.
    #[error("segments {} and {} join the same two nodes", segments[0], segments[1])]
    Duplicate {
        /// The first segment and the repeat.
        segments: [usize; 2],
    },
    /// Two road segments cross where neither has a node.
    #[error("segments {} and {} cross at ({:.1}, {:.1}) without a node", segments[0], segments[1], at[0], at[1])]
    Crossing {
        /// The two segments.
        segments: [usize; 2],
        /// Where they cross.
        at: P,
    },
    /// A node lies on a road segment that does not end at it: within [`ON_SEGMENT`], or within
    /// [`OVERLAP`] when a segment joins it to one of the segment's ends.
    #[error("node {node} lies {distance} m from segment {segment}, which does not end at it")]
    NodeOnSegment {
        /// The node.
        node: usize,
        /// The segment.
        segment: usize,
        /// Their distance (metres).
        distance: f64,
    },
    /// A major or minor road runs over water for more than the [`tolerance`].
    #[error("segment {segment} ({class}) runs {length} m over water around ({:.0}, {:.0})", at[0], at[1])]
    OverWater {
        /// The segment.
        segment: usize,
        /// Its class.
        class: &'static str,
        /// The middle of its longest stretch over water.
        at: P,
        /// That stretch's length (metres, measured between samples: a lower bound).
        length: f64,
    },
    /// A road runs over a forbidden area for more than the [`tolerance`].
    #[error("segment {segment} ({class}) runs {length} m over forbidden ground around ({:.0}, {:.0})", at[0], at[1])]
    OverForbidden {
        /// The segment.
        segment: usize,
        /// Its class.
        class: &'static str,
        /// The middle of its longest stretch over forbidden ground.
        at: P,
        /// That stretch's length (metres, measured between samples: a lower bound).
        length: f64,
    },
}

/// Every violation of `net` on `ctx`'s ground, in a fixed order: references by segment, then
/// crossings, nodes on segments, and water and forbidden ground by segment. Empty when the
/// network is valid.
pub fn validate(net: &Network, ctx: &Context) -> Vec<Violation> {
    let mut out = Vec::new();
    let sound = references(net, &mut out);
    let index = SegmentIndex::new(sound.iter().map(|&s| ends(net, s)).collect(), ctx.spacing.max(1.0));
    crossings(net, &sound, &index, &mut out);
    nodes_on_segments(net, &sound, &index, &mut out);
    let mut ground = Ground::new(ctx);
    for &s in &sound {
        ground_of(net, s, &mut ground, &mut out);
    }
    out
}

fn ends(net: &Network, s: usize) -> (P, P) {
    let r = net.segments[s];
    (net.nodes[r.a], net.nodes[r.b])
}

/// Checks node ids, lengths and repeats; returns the segments fit for the geometric checks
/// (both ends known, not of length zero, not a repeat), ascending.
fn references(net: &Network, out: &mut Vec<Violation>) -> Vec<usize> {
    let mut sound = Vec::with_capacity(net.segments.len());
    let mut first: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for (s, r) in net.segments.iter().enumerate() {
        let missing: Vec<usize> = [r.a, r.b].into_iter().filter(|&n| n >= net.nodes.len()).collect();
        if !missing.is_empty() {
            out.extend(missing.into_iter().map(|node| Violation::MissingNode { segment: s, node }));
            continue;
        }
        if r.a == r.b || dist(net.nodes[r.a], net.nodes[r.b]) < ZERO_LENGTH {
            out.push(Violation::ZeroLength { segment: s, a: r.a, b: r.b });
            continue;
        }
        match first.entry((r.a.min(r.b), r.a.max(r.b))) {
            std::collections::btree_map::Entry::Occupied(e) => {
                out.push(Violation::Duplicate { segments: [*e.get(), s] });
            }
            std::collections::btree_map::Entry::Vacant(e) => {
                e.insert(s);
                sound.push(s);
            }
        }
    }
    sound
}

// Deliberately not `crate::geometry`'s orientation and crossing: this checker keeps its own.
/// `(b − a) × (c − a)`: positive when `c` is left of `a → b`.
fn orient(a: P, b: P, c: P) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Where `ab` and `cd` cross properly (each one's ends strictly on both sides of the other), if
/// they do. Touching and collinear overlaps are left to the node-on-segment check.
fn proper_crossing(a: P, b: P, c: P, d: P) -> Option<P> {
    let (d1, d2) = (orient(c, d, a), orient(c, d, b));
    let (d3, d4) = (orient(a, b, c), orient(a, b, d));
    if (d1 > 0.0 && d2 < 0.0 || d1 < 0.0 && d2 > 0.0) && (d3 > 0.0 && d4 < 0.0 || d3 < 0.0 && d4 > 0.0) {
        let t = d1 / (d1 - d2);
        return Some([a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t]);
    }
    None
}

/// The distance from `p` to segment `ab`.
fn distance_to_segment(p: P, a: P, b: P) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 { (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0) } else { 0.0 };
    dist(p, [a[0] + dx * t, a[1] + dy * t])
}

fn round(p: P) -> P {
    [mm(p[0]), mm(p[1])]
}

/// Proper crossings between sound segments with no node in common (each pair once).
fn crossings(net: &Network, sound: &[usize], index: &SegmentIndex, out: &mut Vec<Violation>) {
    for (k, &s) in sound.iter().enumerate() {
        let (a, b) = ends(net, s);
        let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let r = net.segments[s];
        for j in index.near(mid, dist(a, b) / 2.0) {
            if j <= k {
                continue;
            }
            let t = sound[j];
            let q = net.segments[t];
            if [q.a, q.b].iter().any(|&n| n == r.a || n == r.b) {
                continue;
            }
            let (c, d) = ends(net, t);
            if let Some(x) = proper_crossing(a, b, c, d) {
                out.push(Violation::Crossing { segments: [s, t], at: round(x) });
            }
        }
    }
}

/// Nodes of road segments on a sound segment that does not end at them: within [`ON_SEGMENT`],
/// or [`OVERLAP`] for a node joined to one of its ends.
fn nodes_on_segments(net: &Network, sound: &[usize], index: &SegmentIndex, out: &mut Vec<Violation>) {
    let mut joined: Vec<Vec<usize>> = vec![Vec::new(); net.nodes.len()];
    for &s in sound {
        let r = net.segments[s];
        joined[r.a].push(r.b);
        joined[r.b].push(r.a);
    }
    for (n, &p) in net.nodes.iter().enumerate().filter(|&(n, _)| !joined[n].is_empty()) {
        for j in index.near(p, ON_SEGMENT) {
            let s = sound[j];
            let r = net.segments[s];
            if r.a == n || r.b == n {
                continue;
            }
            let limit = if joined[n].iter().any(|&m| m == r.a || m == r.b) { OVERLAP } else { ON_SEGMENT };
            let (a, b) = ends(net, s);
            let d = distance_to_segment(p, a, b);
            if d < limit {
                out.push(Violation::NodeOnSegment { node: n, segment: s, distance: mm(d) });
            }
        }
    }
}

/// What the lattice makes of a vertex.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cover {
    Land,
    Water,
    Forbidden,
}

/// The context's water and forbidden areas at the lattice vertices, computed when first asked.
struct Ground<'a> {
    spacing: f64,
    nx: usize,
    ny: usize,
    ctx: &'a Context,
    seen: HashMap<usize, Cover>,
}

impl<'a> Ground<'a> {
    fn new(ctx: &'a Context) -> Ground<'a> {
        let [nx, ny] = ctx.dims();
        Ground { spacing: ctx.spacing, nx, ny, ctx, seen: HashMap::new() }
    }

    /// The cover of the lattice vertex nearest to `p` (clamped to the lattice).
    fn at(&mut self, p: P) -> Cover {
        let near = |v: f64, n: usize| ((v / self.spacing).round().max(0.0) as usize).min(n - 1);
        let (x, y) = (near(p[0], self.nx), near(p[1], self.ny));
        let key = y * self.nx + x;
        if let Some(&c) = self.seen.get(&key) {
            return c;
        }
        let c = self.classify([x as f64 * self.spacing, y as f64 * self.spacing]);
        self.seen.insert(key, c);
        c
    }

    /// A vertex's cover by the context's definitions (docs/grow.md).
    fn classify(&self, v: P) -> Cover {
        if self.ctx.forbidden.iter().any(|f| ring_covers(&f.polygon, v)) {
            return Cover::Forbidden;
        }
        let wet = self.ctx.water.iter().any(|w| match (&w.polygon, &w.river, w.width) {
            (Some(ring), _, _) => ring_covers(ring, v),
            (None, Some(line), Some(width)) => {
                line.windows(2).any(|s| dist(v, closest_on_segment(v, s[0], s[1]).0) <= width / 2.0)
            }
            _ => false,
        });
        if wet {
            Cover::Water
        } else {
            Cover::Land
        }
    }

    /// The longest run of samples (every ≤ ℓ/8, ends included) of `ab` on each of water and
    /// forbidden ground: `(length, middle)`, length measured between the run's first and last
    /// samples.
    fn runs(&mut self, a: P, b: P) -> [Option<(f64, P)>; 2] {
        let len = dist(a, b);
        let n = (len / (self.spacing / SAMPLES_PER_SPACING)).ceil().max(1.0) as usize;
        let at = |i: usize| {
            let f = i as f64 / n as f64;
            [a[0] + (b[0] - a[0]) * f, a[1] + (b[1] - a[1]) * f]
        };
        let mut best: [Option<(f64, P)>; 2] = [None, None];
        let mut run: Option<(Cover, usize)> = None;
        for i in 0..=n + 1 {
            let cover = if i <= n { self.at(at(i)) } else { Cover::Land };
            if let Some((c, start)) = run {
                if c != cover {
                    let length = (i - 1 - start) as f64 * len / n as f64;
                    let slot = &mut best[(c == Cover::Forbidden) as usize];
                    if slot.is_none_or(|(l, _)| length > l) {
                        let (p, q) = (at(start), at(i - 1));
                        *slot = Some((length, [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0]));
                    }
                    run = None;
                }
            }
            if run.is_none() && cover != Cover::Land {
                run = Some((cover, i));
            }
        }
        best
    }
}

/// Water (major and minor roads) and forbidden ground (every road) under segment `s`.
fn ground_of(net: &Network, s: usize, ground: &mut Ground, out: &mut Vec<Violation>) {
    let (a, b) = ends(net, s);
    let class = net.segments[s].class;
    let limit = tolerance(ground.spacing);
    let [water, forbidden] = ground.runs(a, b);
    if let Some((length, at)) = water.filter(|&(l, _)| l > limit) {
        if matches!(class, Class::Major | Class::Minor) {
            out.push(Violation::OverWater { segment: s, class: class.name(), at: round(at), length: mm(length) });
        }
    }
    if let Some((length, at)) = forbidden.filter(|&(l, _)| l > limit) {
        out.push(Violation::OverForbidden { segment: s, class: class.name(), at: round(at), length: mm(length) });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ctx(extra: &str) -> Context {
        Context::from_toml(&format!("size = [400, 400]\n{extra}")).unwrap()
    }

    fn net(nodes: &[P], segments: &[(usize, usize, Class)]) -> Network {
        Network {
            nodes: nodes.to_vec(),
            segments: segments.iter().map(|&(a, b, class)| Road { a, b, class }).collect(),
        }
    }

    /// A river 60 m wide along y = 200, as a polygon.
    const RIVER_POLYGON: &str = "[[water]]\npolygon = [[0, 170], [400, 170], [400, 230], [0, 230]]";
    /// The same river as a centre line.
    const RIVER_LINE: &str = "[[water]]\nriver = [[0, 200], [400, 200]]\nwidth = 60";

    #[test]
    fn crossing_segments_are_found_and_split_ones_pass() {
        let c = ctx("");
        let crossed = net(
            &[[0.0, 100.0], [200.0, 100.0], [100.0, 0.0], [100.0, 200.0]],
            &[(0, 1, Class::Minor), (2, 3, Class::Major)],
        );
        assert_eq!(validate(&crossed, &c), vec![Violation::Crossing { segments: [0, 1], at: [100.0, 100.0] }]);
        let split = net(
            &[[0.0, 100.0], [200.0, 100.0], [100.0, 0.0], [100.0, 200.0], [100.0, 100.0]],
            &[(0, 4, Class::Minor), (4, 1, Class::Minor), (2, 4, Class::Major), (4, 3, Class::Major)],
        );
        assert_eq!(validate(&split, &c), vec![]);
    }

    #[test]
    fn a_node_on_a_segment_it_does_not_end_is_found() {
        // A T whose stem ends 0.2 m from the bar, which was not split there.
        let t = net(
            &[[0.0, 100.0], [200.0, 100.0], [100.0, 100.2], [100.0, 300.0]],
            &[(0, 1, Class::Minor), (2, 3, Class::Minor)],
        );
        assert_eq!(validate(&t, &ctx("")), vec![Violation::NodeOnSegment { node: 2, segment: 0, distance: 0.2 }]);
        // A short segment at a sharp angle comes within 0.5 m of its neighbour: planar, joined.
        let sharp = net(
            &[[0.0, 0.0], [20.0, 0.0], [0.51, 0.385], [0.51, 20.0]],
            &[(0, 1, Class::Minor), (0, 2, Class::Minor), (2, 3, Class::Minor)],
        );
        assert_eq!(validate(&sharp, &ctx("")), vec![]);
        // An overlap along a shared node: the shorter one's far end lies on the longer one.
        let overlap =
            net(&[[0.0, 100.0], [200.0, 100.0], [50.0, 100.0]], &[(0, 1, Class::Major), (0, 2, Class::Minor)]);
        assert_eq!(validate(&overlap, &ctx("")), vec![Violation::NodeOnSegment { node: 2, segment: 0, distance: 0.0 }]);
    }

    #[test]
    fn roads_across_a_river_are_found_bridges_pass() {
        let across = |class| net(&[[100.0, 100.0], [100.0, 300.0]], &[(0, 1, class)]);
        for water in [RIVER_POLYGON, RIVER_LINE] {
            let c = ctx(water);
            for class in [Class::Minor, Class::Major] {
                let v = validate(&across(class), &c);
                assert!(
                    matches!(v[..], [Violation::OverWater { segment: 0, length, .. }] if length >= 50.0),
                    "{class:?} over {water}: {v:?}"
                );
            }
            assert_eq!(validate(&across(Class::Bridge), &c), vec![]);
            assert_eq!(validate(&across(Class::Harbour), &c), vec![]);
            // Along the bank, on land.
            assert_eq!(validate(&net(&[[0.0, 260.0], [400.0, 260.0]], &[(0, 1, Class::Minor)]), &c), vec![]);
        }
    }

    #[test]
    fn clipping_a_water_cell_is_tolerated_up_to_half_the_spacing() {
        // One water vertex, (200, 200); its lattice cell is [190, 210]².
        let c = ctx("[[water]]\npolygon = [[195, 195], [205, 195], [205, 205], [195, 205]]");
        // x + y = 415 cuts 7.1 m off the cell's corner; x + y = 405 cuts 21.2 m.
        let clip = net(&[[100.0, 315.0], [315.0, 100.0]], &[(0, 1, Class::Minor)]);
        assert_eq!(validate(&clip, &c), vec![]);
        let cut = net(&[[95.0, 310.0], [310.0, 95.0]], &[(0, 1, Class::Minor)]);
        assert!(matches!(validate(&cut, &c)[..], [Violation::OverWater { .. }]), "{:?}", validate(&cut, &c));
    }

    #[test]
    fn forbidden_ground_is_found_for_every_class() {
        let c = ctx("[[forbidden]]\npolygon = [[150, 150], [250, 150], [250, 250], [150, 250]]");
        let bridge = net(&[[100.0, 200.0], [300.0, 200.0]], &[(0, 1, Class::Bridge)]);
        assert!(matches!(validate(&bridge, &c)[..], [Violation::OverForbidden { class: "bridge", .. }]));
    }

    #[test]
    fn broken_references_are_found() {
        let n = net(
            &[[0.0, 0.0], [100.0, 0.0], [100.0, 0.0]],
            &[(0, 7, Class::Minor), (0, 1, Class::Minor), (1, 0, Class::Major), (1, 2, Class::Minor)],
        );
        assert_eq!(
            validate(&n, &ctx("")),
            vec![
                Violation::MissingNode { segment: 0, node: 7 },
                Violation::Duplicate { segments: [1, 2] },
                Violation::ZeroLength { segment: 3, a: 1, b: 2 },
            ]
        );
        let text = Violation::MissingNode { segment: 0, node: 7 }.to_string();
        assert_eq!(text, "segment 0: node 7 is not in `nodes`");
        let json = serde_json::to_string(&Violation::Duplicate { segments: [1, 2] }).unwrap();
        assert_eq!(json, r#"{"kind":"duplicate","segments":[1,2]}"#);
    }
}
