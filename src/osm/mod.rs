//! Real sites from OpenStreetMap extracts (`netspec site`): the user brings an extract (OSM PBF
//! or OSM XML; netspec never downloads anything) and a box or polygon, and gets the site every
//! design command reads — the region with its water (and optionally parks and railway land) as
//! holes and its major roads — the real drivable streets as a design (`map/`), and optionally a
//! grow context and an IP city spec of the same site.
//!
//! One concern per file: [`read`] (PBF and XML into nodes, ways and multipolygons),
//! [`areas`] (water, coastline, parks and railway land as polygons), [`ways`] (streets: the
//! drivable network split at its junctions, major roads merged into continuous lines),
//! [`site`] (the site itself and the files written; [`site::run`] is the entry point).
//!
//! Every file written carries "© OpenStreetMap contributors, ODbL" ([`ATTRIBUTION`]).

pub mod areas;
pub mod read;
pub mod site;
pub mod ways;

use std::path::PathBuf;

/// The attribution every output that carries OpenStreetMap data states.
pub const ATTRIBUTION: &str = "© OpenStreetMap contributors, ODbL (https://www.openstreetmap.org/copyright)";

/// Why a site could not be made.
#[derive(Debug, thiserror::Error)]
pub enum OsmError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// The file is not an OSM extract.
    #[error("{}: not an OpenStreetMap extract (OSM PBF or OSM XML): {message}", path.display())]
    NotOsm {
        /// The file.
        path: PathBuf,
        /// What the reader said.
        message: String,
    },
    /// The extract holds no nodes.
    #[error("{}: the extract is empty (no nodes)", path.display())]
    Empty {
        /// The file.
        path: PathBuf,
    },
    /// The box is not a longitude/latitude box.
    #[error("--bbox {0}")]
    Bbox(String),
    /// The region lies outside the extract.
    #[error("{what} lies outside the extract {} (which spans {:.5},{:.5},{:.5},{:.5})", path.display(), extent[0], extent[1], extent[2], extent[3])]
    Outside {
        /// The box or the polygon file.
        what: String,
        /// The extract.
        path: PathBuf,
        /// The extract's extent, W,S,E,N.
        extent: [f64; 4],
    },
    /// The region polygon file is wrong.
    #[error("{}: {message}", path.display())]
    Region {
        /// The file (`--polygon`, or the extract for a box).
        path: PathBuf,
        /// What is wrong.
        message: String,
    },
    /// A region drawn on a map (not a file) is wrong.
    #[error("the drawn region: {0}")]
    Drawn(String),
    /// Water or the chosen holes split the region into several pieces.
    #[error("the holes split the region into {} pieces of at least 1 ha ({}); draw a region that one piece fills, or pass --largest to keep the largest", areas.len(), areas.iter().map(|a| format!("{:.2} ha", a / 1e4)).collect::<Vec<_>>().join(", "))]
    Islands {
        /// Each piece's area, m², largest first.
        areas: Vec<f64>,
    },
    /// Nothing of the region is land.
    #[error("no land is left in the region once its holes are taken out")]
    NoLand,
    /// The projection failed.
    #[error(transparent)]
    Site(#[from] crate::geometry::site::SiteError),
    /// A file could not be written as TOML or JSON.
    #[error("writing {what}: {message}")]
    Write {
        /// Which file.
        what: String,
        /// The serialiser's message.
        message: String,
    },
}
