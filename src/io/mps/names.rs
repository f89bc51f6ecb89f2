//! Name handling shared by the MPS reader and writer: a fast string hasher for the name → index
//! maps, and the sanitiser that makes names writable.

use std::borrow::Cow;
use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

/// The Fx hash (as used in rustc): a multiply-rotate hash, much faster than SipHash on the
/// short names found in MPS files. Not DoS-resistant, which does not matter for a file reader.
#[derive(Default, Clone, Copy)]
pub(crate) struct FxHasher {
    hash: u64,
}

const SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl FxHasher {
    #[inline]
    fn add(&mut self, word: u64) {
        self.hash = (self.hash.rotate_left(5) ^ word).wrapping_mul(SEED);
    }
}

impl Hasher for FxHasher {
    #[inline]
    fn write(&mut self, mut bytes: &[u8]) {
        while bytes.len() >= 8 {
            let (head, rest) = bytes.split_at(8);
            let mut w = [0u8; 8];
            w.copy_from_slice(head);
            self.add(u64::from_le_bytes(w));
            bytes = rest;
        }
        if bytes.len() >= 4 {
            let (head, rest) = bytes.split_at(4);
            let mut w = [0u8; 4];
            w.copy_from_slice(head);
            self.add(u32::from_le_bytes(w) as u64);
            bytes = rest;
        }
        for &b in bytes {
            self.add(b as u64);
        }
    }

    #[inline]
    fn write_u8(&mut self, i: u8) {
        self.add(i as u64);
    }

    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.add(i as u64);
    }

    #[inline]
    fn finish(&self) -> u64 {
        // The multiply leaves the low bits (which pick the bucket) weak: fold the high ones in.
        self.hash ^ (self.hash >> 29)
    }
}

/// A `HashMap` with the Fx hasher.
pub(crate) type FxHashMap<K, V> = HashMap<K, V, BuildHasherDefault<FxHasher>>;
/// A `HashSet` with the Fx hasher.
pub(crate) type FxHashSet<K> = HashSet<K, BuildHasherDefault<FxHasher>>;

/// Whether `name` can be written to a free MPS file unchanged: non-empty, no whitespace or
/// control characters, not starting with a comment character (`*` or `$`), and not the
/// `'MARKER'` keyword (which would turn a COLUMNS line into an integrality marker).
pub(crate) fn is_clean(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with(['*', '$'])
        && name != "'MARKER'"
        && !name.chars().any(|c| c.is_whitespace() || c.is_control())
}

/// Words that HiGHS's free-format reader takes for a section header even when indented, so a
/// column with one of these names would end the COLUMNS section there.
const KEYWORDS: &[&str] = &[
    "NAME",
    "OBJSENSE",
    "OBJNAME",
    "MAX",
    "MIN",
    "ROWS",
    "COLUMNS",
    "RHS",
    "BOUNDS",
    "RANGES",
    "QSECTION",
    "QMATRIX",
    "QUADOBJ",
    "QCMATRIX",
    "CSECTION",
    "DELAYEDROWS",
    "MODELCUTS",
    "INDICATORS",
    "SETS",
    "SOS",
    "GENCONS",
    "PWLOBJ",
    "PWLNAM",
    "PWLCON",
    "ENDATA",
];

/// Whether a name is one of [`KEYWORDS`].
pub(crate) fn is_keyword(name: &str) -> bool {
    KEYWORDS.contains(&name)
}

/// The cleaned form of a name (before uniqueness is enforced): whitespace and control
/// characters become `_`, a leading `*` or `$` becomes `_`, the empty name becomes `_`.
pub(crate) fn clean(name: &str) -> Cow<'_, str> {
    if is_clean(name) {
        return Cow::Borrowed(name);
    }
    if name == "'MARKER'" {
        return Cow::Borrowed("_MARKER_");
    }
    let mut out = String::with_capacity(name.len().max(1));
    for (i, c) in name.chars().enumerate() {
        if c.is_whitespace() || c.is_control() || (i == 0 && (c == '*' || c == '$')) {
            out.push('_');
        } else {
            out.push(c);
        }
    }
    if out.is_empty() {
        out.push('_');
    }
    Cow::Owned(out)
}

/// Makes a list of names writable and unique. Clean names that are unique keep their spelling;
/// the others are cleaned and, if needed, given a suffix `_2`, `_3`, … that makes them unique.
/// `reserved` names (e.g. the objective row) are taken before any of `names`. With
/// `avoid_keywords` (for column names), names equal to an MPS section keyword get a `_` suffix,
/// because HiGHS would read them as section headers.
///
/// Returns the written names (borrowed when unchanged) and the list of `(index, new name)` of
/// the names that changed.
pub(crate) fn make_unique<'a>(
    reserved: &[&'a str],
    names: impl ExactSizeIterator<Item = &'a str> + Clone,
    avoid_keywords: bool,
) -> (Vec<Cow<'a, str>>, Vec<(usize, String)>) {
    let n = names.len();
    let mut used: FxHashSet<Cow<'a, str>> = FxHashSet::default();
    used.reserve(n + reserved.len());
    for r in reserved {
        used.insert(Cow::Borrowed(*r));
    }
    // Pass 1: clean names claim their own spelling, first come first served.
    let mut out: Vec<Option<Cow<'a, str>>> = Vec::with_capacity(n);
    let mut pending = Vec::new();
    for (i, name) in names.clone().enumerate() {
        if is_clean(name) && !(avoid_keywords && is_keyword(name)) && used.insert(Cow::Borrowed(name)) {
            out.push(Some(Cow::Borrowed(name)));
        } else {
            out.push(None);
            pending.push(i);
        }
    }
    // Pass 2: the others get a cleaned, suffixed spelling that no other name uses.
    let mut changed = Vec::with_capacity(pending.len());
    if !pending.is_empty() {
        let originals: Vec<&'a str> = names.collect();
        for i in pending {
            let mut base = clean(originals[i]);
            if avoid_keywords && is_keyword(&base) {
                base = Cow::Owned(format!("{base}_"));
            }
            let mut candidate = base.to_string();
            let mut k = 2usize;
            while used.contains(candidate.as_str()) {
                candidate = format!("{base}_{k}");
                k += 1;
            }
            used.insert(Cow::Owned(candidate.clone()));
            changed.push((i, candidate.clone()));
            out[i] = Some(Cow::Owned(candidate));
        }
    }
    let out = out.into_iter().map(|c| c.unwrap_or(Cow::Borrowed("_"))).collect();
    (out, changed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clean_names() {
        assert_eq!(clean("x"), "x");
        assert_eq!(clean("a b"), "a_b");
        assert_eq!(clean(""), "_");
        assert_eq!(clean("$x"), "_x");
        assert_eq!(clean("*x*"), "_x*");
        assert_eq!(clean("a\tb\n"), "a_b_");
        assert_eq!(clean("'MARKER'"), "_MARKER_");
    }

    #[test]
    fn unique_names() {
        let names = ["a b", "a_b", "x", "x", "", "_"];
        let (out, changed) = make_unique(&["obj"], names.iter().copied(), false);
        let out: Vec<&str> = out.iter().map(|c| c.as_ref()).collect();
        assert_eq!(out, ["a_b_2", "a_b", "x", "x_2", "__2", "_"]);
        assert_eq!(changed.len(), 3);
        let (out, _) = make_unique(&["obj"], ["obj", "o"].iter().copied(), false);
        assert_eq!(out[0], "obj_2");
        let (out, _) = make_unique(&[], ["RHS", "RHS_", "x"].iter().copied(), true);
        assert_eq!(out, ["RHS__2", "RHS_", "x"]);
    }
}
