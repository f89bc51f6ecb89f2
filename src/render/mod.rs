//! Every picture and chart: SVG written by hand through one writer ([`writer`]: header,
//! background, the one XML escaper) — deterministic text, snapshot-friendly — and PNG
//! rasterised from it with `resvg`.
//!
//! - [`network`]: a designed network on its mesh (rooms and blocks, obstacles, sinks, forced
//!   elements), and a spec whose requirements conflict, with the conflicting elements
//!   highlighted ([`network::conflict_svg`]);
//! - [`city`]: a city's streets by level, its sub-regions, obstacles and sinks;
//! - [`chart`]: the comparison charts (performance profile, bar chart of times);
//! - [`traffic`]: a network coloured by traffic volume, travel-time histograms, comparisons.
//!
//! Legends list only what the picture shows.

pub mod chart;
pub mod city;
pub mod network;
pub mod traffic;
pub mod writer;

pub use network::{svg, Caption};

/// Why a PNG could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The SVG did not parse (a bug).
    #[error("SVG: {0}")]
    Svg(String),
    /// Rasterising or encoding failed.
    #[error("PNG: {0}")]
    Png(String),
}

/// Rasterises SVG text to PNG bytes (system fonts for the text).
pub fn png(svg_text: &str) -> Result<Vec<u8>, RenderError> {
    let mut opt = resvg::usvg::Options::default();
    opt.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg_text, &opt).map_err(|e| RenderError::Svg(e.to_string()))?;
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| RenderError::Png("empty picture".into()))?;
    resvg::render(&tree, resvg::tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap.encode_png().map_err(|e| RenderError::Png(e.to_string()))
}
