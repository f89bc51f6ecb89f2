//! The one linear algebra the fields need: a symmetric positive definite system with the mesh's
//! (cotangent) Laplacian, some vertices fixed (Dirichlet data), optionally screened by a lumped
//! mass matrix, for complex values — two real solves with the same matrix.
//!
//! The solve is [`crate::geometry::sparse`]'s conjugate gradient.

use super::C;
use crate::geometry::sparse::Csr;

/// Edge weights of a mesh: `(i, j, w)` with `i < j`, each edge once, sorted.
pub(super) type Weights = Vec<(usize, usize, f64)>;

/// The screening term: `(M + t·L) u = M u₀` instead of `L u = 0` on the free vertices.
pub(super) struct Screen<'a> {
    /// Lumped vertex areas (the diagonal of `M`).
    pub mass: &'a [f64],
    /// The diffusion time `t` (m²).
    pub t: f64,
    /// The data `u₀`.
    pub data: &'a [C],
}

/// Minimises `Σ w_ij |u_i − u_j|²` (plus, with a screen, `Σ m_i |u_i − u₀_i|² / t`) over the
/// vertices with `fixed[v] == None`, the others held at their value. Returns every vertex's
/// value. A free vertex with no weight to anything keeps 0 (there is none on a quality mesh).
pub(super) fn solve(n: usize, weights: &Weights, fixed: &[Option<C>], screen: Option<&Screen<'_>>) -> Vec<C> {
    let mut slot = vec![usize::MAX; n];
    let mut free = Vec::new();
    for v in 0..n {
        if fixed[v].is_none() {
            slot[v] = free.len();
            free.push(v);
        }
    }
    let m = free.len();
    let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); m];
    let mut diag = vec![0.0; m];
    let mut rhs = vec![[0.0; 2]; m];
    let scale = screen.map_or(1.0, |s| s.t);
    for &(i, j, w) in weights {
        let w = w * scale;
        for (a, b) in [(i, j), (j, i)] {
            if slot[a] == usize::MAX {
                continue;
            }
            diag[slot[a]] += w;
            match fixed[b] {
                Some(ub) => {
                    rhs[slot[a]][0] += w * ub[0];
                    rhs[slot[a]][1] += w * ub[1];
                }
                None => rows[slot[a]].push((slot[b], -w)),
            }
        }
    }
    if let Some(s) = screen {
        for (k, &v) in free.iter().enumerate() {
            diag[k] += s.mass[v];
            rhs[k][0] += s.mass[v] * s.data[v][0];
            rhs[k][1] += s.mass[v] * s.data[v][1];
        }
    }
    let mut entries = Vec::new();
    for (k, row) in rows.iter().enumerate() {
        entries.push((k, k, diag[k]));
        entries.extend(row.iter().map(|&(c, w)| (k, c, w)));
    }
    let a = Csr::from_triplets(m, &entries);
    let mut out: Vec<C> = fixed.iter().map(|f| f.unwrap_or([0.0; 2])).collect();
    // The real and imaginary parts are independent solves: two threads, the same bits.
    let part = |p: usize| a.solve(&rhs.iter().map(|r| r[p]).collect::<Vec<f64>>());
    let (re, im) = rayon::join(|| part(0), || part(1));
    for (k, &v) in free.iter().enumerate() {
        out[v] = [re[k], im[k]];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A path 0–1–2–3 with the ends fixed: the inner values interpolate linearly.
    #[test]
    fn harmonic_on_a_path_is_linear() {
        let w: Weights = vec![(0, 1, 1.0), (1, 2, 1.0), (2, 3, 1.0)];
        let fixed = [Some([0.0, 3.0]), None, None, Some([3.0, 0.0])];
        let u = solve(4, &w, &fixed, None);
        for (k, v) in u.iter().enumerate() {
            assert!((v[0] - k as f64).abs() < 1e-9 && (v[1] - (3 - k) as f64).abs() < 1e-9, "{u:?}");
        }
    }
}
