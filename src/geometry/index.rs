//! A uniform grid over segments, for "which segments are near this point" queries.

use super::polygon::bounds;
use super::{closest_on_segment, dist, P};

/// Segments bucketed by the grid cells their bounding boxes cover.
#[derive(Clone, Debug)]
pub struct SegmentIndex {
    segments: Vec<(P, P)>,
    origin: P,
    cell: f64,
    dims: [usize; 2],
    buckets: Vec<Vec<u32>>,
}

impl SegmentIndex {
    /// An index over `segments` with cells of about `cell` metres (at most 4 million cells).
    pub fn new(segments: Vec<(P, P)>, cell: f64) -> SegmentIndex {
        let pts: Vec<P> = segments.iter().flat_map(|s| [s.0, s.1]).collect();
        let [lo, hi] = if pts.is_empty() { [[0.0; 2], [1.0; 2]] } else { bounds(&pts) };
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let cell = cell.max(extent / 2000.0).max(1e-9);
        let dims = [((hi[0] - lo[0]) / cell) as usize + 1, ((hi[1] - lo[1]) / cell) as usize + 1];
        let mut index = SegmentIndex { segments, origin: lo, cell, dims, buckets: vec![Vec::new(); dims[0] * dims[1]] };
        for i in 0..index.segments.len() {
            let (a, b) = index.segments[i];
            let (c0, c1) =
                (index.cell_of([a[0].min(b[0]), a[1].min(b[1])]), index.cell_of([a[0].max(b[0]), a[1].max(b[1])]));
            for x in c0[0]..=c1[0] {
                for y in c0[1]..=c1[1] {
                    index.buckets[y * dims[0] + x].push(i as u32);
                }
            }
        }
        index
    }

    /// An empty index over the box `lo`–`hi` with cells of about `cell` metres (at most 4 million
    /// cells), grown with [`SegmentIndex::push`]. Segments outside the box land in its border
    /// cells (still found, only slower).
    pub fn with_bounds(lo: P, hi: P, cell: f64) -> SegmentIndex {
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let cell = cell.max(extent / 2000.0).max(1e-9);
        let dims = [((hi[0] - lo[0]) / cell) as usize + 1, ((hi[1] - lo[1]) / cell) as usize + 1];
        SegmentIndex { segments: Vec::new(), origin: lo, cell, dims, buckets: vec![Vec::new(); dims[0] * dims[1]] }
    }

    /// Adds segment `ab`; returns its index.
    pub fn push(&mut self, a: P, b: P) -> usize {
        let i = self.segments.len();
        self.segments.push((a, b));
        let (c0, c1) = (self.cell_of([a[0].min(b[0]), a[1].min(b[1])]), self.cell_of([a[0].max(b[0]), a[1].max(b[1])]));
        for x in c0[0]..=c1[0] {
            for y in c0[1]..=c1[1] {
                self.buckets[y * self.dims[0] + x].push(i as u32);
            }
        }
        i
    }

    /// Replaces segment `i` by a piece of it (`ab` on the old segment): its buckets are kept,
    /// a superset of the piece's.
    pub fn shrink(&mut self, i: usize, a: P, b: P) {
        self.segments[i] = (a, b);
    }

    fn cell_of(&self, p: P) -> [usize; 2] {
        let f = |k: usize| (((p[k] - self.origin[k]) / self.cell).floor().max(0.0) as usize).min(self.dims[k] - 1);
        [f(0), f(1)]
    }

    /// The segments.
    pub fn segments(&self) -> &[(P, P)] {
        &self.segments
    }

    /// Indices of the segments whose bounding boxes may come within `r` of `p` (each once,
    /// ascending).
    pub fn near(&self, p: P, r: f64) -> Vec<usize> {
        let (c0, c1) = (self.cell_of([p[0] - r, p[1] - r]), self.cell_of([p[0] + r, p[1] + r]));
        let mut out: Vec<usize> = Vec::new();
        for x in c0[0]..=c1[0] {
            for y in c0[1]..=c1[1] {
                out.extend(self.buckets[y * self.dims[0] + x].iter().map(|&i| i as usize));
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The distance from `p` to the nearest segment, if one lies within `r`.
    pub fn distance_within(&self, p: P, r: f64) -> Option<f64> {
        self.near(p, r)
            .into_iter()
            .map(|i| {
                let (a, b) = self.segments[i];
                dist(p, closest_on_segment(p, a, b).0)
            })
            .filter(|&d| d <= r)
            .min_by(f64::total_cmp)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_near_segments_only() {
        let idx = SegmentIndex::new(vec![([0.0, 0.0], [100.0, 0.0]), ([0.0, 50.0], [0.0, 100.0])], 10.0);
        assert_eq!(idx.distance_within([50.0, 3.0], 5.0), Some(3.0));
        assert_eq!(idx.distance_within([50.0, 30.0], 5.0), None);
        assert_eq!(idx.near([1.0, 60.0], 2.0), vec![1]);
    }

    #[test]
    fn grows_and_shrinks() {
        let mut idx = SegmentIndex::with_bounds([0.0, 0.0], [100.0, 100.0], 10.0);
        assert_eq!(idx.push([0.0, 0.0], [100.0, 0.0]), 0);
        idx.shrink(0, [0.0, 0.0], [50.0, 0.0]);
        assert_eq!(idx.push([50.0, 0.0], [100.0, 0.0]), 1);
        assert_eq!(idx.distance_within([80.0, 2.0], 5.0), Some(2.0));
        assert_eq!(idx.segments()[0].1, [50.0, 0.0]);
    }
}
