//! Byte-level tokenizer for LP files.

use super::{ParseError, ParseErrorKind};

/// A comparison operator (`<` and `<=` are the same in LP files).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Cmp {
    Le,
    Ge,
    Eq,
}

/// One token.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(super) enum Tok<'a> {
    /// A word: variable or row name, keyword, `inf`, `free`, …
    Name(&'a str),
    /// An unsigned numeric literal, with its text.
    Num(f64, &'a str),
    Plus,
    Minus,
    Colon,
    Cmp(Cmp),
    /// `->` or `<->` (indicator constraints).
    Arrow,
    /// `[`, `]`, `*`, `^` (quadratic terms).
    Quad(u8),
    Eof,
}

/// A token, where it is, and its position in the token stream.
#[derive(Copy, Clone, Debug)]
pub(super) struct Token<'a> {
    pub tok: Tok<'a>,
    pub line: usize,
    /// 0-based index in the token stream.
    pub idx: u64,
}

/// A `\ netspec: …` comment.
#[derive(Copy, Clone, Debug)]
pub(super) struct Directive<'a> {
    pub line: usize,
    /// Index of the token that follows the comment.
    pub idx: u64,
    /// The text after `netspec:`, trimmed.
    pub text: &'a str,
}

// Byte classes.
const WS: u8 = 0;
const NL: u8 = 1;
const NAME: u8 = 2;
const DIGIT: u8 = 3;
const DOT: u8 = 4;
const OP: u8 = 5;
const BSL: u8 = 6;
const BAD: u8 = 7;

const fn classes() -> [u8; 256] {
    let mut t = [NAME; 256];
    let mut i = 0;
    while i < 32 {
        t[i] = BAD;
        i += 1;
    }
    t[127] = BAD;
    t[b' ' as usize] = WS;
    t[b'\t' as usize] = WS;
    t[b'\r' as usize] = WS;
    t[0x0b] = WS;
    t[0x0c] = WS;
    t[b'\n' as usize] = NL;
    let mut d = b'0';
    while d <= b'9' {
        t[d as usize] = DIGIT;
        d += 1;
    }
    t[b'.' as usize] = DOT;
    let ops = b"+-:<>=[]*^";
    let mut k = 0;
    while k < ops.len() {
        t[ops[k] as usize] = OP;
        k += 1;
    }
    t[b'\\' as usize] = BSL;
    t
}

static CLASS: [u8; 256] = classes();

/// Bytes that continue a name: name characters, digits, `.`.
#[inline]
fn name_cont(c: u8) -> bool {
    matches!(CLASS[c as usize], NAME | DIGIT | DOT)
}

/// Tokenizer over the whole text.
pub(super) struct Lexer<'a> {
    text: &'a str,
    pos: usize,
    line: usize,
    count: u64,
    /// `\ netspec:` comments seen so far and not yet taken.
    pub directives: std::collections::VecDeque<Directive<'a>>,
    /// The first `\Problem name:` comment: (index of the following token, name).
    pub problem_name: Option<(u64, &'a str)>,
}

impl<'a> Lexer<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        Lexer { text, pos: 0, line: 1, count: 0, directives: Default::default(), problem_name: None }
    }

    /// Current line (of the next unread byte).
    pub(super) fn line(&self) -> usize {
        self.line
    }

    /// Whether only blanks and comments are left. Does not move.
    pub(super) fn rest_is_blank(&self) -> bool {
        let mut in_comment = false;
        for &c in &self.text.as_bytes()[self.pos..] {
            match c {
                b'\n' => in_comment = false,
                _ if in_comment => {}
                b'\\' => in_comment = true,
                _ if CLASS[c as usize] == WS => {}
                _ => return false,
            }
        }
        true
    }

    fn comment(&mut self, start: usize) -> usize {
        let b = self.text.as_bytes();
        let end = b[start..].iter().position(|&c| c == b'\n').map_or(b.len(), |k| start + k);
        // Body after the backslash, leading blanks skipped.
        let mut s = start + 1;
        while s < end && (b[s] == b' ' || b[s] == b'\t') {
            s += 1;
        }
        if end - s >= 8 {
            let first = b[s] | 0x20;
            if first == b'n' && &b[s..s + 8] == b"netspec:" {
                if let Some(t) = self.text.get(s + 8..end) {
                    self.directives.push_back(Directive { line: self.line, idx: self.count, text: t.trim() });
                }
            } else if first == b'p'
                && self.problem_name.is_none()
                && end - s >= 13
                && b[s..s + 13].eq_ignore_ascii_case(b"problem name:")
            {
                if let Some(t) = self.text.get(s + 13..end) {
                    self.problem_name = Some((self.count, t.trim()));
                }
            }
        }
        end
    }

    fn err(&self, kind: ParseErrorKind) -> ParseError {
        ParseError { line: self.line, kind }
    }

    /// The next token.
    pub(super) fn lex(&mut self) -> Result<Token<'a>, ParseError> {
        let b = self.text.as_bytes();
        let n = b.len();
        let mut i = self.pos;
        loop {
            if i >= n {
                self.pos = i;
                return Ok(Token { tok: Tok::Eof, line: self.line, idx: self.count });
            }
            match CLASS[b[i] as usize] {
                WS => i += 1,
                NL => {
                    self.line += 1;
                    i += 1;
                }
                BSL => i = self.comment(i),
                _ => break,
            }
        }
        let start = i;
        let c = b[i];
        let tok = match CLASS[c as usize] {
            NAME => {
                i += 1;
                while i < n && name_cont(b[i]) {
                    i += 1;
                }
                Tok::Name(self.slice(start, i)?)
            }
            DOT if !(i + 1 < n && b[i + 1].is_ascii_digit()) => {
                i += 1;
                while i < n && name_cont(b[i]) {
                    i += 1;
                }
                Tok::Name(self.slice(start, i)?)
            }
            DIGIT | DOT => {
                let (v, end) = scan_number(b, i);
                i = end;
                let text = self.slice(start, i)?;
                if v.is_nan() {
                    // Unreachable (the scanner only accepts valid literals), but never a silent NaN.
                    self.pos = i;
                    return Err(self.err(ParseErrorKind::NaN(text.to_string())));
                }
                Tok::Num(v, text)
            }
            OP => {
                let next = if i + 1 < n { b[i + 1] } else { 0 };
                i += 1;
                match c {
                    b'+' => Tok::Plus,
                    b'-' if next == b'>' => {
                        i += 1;
                        Tok::Arrow
                    }
                    b'-' => Tok::Minus,
                    b':' => Tok::Colon,
                    b'<' => match next {
                        b'=' => {
                            i += 1;
                            Tok::Cmp(Cmp::Le)
                        }
                        b'-' if i + 1 < n && b[i + 1] == b'>' => {
                            i += 2;
                            Tok::Arrow
                        }
                        _ => Tok::Cmp(Cmp::Le),
                    },
                    b'>' => {
                        if next == b'=' {
                            i += 1;
                        }
                        Tok::Cmp(Cmp::Ge)
                    }
                    b'=' => match next {
                        b'<' => {
                            i += 1;
                            Tok::Cmp(Cmp::Le)
                        }
                        b'>' => {
                            i += 1;
                            Tok::Cmp(Cmp::Ge)
                        }
                        b'=' => {
                            i += 1;
                            Tok::Cmp(Cmp::Eq)
                        }
                        _ => Tok::Cmp(Cmp::Eq),
                    },
                    other => Tok::Quad(other),
                }
            }
            _ => {
                // BAD: a control character.
                self.pos = i;
                return Err(self.err(ParseErrorKind::InvalidCharacter(c as char)));
            }
        };
        self.pos = i;
        let t = Token { tok, line: self.line, idx: self.count };
        self.count += 1;
        Ok(t)
    }

    fn slice(&self, s: usize, e: usize) -> Result<&'a str, ParseError> {
        // Token boundaries are ASCII bytes (or the end), hence char boundaries; be safe anyway.
        self.text.get(s..e).ok_or_else(|| self.err(ParseErrorKind::InvalidCharacter('\u{fffd}')))
    }
}

/// Powers of ten exactly representable as `f64`.
const POW10: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// Scans an unsigned decimal number starting at `i` (a digit, or `.` followed by a digit):
/// `digits [. digits] [(e|E) [+|-] digits]`; the exponent is taken only if digits follow.
/// Returns the correctly rounded value and the end position.
fn scan_number(b: &[u8], start: usize) -> (f64, usize) {
    let n = b.len();
    let mut i = start;
    let mut mant: u64 = 0;
    let mut ndig = 0u32; // significant digits accumulated in `mant`
    let mut overflow = false;
    let mut frac_digits = 0i32;
    while i < n && b[i].is_ascii_digit() {
        if ndig < 19 {
            mant = mant * 10 + u64::from(b[i] - b'0');
            if mant != 0 {
                ndig += 1;
            }
        } else {
            overflow = true;
        }
        i += 1;
    }
    if i < n && b[i] == b'.' {
        i += 1;
        while i < n && b[i].is_ascii_digit() {
            if ndig < 19 {
                mant = mant * 10 + u64::from(b[i] - b'0');
                if mant != 0 {
                    ndig += 1;
                }
                frac_digits += 1;
            } else {
                overflow = true;
            }
            i += 1;
        }
    }
    let mut has_exp = false;
    if i < n && (b[i] | 0x20) == b'e' {
        let mut j = i + 1;
        if j < n && (b[j] == b'+' || b[j] == b'-') {
            j += 1;
        }
        if j < n && b[j].is_ascii_digit() {
            while j < n && b[j].is_ascii_digit() {
                j += 1;
            }
            i = j;
            has_exp = true;
        }
    }
    // Clinger's fast path: an exact mantissa below 2^53 divided by an exact power of ten is
    // correctly rounded.
    if !has_exp && !overflow && mant < (1u64 << 53) && (frac_digits as usize) < POW10.len() {
        return (mant as f64 / POW10[frac_digits as usize], i);
    }
    // The slice is ASCII digits, '.', 'e', signs: valid UTF-8 and a valid Rust float literal
    // (Rust accepts "5." and ".5").
    let s = std::str::from_utf8(&b[start..i]).unwrap_or("0");
    (s.parse::<f64>().unwrap_or(f64::NAN), i)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(s: &str) -> Vec<Tok<'_>> {
        let mut lx = Lexer::new(s);
        let mut out = Vec::new();
        loop {
            let t = lx.lex().unwrap();
            if t.tok == Tok::Eof {
                return out;
            }
            out.push(t.tok);
        }
    }

    #[test]
    fn numbers() {
        for s in [
            "0",
            "1",
            "5.",
            ".5",
            "3.25",
            "1e30",
            "1e+30",
            "1E-7",
            "123456789012345678901234567890",
            "0.1",
            "2.2250738585072014e-308",
            "5e-324",
            "1.7976931348623157e308",
            "9007199254740993",
            "0.000000000000000000000000001",
            "1e400",
        ] {
            let (v, end) = scan_number(s.as_bytes(), 0);
            assert_eq!(end, s.len(), "{s}");
            assert_eq!(v.to_bits(), s.parse::<f64>().unwrap().to_bits(), "{s}");
        }
        assert_eq!(scan_number(b"2ex", 0), (2.0, 1));
        assert_eq!(scan_number(b"2e+x", 0), (2.0, 1));
        assert_eq!(scan_number(b"1.2.3", 0), (1.2, 3));
    }

    #[test]
    fn tokens() {
        use Tok::*;
        assert_eq!(
            toks("obj: 2x + 3 y \\ comment\n- .5 z <= =< >= => = < > == -> <-> [ ] * ^"),
            vec![
                Name("obj"),
                Colon,
                Num(2.0, "2"),
                Name("x"),
                Plus,
                Num(3.0, "3"),
                Name("y"),
                Minus,
                Num(0.5, ".5"),
                Name("z"),
                Cmp(super::Cmp::Le),
                Cmp(super::Cmp::Le),
                Cmp(super::Cmp::Ge),
                Cmp(super::Cmp::Ge),
                Cmp(super::Cmp::Eq),
                Cmp(super::Cmp::Le),
                Cmp(super::Cmp::Ge),
                Cmp(super::Cmp::Eq),
                Arrow,
                Arrow,
                Quad(b'['),
                Quad(b']'),
                Quad(b'*'),
                Quad(b'^'),
            ]
        );
        assert_eq!(toks("x<-5"), vec![Name("x"), Cmp(super::Cmp::Le), Minus, Num(5.0, "5")]);
        assert_eq!(toks(".x a.b é"), vec![Name(".x"), Name("a.b"), Name("é")]);
        let mut lx = Lexer::new("a\n\\ netspec: ranged row \nb\n\x01");
        assert_eq!(lx.lex().unwrap().line, 1);
        let t = lx.lex().unwrap();
        assert_eq!((t.tok, t.line, t.idx), (Name("b"), 3, 1));
        assert_eq!(lx.directives[0].text, "ranged row");
        assert_eq!(lx.directives[0].idx, 1);
        let e = lx.lex().unwrap_err();
        assert_eq!(e.line, 4);
    }
}
