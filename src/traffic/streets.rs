//! Networks given as street centrelines in metres (a `netspec layout` output): the polylines are
//! split where one street ends on another or two cross, so that junctions are nodes, and their
//! levels mapped to the hierarchy SUMO is given.

use super::network::{Provenance, Region, RoadEdge, RoadNetwork, RoadNode};
use super::{read, TrafficError, TrafficErrorKind};
use crate::geometry::index::SegmentIndex;
use crate::geometry::{closest_on_segment, dist, polyline_length, segment_intersection, P};
use crate::layout::Street;
use serde::Deserialize;
use std::path::Path;

/// Within this distance (metres) a street end lies on another street, and two nodes are one.
const SNAP: f64 = 0.5;

/// The part of `layout.json` a traffic evaluation reads.
#[derive(Deserialize)]
struct LayoutFile {
    name: String,
    outer: Vec<P>,
    streets: Vec<Street>,
    violations: Vec<serde_json::Value>,
}

/// The network of a `netspec layout` output directory (`layout.json`): its streets as a graph
/// (level 0 — major roads and the boundary street — as major roads, the first split as
/// collectors, deeper splits as local streets), entrances where major roads meet the region's
/// boundary, demand drawn in the region's outer ring — the same region a `netspec city` on that
/// site has, so both meet the same trips.
pub fn from_layout(dir: &Path) -> Result<RoadNetwork, TrafficError> {
    let file = dir.join("layout.json");
    let text = read(&file)?;
    let layout: LayoutFile = serde_json::from_str(&text).map_err(|e| {
        TrafficError::new(&file, TrafficErrorKind::Parse { what: "a netspec layout", message: e.to_string() })
    })?;
    if !layout.violations.is_empty() {
        let n = layout.violations.len();
        return Err(TrafficError::new(&file, TrafficErrorKind::Invalid(format!("{n} violations in layout.json"))));
    }
    let lines: Vec<(Vec<P>, u8)> = layout.streets.iter().map(|s| (s.polyline.clone(), level_of(s.level))).collect();
    let (nodes, edges) = graph(&lines, &layout.outer);
    if edges.is_empty() {
        return Err(TrafficError::new(&file, TrafficErrorKind::NoNetwork("the layout has no streets".into())));
    }
    Ok(RoadNetwork {
        name: layout.name,
        source: Provenance {
            kind: "layout".into(),
            path: file.display().to_string(),
            netspec_version: env!("CARGO_PKG_VERSION").into(),
            description: String::new(),
            runs: Vec::new(),
        },
        metres_per_unit: 1.0,
        nodes,
        edges,
        region: Region { boundary: layout.outer.clone(), areas: vec![layout.outer] },
    })
}

/// A layout level as a traffic level (1 major, 2 collector, 3 local).
fn level_of(level: usize) -> u8 {
    (level + 1).min(3) as u8
}

/// The street graph of polylines with levels: nodes at street ends, at points where a street
/// ends on another, and at crossings; an edge per piece between nodes. Nodes of major roads on
/// `outer` are entrances.
pub fn graph(lines: &[(Vec<P>, u8)], outer: &[P]) -> (Vec<RoadNode>, Vec<RoadEdge>) {
    let mut nodes: Vec<RoadNode> = Vec::new();
    let mut edges: Vec<RoadEdge> = Vec::new();
    let lines: Vec<&(Vec<P>, u8)> = lines.iter().filter(|(l, _)| l.len() >= 2 && polyline_length(l) > SNAP).collect();
    let ends = SegmentIndex::new(
        lines.iter().flat_map(|(l, _)| [(l[0], l[0]), (l[l.len() - 1], l[l.len() - 1])]).collect(),
        20.0,
    );
    let mut owner = Vec::new();
    let mut segments = Vec::new();
    for (i, (l, _)) in lines.iter().enumerate() {
        for w in l.windows(2) {
            owner.push(i);
            segments.push((w[0], w[1]));
        }
    }
    let index = Segments { index: SegmentIndex::new(segments, 20.0), owner };
    for (i, (line, level)) in lines.iter().enumerate() {
        let cuts = cut_points(i, line, &index, &ends);
        for piece in split_at(line, &cuts) {
            if polyline_length(&piece) <= SNAP {
                continue;
            }
            let a = node(&mut nodes, piece[0]);
            let b = node(&mut nodes, *piece.last().expect("a piece"));
            if a == b && piece.len() < 3 {
                continue;
            }
            edges.push(RoadEdge { id: edges.len() as u32, a, b, level: *level, shape: piece, local: *level >= 2 });
        }
    }
    let on_outer = |p: P| {
        (0..outer.len()).any(|k| dist(p, closest_on_segment(p, outer[k], outer[(k + 1) % outer.len()]).0) <= SNAP)
    };
    for e in edges.iter().filter(|e| e.level == 1) {
        for n in [e.a, e.b] {
            if on_outer(nodes[n].pos) {
                nodes[n].entrance = true;
            }
        }
    }
    (nodes, edges)
}

/// Every street's segments, with the street each belongs to.
struct Segments {
    index: SegmentIndex,
    owner: Vec<usize>,
}

/// The node at `p`: an existing one within [`SNAP`], else a new one.
fn node(nodes: &mut Vec<RoadNode>, p: P) -> usize {
    if let Some(k) = nodes.iter().position(|n| dist(n.pos, p) <= SNAP) {
        return k;
    }
    nodes.push(RoadNode { id: nodes.len() as u32, pos: p, entrance: false });
    nodes.len() - 1
}

/// Arc lengths along `line` (street `i`) where it must be split: other streets' ends on it and
/// crossings with other streets, sorted, without its own ends.
fn cut_points(i: usize, line: &[P], segments: &Segments, ends: &SegmentIndex) -> Vec<f64> {
    let total = polyline_length(line);
    let mut cuts = Vec::new();
    let mut run = 0.0;
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        for k in ends.near(mid, l / 2.0 + SNAP) {
            let e = ends.segments()[k].0;
            let (q, t) = closest_on_segment(e, w[0], w[1]);
            if dist(q, e) <= SNAP {
                cuts.push(run + t * l);
            }
        }
        for k in segments.index.near(mid, l / 2.0) {
            if segments.owner[k] == i {
                continue;
            }
            let (a, b) = segments.index.segments()[k];
            if let Some((s, _)) = segment_intersection(w[0], w[1], a, b) {
                cuts.push(run + s * l);
            }
        }
        run += l;
    }
    cuts.retain(|&c| c > SNAP && c < total - SNAP);
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= SNAP);
    cuts
}

/// `line` cut at the arc lengths `cuts` (ascending).
fn split_at(line: &[P], cuts: &[f64]) -> Vec<Vec<P>> {
    let mut out = Vec::new();
    let mut piece = vec![line[0]];
    let mut run = 0.0;
    let mut next = cuts.iter().peekable();
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        while let Some(&&c) = next.peek() {
            if c > run + l {
                break;
            }
            let t = if l > 0.0 { (c - run) / l } else { 0.0 };
            let p = [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
            piece.push(p);
            out.push(std::mem::replace(&mut piece, vec![p]));
            next.next();
        }
        if piece.last() != Some(&w[1]) {
            piece.push(w[1]);
        }
        run += l;
    }
    out.push(piece);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A boundary square, a road across it and a street ending on the road: the road splits at
    /// the junction and at the boundary; the road's ends on the boundary are entrances.
    #[test]
    fn junctions_and_crossings_become_nodes() {
        let outer = vec![[0.0, 0.0], [100.0, 0.0], [100.0, 100.0], [0.0, 100.0]];
        let mut ring = outer.clone();
        ring.push(outer[0]);
        let lines = vec![
            (ring, 1u8),
            (vec![[0.0, 50.0], [100.0, 50.0]], 1),
            (vec![[40.0, 50.0], [40.0, 100.0]], 2),
            (vec![[70.0, 20.0], [70.0, 80.0]], 3),
        ];
        let (nodes, edges) = graph(&lines, &outer);
        // The ring: cut at the road's ends and the street's end → 4 pieces; the road: 3 pieces
        // (the street's end, the crossing); the street: 1; the crossing street: 2.
        assert_eq!(edges.len(), 4 + 3 + 1 + 2, "{edges:?}");
        let entrances: Vec<P> = nodes.iter().filter(|n| n.entrance).map(|n| n.pos).collect();
        assert!(entrances.contains(&[0.0, 50.0]) && entrances.contains(&[100.0, 50.0]));
        assert!(nodes.iter().any(|n| n.pos == [70.0, 50.0]), "the crossing is a node");
        let total: f64 = edges.iter().map(|e| e.length()).sum();
        assert!((total - (400.0 + 100.0 + 50.0 + 60.0)).abs() < 1e-9, "{total}");
    }
}
