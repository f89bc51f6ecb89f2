//! Every picture and chart: SVG written by hand through one writer ([`writer`]: header,
//! background, the one XML escaper) — deterministic text, snapshot-friendly — and PNG
//! rasterised from it with `resvg`.
//!
//! A leaf: pictures take plain data (positions, index lists, numbers, text), never the crate's
//! specs, meshes, designs or reports; each domain builds its scene next to its own types
//! (`design::picture`, `explain::conflict_svg`, `traffic::picture`, `urban::output`).
//!
//! - [`network`]: a designed network on its mesh ([`network::NetworkScene`]: rooms and blocks,
//!   obstacles, sinks, forced elements), and a spec whose requirements conflict, with the
//!   conflicting elements highlighted ([`network::conflict_svg`]);
//! - [`city`]: a city's streets by level, its sub-regions, obstacles and sinks;
//! - [`chart`]: the comparison charts (performance profile, bar chart of times);
//! - [`traffic`]: a network coloured by traffic volume, travel-time histograms, comparisons;
//! - [`streets`]: street networks side by side at one scale with their orientation roses.
//!
//! Legends list only what the picture shows.

pub mod chart;
pub mod city;
pub mod field;
pub mod grow;
pub mod layout;
pub mod level;
pub mod network;
pub mod streets;
pub mod traffic;
pub mod writer;

pub use network::{Caption, NetworkScene};

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

#[cfg(test)]
mod tests {
    /// `render` imports nothing from the crate outside itself: no non-comment line of a file
    /// under `src/render/` names the crate root followed by another module than `render`.
    #[test]
    fn render_is_a_leaf() {
        fn files(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
            for entry in std::fs::read_dir(dir).unwrap() {
                let path = entry.unwrap().path();
                if path.is_dir() {
                    files(&path, out);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    out.push(path);
                }
            }
        }
        let mut paths = Vec::new();
        files(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/render"), &mut paths);
        assert!(paths.len() >= 6, "{paths:?}");
        // Spelled in two pieces, so this test's own lines do not match.
        let needle = ["crate", "::"].concat();
        let mut bad = Vec::new();
        for path in &paths {
            let text = std::fs::read_to_string(path).unwrap();
            for (i, line) in text.lines().enumerate() {
                let code = line.trim_start();
                if code.starts_with("//") {
                    continue;
                }
                let code = code.split(" //").next().unwrap_or(code);
                let mut rest = code;
                while let Some(at) = rest.find(&needle) {
                    let after = &rest[at + needle.len()..];
                    let module: String = after.chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
                    // A braced list after the root counts too: the name read is empty.
                    if module != "render" {
                        bad.push(format!("{}:{}: {line}", path.display(), i + 1));
                        break;
                    }
                    rest = after;
                }
            }
        }
        assert!(bad.is_empty(), "render must not import the rest of the crate:\n{}", bad.join("\n"));
    }
}
