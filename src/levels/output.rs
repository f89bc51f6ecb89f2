//! Outputs: `level.json` (status, layouts, the search's figures).

use super::spec::Level;
use super::{LevelError, LevelOutcome};
use std::path::{Path, PathBuf};

fn put(path: &Path, bytes: &[u8]) -> Result<(), LevelError> {
    std::fs::write(path, bytes)
        .map_err(|e| LevelError::Write { path: path.display().to_string(), reason: e.to_string() })
}

/// Writes the outputs into `dir` (created if missing); returns the files written.
pub fn write(dir: &Path, _level: &Level, outcome: &LevelOutcome) -> Result<Vec<PathBuf>, LevelError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| LevelError::Write { path: dir.display().to_string(), reason: e.to_string() })?;
    let json = dir.join("level.json");
    let text = serde_json::to_string_pretty(outcome)
        .map_err(|e| LevelError::Write { path: json.display().to_string(), reason: e.to_string() })?;
    put(&json, text.as_bytes())?;
    Ok(vec![json])
}
