//! Blocks and parcels from streets: the blocks are the region minus the streets' areas (each
//! centreline buffered by half its width, mitred joins, butt ends); each block is cut into
//! parcels by the row parceller below. The same function parcels the blocks of a `netspec city`
//! design, so layouts made by different methods are measured on equal terms.
//!
//! **The row parceller** (the fallback of Yang et al. 2013 §3 where no template fits, in the
//! spirit of the oriented-bounding-box subdivision of Vanegas et al. 2012): take the block's
//! minimum rotated rectangle; up to 1.6 parcel depths deep it is one row, up to 3.2 two rows back
//! to back (cut along its long axis), deeper a row along each long side and the middle worked on
//! again; a row is then cut across into `round(length / width)` parcels of equal frontage. Parcels with no street within reach
//! (an inner row of a deep block) are parks; remnants under a quarter of a parcel's area are
//! "other".

use super::{Parcel, Street, Use};
use crate::geometry::index::SegmentIndex;
use crate::geometry::shape::outer_ring;
use crate::geometry::{dot, Polygon, Shape, P};
use geo::{Area, BooleanOps, Buffer, MinimumRotatedRect};

/// How far a parcel edge may be from a street's side and still front it (metres).
pub const ACCESS_TOLERANCE: f64 = 0.5;

/// Rows deeper than this many parcel depths are cut in two along their length.
const ROW_DEPTH_FACTOR: f64 = 1.6;

/// The area the streets cover inside the region: the union of their buffers (half their width
/// on each side), clipped to the region.
pub(crate) fn street_area(region: &Polygon, streets: &[Street]) -> geo::MultiPolygon<f64> {
    let buffers: Vec<geo::MultiPolygon<f64>> = streets.iter().map(street_buffer).collect();
    let union = geo::unary_union(buffers.iter());
    region.to_geo().intersection(&union)
}

/// A street's area: its centreline buffered by half its width (mitred joins, butt ends).
pub(crate) fn street_buffer(s: &Street) -> geo::MultiPolygon<f64> {
    let line = geo::LineString::from(s.polyline.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>());
    let style = geo::algorithm::buffer::BufferStyle::new(s.width / 2.0)
        .line_join(geo::algorithm::buffer::LineJoin::Miter(4.0))
        .line_cap(geo::algorithm::buffer::LineCap::Butt);
    line.buffer_with_style(style)
}

/// The blocks: the region minus the street area, largest first (ties by position).
pub fn blocks(region: &Polygon, streets: &[Street]) -> Vec<Shape> {
    let mut out = region.to_geo().difference(&street_area(region, streets)).0;
    out.retain(|b| b.unsigned_area() > 1e-6);
    out.sort_by(|a, b| {
        let key = |p: &geo::Polygon<f64>| (-(p.unsigned_area() * 1e3).round(), first_xy(p));
        key(a).partial_cmp(&key(b)).unwrap_or(std::cmp::Ordering::Equal)
    });
    Shape::from_geo_multi(geo::MultiPolygon(out))
}

fn first_xy(p: &geo::Polygon<f64>) -> (i64, i64) {
    p.exterior().0.first().map_or((0, 0), |c| ((c.x * 1e3).round() as i64, (c.y * 1e3).round() as i64))
}

/// An index over the streets' centrelines, with each segment's half width.
pub struct StreetIndex {
    index: SegmentIndex,
    half: Vec<f64>,
}

impl StreetIndex {
    /// The index.
    pub fn new(streets: &[Street]) -> StreetIndex {
        let mut segs = Vec::new();
        let mut half = Vec::new();
        for s in streets {
            for w in s.polyline.windows(2) {
                segs.push((w[0], w[1]));
                half.push(s.width / 2.0);
            }
        }
        StreetIndex { index: SegmentIndex::new(segs, 50.0), half }
    }

    /// Whether some point of the ring (its vertices and edge midpoints) lies within a street's
    /// half width plus [`ACCESS_TOLERANCE`] of its centreline.
    pub fn fronts(&self, ring: &[P]) -> bool {
        let max_half = self.half.iter().copied().fold(0.0, f64::max);
        let n = ring.len();
        (0..n).any(|i| {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            [a, [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0]].into_iter().any(|p| {
                self.index.near(p, max_half + ACCESS_TOLERANCE).into_iter().any(|k| {
                    let (s, e) = self.index.segments()[k];
                    crate::geometry::dist(p, crate::geometry::closest_on_segment(p, s, e).0)
                        <= self.half[k] + ACCESS_TOLERANCE
                })
            })
        })
    }
}

/// Parcels of every block, in block order; within a block in cutting order.
pub fn parcellate(blocks: &[Shape], streets: &StreetIndex, depth: f64, width: f64) -> Vec<Parcel> {
    let mut out = Vec::new();
    for b in blocks {
        for piece in rows_and_parcels(b.geo(), depth, width) {
            let ring = outer_ring(&piece);
            if ring.len() < 3 || piece.unsigned_area() < 1e-3 * depth * width {
                continue;
            }
            let use_ = if piece.unsigned_area() < 0.25 * depth * width {
                Use::Other
            } else if streets.fronts(&ring) {
                Use::Residential
            } else {
                Use::Park
            };
            out.push(Parcel::new(ring, use_));
        }
    }
    out
}

fn rows_and_parcels(block: &geo::Polygon<f64>, depth: f64, width: f64) -> Vec<geo::Polygon<f64>> {
    let Some((c, u, long, short)) = frame(block) else { return vec![block.clone()] };
    let v = [-u[1], u[0]];
    let r = long + short;
    if short > 2.0 * ROW_DEPTH_FACTOR * depth {
        // Deeper than two rows: a row along each long side, the middle worked on again.
        let cuts = [(-r, -short / 2.0 + depth), (-short / 2.0 + depth, short / 2.0 - depth), (short / 2.0 - depth, r)];
        return cuts
            .into_iter()
            .flat_map(|(t0, t1)| slab(block, c, v, u, t0, t1, r).0)
            .flat_map(|part| rows_and_parcels(&part, depth, width))
            .collect();
    }
    if short > ROW_DEPTH_FACTOR * depth {
        // Two rows back to back: cut along the long axis, through the rectangle's centre.
        return [(-r, 0.0), (0.0, r)]
            .into_iter()
            .flat_map(|(t0, t1)| slab(block, c, v, u, t0, t1, r).0)
            .flat_map(|half| rows_and_parcels(&half, depth, width))
            .collect();
    }
    let n = (long / width).round().max(1.0) as usize;
    (0..n)
        .flat_map(|i| {
            let t0 = if i == 0 { -r } else { -long / 2.0 + long * i as f64 / n as f64 };
            let t1 = if i + 1 == n { r } else { -long / 2.0 + long * (i + 1) as f64 / n as f64 };
            slab(block, c, u, v, t0, t1, r).0
        })
        .filter(|p| p.unsigned_area() > 1e-6)
        .collect()
}

/// The block's minimum rotated rectangle as (centre, unit long axis, long side, short side).
fn frame(block: &geo::Polygon<f64>) -> Option<(P, P, f64, f64)> {
    let rect = block.minimum_rotated_rect()?;
    let pts: Vec<P> = rect.exterior().0.iter().map(|c| [c.x, c.y]).collect();
    if pts.len() < 4 {
        return None;
    }
    let e1 = crate::geometry::sub(pts[1], pts[0]);
    let e2 = crate::geometry::sub(pts[2], pts[1]);
    let (l1, l2) = (crate::geometry::norm(e1), crate::geometry::norm(e2));
    if l1 <= 0.0 || l2 <= 0.0 {
        return None;
    }
    let c = [(pts[0][0] + pts[2][0]) / 2.0, (pts[0][1] + pts[2][1]) / 2.0];
    // A canonical axis direction (x ≥ 0, or pointing up when vertical) for determinism.
    let canon = |e: P, l: f64| {
        let u = [e[0] / l, e[1] / l];
        if u[0] < -1e-12 || (u[0].abs() <= 1e-12 && u[1] < 0.0) {
            [-u[0], -u[1]]
        } else {
            u
        }
    };
    Some(if l1 >= l2 { (c, canon(e1, l1), l1, l2) } else { (c, canon(e2, l2), l2, l1) })
}

/// The part of `block` whose coordinate along `u` (from `c`) lies in `[t0, t1]`; `v` spans the
/// slab's other direction, `r` bounds the block's extent.
fn slab(block: &geo::Polygon<f64>, c: P, u: P, v: P, t0: f64, t1: f64, r: f64) -> geo::MultiPolygon<f64> {
    debug_assert!(dot(u, v).abs() < 1e-9);
    let at = |t: f64, s: f64| (c[0] + u[0] * t + v[0] * s, c[1] + u[1] * t + v[1] * s);
    let rect = geo::Polygon::new(
        geo::LineString::from(vec![at(t0, -r), at(t1, -r), at(t1, r), at(t0, r), at(t0, -r)]),
        vec![],
    );
    block.intersection(&rect)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn street(pts: &[P], level: usize) -> Street {
        Street::new(pts.to_vec(), 15.0, level)
    }

    #[test]
    fn a_double_loaded_block_becomes_two_rows_of_parcels() {
        // A 75 m × 225 m strip between two streets along its long sides.
        let region = Polygon::new(vec![[0.0, 0.0], [225.0, 0.0], [225.0, 75.0], [0.0, 75.0]], vec![]).unwrap();
        let streets = [street(&[[-10.0, 0.0], [235.0, 0.0]], 0), street(&[[-10.0, 75.0], [235.0, 75.0]], 0)];
        let blocks = blocks(&region, &streets);
        assert_eq!(blocks.len(), 1);
        assert!((blocks[0].area() - 225.0 * 60.0).abs() < 1e-6);
        let parcels = parcellate(&blocks, &StreetIndex::new(&streets), 30.0, 18.0);
        // 60 m deep → two rows of 30 m; 225 m long → 12 or 13 parcels a row of about 18 m.
        assert_eq!(parcels.len(), 2 * 13);
        assert!(parcels.iter().all(|p| p.use_ == Use::Residential));
        let total: f64 = parcels.iter().map(|p| crate::geometry::ring_area2(&p.polygon) / 2.0).sum();
        assert!((total - 225.0 * 60.0).abs() < 1e-3, "{total}");
    }

    #[test]
    fn inner_rows_of_deep_blocks_are_parks() {
        let region = Polygon::new(vec![[0.0, 0.0], [200.0, 0.0], [200.0, 200.0], [0.0, 200.0]], vec![]).unwrap();
        let streets = [street(&[[0.0, 0.0], [200.0, 0.0], [200.0, 200.0], [0.0, 200.0], [0.0, 0.0]], 0)];
        let parcels = parcellate(&blocks(&region, &streets), &StreetIndex::new(&streets), 30.0, 18.0);
        assert!(parcels.iter().any(|p| p.use_ == Use::Park));
        assert!(parcels.iter().any(|p| p.use_ == Use::Residential));
    }
}
