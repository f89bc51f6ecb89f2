//! The independent validator: plain geometry on the placed polygons, never the model that
//! produced them. A layout is valid when no two blocks overlap (intersection area above
//! [`AREA_TOL`]) and every graph edge is a wall the two blocks share over at least the door
//! width, and no block overlaps an obstacle.

use super::spec::{EdgeId, Level, NodeId};
use super::Layout;
use crate::geometry::convex::{self, length, AREA_TOL, LEN_TOL};
use crate::geometry::{self, dot, scale, sub, P};
use serde::Serialize;

/// The validator's findings on one layout.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Validation {
    /// Pairs of nodes whose blocks overlap, with the area.
    pub overlaps: Vec<(String, String, f64)>,
    /// Nodes whose blocks overlap an obstacle: node, obstacle index, area.
    pub obstacle_overlaps: Vec<(String, usize, f64)>,
    /// Graph edges whose blocks share no wall a door wide, with the longest shared wall.
    pub missing_doors: Vec<(String, String, f64)>,
    /// The door of every graph edge: the shared wall's two ends (empty where there is none).
    #[serde(skip)]
    pub walls: Vec<Option<[P; 2]>>,
}

impl Validation {
    /// Whether the layout passes.
    pub fn is_valid(&self) -> bool {
        self.overlaps.is_empty() && self.missing_doors.is_empty() && self.obstacle_overlaps.is_empty()
    }

    /// One line per finding.
    pub fn problems(&self) -> Vec<String> {
        let o = self.overlaps.iter().map(|(a, b, x)| format!("{a} and {b} overlap (area {x:.3e})"));
        let m = self.missing_doors.iter().map(|(a, b, x)| format!("{a}–{b}: longest shared wall {x:.6}"));
        let q = self.obstacle_overlaps.iter().map(|(a, k, x)| format!("{a} overlaps obstacle[{k}] (area {x:.3e})"));
        o.chain(m).chain(q).collect()
    }
}

/// The longest wall piece two placed polygons share, as its two ends.
pub fn shared_wall(p: &[P], q: &[P]) -> Option<[P; 2]> {
    let mut best: Option<([P; 2], f64)> = None;
    for i in 0..p.len() {
        let (a0, a1) = (p[i], p[(i + 1) % p.len()]);
        let la = length(sub(a1, a0));
        let d = scale(sub(a1, a0), 1.0 / la);
        for j in 0..q.len() {
            let (b0, b1) = (q[j], q[(j + 1) % q.len()]);
            // On the same line, running the other way.
            let on_line = |x: P| geometry::cross(d, sub(x, a0)).abs() < LEN_TOL;
            if !(on_line(b0) && on_line(b1)) || dot(d, sub(b1, b0)) >= 0.0 {
                continue;
            }
            let (lo, hi) = (dot(d, sub(b1, a0)).max(0.0), dot(d, sub(b0, a0)).min(la));
            if hi - lo > best.map_or(0.0, |b| b.1) {
                best = Some(([geometry::add(a0, scale(d, lo)), geometry::add(a0, scale(d, hi))], hi - lo));
            }
        }
    }
    best.map(|b| b.0)
}

/// The pairs `(i, j)`, `i < j`, whose bounding boxes overlap with positive area (others
/// cannot overlap): a sweep over the boxes sorted by their left edge, in ascending pair order.
fn box_pairs(polys: &[Vec<P>]) -> Vec<(usize, usize)> {
    let boxes: Vec<[f64; 4]> = polys.iter().map(|p| convex::bounding_box(p)).collect();
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| boxes[a][0].total_cmp(&boxes[b][0]).then(a.cmp(&b)));
    let mut pairs = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if boxes[j][0] >= boxes[i][1] {
                break;
            }
            if boxes[j][2] < boxes[i][3] && boxes[i][2] < boxes[j][3] {
                pairs.push((i.min(j), i.max(j)));
            }
        }
    }
    pairs.sort_unstable();
    pairs
}

/// Checks a layout of `level` (every node placed).
pub fn validate(level: &Level, layout: &Layout) -> Validation {
    let placed: Vec<Vec<P>> =
        layout.nodes.iter().map(|n| convex::translate(&level.blocks[n.block.0 as usize].polygon, n.position)).collect();
    let tris: Vec<Vec<[P; 3]>> = placed.iter().map(|p| convex::triangulate(p)).collect();
    let mut v = Validation::default();
    for (i, j) in box_pairs(&placed) {
        {
            let area = convex::overlap_area(&tris[i], &tris[j]);
            if area > AREA_TOL {
                v.overlaps.push((
                    level.node_name(NodeId(i as u32)).into(),
                    level.node_name(NodeId(j as u32)).into(),
                    area,
                ));
            }
        }
    }
    for (k, o) in level.obstacles.iter().enumerate() {
        let tri = convex::triangulate(&o.polygon);
        for (i, t) in tris.iter().enumerate() {
            let area = convex::overlap_area(t, &tri);
            if area > AREA_TOL {
                v.obstacle_overlaps.push((level.node_name(NodeId(i as u32)).into(), k, area));
            }
        }
    }
    for e in level.all_edges() {
        let (a, b) = level.edges[e.0 as usize];
        let wall = shared_wall(&placed[a.0 as usize], &placed[b.0 as usize]);
        let len = wall.map_or(0.0, |w| length(sub(w[1], w[0])));
        if len < level.door_width - LEN_TOL {
            v.missing_doors.push((level.node_name(a).into(), level.node_name(b).into(), len));
        }
        v.walls.push(wall);
    }
    v
}

/// The door of edge `e`: a door-wide piece centred on the shared wall.
pub fn door(level: &Level, v: &Validation, e: EdgeId) -> Option<[P; 2]> {
    let w = v.walls.get(e.0 as usize).copied().flatten()?;
    let len = length(sub(w[1], w[0]));
    if len < LEN_TOL {
        return None;
    }
    let d = scale(sub(w[1], w[0]), 1.0 / len);
    let mid = scale(geometry::add(w[0], w[1]), 0.5);
    let half = level.door_width.min(len) / 2.0;
    Some([sub(mid, scale(d, half)), geometry::add(mid, scale(d, half))])
}
