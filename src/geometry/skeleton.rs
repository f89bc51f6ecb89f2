//! The straight skeleton of a simple polygon (Aichholzer et al. 1995) as its faces: every edge
//! moves inward at unit speed, its ends on the bisectors of its corners, and the face of an edge
//! is the region its moving segment sweeps until the polygon has shrunk to nothing.
//!
//! A wavefront simulation: the polygon's vertices are the active vertices of one loop; the next
//! event is found by trying every pair — an *edge event* when an edge of a loop shrinks to a
//! point (its two ends meet; they are replaced by one vertex), a *split event* when a reflex
//! vertex reaches the segment of a non-adjacent edge of its loop (the loop splits in two) — and
//! processed, then the next is looked for (`O(n³)` for `n` vertices, fine for the tens to
//! hundreds of vertices of a block). Each wavefront segment, from the moment both its ends exist
//! until one of them is replaced, sweeps a quadrilateral (its ends move linearly in between); an
//! edge's face is the union of the quadrilaterals its segments swept. Loops of two vertices (the
//! ridge of a strip between parallel edges) and three (a triangle shrinking to a point) end.
//!
//! No crate in the registry computes straight skeletons in f64 under a licence netspec can use
//! and with upkeep (the candidates are GPL, `i16`-lattice or abandoned); this is the textbook
//! event loop, checked by its faces tiling the polygon (the caller falls back when they do not).

use super::{add, cross, dot, norm, scale, sub, P};
use geo::{Area, BooleanOps};

/// A vertex of the wavefront.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    /// Its position at `born`.
    at: P,
    /// Its velocity.
    v: P,
    /// When it was created.
    born: f64,
    /// The edge arriving at it and the edge leaving it (indices of the polygon's edges).
    left: usize,
    right: usize,
    /// Its neighbours in its loop (indices into the vertex list).
    prev: usize,
    next: usize,
    alive: bool,
    /// When the segment from it to `next` started sweeping.
    since: f64,
}

impl Vertex {
    fn pos(&self, t: f64) -> P {
        add(self.at, scale(self.v, t - self.born))
    }
}

/// The faces of the straight skeleton of a simple counter-clockwise ring (not closed), face `i`
/// that of the edge from vertex `i` to `i + 1`; `None` when the simulation does not finish
/// cleanly (degenerate input), so that the caller can fall back.
pub fn faces(ring: &[P]) -> Option<Vec<geo::MultiPolygon<f64>>> {
    let n = ring.len();
    if n < 3 || super::ring_area2(ring) <= 0.0 {
        return None;
    }
    let normal = |e: usize| -> P {
        let d = sub(ring[(e + 1) % n], ring[e]);
        let l = norm(d);
        [-d[1] / l, d[0] / l]
    };
    let normals: Vec<P> = (0..n).map(normal).collect();
    if normals.iter().any(|p| !p[0].is_finite()) {
        return None;
    }
    let velocity = |a: usize, b: usize| -> P {
        let (na, nb) = (normals[a], normals[b]);
        let den = 1.0 + dot(na, nb);
        if den < 1e-9 {
            [0.0, 0.0]
        } else {
            scale(add(na, nb), 1.0 / den)
        }
    };
    let mut vs: Vec<Vertex> = (0..n)
        .map(|i| {
            let left = (i + n - 1) % n;
            Vertex {
                at: ring[i],
                v: velocity(left, i),
                born: 0.0,
                left,
                right: i,
                prev: (i + n - 1) % n,
                next: (i + 1) % n,
                alive: true,
                since: 0.0,
            }
        })
        .collect();
    let mut quads: Vec<Vec<geo::Polygon<f64>>> = vec![Vec::new(); n];
    let mut now = 0.0;
    // Each event removes at least one vertex or splits a loop; bound the loop.
    for _ in 0..(4 * n * n + 16) {
        if !vs.iter().any(|v| v.alive) {
            return finish(ring, quads);
        }
        close_small_loops(&mut vs, &mut quads, now);
        let Some(ev) = next_event(&vs, &normals, ring, now) else {
            if vs.iter().any(|v| v.alive) {
                return None;
            }
            return finish(ring, quads);
        };
        now = ev.time();
        match ev {
            Event::Edge { a, t } => edge_event(&mut vs, &mut quads, a, t, &velocity),
            Event::Split { v, edge_start, t } => split_event(&mut vs, &mut quads, v, edge_start, t, &velocity),
        }
    }
    None
}

/// The next event.
enum Event {
    /// The segment from `a` to its next vertex shrinks to a point.
    Edge { a: usize, t: f64 },
    /// Reflex vertex `v` reaches the segment from `edge_start` to its next vertex.
    Split { v: usize, edge_start: usize, t: f64 },
}

impl Event {
    fn time(&self) -> f64 {
        match self {
            Event::Edge { t, .. } | Event::Split { t, .. } => *t,
        }
    }
}

const EPS: f64 = 1e-9;

fn next_event(vs: &[Vertex], normals: &[P], ring: &[P], now: f64) -> Option<Event> {
    let mut best: Option<Event> = None;
    let mut consider = |e: Event| {
        if best.as_ref().is_none_or(|b| e.time() < b.time() - EPS) {
            best = Some(e);
        }
    };
    for (a, va) in vs.iter().enumerate().filter(|(_, v)| v.alive) {
        let vb = &vs[va.next];
        // Edge event: the segment's length along its edge reaches zero.
        let d = [normals[va.right][1], -normals[va.right][0]];
        let (pa, pb) = (va.pos(now), vb.pos(now));
        let len = dot(sub(pb, pa), d);
        let rate = dot(sub(vb.v, va.v), d);
        if rate < -EPS {
            let t = now + (len / -rate).max(0.0);
            consider(Event::Edge { a, t });
        }
        // Split event: a reflex vertex (turning right) against every other segment of its loop.
        let turn = cross(
            sub(ring[(va.left + 1) % ring.len()], ring[va.left]),
            sub(ring[(va.right + 1) % ring.len()], ring[va.right]),
        );
        if turn >= 0.0 || va.left == va.right {
            continue;
        }
        let mut s = va.next;
        while s != a && vs[s].next != a {
            let seg = &vs[s];
            let e = seg.right;
            if e != va.left && e != va.right {
                let ne = normals[e];
                // The offset line of edge e at time t: ne · (x − ring[e]) = t.
                let den = 1.0 - dot(ne, va.v);
                if den > EPS {
                    let t = (dot(ne, sub(va.pos(now), ring[e])) - now) / den + now;
                    if t > now - EPS {
                        let p = va.pos(t);
                        let (q0, q1) = (seg.pos(t), vs[seg.next].pos(t));
                        let dir = sub(q1, q0);
                        let l2 = dot(dir, dir);
                        let f = if l2 > 0.0 { dot(sub(p, q0), dir) / l2 } else { -1.0 };
                        if f > 1e-7 && f < 1.0 - 1e-7 {
                            consider(Event::Split { v: a, edge_start: s, t: t.max(now) });
                        }
                    }
                }
            }
            s = seg.next;
        }
    }
    best
}

/// Records the quadrilateral the segment from `a` to its next vertex swept since it started.
fn sweep(vs: &[Vertex], quads: &mut [Vec<geo::Polygon<f64>>], a: usize, t: f64) {
    let (va, vb) = (&vs[a], &vs[vs[a].next]);
    let pts = [va.pos(va.since), vb.pos(va.since), vb.pos(t), va.pos(t)];
    let area2 = super::ring_area2(&pts);
    if area2.abs() > 1e-9 {
        let mut ring: Vec<(f64, f64)> = pts.iter().map(|p| (p[0], p[1])).collect();
        if area2 < 0.0 {
            ring.reverse();
        }
        ring.push(ring[0]);
        quads[va.right].push(geo::Polygon::new(geo::LineString::from(ring), vec![]));
    }
}

fn new_vertex(at: P, t: f64, left: usize, right: usize, velocity: &dyn Fn(usize, usize) -> P) -> Vertex {
    Vertex { at, v: velocity(left, right), born: t, left, right, prev: 0, next: 0, alive: true, since: t }
}

fn edge_event(
    vs: &mut Vec<Vertex>,
    quads: &mut [Vec<geo::Polygon<f64>>],
    a: usize,
    t: f64,
    velocity: &dyn Fn(usize, usize) -> P,
) {
    let b = vs[a].next;
    let (p, q) = (vs[a].prev, vs[b].next);
    for s in [p, a, b] {
        sweep(vs, quads, s, t);
    }
    let at = scale(add(vs[a].pos(t), vs[b].pos(t)), 0.5);
    let mut z = new_vertex(at, t, vs[a].left, vs[b].right, velocity);
    (z.prev, z.next) = (p, q);
    vs[a].alive = false;
    vs[b].alive = false;
    let zi = vs.len();
    vs.push(z);
    vs[p].next = zi;
    vs[q].prev = zi;
    vs[p].since = t;
}

fn split_event(
    vs: &mut Vec<Vertex>,
    quads: &mut [Vec<geo::Polygon<f64>>],
    v: usize,
    s: usize,
    t: f64,
    velocity: &dyn Fn(usize, usize) -> P,
) {
    let (vp, vn, y) = (vs[v].prev, vs[v].next, vs[s].next);
    let e = vs[s].right;
    for k in [vp, v, s] {
        sweep(vs, quads, k, t);
    }
    let at = vs[v].pos(t);
    // One loop: s → z2 → vn …; the other: vp → z1 → y ….
    let mut z2 = new_vertex(at, t, e, vs[v].right, velocity);
    let mut z1 = new_vertex(at, t, vs[v].left, e, velocity);
    let (i2, i1) = (vs.len(), vs.len() + 1);
    (z2.prev, z2.next) = (s, vn);
    (z1.prev, z1.next) = (vp, y);
    vs[v].alive = false;
    vs.push(z2);
    vs.push(z1);
    vs[s].next = i2;
    vs[s].since = t;
    vs[vn].prev = i2;
    vs[vp].next = i1;
    vs[vp].since = t;
    vs[y].prev = i1;
}

/// Loops that have shrunk to nothing end: loops of two vertices (a ridge between parallel edges),
/// and loops of any length whose area is zero (every vertex met, or the loop collapsed onto its
/// ridges at once, as a strip of constant width does); their segments' last sweeps are recorded
/// and their vertices die.
fn close_small_loops(vs: &mut [Vertex], quads: &mut [Vec<geo::Polygon<f64>>], now: f64) {
    for a in 0..vs.len() {
        if !vs[a].alive {
            continue;
        }
        let b = vs[a].next;
        let two = vs[b].next == a || b == a;
        let members = loop_of(vs, a);
        let collapsed = !two && {
            let pts: Vec<P> = members.iter().map(|&m| vs[m].pos(now)).collect();
            let size: f64 = pts.iter().zip(pts.iter().cycle().skip(1)).map(|(p, q)| norm(sub(*p, *q))).sum();
            super::ring_area2(&pts).abs() <= 1e-9 * size.max(1.0).powi(2)
        };
        if two || collapsed {
            for &m in &members {
                sweep(vs, quads, m, now);
            }
            for &m in &members {
                vs[m].alive = false;
            }
        }
    }
}

/// The vertices of the loop through `a`, in order.
fn loop_of(vs: &[Vertex], a: usize) -> Vec<usize> {
    let mut out = vec![a];
    let mut k = vs[a].next;
    while k != a && out.len() <= vs.len() {
        out.push(k);
        k = vs[k].next;
    }
    out
}

/// The faces as the unions of their quadrilaterals, checked to tile the polygon.
fn finish(ring: &[P], quads: Vec<Vec<geo::Polygon<f64>>>) -> Option<Vec<geo::MultiPolygon<f64>>> {
    let faces: Vec<geo::MultiPolygon<f64>> = quads.iter().map(|q| geo::unary_union(q.iter())).collect();
    let total: f64 = faces.iter().map(|f| f.unsigned_area()).sum();
    let area = super::ring_area2(ring) / 2.0;
    let closed: Vec<(f64, f64)> = ring.iter().chain(ring.first()).map(|p| (p[0], p[1])).collect();
    let poly = geo::Polygon::new(geo::LineString::from(closed), vec![]);
    let union = geo::unary_union(faces.iter().flat_map(|f| f.0.iter()));
    let inside = poly.intersection(&union).unsigned_area();
    ((total - area).abs() <= 1e-4 * area && (inside - area).abs() <= 1e-4 * area).then_some(faces)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn areas(f: &[geo::MultiPolygon<f64>]) -> Vec<f64> {
        f.iter().map(|m| (m.unsigned_area() * 1e6).round() / 1e6).collect()
    }

    #[test]
    fn a_rectangle_has_two_trapezoids_and_two_triangles() {
        let f = faces(&[[0.0, 0.0], [200.0, 0.0], [200.0, 60.0], [0.0, 60.0]]).unwrap();
        // Long sides: trapezoids of (200 + 140) / 2 × 30; short sides: triangles 60 × 30 / 2.
        assert_eq!(areas(&f), vec![5100.0, 900.0, 5100.0, 900.0]);
    }

    #[test]
    fn an_l_shape_splits_at_its_reflex_corner() {
        let ring = [[0.0, 0.0], [100.0, 0.0], [100.0, 40.0], [40.0, 40.0], [40.0, 100.0], [0.0, 100.0]];
        let f = faces(&ring).unwrap();
        let total: f64 = f.iter().map(|m| m.unsigned_area()).sum();
        assert!((total - (100.0 * 40.0 + 40.0 * 60.0)).abs() < 1e-6, "{total}");
        assert!(f.iter().all(|m| m.unsigned_area() > 0.0));
    }

    #[test]
    fn a_concave_polygon_with_a_split_event_tiles() {
        // A wide U: the reflex corners reach across.
        let ring = [
            [0.0, 0.0],
            [300.0, 0.0],
            [300.0, 120.0],
            [200.0, 120.0],
            [200.0, 40.0],
            [100.0, 40.0],
            [100.0, 120.0],
            [0.0, 120.0],
        ];
        let f = faces(&ring).unwrap();
        let total: f64 = f.iter().map(|m| m.unsigned_area()).sum();
        assert!((total - (300.0 * 120.0 - 100.0 * 80.0)).abs() < 1e-6, "{total}");
        // A jagged rotated polygon also finishes or reports failure, never panics.
        let jag: Vec<P> = (0..40)
            .map(|i| {
                let a = i as f64 / 40.0 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 100.0 } else { 70.0 };
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        let _ = faces(&jag);
    }
}
