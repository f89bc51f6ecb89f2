//! Fuzz targets (proptest, a few hundred cases each, seconds in CI): the MPS and LP readers
//! (plain and gzip), the solution-file reader and the spec parser, on mutations of real files —
//! deleted and duplicated spans, swapped lines, tokens of the format inserted, numbers replaced by
//! extreme ones (`nan`, `inf`, `1e400`, `-0`, 2^64). Every input must give a value or a typed
//! error; a panic fails the test. Raise the case counts with `PROPTEST_CASES` for a longer run.

use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn texts(paths: &[&str]) -> Vec<String> {
    paths.iter().map(|p| std::fs::read_to_string(root().join(p)).unwrap_or_else(|e| panic!("{p}: {e}"))).collect()
}

fn mps_seeds() -> Vec<String> {
    texts(&["fixtures/mps/egout.mps", "fixtures/mps/features.mps", "fixtures/mps/fixed_spaces.mps"])
}

fn lp_seeds() -> Vec<String> {
    texts(&[
        "fixtures/highs-check/1448.lp",
        "fixtures/highs-check/fixed-binary.lp",
        "fixtures/highs-check/issue-2388.lp",
    ])
}

fn spec_seeds() -> Vec<String> {
    texts(&[
        "models/fig2b.toml",
        "models/fig9b1.toml",
        "models/fig11a.toml",
        "fixtures/specs/tiny_network.toml",
        "fixtures/specs/tiny_floorplan.toml",
    ])
}

const MPS_TOKENS: &[&str] = &[
    "NAME",
    "ROWS",
    "COLUMNS",
    "RHS",
    "RANGES",
    "BOUNDS",
    "ENDATA",
    "OBJSENSE",
    "MAX",
    " N  obj",
    " L  c",
    " E  e",
    " G  g",
    "    MARKER                 'MARKER'                 'INTORG'",
    "'INTEND'",
    " UP BND x",
    " LO BND x",
    " FX BND",
    " FR BND",
    " MI",
    " PL",
    " BV BND",
    " LI",
    " UI",
    " SC",
    "* netspec: range c 1 0",
    "* netspec: binary x",
    "$",
    "*",
];
const LP_TOKENS: &[&str] = &[
    "Minimize",
    "Maximize",
    "Subject To",
    "st",
    "Bounds",
    "General",
    "Binary",
    "Semi",
    "SOS",
    "End",
    "obj:",
    "c1:",
    ">=",
    "<=",
    "=",
    "+",
    "-",
    "x",
    "y",
    "free",
    "-inf",
    "+infinity",
    "[",
    "]",
    "^",
    "\\",
    ":",
    "e",
    "E+",
];
const SPEC_TOKENS: &[&str] = &[
    "[mesh]",
    "[sinks]",
    "[rooms]",
    "[user]",
    "[[row]]",
    "=",
    "[",
    "]",
    "{",
    "}",
    ",",
    "\"",
    "forbid",
    "width",
    "height",
    "grid",
    "spacing",
    "range",
    "templates",
    "shape",
    "\"rect 0x0\"",
    "\"L 9x1\"",
    "exact",
    "max_placements",
    "level",
    "\"circular\"",
];
const NUMBERS: &[&str] =
    &["nan", "inf", "-inf", "1e400", "-1e400", "-0", "18446744073709551616", "0", "1e-400", "-1", "2"];

/// An edit of a text.
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Duplicate(usize, usize),
    Insert(usize, usize),
    SwapLines(usize, usize),
    Number(usize, usize),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        (any::<usize>(), 0usize..40).prop_map(|(a, n)| Edit::Delete(a, n)),
        (any::<usize>(), 0usize..80).prop_map(|(a, n)| Edit::Duplicate(a, n)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Edit::Insert(a, t)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::SwapLines(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Edit::Number(a, t)),
    ];
    proptest::collection::vec(edit, 1..6)
}

/// The char boundary at or before `i % (len + 1)`.
fn at(text: &str, i: usize) -> usize {
    let mut i = i % (text.len() + 1);
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn mutate(seed: &str, edits: &[Edit], tokens: &[&str]) -> String {
    let mut t = seed.to_string();
    for e in edits {
        match *e {
            Edit::Delete(a, n) => {
                let s = at(&t, a);
                let e = at(&t, s + n);
                if e >= s {
                    t.replace_range(s..e, "");
                }
            }
            Edit::Duplicate(a, n) => {
                let s = at(&t, a);
                let e = at(&t, s + n).max(s);
                let piece = t[s..e].to_string();
                t.insert_str(e, &piece);
            }
            Edit::Insert(a, k) => {
                let s = at(&t, a);
                let tok = tokens[k % tokens.len()];
                t.insert_str(s, &format!(" {tok} "));
            }
            Edit::SwapLines(a, b) => {
                let mut lines: Vec<&str> = t.lines().collect();
                if !lines.is_empty() {
                    let (i, j) = (a % lines.len(), b % lines.len());
                    lines.swap(i, j);
                }
                t = lines.join("\n");
            }
            Edit::Number(a, k) => {
                // Replace the number (run of digits) at or after the position.
                let s = at(&t, a);
                if let Some(off) = t[s..].find(|c: char| c.is_ascii_digit()) {
                    let start = s + off;
                    let len = t[start..].find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(t.len() - start);
                    t.replace_range(start..start + len, NUMBERS[k % NUMBERS.len()]);
                }
            }
        }
    }
    t
}

/// `cases` per target, or `PROPTEST_CASES` when set (for a longer run).
fn config(cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(cases);
    ProptestConfig { cases, failure_persistence: None, ..ProptestConfig::default() }
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn mps_reader_never_panics(seed in 0usize..3, e in edits()) {
        let text = mutate(&mps_seeds()[seed], &e, MPS_TOKENS);
        if let Ok(o) = netspec::io::mps::read_str(&text) {
            let _ = o.model.validate();
            let _ = netspec::milp::screen(&o.model);
            let _ = netspec::io::lp::write(&o.model, &mut Vec::new(), &Default::default());
        }
    }

    #[test]
    fn lp_reader_never_panics(seed in 0usize..3, e in edits()) {
        let text = mutate(&lp_seeds()[seed], &e, LP_TOKENS);
        if let Ok(o) = netspec::io::lp::read_str(&text) {
            let _ = o.model.validate();
            let _ = netspec::milp::screen(&o.model);
            let _ = netspec::io::mps::write(&o.model, &mut Vec::new(), &Default::default());
        }
    }

    #[test]
    fn spec_parser_never_panics(seed in 0usize..5, e in edits()) {
        let text = mutate(&spec_seeds()[seed], &e, SPEC_TOKENS);
        if let Ok(spec) = netspec::spec::Spec::from_toml(&text) {
            // Resolving builds the mesh: only for sizes a test can afford.
            let small = spec.mesh.grid.as_ref().is_some_and(|g| g.width.saturating_mul(g.height) <= 400) && spec.mesh.clipped.is_none();
            // A spec that resolves (every number checked) has a JSON form that parses back (the
            // echo in result.json); non-finite numbers, which JSON cannot hold, never resolve.
            if small && spec.resolve(&root().join("models")).is_ok() {
                let json = serde_json::to_string(&spec).unwrap();
                prop_assert!(serde_json::from_str::<netspec::spec::Spec>(&json).is_ok(), "{json}");
            }
        }
    }

    #[test]
    fn sol_reader_never_panics(e in edits()) {
        let model = netspec::io::mps::read_str(&mps_seeds()[0]).unwrap().model;
        let seed: String = model.vars().iter().enumerate().map(|(j, v)| format!("{} {}\n", v.name, j)).collect();
        let text = mutate(&format!("solution status: optimal\nobjective value: 3\n{seed}"), &e, &["#", "nan", "x", ":"]);
        let _ = netspec::io::sol::parse(&model, &text);
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// Gzip files cut short or with flipped bytes give an error naming the file.
    #[test]
    fn gzip_reader_never_panics(cut in 0usize..4000, flip in any::<(usize, u8)>()) {
        let dir = tempfile::tempdir().unwrap();
        let good = dir.path().join("g.mps.gz");
        let model = netspec::io::mps::read_str(&mps_seeds()[0]).unwrap().model;
        netspec::io::write_model_file(&model, &good).unwrap();
        let mut bytes = std::fs::read(&good).unwrap();
        bytes.truncate(cut.min(bytes.len()));
        if !bytes.is_empty() {
            let i = flip.0 % bytes.len();
            bytes[i] ^= flip.1;
        }
        let bad = dir.path().join("b.mps.gz");
        std::fs::write(&bad, &bytes).unwrap();
        if let Err(e) = netspec::io::read_model_file(&bad) {
            prop_assert!(e.to_string().contains("b.mps.gz"), "{e}");
        }
    }
}
