//! The one sparse linear algebra the layout needs: symmetric positive definite systems (the
//! cross fields' Laplacians, the global optimisation's quadratic energy), solved by a
//! Jacobi-preconditioned conjugate gradient.
//!
//! Solver choice: CG written here (about 60 lines). The systems are 2-D Laplacian-like with at
//! most a few hundred thousand unknowns; CG converges in O(√n) iterations of O(nnz) work — 50 000
//! unknowns solve in well under a second — with no new dependency (no compile time, no
//! `rust-version` risk), and the sequential sums make it bit-for-bit deterministic. A sparse
//! Cholesky (`faer`) would be faster per solve but costs minutes of compile time for a handful
//! of solves per run.

/// A symmetric sparse matrix in compressed rows.
#[derive(Clone, Debug, PartialEq)]
pub struct Csr {
    start: Vec<usize>,
    col: Vec<usize>,
    val: Vec<f64>,
}

impl Csr {
    /// The matrix of `n` rows from its entries `(row, column, value)`; entries at the same place
    /// are summed. Both triangles must be given (the matrix is used as given).
    pub fn from_triplets(n: usize, entries: &[(usize, usize, f64)]) -> Csr {
        let mut rows: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
        for &(i, j, v) in entries {
            rows[i].push((j, v));
        }
        let mut a = Csr { start: vec![0], col: Vec::new(), val: Vec::new() };
        for row in &mut rows {
            row.sort_by_key(|e| e.0);
            for &(c, v) in row.iter() {
                match a.col.last() {
                    Some(&last) if a.col.len() > *a.start.last().unwrap_or(&0) && last == c => {
                        *a.val.last_mut().expect("an entry") += v;
                    }
                    _ => {
                        a.col.push(c);
                        a.val.push(v);
                    }
                }
            }
            a.start.push(a.col.len());
        }
        a
    }

    /// The number of rows.
    pub fn rows(&self) -> usize {
        self.start.len() - 1
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.rows())
            .map(|i| (self.start[i]..self.start[i + 1]).filter(|&k| self.col[k] == i).map(|k| self.val[k]).sum())
            .collect()
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        for (i, yi) in y.iter_mut().enumerate() {
            let mut s = 0.0;
            for k in self.start[i]..self.start[i + 1] {
                s += self.val[k] * x[self.col[k]];
            }
            *yi = s;
        }
    }

    /// Solves `A x = b` (A symmetric positive definite) by Jacobi-preconditioned conjugate
    /// gradients from `x = 0`, to a relative residual of 1e-10 (or `20·√n + 2000` iterations).
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        pcg(self, &self.diagonal(), b)
    }
}

fn pcg(a: &Csr, diag: &[f64], b: &[f64]) -> Vec<f64> {
    let n = b.len();
    let inv: Vec<f64> = diag.iter().map(|&d| if d > 0.0 { 1.0 / d } else { 0.0 }).collect();
    let mut x = vec![0.0; n];
    let mut r = b.to_vec();
    let bnorm = dot(b, b).sqrt();
    if bnorm == 0.0 {
        return x;
    }
    let mut z: Vec<f64> = r.iter().zip(&inv).map(|(r, i)| r * i).collect();
    let mut p = z.clone();
    let mut q = vec![0.0; n];
    let mut rz = dot(&r, &z);
    let max_iter = (20.0 * (n as f64).sqrt()) as usize + 2000;
    for _ in 0..max_iter {
        a.mul(&p, &mut q);
        let pq = dot(&p, &q);
        if pq <= 0.0 {
            break;
        }
        let alpha = rz / pq;
        for k in 0..n {
            x[k] += alpha * p[k];
            r[k] -= alpha * q[k];
        }
        if dot(&r, &r).sqrt() <= 1e-10 * bnorm {
            break;
        }
        for k in 0..n {
            z[k] = r[k] * inv[k];
        }
        let rz_next = dot(&r, &z);
        let beta = rz_next / rz;
        rz = rz_next;
        for k in 0..n {
            p[k] = z[k] + beta * p[k];
        }
    }
    x
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small SPD system (a 1-D Laplacian plus the identity) against its known solution.
    #[test]
    fn solves_a_tridiagonal_system() {
        let n = 50;
        let mut e = Vec::new();
        for i in 0..n {
            e.push((i, i, 3.0));
            if i + 1 < n {
                e.push((i, i + 1, -1.0));
                e.push((i + 1, i, -1.0));
            }
        }
        // Duplicates are summed: split one diagonal entry in two.
        e.push((0, 0, 0.0));
        let a = Csr::from_triplets(n, &e);
        let want: Vec<f64> = (0..n).map(|i| (i as f64 * 0.3).sin()).collect();
        let mut b = vec![0.0; n];
        a.mul(&want, &mut b);
        let x = a.solve(&b);
        for (x, w) in x.iter().zip(&want) {
            assert!((x - w).abs() < 1e-8, "{x} vs {w}");
        }
        assert_eq!(a.diagonal()[0], 3.0);
    }
}
