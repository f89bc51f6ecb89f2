//! `--executor slurm` against a real single-node Slurm cluster on this machine, installed and
//! started by `scripts/slurm-local.sh start` from the first test that needs it. The tests that
//! submit jobs hold one lock: they share the cluster's two CPUs and read its queue.

use netspec::compare::RunRecord;
use std::io::BufRead;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::{Duration, Instant};

/// The cluster's `slurm.conf` (started once per test binary), and the lock of the tests that use it.
fn cluster() -> (MutexGuard<'static, ()>, PathBuf) {
    static CONF: OnceLock<Result<PathBuf, String>> = OnceLock::new();
    static LOCK: Mutex<()> = Mutex::new(());
    let conf = CONF.get_or_init(|| {
        let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/slurm-local.sh");
        let o = Command::new(script).arg("start").output().map_err(|e| e.to_string())?;
        let stdout = String::from_utf8_lossy(&o.stdout);
        match stdout.lines().rev().find_map(|l| l.strip_prefix("SLURM_CONF=")) {
            Some(p) if o.status.success() => Ok(PathBuf::from(p)),
            _ => Err(format!("scripts/slurm-local.sh start failed: {stdout}{}", String::from_utf8_lossy(&o.stderr))),
        }
    });
    let conf = conf.clone().unwrap_or_else(|e| panic!("{e}"));
    (LOCK.lock().unwrap_or_else(|e| e.into_inner()), conf)
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn netspec(conf: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_netspec"));
    c.env("SLURM_CONF", conf).current_dir(root());
    c
}

/// Writes a manifest of `rows` (name, spec path relative to the repository) into `dir`.
fn manifest(dir: &Path, rows: &[(&str, &str)]) -> PathBuf {
    let mut text = String::new();
    for (name, spec) in rows {
        text.push_str(&format!("[[row]]\nname = \"{name}\"\nspec = \"{}\"\n\n", root().join(spec).display()));
    }
    let path = dir.join("manifest.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn records(out: &Path) -> Vec<RunRecord> {
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    serde_json::from_value(json["records"].clone()).unwrap()
}

fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}\n{}", String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Proven: optimal or infeasible (the rows whose objective must agree).
fn proven(r: &RunRecord) -> bool {
    r.status == "optimal" || r.status == "infeasible"
}

#[test]
fn slurm_array_gives_the_local_answers() {
    let (_lock, conf) = cluster();
    let dir = tempfile::tempdir().unwrap();
    let m = manifest(
        dir.path(),
        &[
            ("floorplan", "fixtures/specs/tiny_floorplan.toml"),
            ("network", "fixtures/specs/tiny_network.toml"),
            ("infeasible", "fixtures/specs/infeasible_16x16.toml"),
            ("walled", "fixtures/specs/walled_corner_sink/spec.json"),
        ],
    );
    let run = |executor: &str| {
        let out = dir.path().join(executor);
        let o = netspec(&conf)
            .args(["compare", "--manifest"])
            .arg(&m)
            .args(["--solvers", "highs,scip", "--threads", "1", "--time-limit", "30", "--grace", "5"])
            .args(["--executor", executor, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        (ok(&o), records(&out), out)
    };
    let (_, local, _) = run("local");
    let (stdout, slurm, out) = run("slurm");
    assert!(stdout.contains("submitted Slurm job array") && stdout.contains("(8 tasks)"), "{stdout}");
    assert_eq!(local.len(), 8);
    assert_eq!(slurm.len(), 8);
    let staged: Vec<_> = std::fs::read_dir(out.join("slurm"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("netspec-"))
        .collect();
    assert_eq!(staged.len(), 1, "the binary is staged once: {staged:?}");
    for (l, s) in local.iter().zip(&slurm) {
        assert_eq!((&l.instance, &l.solver), (&s.instance, &s.solver));
        assert_eq!(l.status, s.status, "{l:?}\n{s:?}");
        assert_eq!(l.settings, s.settings, "the same settings: resume and --merge treat them alike");
        assert!(l.binary_digest.is_none());
        assert_eq!(s.binary_digest.as_deref(), Some(staged[0].trim_start_matches("netspec-")));
        if proven(l) {
            assert_eq!(l.objective.map(|v| (v * 1e6).round()), s.objective.map(|v| (v * 1e6).round()), "{l:?}\n{s:?}");
        }
    }
    assert!(local.iter().filter(|r| proven(r)).count() >= 6, "{local:?}");
    // Resumed through Slurm: nothing is submitted again.
    let again = ok(&netspec(&conf)
        .args(["compare", "--manifest"])
        .arg(&m)
        .args(["--solvers", "highs,scip", "--threads", "1", "--time-limit", "30", "--grace", "5"])
        .args(["--executor", "slurm", "--out"])
        .arg(&out)
        .output()
        .unwrap());
    assert_eq!(again.matches("(resumed)").count(), 8, "{again}");
    assert!(!again.contains("submitted"), "{again}");
}

#[test]
fn a_cancelled_task_is_recorded_and_rerun_alone() {
    let (_lock, conf) = cluster();
    let dir = tempfile::tempdir().unwrap();
    // Task 0 is a solve that runs for its whole limit; task 1 a quick one.
    let m = manifest(dir.path(), &[("long", "models/fig2b.toml"), ("quick", "fixtures/specs/tiny_network.toml")]);
    let out = dir.path().join("out");
    let compare = |conf: &Path| {
        let mut c = netspec(conf);
        c.args(["compare", "--manifest"])
            .arg(&m)
            .args(["--solvers", "highs", "--threads", "1", "--time-limit", "6", "--grace", "5"])
            .args(["--executor", "slurm", "--out"])
            .arg(&out);
        c
    };
    let mut child = compare(&conf).stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let mut lines = std::io::BufReader::new(child.stdout.take().unwrap()).lines();
    let job = lines
        .by_ref()
        .map_while(Result::ok)
        .find_map(|l| l.strip_prefix("submitted Slurm job array ").map(|r| r.split(' ').next().unwrap().to_string()))
        .expect("the array is submitted");
    // Cancel task 0 once it runs.
    let task = format!("{job}_0");
    let t0 = Instant::now();
    loop {
        let o = Command::new("squeue").env("SLURM_CONF", &conf).args(["-h", "-j", &task, "-o", "%T"]).output().unwrap();
        if String::from_utf8_lossy(&o.stdout).trim() == "RUNNING" {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(60), "task {task} never ran");
        std::thread::sleep(Duration::from_millis(100));
    }
    std::thread::sleep(Duration::from_millis(500));
    let o = Command::new("scancel").env("SLURM_CONF", &conf).arg(&task).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rest: Vec<String> = lines.map_while(Result::ok).collect();
    let status = child.wait().unwrap();
    assert!(!status.success(), "a run without a result fails the comparison: {rest:?}");
    let recs = records(&out);
    let long = recs.iter().find(|r| r.instance == "long").unwrap();
    assert_eq!((long.status.as_str(), long.slurm_state.as_deref()), ("cancelled", Some("CANCELLED")), "{long:?}");
    assert!(long.error.as_ref().unwrap().contains(&task), "{long:?}");
    let quick = recs.iter().find(|r| r.instance == "quick").unwrap();
    assert_eq!(quick.status, "optimal");
    // The resume solves exactly the cancelled run again.
    let again = ok(&compare(&conf).output().unwrap());
    assert!(again.contains("(1 tasks)"), "{again}");
    let line = |name: &str| again.lines().find(|l| l.starts_with(name) && l.contains("highs")).unwrap().to_string();
    assert!(line("quick").ends_with("(resumed)"), "{again}");
    assert!(line("long").contains("(solved again: its Slurm task ended CANCELLED)"), "{again}");
    let long = records(&out).into_iter().find(|r| r.instance == "long").unwrap();
    assert!(long.slurm_state.is_none() && long.error.is_none() && long.status != "cancelled", "{long:?}");
}

#[test]
fn missing_slurm_is_a_clear_error_and_writes_nothing() {
    let (_lock, conf) = cluster();
    let dir = tempfile::tempdir().unwrap();
    let spec = root().join("fixtures/specs/tiny_network.toml");
    let fail = |cmd: &mut Command, extra: &[&str]| {
        let out = dir.path().join("out");
        let o = cmd
            .arg("compare")
            .arg(&spec)
            .args(extra)
            .args(["--executor", "slurm", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(!o.status.success());
        assert!(!out.exists(), "nothing written");
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    // A controller that is not running: a configuration naming a port nobody listens on.
    let dead = dir.path().join("dead.conf");
    let host = String::from_utf8(Command::new("hostname").arg("-s").output().unwrap().stdout).unwrap();
    std::fs::write(
        &dead,
        format!(
            "ClusterName=dead\nSlurmctldHost={h}\nSlurmctldPort=6999\nNodeName={h} CPUs=1\nPartitionName=debug Nodes={h} Default=YES\n",
            h = host.trim()
        ),
    )
    .unwrap();
    let e = fail(&mut netspec(&dead), &[]);
    assert!(e.contains("controller does not answer") && e.contains("scripts/slurm-local.sh start"), "{e}");
    // A city too: nothing of it is written.
    let out = dir.path().join("city");
    let o = netspec(&dead)
        .arg("city")
        .arg(root().join("fixtures/city/two-regions.toml"))
        .args(["--executor", "slurm", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && e.contains("controller does not answer"), "{e}");
    assert!(!out.exists(), "nothing written");
    // No sbatch on PATH.
    let empty = tempfile::tempdir().unwrap();
    let e = fail(netspec(&conf).env("PATH", empty.path()), &[]);
    assert!(e.contains("`sbatch` is not installed") && e.contains("slurm module"), "{e}");
    // A partition the cluster does not have.
    let e = fail(&mut netspec(&conf), &["--slurm-partition", "nowhere"]);
    assert!(e.contains("partition `nowhere` does not exist (partitions: debug)"), "{e}");
    // Slurm flags without the Slurm executor.
    let o = netspec(&conf).arg("compare").arg(&spec).args(["--slurm-partition", "debug"]).output().unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("need --executor slurm"));
}

/// A two-region city through Slurm (one job per region's level, each after its predecessor):
/// the same levels, states and objectives as the local run, and the same streets.
#[test]
fn slurm_city_equals_the_local_city() {
    let (_lock, conf) = cluster();
    let dir = tempfile::tempdir().unwrap();
    let city = root().join("fixtures/city/two-regions.toml");
    let run = |executor: &str| {
        let out = dir.path().join(executor);
        ok(&netspec(&conf)
            .arg("city")
            .arg(&city)
            .args(["--threads", "2", "--threads-per-solve", "1", "--time-limit", "60", "--gap", "0"])
            .args(["--executor", executor, "--out"])
            .arg(&out)
            .output()
            .unwrap());
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("city.json")).unwrap()).unwrap();
        let levels: Vec<_> = json["regions"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|r| {
                r["levels"].as_array().unwrap().iter().map(move |l| {
                    let obj = l["objective"].as_f64().map(|v| (v * 1e6).round());
                    (
                        r["name"].clone(),
                        l["level"].clone(),
                        l["state"].clone(),
                        l["termination"].clone(),
                        obj,
                        l["new_edges"].clone(),
                    )
                })
            })
            .collect();
        (levels, std::fs::read_to_string(out.join("streets.geojson")).unwrap(), out)
    };
    let (local, local_streets, _) = run("local");
    let (slurm, slurm_streets, out) = run("slurm");
    assert_eq!(local.len(), 4, "{local:?}");
    assert!(local.iter().all(|l| l.2 == "solved" && l.3 == "optimal"), "{local:?}");
    assert_eq!(local, slurm);
    assert_eq!(local_streets, slurm_streets);
    let logs: Vec<String> = std::fs::read_dir(out.join("slurm/logs"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(logs.len(), 4, "one job per region's level: {logs:?}");
}
