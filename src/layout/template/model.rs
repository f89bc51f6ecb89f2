//! A template as the matching uses it: labelled faces, streets, sides and corners of the
//! matching, and how it repeats ([`super::file`] reads them from TOML).

use crate::geometry::P;
use crate::layout::Use;
use serde::Deserialize;

/// How a part of a template may deform (Yang et al. 2013 §4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Class {
    /// Rotation and translation.
    Rigid,
    /// Rotation, translation and a uniform scale within `[lo, hi]`.
    Similarity {
        /// The scale range.
        scale: [f64; 2],
    },
    /// A rotation, then scales along the part's own x and y axes within their ranges (the
    /// paper's constrained affine map: a rectangle stays a rectangle).
    Stretch {
        /// The x scale range.
        x: [f64; 2],
        /// The y scale range.
        y: [f64; 2],
    },
    /// Any affine map.
    Affine,
    /// An affine map whose determinant, the ratio of areas, lies within `[lo, hi]` (the paper's
    /// affine map with area-distortion constraints; reflections excluded).
    AreaAffine {
        /// The area ratio range.
        area: [f64; 2],
    },
}

/// What a template's boundary side may meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SideKind {
    /// A street.
    Street,
    /// No street.
    None,
    /// Either.
    Any,
}

/// A corner's type, for matching template corners to a block's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CornerKind {
    /// Turns left (counter-clockwise boundary).
    Convex,
    /// Turns right.
    Concave,
    /// Not a corner (a regular boundary point).
    None,
}

/// What a face of a template becomes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fill {
    /// A parcel of this use (a residential face without street access becomes a park).
    Use(Use),
    /// An area face: filled by an area template (`kind = "area"`), or by the row parceller when
    /// none fits.
    Area,
}

/// A face of a template: a parcel, park, commercial, school or other piece, or an area face.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// Its polygon (template metres, counter-clockwise).
    pub polygon: Vec<P>,
    /// What it becomes.
    pub fill: Fill,
    /// Its deformation class.
    pub class: Class,
    /// The largest RMS registration distance it may keep (metres); also its weight `1/ε` when
    /// shared vertices are merged.
    pub tolerance: f64,
}

/// The repetition of a unit strip of a template (a row of N parcels, N chosen by the fit).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Repeat {
    /// 0 for x, 1 for y.
    pub axis: usize,
    /// The unit strip `[from, to]` along the axis; faces inside it are copied, points beyond
    /// it shifted.
    pub unit: [f64; 2],
    /// Fewest units.
    pub min: usize,
    /// Most units.
    pub max: usize,
}

/// A template, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Template {
    /// Its name (the file stem unless given).
    pub name: String,
    /// The label of the region it fills, one of [`LABELS`]: a template matches a part only when
    /// the labels agree (the paper's first condition of a match).
    pub kind: String,
    /// Its faces.
    pub faces: Vec<Face>,
    /// Street centrelines along face edges (each point a face vertex; the first on the boundary).
    pub streets: Vec<Vec<P>>,
    /// Side kinds: (a point on the side, its kind).
    pub sides: Vec<(P, SideKind)>,
    /// Corner overrides: (the vertex, its kind).
    pub corners: Vec<(P, CornerKind)>,
    /// The repetition, if any.
    pub repeat: Option<Repeat>,
    /// At most this many uses in a layout.
    pub max_uses: Option<usize>,
    /// At least this many uses (met by backtracking where the parts allow; reported otherwise).
    pub min_uses: usize,
    /// How common it is (the weight of its choice, with its energy; default 1).
    pub probability: f64,
    /// Accepted when its energy is below this (default: the region's `[fit] threshold`).
    pub threshold: Option<f64>,
    /// The file it came from (`builtin:row.toml` for embedded ones).
    pub source: String,
}
