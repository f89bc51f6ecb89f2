//! Blocks and the built-up area (§3.4.2, Eq. 1): the faces of the planar road graph, classified
//! by area into built-up blocks and terrain blocks; the built-up area B rasterised on the
//! lattice as FILL(built-up blocks) ∪ NB(outlines of every block) (the shell taken as the union
//! of bounded faces, so dangling roads are not built up); its settlements, the connected pieces
//! of the built-up blocks and the NB of their outlines (the bands NB lays along the outlines of
//! larger, terrain blocks, such as the initial network's major roads, neither make nor join
//! settlements); and which segments are extendible (no built-up block on either side).

use super::graph::Graph;
use super::terrain::Terrain;
use crate::geometry::planar::face_walks;
use crate::geometry::{closest_on_segment, dist, ring_area2, ring_contains, P};

/// A bounded face of the road graph.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Its boundary (counter-clockwise; dangling roads inside appear twice).
    pub ring: Vec<P>,
    /// Its area (m²).
    pub area: f64,
    /// The step its last boundary segment was built in (its age).
    pub born: u32,
    /// A built-up block (not larger than the terrain-block threshold).
    pub built_up: bool,
}

/// A settlement: a connected piece of the built-up area.
#[derive(Clone, Debug, PartialEq)]
pub struct Settlement {
    /// Its centroid (metres).
    pub center: P,
    /// Its area (m²).
    pub area: f64,
}

/// The blocks and built-up area of one state of the graph.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Blocks {
    /// The bounded faces.
    pub faces: Vec<Face>,
    /// Per lattice vertex: inside B.
    pub built: Vec<bool>,
    /// Per segment: extendible (no built-up block on either side).
    pub extendible: Vec<bool>,
    /// Settlements of at least the context's smallest area: connected pieces of the built-up
    /// blocks with the NB of their outlines.
    pub settlements: Vec<Settlement>,
    /// |B| (m²).
    pub built_area: f64,
}

impl Blocks {
    /// Built-up blocks.
    pub fn block_count(&self) -> usize {
        self.faces.iter().filter(|f| f.built_up).count()
    }
}

/// Traces the faces of the road layer; returns the bounded ones and, per segment, the face on
/// each side (`usize::MAX` for an unbounded one).
pub fn faces(graph: &Graph) -> (Vec<Face>, Vec<[usize; 2]>) {
    let ns = graph.segs.len();
    // The road segments, in id order; half-edge 2k runs a→b along road k.
    let roads: Vec<usize> = (0..ns).filter(|&s| graph.segs[s].class.is_road()).collect();
    let edges: Vec<[u32; 2]> = roads.iter().map(|&s| [graph.segs[s].a, graph.segs[s].b]).collect();
    let positions: Vec<P> = graph.nodes.iter().map(|n| n.pos).collect();
    let walks = face_walks(&positions, &edges, |h| h as u32).walks;
    let mut face_of = vec![usize::MAX; 2 * ns];
    let mut out = Vec::new();
    for halves in walks {
        let ring: Vec<P> = halves.iter().map(|&h| positions[edges[h / 2][h % 2] as usize]).collect();
        let area = ring_area2(&ring) / 2.0;
        if area > 1e-6 {
            let id = out.len();
            let born = halves.iter().map(|&h| graph.segs[roads[h / 2]].born).max().unwrap_or(0);
            out.push(Face { ring, area, born, built_up: false });
            for &h in &halves {
                face_of[2 * roads[h / 2] + h % 2] = id;
            }
        }
    }
    let side = (0..ns).map(|s| [face_of[2 * s], face_of[2 * s + 1]]).collect();
    (out, side)
}

/// Blocks, B, extendible segments and settlements.
pub fn compute(graph: &Graph, terrain: &Terrain, block_area: f64, nb: f64, settlement: f64) -> Blocks {
    let (mut faces, side) = faces(graph);
    for f in &mut faces {
        f.built_up = f.area <= block_area;
    }
    let (nx, ny, s) = (terrain.nx, terrain.ny, terrain.spacing);
    let mut built = vec![false; nx * ny];
    // Built-up blocks and their NB only: the raster settlements are counted on.
    let mut clusters = vec![false; nx * ny];
    let range = |lo: f64, hi: f64, n: usize| {
        let a = (lo / s).ceil().max(0.0) as usize;
        let b = ((hi / s).floor() + 1.0).clamp(0.0, n as f64) as usize;
        a.min(b)..b
    };
    for f in faces.iter().filter(|f| f.built_up) {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
        for p in &f.ring {
            (x0, x1, y0, y1) = (x0.min(p[0]), x1.max(p[0]), y0.min(p[1]), y1.max(p[1]));
        }
        for y in range(y0, y1, ny) {
            for x in range(x0, x1, nx) {
                if !built[y * nx + x] && ring_contains(&f.ring, [x as f64 * s, y as f64 * s]) {
                    built[y * nx + x] = true;
                    clusters[y * nx + x] = true;
                }
            }
        }
    }
    let mut extendible = vec![true; graph.segs.len()];
    for (i, sd) in side.iter().enumerate() {
        let bounded = sd.iter().any(|&f| f != usize::MAX);
        extendible[i] = !sd.iter().any(|&f| f != usize::MAX && faces[f].built_up);
        if !bounded || !graph.segs[i].class.is_road() {
            continue;
        }
        let of_block = !extendible[i];
        let (a, b) = graph.ends(i as u32);
        for y in range(a[1].min(b[1]) - nb, a[1].max(b[1]) + nb, ny) {
            for x in range(a[0].min(b[0]) - nb, a[0].max(b[0]) + nb, nx) {
                let v = y * nx + x;
                if built[v] && (clusters[v] || !of_block) {
                    continue;
                }
                let p = [x as f64 * s, y as f64 * s];
                if dist(p, closest_on_segment(p, a, b).0) <= nb {
                    built[v] = true;
                    clusters[v] |= of_block;
                }
            }
        }
    }
    let cell = s * s;
    let built_area = built.iter().filter(|&&b| b).count() as f64 * cell;
    let settlements = components(&clusters, nx, ny, s).into_iter().filter(|c| c.area >= settlement).collect();
    Blocks { faces, built, extendible, settlements, built_area }
}

/// 4-connected components of the raster, in order of their first vertex.
fn components(built: &[bool], nx: usize, ny: usize, s: f64) -> Vec<Settlement> {
    let mut seen = vec![false; built.len()];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..built.len() {
        if !built[start] || seen[start] {
            continue;
        }
        let (mut n, mut sx, mut sy) = (0usize, 0.0, 0.0);
        seen[start] = true;
        stack.push(start);
        while let Some(v) = stack.pop() {
            let (x, y) = (v % nx, v / nx);
            n += 1;
            sx += x as f64 * s;
            sy += y as f64 * s;
            let mut push = |u: usize| {
                if built[u] && !seen[u] {
                    seen[u] = true;
                    stack.push(u);
                }
            };
            if x > 0 {
                push(v - 1);
            }
            if x + 1 < nx {
                push(v + 1);
            }
            if y > 0 {
                push(v - nx);
            }
            if y + 1 < ny {
                push(v + nx);
            }
        }
        out.push(Settlement { center: [sx / n as f64, sy / n as f64], area: n as f64 * s * s });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::graph::Class;
    use super::*;

    #[test]
    fn a_square_with_a_tail_is_one_block() {
        let mut g = Graph::new([200.0, 200.0]);
        let pts = [[40.0, 40.0], [100.0, 40.0], [100.0, 100.0], [40.0, 100.0]];
        let ids: Vec<u32> = pts.iter().map(|&p| g.node_at(p, true)).collect();
        for i in 0..4 {
            g.insert(ids[i], ids[(i + 1) % 4], Class::Minor, 1.0, i as u32);
        }
        let tail = g.node_at([180.0, 40.0], true);
        g.insert(ids[1], tail, Class::Major, 1.0, 7);
        let (f, side) = faces(&g);
        assert_eq!(f.len(), 1);
        assert!((f[0].area - 3600.0).abs() < 1e-6);
        assert_eq!(f[0].born, 3);
        assert_eq!(side[4], [usize::MAX, usize::MAX]);
        let t = Terrain { nx: 11, ny: 11, spacing: 20.0, z: vec![0.0; 121], class: vec![0; 121] };
        let b = compute(&g, &t, 50_000.0, 20.0, 1000.0);
        assert!(b.built[(60 / 20) * 11 + 60 / 20]);
        assert!(!b.built[(160 / 20) * 11 + 160 / 20]);
        assert!(!b.extendible[0] && b.extendible[4]);
        assert_eq!(b.settlements.len(), 1);
    }

    /// Two small blocks inside opposite corners of a large terrain block: the NB band along the
    /// large block's outline joins them in B, but they are two settlements.
    #[test]
    fn settlements_follow_blocks_not_road_bands() {
        let mut g = Graph::new([1100.0, 1100.0]);
        let square = |g: &mut Graph, x0: f64, y0: f64, side: f64, class: Class| {
            let pts = [[x0, y0], [x0 + side, y0], [x0 + side, y0 + side], [x0, y0 + side]];
            let ids: Vec<u32> = pts.iter().map(|&p| g.node_at(p, true)).collect();
            for i in 0..4 {
                g.insert(ids[i], ids[(i + 1) % 4], class, 1.0, 0);
            }
        };
        square(&mut g, 20.0, 20.0, 1000.0, Class::Major);
        square(&mut g, 60.0, 60.0, 60.0, Class::Minor);
        square(&mut g, 900.0, 900.0, 60.0, Class::Minor);
        let n = 56;
        let t = Terrain { nx: n, ny: n, spacing: 20.0, z: vec![0.0; n * n], class: vec![0; n * n] };
        let b = compute(&g, &t, 50_000.0, 20.0, 5000.0);
        assert_eq!(b.block_count(), 2);
        assert_eq!(b.settlements.len(), 2, "{:?}", b.settlements);
        let band = |x: usize, y: usize| b.built[y * n + x];
        assert!(band(2, 20) && band(20, 1), "the terrain block's outline is in B");
    }
}
