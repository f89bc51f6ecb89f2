//! Game levels on the graphs designers draw (paths, cycles, ladders, grid graphs,
//! caterpillars, binary trees): laid out by the annealer and validated, the same bytes for the
//! same seed, `--method both` side by side, the time limit over the whole command.

use netspec::levels::anneal::{self, AnnealOptions};
use netspec::levels::cspace::CSpaces;
use netspec::levels::generate::Generated;
use netspec::levels::validate::validate;
use netspec::levels::{self, LevelRequest, Method, Status};
use netspec::solvers::SolverKind;
use std::process::Command;

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

fn request(spec: &std::path::Path, method: Method, time_limit: f64) -> LevelRequest {
    LevelRequest {
        spec: spec.to_path_buf(),
        method,
        count: 1,
        solver: SolverKind::default_kind().expect("a backend"),
        time_limit,
        threads: Some(1),
        out: None,
        explain: true,
        seed: 1,
        export: None,
        seeds: 1,
    }
}

#[test]
fn every_family_is_laid_out_by_the_annealer_and_validated() {
    // Small members of each family; the bench and docs/levels.md take the large ones.
    for family in ["path:60", "cycle:20", "ladder:10", "grid:5x5", "caterpillar:20x2", "tree:15", "star:4"] {
        let level = Generated::parse(family).unwrap().level(0.5).unwrap();
        let cs = CSpaces::new(&level);
        for seed in [1, 2] {
            let o = AnnealOptions { seed, count: 2, time_limit: 60.0, ..AnnealOptions::default() };
            let r = anneal::anneal(&level, &cs, &o);
            assert_eq!(r.layouts.len(), 2, "{family} seed {seed}: {r:?}");
            assert_eq!(r.stopped, "count", "{family}");
            for l in &r.layouts {
                let v = validate(&level, l);
                assert!(v.is_valid(), "{family}: {:?}", v.problems());
            }
        }
    }
}

#[test]
fn the_annealer_restarts_until_its_time_limit_instead_of_giving_up() {
    // Five squares around one at door width 0.6: no layout exists; the annealer says so only
    // by running out of time, with restarts made.
    let level = Generated::parse("star:5").unwrap().level(0.6).unwrap();
    let o =
        AnnealOptions { time_limit: 1.0, cycles: 5, trials: 100, partial_variations: 2, ..AnnealOptions::default() };
    let r = anneal::anneal(&level, &CSpaces::new(&level), &o);
    assert!(r.layouts.is_empty());
    assert_eq!(r.stopped, "time limit");
    assert!(r.restarts >= 1, "{r:?}");
}

#[test]
fn same_seed_same_level_json_another_seed_another_layout() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("grid.toml");
    let run = netspec().args(["level-gen", "grid:4x4", "--out"]).arg(&spec).output().unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let layout = |seed: &str, name: &str| {
        let out = dir.path().join(name);
        let run = netspec()
            .arg("level")
            .arg(&spec)
            .args(["--method", "anneal", "--count", "3", "--seed", seed, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
        std::fs::read(out.join("level.json")).unwrap()
    };
    let (a, b, c) = (layout("5", "a"), layout("5", "b"), layout("6", "c"));
    assert_eq!(a, b, "same seed, same bytes");
    assert_ne!(a, c, "another seed, another layout");
    let json: serde_json::Value = serde_json::from_slice(&a).unwrap();
    assert_eq!(json["layouts"].as_array().unwrap().len(), 3);
}

#[test]
fn both_methods_side_by_side_stop_at_the_first_answer() {
    let dir = tempfile::tempdir().unwrap();
    // Feasible: a ladder the annealer lays out at once.
    let spec = dir.path().join("ladder.toml");
    std::fs::write(&spec, Generated::parse("ladder:6").unwrap().to_toml(0.5)).unwrap();
    let o = levels::run(&request(&spec, Method::Both, 60.0)).unwrap();
    assert_eq!(o.status, Status::Feasible);
    assert!(validate(&Generated::parse("ladder:6").unwrap().level(0.5).unwrap(), &o.layouts[0]).is_valid());
    // Infeasible: only the exact side can answer; it stops the annealer.
    let spec = dir.path().join("star.toml");
    std::fs::write(&spec, Generated::parse("star:5").unwrap().to_toml(0.6)).unwrap();
    let o = levels::run(&request(&spec, Method::Both, 60.0)).unwrap();
    assert_eq!(o.status, Status::Infeasible);
    assert_eq!(o.anneal.as_ref().unwrap().stopped, "stopped", "{:?}", o.anneal);
}

#[test]
fn a_level_too_large_for_its_time_limit_is_refused_up_front_with_the_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("path.toml");
    std::fs::write(&spec, Generated::parse("path:15000").unwrap().to_toml(0.5)).unwrap();
    let t = std::time::Instant::now();
    let e = levels::run(&request(&spec, Method::Anneal, 2.0)).unwrap_err().to_string();
    assert!(e.contains("--time-limit") && e.contains("15000 nodes take about"), "{e}");
    assert!(t.elapsed().as_secs_f64() < 2.0, "refused before any work");
}

#[test]
fn level_gen_refuses_bad_families_naming_them() {
    let run = netspec().args(["level-gen", "grid:10"]).output().unwrap();
    assert_eq!(run.status.code(), Some(1));
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(err.contains("family") && err.contains("grid:10"), "{err}");
}
