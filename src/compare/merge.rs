//! Finished comparisons combined into one table (`compare --merge`).

use super::manifest::Manifest;
use super::record::RunRecord;
use super::summary::BackendSummary;
use serde::Deserialize;
use std::path::PathBuf;

/// Why comparisons could not be merged.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A comparison's `results.json` could not be read.
    #[error("{}: {error} (a finished `netspec compare --out {}`?)", path.display(), dir.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The comparison's directory.
        dir: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
    /// The file is not a comparison's results.
    #[error("{}: not a comparison's results: {message}", path.display())]
    NotResults {
        /// The file.
        path: PathBuf,
        /// The JSON reader's message.
        message: String,
    },
    /// The results carry no manifest.
    #[error("{}: settings.manifest is missing", path.display())]
    NoManifest {
        /// The file.
        path: PathBuf,
    },
    /// The results' manifest cannot be read.
    #[error("{}: settings.manifest: {message}", path.display())]
    BadManifest {
        /// The file.
        path: PathBuf,
        /// The JSON reader's message.
        message: String,
    },
    /// Two comparisons have a column of the same label.
    #[error("column `{column}` is in both {} and {}: merge comparisons with different columns", first.display(), second.display())]
    DuplicateColumn {
        /// The label.
        column: String,
        /// The comparison that had it first.
        first: PathBuf,
        /// The one that has it again.
        second: PathBuf,
    },
    /// No directories were given.
    #[error("nothing to merge: no comparison directories given")]
    Nothing,
}

/// Finished comparisons combined into one ([`merge`]).
#[derive(Clone, Debug)]
pub struct Merged {
    /// The rows of the combined table.
    pub manifest: Manifest,
    /// Every column of every comparison, in order.
    pub columns: Vec<String>,
    /// Every record of every comparison.
    pub records: Vec<RunRecord>,
    /// The largest time limit of the comparisons (the charts' axis).
    pub time_limit: f64,
    /// Each comparison's directory and its stored settings, as read.
    pub sources: Vec<(PathBuf, serde_json::Value)>,
}

/// Reads the `results.json` of finished comparisons (`compare --out DIR`, or an earlier merge)
/// and combines them: columns in the order of `dirs`, then of each comparison's own columns.
/// The rows are `manifest`'s if given, else the first comparison's. A column label that
/// appears in two comparisons is an error naming both, as is a directory without a readable
/// `results.json`.
pub fn merge(dirs: &[PathBuf], manifest: Option<Manifest>) -> Result<Merged, MergeError> {
    #[derive(Deserialize)]
    struct Saved {
        settings: serde_json::Value,
        records: Vec<RunRecord>,
        summary: Vec<BackendSummary>,
    }
    // Each column with the comparison it came from (to name both when it comes again).
    let mut columns: Vec<(String, PathBuf)> = Vec::new();
    let (mut records, mut sources, mut time_limit, mut first_manifest) = (Vec::new(), Vec::new(), 0.0f64, None);
    for dir in dirs {
        let path = dir.join("results.json");
        let text = std::fs::read_to_string(&path).map_err(|error| MergeError::Read {
            path: path.clone(),
            dir: dir.clone(),
            error,
        })?;
        let saved: Saved = serde_json::from_str(&text)
            .map_err(|e| MergeError::NotResults { path: path.clone(), message: e.to_string() })?;
        for b in &saved.summary {
            if let Some((_, other)) = columns.iter().find(|(c, _)| *c == b.solver) {
                return Err(MergeError::DuplicateColumn {
                    column: b.solver.clone(),
                    first: other.clone(),
                    second: dir.clone(),
                });
            }
            columns.push((b.solver.clone(), dir.clone()));
        }
        if let Some(limit) = saved.settings.get("time_limit").and_then(|v| v.as_f64()) {
            time_limit = time_limit.max(limit);
        }
        if first_manifest.is_none() {
            let m =
                saved.settings.get("manifest").cloned().ok_or_else(|| MergeError::NoManifest { path: path.clone() })?;
            first_manifest = Some(
                serde_json::from_value::<Manifest>(m)
                    .map_err(|e| MergeError::BadManifest { path: path.clone(), message: e.to_string() })?,
            );
        }
        records.extend(saved.records);
        sources.push((dir.clone(), saved.settings));
    }
    let manifest = manifest.or(first_manifest).ok_or(MergeError::Nothing)?;
    Ok(Merged { manifest, columns: columns.into_iter().map(|(c, _)| c).collect(), records, time_limit, sources })
}
