//! Singularities of a cross field stored as `u = e^{4iθ}` per vertex: around a
//! counter-clockwise triangle `(a, b, c)` the turns `Δ_ab = arg(u_b/u_a)` (wrapped to `(−π, π]`),
//! `Δ_bc`, `Δ_ca` sum to `2πk`; the triangle holds a singularity of index `k/4` (a cross turns by
//! a quarter of `u`'s turn). The sign follows the orientation: `u = z` around a counter-clockwise
//! triangle is `+1/4`, `u = z̄` is `−1/4` (libigl's version reports every index as positive).

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

/// Every triangle with a nonzero index, in triangle order.
pub fn singularities(vertices: &[P], triangles: &[[usize; 3]], power: &[C]) -> Vec<Singularity> {
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
