//! The `netspec` binary, run as a user would.

use crate::corpus::corpus_dir;
use std::process::Command;

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

#[test]
fn solve_file_prints_summary_and_json() {
    let dir = tempfile::tempdir().unwrap();
    let json = dir.path().join("r.json");
    let out =
        netspec().arg("solve-file").arg(corpus_dir().join("afiro.mps")).arg("--json").arg(&json).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("status     optimal"), "{stdout}");
    assert!(stdout.contains("check      valid"), "{stdout}");
    let v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["schema"], "netspec.solve");
    assert_eq!(v["schema_version"], 1);
    assert_eq!(v["valid"], true);
    let obj = v["result"]["objective"].as_f64().unwrap();
    assert!((obj - -464.7531429).abs() < 1e-5, "{obj}");
}

#[test]
fn infeasible_is_a_result_not_a_failure() {
    let out = netspec().arg("solve-file").arg(corpus_dir().join("infeasible-mip0.mps")).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}");
    assert!(stdout.contains("status     infeasible"), "{stdout}");
}

#[test]
fn bad_file_names_file_and_line() {
    let out = netspec().arg("solve-file").arg(corpus_dir().join("nan0.mps")).output().unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("nan0.mps") && stderr.contains("line "), "{stderr}");
}

#[test]
fn missing_file_is_a_clear_error() {
    let out = netspec().args(["solve-file", "does-not-exist.mps"]).output().unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("does-not-exist.mps"), "{stderr}");
}

#[test]
fn unknown_solver_is_refused() {
    let out = netspec().args(["solve-file", "x.mps", "--solver", "gurobi"]).output().unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown solver"));
}

#[test]
fn convert_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let lp = dir.path().join("p.lp");
    let mps = dir.path().join("p.mps");
    assert!(netspec().arg("convert").arg(corpus_dir().join("egout.mps")).arg(&lp).status().unwrap().success());
    assert!(netspec().arg("convert").arg(&lp).arg(&mps).status().unwrap().success());
    let a = netspec::io::read_model_file(&corpus_dir().join("egout.mps")).unwrap().model;
    let b = netspec::io::read_model_file(&mps).unwrap().model;
    assert_eq!(a.stats(), b.stats());
}

#[test]
fn solvers_lists_every_compiled_backend() {
    let out = netspec().args(["solvers", "--json"]).output().unwrap();
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let names: Vec<&str> = v.as_array().unwrap().iter().map(|s| s["name"].as_str().unwrap()).collect();
    for k in netspec::solvers::SolverKind::compiled() {
        assert!(names.contains(&k.name()), "{names:?}");
    }
}

/// The searches take `--threads` as the backends do: 0 is refused with the option named, the
/// heuristic runs one search per thread, and the stochastic search says it runs on one.
#[test]
fn searches_honour_or_refuse_threads() {
    let spec = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/specs/tiny_floorplan.toml");
    let dir = tempfile::tempdir().unwrap();
    let run = |solver: &str, threads: &str| {
        netspec()
            .args(["solve", spec, "--solver", solver, "--threads", threads, "--time-limit", "0.2", "--out"])
            .arg(dir.path())
            .output()
            .unwrap()
    };
    let zero = run("heuristic", "0");
    assert!(!zero.status.success());
    let stderr = String::from_utf8_lossy(&zero.stderr);
    assert!(stderr.contains("--threads must be ≥ 1, got 0"), "{stderr}");
    let two = run("heuristic", "2");
    let stdout = String::from_utf8_lossy(&two.stdout);
    assert!(two.status.success() && stdout.contains("2 independent searches, one per thread"), "{stdout}");
    let anneal = run("anneal", "2");
    let stdout = String::from_utf8_lossy(&anneal.stdout);
    assert!(anneal.status.success() && stdout.contains("--threads 2 not honoured"), "{stdout}");
}

#[test]
fn relax_writes_the_lp_point_after_the_cut_rounds() {
    let dir = tempfile::tempdir().unwrap();
    let sol = dir.path().join("lp.sol");
    let spec = concat!(env!("CARGO_MANIFEST_DIR"), "/fixtures/specs/tiny_network.toml");
    let out = netspec()
        .args(["solve", spec, "--relax", "--formulation", "strong", "--threads", "1", "--sol"])
        .arg(&sol)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{stdout}\n{}", String::from_utf8_lossy(&out.stderr));
    // "LP bound   A as written, B after N cut rounds …": the file holds the point of B.
    let line = stdout.lines().find(|l| l.starts_with("LP bound")).expect("an LP bound line");
    let after: f64 = line.split(", ").nth(1).and_then(|s| s.split_whitespace().next()).unwrap().parse().unwrap();
    let vars: usize = stdout
        .lines()
        .find(|l| l.starts_with("model"))
        .and_then(|l| l.split_whitespace().nth(1))
        .unwrap()
        .parse()
        .unwrap();
    let text = std::fs::read_to_string(&sol).unwrap();
    assert!(text.starts_with("# netspec solution: LP relaxation after "), "{text}");
    let objective: f64 = text.lines().find_map(|l| l.strip_prefix("# Objective value = ")).unwrap().parse().unwrap();
    assert!((objective - after).abs() <= 1e-5 * after.abs().max(1.0), "{objective} against {after}");
    let values: Vec<f64> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split_whitespace().nth(1).unwrap().parse().unwrap())
        .collect();
    assert_eq!(values.len(), vars, "one value per variable");
    assert!(values.iter().any(|v| *v > 1e-9), "not the zero point");
}
