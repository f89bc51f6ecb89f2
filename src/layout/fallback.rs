//! The parcels of a block no template settles (Yang et al. 2013 §3's fallback): the row
//! parceller's ([`super::parcels`]) or the straight-skeleton parceller's ([`super::skeleton`]),
//! whichever leaves fewer undesirable parcels (the rows on a tie).
//!
//! A block with a hole (the land round a lake no street reaches) is also tried cut into pieces
//! without holes: by a line through each hole's centroid, along the block's minimum rotated
//! rectangle's long axis or across it, each piece parcelled as above; the cut is no street, only
//! a parcel boundary, and it is kept when its pieces leave fewer undesirable parcels than the
//! whole block's rows.
//!
//! Parcels without street access in one block (the inner rows of a deep block, the strip along a
//! lake) are one park: they are merged into the connected pieces of their union, since a park is
//! land for its use and not a row of lots.

use super::metrics::parcel_shape;
use super::parcels::{parcellate as rows, StreetIndex};
use super::How;
use super::{Parcel, Use};
use crate::geometry::polygon::geo_polygon;
use crate::geometry::shape::outer_ring;
use crate::geometry::{Shape, P};
use geo::{Area, BooleanOps, Centroid, MinimumRotatedRect};

/// Holes cut through at most this deep (one cut per hole).
const MAX_CUTS: usize = 4;

/// The fallback's parcels of one block (each with `part` set) and how they were made.
pub fn parcel_block(b: &Shape, index: &StreetIndex, depth: f64, width: f64, part: &str) -> (Vec<Parcel>, How) {
    let (mut best, mut how) = whole(b, index, depth, width);
    if b.has_holes() {
        for along in [true, false] {
            let pieces: Vec<Shape> = without_holes(b.geo(), along, MAX_CUTS).into_iter().map(Shape::from_geo).collect();
            if pieces.len() < 2 {
                continue;
            }
            let mut parcels = Vec::new();
            let mut skeleton = false;
            for piece in &pieces {
                let (p, h) = whole(piece, index, depth, width);
                parcels.extend(p);
                skeleton |= h == How::Skeleton;
            }
            let parcels = merge_parks(parcels);
            if undesirable(&parcels) < undesirable(&best) {
                best = parcels;
                how = if skeleton { How::Skeleton } else { How::Rows };
            }
        }
    }
    (best.into_iter().map(|p| Parcel { part: part.to_string(), ..p }).collect(), how)
}

/// The row parceller's or the skeleton parceller's parcels of a block, parks merged.
fn whole(b: &Shape, index: &StreetIndex, depth: f64, width: f64) -> (Vec<Parcel>, How) {
    let by_rows = merge_parks(rows(std::slice::from_ref(b), index, depth, width));
    let r = undesirable(&by_rows);
    if r == 0 {
        return (by_rows, How::Rows);
    }
    match super::skeleton::parcellate(b, index, depth, width).map(merge_parks) {
        Some(sk) if undesirable(&sk) < r => (sk, How::Skeleton),
        _ => (by_rows, How::Rows),
    }
}

/// How many parcels are undesirable (§7: mean corner deviation over 15° or area ratio over 1.2).
pub fn undesirable(parcels: &[Parcel]) -> usize {
    parcels.iter().filter(|p| parcel_shape(&p.polygon).undesirable()).count()
}

/// The parks of a block merged into the connected pieces of their union (a piece whose union
/// holds a hole is left as it was), after the other parcels in their order.
pub fn merge_parks(parcels: Vec<Parcel>) -> Vec<Parcel> {
    let (parks, mut out): (Vec<Parcel>, Vec<Parcel>) = parcels.into_iter().partition(|p| p.use_ == Use::Park);
    if parks.len() < 2 {
        out.extend(parks);
        return out;
    }
    let polys: Vec<geo::Polygon<f64>> = parks.iter().map(|p| geo_polygon(&p.polygon, &[])).collect();
    let union = geo::unary_union(polys.iter());
    if union.0.iter().any(|u| !u.interiors().is_empty()) {
        out.extend(parks);
        return out;
    }
    out.extend(union.0.iter().map(|u| Parcel { part: parks[0].part.clone(), ..Parcel::new(outer_ring(u), Use::Park) }));
    out
}

/// The block cut by a line through each hole's centroid (along the block's long axis when
/// `along`, else across it) into pieces without holes; at most `cuts` deep. Empty when a cut
/// fails to remove a hole.
fn without_holes(b: &geo::Polygon<f64>, along: bool, cuts: usize) -> Vec<geo::Polygon<f64>> {
    let Some(hole) = b.interiors().first() else { return vec![b.clone()] };
    if cuts == 0 {
        return Vec::new();
    }
    let hole = geo::Polygon::new(hole.clone(), vec![]);
    let (Some(c), Some(rect)) = (hole.centroid(), b.minimum_rotated_rect()) else { return Vec::new() };
    let r: Vec<P> = rect.exterior().0.iter().map(|q| [q.x, q.y]).collect();
    let (e1, e2) = (crate::geometry::sub(r[1], r[0]), crate::geometry::sub(r[2], r[1]));
    let long = if crate::geometry::norm(e1) >= crate::geometry::norm(e2) { e1 } else { e2 };
    let u = crate::geometry::scale(long, 1.0 / crate::geometry::norm(long).max(1e-12));
    let d = if along { u } else { [-u[1], u[0]] };
    let reach = 1e5;
    let (cx, cy) = (c.x(), c.y());
    let half = |side: f64| {
        let n = [-d[1] * side, d[0] * side];
        let at = |s: f64, t: f64| (cx + d[0] * s + n[0] * t, cy + d[1] * s + n[1] * t);
        let ring = vec![at(-reach, 0.0), at(reach, 0.0), at(reach, reach), at(-reach, reach), at(-reach, 0.0)];
        geo::Polygon::new(geo::LineString::from(ring), vec![])
    };
    let mut out = Vec::new();
    let before = b.interiors().len();
    for side in [1.0, -1.0] {
        for piece in b.intersection(&half(side)).0.into_iter().filter(|p| p.unsigned_area() > 1.0) {
            if piece.interiors().len() >= before {
                return Vec::new();
            }
            let rest = without_holes(&piece, along, cuts - 1);
            if rest.is_empty() {
                return Vec::new();
            }
            out.extend(rest);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::Street;

    fn square(x0: f64, y0: f64, s: f64) -> geo::LineString<f64> {
        geo::LineString::from(vec![(x0, y0), (x0 + s, y0), (x0 + s, y0 + s), (x0, y0 + s), (x0, y0)])
    }

    #[test]
    fn a_block_round_a_lake_is_cut_into_pieces_without_holes() {
        let b = geo::Polygon::new(square(0.0, 0.0, 160.0), vec![square(50.0, 50.0, 60.0)]);
        for along in [true, false] {
            let pieces = without_holes(&b, along, MAX_CUTS);
            assert_eq!(pieces.len(), 2);
            assert!(pieces.iter().all(|p| p.interiors().is_empty()));
            let total: f64 = pieces.iter().map(|p| p.unsigned_area()).sum();
            assert!((total - b.unsigned_area()).abs() < 1e-6, "{total}");
        }
        assert!(without_holes(&b, true, 0).is_empty(), "no cut left for the hole");
    }

    #[test]
    fn parks_of_a_block_are_one_park_and_the_rest_is_kept() {
        let sq = |x: f64| vec![[x, 0.0], [x + 10.0, 0.0], [x + 10.0, 10.0], [x, 10.0]];
        let parcels = vec![
            Parcel::new(sq(0.0), Use::Park),
            Parcel::new(sq(10.0), Use::Residential),
            Parcel::new(sq(20.0), Use::Park),
            Parcel::new(sq(30.0), Use::Park),
        ];
        let merged = merge_parks(parcels);
        assert_eq!(merged.iter().map(|p| p.use_).collect::<Vec<_>>(), [Use::Residential, Use::Park, Use::Park]);
        let mut areas: Vec<f64> = merged.iter().map(|p| crate::geometry::ring_area2(&p.polygon) / 2.0).collect();
        areas.sort_by(f64::total_cmp);
        assert_eq!(areas, [100.0, 100.0, 200.0]);
    }

    #[test]
    fn the_fallback_keeps_rows_where_they_are_fine() {
        let b = Shape::from_geo(geo::Polygon::new(square(0.0, 0.0, 60.0), vec![]));
        let index = StreetIndex::new(&[Street::new(vec![[-10.0, -7.5], [70.0, -7.5]], 15.0, 0)]);
        let (parcels, how) = parcel_block(&b, &index, 30.0, 18.0, "0.1");
        assert_eq!(how, How::Rows);
        assert!(parcels.iter().all(|p| p.part == "0.1") && undesirable(&parcels) == 0);
    }
}
