//! Tests of the LP reader and writer.

use super::*;
use crate::milp::{RowKind, Sense, VarId, VarKind};
use proptest::prelude::*;

const INF: f64 = f64::INFINITY;

fn read(text: &str) -> crate::io::ReadModel {
    match read_str(text) {
        Ok(o) => o,
        Err(e) => panic!("unexpected error: {e}\n--- input ---\n{text}"),
    }
}

fn err(text: &str) -> ParseError {
    match read_str(text) {
        Ok(o) => panic!("expected an error, got a model with {} vars, {} rows", o.model.num_vars(), o.model.num_rows()),
        Err(e) => e,
    }
}

fn write_str(model: &Model, opts: &WriteOptions) -> (String, crate::io::NameMap) {
    let mut buf = Vec::new();
    let map = write(model, &mut buf, opts).expect("write");
    (String::from_utf8(buf).expect("utf-8"), map)
}

fn var<'m>(m: &'m Model, name: &str) -> &'m crate::milp::Variable {
    m.vars().iter().find(|v| v.name == name).unwrap_or_else(|| panic!("no variable {name}"))
}

fn row_by_name<'m>(m: &'m Model, name: &str) -> crate::milp::RowView<'m> {
    m.rows().find(|r| r.name == name).unwrap_or_else(|| panic!("no row {name}"))
}

fn terms(m: &Model, r: &crate::milp::RowView) -> Vec<(String, f64)> {
    r.terms().map(|(v, a)| (m.var(v).name.clone(), a)).collect()
}

fn t(name: &str, a: f64) -> (String, f64) {
    (name.to_string(), a)
}

// ----- the HiGHS corpus -----

#[test]
fn corpus_1448_is_an_empty_model() {
    let o = read(include_str!("../../../fixtures/highs-check/1448.lp"));
    assert_eq!(o.model.num_vars(), 0);
    assert_eq!(o.model.num_rows(), 0);
    assert!(
        o.warnings.iter().any(|w| w.line == 1 && w.message.contains("before the first section")),
        "{:?}",
        o.warnings
    );
}

#[test]
fn corpus_fixed_binary() {
    let o = read(include_str!("../../../fixtures/highs-check/fixed-binary.lp"));
    let m = &o.model;
    assert_eq!(m.num_vars(), 1);
    assert_eq!(m.num_rows(), 0);
    let x = var(m, "x1");
    assert_eq!((x.kind, x.lb, x.ub, x.obj), (VarKind::Binary, 0.0, 0.0, -1.0));
    m.validate().unwrap();
}

#[test]
fn corpus_issue_2388() {
    let o = read(include_str!("../../../fixtures/highs-check/issue-2388.lp"));
    let m = &o.model;
    m.validate().unwrap();
    assert_eq!(m.name, "QP from CasADi");
    assert_eq!(m.num_rows(), 34);
    assert_eq!(m.vars()[0].name, "x9"); // objective order first
    let c41 = row_by_name(m, "c41");
    assert_eq!((c41.lhs, c41.rhs), (0.0, 0.0));
    assert_eq!(c41.vars.len(), 3);
    let c17 = row_by_name(m, "c17");
    assert_eq!(terms(m, &c17), vec![t("x43", -0.1), t("x49", -0.1), t("x53", -1.0)]);
    assert_eq!((c17.lhs, c17.rhs), (-1.0, INF));
    let x2 = var(m, "x2");
    assert_eq!((x2.lb, x2.ub), (0.18074031231926, 0.301233853865433));
    assert_eq!((var(m, "x5").lb, var(m, "x5").ub), (-INF, INF));
    assert_eq!((var(m, "x23").lb, var(m, "x23").ub), (-INF, 0.0));
    assert!(m.is_mip());
}

#[test]
fn corpus_issue_2585() {
    let o = read(include_str!("../../../fixtures/highs-check/issue-2585.lp"));
    let m = &o.model;
    m.validate().unwrap();
    assert_eq!(m.vars().iter().map(|v| v.name.as_str()).collect::<Vec<_>>(), ["a", "b", "c", "d"]);
    assert_eq!(m.vars().iter().map(|v| v.obj).collect::<Vec<_>>(), [-24.0, 5.0, 7.4, 9.0]);
    assert_eq!(m.objective_name, "obj");
    assert_eq!(m.num_rows(), 6);
    assert_eq!(m.rows().map(|r| r.name.to_string()).collect::<Vec<_>>(), ["R1", "R2", "R3", "R4", "R5", "R6"]);
    let r2 = m.row(crate::milp::RowId(1));
    #[allow(clippy::approx_constant)] // the file's coefficient, not pi
    let a = -3.14;
    assert_eq!(terms(m, &r2), vec![t("a", a), t("b", -78.02)]);
    assert_eq!(r2.rhs, -50.5404);
    assert_eq!(var(m, "c").kind, VarKind::Integer);
    assert_eq!(var(m, "a").kind, VarKind::Continuous);
    assert_eq!((var(m, "d").lb, var(m, "d").ub), (-100.0, 100.0));
}

#[test]
fn corpus_no_newline_eof() {
    let o = read(include_str!("../../../fixtures/highs-check/no-newline-eof.lp"));
    let m = &o.model;
    assert_eq!(m.num_vars(), 2);
    let c1 = row_by_name(m, "c1");
    assert_eq!((c1.lhs, c1.rhs), (-INF, 1.0));
    assert!(o.warnings.is_empty(), "{:?}", o.warnings);
}

#[test]
fn corpus_garbage_is_an_error() {
    let e = err(include_str!("../../../fixtures/highs-check/garbage.lp"));
    assert_eq!(e.line, 2, "{e}");
    assert!(matches!(e.kind, ParseErrorKind::ExpectedSection(_)), "{e}");
    let msg = e.to_string();
    assert!(msg.starts_with("line 2: expected a section keyword"), "{msg}");
    assert!(msg.contains('^'), "{msg}");
}

#[test]
fn corpus_through_read_model_file() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/highs-check");
    for (file, vars, rows) in [
        ("1448.lp", 0, 0),
        ("fixed-binary.lp", 1, 0),
        ("issue-2388.lp", 42, 34),
        ("issue-2585.lp", 4, 6),
        ("no-newline-eof.lp", 2, 1),
    ] {
        let o = crate::io::read_model_file(&dir.join(file)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((o.model.num_vars(), o.model.num_rows()), (vars, rows), "{file}");
    }
    let e = crate::io::read_model_file(&dir.join("garbage.lp")).unwrap_err();
    assert!(matches!(e.kind, crate::io::FileErrorKind::Lp(ParseError { line: 2, .. })), "{e}");
    assert!(e.to_string().contains("garbage.lp: line 2: expected a section keyword"), "{e}");
}

#[test]
fn file_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sample.lp");
    let mut m = sample_model();
    m.sense = Sense::Maximize;
    let map = crate::io::write_model_file(&m, &path).unwrap();
    assert!(map.is_identity());
    let o = crate::io::read_model_file(&path).unwrap();
    assert_eq!(o.model, m);
    assert!(o.warnings.is_empty());
}

// ----- reader syntax -----

#[test]
fn keywords_and_comments() {
    for (obj, sense) in [
        ("Minimize", Sense::Minimize),
        ("MINIMISE", Sense::Minimize),
        ("minimum", Sense::Minimize),
        ("min", Sense::Minimize),
        ("Maximize", Sense::Maximize),
        ("maximise", Sense::Maximize),
        ("MAXIMUM", Sense::Maximize),
        ("max", Sense::Maximize),
    ] {
        for st in ["Subject To", "such that", "st", "S.T.", "st.", "SUBJECT\n  TO"] {
            for gen in ["General", "generals", "GEN", "integer", "Integers", "int"] {
                for bin in ["Binary", "binaries", "BIN"] {
                    let text = format!(
                        "\\ comment\n{obj} \\ another\n obj: x + y\n{st}\n c1: x + y + z >= 1\nBound\n x <= 4\n{gen}\n y\n{bin}\n z\nEND\n"
                    );
                    let m = read(&text).model;
                    assert_eq!(m.sense, sense, "{text}");
                    assert_eq!(m.num_rows(), 1, "{text}");
                    assert_eq!(var(&m, "x").ub, 4.0);
                    assert_eq!(var(&m, "y").kind, VarKind::Integer);
                    assert_eq!((var(&m, "z").kind, var(&m, "z").ub), (VarKind::Binary, 1.0));
                }
            }
        }
    }
}

#[test]
fn keywords_followed_by_colon_are_names() {
    let m = read("min\n obj: x\nst\n end: x >= 1\n st: x <= 5\n bounds: x + free >= 0\nend").model;
    assert_eq!(m.rows().map(|r| r.name.to_string()).collect::<Vec<_>>(), ["end", "st", "bounds"]);
    assert_eq!(m.vars().iter().map(|v| v.name.as_str()).collect::<Vec<_>>(), ["x", "free"]);
}

#[test]
fn names_with_odd_characters() {
    let m = read("min\n obj: a!\"#$%&()/,.;?@_`'{}|~ + .b + é + x.1e5 + 2x3\nst\nend").model;
    let names: Vec<_> = m.vars().iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["a!\"#$%&()/,.;?@_`'{}|~", ".b", "é", "x.1e5", "x3"]);
    assert_eq!(var(&m, "x3").obj, 2.0);
}

#[test]
fn objective_name_and_constant() {
    let m = read("Minimize\n cost: 2 x + 3 y + 7.5\nSubject To\n r: x + y >= 1\nEnd").model;
    assert_eq!(m.objective_name, "cost");
    assert_eq!(m.obj_constant, 7.5);
    let m = read("Minimize\n 7.5 + 2 x - 1 + 3 y\nEnd").model;
    assert_eq!(m.objective_name, "obj");
    assert_eq!(m.obj_constant, 6.5);
    assert_eq!((var(&m, "x").obj, var(&m, "y").obj), (2.0, 3.0));
    let m = read("max\n obj: - 3\nend").model;
    assert_eq!((m.sense, m.obj_constant, m.num_vars()), (Sense::Maximize, -3.0, 0));
    let m = read("min\n obj:\nst\n c: x >= 1\nend").model;
    assert_eq!(m.num_vars(), 1);
}

#[test]
fn repeated_variables_are_summed() {
    let m = read("min\n obj: x + 2 y - x + 0.5 x\nst\n c: 3 x + y - x + 2 z - y <= 4\nend").model;
    assert_eq!(var(&m, "x").obj, 0.5);
    let c = row_by_name(&m, "c");
    assert_eq!(terms(&m, &c), vec![t("x", 2.0), t("y", 0.0), t("z", 2.0)]);
}

#[test]
fn terms_span_lines_and_signs() {
    let text =
        "min\n obj: x\n + y\n -\n 3\n z\nst\n c1: - x\n - - y +\n + 2 z\n >= -4\n c2: -2.5e-1 x +1e+2 y\n <= .5\nend";
    let m = read(text).model;
    assert_eq!(var(&m, "z").obj, -3.0);
    let c1 = row_by_name(&m, "c1");
    assert_eq!(terms(&m, &c1), vec![t("x", -1.0), t("y", 1.0), t("z", 2.0)]);
    assert_eq!(c1.lhs, -4.0);
    let c2 = row_by_name(&m, "c2");
    assert_eq!(terms(&m, &c2), vec![t("x", -0.25), t("y", 100.0)]);
    assert_eq!(c2.rhs, 0.5);
}

#[test]
fn constraint_senses_and_constants() {
    let text = "min\nst\n a: x < 1\n b: x <= 2\n c: x =< 3\n d: x > 4\n e_: x >= 5\n f: x => 6\n g: x = 7\n h: x + 3 >= 5\n i: 2 + x - 1 <= 4\nend";
    let m = read(text).model;
    let sides: Vec<_> = m.rows().map(|r| (r.lhs, r.rhs)).collect();
    assert_eq!(
        sides,
        [
            (-INF, 1.0),
            (-INF, 2.0),
            (-INF, 3.0),
            (4.0, INF),
            (5.0, INF),
            (6.0, INF),
            (7.0, 7.0),
            (2.0, INF),
            (-INF, 3.0)
        ]
    );
}

#[test]
fn ranged_and_reversed_constraints() {
    let text = "min\nst\n r1: -5 <= x + y <= 10\n r2: 10 >= x - y >= -5\n r3: 3 >= x\n r4: -inf <= x + 2 <= 1e30\n r5: 2 = x + y\n r6: 1 <= x + 1 <= 3\nend";
    let m = read(text).model;
    let sides: Vec<_> = m.rows().map(|r| (r.name.to_string(), r.lhs, r.rhs)).collect();
    assert_eq!(
        sides,
        [
            ("r1".into(), -5.0, 10.0),
            ("r2".into(), -5.0, 10.0),
            ("r3".into(), -INF, 3.0),
            ("r4".into(), -INF, INF),
            ("r5".into(), 2.0, 2.0),
            ("r6".into(), 0.0, 2.0),
        ]
    );
    assert_eq!(terms(&m, &row_by_name(&m, "r2")), vec![t("x", 1.0), t("y", -1.0)]);
    let e = err("min\nst\n r: 1 <= x >= 2\nend");
    assert_eq!(e.line, 3);
}

#[test]
fn empty_free_and_infinite_rows() {
    let text = "min\n obj: x\nst\n e1: >= -3\n e2: <= 4\n e3: = 0\n f1: x - y >= -inf\n f2: x <= +inf\n f3: x >= -1e30\n f4: x <= 1e+30\n f5: x >= -Infinity\nend";
    let m = read(text).model;
    let kinds: Vec<_> = m.rows().map(|r| r.kind()).collect();
    assert_eq!(
        kinds,
        [
            RowKind::Ge,
            RowKind::Le,
            RowKind::Eq,
            RowKind::Free,
            RowKind::Free,
            RowKind::Free,
            RowKind::Free,
            RowKind::Free
        ]
    );
    assert!(row_by_name(&m, "e1").vars.is_empty());
    assert_eq!(row_by_name(&m, "e1").lhs, -3.0);
    let e = err("min\nst\n c: x >= +inf\nend");
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)), "{e}");
    let e = err("min\nst\n c: x <= -1e30\nend");
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)), "{e}");
    // A side that a constant moves past 1e30 is infinite, as it would read once written
    // (found by `reader_never_panics_on_lp_like_text`: `st 3 <= 1e30`).
    let m = read("min\nst\n g1: 3 <= 1e30\n g2: x + 1e30 >= 5\nend").model;
    assert_eq!(row_by_name(&m, "g1").kind(), RowKind::Free);
    assert_eq!(row_by_name(&m, "g2").kind(), RowKind::Free);
    let e = err("min\nst\n g3: 2 <= x - 1e30 <= 4\nend");
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)), "{e}");
}

#[test]
fn unnamed_rows_avoid_clashes() {
    let m = read("min\nst\n x >= 1\n R1: x <= 5\n x + y >= 0\n R3: y <= 2\n x = 1\nend").model;
    let names: Vec<_> = m.rows().map(|r| r.name.to_string()).collect();
    assert_eq!(names, ["R1_1", "R1", "R3_1", "R3", "R5"]);
    m.validate().unwrap();
}

#[test]
fn numbers() {
    let text = "min\n obj: 1e+30 a + .5 b + 5. c + 1E-7 d + 0.1 e_ + 123456789012345678 f\nst\nend";
    let m = read(text).model;
    let objs: Vec<_> = m.vars().iter().map(|v| v.obj).collect();
    assert_eq!(objs, [1e30, 0.5, 5.0, 1e-7, 0.1, 123456789012345678.0]);
}

#[test]
fn bounds_forms() {
    let text = "min\n obj: a + b + c + d + e_ + f + g + h + i + j + k + l\nst\nbounds\n a <= 5\n b >= -3\n -inf <= c <= 5\n d free\n e_ = 3\n 5 >= f\n g >= -inf\n -2 <= h\n 1 <= i <= 2\n 4 >= j >= -1\n -1e30 <= k <= 1e30\n l Free\n m <= 7\nend";
    let o = read(text);
    let m = &o.model;
    let b = |n: &str| (var(m, n).lb, var(m, n).ub);
    assert_eq!(b("a"), (0.0, 5.0));
    assert_eq!(b("b"), (-3.0, INF));
    assert_eq!(b("c"), (-INF, 5.0));
    assert_eq!(b("d"), (-INF, INF));
    assert_eq!(b("e_"), (3.0, 3.0));
    assert_eq!(b("f"), (0.0, 5.0));
    assert_eq!(b("g"), (-INF, INF));
    assert_eq!(b("h"), (-2.0, INF));
    assert_eq!(b("i"), (1.0, 2.0));
    assert_eq!(b("j"), (-1.0, 4.0));
    assert_eq!(b("k"), (-INF, INF));
    assert_eq!(b("l"), (-INF, INF));
    assert_eq!(b("m"), (0.0, 7.0));
    assert_eq!(m.vars().last().unwrap().name, "m"); // created by the bounds section
    assert!(o.warnings.iter().any(|w| w.message.contains("`m`") && w.line == 17), "{:?}", o.warnings);
}

#[test]
fn bound_warnings_and_errors() {
    let o = read("min\n obj: x + y\nst\nbounds\n x >= 1\n x >= 2\n y <= -5\nend");
    assert_eq!(var(&o.model, "x").lb, 2.0);
    assert!(o.warnings.iter().any(|w| w.line == 6 && w.message.contains("set again")), "{:?}", o.warnings);
    assert!(
        o.warnings.iter().any(|w| w.line == 7 && w.message.contains("below its default lower bound")),
        "{:?}",
        o.warnings
    );
    let o = read("min\n obj: y\nst\nbounds\n y <= -5\n y >= -10\nend");
    assert!(o.warnings.is_empty(), "{:?}", o.warnings);
    for (text, line) in [
        ("min\nst\nbounds\n x >= inf\nend", 4),
        ("min\nst\nbounds\n x <= -inf\nend", 4),
        ("min\nst\nbounds\n x = 1e30\nend", 4),
    ] {
        let e = err(text);
        assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)), "{e}");
        assert_eq!(e.line, line);
    }
    let e = err("min\nst\nbounds\n x frees\nend");
    assert!(matches!(e.kind, ParseErrorKind::UnknownKeyword { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        "line 4: unknown keyword `frees` (after a variable in the bounds section, expected `free` or a comparison)"
    );
    let e = err("min\nst\nbounds\n 1 <= x >= 0\nend");
    assert_eq!(e.line, 4);
    let e = err("min\nst\nbounds\n x <=\nend");
    assert!(matches!(e.kind, ParseErrorKind::UnexpectedToken { .. }), "{e}");
}

#[test]
fn binaries_and_generals() {
    let text = "min\n obj: - x1 - x2 - x3 - x4 - x5 - x6 - x7\nst\nbounds\n x1 = 0\n x2 <= 5\n -3 <= x3\n x4 free\n x6 <= 10\n 0.25 <= x7 <= 0.75\nbin\n x1 x2 x3 x4 x5\ngen\n x6 x5 x8\nbinaries\n x7\nend";
    let o = read(text);
    let m = &o.model;
    let d = |n: &str| (var(m, n).kind, var(m, n).lb, var(m, n).ub);
    assert_eq!(d("x1"), (VarKind::Binary, 0.0, 0.0));
    assert_eq!(d("x2"), (VarKind::Binary, 0.0, 1.0));
    assert_eq!(d("x3"), (VarKind::Binary, 0.0, 1.0));
    assert_eq!(d("x4"), (VarKind::Binary, 0.0, 1.0));
    assert_eq!(d("x5"), (VarKind::Binary, 0.0, 1.0));
    assert_eq!(d("x6"), (VarKind::Integer, 0.0, 10.0));
    assert_eq!(d("x7"), (VarKind::Binary, 0.25, 0.75));
    assert_eq!(d("x8"), (VarKind::Integer, 0.0, INF));
    m.validate().unwrap();
    let clipped: Vec<_> = o.warnings.iter().filter(|w| w.message.contains("clipped")).map(|w| w.line).collect();
    assert_eq!(clipped, [12, 12, 12]);
    assert!(o.warnings.iter().any(|w| w.message.contains("both general and binary") && w.line == 14));
}

#[test]
fn empty_semi_and_sos_sections_are_fine() {
    let m = read("min\n obj: x\nst\n c: x >= 1\nsemi-continuous\nsos\nsemis\nend").model;
    assert_eq!(m.num_rows(), 1);
}

#[test]
fn unsupported_features() {
    for (text, line, what) in [
        ("min\n obj: x\nst\n c: x >= 1\nsemi-continuous\n x\nend", 6, "semi-continuous"),
        ("min\n obj: x\nsemi\n x\nend", 4, "semi-continuous"),
        ("min\n obj: x\nst\n c: x >= 1\nSOS\n s1: S1:: x:1 y:2\nend", 6, "SOS"),
        ("min\n obj: x + [ x ^ 2 ] / 2\nst\nend", 2, "quadratic"),
        ("min\n obj: x\nst\n c: x + [ x * y ] <= 3\nend", 4, "quadratic"),
        ("min\n obj: x\nst\n c: x * y <= 3\nend", 4, "quadratic"),
        ("min\n obj: x\nst\n c: b = 1 -> x + y <= 3\nend", 4, "indicator"),
        ("min\n obj: x\nst\n c: x >= 1\nlazy constraints\n d: x <= 3\nend", 5, "lazy"),
        ("min\n obj: x\nst\n c: x >= 1\nUser Cuts\n d: x <= 3\nend", 5, "user cuts"),
    ] {
        let e = err(text);
        assert!(matches!(e.kind, ParseErrorKind::Unsupported(_)), "{text}: {e}");
        assert_eq!(e.line, line, "{text}: {e}");
        assert!(e.to_string().contains(what), "{e}");
        assert!(e.to_string().contains("not supported"), "{e}");
    }
}

#[test]
fn error_messages_name_the_line_and_token() {
    let cases: &[(&str, usize, &str)] = &[
        ("min\n obj: x\nst\n c1: x + y 3\nend", 4, "unexpected number `3`"),
        ("min\n obj: x\nst\n c1: x + y >=\nend", 5, "expected a number after the comparison"),
        ("min\n obj: x\nst\n c1: x + >= 3\nend", 4, "expected a term after the sign"),
        ("min\n obj: x y\nst\nend", 2, "unexpected name `y`"),
        ("min\n obj: x\n c1: x >= 1\nend", 3, "Subject To"),
        ("min\n obj: x >= 1\nend", 2, "Subject To"),
        ("min\n obj: x\nst\n c1: x >= 1\n c1: x <= 2\nend", 5, "row `c1` is defined twice (first on line 4)"),
        ("min\n obj: x\nmax\n y\nend", 3, "section `objective` appears twice"),
        ("min\n obj: nan x\nend", 2, "NaN value `nan`"),
        ("min\n obj: x\nst\n c: x <= NaN\nend", 4, "NaN value `NaN`"),
        ("min\n obj: x\nbounds\n x <= nan\nend", 4, "NaN value"),
        ("min\n obj: inf x\nend", 2, "infinite coefficient `inf`"),
        ("min\n obj: 1e400 x\nend", 2, "infinite coefficient `1e400`"),
        ("min\n obj: x + inf\nend", 2, "infinite coefficient"),
        ("min\n obj: x\nst\n c: x + 1e400 >= 3\nend", 4, "infinite coefficient"),
        ("min\n obj: x\x01\nend", 2, "invalid character '\\u{1}'"),
        ("min\n obj: x\ngenerals\n x 3\nend", 4, "expected a variable name"),
        ("3 x\nmin\nend", 1, "expected a section keyword"),
        ("x + y\nmin\nend", 1, "found `+`"),
        ("min\n obj: x\nst\n c: 3 x\n", 5, "unexpected end of file"),
        ("min\n obj: x\nSubject To\n : x >= 1\nend", 4, "unexpected `:`"),
    ];
    for &(text, line, msg) in cases {
        let e = err(text);
        assert_eq!(e.line, line, "{text:?}: {e}");
        assert!(e.to_string().contains(msg), "{text:?}: `{e}` does not contain `{msg}`");
        assert!(e.to_string().starts_with(&format!("line {line}: ")), "{e}");
    }
}

#[test]
fn text_before_first_section_and_after_end() {
    let o = read("this is a title\nmin\n obj: x\nend\nanything ^%$ goes here\n");
    assert_eq!(o.model.num_vars(), 1);
    assert_eq!(o.warnings.len(), 2, "{:?}", o.warnings);
    assert!(o.warnings[0].message.contains("4 word(s) before the first section"));
    assert!(o.warnings[1].message.contains("after `End`"));
    let o = read("");
    assert_eq!(o.model.num_vars(), 0);
    let o = read("\\ only a comment\n");
    assert_eq!(o.model.num_vars(), 0);
    let o = read("\u{feff}Minimize\n obj: x\nEnd");
    assert_eq!(o.model.num_vars(), 1);
    assert!(o.warnings.is_empty());
}

#[test]
fn problem_name_and_directives() {
    let m = read("\\Problem name: my model \nmin\n obj: x\nend").model;
    assert_eq!(m.name, "my model");
    // Max header.
    let text = format!("{NEGATED_MAX_COMMENT}\nMinimize\n obj: - 2 x + 3 y - 5\nEnd");
    let m = read(&text).model;
    assert_eq!(m.sense, Sense::Maximize);
    assert_eq!((var(&m, "x").obj, var(&m, "y").obj, m.obj_constant), (2.0, -3.0, 5.0));
    // Header with `Maximize`: ignored with a warning.
    let o = read(&format!("{NEGATED_MAX_COMMENT}\nMaximize\n obj: 2 x\nEnd"));
    assert_eq!((o.model.sense, var(&o.model, "x").obj), (Sense::Maximize, 2.0));
    assert_eq!(o.warnings.len(), 1);
    // Header after the first section: ignored.
    let o = read(&format!("Minimize\n obj: 2 x\n{NEGATED_MAX_COMMENT}\nst\nEnd"));
    assert_eq!(o.model.sense, Sense::Minimize);
    // Ranged directive.
    let text = format!("min\n obj: x\nst\n{RANGED_ROW_COMMENT}\n r: x + y >= -5\n r_rhs: x + y <= 10\n s: x >= 0\nend");
    let o = read(&text);
    assert!(o.warnings.is_empty(), "{:?}", o.warnings);
    let m = o.model;
    assert_eq!(m.num_rows(), 2);
    assert_eq!((row_by_name(&m, "r").lhs, row_by_name(&m, "r").rhs), (-5.0, 10.0));
    // Mismatched halves: kept apart, with a warning.
    let text = format!("min\n obj: x\nst\n{RANGED_ROW_COMMENT}\n r: x + y >= -5\n r_rhs: x + 2 y <= 10\nend");
    let o = read(&text);
    assert_eq!(o.model.num_rows(), 2);
    assert_eq!(o.warnings.len(), 1);
    assert_eq!(o.warnings[0].line, 4);
    // Directive at the end of the section.
    let text = format!("min\n obj: x\nst\n r: x >= 1\n{RANGED_ROW_COMMENT}\nend");
    let o = read(&text);
    assert_eq!(o.warnings.len(), 1, "{:?}", o.warnings);
}

#[test]
fn sections_in_any_order() {
    let m = read("bounds\n x <= 3\ngenerals\n x\nst\n c: x + y >= 1\nmax\n obj: y\nend").model;
    assert_eq!(m.sense, Sense::Maximize);
    assert_eq!(m.vars().iter().map(|v| v.name.as_str()).collect::<Vec<_>>(), ["x", "y"]);
    assert_eq!((var(&m, "x").kind, var(&m, "x").ub), (VarKind::Integer, 3.0));
}

#[test]
fn many_warnings_are_capped() {
    let mut text = String::from("min\n obj: x\nst\nbounds\n");
    for _ in 0..3000 {
        text.push_str(" x <= 1\n");
    }
    text.push_str("end\n");
    let o = read(&text);
    assert_eq!(o.warnings.len(), MAX_WARNINGS);
    assert!(o.warnings.last().unwrap().message.contains("more warnings"));
}

// ----- writer -----

fn sample_model() -> Model {
    let mut m = Model::new("sample");
    let x = m.add_continuous("x", 0.0, INF, 2.0);
    let y = m.add_continuous("y", -INF, INF, 0.0);
    let b = m.add_binary("b", -1.0);
    let n = m.add_integer("n", -3.0, 7.0, 0.5);
    let f = m.add_binary("fixed", 1.0);
    m.var_mut(f).ub = 0.0;
    m.obj_constant = 7.5;
    m.add_le("le", [(x, 1.0), (y, -1.0)], 4.0);
    m.add_ge("ge", [(x, 3.0), (b, 2.5)], -1.0);
    m.add_eq("eq", [(n, 1.0), (y, 1.0)], 2.0);
    m.add_row("ranged", -5.0, 10.0, [(x, 1.0), (n, -1.0)]);
    m.add_row("fr", -INF, INF, [(x, 1.0), (b, 1.0)]);
    m.add_row("empty", 2.0, INF, []);
    m
}

#[test]
fn writer_output_is_as_documented() {
    let m = sample_model();
    let (text, map) = write_str(&m, &WriteOptions::default());
    assert!(map.is_identity());
    let expected = "\\ Written by netspec VERSION (CPLEX LP format)
\\Problem name: sample
Minimize
 obj: 2 x + 0 y - b + 0.5 n + fixed + 7.5
Subject To
 le: x - y <= 4
 ge: 3 x + 2.5 b >= -1
 eq: n + y = 2
\\ netspec: ranged row
 ranged: x - n >= -5
 ranged_rhs: x - n <= 10
 fr: x + b >= -inf
 empty: >= 2
Bounds
 y free
 -3 <= n <= 7
 fixed = 0
Generals
 n
Binaries
 b fixed
End
"
    .replace("VERSION", env!("CARGO_PKG_VERSION"));
    assert_eq!(text, expected);
    assert_eq!(read(&text).model, m);
}

#[test]
fn writer_negates_maximisation() {
    let mut m = sample_model();
    m.sense = Sense::Maximize;
    let (text, _) = write_str(&m, &WriteOptions::default());
    assert!(text.contains(&format!("{NEGATED_MAX_COMMENT}\n")));
    assert!(text.contains("Minimize\n obj: - 2 x - 0 y + b - 0.5 n - fixed - 7.5\n"), "{text}");
    assert_eq!(read(&text).model, m);
    let (text, _) = write_str(&m, &WriteOptions { negate_max: false, ..Default::default() });
    assert!(text.contains("Maximize\n obj: 2 x + 0 y - b + 0.5 n + fixed + 7.5\n"), "{text}");
    assert_eq!(read(&text).model, m);
}

#[test]
fn writer_renames_unwritable_names() {
    let mut m = Model::new("");
    m.objective_name = "st".into();
    let a = m.add_continuous("a b", 0.0, 1.0, 1.0);
    let b = m.add_continuous("a_b", 0.0, 1.0, 1.0);
    let c = m.add_continuous("2x", 0.0, 1.0, 1.0);
    let d = m.add_continuous("free", 0.0, 1.0, 1.0);
    let e = m.add_continuous("e12", 0.0, 1.0, 1.0);
    let f = m.add_continuous("x/y", 0.0, 1.0, 1.0);
    let g = m.add_continuous("z".repeat(300), 0.0, 1.0, 1.0);
    m.add_le("_st", [(a, 1.0), (b, 1.0), (c, 1.0), (d, 1.0), (e, 1.0), (f, 1.0), (g, 1.0)], 1.0);
    m.add_le("r:1", [(a, 1.0)], 1.0);
    let (text, map) = write_str(&m, &WriteOptions::default());
    assert_eq!(map.vars["a b"], "a_b_1");
    assert!(!map.vars.contains_key("a_b"));
    assert_eq!(map.vars["2x"], "_2x");
    assert_eq!(map.vars["free"], "_free");
    assert_eq!(map.vars["e12"], "_e12");
    assert_eq!(map.vars["x/y"], "x_y");
    assert_eq!(map.vars[&"z".repeat(300)], "z".repeat(100));
    assert_eq!(map.rows["st"], "_st");
    assert_eq!(map.rows["_st"], "_st_1");
    assert_eq!(map.rows["r:1"], "r_1");
    let back = read(&text).model;
    assert_eq!(back.objective_name, "_st");
    assert_eq!(back.num_vars(), 7);
    assert!(text.lines().all(|l| l.len() <= 250));
}

#[test]
fn writer_refuses_unwritable_models() {
    let mut m = Model::new("");
    let x = m.add_continuous("x", 0.0, 1.0, f64::NAN);
    let mut buf = Vec::new();
    let e = write(&m, &mut buf, &WriteOptions::default()).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
    m.var_mut(x).obj = 1.0;
    m.add_le("r", [(x, INF)], 1.0);
    assert!(write(&m, &mut buf, &WriteOptions::default()).is_err());
    let mut m = Model::new("");
    m.add_continuous("x", INF, INF, 1.0);
    assert!(write(&m, &mut buf, &WriteOptions::default()).is_err());
}

#[test]
fn long_rows_are_wrapped_under_255_characters() {
    let mut m = Model::new("wide");
    let vars: Vec<VarId> = (0..1000)
        .map(|j| m.add_integer(format!("variable_with_a_long_name_{j}"), -1e-300 * j as f64, 1e29, -1.0 / 3.0))
        .collect();
    m.add_row(
        "wide_row",
        -123456.789,
        1.0 / 7.0,
        vars.iter().enumerate().map(|(j, &v)| (v, if j % 2 == 0 { -2.0f64.powi(-(j as i32)) } else { 1.0 / 3.0 })),
    );
    let long = "n".repeat(200);
    let v =
        m.add_continuous(long.clone(), -1.2345678901234567e-300, -2.2250738585072014e-308, -1.2345678901234567e-300);
    m.add_row(long.clone(), -1.2345678901234567e-300, 1.2345678901234567e-300, [(v, -1.2345678901234567e-300)]);
    for opts in [
        WriteOptions::default(),
        WriteOptions { max_line_len: 80, ..Default::default() },
        WriteOptions { max_name_len: 200, ..Default::default() },
    ] {
        let (text, map) = write_str(&m, &opts);
        assert_eq!(map.is_identity(), opts.max_name_len >= 200);
        let longest = text.lines().map(str::len).max().unwrap();
        assert!(longest <= opts.max_line_len.max(opts.max_name_len + 37).min(250), "longest line {longest}");
        if opts.max_line_len == 250 {
            assert!(text.lines().filter(|l| l.len() > 200).count() > 10);
        }
        for l in text.lines().skip(1) {
            // Continuation and data lines start with a space; section lines are keywords.
            assert!(l.starts_with(' ') || l.starts_with('\\') || l.chars().next().unwrap().is_ascii_uppercase(), "{l}");
        }
        assert_eq!(read(&text).model, renamed(&m, &map));
    }
}

#[test]
fn numbers_round_trip_bit_exactly() {
    let values = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        0.1,
        1.0 / 3.0,
        2.0 / 3.0,
        1e-300,
        5e-324,
        f64::MIN_POSITIVE,
        f64::MAX,
        -f64::MAX,
        1e15,
        1e16,
        123456789012345.6,
        9007199254740993.0,
        0.30000000000000004,
        1e22,
        1e23,
        4.35e-320,
    ];
    let mut m = Model::new("");
    let vars: Vec<VarId> =
        values.iter().enumerate().map(|(j, &c)| m.add_continuous(format!("x{j}"), 0.0, INF, c)).collect();
    m.add_le("r", vars.iter().zip(&values).map(|(&v, &a)| (v, a)), 1e-300);
    m.obj_constant = -1.0 / 3.0;
    let (text, _) = write_str(&m, &WriteOptions::default());
    let back = read(&text).model;
    for (a, b) in m.vars().iter().zip(back.vars()) {
        assert_eq!(a.obj.to_bits(), b.obj.to_bits(), "{} vs {}", a.obj, b.obj);
    }
    let (r0, r1) = (m.row(crate::milp::RowId(0)), back.row(crate::milp::RowId(0)));
    for (a, b) in r0.coefs.iter().zip(r1.coefs) {
        assert_eq!(a.to_bits(), b.to_bits());
    }
    assert_eq!(back.obj_constant.to_bits(), m.obj_constant.to_bits());
}

#[test]
fn empty_model_round_trips() {
    for sense in [Sense::Minimize, Sense::Maximize] {
        let mut m = Model::new("");
        m.sense = sense;
        let (text, _) = write_str(&m, &WriteOptions::default());
        assert_eq!(read(&text).model, m);
        m.obj_constant = 3.0;
        let (text, _) = write_str(&m, &WriteOptions::default());
        assert_eq!(read(&text).model, m);
    }
}

#[test]
fn writing_to_a_failing_writer_fails() {
    struct Fail;
    impl std::io::Write for Fail {
        fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
            Err(std::io::Error::other("disk full"))
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }
    assert!(write(&sample_model(), &mut Fail, &WriteOptions::default()).is_err());
}

// ----- property tests -----

/// Names that stress the sanitiser: plain, keywords, exponent-like, digits first, bad
/// characters, unicode, long.
fn name_strategy() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => "[a-zA-Z_][a-zA-Z0-9_.]{0,6}",
        1 => prop::sample::select(vec![
            "st", "ST", "end", "free", "inf", "Infinity", "nan", "min", "max", "bounds", "bin", "gen", "int", "e", "E1",
            "e1x", "ee", "inf1", "nanx", "subject", "s.t.", "obj", "R1", "x_rhs", "semi", "sos",
        ])
        .prop_map(String::from),
        2 => "[ -~]{1,8}",
        1 => "\\PC{1,5}",
        1 => "[0-9.(),;][a-z]{0,3}",
        1 => "[a-z]{190,260}",
    ]
}

fn unique(names: Vec<String>) -> Vec<String> {
    let mut seen = std::collections::HashSet::new();
    names
        .into_iter()
        .enumerate()
        .map(|(i, mut n)| {
            while !seen.insert(n.clone()) {
                n = format!("{n}#{i}");
            }
            n
        })
        .collect()
}

/// Any finite value, biased towards awkward ones.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-1000i32..1000).prop_map(f64::from),
        3 => -1e6f64..1e6,
        1 => prop::sample::select(vec![0.0, -0.0, 1.0, -1.0, 0.1, 1.0 / 3.0, 1e-300, 5e-324, 1e29, -9.99e29, 1e15, 1e16, 2.5e-7]),
        1 => (-10.0f64..10.0, -320i32..29).prop_map(|(m, e)| m * 10f64.powi(e)),
    ]
}

/// Any finite coefficient (may exceed 1e30).
fn coef() -> impl Strategy<Value = f64> {
    prop_oneof![4 => value(), 1 => prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO]
}

#[derive(Debug, Clone)]
struct Spec {
    model: Model,
    opts: WriteOptions,
}

fn model_strategy() -> impl Strategy<Value = Spec> {
    let vars = prop::collection::vec((name_strategy(), 0u8..3, value(), value(), 0u8..6, coef()), 0..8);
    let rows = prop::collection::vec(
        (
            name_strategy(),
            0u8..5,
            value(),
            value(),
            prop::collection::vec((any::<prop::sample::Index>(), coef()), 0..6),
        ),
        0..7,
    );
    (vars, rows, "[ -~]{0,20}", name_strategy(), any::<bool>(), value(), any::<bool>(), 40usize..260).prop_map(
        |(vars, rows, mname, oname, max, constant, negate_max, line_len)| {
            let mut m = Model::new(mname.trim());
            m.sense = if max { Sense::Maximize } else { Sense::Minimize };
            m.obj_constant = constant;
            let var_names = unique(vars.iter().map(|v| v.0.clone()).collect());
            for ((_, kind, a, b, bk, obj), name) in vars.into_iter().zip(var_names) {
                let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
                let (kind, lb, ub) = match kind {
                    0 => (VarKind::Continuous, lo, hi),
                    1 => (VarKind::Integer, lo.round(), hi.round()),
                    _ => {
                        let (l, u) = [(0.0, 1.0), (0.0, 0.0), (1.0, 1.0), (0.25, 0.75)][bk as usize % 4];
                        (VarKind::Binary, l, u)
                    }
                };
                let (lb, ub) = if kind == VarKind::Binary {
                    (lb, ub)
                } else {
                    match bk {
                        0 => (0.0, INF),
                        1 => (-INF, INF),
                        2 => (-INF, ub),
                        3 => (lb, INF),
                        4 => (lb, lb),
                        _ => (lb, ub),
                    }
                };
                m.add_var(name, kind, lb, ub, obj);
            }
            let row_names = unique(rows.iter().map(|r| r.0.clone()).chain([oname.clone()]).collect());
            let n = m.num_vars();
            for ((_, kind, a, b, entries), name) in rows.into_iter().zip(&row_names) {
                let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
                let (lhs, rhs) = match kind {
                    0 => (-INF, hi),
                    1 => (lo, INF),
                    2 => (lo, lo),
                    3 if lo < hi => (lo, hi),
                    3 => (lo - 1.0, hi),
                    _ => (-INF, INF),
                };
                let mut seen = std::collections::HashSet::new();
                let terms: Vec<(VarId, f64)> = if n == 0 {
                    vec![]
                } else {
                    entries
                        .into_iter()
                        .map(|(i, c)| (VarId(i.index(n) as u32), c))
                        .filter(|(v, _)| seen.insert(*v))
                        .collect()
                };
                m.add_row(name.clone(), lhs, rhs, terms);
            }
            m.objective_name = row_names.last().cloned().unwrap_or_default();
            Spec { model: m, opts: WriteOptions { negate_max, max_line_len: line_len, ..Default::default() } }
        },
    )
}

/// `model` with names changed as `map` says.
fn renamed(model: &Model, map: &crate::io::NameMap) -> Model {
    let mut m = model.clone();
    for j in 0..m.num_vars() {
        let v = m.var_mut(VarId(j as u32));
        if let Some(n) = map.vars.get(&v.name) {
            v.name = n.clone();
        }
    }
    for r in 0..m.num_rows() {
        let id = crate::milp::RowId(r as u32);
        if let Some(n) = map.rows.get(m.row(id).name) {
            let n = n.clone();
            m.set_row_name(id, n);
        }
    }
    // The objective shares the rows' namespace; a row of the same name owns the map entry.
    if !model.rows().any(|r| r.name == model.objective_name) {
        if let Some(n) = map.rows.get(&m.objective_name) {
            m.objective_name = n.clone();
        }
    }
    m
}

proptest! {
    // 512 cases unless PROPTEST_CASES says otherwise.
    #![proptest_config(ProptestConfig {
        cases: std::env::var("PROPTEST_CASES").ok().and_then(|s| s.parse().ok()).unwrap_or(512),
        ..ProptestConfig::default()
    })]

    #[test]
    fn write_read_round_trip(spec in model_strategy()) {
        let (text, map) = write_str(&spec.model, &spec.opts);
        let back = match read_str(&text) {
            Ok(o) => o,
            Err(e) => return Err(TestCaseError::fail(format!("{e}\n{text}"))),
        };
        prop_assert!(back.warnings.is_empty(), "{:?}\n{}", back.warnings, text);
        let expected = renamed(&spec.model, &map);
        prop_assert_eq!(&back.model, &expected, "\n{}", text);
        // Bit-exact coefficients (== on f64 equates 0.0 and -0.0; a default bound of -0.0 is
        // not written, so bounds may come back as +0.0).
        for (a, b) in back.model.vars().iter().zip(expected.vars()) {
            prop_assert_eq!(a.obj.to_bits(), b.obj.to_bits());
        }
        let (_, _, c1) = back.model.csr();
        let (_, _, c2) = expected.csr();
        prop_assert!(c1.iter().zip(c2).all(|(a, b)| a.to_bits() == b.to_bits()));
        // Names in the file are unique and every line fits.
        let limit = spec.opts.max_line_len.max(250);
        prop_assert!(text.lines().all(|l| l.len() <= limit), "{}", text);
        prop_assert!(back.model.validate().is_ok() || spec.model.validate().is_err());
    }

    #[test]
    fn reader_never_panics_on_random_text(text in "\\PC{0,200}") {
        let _ = read_str(&text);
    }

    #[test]
    fn reader_never_panics_on_lp_like_text(
        parts in prop::collection::vec(prop::sample::select(vec![
            "min", "max", "st", "subject", "to", "bounds", "gen", "bin", "semi", "-", "continuous", "sos", "end", "free",
            "inf", "-inf", "nan", "x", "y", "c1", ":", "::", "+", "-", "<=", ">=", "=", "<", ">", "=>", "=<", "3", "1e30",
            "-2.5", ".5", "5.", "1e400", "[", "]", "*", "^", "/", "->", "\n", " ", "\\ c\n", "\\ netspec: ranged row\n",
            "\\ netspec: maximize, objective negated\n", "\\Problem name: p\n", "lazy", "constraints", "S1", "\t", "\r\n",
        ]), 0..60)
    ) {
        let text: String = parts.join(" ");
        if let Ok(o) = read_str(&text) {
            // Whatever was read can be written and read back.
            if o.model.validate().is_ok() {
                let (again, map) = write_str(&o.model, &WriteOptions::default());
                let mut back = read_str(&again).map_err(|e| TestCaseError::fail(format!("{e}\n{again}")))?.model;
                let expected = renamed(&o.model, &map);
                back.objective_name = expected.objective_name.clone(); // may be ambiguous, see `renamed`
                prop_assert_eq!(back, expected, "\n{}\n{}", text, again);
            }
        }
    }

    #[test]
    fn reader_never_panics_on_mutated_files(
        edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>(), 0u8..3), 1..8)
    ) {
        let (text, _) = write_str(&sample_model(), &WriteOptions::default());
        let mut bytes = text.into_bytes();
        for (i, b, op) in edits {
            if bytes.is_empty() { break; }
            let k = i.index(bytes.len());
            match op {
                0 => bytes[k] = b,
                1 => { bytes.remove(k); }
                _ => bytes.insert(k, b),
            }
        }
        let text = String::from_utf8_lossy(&bytes);
        let _ = read_str(&text);
    }
}

// ----- tools (ignored by default) -----

/// The 10^6-nonzero model of `benches/io.rs`.
fn bench_model() -> Model {
    const ROWS: usize = 50_000;
    const VARS: usize = 100_000;
    const PER_ROW: usize = 20;
    let mut m = Model::new("bench");
    m.reserve(VARS, ROWS, ROWS * PER_ROW);
    let mut s: u64 = 0x2545F4914F6CDD1D;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    for j in 0..VARS {
        let obj = (next() % 1000) as f64 / 7.0;
        match j % 4 {
            0 | 1 => m.add_binary(format!("E_e{j}"), obj),
            2 => m.add_integer(format!("N_v{j}"), 0.0, 10.0, obj),
            _ => m.add_continuous(format!("D_h{j}"), 0.0, 1e4, obj),
        };
    }
    let mut terms = Vec::with_capacity(PER_ROW);
    for r in 0..ROWS {
        terms.clear();
        let base = next() as usize % (VARS - PER_ROW * 5);
        for k in 0..PER_ROW {
            terms.push((VarId((base + k * 5) as u32), ((next() % 200) as f64 - 100.0) / 3.0));
        }
        let rhs = (next() % 100) as f64;
        match r % 4 {
            0 => m.add_le(format!("c{r}"), terms.iter().copied(), rhs),
            1 => m.add_ge(format!("c{r}"), terms.iter().copied(), -rhs),
            2 => m.add_eq(format!("c{r}"), terms.iter().copied(), rhs),
            _ => m.add_row(format!("c{r}"), -rhs, rhs, terms.iter().copied()),
        };
    }
    m
}

/// Measures read and write throughput on the 10^6-nonzero model:
/// `cargo test --release --lib io::lp::tests::throughput -- --ignored --nocapture`.
#[test]
#[ignore]
fn throughput() {
    let m = bench_model();
    let opts = WriteOptions::default();
    let mut buf = Vec::with_capacity(64 << 20);
    write(&m, &mut buf, &opts).unwrap();
    let mb = buf.len() as f64 / 1e6;
    // Best of several runs (the machine may be shared).
    let mut w = f64::INFINITY;
    for _ in 0..7 {
        buf.clear();
        let t = std::time::Instant::now();
        write(&m, &mut buf, &opts).unwrap();
        w = w.min(t.elapsed().as_secs_f64());
    }
    let text = String::from_utf8(buf).unwrap();
    let mut r = f64::INFINITY;
    for _ in 0..7 {
        let t = std::time::Instant::now();
        let o = read_str(&text).unwrap();
        r = r.min(t.elapsed().as_secs_f64());
        assert_eq!(o.model.num_nonzeros(), m.num_nonzeros());
    }
    assert_eq!(read_str(&text).unwrap().model, m);
    println!(
        "LP file {mb:.1} MB, {} nonzeros: write {:.0} MB/s ({w:.3} s), read {:.0} MB/s ({r:.3} s)",
        m.num_nonzeros(),
        mb / w,
        mb / r
    );
}

/// Writes random models and the bench model as LP files plus a JSON description, for checking
/// with other readers (`NETSPEC_LP_DUMP=/dir cargo test ... dump_for_other_readers -- --ignored`).
#[test]
#[ignore]
fn dump_for_other_readers() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let Ok(dir) = std::env::var("NETSPEC_LP_DUMP") else { return };
    let dir = std::path::PathBuf::from(dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut runner = TestRunner::deterministic();
    let strategy = model_strategy();
    // Other readers treat huge values as infinite (HiGHS from 1e20 for coefficients, SCIP 1e20
    // for everything) and drop tiny ones (SCIP below 1e-9): keep values moderate.
    let tame = |v: f64| {
        if v.is_finite() && (v.abs() > 1e9 || (v != 0.0 && v.abs() < 1e-6)) {
            (v.abs().log2() * 7.0).round()
        } else {
            v
        }
    };
    for i in 0..300 {
        let spec = strategy.new_tree(&mut runner).unwrap().current();
        let wild = spec.model;
        let mut m = Model::new(wild.name.clone());
        m.sense = wild.sense;
        m.objective_name = wild.objective_name.clone();
        m.obj_constant = tame(wild.obj_constant);
        for v in wild.vars() {
            let (lb, ub) = (tame(v.lb), tame(v.ub));
            let (lb, ub) = if lb <= ub { (lb, ub) } else { (ub, lb) };
            m.add_var(v.name.clone(), v.kind, lb, ub, tame(v.obj));
        }
        for r in wild.rows() {
            let (lhs, rhs) = (tame(r.lhs), tame(r.rhs));
            let (lhs, rhs) = if lhs <= rhs { (lhs, rhs) } else { (rhs, lhs) };
            m.add_row(r.name, lhs, rhs, r.terms().map(|(v, a)| (v, tame(a))));
        }
        if i % 2 == 0 {
            m.sense = Sense::Maximize;
        }
        let (text, map) = write_str(&m, &spec.opts);
        let m = renamed(&m, &map);
        std::fs::write(dir.join(format!("m{i}.lp")), &text).unwrap();
        let num = |v: f64| -> serde_json::Value {
            if v.is_finite() {
                serde_json::json!(v)
            } else {
                serde_json::json!(if v > 0.0 { "inf" } else { "-inf" })
            }
        };
        // What a reader without our conventions must see.
        let negated = m.sense == Sense::Maximize && spec.opts.negate_max;
        let s = if negated { -1.0 } else { 1.0 };
        let vars: Vec<_> = m
            .vars()
            .iter()
            .map(|v| serde_json::json!({"name": v.name, "kind": format!("{:?}", v.kind), "lb": num(v.lb), "ub": num(v.ub), "obj": s * v.obj}))
            .collect();
        let mut rows = Vec::new();
        for (r, upper) in m.rows().zip(0..) {
            let terms: Vec<_> = r.terms().map(|(v, a)| serde_json::json!([m.var(v).name, a])).collect();
            if r.kind() == RowKind::Ranged {
                let _ = upper;
                rows.push(serde_json::json!({"name": r.name, "lhs": num(r.lhs), "rhs": "inf", "terms": terms}));
                rows.push(serde_json::json!({"name": null, "lhs": "-inf", "rhs": num(r.rhs), "terms": terms}));
            } else {
                rows.push(serde_json::json!({"name": r.name, "lhs": num(r.lhs), "rhs": num(r.rhs), "terms": terms}));
            }
        }
        let desc = serde_json::json!({
            "maximize": m.sense == Sense::Maximize && !negated,
            "offset": s * m.obj_constant,
            "objective_name": m.objective_name,
            "vars": vars,
            "rows": rows,
        });
        std::fs::write(dir.join(format!("m{i}.json")), serde_json::to_string_pretty(&desc).unwrap()).unwrap();
    }
    // The HiGHS corpus, read and written again.
    let corpus = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/highs-check");
    for file in ["1448.lp", "fixed-binary.lp", "issue-2388.lp", "issue-2585.lp", "no-newline-eof.lp"] {
        let m = crate::io::read_model_file(&corpus.join(file)).unwrap().model;
        crate::io::write_model_file(&m, &dir.join(format!("corpus-{file}"))).unwrap();
    }
    let mut f = std::fs::File::create(dir.join("bench.lp")).unwrap();
    write(&bench_model(), &mut f, &WriteOptions::default()).unwrap();
}
