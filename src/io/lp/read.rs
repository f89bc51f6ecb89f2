//! The LP reader: a single pass over the tokens, building the [`Model`] directly.

use super::lexer::{Cmp, Directive, Lexer, Tok, Token};
use super::names::{keyword, value_word, Keyword, ValueWord};
use super::{ParseError, ParseErrorKind, MAX_WARNINGS};
use crate::io::{ReadModel, Warning};
use crate::milp::{Model, RowId, Sense, VarId, VarKind};
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};

/// A small, fast hasher for names (FxHash).
#[derive(Default, Clone, Copy)]
struct FxHasher(u64);

const FX_K: u64 = 0x517c_c1b7_2722_0a95;

impl FxHasher {
    #[inline]
    fn add(&mut self, w: u64) {
        self.0 = (self.0.rotate_left(5) ^ w).wrapping_mul(FX_K);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        let mut chunks = bytes.chunks_exact(8);
        for c in &mut chunks {
            let mut w = [0u8; 8];
            w.copy_from_slice(c);
            self.add(u64::from_le_bytes(w));
        }
        let rest = chunks.remainder();
        if !rest.is_empty() {
            let mut w = [0u8; 8];
            w[..rest.len()].copy_from_slice(rest);
            self.add(u64::from_le_bytes(w) ^ ((rest.len() as u64) << 59));
        }
    }
    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(u64::from(i));
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.0.rotate_left(26)
    }
}

type FxMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;

/// Name → variable index. Names of up to 15 bytes are stored inline (no pointer into the text
/// to follow on a lookup, which would mostly miss the cache on a large file).
#[derive(Default)]
struct NameIndex<'a> {
    short: FxMap<[u64; 2], u32>,
    long: FxMap<&'a str, u32>,
}

impl<'a> NameIndex<'a> {
    #[inline]
    fn pack(name: &str) -> Option<[u64; 2]> {
        let b = name.as_bytes();
        if b.len() > 15 {
            return None;
        }
        let mut k = [0u8; 16];
        k[..b.len()].copy_from_slice(b);
        k[15] = b.len() as u8;
        let (lo, hi) = k.split_at(8);
        Some([u64::from_le_bytes(lo.try_into().ok()?), u64::from_le_bytes(hi.try_into().ok()?)])
    }

    #[inline]
    fn get(&self, name: &str) -> Option<u32> {
        match Self::pack(name) {
            Some(k) => self.short.get(&k).copied(),
            None => self.long.get(name).copied(),
        }
    }

    fn insert(&mut self, name: &'a str, j: u32) {
        match Self::pack(name) {
            Some(k) => self.short.insert(k, j),
            None => self.long.insert(name, j),
        };
    }
}

/// Values with `|v| ≥ 1e30` are infinite in bounds and row sides.
const INF_THRESHOLD: f64 = 1e30;

fn to_bound(v: f64) -> f64 {
    if v >= INF_THRESHOLD {
        f64::INFINITY
    } else if v <= -INF_THRESHOLD {
        f64::NEG_INFINITY
    } else {
        v
    }
}

fn describe(t: &Tok) -> String {
    match t {
        Tok::Name(n) => format!("name `{n}`"),
        Tok::Num(_, s) => format!("number `{s}`"),
        Tok::Plus => "`+`".into(),
        Tok::Minus => "`-`".into(),
        Tok::Colon => "`:`".into(),
        Tok::Cmp(Cmp::Le) => "`<=`".into(),
        Tok::Cmp(Cmp::Ge) => "`>=`".into(),
        Tok::Cmp(Cmp::Eq) => "`=`".into(),
        Tok::Arrow => "`->`".into(),
        Tok::Quad(c) => format!("`{}`", *c as char),
        Tok::Eof => "end of file".into(),
    }
}

/// A section being read.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Section {
    Objective(Sense),
    Constraints,
    Bounds,
    Generals,
    Binaries,
    Semi,
    Sos,
    End,
}

/// What an expression held besides its terms (which are in `Parser::terms`).
#[derive(Clone, Copy, Debug, Default)]
struct Expr {
    has_terms: bool,
    n_const: usize,
    constant: f64,
    /// Line of the first constant (for errors).
    const_line: usize,
}

// Flags per variable.
const LB_SET: u8 = 1;
const UB_SET: u8 = 2;
const IN_BODY: u8 = 4;
const GENERAL: u8 = 8;
const BINARY: u8 = 16;

struct Parser<'a> {
    lx: Lexer<'a>,
    buf: [Token<'a>; 2],
    nbuf: usize,
    model: Model,
    index: NameIndex<'a>,
    flags: Vec<u8>,
    /// Per variable: 1 + position in `terms` while an expression is read, else 0.
    slot: Vec<u32>,
    terms: Vec<(VarId, f64)>,
    /// Explicit row names → line.
    row_names: FxMap<&'a str, usize>,
    unnamed: Vec<RowId>,
    warnings: Vec<Warning>,
    dropped_warnings: usize,
    have_objective: bool,
    negated_max: bool,
    /// A ranged-row directive applies to the next row.
    range_first: Option<(RowId, usize)>,
    /// Variables created outside the objective and constraints: count, first (name, line).
    side_vars: (usize, Option<(String, usize)>),
    /// Variables listed as binary, with the line.
    binary_lines: Vec<(VarId, usize)>,
    /// Negative upper bounds set while the lower bound was the default 0.
    negative_ub: Vec<(VarId, usize)>,
}

/// Reads an LP file.
pub(super) fn read_str(text: &str) -> Result<ReadModel, ParseError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let eof = Token { tok: Tok::Eof, line: 1, idx: 0 };
    let mut p = Parser {
        lx: Lexer::new(text),
        buf: [eof, eof],
        nbuf: 0,
        model: Model::new(""),
        index: NameIndex::default(),
        flags: Vec::new(),
        slot: Vec::new(),
        terms: Vec::new(),
        row_names: FxMap::default(),
        unnamed: Vec::new(),
        warnings: Vec::new(),
        dropped_warnings: 0,
        have_objective: false,
        negated_max: false,
        range_first: None,
        side_vars: (0, None),
        binary_lines: Vec::new(),
        negative_ub: Vec::new(),
    };
    p.run()?;
    Ok(p.finish())
}

impl<'a> Parser<'a> {
    // ----- token stream -----

    #[inline]
    fn peek(&mut self) -> Result<Token<'a>, ParseError> {
        if self.nbuf == 0 {
            self.buf[0] = self.lx.lex()?;
            self.nbuf = 1;
        }
        Ok(self.buf[0])
    }

    #[inline]
    fn peek2(&mut self) -> Result<Token<'a>, ParseError> {
        self.peek()?;
        if self.nbuf == 1 {
            self.buf[1] = self.lx.lex()?;
            self.nbuf = 2;
        }
        Ok(self.buf[1])
    }

    /// Drops the peeked token.
    #[inline]
    fn bump(&mut self) {
        if self.nbuf == 2 {
            self.buf[0] = self.buf[1];
            self.nbuf = 1;
        } else {
            self.nbuf = 0;
        }
    }

    fn warn(&mut self, line: usize, message: impl Into<String>) {
        if self.warnings.len() < MAX_WARNINGS - 1 {
            self.warnings.push(Warning { line, message: message.into() });
        } else {
            self.dropped_warnings += 1;
        }
    }

    fn unexpected(t: &Token, expected: &'static str) -> ParseError {
        let kind = match t.tok {
            Tok::Eof => ParseErrorKind::UnexpectedEof(expected),
            Tok::Quad(_) => ParseErrorKind::Unsupported("quadratic terms"),
            Tok::Arrow => ParseErrorKind::Unsupported("indicator constraints"),
            _ => ParseErrorKind::UnexpectedToken { found: describe(&t.tok), expected },
        };
        ParseError { line: t.line, kind }
    }

    fn error(line: usize, kind: ParseErrorKind) -> ParseError {
        ParseError { line, kind }
    }

    // ----- sections -----

    /// The section keyword at the current token, if it is one (not consumed).
    fn section_at(&mut self) -> Result<Option<Section>, ParseError> {
        let t = self.peek()?;
        let Tok::Name(w) = t.tok else { return Ok(None) };
        let Some(kw) = keyword(w) else { return Ok(None) };
        if kw == Keyword::End {
            // Whatever follows `End` is ignored, even text the lexer would reject.
            return Ok(match self.peek2() {
                Ok(t2) if t2.tok == Tok::Colon => None,
                _ => Some(Section::End),
            });
        }
        let t2 = self.peek2()?;
        if t2.tok == Tok::Colon {
            return Ok(None); // a name such as `st:` or `bounds:`
        }
        let second = |want: &str| matches!(t2.tok, Tok::Name(n) if n.eq_ignore_ascii_case(want));
        Ok(Some(match kw {
            Keyword::Minimize => Section::Objective(Sense::Minimize),
            Keyword::Maximize => Section::Objective(Sense::Maximize),
            Keyword::SubjectTo => Section::Constraints,
            Keyword::Subject if second("to") => Section::Constraints,
            Keyword::Such if second("that") => Section::Constraints,
            Keyword::Subject | Keyword::Such => return Ok(None),
            Keyword::Lazy if second("constraints") => {
                return Err(Self::error(t.line, ParseErrorKind::Unsupported("lazy constraints")))
            }
            Keyword::User if second("cuts") => {
                return Err(Self::error(t.line, ParseErrorKind::Unsupported("user cuts")))
            }
            Keyword::Lazy | Keyword::User => return Ok(None),
            Keyword::Bounds => Section::Bounds,
            Keyword::Generals => Section::Generals,
            Keyword::Binaries => Section::Binaries,
            Keyword::Semi => Section::Semi,
            Keyword::Sos => Section::Sos,
            Keyword::End => Section::End,
        }))
    }

    /// Consumes the keyword of `section` (one or two words; `semi-continuous` is three tokens).
    fn consume_section(&mut self, section: Section) -> Result<(), ParseError> {
        let t = self.peek()?;
        self.bump();
        match section {
            Section::Constraints => {
                if let Tok::Name(w) = t.tok {
                    if matches!(keyword(w), Some(Keyword::Subject | Keyword::Such)) {
                        self.bump();
                    }
                }
            }
            Section::Semi => {
                let continuous = self.peek()?.tok == Tok::Minus
                    && matches!(self.peek2()?.tok, Tok::Name(w) if w.eq_ignore_ascii_case("continuous"));
                if continuous {
                    self.bump();
                    self.bump();
                }
            }
            _ => {}
        }
        Ok(())
    }

    fn run(&mut self) -> Result<(), ParseError> {
        // Before the first section: plain words are a title (skipped), anything else an error.
        let mut skipped: Option<(usize, String, usize)> = None; // line, first words, count
        let first = loop {
            let t = self.peek()?;
            match t.tok {
                Tok::Eof => break None,
                Tok::Name(w) => {
                    if let Some(s) = self.section_at()? {
                        break Some((s, t));
                    }
                    self.bump();
                    match &mut skipped {
                        None => skipped = Some((t.line, w.to_string(), 1)),
                        Some((_, text, n)) => {
                            if text.len() < 40 {
                                text.push(' ');
                                text.push_str(w);
                            }
                            *n += 1;
                        }
                    }
                }
                _ => return Err(Self::error(t.line, ParseErrorKind::ExpectedSection(describe(&t.tok)))),
            }
        };
        if let Some((line, text, n)) = skipped {
            self.warn(line, format!("{n} word(s) before the first section ignored (`{text}`)"));
        }
        let first_idx = first.map_or(u64::MAX, |(_, t)| t.idx);
        if let Some((idx, name)) = self.lx.problem_name {
            if idx <= first_idx {
                self.model.name = name.to_string();
            }
        }
        let mut max_header = None;
        while let Some(d) = self.lx.directives.front().copied() {
            if d.idx > first_idx {
                break;
            }
            self.lx.directives.pop_front();
            if d.text.starts_with("maximize, objective negated") {
                max_header = Some(d.line);
            } else {
                self.stray_directive(d);
            }
        }
        let Some((mut section, _)) = first else {
            if self.model.num_vars() == 0 {
                self.warn(self.lx.line(), "no section found: the model is empty");
            }
            return Ok(());
        };
        let mut saw_objective_sense = None;
        loop {
            let kw_line = self.peek()?.line;
            self.consume_section(section)?;
            match section {
                Section::Objective(sense) => {
                    if self.have_objective {
                        return Err(Self::error(kw_line, ParseErrorKind::DuplicateSection("objective")));
                    }
                    saw_objective_sense = Some(sense);
                    self.objective(sense)?;
                }
                Section::Constraints => self.constraints()?,
                Section::Bounds => self.bounds()?,
                Section::Generals => self.name_list(GENERAL)?,
                Section::Binaries => self.name_list(BINARY)?,
                Section::Semi => self.unsupported_list("semi-continuous variables")?,
                Section::Sos => self.unsupported_list("SOS constraints")?,
                Section::End => {
                    if !self.lx.rest_is_blank() || (self.nbuf > 0 && self.buf[0].tok != Tok::Eof) {
                        self.warn(self.lx.line(), "text after `End` ignored");
                    }
                    break;
                }
            }
            if let Some(first) = self.range_first.take() {
                self.warn(first.1, "`ranged row` comment ignored: no second row follows");
            }
            match self.section_at()? {
                Some(s) => section = s,
                None => {
                    let t = self.peek()?;
                    if t.tok == Tok::Eof {
                        break;
                    }
                    // Each section reader stops only at a section keyword or the end.
                    return Err(Self::unexpected(&t, "a section keyword"));
                }
            }
        }
        while let Some(d) = self.lx.directives.pop_front() {
            self.stray_directive(d);
        }
        if let Some(line) = max_header {
            match saw_objective_sense {
                Some(Sense::Maximize) => self.warn(
                    line,
                    "`netspec: maximize, objective negated` comment ignored: the objective is already `Maximize`",
                ),
                _ => self.negated_max = true,
            }
        }
        Ok(())
    }

    fn stray_directive(&mut self, d: Directive) {
        let msg = if d.text.starts_with("ranged row") {
            "`netspec: ranged row` comment ignored: it must come right before a row".to_string()
        } else if d.text.starts_with("maximize, objective negated") {
            "`netspec: maximize, objective negated` comment ignored: it must come before the first section".to_string()
        } else {
            format!("unknown `netspec:` comment ignored (`{}`)", d.text)
        };
        self.warn(d.line, msg);
    }

    // ----- variables and expressions -----

    /// The id of variable `name`, created if new.
    #[inline]
    fn var(&mut self, name: &'a str, line: usize, in_body: bool) -> VarId {
        if let Some(j) = self.index.get(name) {
            if in_body {
                self.flags[j as usize] |= IN_BODY;
            }
            return VarId(j);
        }
        let id = self.model.add_var(name, VarKind::Continuous, 0.0, f64::INFINITY, 0.0);
        self.index.insert(name, id.0);
        self.flags.push(if in_body { IN_BODY } else { 0 });
        self.slot.push(0);
        if !in_body {
            self.side_vars.0 += 1;
            if self.side_vars.1.is_none() {
                self.side_vars.1 = Some((name.to_string(), line));
            }
        }
        id
    }

    #[inline]
    fn add_term(&mut self, name: &'a str, coef: f64, line: usize) {
        let v = self.var(name, line, true);
        let s = self.slot[v.index()] as usize;
        if s == 0 {
            self.terms.push((v, coef));
            self.slot[v.index()] = self.terms.len() as u32;
        } else {
            self.terms[s - 1].1 += coef;
        }
    }

    fn clear_terms(&mut self) {
        for &(v, _) in &self.terms {
            self.slot[v.index()] = 0;
        }
        self.terms.clear();
    }

    /// Whether the peeked token `Name(w)` is a variable here: not a section keyword, not a row
    /// name (followed by `:`), not `inf`/`nan`.
    fn is_var_word(&mut self, w: &str) -> Result<bool, ParseError> {
        if value_word(w).is_some() {
            return Ok(false);
        }
        if keyword(w).is_some() && self.section_at()?.is_some() {
            return Ok(false);
        }
        Ok(self.peek2()?.tok != Tok::Colon)
    }

    /// Reads `[sign]… (number | inf)` at the current token, or `None` (nothing consumed) if
    /// there is no sign and no value there.
    fn value(&mut self, expected: &'static str) -> Result<Option<(f64, Token<'a>)>, ParseError> {
        let mut sign = 1.0;
        let mut have_sign = false;
        loop {
            let t = self.peek()?;
            match t.tok {
                Tok::Plus => have_sign = true,
                Tok::Minus => {
                    have_sign = true;
                    sign = -sign;
                }
                Tok::Num(v, _) => {
                    self.bump();
                    return Ok(Some((sign * v, t)));
                }
                Tok::Name(w) => match value_word(w) {
                    Some(ValueWord::Infinity) => {
                        self.bump();
                        return Ok(Some((sign * f64::INFINITY, t)));
                    }
                    Some(ValueWord::NaN) => return Err(Self::error(t.line, ParseErrorKind::NaN(w.to_string()))),
                    None if have_sign => return Err(Self::unexpected(&t, expected)),
                    None => return Ok(None),
                },
                _ if have_sign => return Err(Self::unexpected(&t, expected)),
                _ => return Ok(None),
            }
            self.bump();
        }
    }

    /// Reads a linear expression into `self.terms` (which must be empty); stops before
    /// anything that cannot continue it.
    fn expr(&mut self) -> Result<Expr, ParseError> {
        let mut e = Expr::default();
        let mut first = true;
        loop {
            let mut t = self.peek()?;
            let mut sign = 1.0;
            let mut have_sign = false;
            while matches!(t.tok, Tok::Plus | Tok::Minus) {
                if t.tok == Tok::Minus {
                    sign = -sign;
                }
                have_sign = true;
                self.bump();
                t = self.peek()?;
            }
            if !have_sign && !first {
                return Ok(e);
            }
            first = false;
            let (coef, coef_tok) = match t.tok {
                Tok::Num(v, _) => {
                    self.bump();
                    (sign * v, Some(t))
                }
                Tok::Name(w) => match value_word(w) {
                    Some(ValueWord::NaN) => return Err(Self::error(t.line, ParseErrorKind::NaN(w.to_string()))),
                    Some(ValueWord::Infinity) => {
                        self.bump();
                        (sign * f64::INFINITY, Some(t))
                    }
                    None => {
                        if !self.is_var_word(w)? {
                            if have_sign {
                                return Err(Self::unexpected(&t, "a term after the sign"));
                            }
                            return Ok(e);
                        }
                        self.bump();
                        self.add_term(w, sign, t.line);
                        e.has_terms = true;
                        continue;
                    }
                },
                Tok::Quad(_) | Tok::Arrow => return Err(Self::unexpected(&t, "a term")),
                _ => {
                    if have_sign {
                        return Err(Self::unexpected(&t, "a term after the sign"));
                    }
                    return Ok(e);
                }
            };
            // A number: the coefficient of the name that follows, or a constant.
            let t2 = self.peek()?;
            if let Tok::Name(w) = t2.tok {
                if value_word(w) == Some(ValueWord::NaN) {
                    return Err(Self::error(t2.line, ParseErrorKind::NaN(w.to_string())));
                }
                if self.is_var_word(w)? {
                    if !coef.is_finite() {
                        let text = match coef_tok.map(|c| c.tok) {
                            Some(Tok::Num(_, s)) | Some(Tok::Name(s)) => s,
                            _ => "inf",
                        };
                        return Err(Self::error(t.line, ParseErrorKind::InfiniteCoefficient(text.to_string())));
                    }
                    self.bump();
                    self.add_term(w, coef, t2.line);
                    e.has_terms = true;
                    continue;
                }
            } else if matches!(t2.tok, Tok::Quad(_)) {
                return Err(Self::unexpected(&t2, "a term"));
            }
            if e.n_const == 0 {
                e.constant = coef;
                e.const_line = t.line;
            } else {
                e.constant += coef;
            }
            e.n_const += 1;
        }
    }

    // ----- objective -----

    fn objective(&mut self, sense: Sense) -> Result<(), ParseError> {
        self.have_objective = true;
        self.model.sense = sense;
        let t = self.peek()?;
        if let Tok::Name(w) = t.tok {
            if self.peek2()?.tok == Tok::Colon && (keyword(w).is_none() || self.section_at()?.is_none()) {
                self.model.objective_name = w.to_string();
                self.bump();
                self.bump();
            }
        }
        let e = self.expr()?;
        for &(v, c) in &self.terms {
            self.model.var_mut(v).obj = c;
        }
        self.clear_terms();
        if e.n_const > 0 {
            if !e.constant.is_finite() {
                return Err(Self::error(e.const_line, ParseErrorKind::InfiniteCoefficient(e.constant.to_string())));
            }
            self.model.obj_constant = e.constant;
        }
        let t = self.peek()?;
        match t.tok {
            Tok::Eof => Ok(()),
            Tok::Cmp(_) => Err(Self::error(
                t.line,
                ParseErrorKind::MissingSection(
                    "comparison in the objective: is `Subject To` missing before the constraints?",
                ),
            )),
            Tok::Name(_) if self.peek2()?.tok == Tok::Colon => Err(Self::error(
                t.line,
                ParseErrorKind::MissingSection("second named expression in the objective: is `Subject To` missing?"),
            )),
            Tok::Name(_) if self.section_at()?.is_some() => Ok(()),
            _ => Err(Self::unexpected(&t, "`+` or `-` before the next term, or a section keyword")),
        }
    }

    // ----- constraints -----

    fn constraints(&mut self) -> Result<(), ParseError> {
        loop {
            let t = self.peek()?;
            if t.tok == Tok::Eof || self.section_at()?.is_some() {
                return Ok(());
            }
            self.constraint(t)?;
        }
    }

    fn constraint(&mut self, first: Token<'a>) -> Result<(), ParseError> {
        // A `ranged row` comment right before this row?
        let mut ranged_here = None;
        while let Some(d) = self.lx.directives.front().copied() {
            if d.idx > first.idx {
                break;
            }
            self.lx.directives.pop_front();
            if d.idx == first.idx && d.text.starts_with("ranged row") {
                ranged_here = Some(d.line);
            } else {
                self.stray_directive(d);
            }
        }
        let line = first.line;
        let mut name = None;
        if let Tok::Name(w) = first.tok {
            if self.peek2()?.tok == Tok::Colon {
                name = Some(w);
                self.bump();
                self.bump();
            }
        }
        let e1 = self.expr()?;
        let t = self.peek()?;
        let Tok::Cmp(c1) = t.tok else {
            return Err(Self::unexpected(&t, "a comparison (`<=`, `>=`, `=`) or the next term"));
        };
        self.bump();
        let (lhs, rhs);
        if !e1.has_terms && e1.n_const > 0 {
            // `value cmp expr` or `value cmp expr cmp value`.
            if e1.n_const > 1 && !e1.constant.is_finite() {
                return Err(Self::error(e1.const_line, ParseErrorKind::InfiniteCoefficient(e1.constant.to_string())));
            }
            let first_value = to_bound(e1.constant);
            let e2 = self.expr()?;
            let c = self.finite_constant(&e2)?;
            let t2 = self.peek()?;
            if let Tok::Cmp(c2) = t2.tok {
                self.bump();
                let (second, _) = self.value("a number")?.ok_or_else(|| Self::unexpected(&t2, "a number"))?;
                let second = to_bound(second);
                let (lo, hi) = match (c1, c2) {
                    (Cmp::Le, Cmp::Le) => (first_value, second),
                    (Cmp::Ge, Cmp::Ge) => (second, first_value),
                    _ => {
                        return Err(Self::error(
                            t2.line,
                            ParseErrorKind::UnexpectedToken {
                                found: describe(&t2.tok),
                                expected:
                                    "the same direction on both sides of a ranged constraint (`lo <= expr <= hi`)",
                            },
                        ))
                    }
                };
                lhs = lo - c;
                rhs = hi - c;
            } else {
                let v = first_value - c;
                (lhs, rhs) = match c1 {
                    Cmp::Le => (v, f64::INFINITY),
                    Cmp::Ge => (f64::NEG_INFINITY, v),
                    Cmp::Eq => (v, v),
                };
            }
        } else {
            let c = self.finite_constant(&e1)?;
            let (v, _) = self.value("a number after the comparison")?.ok_or_else(|| {
                let t = self.buf[0];
                Self::unexpected(&t, "a number after the comparison")
            })?;
            let v = if e1.n_const > 0 { to_bound(v) - c } else { to_bound(v) };
            (lhs, rhs) = match c1 {
                Cmp::Le => (f64::NEG_INFINITY, v),
                Cmp::Ge => (v, f64::INFINITY),
                Cmp::Eq => (v, v),
            };
        }
        // A side that a constant moved to |v| ≥ 1e30 is infinite too, as the same value written
        // would read (so whatever is read writes and reads back the same).
        let (lhs, rhs) = (to_bound(lhs), to_bound(rhs));
        let display = name.unwrap_or("(unnamed)");
        if lhs == f64::INFINITY {
            return Err(Self::error(
                line,
                ParseErrorKind::InfiniteBound(format!("row `{display}` has lower side +infinity")),
            ));
        }
        if rhs == f64::NEG_INFINITY {
            return Err(Self::error(
                line,
                ParseErrorKind::InfiniteBound(format!("row `{display}` has upper side -infinity")),
            ));
        }
        self.finish_row(name, line, lhs, rhs, ranged_here)?;
        self.clear_terms();
        Ok(())
    }

    /// The sum of an expression's constants, which must be finite.
    fn finite_constant(&self, e: &Expr) -> Result<f64, ParseError> {
        if e.n_const == 0 {
            return Ok(0.0);
        }
        if !e.constant.is_finite() {
            return Err(Self::error(e.const_line, ParseErrorKind::InfiniteCoefficient(e.constant.to_string())));
        }
        Ok(e.constant)
    }

    fn finish_row(
        &mut self,
        name: Option<&'a str>,
        line: usize,
        lhs: f64,
        rhs: f64,
        ranged_here: Option<usize>,
    ) -> Result<(), ParseError> {
        // Second half of a ranged row written by us?
        if let Some((first, dline)) = self.range_first.take() {
            let row = self.model.row(first);
            let same = row.vars.len() == self.terms.len()
                && row
                    .vars
                    .iter()
                    .zip(row.coefs)
                    .zip(&self.terms)
                    .all(|((v, a), (w, b))| v == w && a.to_bits() == b.to_bits());
            if same && row.rhs == f64::INFINITY && row.lhs.is_finite() && lhs == f64::NEG_INFINITY && rhs.is_finite() {
                let lo = row.lhs;
                self.model.set_row_sides(first, lo, rhs);
                return Ok(());
            }
            self.warn(
                dline,
                "`ranged row` comment ignored: the two rows after it are not the `>=` and `<=` halves of one row",
            );
        }
        if let Some(n) = name {
            if let Some(&first_line) = self.row_names.get(n) {
                return Err(Self::error(line, ParseErrorKind::DuplicateRow { name: n.to_string(), first_line }));
            }
            self.row_names.insert(n, line);
        }
        let id = self.model.add_row(name.unwrap_or(""), lhs, rhs, self.terms.iter().copied());
        if name.is_none() {
            self.unnamed.push(id);
        }
        if let Some(dline) = ranged_here {
            self.range_first = Some((id, dline));
        }
        Ok(())
    }

    // ----- bounds -----

    fn set_lb(&mut self, v: VarId, value: f64, line: usize) -> Result<(), ParseError> {
        if value == f64::INFINITY {
            let name = &self.model.var(v).name;
            return Err(Self::error(
                line,
                ParseErrorKind::InfiniteBound(format!("lower bound of `{name}` is +infinity")),
            ));
        }
        if self.flags[v.index()] & LB_SET != 0 {
            let name = self.model.var(v).name.clone();
            self.warn(line, format!("lower bound of `{name}` set again (the last one counts)"));
        }
        self.flags[v.index()] |= LB_SET;
        self.model.var_mut(v).lb = value;
        Ok(())
    }

    fn set_ub(&mut self, v: VarId, value: f64, line: usize) -> Result<(), ParseError> {
        if value == f64::NEG_INFINITY {
            let name = &self.model.var(v).name;
            return Err(Self::error(
                line,
                ParseErrorKind::InfiniteBound(format!("upper bound of `{name}` is -infinity")),
            ));
        }
        if self.flags[v.index()] & UB_SET != 0 {
            let name = self.model.var(v).name.clone();
            self.warn(line, format!("upper bound of `{name}` set again (the last one counts)"));
        }
        self.flags[v.index()] |= UB_SET;
        self.model.var_mut(v).ub = value;
        if value < 0.0 && self.flags[v.index()] & LB_SET == 0 {
            self.negative_ub.push((v, line));
        }
        Ok(())
    }

    /// Applies `var cmp value`.
    fn apply_bound(&mut self, v: VarId, cmp: Cmp, value: f64, line: usize) -> Result<(), ParseError> {
        match cmp {
            Cmp::Le => self.set_ub(v, value, line),
            Cmp::Ge => self.set_lb(v, value, line),
            Cmp::Eq => {
                if !value.is_finite() {
                    let name = self.model.var(v).name.clone();
                    return Err(Self::error(
                        line,
                        ParseErrorKind::InfiniteBound(format!("`{name}` fixed at an infinite value")),
                    ));
                }
                self.set_lb(v, value, line)?;
                // A fixing sets both sides at once: do not warn about the upper side.
                self.flags[v.index()] &= !UB_SET;
                self.set_ub(v, value, line)
            }
        }
    }

    /// The variable name at the current token in the bounds section.
    fn bound_var(&mut self, what: &'static str) -> Result<(VarId, Token<'a>), ParseError> {
        let t = self.peek()?;
        match t.tok {
            Tok::Name(w) if value_word(w).is_none() && (keyword(w).is_none() || self.section_at()?.is_none()) => {
                self.bump();
                Ok((self.var(w, t.line, false), t))
            }
            _ => Err(Self::unexpected(&t, what)),
        }
    }

    fn bounds(&mut self) -> Result<(), ParseError> {
        loop {
            let t = self.peek()?;
            if t.tok == Tok::Eof || self.section_at()?.is_some() {
                return Ok(());
            }
            match t.tok {
                Tok::Name(w) if value_word(w).is_none() => {
                    let (v, _) = self.bound_var("a variable")?;
                    let t2 = self.peek()?;
                    match t2.tok {
                        Tok::Name(f) if f.eq_ignore_ascii_case("free") => {
                            self.bump();
                            self.set_lb(v, f64::NEG_INFINITY, t2.line)?;
                            self.set_ub(v, f64::INFINITY, t2.line)?;
                        }
                        Tok::Cmp(c) => {
                            self.bump();
                            let (value, _) =
                                self.value("a number")?.ok_or_else(|| Self::unexpected(&self.buf[0], "a number"))?;
                            self.apply_bound(v, c, to_bound(value), t2.line)?;
                        }
                        Tok::Name(f) => {
                            return Err(Self::error(
                                t2.line,
                                ParseErrorKind::UnknownKeyword {
                                    found: f.to_string(),
                                    context: "after a variable in the bounds section, expected `free` or a comparison",
                                },
                            ))
                        }
                        _ => return Err(Self::unexpected(&t2, "`free` or a comparison")),
                    }
                }
                _ => {
                    // value cmp var [cmp value]
                    let Some((first, _)) = self.value("a number")? else {
                        return Err(Self::unexpected(&t, "a bound (`x <= 5`, `-inf <= x <= 5`, `x free`)"));
                    };
                    let first = to_bound(first);
                    let t2 = self.peek()?;
                    let Tok::Cmp(c1) = t2.tok else { return Err(Self::unexpected(&t2, "a comparison")) };
                    self.bump();
                    let (v, _) = self.bound_var("a variable")?;
                    let t3 = self.peek()?;
                    if let Tok::Cmp(c2) = t3.tok {
                        self.bump();
                        let (second, _) =
                            self.value("a number")?.ok_or_else(|| Self::unexpected(&self.buf[0], "a number"))?;
                        let second = to_bound(second);
                        match (c1, c2) {
                            (Cmp::Le, Cmp::Le) => {
                                self.set_lb(v, first, t2.line)?;
                                self.set_ub(v, second, t3.line)?;
                            }
                            (Cmp::Ge, Cmp::Ge) => {
                                self.set_ub(v, first, t2.line)?;
                                self.set_lb(v, second, t3.line)?;
                            }
                            _ => {
                                return Err(Self::error(
                                    t3.line,
                                    ParseErrorKind::UnexpectedToken {
                                        found: describe(&t3.tok),
                                        expected: "the same direction on both sides of a double bound (`l <= x <= u`)",
                                    },
                                ))
                            }
                        }
                    } else {
                        // `value cmp var` is `var (reversed cmp) value`.
                        let rev = match c1 {
                            Cmp::Le => Cmp::Ge,
                            Cmp::Ge => Cmp::Le,
                            Cmp::Eq => Cmp::Eq,
                        };
                        self.apply_bound(v, rev, first, t2.line)?;
                    }
                }
            }
        }
    }

    // ----- generals, binaries, unsupported sections -----

    fn name_list(&mut self, flag: u8) -> Result<(), ParseError> {
        loop {
            let t = self.peek()?;
            if t.tok == Tok::Eof || self.section_at()?.is_some() {
                return Ok(());
            }
            match t.tok {
                Tok::Name(w) if value_word(w).is_none() => {
                    self.bump();
                    let v = self.var(w, t.line, false);
                    let f = &mut self.flags[v.index()];
                    let before = *f;
                    *f |= flag;
                    if before & (GENERAL | BINARY) != 0 && before & flag == 0 {
                        self.warn(t.line, format!("`{w}` is listed as both general and binary: it is binary"));
                    }
                    if flag == BINARY && before & BINARY == 0 {
                        self.binary_lines.push((v, t.line));
                    }
                }
                _ => return Err(Self::unexpected(&t, "a variable name")),
            }
        }
    }

    fn unsupported_list(&mut self, what: &'static str) -> Result<(), ParseError> {
        let t = self.peek()?;
        if t.tok == Tok::Eof || self.section_at()?.is_some() {
            return Ok(()); // an empty section, as HiGHS writes them
        }
        Err(Self::error(t.line, ParseErrorKind::Unsupported(what)))
    }

    // ----- the end -----

    fn finish(mut self) -> ReadModel {
        // Integrality.
        for j in 0..self.flags.len() {
            if self.flags[j] & (GENERAL | BINARY) == GENERAL {
                self.model.var_mut(VarId(j as u32)).kind = VarKind::Integer;
            }
        }
        for (id, line) in std::mem::take(&mut self.negative_ub) {
            let v = self.model.var(id);
            if self.flags[id.index()] & LB_SET == 0 && v.ub < 0.0 && self.flags[id.index()] & BINARY == 0 {
                let msg = format!(
                    "upper bound {} of `{}` is below its default lower bound 0 (the bounds cross)",
                    v.ub, v.name
                );
                self.warn(line, msg);
            }
        }
        for (id, line) in std::mem::take(&mut self.binary_lines) {
            let f = self.flags[id.index()];
            let v = self.model.var_mut(id);
            v.kind = VarKind::Binary;
            let (lb, ub) = (v.lb, v.ub);
            v.lb = lb.max(0.0);
            v.ub = ub.min(1.0);
            if (f & LB_SET != 0 && lb < 0.0) || (f & UB_SET != 0 && ub > 1.0) {
                let msg =
                    format!("bounds [{lb}, {ub}] of binary variable `{}` clipped to [{}, {}]", v.name, v.lb, v.ub);
                self.warn(line, msg);
            }
        }
        // Names for unnamed rows: R<position>, avoiding names used in the file.
        if !self.unnamed.is_empty() {
            let mut taken: std::collections::HashSet<String> = std::collections::HashSet::new();
            for id in std::mem::take(&mut self.unnamed) {
                let base = format!("R{}", id.0 as u64 + 1);
                let mut name = base.clone();
                let mut k = 1u64;
                while self.row_names.contains_key(name.as_str()) || taken.contains(&name) {
                    name = format!("{base}_{k}");
                    k += 1;
                }
                taken.insert(name.clone());
                self.model.set_row_name(id, name);
            }
        }
        if self.negated_max {
            self.model.sense = Sense::Maximize;
            for j in 0..self.model.num_vars() {
                let v = self.model.var_mut(VarId(j as u32));
                v.obj = -v.obj;
            }
            self.model.obj_constant = -self.model.obj_constant;
        }
        if let (n, Some((name, line))) = &self.side_vars {
            let msg = if *n == 1 {
                format!("variable `{name}` appears only in the bounds or type sections")
            } else {
                format!("{n} variables appear only in the bounds or type sections (the first is `{name}`)")
            };
            let line = *line;
            self.warn(line, msg);
        }
        if self.dropped_warnings > 0 {
            let n = self.dropped_warnings;
            self.warnings.push(Warning { line: 0, message: format!("{n} more warnings not shown") });
        }
        ReadModel { model: self.model, warnings: self.warnings }
    }
}
