//! The MPS reader. See the module documentation of [`super`] for the conventions.

use super::names::{make_unique, FxHashMap};
use super::{ParseError, ParseErrorKind, BINARY_COMMENT_PREFIX, NEGATED_MAX_COMMENT, RANGE_COMMENT_PREFIX};
use crate::io::{ReadModel, Warning};
use crate::milp::{Model, Sense, VarId, VarKind};

/// Values with at least this magnitude in RHS, RANGES and BOUNDS are infinite.
const INFINITY_THRESHOLD: f64 = 1e30;
/// The row index of the objective in the row map.
const OBJ: u32 = u32::MAX;
/// "No column" marker.
const NONE: u32 = u32::MAX;
/// At most this many fields are kept per line (the longest valid line has 5).
const MAX_FIELDS: usize = 7;

/// Reads an MPS model from text: free format first, fixed format as a fallback (see the module
/// documentation). Never panics.
pub fn read_str(text: &str) -> Result<ReadModel, ParseError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    match Parser::new(Mode::Free).run(text) {
        Ok(read) => Ok(read),
        Err(free_err) if fixed_may_help(&free_err.kind) => match Parser::new(Mode::Fixed).run(text) {
            Ok(mut read) => {
                read.warnings.insert(
                    0,
                    Warning {
                        line: free_err.line,
                        message: format!(
                            "not valid free MPS ({}); the file was read as fixed-format MPS",
                            free_err.kind
                        ),
                    },
                );
                Ok(read)
            }
            Err(_) => Err(free_err),
        },
        Err(e) => Err(e),
    }
}

/// Whether a free-format error may come from a fixed-format file with spaces in names.
fn fixed_may_help(kind: &ParseErrorKind) -> bool {
    matches!(
        kind,
        ParseErrorKind::FieldCount { .. }
            | ParseErrorKind::BadNumber(_)
            | ParseErrorKind::UnknownRow(_)
            | ParseErrorKind::UnknownColumn(_)
            | ParseErrorKind::DuplicateColumn(_)
            | ParseErrorKind::DuplicateRow(_)
            | ParseErrorKind::BadMarker(_)
            | ParseErrorKind::BadRowType(_)
            | ParseErrorKind::UnknownBoundType(_)
    )
}

#[derive(Copy, Clone, PartialEq, Eq, Debug)]
enum Mode {
    Free,
    Fixed,
}

#[derive(Copy, Clone, PartialEq, Eq, Debug)]
enum Section {
    None,
    Name,
    ObjSense,
    ObjName,
    Rows,
    Columns,
    Rhs,
    Ranges,
    Bounds,
}

impl Section {
    fn label(self) -> &'static str {
        match self {
            Section::None => "",
            Section::Name => "NAME",
            Section::ObjSense => "OBJSENSE",
            Section::ObjName => "OBJNAME",
            Section::Rows => "ROWS",
            Section::Columns => "COLUMNS",
            Section::Rhs => "RHS",
            Section::Ranges => "RANGES",
            Section::Bounds => "BOUNDS",
        }
    }

    fn bit(self) -> u16 {
        1 << (self as u16)
    }
}

/// Sections this reader recognises but does not support.
const UNSUPPORTED_SECTIONS: &[&str] = &[
    "QMATRIX",
    "QUADOBJ",
    "QSECTION",
    "QCMATRIX",
    "CSECTION",
    "SOS",
    "SETS",
    "INDICATORS",
    "DELAYEDROWS",
    "MODELCUTS",
    "USERCUTS",
    "LAZYCONS",
    "GENCONS",
    "PWLOBJ",
    "PWLNAM",
    "PWLCON",
    "BRANCH",
];

/// A row type from ROWS.
#[derive(Copy, Clone, PartialEq, Eq, Debug)]
enum RowType {
    L,
    G,
    E,
    /// An N row other than the objective.
    Free,
}

struct Column<'a> {
    name: &'a str,
    obj: f64,
    marker_int: bool,
    int: bool,
    bv: bool,
    any_bound: bool,
    lb_set: bool,
    ub_set: bool,
    lb: f64,
    ub: f64,
}

/// Which vector (RHS, RANGES, BOUNDS) is in use, and whether others were reported.
#[derive(Default)]
struct VectorChoice<'a> {
    first: Option<&'a str>,
    warned: bool,
}

struct Parser<'a> {
    mode: Mode,
    warnings: Vec<Warning>,
    section: Section,
    seen: u16,
    name: &'a str,
    sense: Sense,
    negated: bool,
    obj_hint: Option<&'a str>,
    obj_name: Option<&'a str>,
    obj_constant: Option<f64>,
    row_index: FxHashMap<&'a str, u32>,
    row_names: Vec<&'a str>,
    row_type: Vec<RowType>,
    rhs: Vec<f64>,
    rhs_set: Vec<bool>,
    ranges: Vec<(u32, f64, usize)>,
    range_set: Vec<bool>,
    col_index: FxHashMap<&'a str, u32>,
    cols: Vec<Column<'a>>,
    entry_row: Vec<u32>,
    entry_col: Vec<u32>,
    entry_val: Vec<f64>,
    row_last_col: Vec<u32>,
    cur_col: u32,
    cur_obj_seen: bool,
    in_int: bool,
    int_open_line: usize,
    rhs_vec: VectorChoice<'a>,
    ranges_vec: VectorChoice<'a>,
    bounds_vec: VectorChoice<'a>,
    binary_comments: Vec<(&'a str, usize)>,
    range_comments: Vec<(&'a str, usize)>,
}

type PResult<T> = Result<T, ParseErrorKind>;

fn err(line: usize, kind: ParseErrorKind) -> ParseError {
    ParseError { line, kind }
}

/// Parses a number; `nan` is an error, and so is anything `f64::from_str` rejects (after
/// accepting a Fortran `D` exponent).
#[inline]
fn parse_num(tok: &str) -> PResult<f64> {
    match tok.parse::<f64>() {
        Ok(v) if v.is_nan() => Err(ParseErrorKind::NaN(tok.to_string())),
        Ok(v) => Ok(v),
        Err(_) => parse_num_slow(tok),
    }
}

#[cold]
fn parse_num_slow(tok: &str) -> PResult<f64> {
    if tok.contains(['d', 'D']) {
        if let Ok(v) = tok.replace(['d', 'D'], "e").parse::<f64>() {
            if v.is_nan() {
                return Err(ParseErrorKind::NaN(tok.to_string()));
            }
            return Ok(v);
        }
    }
    Err(ParseErrorKind::BadNumber(tok.to_string()))
}

/// A matrix or objective coefficient: finite.
#[inline]
fn parse_coef(tok: &str) -> PResult<f64> {
    let v = parse_num(tok)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(ParseErrorKind::InfiniteCoefficient(tok.to_string()))
    }
}

/// A bound, side or range value: `|v| ≥ 1e30` is infinite.
#[inline]
fn parse_bound(tok: &str) -> PResult<f64> {
    let v = parse_num(tok)?;
    Ok(if v >= INFINITY_THRESHOLD {
        f64::INFINITY
    } else if v <= -INFINITY_THRESHOLD {
        f64::NEG_INFINITY
    } else {
        v
    })
}

#[inline]
fn is_blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// Splits a free-format data line into fields. Stops at a `$` token, or a `*` token after the
/// first (comments). Returns the number of fields (which may exceed `MAX_FIELDS`; only the first
/// `MAX_FIELDS` are stored).
#[inline]
fn free_fields<'a>(line: &'a str, out: &mut [&'a str; MAX_FIELDS]) -> usize {
    let mut n = 0;
    for tok in line.split_ascii_whitespace() {
        if tok.starts_with('$') || (n > 0 && tok.starts_with('*')) {
            break;
        }
        if n < MAX_FIELDS {
            out[n] = tok;
        }
        n += 1;
    }
    n
}

/// Fixed-format field positions (0-based byte ranges), and the gaps that must be blank.
const FIXED_FIELDS: [(usize, usize); 6] = [(1, 3), (4, 12), (14, 22), (24, 36), (39, 47), (49, 61)];
const FIXED_GAPS: [(usize, usize); 6] = [(0, 1), (3, 4), (12, 14), (22, 24), (36, 39), (47, 49)];

/// Splits a fixed-format data line into its non-empty fields (trimmed). A `$` at the start of
/// field 3 or 5 starts a comment; text beyond column 61 is ignored.
fn fixed_fields<'a>(line: &'a str, out: &mut [&'a str; MAX_FIELDS]) -> PResult<usize> {
    let bytes = line.as_bytes();
    let len = bytes.len().min(61);
    // The gaps between fields must be blank.
    for &(a, b) in FIXED_GAPS.iter() {
        if a >= len {
            break;
        }
        if !bytes[a..b.min(len)].iter().all(|&c| is_blank(c)) {
            return Err(ParseErrorKind::BadFixedLine);
        }
    }
    let mut n = 0;
    for (k, &(a, b)) in FIXED_FIELDS.iter().enumerate() {
        if a >= len {
            break;
        }
        let field = line.get(a..b.min(len)).ok_or(ParseErrorKind::BadFixedLine)?;
        let field = field.trim_matches(|c| c == ' ' || c == '\t');
        if field.is_empty() {
            continue;
        }
        if (k == 2 || k == 4) && field.starts_with('$') {
            break;
        }
        out[n] = field;
        n += 1;
    }
    Ok(n)
}

fn has_control(name: &str) -> bool {
    name.chars().any(|c| c.is_control())
}

impl<'a> Parser<'a> {
    fn new(mode: Mode) -> Self {
        Parser {
            mode,
            warnings: Vec::new(),
            section: Section::None,
            seen: 0,
            name: "",
            sense: Sense::Minimize,
            negated: false,
            obj_hint: None,
            obj_name: None,
            obj_constant: None,
            row_index: FxHashMap::default(),
            row_names: Vec::new(),
            row_type: Vec::new(),
            rhs: Vec::new(),
            rhs_set: Vec::new(),
            ranges: Vec::new(),
            range_set: Vec::new(),
            col_index: FxHashMap::default(),
            cols: Vec::new(),
            entry_row: Vec::new(),
            entry_col: Vec::new(),
            entry_val: Vec::new(),
            row_last_col: Vec::new(),
            cur_col: NONE,
            cur_obj_seen: false,
            in_int: false,
            int_open_line: 0,
            rhs_vec: VectorChoice::default(),
            ranges_vec: VectorChoice::default(),
            bounds_vec: VectorChoice::default(),
            binary_comments: Vec::new(),
            range_comments: Vec::new(),
        }
    }

    fn warn(&mut self, line: usize, message: String) {
        self.warnings.push(Warning { line, message });
    }

    fn run(mut self, text: &'a str) -> Result<ReadModel, ParseError> {
        // A rough size hint: one nonzero per ~20 bytes.
        let hint = text.len() / 24;
        self.entry_row.reserve(hint);
        self.entry_col.reserve(hint);
        self.entry_val.reserve(hint);

        let mut line_no = 0usize;
        let mut ended = false;
        let mut fields: [&'a str; MAX_FIELDS] = [""; MAX_FIELDS];
        for raw in text.split('\n') {
            line_no += 1;
            let line = raw.strip_suffix('\r').unwrap_or(raw);
            let bytes = line.as_bytes();
            if bytes.is_empty() {
                continue;
            }
            if !is_blank(bytes[0]) {
                // Column 1: a comment, a section header, or unindented data.
                if bytes[0] == b'*' {
                    self.comment(line, line_no);
                    continue;
                }
                let (word, rest) = match line.find([' ', '\t']) {
                    Some(p) => (&line[..p], &line[p..]),
                    None => (line, ""),
                };
                match self.header(word, rest, line_no)? {
                    HeaderRead::Handled => continue,
                    HeaderRead::End => {
                        ended = true;
                        break;
                    }
                    HeaderRead::NotHeader => {}
                }
            } else {
                let trimmed = line.trim_start_matches([' ', '\t']);
                if trimmed.is_empty() {
                    continue;
                }
                if trimmed.starts_with('*') {
                    continue;
                }
            }
            // A data line.
            let n = match (self.mode, self.section) {
                (Mode::Fixed, Section::Rows | Section::Columns | Section::Rhs | Section::Ranges | Section::Bounds) => {
                    fixed_fields(line, &mut fields).map_err(|k| err(line_no, k))?
                }
                _ => free_fields(line, &mut fields),
            };
            if n == 0 {
                continue;
            }
            let f = &fields[..n.min(MAX_FIELDS)];
            let res = match self.section {
                Section::None | Section::Name => Err(ParseErrorKind::ExpectedSection(truncate(line.trim(), 40))),
                Section::ObjSense => self.objsense_line(f, n),
                Section::ObjName => self.objname_line(f, n, line_no),
                Section::Rows => self.rows_line(f, n),
                Section::Columns => self.columns_line(f, n, line_no),
                Section::Rhs => self.rhs_line(f, n, line_no),
                Section::Ranges => self.ranges_line(f, n, line_no),
                Section::Bounds => self.bounds_line(f, n, line_no),
            };
            res.map_err(|k| err(line_no, k))?;
        }
        if !ended && text.ends_with('\n') {
            // The empty piece after the final newline is not a line.
            line_no -= 1;
        }
        let line_no = line_no.max(1);
        if !ended {
            self.leave_section(line_no);
            self.warn(line_no, "missing ENDATA: the file ends without it".into());
        }
        if self.seen & Section::Rows.bit() == 0 {
            return Err(err(line_no, ParseErrorKind::MissingSection("ROWS")));
        }
        self.build(line_no)
    }

    fn comment(&mut self, line: &'a str, line_no: usize) {
        if !line.starts_with("* netspec:") {
            return;
        }
        let line = line.trim_end();
        if line == NEGATED_MAX_COMMENT {
            if self.seen & Section::Rows.bit() == 0 {
                self.negated = true;
            } else {
                self.warn(line_no, "netspec sense comment after ROWS ignored".into());
            }
        } else if let Some(name) = line.strip_prefix(BINARY_COMMENT_PREFIX) {
            self.binary_comments.push((name.trim(), line_no));
        } else if let Some(rest) = line.strip_prefix(RANGE_COMMENT_PREFIX) {
            self.range_comments.push((rest, line_no));
        }
    }

    fn header(&mut self, word: &'a str, rest: &'a str, line_no: usize) -> Result<HeaderRead, ParseError> {
        let section = match word {
            "NAME" => Section::Name,
            "OBJSENSE" => Section::ObjSense,
            "OBJNAME" => Section::ObjName,
            "ROWS" => Section::Rows,
            "COLUMNS" => Section::Columns,
            "RHS" => Section::Rhs,
            "RANGES" => Section::Ranges,
            "BOUNDS" => Section::Bounds,
            "ENDATA" => {
                self.leave_section(line_no);
                return Ok(HeaderRead::End);
            }
            w if UNSUPPORTED_SECTIONS.contains(&w) => {
                return Err(err(line_no, ParseErrorKind::UnsupportedSection(w.to_string())));
            }
            _ if self.section == Section::None || self.section == Section::Name => {
                return Err(err(line_no, ParseErrorKind::ExpectedSection(truncate(word, 40))));
            }
            _ => return Ok(HeaderRead::NotHeader),
        };
        if self.seen & section.bit() != 0 {
            return Err(err(line_no, ParseErrorKind::DuplicateSection(section.label().to_string())));
        }
        let needs = match section {
            Section::Columns | Section::Rhs | Section::Ranges => Some(Section::Rows),
            Section::Bounds => Some(Section::Columns),
            _ => None,
        };
        if let Some(needs) = needs {
            if self.seen & needs.bit() == 0 {
                return Err(err(
                    line_no,
                    ParseErrorKind::SectionOrder { section: section.label().to_string(), needs: needs.label() },
                ));
            }
        }
        if section == Section::Rows && self.seen & Section::Columns.bit() != 0 {
            return Err(err(line_no, ParseErrorKind::SectionOrder { section: "COLUMNS".into(), needs: "ROWS" }));
        }
        self.leave_section(line_no);
        self.seen |= section.bit();
        self.section = section;
        let rest_trim = rest.trim();
        match section {
            Section::Name => self.name = rest_trim,
            Section::ObjSense | Section::ObjName if !rest_trim.is_empty() => {
                let mut f: [&'a str; MAX_FIELDS] = [""; MAX_FIELDS];
                let n = free_fields(rest_trim, &mut f);
                if n > 0 {
                    let res = if section == Section::ObjSense {
                        self.objsense_line(&f[..n.min(MAX_FIELDS)], n)
                    } else {
                        self.objname_line(&f[..n.min(MAX_FIELDS)], n, line_no)
                    };
                    res.map_err(|k| err(line_no, k))?;
                }
            }
            Section::Rows | Section::Columns | Section::Rhs | Section::Ranges | Section::Bounds => {
                let mut f: [&'a str; MAX_FIELDS] = [""; MAX_FIELDS];
                if free_fields(rest_trim, &mut f) > 0 {
                    self.warn(line_no, format!("text after the {} header ignored", section.label()));
                }
            }
            _ => {}
        }
        Ok(HeaderRead::Handled)
    }

    /// Called when a section ends.
    fn leave_section(&mut self, line_no: usize) {
        match self.section {
            Section::Columns => {
                if self.in_int {
                    let l = self.int_open_line;
                    self.warn(l, "integer MARKER block opened here is never closed (INTEND missing)".into());
                    self.in_int = false;
                }
                self.cur_col = NONE;
            }
            Section::Rows if self.obj_name.is_none() => {
                let message = match self.obj_hint {
                    Some(h) => format!("OBJNAME names `{h}`, which is not an N row: the objective is zero"),
                    None => "no objective (N) row: the objective is zero".to_string(),
                };
                self.warn(line_no, message);
            }
            _ => {}
        }
    }

    fn objsense_line(&mut self, f: &[&'a str], n: usize) -> PResult<()> {
        if n != 1 {
            return Err(ParseErrorKind::FieldCount { section: "OBJSENSE", found: n, expected: "1" });
        }
        let s = f[0].to_ascii_uppercase();
        self.sense = match s.as_str() {
            "MAX" | "MAXIMIZE" | "MAXIMISE" => Sense::Maximize,
            "MIN" | "MINIMIZE" | "MINIMISE" => Sense::Minimize,
            _ => return Err(ParseErrorKind::BadObjSense(truncate(f[0], 40))),
        };
        Ok(())
    }

    fn objname_line(&mut self, f: &[&'a str], n: usize, line_no: usize) -> PResult<()> {
        if n != 1 {
            return Err(ParseErrorKind::FieldCount { section: "OBJNAME", found: n, expected: "1" });
        }
        if self.seen & Section::Rows.bit() != 0 {
            self.warn(line_no, "OBJNAME after ROWS ignored".into());
        } else {
            self.obj_hint = Some(f[0]);
        }
        Ok(())
    }

    fn rows_line(&mut self, f: &[&'a str], n: usize) -> PResult<()> {
        if n != 2 {
            return Err(ParseErrorKind::FieldCount { section: "ROWS", found: n, expected: "2 (type, name)" });
        }
        let (t, name) = (f[0], f[1]);
        let kind = match t {
            "N" | "n" => None,
            "L" | "l" => Some(RowType::L),
            "G" | "g" => Some(RowType::G),
            "E" | "e" => Some(RowType::E),
            _ => return Err(ParseErrorKind::BadRowType(truncate(t, 40))),
        };
        if has_control(name) {
            return Err(ParseErrorKind::BadName(name.to_string()));
        }
        let idx = match kind {
            None if self.obj_name.is_none() && self.obj_hint.is_none_or(|h| h == name) => {
                self.obj_name = Some(name);
                OBJ
            }
            _ => self.row_names.len() as u32,
        };
        if self.row_index.insert(name, idx).is_some() {
            return Err(ParseErrorKind::DuplicateRow(name.to_string()));
        }
        if idx != OBJ {
            self.row_names.push(name);
            self.row_type.push(kind.unwrap_or(RowType::Free));
        }
        Ok(())
    }

    fn start_column(&mut self, name: &'a str) -> PResult<u32> {
        if self.cur_col != NONE && self.cols[self.cur_col as usize].name == name {
            return Ok(self.cur_col);
        }
        if has_control(name) {
            return Err(ParseErrorKind::BadName(name.to_string()));
        }
        let j = self.cols.len() as u32;
        if self.col_index.insert(name, j).is_some() {
            return Err(ParseErrorKind::DuplicateColumn(name.to_string()));
        }
        self.cols.push(Column {
            name,
            obj: 0.0,
            marker_int: self.in_int,
            int: self.in_int,
            bv: false,
            any_bound: false,
            lb_set: false,
            ub_set: false,
            lb: 0.0,
            ub: f64::INFINITY,
        });
        self.cur_col = j;
        self.cur_obj_seen = false;
        Ok(j)
    }

    fn columns_line(&mut self, f: &[&'a str], n: usize, line_no: usize) -> PResult<()> {
        // Integrality markers: `name 'MARKER' 'INTORG'` (also without the name).
        let marker = if n >= 2 && f[1] == "'MARKER'" {
            Some(&f[2.min(f.len())..])
        } else if f[0] == "'MARKER'" {
            Some(&f[1..])
        } else {
            None
        };
        if let Some(m) = marker {
            if m.len() != 1 || n > 3 {
                return Err(ParseErrorKind::BadMarker("expected 'INTORG' or 'INTEND' after 'MARKER'".into()));
            }
            match (m[0], self.in_int) {
                ("'INTORG'", false) => {
                    self.in_int = true;
                    self.int_open_line = line_no;
                }
                ("'INTEND'", true) => self.in_int = false,
                ("'INTORG'", true) => return Err(ParseErrorKind::BadMarker("'INTORG' inside an integer block".into())),
                ("'INTEND'", false) => {
                    return Err(ParseErrorKind::BadMarker("'INTEND' without a matching 'INTORG'".into()))
                }
                (other, _) => {
                    return Err(ParseErrorKind::BadMarker(format!("unknown marker `{}`", truncate(other, 40))))
                }
            }
            self.cur_col = NONE;
            return Ok(());
        }
        if n != 3 && n != 5 {
            return Err(ParseErrorKind::FieldCount {
                section: "COLUMNS",
                found: n,
                expected: "3 or 5 (column, row, value[, row, value])",
            });
        }
        let j = self.start_column(f[0])?;
        self.column_entry(j, f[1], f[2], line_no)?;
        if n == 5 {
            self.column_entry(j, f[3], f[4], line_no)?;
        }
        Ok(())
    }

    #[inline]
    fn column_entry(&mut self, j: u32, row: &'a str, val: &'a str, line_no: usize) -> PResult<()> {
        let r = match self.row_index.get(row) {
            Some(&r) => r,
            None => return Err(ParseErrorKind::UnknownRow(row.to_string())),
        };
        let v = parse_coef(val)?;
        if r == OBJ {
            if self.cur_obj_seen {
                let name = self.cols[j as usize].name;
                self.warn(line_no, format!("duplicate objective entry for column `{name}` ignored (first one kept)"));
            } else {
                self.cur_obj_seen = true;
                self.cols[j as usize].obj = v;
            }
            return Ok(());
        }
        if self.row_last_col.len() != self.row_names.len() {
            self.row_last_col.resize(self.row_names.len(), NONE);
        }
        let last = &mut self.row_last_col[r as usize];
        if *last == j {
            let name = self.cols[j as usize].name;
            self.warn(line_no, format!("duplicate entry for column `{name}` in row `{row}` ignored (first one kept)"));
            return Ok(());
        }
        *last = j;
        self.entry_row.push(r);
        self.entry_col.push(j);
        self.entry_val.push(v);
        Ok(())
    }

    /// Splits an RHS/RANGES line into its vector name (if any) and (row, value) pairs, and
    /// checks the vector. Returns `None` when the line belongs to another vector.
    fn vector_pairs<'f>(
        &mut self,
        f: &'f [&'a str],
        n: usize,
        which: Section,
        line_no: usize,
    ) -> PResult<Option<&'f [&'a str]>> {
        let section = which.label();
        let pairs = match n {
            2 | 4 => f,
            3 | 5 => {
                let set = f[0];
                let choice = if which == Section::Rhs { &mut self.rhs_vec } else { &mut self.ranges_vec };
                match choice.first {
                    None => choice.first = Some(set),
                    Some(first) if first == set => {}
                    Some(first) => {
                        if !choice.warned {
                            choice.warned = true;
                            self.warn(
                                line_no,
                                format!("{section} vector `{set}` ignored: only the first vector, `{first}`, is used"),
                            );
                        }
                        return Ok(None);
                    }
                }
                &f[1..]
            }
            _ => {
                return Err(ParseErrorKind::FieldCount {
                    section,
                    found: n,
                    expected: "2 to 5 ([vector,] row, value[, row, value])",
                })
            }
        };
        Ok(Some(pairs))
    }

    fn lookup_row(&self, row: &str) -> PResult<u32> {
        match self.row_index.get(row) {
            Some(&r) => Ok(r),
            None => Err(ParseErrorKind::UnknownRow(row.to_string())),
        }
    }

    fn rhs_line(&mut self, f: &[&'a str], n: usize, line_no: usize) -> PResult<()> {
        let Some(pairs) = self.vector_pairs(f, n, Section::Rhs, line_no)? else { return Ok(()) };
        for pair in pairs.chunks_exact(2) {
            let (row, val) = (pair[0], pair[1]);
            let r = self.lookup_row(row)?;
            if r == OBJ {
                let v = parse_coef(val)?;
                if self.obj_constant.is_some() {
                    self.warn(line_no, format!("duplicate RHS entry for the objective `{row}` ignored"));
                } else {
                    self.obj_constant = Some(-v);
                }
                continue;
            }
            let v = parse_bound(val)?;
            let ri = r as usize;
            if self.rhs.len() != self.row_names.len() {
                self.rhs.resize(self.row_names.len(), 0.0);
                self.rhs_set.resize(self.row_names.len(), false);
            }
            let t = self.row_type[ri];
            if t == RowType::Free {
                self.warn(line_no, format!("RHS entry for free row `{row}` ignored"));
                continue;
            }
            if self.rhs_set[ri] {
                self.warn(line_no, format!("duplicate RHS entry for row `{row}` ignored (first one kept)"));
                continue;
            }
            let bad = match t {
                RowType::L => v == f64::NEG_INFINITY,
                RowType::G => v == f64::INFINITY,
                RowType::E => v.is_infinite(),
                RowType::Free => false,
            };
            if bad {
                return Err(ParseErrorKind::InfiniteBound(format!(
                    "infinite right-hand side `{val}` makes row `{row}` infeasible"
                )));
            }
            self.rhs[ri] = v;
            self.rhs_set[ri] = true;
        }
        Ok(())
    }

    fn ranges_line(&mut self, f: &[&'a str], n: usize, line_no: usize) -> PResult<()> {
        let Some(pairs) = self.vector_pairs(f, n, Section::Ranges, line_no)? else { return Ok(()) };
        for pair in pairs.chunks_exact(2) {
            let (row, val) = (pair[0], pair[1]);
            let r = self.lookup_row(row)?;
            let v = parse_bound(val)?;
            if r == OBJ {
                self.warn(line_no, format!("RANGES entry for the objective `{row}` ignored"));
                continue;
            }
            let ri = r as usize;
            if self.row_type[ri] == RowType::Free {
                self.warn(line_no, format!("RANGES entry for free row `{row}` ignored"));
                continue;
            }
            if self.range_set.len() != self.row_names.len() {
                self.range_set.resize(self.row_names.len(), false);
            }
            if self.range_set[ri] {
                self.warn(line_no, format!("duplicate RANGES entry for row `{row}` ignored (first one kept)"));
                continue;
            }
            self.range_set[ri] = true;
            self.ranges.push((r, v, line_no));
        }
        Ok(())
    }

    fn lookup_col(&self, col: &str) -> PResult<u32> {
        match self.col_index.get(col) {
            Some(&j) => Ok(j),
            None => Err(ParseErrorKind::UnknownColumn(col.to_string())),
        }
    }

    fn bounds_line(&mut self, f: &[&'a str], n: usize, line_no: usize) -> PResult<()> {
        let t = f[0];
        let upper = t.to_ascii_uppercase();
        let needs_value = match upper.as_str() {
            "UP" | "LO" | "FX" | "LI" | "UI" => true,
            "MI" | "PL" | "FR" | "BV" => false,
            "SC" => return Err(ParseErrorKind::UnsupportedBound(t.to_string(), "semi-continuous")),
            "SI" => return Err(ParseErrorKind::UnsupportedBound(t.to_string(), "semi-integer")),
            _ => return Err(ParseErrorKind::UnknownBoundType(truncate(t, 40))),
        };
        // (vector, column, value)
        let (set, col, val) = match (needs_value, n) {
            (true, 4) => (Some(f[1]), f[2], Some(f[3])),
            (true, 3) => (None, f[1], Some(f[2])),
            (false, 4) => (Some(f[1]), f[2], None),
            (false, 2) => (None, f[1], None),
            (false, 3) => {
                if self.col_index.contains_key(f[2]) {
                    (Some(f[1]), f[2], None)
                } else if self.col_index.contains_key(f[1]) {
                    (None, f[1], None)
                } else {
                    return Err(ParseErrorKind::UnknownColumn(f[2].to_string()));
                }
            }
            _ => {
                return Err(ParseErrorKind::FieldCount {
                    section: "BOUNDS",
                    found: n,
                    expected: if needs_value {
                        "3 or 4 (type, [vector,] column, value)"
                    } else {
                        "2 to 4 (type, [vector,] column)"
                    },
                })
            }
        };
        if let Some(set) = set {
            match self.bounds_vec.first {
                None => self.bounds_vec.first = Some(set),
                Some(first) if first == set => {}
                Some(first) => {
                    if !self.bounds_vec.warned {
                        self.bounds_vec.warned = true;
                        self.warn(
                            line_no,
                            format!("BOUNDS vector `{set}` ignored: only the first vector, `{first}`, is used"),
                        );
                    }
                    return Ok(());
                }
            }
        }
        let j = self.lookup_col(col)? as usize;
        let v = match val {
            Some(tok) => parse_bound(tok)?,
            None => 0.0,
        };
        let (sets_lb, sets_ub) = match upper.as_str() {
            "UP" | "UI" | "PL" => (false, true),
            "LO" | "LI" | "MI" => (true, false),
            _ => (true, true),
        };
        let c = &self.cols[j];
        if (sets_lb && c.lb_set) || (sets_ub && c.ub_set) {
            self.warn(line_no, format!("bound `{t}` redefines a bound of column `{col}` (the later one applies)"));
        }
        let inf_err = |what: &str| {
            ParseErrorKind::InfiniteBound(format!("bound `{t} {}` for column `{col}` is {what}", val.unwrap_or("")))
        };
        let mut warning = None;
        let c = &mut self.cols[j];
        c.any_bound = true;
        c.bv = false;
        match upper.as_str() {
            "UP" | "UI" => {
                if v == f64::NEG_INFINITY {
                    return Err(inf_err("minus infinity"));
                }
                if v < 0.0 && !c.lb_set && c.lb == 0.0 {
                    c.lb = f64::NEG_INFINITY;
                    warning = Some(format!(
                        "negative upper bound {v} on column `{col}` with no lower bound: lower bound set to -inf"
                    ));
                }
                c.ub = v;
            }
            "LO" | "LI" => {
                if v == f64::INFINITY {
                    return Err(inf_err("plus infinity"));
                }
                c.lb = v;
            }
            "FX" => {
                if v.is_infinite() {
                    return Err(inf_err("infinite"));
                }
                c.lb = v;
                c.ub = v;
            }
            "MI" => c.lb = f64::NEG_INFINITY,
            "PL" => c.ub = f64::INFINITY,
            "FR" => {
                c.lb = f64::NEG_INFINITY;
                c.ub = f64::INFINITY;
            }
            _ => {
                // BV
                c.lb = 0.0;
                c.ub = 1.0;
                c.int = true;
                c.bv = true;
            }
        }
        if upper == "LI" || upper == "UI" {
            c.int = true;
            if v.is_finite() && v.fract() != 0.0 {
                warning = Some(format!("integer bound `{t}` for column `{col}` is not an integer: {v}"));
            }
        }
        c.lb_set |= sets_lb;
        c.ub_set |= sets_ub;
        if let Some(w) = warning {
            self.warn(line_no, w);
        }
        Ok(())
    }

    /// Builds the model once the whole file is read.
    fn build(mut self, last_line: usize) -> Result<ReadModel, ParseError> {
        let nrows = self.row_names.len();
        let ncols = self.cols.len();
        self.rhs.resize(nrows, 0.0);

        // Row sides.
        let mut lhs = Vec::with_capacity(nrows);
        let mut rhs = Vec::with_capacity(nrows);
        for (r, t) in self.row_type.iter().enumerate() {
            let b = self.rhs[r];
            let (l, u) = match t {
                RowType::L => (f64::NEG_INFINITY, b),
                RowType::G => (b, f64::INFINITY),
                RowType::E => (b, b),
                RowType::Free => (f64::NEG_INFINITY, f64::INFINITY),
            };
            lhs.push(l);
            rhs.push(u);
        }
        for &(r, v, line) in &self.ranges {
            let r = r as usize;
            let (b, a) = (self.rhs[r], v.abs());
            match self.row_type[r] {
                RowType::L => lhs[r] = b - a,
                RowType::G => rhs[r] = b + a,
                RowType::E if v > 0.0 => rhs[r] = b + a,
                RowType::E if v < 0.0 => lhs[r] = b - a,
                _ => {}
            }
            let (l, u) = (lhs[r], rhs[r]);
            if l.is_nan() || u.is_nan() || l == f64::INFINITY || u == f64::NEG_INFINITY {
                return Err(err(
                    line,
                    ParseErrorKind::InfiniteBound(format!(
                        "range {v} on row `{}` with right-hand side {b} gives no usable sides",
                        self.row_names[r]
                    )),
                ));
            }
        }

        // Exact sides of ranged rows from our own comments.
        for &(text, line) in &self.range_comments {
            let f: Vec<&str> = text.split_ascii_whitespace().collect();
            let parsed = match f.as_slice() {
                [name, l, u] => match (self.row_index.get(name), l.parse::<f64>(), u.parse::<f64>()) {
                    (Some(&r), Ok(l), Ok(u)) if r != OBJ => Some((r as usize, l, u)),
                    _ => None,
                },
                _ => None,
            };
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0);
            match parsed {
                Some((r, l, u))
                    if self.range_set.get(r).copied().unwrap_or(false) && close(l, lhs[r]) && close(u, rhs[r]) =>
                {
                    lhs[r] = l;
                    rhs[r] = u;
                }
                _ => self.warnings.push(Warning {
                    line,
                    message: "netspec range comment does not match a ranged row: ignored".into(),
                }),
            }
        }

        // Column kinds and default bounds.
        for c in &mut self.cols {
            if c.marker_int && !c.any_bound {
                c.lb = 0.0;
                c.ub = 1.0;
            }
        }
        let mut binary_flag = vec![false; ncols];
        for &(name, line) in &self.binary_comments {
            match self.col_index.get(name) {
                Some(&j) => {
                    let c = &self.cols[j as usize];
                    if c.int && c.lb >= 0.0 && c.ub <= 1.0 {
                        binary_flag[j as usize] = true;
                    } else {
                        let message =
                            format!("column `{name}` marked binary is not an integer column within [0, 1]: kept as is");
                        self.warnings.push(Warning { line, message });
                    }
                }
                None => {
                    let message = format!("column `{name}` marked binary does not exist");
                    self.warnings.push(Warning { line, message });
                }
            }
        }

        // Names: in fixed format they may contain spaces, which are replaced.
        let fixed_names = self.mode == Mode::Fixed
            && (self.row_names.iter().any(|n| n.contains(' ')) || self.cols.iter().any(|c| c.name.contains(' ')));
        let (row_out, col_out) = if fixed_names {
            let obj = self.obj_name.map(|o| o.replace(' ', "_"));
            let reserved: Vec<&str> = obj.as_deref().into_iter().collect();
            let (rows, rc) = make_unique(&reserved, self.row_names.iter().copied(), false);
            let rows: Vec<String> = rows.into_iter().map(|c| c.into_owned()).collect();
            let (cols, cc) = make_unique(&[], self.cols.iter().map(|c| c.name), false);
            let cols: Vec<String> = cols.into_iter().map(|c| c.into_owned()).collect();
            if !rc.is_empty() || !cc.is_empty() {
                self.warnings.push(Warning {
                    line: last_line,
                    message: format!("{} names containing spaces were rewritten with `_`", rc.len() + cc.len()),
                });
            }
            (Some(rows), Some(cols))
        } else {
            (None, None)
        };

        let mut model = Model::new(self.name);
        model.sense = self.sense;
        model.objective_name = match self.obj_name {
            Some(n) if fixed_names => n.replace(' ', "_"),
            Some(n) => n.to_string(),
            None => "obj".to_string(),
        };
        model.obj_constant = self.obj_constant.unwrap_or(0.0);
        let nnz = self.entry_row.len();
        model.reserve(ncols, nrows, nnz);
        for (j, c) in self.cols.iter().enumerate() {
            let kind = if c.bv || binary_flag[j] {
                VarKind::Binary
            } else if c.int {
                VarKind::Integer
            } else {
                VarKind::Continuous
            };
            let name = match &col_out {
                Some(v) => v[j].clone(),
                None => c.name.to_string(),
            };
            model.add_var(name, kind, c.lb, c.ub, c.obj);
        }

        // Column-ordered entries → rows (within a row, entries stay in column order).
        let mut start = vec![0usize; nrows + 1];
        for &r in &self.entry_row {
            start[r as usize + 1] += 1;
        }
        for r in 0..nrows {
            start[r + 1] += start[r];
        }
        let mut next = start.clone();
        let mut ecol = vec![VarId(0); nnz];
        let mut eval = vec![0f64; nnz];
        for k in 0..nnz {
            let r = self.entry_row[k] as usize;
            let p = next[r];
            ecol[p] = VarId(self.entry_col[k]);
            eval[p] = self.entry_val[k];
            next[r] = p + 1;
        }
        drop(next);
        for r in 0..nrows {
            let (s, e) = (start[r], start[r + 1]);
            let name = match &row_out {
                Some(v) => v[r].clone(),
                None => self.row_names[r].to_string(),
            };
            model.add_row(name, lhs[r], rhs[r], ecol[s..e].iter().copied().zip(eval[s..e].iter().copied()));
        }

        if self.negated {
            model.sense = match model.sense {
                Sense::Minimize => Sense::Maximize,
                Sense::Maximize => Sense::Minimize,
            };
            model.obj_constant = -model.obj_constant;
            for j in 0..ncols {
                let v = model.var_mut(VarId(j as u32));
                v.obj = -v.obj;
            }
        }
        Ok(ReadModel { model, warnings: self.warnings })
    }
}

enum HeaderRead {
    Handled,
    End,
    NotHeader,
}

/// At most `max` characters of `s` (for error messages about garbage).
fn truncate(s: &str, max: usize) -> String {
    match s.char_indices().nth(max) {
        Some((i, _)) => format!("{}...", &s[..i]),
        None => s.to_string(),
    }
}
