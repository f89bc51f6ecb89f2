//! Blocks: the bounded faces of the street graph, made planar (streets noded where they cross,
//! bridges included: a block is land enclosed by streets, whatever their grade).

use super::graph::Network;
use crate::geometry::planar::{polygon_label_point, PlanarGraph};
use crate::geometry::{Polygon, P};

/// A block: its area (m²), perimeter (m: the streets that bound it, cul-de-sacs poking into it
/// excluded) and a point inside it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Block {
    /// Area, m².
    pub area: f64,
    /// Perimeter, m.
    pub perimeter: f64,
    /// A point strictly inside.
    pub label: P,
}

/// Streets within this distance (metres) meet when the graph is made planar.
const SNAP: f64 = 0.01;

/// The blocks of a network whose label point lies in `region` (every block without one).
pub fn blocks(net: &Network, region: Option<&Polygon>) -> Vec<Block> {
    let segments: Vec<[P; 2]> = net.edges.iter().flat_map(|e| e.shape.windows(2).map(|w| [w[0], w[1]])).collect();
    let g = PlanarGraph::from_segments(&segments, SNAP);
    let at = |r: &[u32]| r.iter().map(|&v| g.positions[v as usize]).collect::<Vec<P>>();
    g.faces()
        .faces
        .iter()
        .filter_map(|f| {
            let outer = at(&f.boundary);
            let holes: Vec<Vec<P>> = f.holes.iter().map(|h| at(h)).collect();
            let label = polygon_label_point(&outer, &holes)?;
            region.is_none_or(|r| r.contains(label)).then_some(Block { area: f.area, perimeter: f.perimeter, label })
        })
        .collect()
}
