//! Urban layouts by hierarchical domain splitting (Yang, Wang, Vouga, Wonka 2013): every part of
//! a region is matched against a library of templates first and split along a streamline of a
//! boundary-aligned cross field only where none fits, down to parcels ([`tree`]).

pub mod fallback;
pub mod field;
pub mod metrics;
pub mod optimise;
pub mod parcels;
pub mod region;
pub mod relayout;
pub mod run;
pub mod settings;
pub mod skeleton;
pub mod split;
pub mod streamline;
pub mod template;
pub mod tree;
pub mod validate;
pub mod zone;

use crate::geometry::P;
use serde::{Deserialize, Serialize};

/// A street: its centreline, width and level (0: major roads and the boundary street; 1: the
/// first split; …).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Street {
    /// The centreline.
    pub polyline: Vec<P>,
    /// The width (metres).
    pub width: f64,
    /// The level.
    pub level: usize,
    /// The part of the layout's tree whose split made it (`""`: given, or not from a layout).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub part: String,
}

impl Street {
    /// A street of no part.
    pub fn new(polyline: Vec<P>, width: f64, level: usize) -> Street {
        Street { polyline, width, level, part: String::new() }
    }
}

/// What a parcel is used for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Use {
    /// Houses: a parcel with street access.
    Residential,
    /// Green space: a parcel without street access inside a block.
    Park,
    /// Shops and offices.
    Commercial,
    /// A school and its grounds.
    School,
    /// Land kept as it is (a `keep` zone).
    Keep,
    /// Remnants too small or too thin to build on.
    Other,
}

/// The label of a part between streets.
pub const BLOCK: &str = "block";

/// How a part was split or settled.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum How {
    /// Cut along the given major roads, and the zones set apart.
    Given,
    /// Cut along a streamline.
    Streamline,
    /// Settled by a template.
    Template,
    /// Parcelled by the row parceller (no template accepted).
    Rows,
    /// Parcelled by the straight-skeleton parceller (no template accepted, and the rows leave
    /// more undesirable parcels).
    Skeleton,
    /// A zone no template of its use fills: one parcel of its use.
    Zone,
}

/// A parcel.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Parcel {
    /// Its boundary, counter-clockwise, not closed.
    pub polygon: Vec<P>,
    /// Its use.
    #[serde(rename = "use")]
    pub use_: Use,
    /// The template it comes from (`None`: the row parceller).
    #[serde(default)]
    pub template: Option<String>,
    /// The leaf of the layout's tree it lies in (`""`: not from a layout).
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub part: String,
    /// A template parcel's registration distance to its ideal (metres): the mean distance of the
    /// face's vertices from the template face registered onto them by a similarity.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub registration: Option<f64>,
    /// A template parcel's ideal area (m²): its template face's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ideal: Option<f64>,
}

impl Parcel {
    /// A parcel of no part, template or ideal.
    pub fn new(polygon: Vec<P>, use_: Use) -> Parcel {
        Parcel { polygon, use_, template: None, part: String::new(), registration: None, ideal: None }
    }
}
