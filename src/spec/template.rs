//! Room templates: polyominoes of unit cells, the shapes a spec's `[rooms]` section names
//! (`rect AxB`, `L AxB` or explicit cells). Their placements on a mesh are enumerated by
//! [`crate::rules::placements`].

use serde::{Deserialize, Serialize};

/// A room template: a polyomino given as unit cells (x, y) ≥ 0.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Template {
    /// A name for reports.
    pub name: String,
    /// The unit cells `(x, y)`; duplicates are ignored and the cells are normalised by
    /// [`Template::images`], so any offset works.
    pub cells: Vec<(i32, i32)>,
    /// Whether the 90°, 180° and 270° rotations of the cells are images too.
    pub rotations: bool,
    /// Whether the mirror images (x ↦ −x, with their rotations if `rotations`) are images too.
    pub reflections: bool,
}

impl Template {
    /// An `a × b` rectangle (`a` cells along x, `b` along y), rotations and reflections on.
    /// Non-positive sizes give an empty template (which has no placements).
    pub fn rect(name: &str, a: i32, b: i32) -> Template {
        let mut cells = Vec::new();
        for y in 0..b.max(0) {
            for x in 0..a.max(0) {
                cells.push((x, y));
            }
        }
        Template { name: name.to_string(), cells, rotations: true, reflections: true }
    }

    /// An L: `a` cells along x starting at `(0, 0)`, plus a column of `b` cells up from that
    /// first cell (sharing it), so `a + b − 1` cells; meant for `a, b ≥ 2` (smaller values give
    /// a bar or a single cell). Rotations and reflections on.
    pub fn l_shape(name: &str, a: i32, b: i32) -> Template {
        let mut cells = Vec::new();
        for x in 0..a.max(1) {
            cells.push((x, 0));
        }
        for y in 1..b.max(1) {
            cells.push((0, y));
        }
        Template { name: name.to_string(), cells, rotations: true, reflections: true }
    }

    /// The distinct symmetry images (normalised so min x = min y = 0, cells sorted),
    /// deduplicated, in a deterministic order: unreflected first, then reflected (if
    /// `reflections`), each in rotation order 0°, 90°, 180°, 270° (only 0° without
    /// `rotations`); an image equal to an earlier one is dropped. Empty for an empty template.
    pub fn images(&self) -> Vec<Vec<(i32, i32)>> {
        if self.cells.is_empty() {
            return Vec::new();
        }
        let mut out: Vec<Vec<(i32, i32)>> = Vec::new();
        let reflections: &[bool] = if self.reflections { &[false, true] } else { &[false] };
        let rotations = if self.rotations { 4 } else { 1 };
        for &mirror in reflections {
            for rot in 0..rotations {
                let img = normalise(self.cells.iter().map(|&(x, y)| {
                    // Work in i64 so extreme coordinates cannot overflow.
                    let (mut x, mut y) = (x as i64, y as i64);
                    if mirror {
                        x = -x;
                    }
                    for _ in 0..rot {
                        let (nx, ny) = (-y, x);
                        x = nx;
                        y = ny;
                    }
                    (x, y)
                }));
                if !out.contains(&img) {
                    out.push(img);
                }
            }
        }
        out
    }
}

/// Shifts cells so min x = min y = 0, sorts and deduplicates them.
fn normalise(cells: impl Iterator<Item = (i64, i64)>) -> Vec<(i32, i32)> {
    let cells: Vec<(i64, i64)> = cells.collect();
    let mx = cells.iter().map(|c| c.0).min().unwrap_or(0);
    let my = cells.iter().map(|c| c.1).min().unwrap_or(0);
    let mut out: Vec<(i32, i32)> = cells
        .iter()
        .map(|&(x, y)| ((x - mx).clamp(0, i32::MAX as i64) as i32, (y - my).clamp(0, i32::MAX as i64) as i32))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}
