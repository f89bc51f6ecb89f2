//! Fuzz targets (proptest, a few hundred cases each, seconds in CI): the MPS and LP readers
//! (plain and gzip) with every backend's numeric screen, the solution-file reader, the spec, city
//! spec and manifest parsers, formulation variants, solve settings and output-folder names, on
//! mutations of real files — deleted and duplicated spans, swapped lines, tokens of the format
//! inserted, numbers replaced by extreme ones (`nan`, `inf`, `1e400`, `1e20`, `-0`, 2^64, the
//! smallest subnormal), control and direction-override characters, path-like names, giant meshes
//! and extreme option values. Every input must give a value or a typed error, quickly; a panic
//! fails the test. Raise the case counts with `PROPTEST_CASES` for a longer run (the campaign in
//! docs/robustness.md).

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
    "name = \"../../escaped\"",
    "name = \"/tmp/abs\"",
    "name = \".\"",
    "name = \"a\\u0000b\"",
    "description = \"\\u0007\"",
    "grid = { width = 100000, height = 100000 }",
    "clipped = { outer = [[0, 0], [1e9, 0], [1e9, 1e9]], spacing = 1e-9 }",
    "clipped = { outer = [[0, 0], [4, 0], [4, 4]], spacing = 0.001 }",
    "obstacle_polygons = [[[0, 0], [1, nan], [1, 1]]]",
    "points = [[inf, 0]]",
    "[solver]",
    "threads = 100000",
    "time_limit = -1",
    "gap = nan",
    "seed = 18446744073709551615",
    "[formulation]",
    "out_arcs = false",
    "split_objective = true",
];
const NUMBERS: &[&str] = &[
    "nan",
    "inf",
    "-inf",
    "1e400",
    "-1e400",
    "-0",
    "18446744073709551616",
    "0",
    "1e-400",
    "-1",
    "2",
    "1e20",
    "-1e20",
    "1e15",
    "1e308",
    "4.9e-324",
    "100000",
    "4294967296",
];

/// Characters that break pictures, terminals and file formats when they reach them.
const CHARS: &[&str] =
    &["\u{0}", "\u{7}", "\u{1b}[2J", "\u{202e}", "\r", "\t", "\u{feff}", "\u{fffd}", "..", "/", "\\"];

/// An edit of a text.
#[derive(Clone, Debug)]
enum Edit {
    Delete(usize, usize),
    Duplicate(usize, usize),
    Insert(usize, usize),
    SwapLines(usize, usize),
    Number(usize, usize),
    Char(usize, usize),
}

fn edits() -> impl Strategy<Value = Vec<Edit>> {
    let edit = prop_oneof![
        (any::<usize>(), 0usize..40).prop_map(|(a, n)| Edit::Delete(a, n)),
        (any::<usize>(), 0usize..80).prop_map(|(a, n)| Edit::Duplicate(a, n)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Edit::Insert(a, t)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::SwapLines(a, b)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Edit::Number(a, t)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, t)| Edit::Char(a, t)),
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
            Edit::Char(a, k) => {
                let s = at(&t, a);
                t.insert_str(s, CHARS[k % CHARS.len()]);
            }
        }
    }
    t
}

/// The numeric screen against every compiled backend's limits (what runs before any backend).
fn screen_for_every_backend(model: &netspec::milp::Model) {
    for kind in netspec::solvers::SolverKind::compiled() {
        let limits = kind.instance().unwrap().capabilities().numeric;
        let r = netspec::milp::numeric_screen(model, &limits, kind.name());
        let _ = r.warning(kind.name(), &limits);
    }
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
            screen_for_every_backend(&o.model);
            let _ = netspec::io::lp::write(&o.model, &mut Vec::new(), &Default::default());
        }
    }

    #[test]
    fn lp_reader_never_panics(seed in 0usize..3, e in edits()) {
        let text = mutate(&lp_seeds()[seed], &e, LP_TOKENS);
        if let Ok(o) = netspec::io::lp::read_str(&text) {
            let _ = o.model.validate();
            let _ = netspec::milp::screen(&o.model);
            screen_for_every_backend(&o.model);
            let _ = netspec::io::mps::write(&o.model, &mut Vec::new(), &Default::default());
        }
    }

    #[test]
    fn spec_parser_never_panics(seed in 0usize..5, e in edits()) {
        let text = mutate(&spec_seeds()[seed], &e, SPEC_TOKENS);
        if let Ok(spec) = netspec::spec::Spec::from_toml(&text) {
            // Text is checked where it is read.
            prop_assert!(!spec.name.chars().any(char::is_control) && !spec.description.chars().any(char::is_control));
            // Resolving builds the mesh: the size cap refuses giant ones before any work (a cap a
            // test can afford).
            // A spec that resolves (every number checked) has a JSON form that parses back (the
            // echo in result.json); non-finite numbers, which JSON cannot hold, never resolve.
            if let Ok(p) = spec.resolve_within(&root().join("models"), 2_000) {
                prop_assert!(p.mesh.num_faces() <= 2_000);
                let json = serde_json::to_string(&spec).unwrap();
                prop_assert!(netspec::spec::Spec::from_json(&json).is_ok(), "{json}");
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

fn city_seeds() -> Vec<String> {
    texts(&["fixtures/city/two-regions.toml", "models/city/fig7a.toml", "models/city/fig8.toml"])
}

const CITY_TOKENS: &[&str] = &[
    "[mesh]",
    "spacing = 0.001",
    "spacing = 1e-9",
    "[levels.3]",
    "subdivide = true",
    "[[region]]",
    "[[road]]",
    "points = [[0, 0], [nan, 1]]",
    "name = \"../x\"",
    "threads = 0",
    "metres_per_unit = -1",
    "=",
    "[",
    "]",
];

proptest! {
    #![proptest_config(config(256))]

    /// City specs: parsed and checked, their size estimate finite or refused, never a panic.
    #[test]
    fn city_spec_parser_never_panics(seed in 0usize..3, e in edits()) {
        let text = mutate(&city_seeds()[seed], &e, CITY_TOKENS);
        if let Ok(spec) = netspec::urban::CitySpec::from_toml(&text) {
            let cells = spec.estimated_cells();
            prop_assert!(!cells.is_nan() || spec.domain.outer.is_empty(), "{cells}");
            let settings = netspec::pipeline::settings::Settings::default();
            let _ = netspec::urban::CityRunOptions::resolve(&spec, Path::new("c.toml"), &settings, None, None, 2_000);
        }
    }

    /// Manifests: loaded from a file and their rows selected by patterns, never a panic.
    #[test]
    fn manifest_loader_never_panics(e in edits(), pattern in "[*?a-z0-9-]{0,6}") {
        let text = mutate(&texts(&["models/table1.toml"])[0], &e, &["[[row]]", "name", "spec", "missing", "paper", "=", "\""]);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.toml");
        std::fs::write(&path, text).unwrap();
        if let Ok(m) = netspec::compare::Manifest::load(&path) {
            if let Ok(sel) = m.select(std::slice::from_ref(&pattern)) {
                prop_assert!(sel.row.iter().all(|r| netspec::compare::glob_match(&pattern, &r.name)));
            }
        }
    }

    /// Formulation variants: parsed or refused with a message; a parsed one prints back to
    /// itself.
    #[test]
    fn variants_parse_and_print_back(words in proptest::collection::vec(prop_oneof![
        Just("strong"), Just("paper"), Just("tight"), Just("out_arcs"), Just("split_objective"),
        Just("connectivity"), Just("flow"), Just("on"), Just("off"), Just("="), Just(":"), Just("\u{0}"), Just(""),
    ], 0..8)) {
        let text: String = words.concat();
        if let Ok(v) = text.parse::<netspec::spec::Variant>() {
            let again: netspec::spec::Variant = v.to_string().parse().unwrap();
            prop_assert_eq!(again, v);
        }
    }

    /// Solve settings of any values: resolved or refused naming the flag, never a panic.
    #[test]
    fn settings_resolve_or_name_the_flag(
        time_limit in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(-1.0), any::<f64>()],
        gap in prop_oneof![Just(f64::NAN), Just(-0.0), any::<f64>()],
        threads in any::<u32>(),
        seed in any::<u64>(),
    ) {
        use netspec::pipeline::settings::{resolve, Origin, Settings};
        let s = Settings { time_limit: Some(time_limit), gap: Some(gap), threads: Some(threads), seed: Some(seed), ..Settings::default() };
        match resolve(&[(Origin::Flags, s)]) {
            Ok((_, o)) => prop_assert!(o.threads.is_some_and(|t| (1..=netspec::solvers::MAX_THREADS).contains(&t))),
            Err(e) => prop_assert!(e.place.starts_with("--"), "{e}"),
        }
    }

    /// Output folder names: whatever the name, one safe path component.
    #[test]
    fn output_names_are_one_safe_component(name in "\\PC{0,12}") {
        let c = netspec::run::safe_component(&name);
        prop_assert!(!c.is_empty() && c != "." && c != ".." && !c.contains(['/', '\\', '\0']), "{c:?}");
        prop_assert!(!c.starts_with('.'));
    }
}
