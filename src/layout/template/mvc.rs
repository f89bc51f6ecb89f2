//! Mean-value coordinates (Floater 2003; Hormann and Floater 2006 for any simple polygon): the
//! weights that write a point as an affine combination of a polygon's vertices. They reproduce
//! affine maps exactly, so an undistorted boundary gives an undistorted interior.

use crate::geometry::{cross, dist, dot, norm, sub, P};

/// The mean-value coordinates of `x` with respect to the polygon `poly` (either orientation);
/// they sum to one. A point on a vertex or an edge gets that vertex or the edge's linear weights.
pub fn mean_value_coordinates(poly: &[P], x: P) -> Vec<f64> {
    let n = poly.len();
    let d: Vec<P> = poly.iter().map(|&v| sub(v, x)).collect();
    let r: Vec<f64> = d.iter().map(|&v| norm(v)).collect();
    let scale = poly.iter().map(|&v| dist(v, poly[0])).fold(0.0, f64::max).max(1e-300);
    let eps = 1e-12 * scale;
    let mut w = vec![0.0; n];
    if let Some(i) = r.iter().position(|&ri| ri <= eps) {
        w[i] = 1.0;
        return w;
    }
    // tan(α_i / 2) for the angle at x between v_i and v_{i+1}; on an edge, linear weights.
    let mut t = vec![0.0; n];
    for i in 0..n {
        let j = (i + 1) % n;
        let c = cross(d[i], d[j]);
        let s = dot(d[i], d[j]);
        if c.abs() <= eps * (r[i] + r[j]) && s < 0.0 {
            w[i] = r[j] / (r[i] + r[j]);
            w[j] = r[i] / (r[i] + r[j]);
            return w;
        }
        // tan(α/2) = sin α / (1 + cos α), stable when x lies on the line of an edge beyond it.
        t[i] = c / (r[i] * r[j] + s);
    }
    for i in 0..n {
        w[i] = (t[(i + n - 1) % n] + t[i]) / r[i];
    }
    let sum: f64 = w.iter().sum();
    w.iter_mut().for_each(|v| *v /= sum);
    w
}

/// `Σ w_i p_i`.
pub fn combine(w: &[f64], pts: &[P]) -> P {
    w.iter().zip(pts).fold([0.0, 0.0], |acc, (&wi, p)| [acc[0] + wi * p[0], acc[1] + wi * p[1]])
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: [P; 6] = [[0.0, 0.0], [4.0, 0.0], [4.0, 1.0], [1.0, 1.0], [1.0, 3.0], [0.0, 3.0]];

    #[test]
    fn partition_of_unity_and_linear_precision() {
        for x in [[0.5, 0.5], [3.0, 0.5], [0.5, 2.5], [1.0, 0.5], [0.9, 0.9]] {
            let w = mean_value_coordinates(&L, x);
            assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{w:?}");
            let p = combine(&w, &L);
            assert!(dist(p, x) < 1e-12, "{x:?} → {p:?}");
        }
    }

    #[test]
    fn affine_maps_are_reproduced_exactly() {
        let f = |p: P| [2.0 * p[0] - 0.7 * p[1] + 5.0, 0.3 * p[0] + 1.5 * p[1] - 2.0];
        let image: Vec<P> = L.iter().map(|&p| f(p)).collect();
        for x in [[0.5, 0.5], [3.5, 0.2], [0.2, 2.8], [0.5, 1.7]] {
            let w = mean_value_coordinates(&L, x);
            assert!(dist(combine(&w, &image), f(x)) < 1e-12);
        }
        // On an edge and on a vertex.
        assert_eq!(mean_value_coordinates(&L, [2.0, 0.0])[..2], [0.5, 0.5]);
        assert_eq!(mean_value_coordinates(&L, [4.0, 1.0])[2], 1.0);
    }
}
