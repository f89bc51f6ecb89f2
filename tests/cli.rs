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

// ---------------------------------------------------------------------------------------------
// Bad input, as fuzzing found it: each a clear error (or a result), never a panic, a hang, or a
// file written where the input says.

/// Runs netspec in `dir` and returns (success, stdout, stderr).
fn run_in(dir: &std::path::Path, args: &[&str]) -> (bool, String, String) {
    let o = netspec().current_dir(dir).args(args).output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

const TINY: &str = "[mesh]\ngrid = { width = 3, height = 3 }\n[sinks]\nall_boundary = true\n";

/// A spec's `name` is a label: the output folder comes from the file's name, made safe, whatever
/// the name says (`../../escaped`, an absolute path, `.`).
#[test]
fn a_spec_name_never_chooses_where_files_go() {
    let root = tempfile::tempdir().unwrap();
    let work = root.path().join("a/b");
    std::fs::create_dir_all(&work).unwrap();
    for (i, name) in ["../../escaped", "/tmp/netspec-escaped-abs", "."].iter().enumerate() {
        let file = work.join(format!("s{i}.toml"));
        std::fs::write(&file, format!("name = {name:?}\n{TINY}")).unwrap();
        let (ok, out, err) =
            run_in(&work, &["solve", file.to_str().unwrap(), "--solver", "heuristic", "--time-limit", "1"]);
        assert!(ok, "{name}: {out}{err}");
        assert!(work.join(format!("out/s{i}/result.json")).is_file(), "{name}: {out}");
    }
    assert!(!root.path().join("escaped").exists() && !root.path().join("a/escaped").exists());
    assert!(!std::path::Path::new("/tmp/netspec-escaped-abs").exists());
}

/// A coefficient SCIP cannot load: an error naming the row, the column and the backend, no
/// panic; the same file on every backend is refused or solved, never a crash.
#[test]
fn huge_coefficients_are_refused_naming_the_row_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.mps");
    std::fs::write(
        &big,
        "NAME          BIG\nROWS\n N  COST\n L  R1\nCOLUMNS\n    X         COST      -1.0   R1   1e20\nRHS\n    RHS       R1        1.0\nBOUNDS\n UP BND       X         10\nENDATA\n",
    )
    .unwrap();
    for kind in
        netspec::solvers::SolverKind::compiled().into_iter().filter(|k| *k != netspec::solvers::SolverKind::GoodLp)
    {
        let (ok, out, err) = run_in(dir.path(), &["solve-file", "big.mps", "--solver", kind.name()]);
        assert!(!ok && !err.contains("panicked"), "{kind}: {out}{err}");
        assert!(err.contains("row `R1`, column `X`") && err.contains(kind.name()), "{kind}: {err}");
    }
}

/// Sizes are checked before any work, with the estimate in the message; a thread count past
/// the cap is refused.
#[test]
fn runaway_sizes_and_thread_counts_are_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("huge.toml"),
        "name = \"huge\"\n[mesh]\nclipped = { outer = [[0, 0], [4, 0], [4, 4], [0, 4]], spacing = 0.001 }\n[sinks]\nall_boundary = true\n",
    )
    .unwrap();
    let t0 = std::time::Instant::now();
    let (ok, _, err) = run_in(dir.path(), &["solve", "huge.toml", "--time-limit", "2"]);
    assert!(
        !ok && err.contains("mesh.clipped.spacing") && err.contains("16000000 cells") && err.contains("--max-cells"),
        "{err}"
    );
    assert!(t0.elapsed().as_secs() < 30, "refused before building anything");
    std::fs::write(dir.path().join("t.toml"), format!("name = \"t\"\n{TINY}")).unwrap();
    let (ok, _, err) = run_in(dir.path(), &["solve", "t.toml", "--threads", "100000"]);
    assert!(!ok && err.contains("--threads must be at most 256, got 100000"), "{err}");
    let (ok, _, err) =
        run_in(dir.path(), &["solve-file", corpus_dir().join("afiro.mps").to_str().unwrap(), "--threads", "100000"]);
    assert!(!ok && err.contains("--threads must be at most 256"), "{err}");
}

/// Values are checked where they are read, naming the field: control characters in text, NaN
/// coordinates, negative gaps whatever the method, options a backend cannot honour named where
/// they were set, a log file in a missing folder, text that is not UTF-8 (the line named).
#[test]
fn bad_values_name_their_field_or_line() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &[&str], &str)] = &[
        ("nul.toml", "name = \"a\\u0000b\"\n", &[], "field `name`: contains the control character U+0000"),
        ("desc.toml", "name = \"d\"\ndescription = \"x\\u0007\"\n", &[], "field `description`"),
        (
            "nan.toml",
            "name = \"n\"\n[user]\nobstacle_polygons = [[[0, 0], [1, nan], [1, 1]]]\n",
            &[],
            "field `user.obstacle_polygons[0][1]`: coordinates must be finite",
        ),
        (
            "gap.toml",
            "name = \"g\"\n[solver]\nabs_gap = -1\n",
            &["--solver", "heuristic"],
            "solver.abs_gap must be a finite number ≥ 0",
        ),
        (
            "seed.toml",
            "name = \"s\"\n[solver]\nseed = 3\n",
            &["--solver", "microlp"],
            "solver.seed: microlp does not support it",
        ),
        (
            "log.toml",
            "name = \"l\"\n",
            &["--log-file", "no/such/folder/x.log"],
            "the folder no/such/folder does not exist",
        ),
    ];
    for (file, head, args, says) in cases {
        // The sections after `name`: keep the tiny mesh unless the case gives its own.
        let body = if head.contains("[user]") || head.contains("[solver]") {
            let (top, rest) = head.split_once('\n').unwrap();
            format!("{top}\n{TINY}{rest}")
        } else {
            format!("{head}{TINY}")
        };
        std::fs::write(dir.path().join(file), body).unwrap();
        let mut all = vec!["solve", file];
        all.extend_from_slice(args);
        let (ok, out, err) = run_in(dir.path(), &all);
        assert!(!ok && err.contains(says), "{file}: {out}{err}");
    }
    std::fs::write(dir.path().join("latin1.toml"), b"name = \"t\"\n# caf\xe9\n[mesh]\n").unwrap();
    let (ok, _, err) = run_in(dir.path(), &["solve", "latin1.toml"]);
    assert!(!ok && err.contains("line 2, column 6: not valid UTF-8"), "{err}");
    std::fs::write(dir.path().join("bad.mps"), b"NAME x\nROWS\n N  c\xff\nENDATA\n").unwrap();
    let (ok, _, err) = run_in(dir.path(), &["solve-file", "bad.mps"]);
    assert!(!ok && err.contains("line 3, column 6: not valid UTF-8"), "{err}");
}

/// A city whose level meshes would be far too big is refused before any work.
#[test]
fn a_runaway_city_is_refused_up_front() {
    let dir = tempfile::tempdir().unwrap();
    let spec = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/city/two-regions.toml"),
    )
    .unwrap();
    assert!(spec.contains("mesh = { spacing = 1 }"));
    let spec = spec.replace("mesh = { spacing = 1 }", "mesh = { spacing = 0.01 }");
    std::fs::write(dir.path().join("c.toml"), spec).unwrap();
    let t0 = std::time::Instant::now();
    let (ok, _, err) = run_in(dir.path(), &["city", "c.toml", "--time-limit", "1"]);
    assert!(!ok && err.contains("mesh.spacing") && err.contains("--max-cells"), "{err}");
    assert!(t0.elapsed().as_secs() < 30);
}
