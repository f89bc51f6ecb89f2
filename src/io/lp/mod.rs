//! CPLEX LP reader and writer.
//!
//! # Reading ([`read_str`])
//!
//! The reader accepts CPLEX LP files as written by CPLEX, HiGHS, SCIP, Gurobi and CBC:
//!
//! * **Sections** (keywords case-insensitive): `minimize`/`minimise`/`minimum`/`min`,
//!   `maximize`/`maximise`/`maximum`/`max`, `subject to`/`such that`/`st`/`s.t.`/`st.`,
//!   `bounds`/`bound`, `general`/`generals`/`gen`/`integer`/`integers`/`int`,
//!   `binary`/`binaries`/`bin`, `semi-continuous`/`semis`/`semi`, `sos`, `end`. A keyword
//!   followed by `:` is a name (`end: x >= 1` is a row called `end`). Sections may come in any
//!   order and all are optional; everything after `End` is ignored (with a warning). A
//!   semi-continuous or SOS section must be empty (as in files HiGHS writes): any entry in it,
//!   `Lazy Constraints`, `User Cuts`, quadratic terms (`[`, `*`, `^`) and indicator constraints
//!   (`->`) are [`ParseErrorKind::Unsupported`].
//! * **Before the first section**, plain words (a title, as in `1448.lp`) are skipped with a
//!   warning, as SCIP and HiGHS do; anything else (numbers, operators, `:`) is an error, so a
//!   file of garbage is reported rather than read as an empty model.
//! * **Comments** run from `\` to the end of the line. `\Problem name: NAME` before the first
//!   section sets [`Model::name`].
//! * **Expressions**: terms `[sign] [coefficient] name` (a coefficient may touch its name, as in
//!   `2x`), spanning any number of lines; every term but the first needs a sign; a variable
//!   repeated in one expression gets the sum of its coefficients (the entry stays at its first
//!   position). Constants are allowed anywhere in an expression: in the objective they add up to
//!   [`Model::obj_constant`], in a constraint they are moved to the other side (`x + 3 >= 5` is
//!   `x >= 2`). Numbers: `3`, `-2.5`, `.5`, `5.`, `1e+30`, `inf`, `infinity` (any case).
//!   `nan` anywhere, and an infinite coefficient, are errors.
//! * **Constraints**: `[name:] expr sense value` with sense `<`, `<=`, `=<`, `>`, `>=`, `=>`,
//!   `=` (strict and non-strict are the same), plus the reversed form `value sense expr` and
//!   the ranged form `lo <= expr <= hi` (or `hi >= expr >= lo`) that CPLEX and CBC accept. An
//!   empty left side (`r: >= 2`, as HiGHS and SCIP write empty rows) gives a row without
//!   entries. Unnamed rows are called `R1`, `R2`, … after their position, avoiding names used
//!   elsewhere in the file. A row name used twice is an error.
//! * **Infinity**: a bound or a row side `v` with `|v| ≥ 1e30` is infinite (the HiGHS and CPLEX
//!   convention), also where a constant of the row moves its side there (`x + 1e30 >= 5` is a
//!   free row); coefficients and the objective constant are taken as written. A lower side
//!   of `+∞` or an upper side of `−∞` is an error.
//! * **Bounds**: `x <= u`, `x >= l`, `x = v`, `l <= x <= u`, `u >= x >= l`, the reversed
//!   `5 >= x`, `x free`, `-inf <= x`, `x >= -inf`. A later bound on the same side overrides an
//!   earlier one (with a warning). Default bounds are `[0, +∞)`; note that `x <= -5` leaves
//!   the lower bound at 0 (a warning is given; HiGHS rejects such a file).
//! * **Generals** make a variable [`VarKind::Integer`], keeping its bounds (default
//!   `[0, +∞)`). **Binaries** make it [`VarKind::Binary`] with its bounds intersected with
//!   `[0, 1]` (so a bare binary gets `[0, 1]` and `x = 0` stays fixed at 0, as in
//!   `fixed-binary.lp`); declared bounds reaching outside `[0, 1]` are clipped with a warning
//!   (SCIP and CBC clip the same way; HiGHS keeps an upper bound such as 5). A variable listed
//!   in both sections is binary (with a warning). Binaries are applied after the whole file is
//!   read, so section order does not matter.
//! * **Variables** are created at their first appearance, in file order (objective, then
//!   constraints, bounds, generals, binaries for a file in the usual order); variables that
//!   appear only in the bounds or type sections are created too (with one summary warning).
//! * **Our own conventions** (see the writer below) are recognised through `\ netspec:`
//!   comments: [`NEGATED_MAX_COMMENT`] before the first section turns a `Minimize` objective
//!   back into a maximisation (negating the coefficients and the constant), and
//!   [`RANGED_ROW_COMMENT`] before a row joins it with the row that follows into one ranged
//!   row (if the two rows have the same entries, the first being `>=` and the second `<=`;
//!   otherwise the comment is ignored with a warning). Other readers see ordinary comments.
//!
//! Lines are numbered from 1 in errors and warnings. The reader never panics; at most
//! [`MAX_WARNINGS`] warnings are kept (a last one says how many more there were).
//!
//! # Writing ([`write`])
//!
//! The writer emits a file that HiGHS (1.15), SCIP (10) and CBC's `CoinLpIO` (2.11) all read
//! back as the same model (checked by reading hundreds of random written files with all three;
//! note that SCIP itself drops coefficients below 1e-9 and takes values from 1e20 as infinite),
//! and that this reader reads back *exactly* (`==` on [`Model`] after renaming through the
//! [`NameMap`], every coefficient bit for bit):
//!
//! * **Layout**: a `\` comment header, `\Problem name: …`, `Minimize`/`Maximize`, the objective
//!   (` obj: …`), `Subject To`, `Bounds`, `Generals`, `Binaries`, `End`. Lines are wrapped
//!   before [`WriteOptions::max_line_len`] characters; a continuation line starts with a
//!   space and no term, sense or right-hand side is ever split.
//! * **Numbers** are written in the shortest form that reads back to the same `f64` (`ryu`),
//!   with the sign always explicit between terms; a coefficient `1` is omitted.
//! * **Variable order**: every variable is written in the objective, with `+ 0 x` when its
//!   objective coefficient is zero, so that first appearance order (which every reader uses)
//!   is the model's order.
//! * **Objective constant**: a trailing constant term (`obj: 2 x + 3 y + 7.5`). HiGHS, SCIP
//!   and CoinLpIO read it as the objective offset (SCIP and CoinLpIO reject a constant *before*
//!   the first term, hence at the end). The `cbc` 2.10 command-line program reads such a file
//!   but then drops the offset from the objective values it reports.
//! * **Maximisation**: by default ([`WriteOptions::negate_max`]) a maximisation is written as
//!   `Minimize` of the negated objective under the header comment [`NEGATED_MAX_COMMENT`]
//!   (the same convention as our MPS writer); other readers then solve the equivalent
//!   minimisation, and objective values must be negated. With `negate_max = false`, `Maximize`
//!   is written; HiGHS and SCIP read that correctly, but CoinLpIO turns it into a minimisation
//!   by negating the coefficients and *not* the constant.
//! * **Ranged rows** (`lo <= a·x <= hi`, both finite and different) are written as two rows,
//!   `name: a·x >= lo` and `name_rhs: a·x <= hi` (the second name made unique), preceded by the
//!   comment [`RANGED_ROW_COMMENT`]. The one-line form `lo <= a·x <= hi` is rejected by HiGHS
//!   and SCIP and misread by CoinLpIO, and the HiGHS and SCIP writers split ranged rows the
//!   same way; other readers therefore see one more row per ranged row.
//! * **Free rows** (both sides infinite) are written `name: a·x >= -inf`, which all three
//!   readers keep as a row with two infinite sides (the HiGHS and SCIP writers drop such rows).
//! * **Empty rows** are written `name: >= 2` (no terms), the form the HiGHS and SCIP writers
//!   use, which all three readers accept.
//! * **Bounds**: continuous columns only when not `[0, +∞)`; every general integer column
//!   explicitly; binary columns only when their bounds are not `[0, 1]` (e.g. fixed ones), and
//!   they are listed under `Binaries`. Forms: `x = v`, `x free`, `-inf <= x <= u`, `x >= l`,
//!   `l <= x <= u`. Finite bounds or sides with `|v| ≥ 1e30` cannot be written faithfully:
//!   they read back as infinite.
//! * **Names** are made portable: characters other than ASCII letters, digits and
//!   ``!"#$%&(),.;?@_`'{}~`` become `_` (`/` breaks HiGHS and CoinLpIO, `|` CoinLpIO); a name
//!   starting with a digit or one of `.(),;`, equal to a keyword (`st`, `end`, `free`, `inf`,
//!   `bin`, …), starting like an exponent (`e`, `e12`, `ee…`) or with `inf`/`nan` (HiGHS parses
//!   `inf1` as a number) gets a `_` prefix; names longer than [`WriteOptions::max_name_len`]
//!   (default 100, the CoinLpIO limit) are shortened; clashes get a `_1`, `_2`, … suffix.
//!   Changed names are returned in the [`NameMap`]. The objective name shares the rows'
//!   namespace (CoinLpIO wants it distinct from every row name): a row named like the
//!   objective is renamed, and a renamed objective appears in the map's `rows` part (unless a
//!   row has the same original name). The upper halves of ranged rows are not in the map.
//! * A model that has no LP form (a NaN, an infinite coefficient or constant, a bound or side
//!   on the wrong side of infinity) is refused with [`std::io::ErrorKind::InvalidInput`].

mod lexer;
mod names;
mod read;
mod write;

#[cfg(test)]
mod tests;

use crate::io::NameMap;
use crate::milp::Model;
#[allow(unused_imports)] // used by the docs
use crate::milp::VarKind;

/// The comment line by which [`write`] marks a maximisation written as the minimisation of the
/// negated objective (recognised by [`read_str`] before the first section).
pub const NEGATED_MAX_COMMENT: &str = "\\ netspec: maximize, objective negated";

/// The comment line by which [`write`] marks a ranged row written as two rows (`>=`, then
/// `<=`); [`read_str`] joins the two rows that follow it back into one.
pub const RANGED_ROW_COMMENT: &str = "\\ netspec: ranged row";

/// At most this many warnings are returned by [`read_str`]; the last one counts the rest.
pub const MAX_WARNINGS: usize = 1000;

/// Options for [`write`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WriteOptions {
    /// Write a maximisation as the minimisation of the negated objective (and constant), under
    /// the comment [`NEGATED_MAX_COMMENT`], which [`read_str`] undoes. When `false`, `Maximize`
    /// is written. Default `true`.
    pub negate_max: bool,
    /// Wrap lines before they exceed this many characters. A line is longer only when a single
    /// piece (a term with a long name, a bound) is; the longest piece is the name plus 37
    /// characters. Default `250` (CPLEX and older readers truncate lines beyond 255).
    pub max_line_len: usize,
    /// Names longer than this are shortened (and the change recorded in the [`NameMap`]).
    /// Default `100`: CoinLpIO (CBC's reader) rejects longer names, and renames *every*
    /// variable or row of a file that has one. Values are clamped to `8..=255` (255 is the CPLEX
    /// limit); with names of at most 200 characters no line exceeds 250 characters.
    pub max_name_len: usize,
    /// Comment lines written after the header (`\ …`), e.g. what a formulation left out or
    /// wrote in another form. Line breaks in a comment start new comment lines.
    pub comments: Vec<String>,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions { negate_max: true, max_line_len: 250, max_name_len: 100, comments: Vec::new() }
    }
}

/// Reads a model in CPLEX LP format (see the [module documentation](self) for the accepted
/// syntax).
pub fn read_str(text: &str) -> Result<crate::io::ReadModel, ParseError> {
    read::read_str(text)
}

/// Writes `model` in CPLEX LP format and returns how names were changed to make them
/// writable (see the [module documentation](self) for the encoding).
///
/// Fails with [`std::io::ErrorKind::InvalidInput`] on a model that has no LP form: a NaN
/// anywhere, an infinite coefficient or objective constant, or a bound or side on the wrong
/// side of infinity.
pub fn write<W: std::io::Write>(model: &Model, w: &mut W, opts: &WriteOptions) -> std::io::Result<NameMap> {
    write::write(model, w, opts)
}

/// A malformed LP file: where, and what.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}: {kind}")]
pub struct ParseError {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub kind: ParseErrorKind,
}

/// What is wrong in an LP file.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParseErrorKind {
    /// A token where something else was expected.
    #[error("unexpected {found}, expected {expected}")]
    UnexpectedToken {
        /// The token found, quoted (e.g. `` `^` `` or ``name `x` ``).
        found: String,
        /// What the reader expected there.
        expected: &'static str,
    },
    /// The file ends in the middle of something.
    #[error("unexpected end of file, expected {0}")]
    UnexpectedEof(&'static str),
    /// Something other than plain words before the first section keyword.
    #[error("expected a section keyword (Minimize, Maximize, Subject To, Bounds, ...), found {0}")]
    ExpectedSection(String),
    /// Content that belongs in a section the file does not open (e.g. a constraint in the
    /// objective section: `Subject To` is missing).
    #[error("{0}")]
    MissingSection(&'static str),
    /// A word where a keyword was expected (e.g. `x frees` in the bounds section).
    #[error("unknown keyword `{found}` ({context})")]
    UnknownKeyword {
        /// The word found.
        found: String,
        /// Where, and what was expected.
        context: &'static str,
    },
    /// A section that may appear only once appears again.
    #[error("section `{0}` appears twice")]
    DuplicateSection(&'static str),
    /// A NaN value.
    #[error("NaN value `{0}`")]
    NaN(String),
    /// An infinite coefficient (matrix or objective) or an infinite constant in an expression.
    #[error("infinite coefficient `{0}`")]
    InfiniteCoefficient(String),
    /// A bound or row side on the wrong side of infinity (e.g. `x >= inf`).
    #[error("{0}")]
    InfiniteBound(String),
    /// A feature of the LP format that this reader does not support.
    #[error("{0} are not supported")]
    Unsupported(&'static str),
    /// A row name defined twice.
    #[error("row `{name}` is defined twice (first on line {first_line})")]
    DuplicateRow {
        /// The name.
        name: String,
        /// Where it was first defined.
        first_line: usize,
    },
    /// A character that cannot appear in an LP file (a control character).
    #[error("invalid character {0:?}")]
    InvalidCharacter(char),
}
