//! Reading and writing models as free MPS and CPLEX LP files.
//!
//! Both formats share [`NameMap`] (how names were sanitised on write), [`Warning`] (what a
//! reader accepted but found odd), and [`ReadError`] (a file-level error naming the path).

pub mod lp;
pub mod mps;
pub mod sol;

use crate::milp::Model;
use indexmap::IndexMap;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// How names were changed when writing: original name → written name, only for names that
/// had to change. Variables and rows are kept apart because they live in separate namespaces.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct NameMap {
    /// Renamed variables.
    pub vars: IndexMap<String, String>,
    /// Renamed rows.
    pub rows: IndexMap<String, String>,
}

impl NameMap {
    /// Whether every name was written unchanged.
    pub fn is_identity(&self) -> bool {
        self.vars.is_empty() && self.rows.is_empty()
    }
}

/// Something a reader accepted but that may not mean what the author intended.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Warning {
    /// 1-based line number.
    pub line: usize,
    /// What was odd and what the reader did.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "line {}: {}", self.line, self.message)
    }
}

/// A model read from a file, with the reader's warnings.
#[derive(Clone, Debug)]
pub struct ReadModel {
    /// The model.
    pub model: Model,
    /// Warnings, in file order.
    pub warnings: Vec<Warning>,
}

/// A file format.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// Free (or fixed) MPS.
    Mps,
    /// CPLEX LP.
    Lp,
}

impl Format {
    /// The format named by a path's extension: `.mps` or `.lp`, also gzip-compressed
    /// (`.mps.gz`, `.lp.gz`, as MIPLIB ships them; see [`is_gzip`]).
    pub fn from_path(path: &Path) -> Option<Format> {
        let inner = if is_gzip(path) { Path::new(path.file_stem()?) } else { path };
        match inner.extension()?.to_str()?.to_ascii_lowercase().as_str() {
            "mps" => Some(Format::Mps),
            "lp" => Some(Format::Lp),
            _ => None,
        }
    }
}

/// Whether a path names a gzip-compressed file (`.gz`).
pub fn is_gzip(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("gz"))
}

/// Reads a whole text file, decompressing it if its name ends in `.gz`; text that is not UTF-8
/// is an error naming the line and column ([`utf8`]).
fn read_text(path: &Path) -> std::io::Result<String> {
    if !is_gzip(path) {
        return read_utf8(path);
    }
    let mut bytes = Vec::new();
    std::io::Read::read_to_end(
        &mut flate2::read::MultiGzDecoder::new(std::io::BufReader::new(std::fs::File::open(path)?)),
        &mut bytes,
    )?;
    utf8(bytes)
}

/// Reads a whole text file; text that is not UTF-8 is an error naming the line and column
/// ([`utf8`]).
pub fn read_utf8(path: &Path) -> std::io::Result<String> {
    utf8(std::fs::read(path)?)
}

/// Bytes as text, or an error (`InvalidData`) naming the line and column of the first byte that
/// is not UTF-8.
pub fn utf8(bytes: Vec<u8>) -> std::io::Result<String> {
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let b = e.as_bytes();
        let line = 1 + b[..at].iter().filter(|&&c| c == b'\n').count();
        let column = 1 + at - b[..at].iter().rposition(|&c| c == b'\n').map_or(0, |p| p + 1);
        std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("line {line}, column {column}: not valid UTF-8 (byte 0x{:02x})", b[at]),
        )
    })
}

/// Why a file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum FileErrorKind {
    /// The extension is neither `.mps` nor `.lp` (nor either followed by `.gz`).
    #[error("unknown file format (expected a .mps, .lp, .mps.gz or .lp.gz extension)")]
    UnknownFormat,
    /// The operating system refused.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The MPS text is malformed.
    #[error(transparent)]
    Mps(#[from] mps::ParseError),
    /// The LP text is malformed.
    #[error(transparent)]
    Lp(#[from] lp::ParseError),
    /// The model read is structurally invalid (e.g. a NaN coefficient).
    #[error(transparent)]
    Model(#[from] crate::milp::ModelError),
}

/// A file-level error: which file, and what went wrong.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct FileError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    #[source]
    pub kind: FileErrorKind,
}

fn file_err(path: &Path, kind: impl Into<FileErrorKind>) -> FileError {
    FileError { path: path.to_path_buf(), kind: kind.into() }
}

/// Reads a `.mps` or `.lp` file, or either gzip-compressed (chosen by extension), and validates
/// the model.
pub fn read_model_file(path: &Path) -> Result<ReadModel, FileError> {
    let format = Format::from_path(path).ok_or_else(|| file_err(path, FileErrorKind::UnknownFormat))?;
    let text = read_text(path).map_err(|e| file_err(path, e))?;
    let read = match format {
        Format::Mps => mps::read_str(&text).map_err(|e| file_err(path, e))?,
        Format::Lp => lp::read_str(&text).map_err(|e| file_err(path, e))?,
    };
    read.model.validate().map_err(|e| file_err(path, e))?;
    Ok(read)
}

/// Writes a model to a `.mps` or `.lp` file, or either gzip-compressed (chosen by extension),
/// and returns the name map.
pub fn write_model_file(model: &Model, path: &Path) -> Result<NameMap, FileError> {
    write_model_file_with_comments(model, path, &[])
}

/// Writes a model file like [`write_model_file`], with comment lines at the top.
pub fn write_model_file_with_comments(model: &Model, path: &Path, comments: &[String]) -> Result<NameMap, FileError> {
    let format = Format::from_path(path).ok_or_else(|| file_err(path, FileErrorKind::UnknownFormat))?;
    let file = std::fs::File::create(path).map_err(|e| file_err(path, e))?;
    let w = std::io::BufWriter::with_capacity(1 << 20, file);
    let write = |mut w: &mut dyn std::io::Write| match format {
        Format::Mps => {
            mps::write(model, &mut w, &mps::WriteOptions { comments: comments.to_vec(), ..Default::default() })
        }
        Format::Lp => lp::write(model, &mut w, &lp::WriteOptions { comments: comments.to_vec(), ..Default::default() }),
    };
    let map = if is_gzip(path) {
        let mut gz = flate2::write::GzEncoder::new(w, flate2::Compression::default());
        let map = write(&mut gz).map_err(|e| file_err(path, e))?;
        let mut w = gz.finish().map_err(|e| file_err(path, e))?;
        std::io::Write::flush(&mut w).map_err(|e| file_err(path, e))?;
        map
    } else {
        let mut w = w;
        let map = write(&mut w).map_err(|e| file_err(path, e))?;
        std::io::Write::flush(&mut w).map_err(|e| file_err(path, e))?;
        map
    };
    Ok(map)
}

/// Writes `text` to `path` through a temporary file and a rename, so a reader (or a resumed run)
/// never sees a half-written file.
pub(crate) fn write_atomic(path: &Path, text: &str) -> std::io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

/// FNV-1a, 64 bits, as 16 hex digits: a stable digest of some inputs, each part delimited (for
/// resuming: "are these the same inputs as last time?"; not for security).
pub(crate) fn digest(parts: &[&[u8]]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for p in parts {
        for &b in *p {
            h ^= b as u64;
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
        h ^= 0xff;
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// What [`convert`] did.
pub struct Converted {
    /// The model's size.
    pub stats: crate::milp::ModelStats,
    /// Warnings from reading the input.
    pub warnings: Vec<String>,
    /// Names changed to fit the output format.
    pub renamed: usize,
}

/// Reads a model file and writes it in the format of `output`'s extension.
pub fn convert(input: &Path, output: &Path) -> Result<Converted, FileError> {
    let read = read_model_file(input)?;
    let map = write_model_file(&read.model, output)?;
    Ok(Converted {
        stats: read.model.stats(),
        warnings: read.warnings.iter().map(|w| w.to_string()).collect(),
        renamed: if map.is_identity() { 0 } else { map.vars.len() + map.rows.len() },
    })
}

#[cfg(test)]
mod text_tests {
    #[test]
    fn utf8_errors_name_the_line_and_column() {
        let e = super::utf8(b"NAME x\nROWS\n N  c\xff\n".to_vec()).unwrap_err().to_string();
        assert_eq!(e, "line 3, column 6: not valid UTF-8 (byte 0xff)");
        assert_eq!(super::utf8(b"ok\n".to_vec()).unwrap(), "ok\n");
    }
}
