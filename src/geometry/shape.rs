//! Shapes: polygons with holes as boolean operations leave them (blocks, street areas, parcels
//! while they are cut, the sea), unchecked where [`super::Polygon`] is checked. A shape wraps a
//! `geo` polygon so that booleans, buffers and rotated rectangles run on it without a copy, and
//! so that `geo`'s types stay inside this layer: code above reads a shape through its rings.

use super::{cross, dist, dot, ring_area2, sub, P};
use geo::Area;

/// A polygon with holes as a boolean operation leaves it: rings closed (first point repeated),
/// possibly touching themselves, not normalised.
#[derive(Clone, Debug, PartialEq)]
pub struct Shape(geo::Polygon<f64>);

/// Spikes narrower than this (metres) are removed by [`Shape::ring`].
pub const SPIKE_WIDTH: f64 = 0.05;

impl Shape {
    /// The shape of an outer ring and holes (not closed; each is closed here, orientations kept).
    pub fn new(outer: &[P], holes: &[Vec<P>]) -> Shape {
        Shape(super::polygon::geo_polygon(outer, holes))
    }

    /// The shape of a `geo` polygon.
    pub(crate) fn from_geo(p: geo::Polygon<f64>) -> Shape {
        Shape(p)
    }

    /// The shapes of a `geo` multipolygon, in its order.
    pub(crate) fn from_geo_multi(m: geo::MultiPolygon<f64>) -> Vec<Shape> {
        m.0.into_iter().map(Shape).collect()
    }

    /// The `geo` polygon, for booleans and the other `geo` algorithms.
    pub(crate) fn geo(&self) -> &geo::Polygon<f64> {
        &self.0
    }

    /// Its area (holes subtracted).
    pub fn area(&self) -> f64 {
        self.0.unsigned_area()
    }

    /// Whether it has holes.
    pub fn has_holes(&self) -> bool {
        !self.0.interiors().is_empty()
    }

    /// Its rings as stored, the outer first, then the holes: each closed (first point
    /// repeated), orientations as the boolean left them.
    pub fn rings(&self) -> Vec<Vec<P>> {
        std::iter::once(self.0.exterior())
            .chain(self.0.interiors())
            .map(|l| l.0.iter().map(|c| [c.x, c.y]).collect())
            .collect()
    }

    /// Its outer ring: counter-clockwise, not closed, without spikes (see [`without_spikes`]).
    pub fn ring(&self) -> Vec<P> {
        outer_ring(&self.0)
    }
}

/// The outer ring of a `geo` polygon as [`Shape::ring`] gives it.
pub(crate) fn outer_ring(p: &geo::Polygon<f64>) -> Vec<P> {
    let mut r: Vec<P> = p.exterior().0.iter().map(|c| [c.x, c.y]).collect();
    if r.len() > 1 && r.first() == r.last() {
        r.pop();
    }
    if ring_area2(&r) < 0.0 {
        r.reverse();
    }
    without_spikes(r)
}

/// A ring with its spikes removed: vertices whose two edges run back along each other (their
/// triangle's height over its longest side under [`SPIKE_WIDTH`], the neighbours on the same
/// side of it), as a boolean leaves where a cut ends exactly on an edge; and repeated vertices.
pub fn without_spikes(mut r: Vec<P>) -> Vec<P> {
    let mut i = 0;
    while r.len() > 3 && i < r.len() {
        let n = r.len();
        let (a, b, c) = (r[(i + n - 1) % n], r[i], r[(i + 1) % n]);
        let (u, v) = (sub(a, b), sub(c, b));
        let base = dist(a, c).max(dist(a, b)).max(dist(b, c));
        let spike = dot(u, v) > 0.0 && cross(u, v).abs() <= SPIKE_WIDTH * base;
        if spike || dist(a, b) < 1e-9 {
            r.remove(i);
            i = i.saturating_sub(1);
        } else {
            i += 1;
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::polygon::geo_polygon;

    #[test]
    fn spikes_are_removed_from_rings() {
        let r = without_spikes(vec![[0.0, 0.0], [15.0, 0.0], [15.0, 22.0], [15.0, 30.0], [15.0, 23.0], [0.0, 23.0]]);
        assert_eq!(r, vec![[0.0, 0.0], [15.0, 0.0], [15.0, 22.0], [15.0, 23.0], [0.0, 23.0]]);
        // A boolean's spike is off by a few millimetres; a real sharp corner is kept.
        let r =
            without_spikes(vec![[455.252, 30.23], [455.25, 37.729], [455.254, 7.5], [470.162, 7.5], [470.16, 30.234]]);
        assert_eq!(r.len(), 4, "{r:?}");
        let wedge = vec![[0.0, 0.0], [30.0, 0.0], [0.0, 5.0]];
        assert_eq!(without_spikes(wedge.clone()), wedge);
    }

    #[test]
    fn ring_is_open_and_counter_clockwise() {
        let cw = Shape::from_geo(geo_polygon(&[[0.0, 0.0], [0.0, 2.0], [3.0, 2.0], [3.0, 0.0]], &[]));
        assert_eq!(cw.ring(), vec![[3.0, 0.0], [3.0, 2.0], [0.0, 2.0], [0.0, 0.0]]);
        assert_eq!(cw.area(), 6.0);
        assert!(!cw.has_holes());
        assert_eq!(cw.rings()[0].len(), 5);
    }
}
