//! The instances of a comparison: a manifest such as `models/table1.toml` (rows with the
//! paper's figures) or plain spec files named by [`instance_ids`], and `--rows` selections.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Why a manifest could not be read, or a selection of its rows made.
#[derive(Debug, thiserror::Error)]
pub enum ManifestError {
    /// The file could not be read.
    #[error("{}: {error}", path.display())]
    Read {
        /// The manifest.
        path: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
    /// The file is not a manifest's TOML.
    #[error("{}: {message}", path.display())]
    Parse {
        /// The manifest.
        path: PathBuf,
        /// The TOML reader's message.
        message: String,
    },
    /// Two rows share a name.
    #[error("{}: row[{row}] has the same name as row[{first}] ({name:?}); names must be unique", path.display())]
    DuplicateName {
        /// The manifest.
        path: PathBuf,
        /// The later row.
        row: usize,
        /// The earlier row.
        first: usize,
        /// Their name.
        name: String,
    },
    /// A row gives both or neither of `spec` and `missing`.
    #[error("{}: row[{row}] ({name}): give exactly one of `spec` or `missing`", path.display())]
    SpecOrMissing {
        /// The manifest.
        path: PathBuf,
        /// The row.
        row: usize,
        /// Its name.
        name: String,
    },
    /// A `--rows` pattern matches no row.
    #[error("--rows: `{pattern}` matches no row (rows: {})", rows.join(", "))]
    NoMatch {
        /// The pattern.
        pattern: String,
        /// Every row's name.
        rows: Vec<String>,
    },
}

/// The paper's figures for one instance (Table 1).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperRow {
    /// Mesh edges.
    #[serde(default)]
    pub edges: Option<usize>,
    /// Variables.
    #[serde(default)]
    pub variables: Option<usize>,
    /// Gurobi time as printed (street rows: `level2/level3/level4`).
    #[serde(default)]
    pub time: Option<String>,
}

/// One row of a manifest such as `models/table1.toml`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestRow {
    /// The row's name (the paper's figure id).
    pub name: String,
    /// The spec file, relative to the manifest; absent when the row cannot run yet.
    #[serde(default)]
    pub spec: Option<PathBuf>,
    /// Why the row cannot run yet (shown in the table; rows are never dropped silently).
    #[serde(default)]
    pub missing: Option<String>,
    /// The paper's figures.
    #[serde(default)]
    pub paper: PaperRow,
}

/// A manifest: instances with the paper's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The rows, in table order.
    pub row: Vec<ManifestRow>,
}

impl Manifest {
    /// Reads a TOML manifest; spec paths become relative to the current directory.
    pub fn load(path: &Path) -> Result<Manifest, ManifestError> {
        let text = crate::io::read_utf8(path).map_err(|error| ManifestError::Read { path: path.into(), error })?;
        let mut m: Manifest =
            toml::from_str(&text).map_err(|e| ManifestError::Parse { path: path.into(), message: e.to_string() })?;
        let base = path.parent().unwrap_or(Path::new("."));
        for (i, r) in m.row.iter().enumerate() {
            if let Some(j) = m.row[..i].iter().position(|o| o.name == r.name) {
                return Err(ManifestError::DuplicateName { path: path.into(), row: i, first: j, name: r.name.clone() });
            }
        }
        for (i, r) in m.row.iter_mut().enumerate() {
            match (&r.spec, &r.missing) {
                (Some(s), None) => r.spec = Some(base.join(s)),
                (None, Some(_)) => {}
                _ => return Err(ManifestError::SpecOrMissing { path: path.into(), row: i, name: r.name.clone() }),
            }
        }
        Ok(m)
    }

    /// A manifest of plain spec files, no paper figures, each named by [`instance_ids`].
    pub fn from_specs(specs: &[PathBuf]) -> Manifest {
        Manifest {
            row: specs
                .iter()
                .zip(instance_ids(specs))
                .map(|(p, name)| ManifestRow { name, spec: Some(p.clone()), missing: None, paper: PaperRow::default() })
                .collect(),
        }
    }

    /// The rows whose names match one of `patterns` (a name, or a glob with `*` and `?`:
    /// `2*`, `*-L4`), in table order. A pattern that matches no row is an error naming it.
    pub fn select(&self, patterns: &[String]) -> Result<Manifest, ManifestError> {
        if patterns.is_empty() {
            return Ok(self.clone());
        }
        if let Some(p) = patterns.iter().find(|p| !self.row.iter().any(|r| glob_match(p, &r.name))) {
            let rows = self.row.iter().map(|r| r.name.clone()).collect();
            return Err(ManifestError::NoMatch { pattern: p.clone(), rows });
        }
        let row = self.row.iter().filter(|r| patterns.iter().any(|p| glob_match(p, &r.name))).cloned().collect();
        Ok(Manifest { row })
    }

    /// The directory name of each row's runs (under `runs/`): its name with characters other
    /// than letters, digits, `.`, `_` and `-` replaced by `-` (`fig1b/L2/spec` →
    /// `fig1b-L2-spec`), plus a digest of the name where that would make two rows share one.
    pub fn run_keys(&self) -> Vec<String> {
        let safe: Vec<String> = self
            .row
            .iter()
            .map(|r| {
                r.name.chars().map(|c| if c.is_ascii_alphanumeric() || "._-".contains(c) { c } else { '-' }).collect()
            })
            .collect();
        safe.iter()
            .zip(&self.row)
            .map(|(k, r)| {
                if safe.iter().filter(|o| *o == k).count() > 1 {
                    format!("{k}-{}", &crate::io::digest(&[r.name.as_bytes()])[..8])
                } else {
                    k.clone()
                }
            })
            .collect()
    }
}

/// Unique instance names from spec paths: each path without its extension, cut to the shortest
/// trailing run of components that no other spec shares (`models/streets/fig1b/L2/spec.json` and
/// `models/streets/fig7e/L2/spec.json` → `fig1b/L2/spec` and `fig7e/L2/spec`; `models/fig2b.toml`
/// alone → `fig2b`). Specs that differ only by extension keep it; a path given twice gets `#2`.
pub fn instance_ids(specs: &[PathBuf]) -> Vec<String> {
    let parts: Vec<Vec<String>> = specs
        .iter()
        .map(|p| {
            let mut c: Vec<String> = p
                .components()
                .filter(|c| {
                    !matches!(
                        c,
                        std::path::Component::CurDir | std::path::Component::RootDir | std::path::Component::Prefix(_)
                    )
                })
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if let (Some(last), Some(stem)) = (c.last_mut(), p.file_stem()) {
                *last = stem.to_string_lossy().into_owned();
            }
            c
        })
        .collect();
    let suffix = |i: usize, k: usize| parts[i][parts[i].len().saturating_sub(k)..].join("/");
    let mut k = vec![1usize; specs.len()];
    loop {
        let ids: Vec<String> = (0..specs.len()).map(|i| suffix(i, k[i])).collect();
        let mut grew = false;
        for i in 0..specs.len() {
            if k[i] < parts[i].len() && ids.iter().enumerate().any(|(j, id)| j != i && *id == ids[i]) {
                k[i] += 1;
                grew = true;
            }
        }
        if !grew {
            break;
        }
    }
    let mut ids: Vec<String> = (0..specs.len()).map(|i| suffix(i, k[i])).collect();
    // Still equal: the same path but for the extension, or the same path twice.
    let clashing: Vec<bool> =
        (0..ids.len()).map(|i| (0..ids.len()).any(|j| ids[j] == ids[i] && specs[j] != specs[i])).collect();
    for (i, clash) in clashing.into_iter().enumerate() {
        if let (true, Some(ext)) = (clash, specs[i].extension()) {
            ids[i] = format!("{}.{}", ids[i], ext.to_string_lossy());
        }
    }
    for i in 0..ids.len() {
        let mut n = 1;
        let base = ids[i].clone();
        while ids[..i].contains(&ids[i]) {
            n += 1;
            ids[i] = format!("{base}#{n}");
        }
    }
    ids
}

/// Whether `name` matches `pattern`, where `*` stands for any run of characters and `?` for
/// one.
pub fn glob_match(pattern: &str, name: &str) -> bool {
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // The classic two-pointer match with backtracking to the last `*`.
    let (mut i, mut j, mut star, mut mark) = (0, 0, None, 0);
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some(i);
            mark = j;
            i += 1;
        } else if let Some(s) = star {
            i = s + 1;
            mark += 1;
            j = mark;
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
}

/// The paper's time for a row, in seconds, when it is a single number (`"132"`); `None` for
/// per-level times (`"379/366/49"`), `"-"` or no time.
pub fn paper_seconds(p: &PaperRow) -> Option<f64> {
    p.time.as_deref()?.trim().parse::<f64>().ok().filter(|t| t.is_finite() && *t >= 0.0)
}
