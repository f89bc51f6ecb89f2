//! Street orientations: the bearing histogram, its Shannon entropy and Boeing's order φ
//! (Boeing 2019, "Urban spatial order: street network orientation, configuration, and entropy",
//! Applied Network Science 4:67), as `osmnx.bearing.orientation_entropy` computes them; and the
//! axial histogram in bits that `netspec grow` reports per era.

use crate::geometry::{sub, P};

/// Bins of OSMnx's histogram (10° each).
pub const BINS: usize = 36;

/// The compass bearing of the chord from `a` to `b`, degrees in `[0, 360)`, 0 north, clockwise
/// (local metres: north is +y). `None` for a zero-length chord.
pub fn bearing(a: P, b: P) -> Option<f64> {
    let d = sub(b, a);
    if d[0] == 0.0 && d[1] == 0.0 {
        return None;
    }
    Some(d[0].atan2(d[1]).to_degrees().rem_euclid(360.0))
}

/// OSMnx's bin of a bearing: 36 bins of 10° centred on 0°, 10°, …, 350° (the first spans
/// 355°–5°), each bin's lower edge included.
pub fn bin(bearing: f64) -> usize {
    (((bearing + 5.0).rem_euclid(360.0) / 10.0) as usize).min(BINS - 1)
}

/// The length-weighted histogram of undirected streets: each street's chord bearing and its
/// reverse, both with the street's weight (OSMnx on an undirected graph with
/// `weight="length"`).
#[derive(Clone, Debug, PartialEq)]
pub struct Histogram {
    /// Weight per bin.
    pub bins: [f64; BINS],
}

impl Default for Histogram {
    fn default() -> Self {
        Histogram { bins: [0.0; BINS] }
    }
}

impl Histogram {
    /// Adds a street whose chord runs from `a` to `b`, with `weight` (its length).
    pub fn add(&mut self, a: P, b: P, weight: f64) {
        if let Some(t) = bearing(a, b) {
            self.bins[bin(t)] += weight;
            self.bins[bin((t + 180.0).rem_euclid(360.0))] += weight;
        }
    }

    /// The Shannon entropy in nats of the bin shares (`scipy.stats.entropy`); `None` when empty.
    pub fn entropy(&self) -> Option<f64> {
        entropy_nats(&self.bins)
    }
}

/// The Shannon entropy (nats) of weights normalised to shares; `None` when they sum to zero.
pub fn entropy_nats(weights: &[f64]) -> Option<f64> {
    let total: f64 = weights.iter().sum();
    (total > 0.0).then(|| -weights.iter().filter(|&&w| w > 0.0).map(|&w| (w / total) * (w / total).ln()).sum::<f64>())
}

/// Boeing's orientation order φ = 1 − ((H − H_g) / (H_max − H_g))², H_g = ln 4 (a perfect
/// grid), H_max = ln 36 (uniform): 1 for a grid, 0 for no order.
pub fn order(entropy: f64) -> f64 {
    let (hg, hmax) = (4f64.ln(), (BINS as f64).ln());
    1.0 - ((entropy - hg) / (hmax - hg)).powi(2)
}

/// The axial histogram `netspec grow` reports per era: segment directions modulo 180° (from
/// the +x axis) in `bins` equal bins, weighted by length, and its entropy in bits (0 when
/// empty).
pub fn axial_entropy_bits(segments: impl IntoIterator<Item = (P, P)>, bins: usize) -> f64 {
    let mut w = vec![0.0f64; bins];
    for (a, b) in segments {
        let d = sub(b, a);
        let ang = d[1].atan2(d[0]).rem_euclid(std::f64::consts::PI);
        w[((ang / std::f64::consts::PI * bins as f64) as usize).min(bins - 1)] += crate::geometry::norm(d);
    }
    entropy_nats(&w).map_or(0.0, |h| h / std::f64::consts::LN_2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_are_centred_on_the_compass_directions() {
        assert_eq!(bin(0.0), 0);
        assert_eq!(bin(4.999), 0);
        assert_eq!(bin(5.0), 1);
        assert_eq!(bin(355.0), 0);
        assert_eq!(bin(354.999), 35);
        assert_eq!(bin(90.0), 9);
        assert_eq!(bearing([0.0, 0.0], [1.0, 0.0]), Some(90.0));
        assert_eq!(bearing([0.0, 0.0], [0.0, -1.0]), Some(180.0));
    }

    #[test]
    fn a_grid_has_entropy_ln4_and_order_one() {
        let mut h = Histogram::default();
        h.add([0.0, 0.0], [100.0, 0.0], 100.0);
        h.add([0.0, 0.0], [0.0, 100.0], 100.0);
        assert!((h.entropy().unwrap() - 4f64.ln()).abs() < 1e-12);
        assert!((order(4f64.ln()) - 1.0).abs() < 1e-12);
        assert!(order(36f64.ln()).abs() < 1e-12);
        assert_eq!(Histogram::default().entropy(), None);
        // One direction in 18 axial bins: 0 bits; two equal directions: 1 bit.
        assert_eq!(axial_entropy_bits([([0.0, 0.0], [1.0, 0.0])], 18), 0.0);
        let two = axial_entropy_bits([([0.0, 0.0], [1.0, 0.0]), ([0.0, 0.0], [0.0, 1.0])], 18);
        assert!((two - 1.0).abs() < 1e-12);
    }
}
