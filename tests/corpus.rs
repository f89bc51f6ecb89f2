//! Every file of `fixtures/highs-check/` (HiGHS's test instances) is read, solved with every backend and matched
//! against its `EXPECTED.csv` row; the malformed ones must give clear errors that name the line.

use crate::conformance::assert_checked;
use netspec::io::read_model_file;
use netspec::milp::objectives_agree;
use netspec::solvers::{SolveOptions, SolverKind, Termination};
use std::path::PathBuf;

pub fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("fixtures/highs-check")
}

/// One row of EXPECTED.csv.
pub struct Expected {
    pub file: String,
    pub kind: String,
    pub status: String,
    pub objective: Option<f64>,
}

pub fn expected() -> Vec<Expected> {
    let text = std::fs::read_to_string(corpus_dir().join("EXPECTED.csv")).expect("fixtures/highs-check/EXPECTED.csv");
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.splitn(5, ',').collect();
            Expected { file: f[0].into(), kind: f[1].into(), status: f[2].into(), objective: f[3].parse().ok() }
        })
        .collect()
}

/// microlp is a simple pure-Rust branch and bound: it gets the files it solves in well under a
/// second in a release build. The others are MIPLIB instances that take it minutes or more.
pub const MICROLP_FILES: &[&str] = &[
    "adlittle.mps",
    "afiro.mps",
    "avgas.mps",
    "bgetam.mps",
    "blending.mps",
    "comment.mps",
    "ex72a.mps",
    "flugpl.mps",
    "infeasible-mip0.mps",
    "infeasible-mip1.mps",
    "silly-names.mps",
    "small_mip.mps",
    "1448.lp",
    "fixed-binary.lp",
    "issue-2388.lp",
    "issue-2585.lp",
    "no-newline-eof.lp",
];

fn run_backend(kind: SolverKind) {
    let mut solved = 0;
    for e in expected().iter().filter(|e| e.kind != "bad") {
        if kind == SolverKind::Microlp && !MICROLP_FILES.contains(&e.file.as_str()) {
            continue;
        }
        let path = corpus_dir().join(&e.file);
        let read = read_model_file(&path).unwrap_or_else(|err| panic!("{err}"));
        let o = SolveOptions { time_limit: Some(60.0), ..Default::default() };
        let r = kind.instance().unwrap().solve(&read.model, &o).unwrap_or_else(|err| panic!("{}: {err}", e.file));
        match e.status.as_str() {
            "optimal" => {
                assert_eq!(r.termination, Termination::Optimal, "{kind} on {}", e.file);
                assert_checked(&read.model, &r);
                let (got, want) = (r.objective.unwrap(), e.objective.unwrap());
                assert!(objectives_agree(got, want, 1e-6), "{kind} on {}: objective {got}, expected {want}", e.file);
            }
            "infeasible" => assert!(
                matches!(r.termination, Termination::Infeasible | Termination::InfeasibleOrUnbounded),
                "{kind} on {}: {}",
                e.file,
                r.termination
            ),
            s => panic!("unknown expected status {s}"),
        }
        solved += 1;
    }
    assert!(solved >= MICROLP_FILES.len(), "{kind}: only {solved} corpus files solved");
}

#[cfg(feature = "highs")]
#[test]
fn corpus_highs() {
    run_backend(SolverKind::Highs);
}

#[cfg(feature = "cbc")]
#[test]
fn corpus_cbc() {
    run_backend(SolverKind::Cbc);
}

#[cfg(feature = "scip")]
#[test]
fn corpus_scip() {
    run_backend(SolverKind::Scip);
}

#[cfg(feature = "microlp")]
#[test]
fn corpus_microlp() {
    run_backend(SolverKind::Microlp);
}

#[test]
fn bad_files_give_clear_errors() {
    for e in expected().iter().filter(|e| e.kind == "bad") {
        let path = corpus_dir().join(&e.file);
        match read_model_file(&path) {
            Err(err) => {
                let msg = format!("{err}");
                assert!(msg.contains(&e.file), "{}: error does not name the file: {msg}", e.file);
                assert!(msg.contains("line "), "{}: error does not name the line: {msg}", e.file);
            }
            Ok(read) => {
                assert_eq!(e.status, "error-or-warnings", "{} must be rejected", e.file);
                assert!(!read.warnings.is_empty(), "{}: read without warnings", e.file);
            }
        }
    }
}
