//! The straight-skeleton parceller (the paper's fallback, §3, after Vanegas et al. 2012): a block
//! is split into the faces of its straight skeleton ([`crate::geometry::skeleton`]); the faces of
//! the edges along one side of the block (between corners turning 30° or more) make that side's
//! strip, every point of which is nearer that side than any other; each strip is cut across into
//! `round(length / width)` parcels by lines along the side's local normal, at equal steps of arc
//! length, so parcels front their street even where the block curves. A parcel with no street
//! within reach is a park, a piece under a quarter of a parcel's area "other", as in the row
//! parceller.

use super::parcels::StreetIndex;
use super::template::instance::{turn, CORNER_TURN};
use super::{Parcel, Use};
use crate::geometry::shape::outer_ring;
use crate::geometry::skeleton::faces;
use crate::geometry::{add, dist, norm, scale, sub, Shape, P};
use geo::{Area, BooleanOps, Simplify};

/// The parcels of a block without holes by its straight skeleton; `None` when the skeleton
/// cannot be built (the caller keeps the row parceller's).
pub fn parcellate(block: &Shape, streets: &StreetIndex, depth: f64, width: f64) -> Option<Vec<Parcel>> {
    if block.has_holes() {
        return None;
    }
    let ring = outer_ring(&block.geo().simplify(0.5));
    let n = ring.len();
    let faces = faces(&ring)?;
    let parcel_area = depth * width;
    let mut out = Vec::new();
    for side in sides(&ring) {
        let strip = geo::unary_union(side.iter().flat_map(|&e| faces[e].0.iter()));
        let line: Vec<P> = side.iter().map(|&e| ring[e]).chain(side.last().map(|&e| ring[(e + 1) % n])).collect();
        for piece in cut_across(&strip, &line, width) {
            let area = piece.unsigned_area();
            let r = outer_ring(&piece);
            if r.len() < 3 || area < 1e-3 * parcel_area {
                continue;
            }
            let use_ = if area < 0.25 * parcel_area {
                Use::Other
            } else if streets.fronts(&r) {
                Use::Residential
            } else {
                Use::Park
            };
            out.push(Parcel::new(r, use_));
        }
    }
    Some(out)
}

/// The ring's edges grouped into sides: runs of edges between vertices that turn 30° or more.
fn sides(ring: &[P]) -> Vec<Vec<usize>> {
    let n = ring.len();
    let corner: Vec<bool> =
        (0..n).map(|i| turn(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]).abs() >= CORNER_TURN).collect();
    let Some(start) = (0..n).find(|&i| corner[i]) else { return vec![(0..n).collect()] };
    let mut out: Vec<Vec<usize>> = Vec::new();
    for k in 0..n {
        let e = (start + k) % n;
        if corner[e] || out.is_empty() {
            out.push(Vec::new());
        }
        if let Some(last) = out.last_mut() {
            last.push(e);
        }
    }
    out
}

/// A strip cut into `round(length / width)` pieces by lines through equally spaced points of its
/// side, along the side's normal there (pointing into the block).
fn cut_across(strip: &geo::MultiPolygon<f64>, side: &[P], width: f64) -> Vec<geo::Polygon<f64>> {
    let len = crate::geometry::polyline_length(side);
    let k = ((len / width).round() as usize).max(1);
    if k == 1 {
        return strip.0.clone();
    }
    let reach = 1e4;
    // The half-plane behind the cut at arc length s: the side's start lies in it.
    let behind = |s: f64| -> geo::Polygon<f64> {
        let p = crate::geometry::point_at_length(side, s);
        let t = tangent(side, s);
        let nrm = [-t[1], t[0]];
        let a = add(p, scale(nrm, -reach));
        let b = add(p, scale(nrm, reach));
        let back = scale(t, -reach);
        let pts = [a, b, add(b, back), add(a, back), a];
        geo::Polygon::new(geo::LineString::from(pts.iter().map(|q| (q[0], q[1])).collect::<Vec<_>>()), vec![])
    };
    let mut rest = strip.clone();
    let mut out = Vec::new();
    for i in 1..k {
        let h = behind(len * i as f64 / k as f64);
        out.extend(rest.intersection(&h).0);
        rest = rest.difference(&h);
    }
    out.extend(rest.0);
    out
}

/// The unit tangent of a polyline at arc length `s` (of the segment holding it).
fn tangent(line: &[P], s: f64) -> P {
    let mut run = 0.0;
    for w in line.windows(2) {
        let l = dist(w[0], w[1]);
        if run + l >= s && l > 0.0 {
            return scale(sub(w[1], w[0]), 1.0 / l);
        }
        run += l;
    }
    let d = sub(line[line.len() - 1], line[0]);
    scale(d, 1.0 / norm(d).max(1e-12))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::Street;

    fn poly(pts: &[P]) -> Shape {
        Shape::new(pts, &[])
    }

    #[test]
    fn a_strip_between_two_streets_gives_two_rows_fronting_them() {
        let block = poly(&[[0.0, 0.0], [180.0, 0.0], [180.0, 60.0], [0.0, 60.0]]);
        let streets = StreetIndex::new(&[
            Street::new(vec![[-10.0, -7.5], [190.0, -7.5]], 15.0, 0),
            Street::new(vec![[-10.0, 67.5], [190.0, 67.5]], 15.0, 0),
        ]);
        let parcels = parcellate(&block, &streets, 30.0, 18.0).unwrap();
        let total: f64 = parcels.iter().map(|p| crate::geometry::ring_area2(&p.polygon) / 2.0).sum();
        assert!((total - 180.0 * 60.0).abs() < 1e-3, "{total}");
        // Ten parcels along each long side; the short sides' triangles (60 m / 18 m: three each).
        let front = parcels.iter().filter(|p| p.use_ == Use::Residential).count();
        assert!(front >= 20, "{front} of {}", parcels.len());
    }

    #[test]
    fn a_curved_block_is_cut_along_its_normals() {
        // A quarter annulus, 60 m deep: every parcel touches the outer or the inner arc.
        let mut ring: Vec<P> = (0..=12)
            .map(|i| {
                let a = i as f64 / 12.0 * std::f64::consts::FRAC_PI_2;
                [200.0 * a.cos(), 200.0 * a.sin()]
            })
            .collect();
        ring.extend((0..=12).rev().map(|i| {
            let a = i as f64 / 12.0 * std::f64::consts::FRAC_PI_2;
            [140.0 * a.cos(), 140.0 * a.sin()]
        }));
        let parcels = parcellate(&poly(&ring), &StreetIndex::new(&[]), 30.0, 18.0).unwrap();
        let total: f64 = parcels.iter().map(|p| crate::geometry::ring_area2(&p.polygon) / 2.0).sum();
        let area = std::f64::consts::FRAC_PI_4 * (200.0f64.powi(2) - 140.0f64.powi(2));
        assert!((total - area).abs() < 0.01 * area, "{total} of {area}");
        assert!(parcels.len() > 20);
    }
}
