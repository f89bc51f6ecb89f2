//! Singularities of a cross field stored as `u = e^{4iθ}` per vertex: around a
//! counter-clockwise triangle `(a, b, c)` the turns `Δ_ab = arg(u_b/u_a)` (wrapped to `(−π, π]`),
//! `Δ_bc`, `Δ_ca` sum to `2πk`; the triangle holds a singularity of index `k/4` (a cross turns by
//! a quarter of `u`'s turn). The sign follows the orientation: `u = z` around a counter-clockwise
//! triangle is `+1/4`, `u = z̄` is `−1/4` (libigl's version reports every index as positive).
//!
//! **Pairs at the mesh scale cancel.** A `+1/4` and a `−1/4` in two triangles sharing a vertex
//! are dropped together ([`cancel_pairs`]). Such a pair is not resolved by the mesh: changing
//! the one shared vertex's value slightly creates or removes it, and it carries no net turning
//! (a loop around both triangles sees index 0), so no street could tell it from no singularity.
//! It appears where `|u|` is tiny over several triangles — a degenerate zero, as at the middle
//! of a disc, where the smooth field is `z⁴` (one `+1` zero) and rounding and the mesh's
//! irregularity split it into five `+1/4` around a `−1/4` instead of four `+1/4`. Signs are still
//! counted after cancelling: the sum is unchanged, and the remaining indices all keep theirs.

use super::C;
use crate::geometry::P;
use serde::Serialize;
use std::f64::consts::PI;

/// A singular triangle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Singularity {
    /// The triangle's barycentre.
    pub at: P,
    /// The index: `+1/4` (three streets meet, as in a triangle's middle), `−1/4` (five), …
    pub index: f64,
    /// The triangle.
    pub triangle: usize,
}

/// `arg(v/u)` wrapped to `(−π, π]`.
pub fn turn(u: C, v: C) -> f64 {
    let a = (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]);
    if a <= -PI {
        PI
    } else {
        a
    }
}

/// The integer `k` of a counter-clockwise triangle's total turn `2πk`.
pub fn turns(power: &[C], tri: [usize; 3]) -> i64 {
    let [a, b, c] = tri.map(|v| power[v]);
    let total = turn(a, b) + turn(b, c) + turn(c, a);
    (total / (2.0 * PI)).round() as i64
}

/// Every triangle with a nonzero index, in triangle order, after [`cancel_pairs`].
pub fn singularities(vertices: &[P], triangles: &[[usize; 3]], power: &[C]) -> Vec<Singularity> {
    cancel_pairs(triangles, raw_singularities(vertices, triangles, power))
}

/// Every triangle with a nonzero index, in triangle order.
pub fn raw_singularities(vertices: &[P], triangles: &[[usize; 3]], power: &[C]) -> Vec<Singularity> {
    let mut out = Vec::new();
    for (t, &tri) in triangles.iter().enumerate() {
        let k = turns(power, tri);
        if k != 0 {
            let [a, b, c] = tri.map(|v| vertices[v]);
            let at = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
            out.push(Singularity { at, index: k as f64 / 4.0, triangle: t });
        }
    }
    out
}

/// Drops pairs of opposite singularities (`±1/4` and `∓1/4`) in triangles sharing a vertex,
/// closest barycentres first (ties by triangle), each singularity in at most one pair; the rest
/// keep their order.
pub fn cancel_pairs(triangles: &[[usize; 3]], found: Vec<Singularity>) -> Vec<Singularity> {
    let mut at_vertex: std::collections::BTreeMap<usize, Vec<usize>> = std::collections::BTreeMap::new();
    for (k, s) in found.iter().enumerate() {
        for v in triangles[s.triangle] {
            at_vertex.entry(v).or_default().push(k);
        }
    }
    let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
    for (i, s) in found.iter().enumerate() {
        for v in triangles[s.triangle] {
            for &j in &at_vertex[&v] {
                if i < j && s.index == -found[j].index {
                    pairs.push((crate::geometry::dist(s.at, found[j].at), i, j));
                }
            }
        }
    }
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.1, a.2).cmp(&(b.1, b.2))));
    pairs.dedup();
    let mut gone = vec![false; found.len()];
    for (_, i, j) in pairs {
        if !gone[i] && !gone[j] {
            (gone[i], gone[j]) = (true, true);
        }
    }
    found.into_iter().zip(gone).filter(|(_, g)| !g).map(|(s, _)| s).collect()
}
