//! Graph families a level designer draws, as level files of unit squares: paths, cycles,
//! ladders, grid graphs, caterpillars, stars and complete binary trees — for tests, benches and
//! `netspec level-gen`.
//!
//! A family is written `NAME:SIZE`: `path:100`, `cycle:200`, `ladder:50` (2 × 50),
//! `grid:10x10`, `caterpillar:100x2` (a spine of 100, two legs on each spine node),
//! `star:4`, `tree:31` (a complete binary tree of 31 nodes). `+triangle` adds one diagonal edge
//! that closes a triangle (on a grid or a ladder: nodes `(0,0)`, `(0,1)` and `(1,1)`; elsewhere
//! the first node and its neighbour's neighbour).

use super::spec::Level;
use super::LevelError;
use std::fmt::Write as _;

/// A graph family and its size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// A path of `n` nodes.
    Path(usize),
    /// A cycle of `n` nodes.
    Cycle(usize),
    /// Two rows of `n` nodes, rungs between them (a 2 × n grid graph).
    Ladder(usize),
    /// An `r × c` grid graph.
    Grid(usize, usize),
    /// A spine path of `n` nodes, each with `legs` leaves.
    Caterpillar(usize, usize),
    /// A hub and `n` leaves.
    Star(usize),
    /// A complete binary tree of `n` nodes (heap order).
    Tree(usize),
}

/// A family with options: the graph, an extra triangle edge.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Generated {
    /// The family.
    pub family: Family,
    /// Whether one extra edge closes a triangle.
    pub triangle: bool,
}

fn bad(text: &str, why: &str) -> LevelError {
    LevelError::Field { field: "family".into(), reason: format!("`{text}`: {why}") }
}

/// The largest graph a generator makes (nodes).
pub const MAX_NODES: usize = 100_000;

impl Generated {
    /// Parses `NAME:SIZE[+triangle]` (see the module docs).
    pub fn parse(text: &str) -> Result<Generated, LevelError> {
        let (body, triangle) = match text.strip_suffix("+triangle") {
            Some(b) => (b, true),
            None => (text, false),
        };
        let (name, size) = body.split_once(':').ok_or_else(|| bad(text, "expected NAME:SIZE, e.g. grid:10x10"))?;
        let num = |s: &str| -> Result<usize, LevelError> {
            s.trim().parse::<usize>().map_err(|_| bad(text, &format!("`{s}` is not a whole number")))
        };
        let pair = |s: &str| -> Result<(usize, usize), LevelError> {
            let (a, b) = s.split_once('x').ok_or_else(|| bad(text, "expected AxB"))?;
            Ok((num(a)?, num(b)?))
        };
        let family = match name {
            "path" => Family::Path(num(size)?),
            "cycle" => Family::Cycle(num(size)?),
            "ladder" => Family::Ladder(num(size)?),
            "grid" => {
                let (r, c) = pair(size)?;
                Family::Grid(r, c)
            }
            "caterpillar" => {
                let (n, l) = pair(size)?;
                Family::Caterpillar(n, l)
            }
            "star" => Family::Star(num(size)?),
            "tree" => Family::Tree(num(size)?),
            _ => return Err(bad(text, "unknown family (path, cycle, ladder, grid, caterpillar, star, tree)")),
        };
        let g = Generated { family, triangle };
        let n = g.nodes();
        let min = match family {
            Family::Cycle(_) => 3,
            _ => 1,
        };
        if n < min || n > MAX_NODES {
            return Err(bad(text, &format!("{n} nodes; a family has {min} to {MAX_NODES}")));
        }
        if triangle && g.triangle_edge().is_none() {
            return Err(bad(text, "this graph has no two-hop pair to close a triangle on"));
        }
        Ok(g)
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        match self.family {
            Family::Path(n) | Family::Cycle(n) | Family::Tree(n) => n,
            Family::Ladder(n) => 2 * n,
            Family::Grid(r, c) => r * c,
            Family::Caterpillar(n, l) => n * (l + 1),
            Family::Star(n) => n + 1,
        }
    }

    /// Node names, in order.
    pub fn names(&self) -> Vec<String> {
        match self.family {
            Family::Ladder(n) => (0..2).flat_map(|r| (0..n).map(move |c| format!("r{r}c{c}"))).collect(),
            Family::Grid(rows, cols) => (0..rows).flat_map(|r| (0..cols).map(move |c| format!("r{r}c{c}"))).collect(),
            Family::Caterpillar(n, l) => {
                let spine = (0..n).map(|i| format!("s{i}"));
                spine.chain((0..n).flat_map(move |i| (0..l).map(move |j| format!("s{i}l{j}")))).collect()
            }
            Family::Star(n) => std::iter::once("hub".to_string()).chain((0..n).map(|i| format!("leaf{i}"))).collect(),
            _ => (0..self.nodes()).map(|i| format!("n{i}")).collect(),
        }
    }

    /// Edges as node index pairs (the extra triangle edge last).
    pub fn edges(&self) -> Vec<(usize, usize)> {
        let mut e = Vec::new();
        match self.family {
            Family::Path(n) => e.extend((1..n).map(|i| (i - 1, i))),
            Family::Cycle(n) => {
                e.extend((1..n).map(|i| (i - 1, i)));
                e.push((0, n - 1));
            }
            Family::Ladder(n) => grid_edges(&mut e, 2, n),
            Family::Grid(r, c) => grid_edges(&mut e, r, c),
            Family::Caterpillar(n, l) => {
                e.extend((1..n).map(|i| (i - 1, i)));
                e.extend((0..n).flat_map(|i| (0..l).map(move |j| (i, n + i * l + j))));
            }
            Family::Star(n) => e.extend((1..=n).map(|i| (0, i))),
            Family::Tree(n) => e.extend((1..n).map(|i| ((i - 1) / 2, i))),
        }
        if self.triangle {
            e.extend(self.triangle_edge());
        }
        e
    }

    /// The extra edge that closes a triangle.
    fn triangle_edge(&self) -> Option<(usize, usize)> {
        match self.family {
            Family::Grid(r, c) if r >= 2 && c >= 2 => Some((0, c + 1)),
            Family::Ladder(n) if n >= 2 => Some((0, n + 1)),
            Family::Path(n) | Family::Caterpillar(n, 0) if n >= 3 => Some((0, 2)),
            Family::Cycle(n) if n >= 4 => Some((0, 2)),
            Family::Star(n) if n >= 2 => Some((1, 2)),
            Family::Tree(n) if n >= 4 => Some((0, 3)),
            Family::Caterpillar(n, l) if n >= 2 && l >= 1 => Some((1, n)),
            _ => None,
        }
    }

    /// The level file: unit squares, door width `w`.
    pub fn to_toml(&self, w: f64) -> String {
        let names = self.names();
        let mut s = format!(
            "# {} nodes, generated by `netspec level-gen`\ndoor_width = {w}\n\n[[block]]\nname = \"square\"\n\
             polygon = [[0, 0], [1, 0], [1, 1], [0, 1]]\n",
            names.len()
        );
        for n in &names {
            let _ = write!(s, "\n[[node]]\nname = \"{n}\"\n");
        }
        for (a, b) in self.edges() {
            let _ = write!(s, "\n[[edge]]\nnodes = [\"{}\", \"{}\"]\n", names[a], names[b]);
        }
        s
    }

    /// The level, resolved.
    pub fn level(&self, w: f64) -> Result<Level, LevelError> {
        Level::from_toml(&self.to_toml(w))
    }
}

fn grid_edges(e: &mut Vec<(usize, usize)>, rows: usize, cols: usize) {
    for r in 0..rows {
        for c in 0..cols {
            let i = r * cols + c;
            if c + 1 < cols {
                e.push((i, i + 1));
            }
            if r + 1 < rows {
                e.push((i, i + cols));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_edges() {
        let cases = [
            ("path:5", 5, 4),
            ("cycle:6", 6, 6),
            ("ladder:4", 8, 10),
            ("grid:3x4", 12, 17),
            ("caterpillar:3x2", 9, 8),
            ("star:5", 6, 5),
            ("tree:31", 31, 30),
            ("grid:3x3+triangle", 9, 13),
        ];
        for (text, n, m) in cases {
            let g = Generated::parse(text).unwrap();
            assert_eq!((g.nodes(), g.edges().len()), (n, m), "{text}");
            let level = g.level(0.5).unwrap();
            assert_eq!((level.nodes.len(), level.edges.len()), (n, m), "{text}");
        }
    }

    #[test]
    fn bad_families_name_the_problem() {
        for (text, want) in [
            ("grid10", "NAME:SIZE"),
            ("blob:3", "unknown family"),
            ("grid:3", "AxB"),
            ("path:x", "not a whole number"),
            ("cycle:2", "3 to"),
            ("path:0", "1 to"),
            ("path:2+triangle", "no two-hop"),
        ] {
            let e = Generated::parse(text).unwrap_err().to_string();
            assert!(e.contains(want) && e.contains("family"), "{text}: {e}");
        }
    }

    #[test]
    fn the_triangle_closes_on_two_hop_nodes() {
        let g = Generated::parse("grid:10x10+triangle").unwrap();
        let (a, b) = *g.edges().last().unwrap();
        assert_eq!((g.names()[a].as_str(), g.names()[b].as_str()), ("r0c0", "r1c1"));
    }
}
