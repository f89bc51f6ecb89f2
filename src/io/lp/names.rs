//! Keywords, and the names the writer may use.

use crate::io::NameMap;
use crate::milp::Model;
use std::borrow::Cow;
use std::collections::{HashMap, HashSet};

/// A word that opens a section (or the first word of a two-word one).
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Keyword {
    Minimize,
    Maximize,
    /// `st`, `s.t.`, `st.`
    SubjectTo,
    /// `subject` (needs `to`)
    Subject,
    /// `such` (needs `that`)
    Such,
    Bounds,
    Generals,
    Binaries,
    /// `semi`, `semis` (and `semi-continuous`, which the lexer splits at the `-`)
    Semi,
    Sos,
    End,
    /// `lazy` (needs `constraints`)
    Lazy,
    /// `user` (needs `cuts`)
    User,
}

/// The keyword a word is, if any (case-insensitive). Fast rejection by length and first byte.
pub(super) fn keyword(word: &str) -> Option<Keyword> {
    let b = word.as_bytes();
    if b.len() < 2 || b.len() > 8 {
        return None;
    }
    if !matches!(b[0] | 0x20, b'm' | b's' | b'b' | b'g' | b'i' | b'e' | b'l' | b'u') {
        return None;
    }
    let mut low = [0u8; 8];
    for (d, s) in low.iter_mut().zip(b) {
        *d = s.to_ascii_lowercase();
    }
    Some(match &low[..b.len()] {
        b"min" | b"minimize" | b"minimise" | b"minimum" => Keyword::Minimize,
        b"max" | b"maximize" | b"maximise" | b"maximum" => Keyword::Maximize,
        b"st" | b"s.t." | b"st." => Keyword::SubjectTo,
        b"subject" => Keyword::Subject,
        b"such" => Keyword::Such,
        b"bound" | b"bounds" => Keyword::Bounds,
        b"gen" | b"general" | b"generals" | b"int" | b"integer" | b"integers" => Keyword::Generals,
        b"bin" | b"binary" | b"binaries" => Keyword::Binaries,
        b"semi" | b"semis" => Keyword::Semi,
        b"sos" => Keyword::Sos,
        b"end" => Keyword::End,
        b"lazy" => Keyword::Lazy,
        b"user" => Keyword::User,
        _ => return None,
    })
}

/// What a word means where a value may stand.
#[derive(Copy, Clone, Debug, PartialEq)]
pub(super) enum ValueWord {
    Infinity,
    NaN,
}

/// `inf`, `infinity` and `nan` (any case).
pub(super) fn value_word(word: &str) -> Option<ValueWord> {
    let b = word.as_bytes();
    match b.len() {
        3 if b.eq_ignore_ascii_case(b"inf") => Some(ValueWord::Infinity),
        3 if b.eq_ignore_ascii_case(b"nan") => Some(ValueWord::NaN),
        8 if b.eq_ignore_ascii_case(b"infinity") => Some(ValueWord::Infinity),
        _ => None,
    }
}

/// Words the writer never uses as a name (case-insensitive), beyond [`keyword`] ones.
const RESERVED: [&str; 4] = ["free", "inf", "infinity", "nan"];

/// Characters allowed in a written name (besides ASCII letters and digits).
fn allowed_char(c: u8) -> bool {
    c.is_ascii_alphanumeric() || b"!\"#$%&(),.;?@_`'{}~".contains(&c)
}

/// Whether `name` may be written as it is (limit `max_len` bytes).
pub(super) fn is_writable(name: &str, max_len: usize) -> bool {
    let b = name.as_bytes();
    if b.is_empty() || b.len() > max_len || !b.iter().all(|&c| allowed_char(c)) {
        return false;
    }
    !needs_prefix(b)
}

/// Whether an otherwise well-formed name must get a `_` prefix.
fn needs_prefix(b: &[u8]) -> bool {
    let c0 = b[0];
    if c0.is_ascii_digit() || b".(),;".contains(&c0) {
        return true;
    }
    // Looks like an exponent: `e`, `e12`, `ee…` (CPLEX rule).
    if (c0 | 0x20) == b'e' && (b.len() == 1 || b[1].is_ascii_digit() || (b[1] | 0x20) == b'e') {
        return true;
    }
    // HiGHS reads `inf…`/`nan…` as a number followed by a name.
    if b.len() >= 3 && (b[..3].eq_ignore_ascii_case(b"inf") || b[..3].eq_ignore_ascii_case(b"nan")) {
        return true;
    }
    let s = std::str::from_utf8(b).unwrap_or("");
    keyword(s).is_some() || RESERVED.iter().any(|r| r.eq_ignore_ascii_case(s))
}

/// A writable form of `name` (not yet made unique): bad characters become `_`, a `_` prefix
/// where needed, shortened to `max_len` bytes.
pub(super) fn sanitize(name: &str, max_len: usize) -> String {
    let mut out = String::with_capacity(name.len().min(max_len) + 1);
    for ch in name.chars() {
        if ch.is_ascii() && allowed_char(ch as u8) {
            out.push(ch);
        } else {
            out.push('_');
        }
    }
    if out.is_empty() || needs_prefix(out.as_bytes()) {
        out.insert(0, '_');
    }
    out.truncate(max_len.max(1)); // all ASCII: any byte index is a char boundary
    out
}

/// Hands out unique names within one namespace.
pub(super) struct Namer<'a> {
    taken: HashSet<Cow<'a, str>>,
    /// Next suffix to try per base name.
    next: HashMap<String, u64>,
    max_len: usize,
}

impl<'a> Namer<'a> {
    pub(super) fn new(capacity: usize, max_len: usize) -> Self {
        Namer { taken: HashSet::with_capacity(capacity), next: HashMap::new(), max_len }
    }

    /// Claims `name` as it is; `false` if it is already taken.
    pub(super) fn claim(&mut self, name: &'a str) -> bool {
        self.taken.insert(Cow::Borrowed(name))
    }

    /// A unique name based on the writable `base` (adds `_1`, `_2`, … if needed) and claims it.
    pub(super) fn fresh(&mut self, base: String) -> String {
        if !self.taken.contains(base.as_str()) {
            self.taken.insert(Cow::Owned(base.clone()));
            return base;
        }
        let mut k = self.next.get(&base).copied().unwrap_or(1);
        loop {
            let suffix = format!("_{k}");
            let keep = self.max_len.saturating_sub(suffix.len()).min(base.len());
            let cand = format!("{}{}", &base[..keep], suffix);
            k += 1;
            if !self.taken.contains(cand.as_str()) {
                self.next.insert(base, k);
                self.taken.insert(Cow::Owned(cand.clone()));
                return cand;
            }
        }
    }
}

/// The names to write for a model.
pub(super) struct Names<'a> {
    pub vars: Vec<Cow<'a, str>>,
    pub rows: Vec<Cow<'a, str>>,
    pub objective: Cow<'a, str>,
    /// For each ranged row, the name of its `<=` half (indexed by row; `None` otherwise).
    pub range_upper: Vec<Option<String>>,
    pub map: NameMap,
}

/// Assigns writable, unique names to everything in `model`.
pub(super) fn assign(model: &Model, max_len: usize, is_ranged: impl Fn(usize) -> bool) -> Names<'_> {
    let max_len = max_len.clamp(8, 255);
    let mut map = NameMap::default();

    // Variables.
    let vars = model.vars();
    let mut namer = Namer::new(vars.len(), max_len);
    let mut out: Vec<Option<Cow<str>>> = Vec::with_capacity(vars.len());
    for v in vars {
        if is_writable(&v.name, max_len) && namer.claim(&v.name) {
            out.push(Some(Cow::Borrowed(v.name.as_str())));
        } else {
            out.push(None);
        }
    }
    let var_names: Vec<Cow<str>> = out
        .into_iter()
        .zip(vars)
        .map(|(n, v)| match n {
            Some(n) => n,
            None => {
                let fresh = namer.fresh(sanitize(&v.name, max_len));
                map.vars.entry(v.name.clone()).or_insert_with(|| fresh.clone());
                Cow::Owned(fresh)
            }
        })
        .collect();

    // Objective and rows share one namespace (CoinLpIO wants them distinct).
    let mut namer = Namer::new(model.num_rows() + 1, max_len);
    let objective: Cow<str> = if is_writable(&model.objective_name, max_len) {
        namer.claim(&model.objective_name);
        Cow::Borrowed(model.objective_name.as_str())
    } else {
        let base =
            if model.objective_name.is_empty() { "obj".to_string() } else { sanitize(&model.objective_name, max_len) };
        let fresh = namer.fresh(base);
        map.rows.insert(model.objective_name.clone(), fresh.clone());
        Cow::Owned(fresh)
    };
    let mut out: Vec<Option<Cow<str>>> = Vec::with_capacity(model.num_rows());
    for r in model.rows() {
        if is_writable(r.name, max_len) && namer.claim(r.name) {
            out.push(Some(Cow::Borrowed(r.name)));
        } else {
            out.push(None);
        }
    }
    let mut row_names = Vec::with_capacity(model.num_rows());
    for (n, r) in out.into_iter().zip(model.rows()) {
        row_names.push(match n {
            Some(n) => n,
            None => {
                let fresh = namer.fresh(sanitize(r.name, max_len));
                // A row owns the entry for its name, even if the objective has the same name.
                map.rows.insert(r.name.to_string(), fresh.clone());
                Cow::Owned(fresh)
            }
        });
    }
    let mut range_upper = vec![None; model.num_rows()];
    for (i, slot) in range_upper.iter_mut().enumerate() {
        if is_ranged(i) {
            let base = &row_names[i];
            let keep = max_len.saturating_sub(4).min(base.len());
            let cand = format!("{}_rhs", &base[..keep]);
            *slot = Some(namer.fresh(cand));
        }
    }
    Names { vars: var_names, rows: row_names, objective, range_upper, map }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writable_names() {
        for ok in ["x", "x1", "E_e0", "abc.def", "a!\"#$%&(),.;?@_`'{}~", "_1", "stx", "free1", "ex", "Ex1"] {
            assert!(is_writable(ok, 255), "{ok}");
        }
        for bad in [
            "", "1x", ".x", "(x", ",x", ";x", "e", "E", "e1", "e1x", "ee", "EEl", "inf", "INF1", "nanx", "infinity",
            "st", "S.T.", "end", "Free", "bin", "subject", "a b", "a/b", "a|b", "a:b", "a-b", "a+b", "a[b", "a^b",
            "a*b", "a<b", "a\\b", "é",
        ] {
            assert!(!is_writable(bad, 255), "{bad}");
            let s = sanitize(bad, 255);
            assert!(is_writable(&s, 255), "{bad} -> {s}");
        }
        assert!(!is_writable(&"x".repeat(201), 200));
        assert_eq!(sanitize(&"x".repeat(300), 200).len(), 200);
        assert_eq!(sanitize("a b", 255), "a_b");
        assert_eq!(sanitize("st", 255), "_st");
        assert_eq!(sanitize("2x", 255), "_2x");
        assert_eq!(sanitize("é", 255), "_");
    }

    #[test]
    fn namer_suffixes() {
        let mut n = Namer::new(4, 10);
        assert!(n.claim("a_1"));
        assert_eq!(n.fresh("a".into()), "a");
        assert_eq!(n.fresh("a".into()), "a_2");
        assert_eq!(n.fresh("a".into()), "a_3");
        assert_eq!(n.fresh("abcdefghij".into()), "abcdefghij");
        assert_eq!(n.fresh("abcdefghij".into()), "abcdefgh_1");
    }
}
