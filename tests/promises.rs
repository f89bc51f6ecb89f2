//! Promises kept under real conditions: one time limit bounds a whole command (the explanation of
//! an infeasible spec included), and a process killed at any moment leaves the last complete
//! design on disk (`solve`'s output folder, a server's run shown `interrupted`). Timings are
//! asserted with generous bounds; kill moments are seeded.

use serde_json::{json, Value};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Seconds in `[lo, hi)` from a seeded xorshift: the kill moments, the same on every run.
struct Moments(u64);

impl Moments {
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        lo + (hi - lo) * (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `netspec solve --time-limit 2` on an infeasible spec whose explanation alone runs about 27 s
/// on its own budget: the explanation gets what is left of the 2 s.
#[test]
fn solve_time_limit_bounds_the_explanation() {
    let dir = tempfile::tempdir().unwrap();
    let spec = root().join("fixtures/specs/infeasible_16x16_hard.toml");
    let t = Instant::now();
    let o = netspec().arg("solve").arg(&spec).args(["--time-limit", "2", "--out"]).arg(dir.path()).output().unwrap();
    let secs = t.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    assert!(secs < 10.0, "{secs:.1} s for a 2 s limit:\n{stdout}");
    assert!(!stdout.contains("may run past"), "{stdout}");
    let result: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("result.json")).unwrap()).unwrap();
    assert_eq!(result["status"], "finished");
    assert_eq!(result["solve"]["termination"]["reason"], "infeasible", "{}", result["solve"]["termination"]);
    assert!(
        result["infeasibility"]["conflicts"].as_array().is_some_and(|c| !c.is_empty()),
        "{}",
        result["infeasibility"]
    );
    // Its own budget is said up front, before any work.
    let o = netspec()
        .arg("solve")
        .arg(&spec)
        .args(["--time-limit", "2", "--explain-time", "1", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    let first = stdout.lines().next().unwrap_or_default();
    assert!(first.contains("--explain-time 1 s") && first.contains("past the 2 s time limit"), "{stdout}");
}

/// Checks what a killed run left in `dir`: every file there is complete, and a `result.json`
/// (running or finished) holds a design the validator accepts. Returns whether it held one.
fn check_left_on_disk(dir: &Path, spec: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(dir.join("result.json")) else { return false };
    let result: Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("result.json is not complete: {e}"));
    assert_eq!(result["schema"], "netspec.design");
    let status = result["status"].as_str().unwrap();
    assert!(matches!(status, "running" | "finished"), "{status}");
    let net: netspec::design::Network = serde_json::from_value(result["network"].clone()).unwrap();
    let p = netspec::run::load(spec, None, netspec::spec::DEFAULT_MAX_CELLS).unwrap();
    let f = netspec::pipeline::build(&p);
    let violations = netspec::design::validate(&p, &net, f.path_sets.as_ref());
    assert!(violations.is_empty(), "the design left on disk ({status}) is invalid: {violations:?}");
    let png = std::fs::read(dir.join("network.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG") && png.ends_with(b"IEND\xaeB`\x82"), "network.png is cut short");
    let svg = std::fs::read_to_string(dir.join("network.svg")).unwrap();
    assert!(svg.trim_end().ends_with("</svg>"), "network.svg is cut short");
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        assert!(!name.ends_with(".tmp") || name.starts_with('.'), "{name}");
    }
    true
}

/// `netspec solve` killed with SIGKILL at seeded moments: what is on disk is always complete and
/// valid, and once the first design has been found, there is one.
#[test]
fn a_killed_solve_leaves_its_last_design() {
    let spec = root().join("models/fig2e.toml");
    let mut moments = Moments(0x5eed_2026);
    let mut found = 0;
    for i in 0..5 {
        let dir = tempfile::tempdir().unwrap();
        // The last moment is late enough for the heuristic's design (found in its first second).
        let at = if i == 4 { 4.0 } else { moments.next(0.2, 4.0) };
        let mut child = netspec()
            .arg("solve")
            .arg(&spec)
            .args(["--time-limit", "60", "--threads", "1", "--out"])
            .arg(dir.path())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_secs_f64(at));
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
        if check_left_on_disk(dir.path(), &spec) {
            found += 1;
        } else {
            assert!(at < 3.0, "killed at {at:.2} s, no design on disk");
        }
    }
    assert!(found >= 1);
}

/// `netspec serve` killed with SIGKILL while a solve runs: after a restart the run is
/// `interrupted`, with the last design it wrote, validated.
#[test]
fn a_killed_server_shows_the_run_interrupted() {
    let root_dir = tempfile::tempdir().unwrap();
    let mut child = netspec()
        .arg("serve")
        .arg("--root")
        .arg(root_dir.path())
        .args(["--port", "0", "--threads", "2"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut line = String::new();
    std::io::BufRead::read_line(&mut std::io::BufReader::new(child.stdout.take().unwrap()), &mut line).unwrap();
    let base = line.split_whitespace().find(|w| w.starts_with("http://")).unwrap().trim_end_matches('/').to_string();
    let rt = crate::serve::runtime();
    let id = rt.block_on(async {
        let spec: Value = {
            let s: netspec::spec::Spec = toml::from_str(&crate::serve::long_spec()).unwrap();
            serde_json::to_value(s).unwrap()
        };
        let c = reqwest::Client::new();
        let r: Value = c
            .post(format!("{base}/api/solve"))
            .header("content-type", "application/json")
            .body(json!({ "spec": spec }).to_string())
            .send()
            .await
            .unwrap()
            .json()
            .await
            .unwrap();
        let id = r["id"].as_str().unwrap().to_string();
        crate::serve::follow(&base, &id, |e| e["kind"] != "design").await;
        id
    });
    // The page draws a design as the solver hands it over; the run's folder has it once written.
    let run_dir = root_dir.path().join("runs").join(&id);
    let t = Instant::now();
    while netspec::run::left_design(&run_dir).is_none() {
        assert!(t.elapsed() < Duration::from_secs(60), "no design written into {}", run_dir.display());
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_secs_f64(Moments(7).next(0.0, 1.0)));
    child.kill().unwrap(); // SIGKILL
    child.wait().unwrap();
    let rec: Value = serde_json::from_str(&std::fs::read_to_string(run_dir.join("run.json")).unwrap()).unwrap();
    assert_eq!(rec["state"], "running", "the record as the killed server left it");
    let srv = crate::serve::server(root_dir.path(), 1);
    let base = format!("http://{}", srv.addr());
    rt.block_on(async {
        let runs: Value = reqwest::get(format!("{base}/api/runs")).await.unwrap().json().await.unwrap();
        let run = runs["runs"].as_array().unwrap().iter().find(|r| r["id"] == id.as_str()).unwrap().clone();
        assert_eq!(run["state"], "interrupted", "{run}");
        let events = crate::serve::follow(&base, &id, |_| true).await;
        let summary = &events[0]["summary"];
        assert_eq!(summary["verdict"], "valid", "{summary}");
        assert_eq!(summary["interrupted"], true);
        assert!(summary["objective"].as_f64().is_some(), "{summary}");
    });
}

/// `netspec city` with a level limit of 1 s and a total limit of 3 s on a city whose levels
/// otherwise run for minutes: every level's work within its limit, the city within its total,
/// levels left when the total runs out skipped, and the city still assembled and written.
#[test]
fn city_time_limits_bound_levels_and_the_city() {
    let dir = tempfile::tempdir().unwrap();
    let t = Instant::now();
    let o = netspec()
        .arg("city")
        .arg(root().join("models/city/fig7a.toml"))
        .args(["--time-limit", "1", "--total-time-limit", "3", "--fresh", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    let secs = t.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(secs < 10.0, "{secs:.1} s for a 3 s total limit:\n{stdout}");
    assert!(dir.path().join("city.json").exists(), "{stdout}{}", String::from_utf8_lossy(&o.stderr));
    let city: Value = serde_json::from_str(&std::fs::read_to_string(dir.path().join("city.json")).unwrap()).unwrap();
    let levels: Vec<&Value> =
        city["regions"].as_array().unwrap().iter().flat_map(|r| r["levels"].as_array().unwrap()).collect();
    assert!(!levels.is_empty());
    for l in levels {
        if let Some(w) = l["wall_time"].as_f64() {
            assert!(w < 4.0, "a level with a 1 s limit took {w:.1} s: {l}");
        }
    }
}

/// `netspec traffic --time-limit 2` on a demand that keeps SUMO busy for minutes: the tool is
/// stopped at the limit and the command fails saying so.
#[test]
fn traffic_time_limit_stops_sumo() {
    crate::setup_part("sumo");
    let dir = tempfile::tempdir().unwrap();
    let design = dir.path().join("tiny");
    let o = netspec()
        .arg("solve")
        .arg(root().join("fixtures/specs/tiny_network.toml"))
        .arg("--out")
        .arg(&design)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = Instant::now();
    let o = netspec()
        .arg("traffic")
        .arg(&design)
        .args(["--duration", "100000", "--through-rate", "5000", "--local-rate", "5000", "--time-limit", "2", "--out"])
        .arg(dir.path().join("traffic"))
        .output()
        .unwrap();
    let secs = t.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(stderr.contains("the time limit ran out"), "{stderr}");
    assert!(secs < 10.0, "{secs:.1} s for a 2 s limit: {stderr}");
}
