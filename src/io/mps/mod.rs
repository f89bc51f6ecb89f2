//! Free MPS reader and writer (with a fixed-format fallback on reading).
//!
//! # Reading ([`read_str`])
//!
//! Sections `NAME`, `OBJSENSE` (`OBJSENSE MAX` on one line, or `MAX`/`MAXIMIZE`/`MIN`/`MINIMIZE`
//! on the following line), `OBJNAME`, `ROWS`, `COLUMNS` (with `'MARKER'` `'INTORG'`/`'INTEND'`
//! integrality blocks), `RHS`, `RANGES`, `BOUNDS` and `ENDATA`. Conventions:
//!
//! * **Layout.** A section header starts in column 1; data lines start with a blank (so a
//!   column named `RHS` or `OBJSENSE` is fine, as in `silly-names.mps`). An unindented line that
//!   is not a section keyword is read as data. Lines whose first non-blank character is `*` are
//!   comments, and so is everything from a token starting with `$` or `*` that follows a line's
//!   first token (`comment.mps`). Names therefore cannot start with `*` or `$`.
//! * **Free, then fixed.** The file is read as free MPS (fields separated by blanks). If that
//!   fails, it is read again as fixed MPS (fields in columns 2-3, 5-12, 15-22, 25-36, 40-47,
//!   50-61), which allows names containing spaces; if that succeeds the model is returned with a
//!   warning, the spaces in names being replaced by `_`. Otherwise the free-format error is
//!   returned.
//! * **Objective.** The first `N` row is the objective (or the one named in `OBJNAME`). Later
//!   `N` rows are kept as [`RowKind::Free`](crate::milp::RowKind::Free) rows (both sides
//!   infinite) with their coefficients, so that they survive a read → write → read cycle; RHS
//!   and RANGES entries on them are ignored with a warning. An RHS entry `v` on the objective row
//!   sets the objective constant to `-v` (the HiGHS and CPLEX convention).
//! * **Infinity.** In RHS, RANGES and BOUNDS, any value with `|v| ≥ 1e30` (including `inf`,
//!   `infinity`) is infinite. Matrix and objective coefficients must be finite. `nan` anywhere is
//!   an error naming the line.
//! * **RANGES** `R` on row with RHS `b`: `E` row, `R > 0`: `[b, b + |R|]`; `E`, `R < 0`:
//!   `[b − |R|, b]`; `L`: `[b − |R|, b]`; `G`: `[b, b + |R|]`. RHS and RANGES may come in either
//!   order. Only the first RHS (RANGES, BOUNDS) vector is used; entries of other vectors are
//!   ignored with a warning.
//! * **Integers.** A column inside a `MARKER` block is integer. If no BOUNDS entry mentions it,
//!   it gets bounds `[0, 1]` (as HiGHS does; readers disagree here) but stays
//!   [`VarKind::Integer`](crate::milp::VarKind::Integer); any bound entry switches this default
//!   off, so `UP x 5` gives `[0, 5]` and `LO x 0` gives `[0, +∞)`.
//! * **BOUNDS** `UP`, `LO`, `FX`, `FR`, `MI`, `PL`, `BV`, `LI`, `UI` are supported, applied in
//!   file order (a later entry for the same side overrides the earlier one, with a warning).
//!   `BV` makes the column [`VarKind::Binary`](crate::milp::VarKind::Binary) with bounds
//!   `[0, 1]` (a later bound entry turns it back into an integer column); `LI`/`UI` make it
//!   integer. `UP` with a negative value on a column whose lower bound was not given sets the
//!   lower bound to `-∞` (CPLEX convention) with a warning. `SC` and `SI` (semi-continuous,
//!   semi-integer) are rejected as unsupported.
//! * **Anomalies** that have a safe reading are warnings
//!   ([`Warning`](crate::io::Warning)): a duplicate matrix, RHS or RANGES entry (the first one is
//!   kept, as HiGHS does), a missing `ENDATA`, an unclosed `MARKER` block, a missing objective
//!   row, a non-integral `LI`/`UI` bound. References to undefined rows or columns, a column
//!   whose entries are split in two blocks, a duplicate row and unknown bound types are errors
//!   ([`ParseError`]).
//! * **Our own comments.** A comment line `* netspec: maximize, objective negated` before
//!   `ROWS` (which [`write()`] emits) flips the sense back to maximisation and negates the
//!   objective and its constant, so that write → read gives back the same model exactly. A
//!   comment `* netspec: binary NAME` marks an integer column with bounds inside `[0, 1]` as
//!   [`VarKind::Binary`](crate::milp::VarKind::Binary) (used for binaries whose bounds are not
//!   `[0, 1]`). A comment `* netspec: range NAME LHS RHS` gives the exact sides of a ranged row
//!   whose width `RHS − LHS` is not representable (so that no RANGES value reproduces both
//!   sides exactly).
//!
//! # Writing ([`write()`])
//!
//! Free MPS in the classic layout. Integer and binary columns are written inside `MARKER`
//! blocks and always with explicit bounds (readers disagree on the default bounds of integer
//! columns); binaries with bounds `[0, 1]` as `BV`; continuous columns only with the bounds that
//! differ from `[0, +∞)`. A column with no entries gets a zero objective entry so that it
//! exists. Numbers are written in the shortest form that reads back to the same `f64`. The RHS
//! section is written even when empty (SCIP's reader requires it after COLUMNS).
//!
//! Ranged rows are written as `L` or `G` rows plus a RANGES entry chosen so that the two sides
//! read back exactly whenever such an entry exists (otherwise other readers get the sides within
//! an ulp, and ours reads the exact sides from a `* netspec: range` comment). Free rows are
//! written as `N` rows after the objective row.
//!
//! Names are made writable and unique (see [`NameMap`]): whitespace and control characters
//! become `_`, a leading `*` or `$` becomes `_`, an empty name becomes `_`, a column named like
//! a section keyword (`RHS`, `BOUNDS`, `MAX`, ...; HiGHS reads those as headers even when
//! indented) gets a `_` suffix, and clashes get a `_2`, `_3`, ... suffix. The objective row's
//! name is claimed first, so a constraint with the same name is the one renamed.
//!
//! By default a maximisation is written as the minimisation of the negated objective, because
//! some readers (CBC) ignore `OBJSENSE`; see [`WriteOptions::negate_max`]. Finite bounds and
//! sides with `|v| ≥ 1e30` cannot be written faithfully: they read back as infinite.

mod names;
mod read;
mod write;

#[cfg(test)]
mod tests;

use crate::io::NameMap;
use crate::milp::Model;

pub use read::read_str;

/// The comment line by which [`write()`] marks a maximisation written as the minimisation of the
/// negated objective (recognised by [`read_str`]).
pub const NEGATED_MAX_COMMENT: &str = "* netspec: maximize, objective negated";

/// The prefix of the comment line by which [`write()`] marks a binary column whose bounds are not
/// `[0, 1]` (the column name follows).
pub const BINARY_COMMENT_PREFIX: &str = "* netspec: binary ";

/// The prefix of the comment line by which [`write()`] gives the exact sides of a ranged row
/// when no RANGES value reproduces both (the row name and the two sides follow). Our reader
/// applies them when they agree with the sides from RHS and RANGES to within `1e-9` relative.
pub const RANGE_COMMENT_PREFIX: &str = "* netspec: range ";

/// Options for [`write()`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WriteOptions {
    /// Write a maximisation as the minimisation of the negated objective (and negated
    /// constant), preceded by the comment [`NEGATED_MAX_COMMENT`] which [`read_str`] undoes.
    /// Portable: some readers (e.g. CBC's) ignore `OBJSENSE`. When `false`, an `OBJSENSE`
    /// section with `MAX` is written instead. Default `true`.
    pub negate_max: bool,
    /// Pad names to 8 characters so that short-named files line up like fixed MPS (readability
    /// only; the file is free MPS either way). Default `true`.
    pub align: bool,
    /// Comment lines written at the top of the file (`* …`), e.g. what a formulation left out
    /// or wrote in another form. Line breaks in a comment start new comment lines.
    pub comments: Vec<String>,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions { negate_max: true, align: true, comments: Vec::new() }
    }
}

/// Writes `model` as free MPS and returns how names were changed to make them writable.
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] on a model that has no MPS form: a NaN
/// anywhere, an infinite coefficient, or a bound or side on the wrong side of infinity.
pub fn write<W: std::io::Write>(model: &Model, w: &mut W, opts: &WriteOptions) -> std::io::Result<NameMap> {
    write::write(model, w, opts)
}

/// A malformed MPS file: where, and what.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}: {kind}")]
pub struct ParseError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub kind: ParseErrorKind,
}

/// What is wrong in an MPS file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParseErrorKind {
    /// A line outside any section that is not a section header.
    #[error("expected a section header (NAME, ROWS, COLUMNS, ...), found `{0}`")]
    ExpectedSection(String),
    /// A section this reader does not support (quadratic, SOS, indicator, ... sections).
    #[error("section `{0}` is not supported")]
    UnsupportedSection(String),
    /// A section that appears twice.
    #[error("section `{0}` appears twice")]
    DuplicateSection(String),
    /// A section that needs an earlier one (e.g. COLUMNS before ROWS).
    #[error("section `{section}` must come after `{needs}`")]
    SectionOrder {
        /// The section found.
        section: String,
        /// The section that must precede it.
        needs: &'static str,
    },
    /// The file ends without a required section.
    #[error("missing {0} section")]
    MissingSection(&'static str),
    /// A line with the wrong number of fields.
    #[error("wrong number of fields in {section} line: found {found}, expected {expected}")]
    FieldCount {
        /// The section.
        section: &'static str,
        /// How many fields the line has.
        found: usize,
        /// What was expected.
        expected: &'static str,
    },
    /// A token that should be a number.
    #[error("invalid number `{0}`")]
    BadNumber(String),
    /// A NaN value.
    #[error("NaN value `{0}`")]
    NaN(String),
    /// An infinite matrix or objective coefficient (or objective constant).
    #[error("infinite coefficient `{0}`")]
    InfiniteCoefficient(String),
    /// A row type other than N, L, G, E.
    #[error("unknown row type `{0}` (expected N, L, G or E)")]
    BadRowType(String),
    /// A row name defined twice in ROWS.
    #[error("row `{0}` is defined twice")]
    DuplicateRow(String),
    /// A column whose entries are split into two separate blocks of COLUMNS.
    #[error("column `{0}` appears again after other columns")]
    DuplicateColumn(String),
    /// A reference to a row not defined in ROWS.
    #[error("unknown row `{0}`")]
    UnknownRow(String),
    /// A reference to a column not defined in COLUMNS.
    #[error("unknown column `{0}`")]
    UnknownColumn(String),
    /// A name that cannot be used (contains control characters).
    #[error("unusable name {0:?}")]
    BadName(String),
    /// A malformed integrality marker line.
    #[error("bad integrality marker: {0}")]
    BadMarker(String),
    /// An unknown OBJSENSE value.
    #[error("unknown objective sense `{0}` (expected MAX or MIN)")]
    BadObjSense(String),
    /// An unknown bound type.
    #[error("unknown bound type `{0}`")]
    UnknownBoundType(String),
    /// A bound type this reader does not support (SC, SI).
    #[error("bound type `{0}` ({1}) is not supported")]
    UnsupportedBound(String, &'static str),
    /// A bound or row side on the wrong side of infinity (e.g. `UP x -1e30`).
    #[error("{0}")]
    InfiniteBound(String),
    /// A fixed-format line that cannot be cut into fields.
    #[error("fixed-format line cannot be split into fields")]
    BadFixedLine,
}
