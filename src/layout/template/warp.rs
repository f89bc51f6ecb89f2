//! The warp of a concrete template onto a block (Yang et al. 2013 §4.1): boundary vertices by
//! arc-length scaling of each template side onto the matched block side, interior vertices by
//! mean-value coordinates, then rounds of registration (each face fitted within its class) and
//! regression (each vertex the `1/ε`-weighted mean of its faces' images; boundary vertices
//! projected back onto their side, in order; corners fixed).
//!
//! The energy is the mean over faces of the mean distance of a face's vertices from its
//! registered ideal shape, over the square root of the block's area.

use super::arclength::{side_lengths, Block, Match};
use super::file::{Class, Template};
use super::instance::Instance;
use super::mvc::{combine, mean_value_coordinates};
use super::register::{mean_distance, register, rms};
use crate::geometry::{dist, P};

/// Rounds of registration and regression (the paper: about 30).
pub const ROUNDS: usize = 30;
/// Boundary vertices of a side keep at least this gap (metres) along it.
const MIN_GAP: f64 = 0.5;

/// A warped template.
#[derive(Clone, Debug)]
pub struct Warp {
    /// Vertex positions on the block.
    pub pos: Vec<P>,
    /// Arc length on the block's ring of each boundary vertex (by position in the boundary loop).
    pub s: Vec<f64>,
    /// Per face: the mean distance (metres) of its vertices from its registered ideal shape.
    pub face_distance: Vec<f64>,
    /// Per face: the same distance with the ideal registered by a similarity (rotation,
    /// translation, uniform scale): §7's per-parcel similarity distortion.
    pub face_similarity: Vec<f64>,
    /// The mean of `face_distance` (metres).
    pub distance: f64,
    /// `distance / √area`.
    pub energy: f64,
    /// Every face's RMS registration distance is within its tolerance.
    pub within_tolerance: bool,
}

/// Warps `inst` (of `t`) onto `block` by match `m`, with `rounds` rounds (0: arc length and
/// mean-value coordinates only).
pub fn warp(t: &Template, inst: &Instance, block: &Block, m: &Match, rounds: usize) -> Warp {
    let n = inst.boundary.len();
    let k = inst.corners.len();
    let l = block.ring.length();
    let tl = side_lengths(inst);
    // Side of each boundary position, and the arc-length initialisation.
    let mut side_of = vec![0; n];
    let mut s = vec![0.0; n];
    for (i, &len) in tl.iter().enumerate() {
        let (a, b) = (inst.corners[i].0, inst.corners[(i + 1) % k].0);
        let (s0, s1) = (m.s[i], if i + 1 < k { m.s[i + 1] } else { m.s[0] + l });
        let steps = match (b + n - a) % n {
            0 => n,
            x => x,
        };
        let mut acc = 0.0;
        for j in 0..steps {
            let at = (a + j) % n;
            side_of[at] = i;
            s[at] = s0 + (s1 - s0) * acc / len;
            acc += dist(inst.verts[inst.boundary[at]], inst.verts[inst.boundary[(at + 1) % n]]);
        }
    }
    let mut pos = inst.verts.clone();
    let on_boundary: Vec<Option<usize>> = {
        let mut v = vec![None; inst.verts.len()];
        for (i, &b) in inst.boundary.iter().enumerate() {
            v[b] = Some(i);
        }
        v
    };
    for (i, &b) in inst.boundary.iter().enumerate() {
        pos[b] = block.ring.at(s[i]);
    }
    let tpl_boundary: Vec<P> = inst.boundary.iter().map(|&b| inst.verts[b]).collect();
    let warped_boundary: Vec<P> = inst.boundary.iter().map(|&b| pos[b]).collect();
    for v in 0..inst.verts.len() {
        if on_boundary[v].is_none() {
            pos[v] = combine(&mean_value_coordinates(&tpl_boundary, inst.verts[v]), &warped_boundary);
        }
    }
    let is_corner: Vec<bool> = (0..n).map(|i| inst.corners.iter().any(|c| c.0 == i)).collect();
    let src: Vec<Vec<P>> = inst.faces.iter().map(|f| f.iter().map(|&v| inst.verts[v]).collect()).collect();
    for _ in 0..rounds {
        let mut acc = vec![[0.0, 0.0, 0.0]; inst.verts.len()];
        for (fi, f) in inst.faces.iter().enumerate() {
            let face = &t.faces[inst.face_of[fi]];
            let dst: Vec<P> = f.iter().map(|&v| pos[v]).collect();
            let alpha = register(&src[fi], &dst, face.class);
            let w = 1.0 / face.tolerance;
            for (&v, &p) in f.iter().zip(&src[fi]) {
                let q = alpha.apply(p);
                acc[v] = [acc[v][0] + w * q[0], acc[v][1] + w * q[1], acc[v][2] + w];
            }
        }
        for v in 0..inst.verts.len() {
            if acc[v][2] > 0.0 {
                pos[v] = [acc[v][0] / acc[v][2], acc[v][1] / acc[v][2]];
            }
        }
        // Boundary vertices back onto their sides, in order; corners stay.
        for i in 0..k {
            let (s0, s1) = (m.s[i], if i + 1 < k { m.s[i + 1] } else { m.s[0] + l });
            let at: Vec<usize> = (0..n).filter(|&j| side_of[j] == i && !is_corner[j]).collect();
            let mut order: Vec<usize> = at.clone();
            order.sort_by(|&a, &b| s[a].total_cmp(&s[b]));
            for &j in &order {
                s[j] = block.ring.project(pos[inst.boundary[j]], s0, s1);
            }
            let mut lo = s0;
            for &j in &order {
                s[j] = s[j].max(lo + MIN_GAP);
                lo = s[j];
            }
            let mut hi = s1;
            for &j in order.iter().rev() {
                s[j] = s[j].min(hi - MIN_GAP);
                hi = s[j];
            }
        }
        for (i, &b) in inst.boundary.iter().enumerate() {
            pos[b] = block.ring.at(s[i]);
        }
    }
    let mut within_tolerance = true;
    let face_distance: Vec<f64> = inst
        .faces
        .iter()
        .enumerate()
        .map(|(fi, f)| {
            let face = &t.faces[inst.face_of[fi]];
            let dst: Vec<P> = f.iter().map(|&v| pos[v]).collect();
            let alpha = register(&src[fi], &dst, face.class);
            if rms(&alpha, &src[fi], &dst) > face.tolerance {
                within_tolerance = false;
            }
            mean_distance(&alpha, &src[fi], &dst)
        })
        .collect();
    let similarity = Class::Similarity { scale: [0.0, f64::INFINITY] };
    let face_similarity: Vec<f64> = inst
        .faces
        .iter()
        .enumerate()
        .map(|(fi, f)| {
            let dst: Vec<P> = f.iter().map(|&v| pos[v]).collect();
            mean_distance(&register(&src[fi], &dst, similarity), &src[fi], &dst)
        })
        .collect();
    let distance = face_distance.iter().sum::<f64>() / face_distance.len().max(1) as f64;
    Warp {
        pos,
        s,
        face_distance,
        face_similarity,
        distance,
        energy: distance / block.area.sqrt().max(1e-9),
        within_tolerance,
    }
}

/// The faces of a warp as polygons on the block: boundary edges follow the block's ring between
/// their ends, so the faces tile the block exactly when the warp does not fold.
pub fn face_polygons(inst: &Instance, block: &Block, w: &Warp) -> Vec<Vec<P>> {
    let n = inst.boundary.len();
    let mut at = vec![None; inst.verts.len()];
    for (i, &b) in inst.boundary.iter().enumerate() {
        at[b] = Some(i);
    }
    let l = block.ring.length();
    inst.faces
        .iter()
        .map(|f| {
            let mut ring = Vec::new();
            for j in 0..f.len() {
                let (u, v) = (f[j], f[(j + 1) % f.len()]);
                ring.push(w.pos[u]);
                if let (Some(iu), Some(iv)) = (at[u], at[v]) {
                    if (iu + 1) % n == iv {
                        let (s0, mut s1) = (w.s[iu], w.s[iv]);
                        while s1 < s0 {
                            s1 += l;
                        }
                        ring.extend(block.ring.between(s0, s1));
                    }
                }
            }
            ring.dedup_by(|a, b| dist(*a, *b) < 1e-9);
            while ring.len() > 1 && dist(ring[0], ring[ring.len() - 1]) < 1e-9 {
                ring.pop();
            }
            ring
        })
        .collect()
}

/// Whether a ring is simple (no two non-adjacent edges meet) and counter-clockwise.
pub fn simple_ccw(ring: &[P]) -> bool {
    let n = ring.len();
    if n < 3 || crate::geometry::ring_area2(ring) <= 0.0 {
        return false;
    }
    for i in 0..n {
        for j in i + 1..n {
            if j == i + 1 || (i == 0 && j == n - 1) {
                continue;
            }
            if crate::geometry::segment_intersection(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n]).is_some() {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::super::arclength::matches;
    use super::super::file::builtin;
    use super::super::instance::instantiate;
    use super::*;
    use crate::layout::parcels::StreetIndex;
    use crate::layout::Street;

    fn block(pts: Vec<P>) -> Block {
        let street = Street::new(vec![[-50.0, -7.5], [400.0, -7.5]], 15.0, 0);
        Block::new(pts, &StreetIndex::new(&[street]), 10.0)
    }

    #[test]
    fn a_row_warps_exactly_onto_its_own_rectangle_and_along_the_street() {
        let row = builtin().into_iter().find(|t| t.name == "row").unwrap();
        let inst = instantiate(&row, 10, 1.0).unwrap();
        let b = block(vec![[0.0, 0.0], [180.0, 0.0], [180.0, 30.0], [0.0, 30.0]]);
        let m = matches(&inst, &b);
        // Only the rotation that puts the template's street side on the block's street side.
        assert_eq!(m.len(), 1);
        assert!(m[0].distortion < 1e-12 && m[0].s[0] == 0.0);
        let w = warp(&row, &inst, &b, &m[0], ROUNDS);
        assert!(w.energy < 1e-9 && w.within_tolerance);
        for (p, q) in w.pos.iter().zip(&inst.verts) {
            assert!(dist(*p, *q) < 1e-9);
        }
        let faces = face_polygons(&inst, &b, &w);
        let area: f64 = faces.iter().map(|f| crate::geometry::ring_area2(f) / 2.0).sum();
        assert!((area - 180.0 * 30.0).abs() < 1e-6 && faces.iter().all(|f| simple_ccw(f)));
    }

    #[test]
    fn registration_rounds_lower_the_distance_of_the_initial_warp() {
        let row = builtin().into_iter().find(|t| t.name == "row").unwrap();
        let inst = instantiate(&row, 10, 1.0).unwrap();
        // A trapezoid: the back side shorter and shifted.
        let b = block(vec![[0.0, 0.0], [190.0, 0.0], [170.0, 32.0], [10.0, 30.0]]);
        let m = &matches(&inst, &b)[0];
        let (w0, w) = (warp(&row, &inst, &b, m, 0), warp(&row, &inst, &b, m, ROUNDS));
        assert!(w.distance < w0.distance, "{} ≥ {}", w.distance, w0.distance);
        let faces = face_polygons(&inst, &b, &w);
        let area: f64 = faces.iter().map(|f| crate::geometry::ring_area2(f) / 2.0).sum();
        assert!((area - b.area).abs() < 1e-6 * b.area && faces.iter().all(|f| simple_ccw(f)));
    }
}
