//! Registration (Yang et al. 2013 §4.1, eq. 1): the map within a part's deformation class that
//! takes its template vertices nearest, in least squares, to their current positions. Every map
//! is affine, `α(p) = A p + a`; the barycentre goes to the barycentre, leaving the linear part:
//! * rigid: the Procrustes rotation `φ = atan2(Σ p×q, Σ p·q)` (centred coordinates);
//! * similarity: `c = Σ p·q / Σ|p|²`, `s = Σ p×q / Σ|p|²`, scale `√(c² + s²)` clamped to its range;
//! * stretch (the paper's constrained affine map): the Procrustes rotation, then a scale along
//!   each of the part's own axes, each the 1-D least-squares solution clamped to its range (the
//!   two-unknown quadratic program is separable);
//! * affine: `A = (Σ q pᵀ)(Σ p pᵀ)⁻¹`.

use super::file::Class;
use crate::geometry::{cross, dist, dot, P};

/// An affine map `p ↦ A p + t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// The linear part, row major.
    pub a: [[f64; 2]; 2],
    /// The translation.
    pub t: P,
}

impl Affine {
    /// The image of `p`.
    pub fn apply(&self, p: P) -> P {
        let a = &self.a;
        [a[0][0] * p[0] + a[0][1] * p[1] + self.t[0], a[1][0] * p[0] + a[1][1] * p[1] + self.t[1]]
    }
}

fn centroid(p: &[P]) -> P {
    let n = p.len().max(1) as f64;
    let s = p.iter().fold([0.0, 0.0], |a, q| [a[0] + q[0], a[1] + q[1]]);
    [s[0] / n, s[1] / n]
}

fn rotation(phi: f64, sx: f64, sy: f64) -> [[f64; 2]; 2] {
    let (s, c) = phi.sin_cos();
    [[c * sx, -s * sy], [s * sx, c * sy]]
}

/// The map of the class taking `src` nearest to `dst` (equal lengths).
pub fn register(src: &[P], dst: &[P], class: Class) -> Affine {
    let (cs, cd) = (centroid(src), centroid(dst));
    let p: Vec<P> = src.iter().map(|v| [v[0] - cs[0], v[1] - cs[1]]).collect();
    let q: Vec<P> = dst.iter().map(|v| [v[0] - cd[0], v[1] - cd[1]]).collect();
    let (sd, sc, spp) = p
        .iter()
        .zip(&q)
        .fold((0.0, 0.0, 0.0), |(d, c, n), (a, b)| (d + dot(*a, *b), c + cross(*a, *b), n + dot(*a, *a)));
    let phi = sc.atan2(sd);
    let a = match class {
        Class::Rigid => rotation(phi, 1.0, 1.0),
        Class::Similarity { scale } => {
            let lambda = if spp > 0.0 { sd.hypot(sc) / spp } else { 1.0 };
            let l = lambda.clamp(scale[0], scale[1]);
            rotation(phi, l, l)
        }
        Class::Stretch { x, y } => {
            let (s, c) = phi.sin_cos();
            // q rotated back by φ, against p along each axis.
            let (mut nx, mut dx, mut ny, mut dy) = (0.0, 0.0, 0.0, 0.0);
            for (a, b) in p.iter().zip(&q) {
                let r = [c * b[0] + s * b[1], -s * b[0] + c * b[1]];
                nx += a[0] * r[0];
                dx += a[0] * a[0];
                ny += a[1] * r[1];
                dy += a[1] * a[1];
            }
            let sx = if dx > 0.0 { nx / dx } else { 1.0 };
            let sy = if dy > 0.0 { ny / dy } else { 1.0 };
            rotation(phi, sx.clamp(x[0], x[1]), sy.clamp(y[0], y[1]))
        }
        Class::Affine => {
            let (mut m, mut qp) = ([[0.0; 2]; 2], [[0.0; 2]; 2]);
            for (a, b) in p.iter().zip(&q) {
                for i in 0..2 {
                    for j in 0..2 {
                        m[i][j] += a[i] * a[j];
                        qp[i][j] += b[i] * a[j];
                    }
                }
            }
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            if det.abs() <= 1e-12 * (m[0][0] + m[1][1]).powi(2).max(f64::MIN_POSITIVE) {
                return register(src, dst, Class::Similarity { scale: [0.0, f64::INFINITY] });
            }
            let inv = [[m[1][1] / det, -m[0][1] / det], [-m[1][0] / det, m[0][0] / det]];
            let mut a = [[0.0; 2]; 2];
            for i in 0..2 {
                for j in 0..2 {
                    a[i][j] = qp[i][0] * inv[0][j] + qp[i][1] * inv[1][j];
                }
            }
            a
        }
    };
    let t = [cd[0] - (a[0][0] * cs[0] + a[0][1] * cs[1]), cd[1] - (a[1][0] * cs[0] + a[1][1] * cs[1])];
    Affine { a, t }
}

/// The root mean square distance between `α(src)` and `dst`.
pub fn rms(alpha: &Affine, src: &[P], dst: &[P]) -> f64 {
    let n = src.len().max(1) as f64;
    (src.iter().zip(dst).map(|(&s, &d)| dist(alpha.apply(s), d).powi(2)).sum::<f64>() / n).sqrt()
}

/// The mean distance between `α(src)` and `dst`.
pub fn mean_distance(alpha: &Affine, src: &[P], dst: &[P]) -> f64 {
    let n = src.len().max(1) as f64;
    src.iter().zip(dst).map(|(&s, &d)| dist(alpha.apply(s), d)).sum::<f64>() / n
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQ: [P; 5] = [[0.0, 0.0], [18.0, 0.0], [18.0, 30.0], [0.0, 30.0], [7.0, 11.0]];

    fn map(a: [[f64; 2]; 2], t: P) -> Vec<P> {
        SQ.iter().map(|&p| Affine { a, t }.apply(p)).collect()
    }

    #[test]
    fn procrustes_recovers_a_known_similarity() {
        let a = rotation(0.4, 1.3, 1.3);
        let dst = map(a, [5.0, -2.0]);
        let r = register(&SQ, &dst, Class::Similarity { scale: [0.5, 2.0] });
        assert!(rms(&r, &SQ, &dst) < 1e-9);
        assert!((r.a[0][0] - a[0][0]).abs() < 1e-12 && (r.a[1][0] - a[1][0]).abs() < 1e-12);
        // A rigid fit keeps the rotation, loses the scale; a clamped similarity stops at its bound.
        let rigid = register(&SQ, &dst, Class::Rigid);
        assert!((rigid.a[1][0] - 0.4f64.sin()).abs() < 1e-12);
        let bounded = register(&SQ, &dst, Class::Similarity { scale: [0.9, 1.1] });
        assert!((bounded.a[0][0].hypot(bounded.a[1][0]) - 1.1).abs() < 1e-12);
    }

    #[test]
    fn affine_and_stretch_fits() {
        let a = [[1.2, 0.3], [-0.1, 0.9]];
        let dst = map(a, [1.0, 2.0]);
        let r = register(&SQ, &dst, Class::Affine);
        assert!(rms(&r, &SQ, &dst) < 1e-9);
        let s = rotation(-0.3, 1.1, 0.95);
        let dst = map(s, [3.0, 4.0]);
        let r = register(&SQ, &dst, Class::Stretch { x: [0.8, 1.25], y: [0.8, 1.25] });
        assert!(rms(&r, &SQ, &dst) < 0.05, "{}", rms(&r, &SQ, &dst));
        let r = register(&SQ, &dst, Class::Stretch { x: [1.0, 1.0], y: [1.0, 1.0] });
        assert!(rms(&r, &SQ, &dst) > 0.1);
    }
}
