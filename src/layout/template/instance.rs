//! A template made concrete: its repetition unrolled (N units), scaled to the region's parcel,
//! vertices shared between faces merged, T-junctions inserted into the edges they lie on, and its
//! boundary loop, corners and sides found.

use super::model::{CornerKind, SideKind, Template};
use crate::geometry::{closest_on_segment, cross, dist, dot, sub, P};
use std::collections::BTreeMap;

/// Turns of at least this many degrees are corners (templates and blocks alike).
pub const CORNER_TURN: f64 = 30.0;

/// A concrete template.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    /// Vertex positions (metres, template coordinates).
    pub verts: Vec<P>,
    /// Faces as counter-clockwise loops of vertex indices.
    pub faces: Vec<Vec<usize>>,
    /// For each face, its index among the template's faces.
    pub face_of: Vec<usize>,
    /// The boundary loop (counter-clockwise).
    pub boundary: Vec<usize>,
    /// Corners: (position in `boundary`, kind), in boundary order.
    pub corners: Vec<(usize, CornerKind)>,
    /// Side `i` runs from corner `i` to corner `i + 1`: its kind.
    pub sides: Vec<SideKind>,
    /// Street centrelines as vertex chains.
    pub streets: Vec<Vec<usize>>,
    /// The number of units (1 without repetition).
    pub units: usize,
    /// Its area (m²).
    pub area: f64,
}

/// Why a template cannot be made concrete.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InstanceError {
    /// The faces do not form one polygon without holes.
    #[error("the faces do not form one polygon without holes")]
    NotADisc,
    /// Fewer than three corners.
    #[error("the boundary has fewer than three corners")]
    FewCorners,
}

/// The template with `units` repetitions (ignored without a `repeat`), scaled by `k`.
pub fn instantiate(t: &Template, units: usize, k: f64) -> Result<Instance, InstanceError> {
    let units = if t.repeat.is_some() { units.max(1) } else { 1 };
    let shift = |p: P| -> P {
        let Some(r) = t.repeat else { return p };
        let mut q = p;
        if p[r.axis] >= r.unit[1] - 1e-9 {
            q[r.axis] += (units - 1) as f64 * (r.unit[1] - r.unit[0]);
        }
        q
    };
    // Faces in template coordinates, unrolled.
    let mut polys: Vec<(Vec<P>, usize)> = Vec::new();
    for (i, f) in t.faces.iter().enumerate() {
        let inside = t
            .repeat
            .is_some_and(|r| f.polygon.iter().all(|p| p[r.axis] >= r.unit[0] - 1e-9 && p[r.axis] <= r.unit[1] + 1e-9));
        match t.repeat {
            Some(r) if inside => {
                for u in 0..units {
                    let off = u as f64 * (r.unit[1] - r.unit[0]);
                    let poly = f.polygon.iter().map(|&p| {
                        let mut q = p;
                        q[r.axis] += off;
                        q
                    });
                    polys.push((poly.collect(), i));
                }
            }
            _ => polys.push((f.polygon.iter().map(|&p| shift(p)).collect(), i)),
        }
    }
    let mut ids: BTreeMap<(i64, i64), usize> = BTreeMap::new();
    let mut verts: Vec<P> = Vec::new();
    let mut id = |p: P, verts: &mut Vec<P>| {
        let key = ((p[0] * 1e6).round() as i64, (p[1] * 1e6).round() as i64);
        *ids.entry(key).or_insert_with(|| {
            verts.push([p[0] * k, p[1] * k]);
            verts.len() - 1
        })
    };
    let mut faces: Vec<Vec<usize>> = Vec::new();
    let mut face_of = Vec::new();
    for (poly, i) in &polys {
        let mut loop_: Vec<usize> = poly.iter().map(|&p| id(p, &mut verts)).collect();
        loop_.dedup();
        faces.push(loop_);
        face_of.push(*i);
    }
    let streets: Vec<Vec<usize>> = t
        .streets
        .iter()
        .map(|line| {
            let chain: Vec<usize> = line.iter().map(|&p| id(shift(p), &mut verts)).collect();
            conform(&chain, &verts, false)
        })
        .collect();
    let faces: Vec<Vec<usize>> = faces.iter().map(|f| conform(f, &verts, true)).collect();
    let boundary = boundary_loop(&faces).ok_or(InstanceError::NotADisc)?;
    let corners = corners(t, &verts, &boundary, k, &shift);
    if corners.len() < 3 {
        return Err(InstanceError::FewCorners);
    }
    let sides = sides(t, &verts, &boundary, &corners, k, &shift);
    let ring: Vec<P> = boundary.iter().map(|&v| verts[v]).collect();
    let area = crate::geometry::ring_area2(&ring).abs() / 2.0;
    Ok(Instance { verts, faces, face_of, boundary, corners, sides, streets, units, area })
}

/// The loop (closed when `closed`) with every vertex lying on one of its edges inserted in order.
fn conform(chain: &[usize], verts: &[P], closed: bool) -> Vec<usize> {
    let n = chain.len();
    let edges = if closed { n } else { n - 1 };
    let mut out = Vec::with_capacity(n);
    for i in 0..edges {
        let (a, b) = (chain[i], chain[(i + 1) % n]);
        out.push(a);
        let (pa, pb) = (verts[a], verts[b]);
        let len = dist(pa, pb);
        let mut on: Vec<(f64, usize)> = (0..verts.len())
            .filter(|&v| v != a && v != b)
            .filter_map(|v| {
                let (q, t) = closest_on_segment(verts[v], pa, pb);
                (dist(q, verts[v]) < 1e-6 * len.max(1.0) && t > 1e-9 && t < 1.0 - 1e-9).then_some((t, v))
            })
            .collect();
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        out.extend(on.into_iter().map(|(_, v)| v));
    }
    if !closed {
        out.push(chain[n - 1]);
    }
    out
}

/// The boundary: the directed edges whose reverse no face has, chained into one loop.
fn boundary_loop(faces: &[Vec<usize>]) -> Option<Vec<usize>> {
    let mut directed: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    for f in faces {
        for i in 0..f.len() {
            *directed.entry((f[i], f[(i + 1) % f.len()])).or_default() += 1;
        }
    }
    let mut next: BTreeMap<usize, usize> = BTreeMap::new();
    for (&(a, b), &c) in &directed {
        if c > 1 {
            return None;
        }
        if !directed.contains_key(&(b, a)) && next.insert(a, b).is_some() {
            return None;
        }
    }
    let &start = next.keys().next()?;
    let mut out = vec![start];
    let mut v = next[&start];
    while v != start {
        if out.len() > next.len() {
            return None;
        }
        out.push(v);
        v = *next.get(&v)?;
    }
    (out.len() == next.len()).then_some(out)
}

/// The signed turn (degrees, left positive) at the middle point.
pub fn turn(a: P, b: P, c: P) -> f64 {
    let (d1, d2) = (sub(b, a), sub(c, b));
    cross(d1, d2).atan2(dot(d1, d2)).to_degrees()
}

fn corners(t: &Template, verts: &[P], boundary: &[usize], k: f64, shift: &dyn Fn(P) -> P) -> Vec<(usize, CornerKind)> {
    let n = boundary.len();
    (0..n)
        .filter_map(|i| {
            let p = verts[boundary[i]];
            let over =
                t.corners.iter().find(|(at, _)| dist([shift(*at)[0] * k, shift(*at)[1] * k], p) < 1e-6 * k.max(1.0));
            let kind = match over {
                Some((_, kind)) => *kind,
                None => {
                    let a = turn(verts[boundary[(i + n - 1) % n]], p, verts[boundary[(i + 1) % n]]);
                    if a >= CORNER_TURN {
                        CornerKind::Convex
                    } else if a <= -CORNER_TURN {
                        CornerKind::Concave
                    } else {
                        CornerKind::None
                    }
                }
            };
            (kind != CornerKind::None).then_some((i, kind))
        })
        .collect()
}

fn sides(
    t: &Template,
    verts: &[P],
    boundary: &[usize],
    corners: &[(usize, CornerKind)],
    k: f64,
    shift: &dyn Fn(P) -> P,
) -> Vec<SideKind> {
    let n = boundary.len();
    let mut out = vec![SideKind::Any; corners.len()];
    for (at, kind) in &t.sides {
        let p = shift(*at);
        let p = [p[0] * k, p[1] * k];
        // The boundary edge nearest the point, then the side holding it.
        let edge = (0..n)
            .min_by(|&i, &j| {
                let d = |e: usize| dist(p, closest_on_segment(p, verts[boundary[e]], verts[boundary[(e + 1) % n]]).0);
                d(i).total_cmp(&d(j))
            })
            .unwrap_or(0);
        let side = corners.iter().rposition(|&(c, _)| c <= edge).unwrap_or(corners.len() - 1);
        out[side] = *kind;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::file::parse_template;
    use super::*;

    #[test]
    fn a_repeated_row_is_a_box_with_shared_vertices() {
        let t = parse_template(
            "kind = \"block\"\n[repeat]\naxis = \"x\"\nunit = [0, 18]\n[[side]]\nat = [9, 0]\nkind = \"street\"\n\
             [[face]]\npolygon = [[0, 0], [18, 0], [18, 30], [0, 30]]\nuse = \"residential\"\n",
            "t",
            "t",
        )
        .unwrap();
        let i = instantiate(&t, 5, 1.0).unwrap();
        assert_eq!((i.faces.len(), i.verts.len(), i.boundary.len(), i.corners.len()), (5, 12, 12, 4));
        let street = i.sides.iter().position(|&s| s == SideKind::Street).unwrap();
        // The street side starts at (0, 0).
        assert_eq!(i.verts[i.boundary[i.corners[street].0]], [0.0, 0.0]);
    }

    #[test]
    fn t_junctions_are_inserted() {
        let i = instantiate(&super::super::file::builtin().into_iter().find(|t| t.name == "park").unwrap(), 3, 1.0)
            .unwrap();
        // Every directed interior edge has its reverse: no T-junctions left.
        let edges: Vec<(usize, usize)> =
            i.faces.iter().flat_map(|f| (0..f.len()).map(move |k| (f[k], f[(k + 1) % f.len()]))).collect();
        let boundary = edges.iter().filter(|&&(a, b)| !edges.contains(&(b, a))).count();
        assert_eq!(boundary, i.boundary.len());
    }
}
