//! Solution files: one `name value` pair per line, as written by CPLEX's, Gurobi's and SCIP's
//! `.sol` writers and read by PuLP, JuMP and python-mip users.
//!
//! # Writing ([`write`])
//!
//! ```text
//! # netspec solution: highs 1.11.0, optimal
//! # Objective value = 12.5
//! x 1
//! y 0.5
//! ```
//!
//! Every variable is written, in model order, with the shortest text that reads back to the
//! same `f64`.
//!
//! # Reading ([`read`])
//!
//! Blank lines and lines starting with `#` are skipped, and so, before the first pair, are the
//! header lines of SCIP's format (`solution status: …`, `objective value: …`) and of HiGHS's
//! (`Model status`, `Objective 12.5`, `Columns 3`). A pair whose name the model does not have is an error naming
//! the line, and so is a bad number or a name given twice. Variables the file does not mention
//! are reported in [`SolutionFile::missing`] and set to 0 (a start is checked as a whole
//! before use anyway).

use crate::milp::Model;
use std::path::{Path, PathBuf};

/// A solution read from a file.
#[derive(Clone, Debug, PartialEq)]
pub struct SolutionFile {
    /// One value per variable of the model, in model order.
    pub values: Vec<f64>,
    /// Names of the variables the file did not mention (set to 0), in model order.
    pub missing: Vec<String>,
}

/// Why a solution file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum SolErrorKind {
    /// The operating system refused.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A name the model does not have.
    #[error("line {line}: the model has no variable `{name}`")]
    UnknownVariable {
        /// 1-based line.
        line: usize,
        /// The name.
        name: String,
    },
    /// A value that is not a finite number.
    #[error("line {line}: `{text}` is not a finite number")]
    BadValue {
        /// 1-based line.
        line: usize,
        /// The text.
        text: String,
    },
    /// A variable given twice.
    #[error("line {line}: variable `{name}` appears twice")]
    Duplicate {
        /// 1-based line.
        line: usize,
        /// The name.
        name: String,
    },
}

/// A solution-file error: which file, and what.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct SolError {
    /// The file.
    pub path: PathBuf,
    /// What went wrong.
    #[source]
    pub kind: SolErrorKind,
}

/// Writes `x` (one value per variable) as a solution file; `header` becomes a comment line.
pub fn write(model: &Model, x: &[f64], objective: Option<f64>, header: &str, path: &Path) -> Result<(), SolError> {
    let err = |e| SolError { path: path.to_path_buf(), kind: SolErrorKind::Io(e) };
    let mut text = String::with_capacity(16 * x.len() + 64);
    text.push_str(&format!("# netspec solution: {header}\n"));
    if let Some(obj) = objective {
        text.push_str(&format!("# Objective value = {}\n", ryu::Buffer::new().format(obj)));
    }
    for (v, value) in model.vars().iter().zip(x) {
        // Integral values print as integers (`1`, not `1.0`).
        let value = if *value == 0.0 { 0.0 } else { *value };
        if value.fract() == 0.0 && value.abs() < 1e15 {
            text.push_str(&format!("{} {}\n", v.name, value as i64));
        } else {
            text.push_str(&format!("{} {}\n", v.name, ryu::Buffer::new().format(value)));
        }
    }
    crate::io::write_atomic(path, &text).map_err(err)
}

/// Reads a solution file for `model` (see the module docs).
pub fn read(model: &Model, path: &Path) -> Result<SolutionFile, SolError> {
    let text = super::read_utf8(path).map_err(|e| SolError { path: path.to_path_buf(), kind: e.into() })?;
    parse(model, &text).map_err(|kind| SolError { path: path.to_path_buf(), kind })
}

/// Whether a line before the first pair is a header of another tool's format: its value is not
/// a number (`Model status`, `solution status: optimal …`), or its name is not a variable and is
/// one of the header words (`objective value: 1.5`, HiGHS's `Objective 12.5`, `Columns 3`).
fn looks_like_header(name: &str, value: &str, known: bool) -> bool {
    let word = name.trim_end_matches(':').to_ascii_lowercase();
    value.parse::<f64>().is_err()
        || (!known
            && (name.ends_with(':')
                || ["objective", "columns", "rows", "model", "solution", "t"].contains(&word.as_str())))
}

/// Parses the text of a solution file for `model`.
pub fn parse(model: &Model, text: &str) -> Result<SolutionFile, SolErrorKind> {
    let index = model.var_index();
    let mut values: Vec<Option<f64>> = vec![None; model.num_vars()];
    let mut in_pairs = false;
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let mut fields = t.split_whitespace();
        let (Some(name), Some(value)) = (fields.next(), fields.next()) else {
            if in_pairs {
                return Err(SolErrorKind::BadValue { line: line_no, text: t.to_string() });
            }
            continue;
        };
        if !in_pairs && looks_like_header(name, value, index.contains_key(name)) {
            continue;
        }
        let Some(&var) = index.get(name) else {
            return Err(SolErrorKind::UnknownVariable { line: line_no, name: name.to_string() });
        };
        let v: f64 = value
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| SolErrorKind::BadValue { line: line_no, text: value.to_string() })?;
        if values[var.index()].replace(v).is_some() {
            return Err(SolErrorKind::Duplicate { line: line_no, name: name.to_string() });
        }
        in_pairs = true;
    }
    let missing =
        model.vars().iter().zip(&values).filter(|(_, v)| v.is_none()).map(|(var, _)| var.name.clone()).collect();
    Ok(SolutionFile { values: values.into_iter().map(|v| v.unwrap_or(0.0)).collect(), missing })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> Model {
        let mut m = Model::new("s");
        m.add_binary("x", 1.0);
        m.add_continuous("y", 0.0, 10.0, 0.5);
        m.add_integer("z", 0.0, 5.0, 0.0);
        m
    }

    #[test]
    fn round_trip() {
        let m = model();
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.sol");
        write(&m, &[1.0, 0.1 + 0.2, 3.0], Some(1.15), "test, optimal", &p).unwrap();
        let text = std::fs::read_to_string(&p).unwrap();
        assert_eq!(
            text,
            "# netspec solution: test, optimal\n# Objective value = 1.15\nx 1\ny 0.30000000000000004\nz 3\n"
        );
        let back = read(&m, &p).unwrap();
        assert_eq!(back, SolutionFile { values: vec![1.0, 0.1 + 0.2, 3.0], missing: vec![] });
    }

    #[test]
    fn other_tools_headers_and_missing_names() {
        let m = model();
        let scip = "solution status: optimal solution found\nobjective value:                    1.5\nx 1 \t(obj:1)\ny 1 \t(obj:0.5)\n";
        let s = parse(&m, scip).unwrap();
        assert_eq!(s.values, vec![1.0, 1.0, 0.0]);
        assert_eq!(s.missing, vec!["z".to_string()]);
    }

    #[test]
    fn errors_name_the_line() {
        let m = model();
        assert!(matches!(parse(&m, "x 1\nw 2\n"), Err(SolErrorKind::UnknownVariable { line: 2, .. })));
        assert!(matches!(parse(&m, "w 2\nx 1\n"), Err(SolErrorKind::UnknownVariable { line: 1, .. })));
        assert!(matches!(parse(&m, "x 1\ny nan\n"), Err(SolErrorKind::BadValue { line: 2, .. })));
        assert!(matches!(parse(&m, "x 1\nx 0\n"), Err(SolErrorKind::Duplicate { line: 2, .. })));
        assert!(matches!(parse(&m, "x 1\nlonely\n"), Err(SolErrorKind::BadValue { line: 2, .. })));
    }
}
