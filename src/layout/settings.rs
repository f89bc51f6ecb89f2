//! A region's settings of the control loop: the block size, the fit thresholds and the weights
//! of the streamline scores (TOML `[block]`, `[fit]`, `[weights]`; GeoJSON properties
//! `block_width`, `block_length`, `fit_threshold`). Where the paper gives a value it is the
//! default; otherwise netspec's, as `docs/layout.md`'s deviations table lists.

use serde::{Deserialize, Serialize};

/// The block every cut aims for.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BlockSize {
    /// Centreline to centreline across a double-loaded block (metres; the paper's 75 m:
    /// `2 · depth + street`): the widths the boundary-fit score explains distances by.
    pub width: f64,
    /// The longest block along its street (metres): no template is repeated beyond it, and a
    /// part longer than it is cut.
    pub max_length: f64,
}

/// When a part is settled.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fit {
    /// A template is accepted below this energy (mean registration distance over the square root
    /// of the block's area) unless its file sets its own.
    pub threshold: f64,
    /// A part no template matches is not cut further when its inscribed width is at most this
    /// many block widths and it is no longer than [`BlockSize::max_length`].
    pub max_width: f64,
    /// … or when it is smaller than this many parcels.
    pub min_parcels: f64,
    /// A part round a hole that no streamline crosses is cut by two streamlines from its outer
    /// ring to the hole (§5's split along several streamlines) instead of being settled whole.
    pub round_holes: bool,
}

/// The weights λ of the four streamline scores (the paper's are all 1).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Weights {
    /// Divergence.
    #[serde(default = "one")]
    pub divergence: f64,
    /// Fit of the distances to the boundary with block widths.
    #[serde(default = "one")]
    pub boundary: f64,
    /// Nearness to singularities.
    #[serde(default = "one")]
    pub singularities: f64,
    /// Continuity with earlier street ends.
    #[serde(default = "one")]
    pub continuity: f64,
}

impl Default for Weights {
    fn default() -> Self {
        Weights { divergence: 1.0, boundary: 1.0, singularities: 1.0, continuity: 1.0 }
    }
}

impl Weights {
    /// In the order of the scores: divergence, boundary, singularities, continuity.
    pub fn as_array(&self) -> [f64; 4] {
        [self.divergence, self.boundary, self.singularities, self.continuity]
    }
}

fn one() -> f64 {
    1.0
}

/// The default energy threshold of a template.
pub const DEFAULT_THRESHOLD: f64 = 0.02;
/// The default longest block, in parcel widths.
pub const DEFAULT_LENGTH_PARCELS: f64 = 14.0;
/// The default widest part left uncut, in block widths.
pub const DEFAULT_MAX_WIDTH: f64 = 1.35;
/// The default smallest part cut, in parcels.
pub const DEFAULT_MIN_PARCELS: f64 = 4.0;

/// `[block]` as written.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockToml {
    /// Overrides [`BlockSize::width`].
    #[serde(default)]
    pub width: Option<f64>,
    /// Overrides [`BlockSize::max_length`].
    #[serde(default)]
    pub max_length: Option<f64>,
}

/// `[fit]` as written.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitToml {
    /// Overrides [`Fit::threshold`].
    #[serde(default)]
    pub threshold: Option<f64>,
    /// Overrides [`Fit::max_width`].
    #[serde(default)]
    pub max_width: Option<f64>,
    /// Overrides [`Fit::min_parcels`].
    #[serde(default)]
    pub min_parcels: Option<f64>,
    /// Overrides [`Fit::round_holes`] (off by default).
    #[serde(default)]
    pub round_holes: Option<bool>,
}

impl BlockToml {
    /// The block size, defaults from the parcel size and the first split's street width.
    pub fn resolve(&self, depth: f64, width: f64, street: f64) -> BlockSize {
        BlockSize {
            width: self.width.unwrap_or(2.0 * depth + street),
            max_length: self.max_length.unwrap_or(DEFAULT_LENGTH_PARCELS * width),
        }
    }
}

impl FitToml {
    /// The thresholds, defaults filled in.
    pub fn resolve(&self) -> Fit {
        Fit {
            threshold: self.threshold.unwrap_or(DEFAULT_THRESHOLD),
            max_width: self.max_width.unwrap_or(DEFAULT_MAX_WIDTH),
            min_parcels: self.min_parcels.unwrap_or(DEFAULT_MIN_PARCELS),
            round_holes: self.round_holes.unwrap_or(false),
        }
    }
}

/// Every setting that must be a positive number, by its TOML key.
pub fn positive_fields(block: &BlockSize, fit: &Fit) -> [(&'static str, f64); 5] {
    [
        ("block.width", block.width),
        ("block.max_length", block.max_length),
        ("fit.threshold", fit.threshold),
        ("fit.max_width", fit.max_width),
        ("fit.min_parcels", fit.min_parcels),
    ]
}

/// Why the weights are refused, if they are: each must be a finite number at least 0, and one
/// of them positive.
pub fn check_weights(w: &Weights) -> Option<(&'static str, f64)> {
    let named = [
        ("weights.divergence", w.divergence),
        ("weights.boundary", w.boundary),
        ("weights.singularities", w.singularities),
        ("weights.continuity", w.continuity),
    ];
    if let Some(&bad) = named.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
        return Some(bad);
    }
    (named.iter().map(|(_, v)| v).sum::<f64>() <= 0.0).then_some(("weights", 0.0))
}
