//! Point location: a uniform grid over the mesh's bounding box, each cell listing (in index
//! order) the triangles whose bounding boxes overlap it. Cells are about the size of a triangle,
//! so a query tests a handful of triangles.

use crate::geometry::P;

/// Barycentric coordinates below `-EPS` mean outside (points on a shared edge find the first
/// triangle in index order).
const EPS: f64 = 1e-9;

/// The triangle buckets.
#[derive(Clone, Debug, Default)]
pub struct Grid {
    origin: P,
    cell: f64,
    dims: [usize; 2],
    /// Cell `c`'s triangles are `items[start[c]..start[c + 1]]`.
    start: Vec<usize>,
    items: Vec<usize>,
}

impl Grid {
    /// Buckets the triangles; cells are about as large as the mean triangle.
    pub fn new(vertices: &[P], triangles: &[[usize; 3]]) -> Grid {
        if triangles.is_empty() {
            return Grid::default();
        }
        let [lo, hi] = crate::geometry::polygon::bounds(vertices);
        let (w, h) = ((hi[0] - lo[0]).max(1e-12), (hi[1] - lo[1]).max(1e-12));
        // About two triangles per cell on average over the box.
        let cell = (2.0 * w * h / triangles.len() as f64).sqrt();
        let dims = [((w / cell).ceil() as usize).max(1), ((h / cell).ceil() as usize).max(1)];
        let mut grid = Grid { origin: lo, cell, dims, start: Vec::new(), items: Vec::new() };
        let ranges: Vec<[[usize; 2]; 2]> = triangles
            .iter()
            .map(|t| {
                let [a, b] = crate::geometry::polygon::bounds(&t.map(|v| vertices[v]));
                [grid.cell_of(a), grid.cell_of(b)]
            })
            .collect();
        let mut count = vec![0usize; dims[0] * dims[1] + 1];
        for r in &ranges {
            for y in r[0][1]..=r[1][1] {
                for x in r[0][0]..=r[1][0] {
                    count[y * dims[0] + x + 1] += 1;
                }
            }
        }
        for c in 1..count.len() {
            count[c] += count[c - 1];
        }
        let mut fill = count.clone();
        grid.items = vec![0; count[count.len() - 1]];
        for (t, r) in ranges.iter().enumerate() {
            for y in r[0][1]..=r[1][1] {
                for x in r[0][0]..=r[1][0] {
                    let c = y * dims[0] + x;
                    grid.items[fill[c]] = t;
                    fill[c] += 1;
                }
            }
        }
        grid.start = count;
        grid
    }

    /// The cell of a point, clamped to the grid.
    fn cell_of(&self, p: P) -> [usize; 2] {
        let f = |k: usize| {
            let x = ((p[k] - self.origin[k]) / self.cell).floor();
            if x.is_nan() || x < 0.0 {
                0
            } else {
                (x as usize).min(self.dims[k] - 1)
            }
        };
        [f(0), f(1)]
    }

    /// The first triangle (in index order) of `p`'s cell that contains it.
    pub fn locate(&self, vertices: &[P], triangles: &[[usize; 3]], p: P) -> Option<usize> {
        if self.start.is_empty() || !(p[0].is_finite() && p[1].is_finite()) {
            return None;
        }
        let cell = self.cell;
        let outside =
            |k: usize| p[k] < self.origin[k] - cell || p[k] > self.origin[k] + cell * (self.dims[k] as f64 + 1.0);
        if outside(0) || outside(1) {
            return None;
        }
        let [x, y] = self.cell_of(p);
        let c = y * self.dims[0] + x;
        self.items[self.start[c]..self.start[c + 1]]
            .iter()
            .copied()
            .find(|&t| barycentric(vertices, triangles[t], p).iter().all(|&l| l >= -EPS))
    }
}

/// The barycentric coordinates of `p` in a triangle.
pub fn barycentric(vertices: &[P], tri: [usize; 3], p: P) -> [f64; 3] {
    let [a, b, c] = tri.map(|v| vertices[v]);
    let area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    let part = |q: P, r: P| ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])) / area2;
    [part(b, c), part(c, a), part(a, b)]
}
