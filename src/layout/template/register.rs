//! Registration (Yang et al. 2013 §4.1, eq. 1): the map within a part's deformation class that
//! takes its template vertices nearest, in least squares, to their current positions. Every map
//! is affine, `α(p) = A p + a`; the barycentre goes to the barycentre, leaving the linear part:
//! * rigid: the Procrustes rotation `φ = atan2(Σ p×q, Σ p·q)` (centred coordinates);
//! * similarity: `c = Σ p·q / Σ|p|²`, `s = Σ p×q / Σ|p|²`, scale `√(c² + s²)` clamped to its range;
//! * stretch (the paper's constrained affine map): the Procrustes rotation, then a scale along
//!   each of the part's own axes, each the 1-D least-squares solution clamped to its range (the
//!   two-unknown quadratic program is separable);
//! * affine: `A = (Σ q pᵀ)(Σ p pᵀ)⁻¹`;
//! * affine with an area range `[lo, hi]` (the paper's area-distortion constraint, `det A` in the
//!   range): with `S = Σ p pᵀ` and `M = Σ q pᵀ`, eq. 1's energy is
//!   `E(A) = ‖A S^{1/2} − M S^{-1/2}‖²_F + const`. When the affine solution's determinant is in
//!   the range it is the answer. Otherwise `E` is convex, so the optimum lies on the bound on the
//!   determinant's side, `det A = δ`. Substituting `B = A S^{1/2}` (`det B = δ √det S =: d`) and
//!   `C = M S^{-1/2}`, the nearest `B` to `C` with `det B = d` shares `C`'s singular vectors (von
//!   Neumann's trace inequality): with `C = U diag(σ1, σ2) Vᵀ` (`U`, `V` rotations,
//!   `σ1 ≥ |σ2|`, `σ2` carrying the sign of `det C`), `B = U diag(x, d/x) Vᵀ` for the `x > 0`
//!   minimising `(σ1 − x)² + (σ2 − d/x)²`: sampled on a logarithmic grid over a bracket that
//!   must hold it, then refined by golden-section search around the best sample. Then
//!   `A = B S^{-1/2}`.
//!
//! With the points on a line (`S` singular) both affine classes fall back to a similarity, its
//! scale free for affine and within `[√lo, √hi]` for an area range.

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

type M2 = [[f64; 2]; 2];

/// `(Σ p pᵀ, Σ q pᵀ)` over centred coordinates.
fn moments(p: &[P], q: &[P]) -> (M2, M2) {
    let (mut m, mut qp) = ([[0.0; 2]; 2], [[0.0; 2]; 2]);
    for (a, b) in p.iter().zip(q) {
        for i in 0..2 {
            for j in 0..2 {
                m[i][j] += a[i] * a[j];
                qp[i][j] += b[i] * a[j];
            }
        }
    }
    (m, qp)
}

fn determinant(m: M2) -> f64 {
    m[0][0] * m[1][1] - m[0][1] * m[1][0]
}

/// Whether the symmetric `Σ p pᵀ` is (numerically) singular: the points lie on a line.
fn singular(m: M2) -> bool {
    determinant(m).abs() <= 1e-12 * (m[0][0] + m[1][1]).powi(2).max(f64::MIN_POSITIVE)
}

fn inverse(m: M2) -> M2 {
    let det = determinant(m);
    [[m[1][1] / det, -m[0][1] / det], [-m[1][0] / det, m[0][0] / det]]
}

fn mul(a: M2, b: M2) -> M2 {
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j];
        }
    }
    c
}

/// The square root of a symmetric positive definite `S`: `(S + √det S I) / √(tr S + 2√det S)`.
fn sqrt_spd(s: M2) -> M2 {
    let r = determinant(s).sqrt();
    let k = (s[0][0] + s[1][1] + 2.0 * r).sqrt();
    [[(s[0][0] + r) / k, s[0][1] / k], [s[1][0] / k, (s[1][1] + r) / k]]
}

/// The signed singular value decomposition `C = R(φ) diag(σ1, σ2) R(θ)` (`R` a rotation,
/// `σ1 ≥ |σ2|`, `σ2` of the sign of `det C`): returns `(φ, [σ1, σ2], θ)`.
fn svd(c: M2) -> (f64, [f64; 2], f64) {
    let (e, h) = ((c[0][0] + c[1][1]) / 2.0, (c[1][0] - c[0][1]) / 2.0);
    let (f, g) = ((c[0][0] - c[1][1]) / 2.0, (c[1][0] + c[0][1]) / 2.0);
    let (q, r) = (e.hypot(h), f.hypot(g));
    let (alpha, psi) = (h.atan2(e), g.atan2(f));
    ((alpha + psi) / 2.0, [q + r, q - r], (alpha - psi) / 2.0)
}

/// The linear part with `det A = delta` nearest in eq. 1's energy, `S = m`, `M = qp` (module doc).
fn area_fit(m: M2, qp: M2, delta: f64) -> M2 {
    let root = sqrt_spd(m);
    let root_inv = inverse(root);
    let d = delta * determinant(root);
    let (phi, sigma, theta) = svd(mul(qp, root_inv));
    let x = nearest_split(sigma, d);
    mul(rotation(phi, x, d / x), mul(rotation(theta, 1.0, 1.0), root_inv))
}

/// The `x > 0` minimising `(σ1 − x)² + (σ2 − d/x)²` (`d > 0`). Any `x` no worse than `√d` has
/// `|σ1 − x|` and `|σ2 − d/x|` at most `√f(√d)`, which brackets the minimum; it is sampled on a
/// logarithmic grid, then refined by golden-section search between the best sample's neighbours.
fn nearest_split(sigma: [f64; 2], d: f64) -> f64 {
    const SAMPLES: usize = 4096;
    let f = |t: f64| {
        let x = t.exp();
        (sigma[0] - x).powi(2) + (sigma[1] - d / x).powi(2)
    };
    let reach = f(0.5 * d.ln()).sqrt();
    let (lo, hi) = ((d / (sigma[1].abs() + reach)).ln(), (sigma[0] + reach).ln());
    if lo.is_nan() || hi.is_nan() || hi <= lo {
        return d.sqrt();
    }
    let at = |k: usize| lo + (hi - lo) * k as f64 / SAMPLES as f64;
    let best = (0..=SAMPLES).min_by(|&a, &b| f(at(a)).total_cmp(&f(at(b)))).unwrap_or(0);
    let t = golden(&f, at(best.saturating_sub(1)), at((best + 1).min(SAMPLES)));
    if f(t) <= f(at(best)) {
        t.exp()
    } else {
        at(best).exp()
    }
}

/// Golden-section search for a minimum of `f` on `[a, b]`.
fn golden(f: &impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut c, mut d) = (b - g * (b - a), a + g * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..100 {
        if fc < fd {
            (b, d, fd) = (d, c, fc);
            c = b - g * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    (a + b) / 2.0
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
            let (m, qp) = moments(&p, &q);
            if singular(m) {
                return register(src, dst, Class::Similarity { scale: [0.0, f64::INFINITY] });
            }
            mul(qp, inverse(m))
        }
        Class::AreaAffine { area } => {
            let (m, qp) = moments(&p, &q);
            if singular(m) {
                return register(src, dst, Class::Similarity { scale: [area[0].sqrt(), area[1].sqrt()] });
            }
            let free = mul(qp, inverse(m));
            let det = determinant(free);
            if area[0] <= det && det <= area[1] {
                free
            } else {
                area_fit(m, qp, det.clamp(area[0], area[1]))
            }
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

    /// The least rms over a fine sampling of every linear part with determinant `det`,
    /// `R(φ) diag(x, det/x) R(θ)`, each with its best translation.
    fn sampled_min(dst: &[P], det: f64) -> f64 {
        let (cs, cd) = (centroid(&SQ), centroid(dst));
        let mut best = f64::INFINITY;
        for i in 0..90 {
            for j in 0..90 {
                for k in 0..=60 {
                    let (phi, theta) = (i as f64 * 4.0f64.to_radians(), j as f64 * 4.0f64.to_radians());
                    let x = (-1.5 + 3.0 * k as f64 / 60.0).exp();
                    let (s, c) = theta.sin_cos();
                    let a = mul(rotation(phi, x, det / x), [[c, -s], [s, c]]);
                    let t = [cd[0] - (a[0][0] * cs[0] + a[0][1] * cs[1]), cd[1] - (a[1][0] * cs[0] + a[1][1] * cs[1])];
                    best = best.min(rms(&Affine { a, t }, &SQ, dst));
                }
            }
        }
        best
    }

    #[test]
    fn signed_svd_reconstructs() {
        for c in [[[1.2, 0.3], [-0.1, 0.9]], [[1.1, 0.2], [0.1, -0.9]], [[0.0, -2.0], [0.5, 0.0]]] {
            let (phi, sigma, theta) = svd(c);
            let back = mul(rotation(phi, sigma[0], sigma[1]), rotation(theta, 1.0, 1.0));
            assert!(sigma[0] >= sigma[1].abs() && sigma[1].signum() == determinant(c).signum());
            assert!((0..4).all(|k| (back[k / 2][k % 2] - c[k / 2][k % 2]).abs() < 1e-12), "{back:?}");
        }
        let s = [[3.0, 1.0], [1.0, 2.0]];
        let r = sqrt_spd(s);
        let back = mul(r, r);
        assert!((0..4).all(|k| (back[k / 2][k % 2] - s[k / 2][k % 2]).abs() < 1e-12), "{back:?}");
    }

    #[test]
    fn area_affine_within_its_range_is_the_affine_fit() {
        let a = [[1.2, 0.3], [-0.1, 0.9]];
        let dst = map(a, [1.0, 2.0]);
        let r = register(&SQ, &dst, Class::AreaAffine { area: [0.8, 1.25] });
        assert!(rms(&r, &SQ, &dst) < 1e-9);
        assert_eq!(r, register(&SQ, &dst, Class::Affine));
    }

    /// A fit to `a`'s image within `[0.8, 1.25]`: its determinant is `det`, and no sampled linear
    /// part of that determinant does better.
    fn bounded_fit(a: [[f64; 2]; 2], det: f64) {
        let dst = map(a, [3.0, -4.0]);
        let r = register(&SQ, &dst, Class::AreaAffine { area: [0.8, 1.25] });
        assert!((determinant(r.a) - det).abs() < 1e-9, "{}", determinant(r.a));
        let (found, sampled) = (rms(&r, &SQ, &dst), sampled_min(&dst, det));
        assert!(found <= sampled + 1e-9, "{found} > {sampled}");
        assert!(found > 1e-3, "{found}");
    }

    #[test]
    fn area_affine_above_its_range_stops_at_the_upper_bound() {
        bounded_fit([[1.5, 0.4], [0.2, 1.0 + 0.08 / 1.5]], 1.25);
    }

    #[test]
    fn area_affine_below_its_range_stops_at_the_lower_bound() {
        bounded_fit([[0.9, -0.3], [0.2, 0.5]], 0.8);
    }

    #[test]
    fn area_affine_of_a_reflection_keeps_its_orientation() {
        bounded_fit([[1.1, 0.2], [0.1, -0.9]], 0.8);
    }
}
