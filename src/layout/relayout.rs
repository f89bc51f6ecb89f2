//! A part laid out again with the rest fixed (the paper's interactive step: "recompute
//! subregions", §3): `netspec layout REGION --from LAYOUT.json --relayout PART`. The streets and
//! parcels of the part's subtree are dropped, the part (less the region's zones inside it) is grown
//! again — templates first, its own cross fields — among the kept streets, its leaves take
//! templates with the counts of the kept ones counted, and the new subtree replaces the old one.

use super::tree::PartTree;
use super::{Parcel, Street};
use crate::geometry::{Polygon, P};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The part of `layout.json` a relayout reads.
#[derive(Clone, Debug, Deserialize)]
pub struct LayoutFile {
    /// Streets, each naming the part whose split made it.
    pub streets: Vec<Street>,
    /// Parcels, each naming its leaf.
    pub parcels: Vec<Parcel>,
    /// The tree of parts.
    pub parts: PartTree,
}

/// Why a relayout was refused.
#[derive(Debug, thiserror::Error)]
pub enum RelayoutError {
    /// The file could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Not a `netspec layout` output.
    #[error("{}: not a layout.json of netspec layout: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message.
        message: String,
    },
    /// No such part.
    #[error("{}: no part {part} in its tree (parts are named like {examples})", path.display())]
    NoPart {
        /// The file.
        path: PathBuf,
        /// The part asked for.
        part: String,
        /// A few of the ids there are.
        examples: String,
    },
    /// The part's rings are not a polygon.
    #[error("{}: part {part}: {message}", path.display())]
    BadPart {
        /// The file.
        path: PathBuf,
        /// The part.
        part: String,
        /// Why.
        message: String,
    },
}

/// A layout file read for a relayout, with the part found.
#[derive(Clone, Debug)]
pub struct Relayout {
    /// The file.
    pub file: LayoutFile,
    /// The part's id.
    pub part: String,
    /// Its polygon.
    pub polygon: Polygon,
    /// Its label and level.
    pub label: String,
    /// The level of the street that made it.
    pub level: usize,
}

/// Whether `id` is `part` or lies below it.
pub fn within(id: &str, part: &str) -> bool {
    id == part || (id.starts_with(part) && id[part.len()..].starts_with('.'))
}

/// Reads `layout.json` and finds the part.
pub fn read(path: &Path, part: &str) -> Result<Relayout, RelayoutError> {
    let text = std::fs::read_to_string(path).map_err(|source| RelayoutError::Io { path: path.into(), source })?;
    let file: LayoutFile =
        serde_json::from_str(&text).map_err(|e| RelayoutError::Parse { path: path.into(), message: e.to_string() })?;
    let Some(node) = find(&file.parts, part) else {
        let mut ids = Vec::new();
        collect_ids(&file.parts, &mut ids);
        let examples = ids.iter().take(6).cloned().collect::<Vec<_>>().join(", ");
        return Err(RelayoutError::NoPart { path: path.into(), part: part.into(), examples });
    };
    let polygon = Polygon::new(node.outer.clone(), node.holes.clone()).map_err(|e| RelayoutError::BadPart {
        path: path.into(),
        part: part.into(),
        message: e.to_string(),
    })?;
    let (label, level) = (node.label.clone(), node.level);
    Ok(Relayout { part: part.into(), polygon, label, level, file })
}

/// The node of a tree with this id.
pub fn find<'t>(t: &'t PartTree, id: &str) -> Option<&'t PartTree> {
    if t.id == id {
        return Some(t);
    }
    t.children.iter().find(|c| within(id, &c.id)).and_then(|c| find(c, id))
}

fn collect_ids(t: &PartTree, out: &mut Vec<String>) {
    out.push(t.id.clone());
    for c in &t.children {
        collect_ids(c, out);
    }
}

/// The tree with the node of `sub.id` replaced by `sub`.
pub fn replace(t: &PartTree, sub: &PartTree) -> PartTree {
    if t.id == sub.id {
        return sub.clone();
    }
    PartTree { children: t.children.iter().map(|c| replace(c, sub)).collect(), ..t.clone() }
}

/// Per template name, its uses in the tree outside `part` (the templates that settled leaves and
/// the area templates within them).
pub fn uses_outside(t: &PartTree, part: &str) -> std::collections::BTreeMap<String, usize> {
    let mut out = std::collections::BTreeMap::new();
    fn walk(t: &PartTree, part: &str, out: &mut std::collections::BTreeMap<String, usize>) {
        if within(&t.id, part) {
            return;
        }
        for name in t.template.iter().chain(&t.nested) {
            *out.entry(name.clone()).or_default() += 1;
        }
        t.children.iter().for_each(|c| walk(c, part, out));
    }
    walk(t, part, &mut out);
    out
}

/// The ids of the tree's leaves.
pub fn leaf_ids(t: &PartTree, out: &mut std::collections::BTreeSet<String>) {
    if t.children.is_empty() {
        out.insert(t.id.clone());
    }
    t.children.iter().for_each(|c| leaf_ids(c, out));
}

/// Rounds a ring to the millimetre (how `layout.json` stores it), for comparisons.
pub fn rounded(ring: &[P]) -> Vec<P> {
    ring.iter().map(|p| [(p[0] * 1000.0).round() / 1000.0, (p[1] * 1000.0).round() / 1000.0]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_below_a_part() {
        assert!(within("0.1", "0.1") && within("0.1.0.3", "0.1"));
        assert!(!within("0.10", "0.1") && !within("0", "0.1"));
    }
}
