//! Unit and property tests of the MPS reader and writer.

use super::*;
use crate::io::ReadModel;
use crate::milp::{RowId, RowKind, Sense, VarId, VarKind};
use proptest::prelude::*;
use std::path::PathBuf;

const INF: f64 = f64::INFINITY;

fn read(text: &str) -> ReadModel {
    match read_str(text) {
        Ok(o) => o,
        Err(e) => panic!("unexpected parse error: {e}\n{text}"),
    }
}

fn read_err(text: &str) -> ParseError {
    match read_str(text) {
        Ok(o) => panic!("expected an error, got {:?}", o.model),
        Err(e) => e,
    }
}

fn to_string(model: &Model, opts: &WriteOptions) -> (String, NameMap) {
    let mut buf = Vec::new();
    let map = write(model, &mut buf, opts).expect("write");
    (String::from_utf8(buf).expect("utf-8"), map)
}

fn var<'a>(m: &'a Model, name: &str) -> &'a crate::milp::Variable {
    m.vars().iter().find(|v| v.name == name).unwrap_or_else(|| panic!("no variable {name}"))
}

fn row<'a>(m: &'a Model, name: &str) -> crate::milp::RowView<'a> {
    m.rows().find(|r| r.name == name).unwrap_or_else(|| panic!("no row {name}"))
}

// ---------------------------------------------------------------------------------------------
// Reader: features.

#[test]
fn reads_features_fixture() {
    let o = read(include_str!("../../../fixtures/mps/features.mps"));
    let m = &o.model;
    assert!(o.warnings.is_empty(), "{:?}", o.warnings);
    assert_eq!(m.name, "features test");
    assert_eq!(m.sense, Sense::Maximize);
    assert_eq!(m.objective_name, "profit");
    assert_eq!(m.obj_constant, 5.5);
    let sides = |n: &str| {
        let r = row(m, n);
        (r.lhs, r.rhs)
    };
    assert_eq!(sides("le"), (6.0, 10.0));
    assert_eq!(sides("ge"), (2.0, 7.0));
    assert_eq!(sides("eqpos"), (3.0, 5.0));
    assert_eq!(sides("eqneg"), (1.0, 4.0));
    assert_eq!(sides("eqzero"), (1.0, 1.0));
    assert_eq!(sides("spare"), (-INF, INF));
    assert_eq!(row(m, "spare").kind(), RowKind::Free);
    assert_eq!(row(m, "spare").coefs, &[3.0]);
    let x = var(m, "x");
    assert_eq!((x.kind, x.lb, x.ub, x.obj), (VarKind::Continuous, -2.0, INF, 1.0));
    let i = var(m, "i");
    assert_eq!((i.kind, i.lb, i.ub, i.obj), (VarKind::Integer, 0.0, 1.0, 2.0));
    let j = var(m, "j");
    assert_eq!((j.kind, j.lb, j.ub), (VarKind::Integer, 0.0, 7.0));
    let b = var(m, "b");
    assert_eq!((b.kind, b.lb, b.ub), (VarKind::Binary, 0.0, 1.0));
    let u = var(m, "u");
    assert_eq!((u.kind, u.lb, u.ub, u.obj), (VarKind::Integer, 2.0, 8.0, 0.0));
    let f = var(m, "f");
    assert_eq!((f.kind, f.lb, f.ub, f.obj), (VarKind::Continuous, -INF, INF, -1.0));
    // Row `le` holds x and i, in column order.
    assert_eq!(row(m, "le").vars, &[VarId(0), VarId(1)]);
    m.validate().unwrap();
}

#[test]
fn reads_fixed_format_with_spaces_in_names() {
    let o = read(include_str!("../../../fixtures/mps/fixed_spaces.mps"));
    let m = &o.model;
    assert!(o.warnings.iter().any(|w| w.message.contains("fixed-format")), "{:?}", o.warnings);
    assert_eq!(m.name, "FIXED SPACES");
    assert_eq!(m.objective_name, "COST");
    let names: Vec<&str> = m.rows().map(|r| r.name).collect();
    assert_eq!(names, ["LIM_1", "LIM_2", "MY_EQN"]);
    let names: Vec<&str> = m.vars().iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["X_ONE", "Y_TWO", "Z_3"]);
    assert_eq!((row(m, "LIM_1").lhs, row(m, "LIM_1").rhs), (-INF, 4.0));
    assert_eq!((row(m, "LIM_2").lhs, row(m, "LIM_2").rhs), (1.0, INF));
    assert_eq!((row(m, "MY_EQN").lhs, row(m, "MY_EQN").rhs), (7.0, 9.0));
    let y = var(m, "Y_TWO");
    assert_eq!((y.kind, y.lb, y.ub, y.obj), (VarKind::Integer, 0.0, 3.0, 2.0));
    let z = var(m, "Z_3");
    assert_eq!((z.lb, z.ub, z.obj), (-INF, INF, -1.0));
    assert_eq!(m.num_nonzeros(), 5);
    m.validate().unwrap();
}

#[test]
fn objsense_forms() {
    let body = "ROWS\n N obj\nCOLUMNS\n    x obj 1\nENDATA\n";
    for (head, sense) in [
        ("OBJSENSE MAX\n", Sense::Maximize),
        ("OBJSENSE\n    MAX\n", Sense::Maximize),
        ("OBJSENSE\n    MAXIMIZE\n", Sense::Maximize),
        ("OBJSENSE\nMAX\n", Sense::Maximize),
        ("OBJSENSE    MINIMIZE\n", Sense::Minimize),
        ("OBJSENSE\n    MIN\n", Sense::Minimize),
        ("", Sense::Minimize),
    ] {
        let m = read(&format!("NAME t\n{head}{body}")).model;
        assert_eq!(m.sense, sense, "{head}");
    }
    let e = read_err("NAME t\nOBJSENSE\n    UP\nROWS\n N obj\nENDATA\n");
    assert_eq!(e.line, 3);
    assert!(matches!(e.kind, ParseErrorKind::BadObjSense(_)));
}

#[test]
fn ranges_sign_rules() {
    let text = "NAME\nROWS\n N o\n E e1\n E e2\n L l1\n L l2\n G g1\n G g2\nCOLUMNS\n    x e1 1 e2 1\n    x l1 1 l2 1\n    x g1 1 g2 1\nRHS\n    R e1 10 e2 10\n    R l1 10 l2 10\n    R g1 10 g2 10\nRANGES\n    R e1 3 e2 -3\n    R l1 3 l2 -3\n    R g1 3 g2 -3\nENDATA\n";
    let m = read(text).model;
    let s = |n: &str| (row(&m, n).lhs, row(&m, n).rhs);
    assert_eq!(s("e1"), (10.0, 13.0));
    assert_eq!(s("e2"), (7.0, 10.0));
    assert_eq!(s("l1"), (7.0, 10.0));
    assert_eq!(s("l2"), (7.0, 10.0));
    assert_eq!(s("g1"), (10.0, 13.0));
    assert_eq!(s("g2"), (10.0, 13.0));
}

#[test]
fn ranges_before_rhs_and_infinite_range() {
    let text =
        "NAME\nROWS\n N o\n L l\n E e\nCOLUMNS\n    x l 1 e 1\nRANGES\n    R l 3 e 1e30\nRHS\n    R l 10 e 2\nENDATA\n";
    let m = read(text).model;
    assert_eq!((row(&m, "l").lhs, row(&m, "l").rhs), (7.0, 10.0));
    assert_eq!((row(&m, "e").lhs, row(&m, "e").rhs), (2.0, INF));
}

#[test]
fn bounds_all_types() {
    let text = "NAME\nROWS\n N o\nCOLUMNS\n    up o 1\n    lo o 1\n    fx o 1\n    fr o 1\n    mi o 1\n    pl o 1\n    bv o 1\n    li o 1\n    ui o 1\n    neg o 1\n    inf o 1\nBOUNDS\n UP B up 4\n LO B lo -3\n FX B fx 2.5\n FR B fr\n MI B mi\n PL B pl\n BV B bv\n LI B li 2\n UI B ui 9\n UP B neg -2\n UP B inf 1e31\n LO B inf -infinity\nENDATA\n";
    let o = read(text);
    let m = &o.model;
    let b = |n: &str| {
        let v = var(m, n);
        (v.kind, v.lb, v.ub)
    };
    use VarKind::*;
    assert_eq!(b("up"), (Continuous, 0.0, 4.0));
    assert_eq!(b("lo"), (Continuous, -3.0, INF));
    assert_eq!(b("fx"), (Continuous, 2.5, 2.5));
    assert_eq!(b("fr"), (Continuous, -INF, INF));
    assert_eq!(b("mi"), (Continuous, -INF, INF));
    assert_eq!(b("pl"), (Continuous, 0.0, INF));
    assert_eq!(b("bv"), (Binary, 0.0, 1.0));
    assert_eq!(b("li"), (Integer, 2.0, INF));
    assert_eq!(b("ui"), (Integer, 0.0, 9.0));
    assert_eq!(b("neg"), (Continuous, -INF, -2.0));
    assert_eq!(b("inf"), (Continuous, -INF, INF));
    // The negative upper bound is reported.
    assert_eq!(o.warnings.len(), 1, "{:?}", o.warnings);
    assert_eq!(o.warnings[0].line, 26);
    assert!(o.warnings[0].message.contains("lower bound set to -inf"));
}

#[test]
fn bounds_without_vector_name() {
    let text = "NAME\nROWS\n N o\nCOLUMNS\n    x o 1\n    y o 1\n    z o 1\nBOUNDS\n UP x 4\n FR y\n MI z 0\nENDATA\n";
    let m = read(text).model;
    assert_eq!((var(&m, "x").lb, var(&m, "x").ub), (0.0, 4.0));
    assert_eq!((var(&m, "y").lb, var(&m, "y").ub), (-INF, INF));
    assert_eq!((var(&m, "z").lb, var(&m, "z").ub), (-INF, INF));
}

#[test]
fn unsupported_and_unknown_bounds() {
    let base = "NAME\nROWS\n N o\nCOLUMNS\n    x o 1\nBOUNDS\n";
    let e = read_err(&format!("{base} SC B x 4\nENDATA\n"));
    assert_eq!(e.line, 7);
    assert!(matches!(e.kind, ParseErrorKind::UnsupportedBound(..)));
    assert!(e.to_string().starts_with("line 7: bound type `SC` (semi-continuous) is not supported"), "{e}");
    let e = read_err(&format!("{base} XX B x 4\nENDATA\n"));
    assert!(matches!(e.kind, ParseErrorKind::UnknownBoundType(_)));
    let e = read_err(&format!("{base} UP B y 4\nENDATA\n"));
    assert_eq!(e.kind, ParseErrorKind::UnknownColumn("y".into()));
    let e = read_err(&format!("{base} UP B x -1e30\nENDATA\n"));
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)));
    let e = read_err(&format!("{base} FX B x inf\nENDATA\n"));
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)));
}

#[test]
fn integer_marker_default_bounds() {
    // HiGHS: integer columns from markers without any bound entry get [0, 1]; any bound entry
    // switches that off.
    let text = "NAME\nROWS\n N o\n L c\nCOLUMNS\n    M 'MARKER' 'INTORG'\n    a o 1 c 1\n    b o 1\n    c o 1\n    d o 1\n    M 'MARKER' 'INTEND'\n    e o 1\nBOUNDS\n UP B b 5\n LO B c 0\n UP B d -3\nENDATA\n";
    let o = read(text);
    let m = &o.model;
    let b = |n: &str| {
        let v = var(m, n);
        (v.kind, v.lb, v.ub)
    };
    assert_eq!(b("a"), (VarKind::Integer, 0.0, 1.0));
    assert_eq!(b("b"), (VarKind::Integer, 0.0, 5.0));
    assert_eq!(b("c"), (VarKind::Integer, 0.0, INF));
    assert_eq!(b("d"), (VarKind::Integer, -INF, -3.0));
    assert_eq!(b("e"), (VarKind::Continuous, 0.0, INF));
    assert_eq!(o.warnings.len(), 1);
}

#[test]
fn objective_constant_and_infinity() {
    let text = "NAME\nROWS\n N o\n L c\n G d\nCOLUMNS\n    x o 1 c 1\n    x d 1\nRHS\n    RHS o 2.5 c 1e30\n    RHS d -Infinity\nENDATA\n";
    let m = read(text).model;
    assert_eq!(m.obj_constant, -2.5);
    assert_eq!(row(&m, "c").kind(), RowKind::Free);
    assert_eq!(row(&m, "d").kind(), RowKind::Free);
    let e = read_err("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o 1 c 1\nRHS\n    RHS c -1e30\nENDATA\n");
    assert_eq!(e.line, 8);
    assert!(matches!(e.kind, ParseErrorKind::InfiniteBound(_)));
    let e = read_err("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o inf c 1\nENDATA\n");
    assert_eq!(e.kind, ParseErrorKind::InfiniteCoefficient("inf".into()));
}

#[test]
fn nan_is_an_error_everywhere() {
    for (text, line) in [
        ("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o NaN c 1\nENDATA\n", 6),
        ("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o 1 c 1\nRHS\n    R c nan\nENDATA\n", 8),
        ("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o 1 c 1\nRANGES\n    R c -nan\nENDATA\n", 8),
        ("NAME\nROWS\n N o\n L c\nCOLUMNS\n    x o 1 c 1\nBOUNDS\n UP B x NAN\nENDATA\n", 8),
    ] {
        let e = read_err(text);
        assert_eq!(e.line, line, "{text}");
        assert!(matches!(e.kind, ParseErrorKind::NaN(_)), "{e}");
    }
}

#[test]
fn comments_and_missing_endata() {
    let text = "* head\nNAME x\nROWS\n N o $ obj\n L c * le\n*\n   * indented comment\n\nCOLUMNS\n    x o 1 $ c 2\n    x c 3 *Comment\nRHS\n    $ nothing\n    R c 4";
    let o = read(text);
    assert_eq!(o.model.var(VarId(0)).obj, 1.0);
    assert_eq!(o.model.row(RowId(0)).coefs, &[3.0]);
    assert_eq!(o.model.row(RowId(0)).rhs, 4.0);
    assert_eq!(o.warnings.len(), 1);
    assert!(o.warnings[0].message.contains("ENDATA"));
    assert_eq!(o.warnings[0].line, 14);
    let o = read(&format!("{text}\n"));
    assert_eq!(o.warnings[0].line, 14);
}

#[test]
fn crlf_bom_and_tabs() {
    let text =
        "\u{feff}NAME\tt\r\nROWS\r\n N\tobj\r\n L\tc\r\nCOLUMNS\r\n\tx\tobj\t1\tc\t1\r\nRHS\r\n\tR\tc\t2\r\nENDATA\r\n";
    let m = read(text).model;
    assert_eq!(m.name, "t");
    assert_eq!(m.row(RowId(0)).rhs, 2.0);
}

#[test]
fn duplicates_and_odd_entries_warn() {
    let text = "NAME\nROWS\n N o\n L c\n N free\nCOLUMNS\n    x o 1 o 2\n    x c 1 c 2\nRHS\n    R c 1 c 2\n    R free 3\n    OTHER c 5\nRANGES\n    R o 1 free 1\nBOUNDS\n UP B x 1\n UP B x 2\n LI B x 1.5\nENDATA\n";
    let o = read(text);
    let m = &o.model;
    assert_eq!(m.var(VarId(0)).obj, 1.0);
    assert_eq!(m.row(RowId(0)).coefs, &[1.0]);
    assert_eq!(m.row(RowId(0)).rhs, 1.0);
    assert_eq!(m.var(VarId(0)).ub, 2.0);
    assert_eq!(m.var(VarId(0)).lb, 1.5);
    assert_eq!(m.var(VarId(0)).kind, VarKind::Integer);
    let lines: Vec<usize> = o.warnings.iter().map(|w| w.line).collect();
    assert_eq!(lines, [7, 8, 10, 11, 12, 14, 14, 17, 18], "{:?}", o.warnings);
}

#[test]
fn structural_errors_name_the_line() {
    let cases: &[(&str, usize)] = &[
        ("garbage\n", 1),
        ("NAME\nROWS\n X c\nENDATA\n", 3),
        ("NAME\nROWS\n N o\n L c\n G c\nENDATA\n", 5),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x nope 1\nENDATA\n", 5),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x o 1\n    y o 1\n    x o 1\nENDATA\n", 7),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x o\nENDATA\n", 5),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x o 1x\nENDATA\n", 5),
        ("NAME\nROWS\n N o\nCOLUMNS\n    M 'MARKER' 'INTEND'\nENDATA\n", 5),
        ("NAME\nCOLUMNS\n    x o 1\nENDATA\n", 2),
        ("NAME\nROWS\n N o\nROWS\nENDATA\n", 4),
        ("NAME\nQMATRIX\nENDATA\n", 2),
        ("NAME\nENDATA\n", 2),
        ("", 1),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x o 1\nRHS\n    R o 1 o\nENDATA\n", 7),
        ("NAME\nROWS\n N o\nCOLUMNS\n    x o 1\nBOUNDS\n UP B x\nENDATA\n", 7),
    ];
    for (text, line) in cases {
        let e = read_err(text);
        assert_eq!(e.line, *line, "{text:?}: {e}");
        assert!(e.to_string().starts_with(&format!("line {line}: ")));
    }
}

#[test]
fn objname_selects_objective() {
    let text = "NAME\nOBJNAME\n    second\nROWS\n N first\n N second\nCOLUMNS\n    x first 1 second 2\nENDATA\n";
    let m = read(text).model;
    assert_eq!(m.objective_name, "second");
    assert_eq!(m.var(VarId(0)).obj, 2.0);
    assert_eq!(m.row(RowId(0)).name, "first");
    assert_eq!(m.row(RowId(0)).kind(), RowKind::Free);
}

#[test]
fn no_objective_row_warns() {
    let o = read("NAME\nROWS\n L c\nCOLUMNS\n    x c 1\nENDATA\n");
    assert_eq!(o.model.objective_name, "obj");
    assert_eq!(o.warnings.len(), 1);
}

// ---------------------------------------------------------------------------------------------
// The corpus of HiGHS test instances.

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fixtures/highs-check")
}

#[test]
fn corpus_files() {
    let dir = corpus_dir();
    let expected = std::fs::read_to_string(dir.join("EXPECTED.csv")).unwrap();
    let mut checked = 0;
    for line in expected.lines().skip(1) {
        let fields: Vec<&str> = line.split(',').collect();
        let (file, kind) = (fields[0], fields[1]);
        if !file.ends_with(".mps") {
            continue;
        }
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let result = read_str(&text);
        match (kind, file) {
            ("bad", "warnings.mps") => match result {
                Err(e) => assert!(e.line > 0, "{file}: {e}"),
                Ok(o) => assert!(!o.warnings.is_empty(), "{file}: no warnings"),
            },
            ("bad", _) => {
                let e = result.err().unwrap_or_else(|| panic!("{file}: read without error"));
                assert!(e.line > 0, "{file}: {e}");
            }
            (_, _) => {
                let o = result.unwrap_or_else(|e| panic!("{file}: {e}"));
                o.model.validate().unwrap_or_else(|e| panic!("{file}: {e}"));
                assert_eq!(o.model.is_mip(), kind == "milp", "{file}");
                // infeasible-mip1.mps never closes its integer MARKER block.
                let expected_warnings = usize::from(file == "infeasible-mip1.mps");
                assert_eq!(o.warnings.len(), expected_warnings, "{file}: {:?}", o.warnings);
                // What we write, we read back identically.
                let (text, map) = to_string(&o.model, &WriteOptions::default());
                // Only silly-names.mps has names that must change (columns named like keywords).
                assert_eq!(map.is_identity(), file != "silly-names.mps", "{file}");
                assert_eq!(read(&text).model, rename(&o.model, &map), "{file}");
            }
        }
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} corpus files checked");
}

#[test]
fn corpus_specific_files() {
    let dir = corpus_dir();
    let get = |f: &str| read_str(&std::fs::read_to_string(dir.join(f)).unwrap());
    let m = get("afiro.mps").unwrap().model;
    assert_eq!((m.num_rows(), m.num_vars(), m.num_nonzeros()), (27, 32, 83));
    let m = get("adlittle.mps").unwrap().model;
    assert_eq!((m.num_rows(), m.num_vars()), (56, 97));
    let m = get("p0548.mps").unwrap().model;
    assert_eq!((m.num_rows(), m.num_vars()), (176, 548));
    assert!(m.vars().iter().all(|v| v.kind == VarKind::Integer && v.lb == 0.0 && v.ub == 1.0));
    let m = get("flugpl.mps").unwrap().model;
    assert_eq!((m.num_rows(), m.num_vars()), (18, 18));

    let m = get("comment.mps").unwrap().model;
    assert_eq!((m.num_rows(), m.num_vars()), (3, 2));
    assert_eq!(m.objective_name, "COST");
    assert_eq!((m.row(RowId(0)).lhs, m.row(RowId(0)).rhs), (1.0, 2.0));
    assert_eq!((m.row(RowId(1)).lhs, m.row(RowId(2)).lhs), (-2.0, -2.0));
    assert_eq!((m.var(VarId(0)).ub, m.var(VarId(0)).obj, m.var(VarId(1)).obj), (1.0, -1.0, -2.0));

    let m = get("silly-names.mps").unwrap().model;
    let names: Vec<&str> = m.vars().iter().map(|v| v.name.as_str()).collect();
    assert_eq!(names, ["C0", "OBJSENSE", "RANGES", "RHS", "C1"]);
    assert_eq!((m.num_rows(), m.sense, m.objective_name.as_str()), (1, Sense::Minimize, "COST"));

    for (f, line) in [("nan0.mps", 8), ("nan1.mps", 9), ("nan2.mps", 12)] {
        let e = get(f).unwrap_err();
        assert_eq!(e.line, line, "{f}");
        assert!(matches!(e.kind, ParseErrorKind::NaN(_)), "{f}: {e}");
    }
    let e = get("garbage.mps").unwrap_err();
    assert_eq!(e.line, 2);
    assert!(matches!(e.kind, ParseErrorKind::ExpectedSection(_)));
    let e = get("warnings.mps").unwrap_err();
    assert_eq!(e, ParseError { line: 12, kind: ParseErrorKind::UnknownRow("R11".into()) });
}

/// Prints our reading of every corpus file as JSON lines (for a cross-check against HiGHS).
#[test]
#[ignore]
fn corpus_dump_json() {
    let dir = corpus_dir();
    let out = std::env::var("NETSPEC_MPS_DUMP").unwrap_or_else(|_| "/tmp/netspec_mps_dump".into());
    std::fs::create_dir_all(&out).unwrap();
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    files.sort();
    for path in files.into_iter().filter(|p| p.extension().is_some_and(|e| e == "mps")) {
        let Ok(o) = read_str(&std::fs::read_to_string(&path).unwrap()) else { continue };
        let m = &o.model;
        let f = |x: f64| serde_json::Value::from(if x.is_finite() { x.to_string() } else { format!("{x}") });
        let (start, rows, vals) = m.to_csc();
        let json = serde_json::json!({
            "sense": format!("{:?}", m.sense),
            "offset": m.obj_constant,
            "col_names": m.vars().iter().map(|v| v.name.clone()).collect::<Vec<_>>(),
            "col_lower": m.vars().iter().map(|v| f(v.lb)).collect::<Vec<_>>(),
            "col_upper": m.vars().iter().map(|v| f(v.ub)).collect::<Vec<_>>(),
            "cost": m.vars().iter().map(|v| v.obj).collect::<Vec<_>>(),
            "integer": m.vars().iter().map(|v| v.kind.is_integral()).collect::<Vec<_>>(),
            "row_names": m.rows().map(|r| r.name.to_string()).collect::<Vec<_>>(),
            "row_lower": m.rows().map(|r| f(r.lhs)).collect::<Vec<_>>(),
            "row_upper": m.rows().map(|r| f(r.rhs)).collect::<Vec<_>>(),
            "start": start, "index": rows, "value": vals,
        });
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        std::fs::write(format!("{out}/{name}.json"), json.to_string()).unwrap();
        let mut w = std::fs::File::create(format!("{out}/{name}")).unwrap();
        write(m, &mut w, &WriteOptions::default()).unwrap();
    }
    // Our fixtures and a small maximisation (optimum 9), written both ways for maximisations.
    let mut small_max = small_model();
    small_max.sense = Sense::Maximize;
    for (name, m) in [
        ("features", read(include_str!("../../../fixtures/mps/features.mps")).model),
        ("fixed_spaces", read(include_str!("../../../fixtures/mps/fixed_spaces.mps")).model),
        ("small_max", small_max),
    ] {
        for (suffix, negate_max) in [("neg", true), ("objsense", false)] {
            let mut w = std::fs::File::create(format!("{out}/fixture-{name}.{suffix}.mps")).unwrap();
            write(&m, &mut w, &WriteOptions { negate_max, ..Default::default() }).unwrap();
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Writer.

fn small_model() -> Model {
    let mut m = Model::new("small");
    let x = m.add_continuous("x", 0.0, INF, 1.0);
    let y = m.add_integer("y", -5.0, 5.0, -2.0);
    let b = m.add_binary("b", 3.0);
    let _empty = m.add_continuous("empty", -INF, INF, 0.0);
    m.add_le("c1", [(x, 1.0), (y, 2.0)], 10.0);
    m.add_ge("c2", [(y, 1.0), (b, 1.0)], 1.0);
    m.add_eq("c3", [(x, 1.0), (b, -1.0)], 0.5);
    m.add_row("c4", -1.0, 4.0, [(x, 0.25)]);
    m.add_row("c5", -INF, INF, [(b, 7.0)]);
    m.obj_constant = 4.5;
    m
}

#[test]
fn writes_expected_text() {
    let (text, map) = to_string(&small_model(), &WriteOptions::default());
    assert!(map.is_identity());
    let expected = "\
NAME          small
ROWS
 N  obj
 L  c1
 G  c2
 E  c3
 G  c4
 N  c5
COLUMNS
    x         obj       1              c1        1
    x         c3        1              c4        0.25
    MARKER    'MARKER'                 'INTORG'
    y         obj       -2             c1        2
    y         c2        1
    b         obj       3              c2        1
    b         c3        -1             c5        7
    MARKER    'MARKER'                 'INTEND'
    empty     obj       0
RHS
    RHS       obj       -4.5           c1        10
    RHS       c2        1              c3        0.5
    RHS       c4        -1
RANGES
    RNG       c4        5
BOUNDS
 LO BND       y         -5
 UP BND       y         5
 BV BND       b
 FR BND       empty
ENDATA
";
    assert_eq!(text, expected);
    assert_eq!(read(&text).model, small_model());
    let (text, _) = to_string(&small_model(), &WriteOptions { align: false, ..Default::default() });
    assert!(text.contains("\n    x obj 1 c1 1\n"), "{text}");
    assert_eq!(read(&text).model, small_model());
}

#[test]
fn maximisation_round_trips_both_ways() {
    let mut m = small_model();
    m.sense = Sense::Maximize;
    let (text, _) = to_string(&m, &WriteOptions::default());
    assert!(text.starts_with(NEGATED_MAX_COMMENT));
    assert!(!text.contains("OBJSENSE"));
    assert!(text.contains("    y         obj       2 "), "{text}");
    assert!(text.contains("    RHS       obj       4.5 "), "{text}");
    assert_eq!(read(&text).model, m);
    // Other readers see the minimisation of the negated objective.
    let plain = text.replacen(NEGATED_MAX_COMMENT, "* other", 1);
    let neg = read(&plain).model;
    assert_eq!(neg.sense, Sense::Minimize);
    assert_eq!(neg.obj_constant, -4.5);
    assert_eq!(neg.var(VarId(1)).obj, 2.0);

    let (text, _) = to_string(&m, &WriteOptions { negate_max: false, ..Default::default() });
    assert!(text.contains("OBJSENSE\n    MAX\nROWS\n"), "{text}");
    assert_eq!(read(&text).model, m);
}

#[test]
fn binary_and_integer_bounds_round_trip() {
    let mut m = Model::new("b");
    m.add_var("b00", VarKind::Binary, 0.0, 0.0, 1.0);
    m.add_var("b11", VarKind::Binary, 1.0, 1.0, 1.0);
    m.add_var("bhalf", VarKind::Binary, 0.0, 0.5, 1.0);
    m.add_var("i01", VarKind::Integer, 0.0, 1.0, 1.0);
    m.add_var("ifree", VarKind::Integer, -INF, INF, 1.0);
    m.add_var("ipos", VarKind::Integer, 0.0, INF, 1.0);
    m.add_var("ineg", VarKind::Integer, -INF, -2.0, 1.0);
    m.add_var("cneg", VarKind::Continuous, -INF, -2.0, 1.0);
    m.add_var("cneg2", VarKind::Continuous, -3.0, -2.0, 1.0);
    m.add_var("cup", VarKind::Continuous, 0.0, 2.0, 1.0);
    let (text, _) = to_string(&m, &WriteOptions::default());
    let o = read(&text);
    assert!(o.warnings.is_empty(), "{:?}\n{text}", o.warnings);
    assert_eq!(o.model, m, "{text}");
    assert!(text.contains(" PL BND       ipos\n"), "{text}");
    assert!(text.contains("* netspec: binary b00\n FX BND       b00       0\n"), "{text}");
}

#[test]
fn names_are_sanitised_and_mapped() {
    let mut m = Model::new("names");
    m.objective_name = "cost".into();
    let a = m.add_continuous("a b", 0.0, 1.0, 1.0);
    let b = m.add_continuous("a_b", 0.0, 1.0, 1.0);
    let c = m.add_continuous("$c", 0.0, 1.0, 1.0);
    let d = m.add_continuous("'MARKER'", 0.0, 1.0, 1.0);
    m.add_continuous("RHS", 0.0, 1.0, 1.0);
    m.add_le("cost", [(a, 1.0), (b, 1.0)], 1.0);
    m.add_le("*r", [(c, 1.0), (d, 1.0)], 1.0);
    m.add_le("", [(c, 1.0)], 1.0);
    let (text, map) = to_string(&m, &WriteOptions::default());
    assert_eq!(map.vars.get("a b").map(String::as_str), Some("a_b_2"));
    assert_eq!(map.vars.get("$c").map(String::as_str), Some("_c"));
    assert_eq!(map.vars.get("'MARKER'").map(String::as_str), Some("_MARKER_"));
    assert_eq!(map.vars.get("RHS").map(String::as_str), Some("RHS_"));
    assert!(!map.vars.contains_key("a_b"));
    assert_eq!(map.rows.get("cost").map(String::as_str), Some("cost_2"));
    assert_eq!(map.rows.get("*r").map(String::as_str), Some("_r"));
    assert_eq!(map.rows.get("").map(String::as_str), Some("_"));
    let back = read(&text).model;
    back.validate().unwrap();
    assert_eq!(back, rename(&m, &map));
}

#[test]
fn writer_rejects_unwritable_models() {
    let mut m = Model::new("bad");
    m.add_continuous("x", 0.0, 1.0, f64::NAN);
    let e = write(&m, &mut Vec::new(), &WriteOptions::default()).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput);
    let mut m = Model::new("bad");
    let x = m.add_continuous("x", 0.0, 1.0, 0.0);
    m.add_row("r", 2.0, 1.0, [(x, 1.0)]);
    assert!(write(&m, &mut Vec::new(), &WriteOptions::default()).is_err());
}

/// The model with the writer's renamings applied.
fn rename(m: &Model, map: &NameMap) -> Model {
    let mut out = m.clone();
    for j in 0..out.num_vars() {
        let v = out.var_mut(VarId(j as u32));
        if let Some(new) = map.vars.get(&v.name) {
            v.name = new.clone();
        }
    }
    for r in 0..out.num_rows() {
        let id = RowId(r as u32);
        let name = out.row(id).name.to_string();
        if let Some(new) = map.rows.get(&name) {
            out.set_row_name(id, new.clone());
        }
    }
    out
}

// ---------------------------------------------------------------------------------------------
// Property tests.

/// Finite values that MPS can carry in bounds and sides (`|v| < 1e30`), with an emphasis on
/// awkward ones.
fn side_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-20i32..20).prop_map(|i| i as f64),
        2 => -4e29f64..4e29,
        2 => prop::num::f64::NORMAL.prop_filter("below 4e29", |v| v.abs() < 4e29),
        1 => prop::num::f64::SUBNORMAL,
        1 => Just(-0.0),
        1 => -1e3f64..1e3,
    ]
}

/// Any finite coefficient.
fn coef_value() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => (-20i32..20).prop_map(|i| i as f64),
        2 => prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
        1 => -1e3f64..1e3,
    ]
}

fn name_value(prefix: &'static str) -> impl Strategy<Value = String> {
    prop_oneof![
        6 => Just(prefix.to_string()),
        1 => prop::sample::select(vec![
            "a b", "$", "*", "", "RHS", "ENDATA", "'MARKER'", "MARKER", "N", "obj", "x_1", "\t", "é ü",
            "RANGES", "1e5", "-", "'INTORG'",
        ])
        .prop_map(String::from),
    ]
}

#[derive(Debug, Clone)]
enum RowSpec {
    Le(f64),
    Ge(f64),
    Eq(f64),
    Ranged(f64, f64),
    Free,
}

fn row_spec() -> impl Strategy<Value = RowSpec> {
    prop_oneof![
        side_value().prop_map(RowSpec::Le),
        side_value().prop_map(RowSpec::Ge),
        side_value().prop_map(RowSpec::Eq),
        (side_value(), side_value())
            .prop_filter("distinct sides", |(a, b)| a != b)
            .prop_map(|(a, b)| RowSpec::Ranged(a.min(b), a.max(b))),
        Just(RowSpec::Free),
    ]
}

fn bound_pair() -> impl Strategy<Value = (f64, f64)> {
    let lower = prop_oneof![2 => Just(0.0), 1 => Just(f64::NEG_INFINITY), 2 => side_value()];
    let upper = prop_oneof![2 => Just(INF), 1 => Just(1.0), 2 => side_value()];
    (lower, upper).prop_map(|(l, u)| if l <= u { (l, u) } else { (u.max(f64::MIN), l) }).prop_map(|(l, u)| {
        // Never +inf below or -inf above.
        (if l == INF { 0.0 } else { l }, if u == f64::NEG_INFINITY { 0.0 } else { u })
    })
}

fn var_spec() -> impl Strategy<Value = (String, VarKind, f64, f64, f64)> {
    let kind_bounds = prop_oneof![
        bound_pair().prop_map(|(l, u)| (VarKind::Continuous, l, u)),
        bound_pair().prop_map(|(l, u)| (VarKind::Integer, l, u)),
        prop_oneof![
            4 => Just((0.0, 1.0)),
            1 => Just((0.0, 0.0)),
            1 => Just((1.0, 1.0)),
            1 => Just((0.0, 0.5)),
            1 => Just((0.25, 1.0)),
        ]
        .prop_map(|(l, u)| (VarKind::Binary, l, u)),
    ];
    (name_value("x"), kind_bounds, prop_oneof![2 => Just(0.0), 3 => coef_value()])
        .prop_map(|(n, (k, l, u), c)| (n, k, l, u, c))
}

prop_compose! {
    fn arb_model()(
        name in prop::sample::select(vec!["", "m", "my model", "NAME", "x-1 (test)"]),
        maximize in any::<bool>(),
        obj_name in prop::sample::select(vec!["obj", "cost", "r", "COST"]),
        constant in prop_oneof![Just(0.0), coef_value()],
        vars in prop::collection::vec(var_spec(), 0..10),
        rows in prop::collection::vec(
            (name_value("r"), row_spec(), prop::collection::btree_map(0usize..10, coef_value(), 0..6)),
            0..10,
        ),
    ) -> Model {
        let mut m = Model::new(name);
        m.sense = if maximize { Sense::Maximize } else { Sense::Minimize };
        m.objective_name = obj_name.to_string();
        m.obj_constant = constant;
        let mut used = std::collections::HashSet::new();
        for (i, (n, k, l, u, c)) in vars.into_iter().enumerate() {
            let n = if used.insert(n.clone()) { n } else { format!("{n}{i}") };
            used.insert(n.clone());
            m.add_var(n, k, l, u, c);
        }
        let nv = m.num_vars();
        let mut used = std::collections::HashSet::new();
        for (i, (n, spec, terms)) in rows.into_iter().enumerate() {
            let n = if used.insert(n.clone()) { n } else { format!("{n}{i}") };
            used.insert(n.clone());
            let (l, u) = match spec {
                RowSpec::Le(b) => (f64::NEG_INFINITY, b),
                RowSpec::Ge(b) => (b, INF),
                RowSpec::Eq(b) => (b, b),
                RowSpec::Ranged(a, b) => (a, b),
                RowSpec::Free => (f64::NEG_INFINITY, INF),
            };
            let terms: Vec<(VarId, f64)> = terms
                .into_iter()
                .filter(|(j, _)| *j < nv)
                .map(|(j, a)| (VarId(j as u32), a))
                .collect();
            m.add_row(n, l, u, terms);
        }
        m
    }
}

fn bits_equal(a: &Model, b: &Model) -> bool {
    let fb = |x: f64| if x == 0.0 { 0 } else { x.to_bits() };
    a.vars().iter().zip(b.vars()).all(|(x, y)| fb(x.lb) == fb(y.lb) && fb(x.ub) == fb(y.ub) && fb(x.obj) == fb(y.obj))
        && a.row_sides().0.iter().zip(b.row_sides().0).all(|(x, y)| fb(*x) == fb(*y))
        && a.row_sides().1.iter().zip(b.row_sides().1).all(|(x, y)| fb(*x) == fb(*y))
        && a.csr().2.iter().zip(b.csr().2).all(|(x, y)| fb(*x) == fb(*y))
        && fb(a.obj_constant) == fb(b.obj_constant)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn round_trip(m in arb_model(), negate in any::<bool>(), align in any::<bool>()) {
        let opts = WriteOptions { negate_max: negate, align, ..Default::default() };
        let (text, map) = to_string(&m, &opts);
        let o = read_str(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let expected = rename(&m, &map);
        prop_assert!(o.warnings.is_empty(), "{:?}\n{}", o.warnings, text);
        prop_assert_eq!(&o.model, &expected, "{}", text);
        prop_assert!(bits_equal(&o.model, &expected));
        o.model.validate().map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
    }

    #[test]
    fn numbers_round_trip_bit_exactly(v in prop::num::f64::ANY.prop_filter("finite", |v| v.is_finite())) {
        let mut m = Model::new("n");
        let x = m.add_continuous("x", f64::NEG_INFINITY, INF, v);
        m.add_row("r", f64::NEG_INFINITY, INF, [(x, v)]);
        let (text, _) = to_string(&m, &WriteOptions::default());
        let back = read(&text).model;
        prop_assert_eq!(back.var(VarId(0)).obj.to_bits(), if v == 0.0 { 0.0f64.to_bits() } else { v.to_bits() });
        prop_assert_eq!(back.row(RowId(0)).coefs[0].to_bits(), v.to_bits());
    }

    #[test]
    fn ranged_rows_are_exact(a in side_value(), b in side_value()) {
        prop_assume!(a != b);
        let (l, u) = (a.min(b), a.max(b));
        prop_assume!(u - l < 1e30);
        let mut m = Model::new("r");
        let x = m.add_continuous("x", 0.0, INF, 1.0);
        m.add_row("r", l, u, [(x, 1.0)]);
        let (text, _) = to_string(&m, &WriteOptions::default());
        let back = read(&text).model;
        prop_assert_eq!((back.row(RowId(0)).lhs, back.row(RowId(0)).rhs), (l, u), "{}", text);
        // Without our comment (as other readers see it) the sides are off by at most an ulp or so.
        let plain: String = text.lines().filter(|l| !l.starts_with(RANGE_COMMENT_PREFIX)).map(|l| format!("{l}\n")).collect();
        let other = read(&plain).model;
        let (l2, u2) = (other.row(RowId(0)).lhs, other.row(RowId(0)).rhs);
        let tol = 4.0 * f64::EPSILON * l.abs().max(u.abs());
        prop_assert!((l2 - l).abs() <= tol && (u2 - u).abs() <= tol, "{} {} vs {} {}", l, u, l2, u2);
    }

    #[test]
    fn never_panics_on_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        let _ = read_str(&text);
    }

    #[test]
    fn never_panics_on_mps_like_text(lines in prop::collection::vec(mps_like_line(), 0..40)) {
        let text = lines.join("\n");
        if let Ok(o) = read_str(&text) {
            let _ = write(&o.model, &mut Vec::new(), &WriteOptions::default());
        }
    }
}

fn mps_like_line() -> impl Strategy<Value = String> {
    let token = prop::sample::select(vec![
        "NAME", "ROWS", "COLUMNS", "RHS", "RANGES", "BOUNDS", "ENDATA", "OBJSENSE", "MAX", "MIN", "OBJNAME", "N", "L",
        "G", "E", "x", "y", "z", "obj", "c", "d", "'MARKER'", "'INTORG'", "'INTEND'", "UP", "LO", "FX", "FR", "MI",
        "PL", "BV", "LI", "UI", "SC", "SI", "1", "-1", "0", "2.5", "1e30", "-1e30", "inf", "-inf", "nan", "1e400",
        "1D3", "$", "*", "é", "RHS", "BND", "QMATRIX", "-0",
    ]);
    let indent = prop::sample::select(vec!["", " ", "    ", "\t", "  "]);
    let sep = prop::sample::select(vec![" ", "  ", "\t", "      "]);
    (indent, prop::collection::vec((token, sep), 0..7), prop::option::of("[ -~]{0,70}")).prop_map(
        |(indent, toks, raw)| match raw {
            Some(raw) if toks.is_empty() => raw,
            _ => {
                let mut s = indent.to_string();
                for (t, sep) in toks {
                    s.push_str(t);
                    s.push_str(sep);
                }
                s
            }
        },
    )
}

/// Structured MPS-like files: valid skeleton with random data lines.
fn mps_skeleton() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(mps_like_line(), 0..5),
        prop::collection::vec(mps_like_line(), 0..8),
        prop::collection::vec(mps_like_line(), 0..5),
        prop::collection::vec(mps_like_line(), 0..5),
    )
        .prop_map(|(rows, cols, rhs, bounds)| {
            format!(
                "NAME t\nROWS\n N obj\n L c\n G d\n{}\nCOLUMNS\n    x obj 1 c 1\n    y d 2\n{}\nRHS\n{}\nBOUNDS\n{}\nENDATA\n",
                rows.join("\n"),
                cols.join("\n"),
                rhs.join("\n"),
                bounds.join("\n")
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    #[test]
    fn never_panics_on_skeletons(text in mps_skeleton()) {
        if let Ok(o) = read_str(&text) {
            let _ = write(&o.model, &mut Vec::new(), &WriteOptions::default());
        }
        // Any prefix of the text as well.
        for cut in [text.len() / 3, text.len() / 2] {
            if text.is_char_boundary(cut) {
                let _ = read_str(&text[..cut]);
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Throughput (run with `cargo test --release --lib io::mps -- --ignored --nocapture`).

/// A model with about `nnz` nonzeros, 10 per column.
fn big_model(nnz: usize) -> Model {
    let ncols = nnz / 10;
    let nrows = ncols / 2;
    let mut m = Model::new("big");
    m.reserve(ncols, nrows, nnz);
    let mut vars = Vec::with_capacity(ncols);
    for j in 0..ncols {
        let kind = match j % 3 {
            0 => VarKind::Continuous,
            1 => VarKind::Integer,
            _ => VarKind::Binary,
        };
        let (lb, ub) = if kind == VarKind::Binary { (0.0, 1.0) } else { (0.0, 100.0 + j as f64) };
        vars.push(m.add_var(format!("x{j}"), kind, lb, ub, (j % 17) as f64 * 0.37 - 2.0));
    }
    let mut seed = 12345u64;
    let mut next = move || {
        seed = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (seed >> 33) as usize
    };
    for r in 0..nrows {
        let mut cols: Vec<usize> = (0..20).map(|_| next() % ncols).collect();
        cols.sort_unstable();
        cols.dedup();
        let terms: Vec<(VarId, f64)> = cols.iter().map(|&j| (vars[j], (next() % 1000) as f64 / 7.0 - 50.0)).collect();
        match r % 3 {
            0 => m.add_le(format!("c{r}"), terms, (r % 100) as f64),
            1 => m.add_ge(format!("c{r}"), terms, -((r % 50) as f64)),
            _ => m.add_row(format!("c{r}"), -1.5, 2.5 + r as f64, terms),
        };
    }
    m
}

#[test]
#[ignore]
fn throughput() {
    let m = big_model(1_000_000);
    for align in [true, false] {
        let mut buf = Vec::with_capacity(64 << 20);
        let t = std::time::Instant::now();
        write(&m, &mut buf, &WriteOptions { align, ..Default::default() }).unwrap();
        let tw = t.elapsed().as_secs_f64();
        let mb = buf.len() as f64 / 1e6;
        let text = String::from_utf8(buf).unwrap();
        let t = std::time::Instant::now();
        let back = read_str(&text).unwrap().model;
        let tr = t.elapsed().as_secs_f64();
        assert_eq!(back, m);
        println!(
            "MPS (align: {align}): {} nonzeros, {:.1} MB; write {:.3} s = {:.0} MB/s; read {:.3} s = {:.0} MB/s",
            m.num_nonzeros(),
            mb,
            tw,
            mb / tw,
            tr,
            mb / tr
        );
    }
}
