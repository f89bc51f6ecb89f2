//! `netspec compare` on a tiny manifest: two small instances × every compiled backend.

use netspec::compare::{
    bar_chart_svg, instance_ids, paper_seconds, shifted_geometric_mean, summarize, Manifest, ManifestRow, PaperRow,
    RunRecord,
};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The compare tests' two tiny instances (fixtures/specs).
fn fixture(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/specs").join(name)).unwrap()
}

#[test]
fn compare_runs_tables_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.toml"), dir.path().join("b.toml"));
    std::fs::write(&a, fixture("tiny_floorplan.toml")).unwrap();
    std::fs::write(&b, fixture("tiny_network.toml")).unwrap();
    let out = dir.path().join("out");
    let run = || {
        let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
            .arg("compare")
            .args([&a, &b])
            .args(["--time-limit", "20", "--grace", "5", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap()
    };
    let first = run();
    let backends: Vec<&str> = netspec::solvers::SolverKind::compiled()
        .into_iter()
        .filter(|k| *k != netspec::solvers::SolverKind::GoodLp)
        .map(|k| k.name())
        .collect();
    assert!(!first.contains("(resumed)"), "{first}");
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    // Header + separator + two instances, then the summary with a row per backend.
    let table: Vec<&str> = md.lines().filter(|l| l.starts_with("| ")).collect();
    assert!(
        table[0].contains("| instance | edges (paper) | vars (paper) | paper time |")
            && backends.iter().all(|b| table[0].contains(b)),
        "{md}"
    );
    assert!(table.iter().any(|l| l.starts_with("| a |") && l.ends_with("| 3.0000 |")), "{md}");
    assert!(table.iter().any(|l| l.starts_with("| b |")), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let records: Vec<RunRecord> = serde_json::from_value(json["records"].clone()).unwrap();
    assert_eq!(records.len(), 2 * backends.len());
    for r in &records {
        assert!(r.valid && r.status == "optimal" && !r.killed, "{r:?}");
        assert_eq!(r.edges, Some(40));
    }
    let profile = std::fs::read_to_string(out.join("profile.svg")).unwrap();
    assert_eq!(profile.matches(r#"class="profile""#).count(), backends.len(), "one curve per backend");
    // Everything solved: every curve ends at 100 % (y = top of the plot, 30).
    for line in profile.lines().filter(|l| l.contains(r#"class="profile""#)) {
        let last = line.split("points=\"").nth(1).unwrap().split('"').next().unwrap().split(' ').next_back().unwrap();
        assert!(last.ends_with(",30.0"), "{line}");
    }
    // The bar chart: one group per instance, one bar per (instance, backend), all solved.
    let bars = std::fs::read_to_string(out.join("bars.svg")).unwrap();
    assert!(bars.starts_with("<svg") && bars.trim_end().ends_with("</svg>"), "{bars}");
    assert_eq!(bars.matches("<svg").count(), 1);
    assert_eq!(bars.matches(r#"<g class="instance""#).count(), 2, "{bars}");
    assert_eq!(bars.matches("<g").count(), bars.matches("</g>").count(), "{bars}");
    for i in ["a", "b"] {
        assert_eq!(bars.matches(&format!(r#"<g class="instance" data-instance="{i}">"#)).count(), 1, "{bars}");
        for b in &backends {
            let bar = format!(
                r#"<rect class="bar" data-instance="{i}" data-solver="{b}" data-status="optimal" data-solved="true""#
            );
            assert_eq!(bars.matches(&bar).count(), 1, "{i}/{b}: {bars}");
        }
    }
    assert_eq!(bars.matches(r#"class="bar""#).count(), 2 * backends.len());
    assert_eq!(bars.matches(r#"class="limit""#).count(), 1);
    assert!(!bars.contains(r#"class="label""#) && !bars.contains(r#"class="paper""#), "{bars}");
    // The legend lists only what the chart uses: everything solved, no paper times.
    assert!(
        bars.contains(">time limit</text>") && !bars.contains("not solved") && !bars.contains(">failed</text>"),
        "{bars}"
    );
    assert!(!bars.contains("killed at limit") && !bars.contains("paper (Gurobi"), "{bars}");
    assert!(md.contains("`bars.svg`"), "{md}");
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + records.len());
    assert!(csv.lines().skip(1).all(|l| l.ends_with(",true,false,")), "{csv}");
    // Rerun: nothing is solved again.
    let stamp = std::fs::metadata(out.join("runs/a__highs__default/run.json")).unwrap().modified().unwrap();
    let second = run();
    assert_eq!(second.matches("(resumed)").count(), records.len(), "{second}");
    assert_eq!(std::fs::metadata(out.join("runs/a__highs__default/run.json")).unwrap().modified().unwrap(), stamp);
}

#[test]
fn shifted_geometric_mean_by_hand() {
    // (11 · 20 · 110)^(1/3) − 10 = 24200^(1/3) − 10.
    let want = 24200f64.powf(1.0 / 3.0) - 10.0;
    assert!((shifted_geometric_mean(&[1.0, 10.0, 100.0], 10.0) - want).abs() < 1e-9);
    assert!((want - 18.9249).abs() < 1e-4);
}

fn record(instance: &str, solver: &str, status: &str, t: f64) -> RunRecord {
    RunRecord {
        instance: instance.into(),
        solver: solver.into(),
        seed: None,
        edges: None,
        vars: None,
        rows: None,
        nonzeros: None,
        status: status.into(),
        objective: None,
        dual_bound: None,
        gap: None,
        nodes: None,
        solver_time: Some(t),
        wall_time: t + 0.5,
        valid: status == "optimal",
        killed: false,
        solver_version: None,
        exit_code: Some(0),
        time_limit: None,
        error: None,
        settings: None,
        binary_digest: None,
        slurm_state: None,
    }
}

#[test]
fn bar_chart_marks_unsolved_killed_failed_and_paper_times() {
    let row = |name: &str, spec: bool, time: Option<&str>| ManifestRow {
        name: name.into(),
        spec: spec.then(|| format!("{name}.toml").into()),
        missing: (!spec).then(|| "not yet".into()),
        paper: PaperRow { edges: None, variables: None, time: time.map(Into::into) },
    };
    let manifest = Manifest {
        row: vec![row("2a", true, Some("132")), row("1a", false, Some("379/366/49")), row("x<&>", true, Some("-"))],
    };
    assert_eq!(paper_seconds(&manifest.row[0].paper), Some(132.0));
    assert_eq!(paper_seconds(&manifest.row[1].paper), None);
    assert_eq!(paper_seconds(&manifest.row[2].paper), None);
    let solvers: Vec<String> = ["highs", "cbc", "scip"].map(String::from).to_vec();
    let mut gap = record("2a", "cbc", "limit(time)", 60.0);
    gap.gap = Some(0.125);
    let mut killed = record("2a", "scip", "killed", 75.0);
    (killed.killed, killed.solver_time) = (true, None);
    let mut failed = record("x<&>", "cbc", "failed", 0.0);
    failed.solver_time = None;
    let records =
        vec![record("2a", "highs", "optimal", 12.5), gap, killed, record("x<&>", "highs", "optimal", 0.02), failed];
    let svg = bar_chart_svg(&manifest, &records, &solvers, 60.0);
    assert_eq!(svg, bar_chart_svg(&manifest, &records, &solvers, 60.0), "deterministic");
    assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    // Rows without a spec are listed, not drawn; names are escaped.
    assert_eq!(svg.matches(r#"<g class="instance""#).count(), 2, "{svg}");
    assert!(svg.contains(r#"data-instance="x&lt;&amp;&gt;""#) && !svg.contains("x<&>"), "{svg}");
    assert!(svg.contains("Not shown (no spec yet): 1a"), "{svg}");
    // One bar per run; no bar where there is no run (x<&> on scip).
    assert_eq!(svg.matches(r#"class="bar""#).count(), 5, "{svg}");
    assert!(
        svg.contains(
            r#"data-instance="2a" data-solver="highs" data-status="optimal" data-solved="true" data-time="12.5""#
        ),
        "{svg}"
    );
    assert!(
        svg.contains(
            r#"data-instance="2a" data-solver="cbc" data-status="limit(time)" data-solved="false" data-time="60""#
        ),
        "{svg}"
    );
    assert!(
        svg.contains(r#"data-solver="scip" data-status="killed" data-solved="false" data-time="75.5""#),
        "killed: wall time; {svg}"
    );
    assert!(svg.contains(r#"data-solver="cbc" data-status="failed" data-solved="false" data-time="0.5""#), "{svg}");
    assert!(
        svg.contains(">limit(time) 12.5%</text>") && svg.contains(">killed</text>") && svg.contains(">failed</text>"),
        "{svg}"
    );
    assert_eq!(svg.matches(r#"class="killed""#).count(), 1);
    assert_eq!(svg.matches(r#"fill="url(#hatch-"#).count(), 2 + 1, "two hatched bars and the legend");
    // The paper's time only where it is one number; the axis reaches it (1000 s decade).
    assert_eq!(svg.matches(r#"<g class="paper""#).count(), 1);
    assert!(svg.contains(r#"<g class="paper" data-instance="2a" data-time="132">"#), "{svg}");
    assert!(svg.contains(">1000</text>") && svg.contains(">0.01</text>") && svg.contains("log scale"), "{svg}");
    assert!(svg.contains(r#"class="limit""#) && svg.contains("limit 60 s"));
    for entry in [
        ">not solved (status, gap)</text>",
        ">failed</text>",
        ">killed at limit + grace</text>",
        ">time limit</text>",
        ">paper (Gurobi 2014)</text>",
    ] {
        assert!(svg.contains(entry), "legend entry {entry} missing: {svg}");
    }
}

#[test]
fn unsolved_runs_are_charged_the_limit() {
    let rec = |solver: &str, status: &str, t: f64| RunRecord {
        solver_time: None,
        wall_time: t,
        ..record("i", solver, status, t)
    };
    let recs = vec![rec("x", "optimal", 2.0), rec("y", "limit(time)", 7.0)];
    let s = summarize(&recs, &["x".into(), "y".into()], 60.0);
    assert!((s[0].sgm_time - 2.0).abs() < 1e-9 && s[0].solved == 1 && s[0].wins == 1);
    assert!((s[1].sgm_time - 60.0).abs() < 1e-9 && s[1].solved == 0 && s[1].wins == 0);
}

#[test]
fn manifest_rows_that_cannot_run_are_shown_missing() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("n.toml"), fixture("tiny_network.toml")).unwrap();
    std::fs::write(
        dir.path().join("m.toml"),
        r#"
[[row]]
name = "net"
spec = "n.toml"
paper = { edges = 40, variables = 100, time = "1" }

[[row]]
name = "street"
missing = "not built yet"
paper = { edges = 657, time = "379/366/49" }
"#,
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .args(["compare", "--solvers", "highs", "--time-limit", "2", "--manifest"])
        .arg(dir.path().join("m.toml"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    assert!(md.contains("| net | 40 (40) |"), "{md}");
    assert!(md.contains("| street | - (657) | - (-) | 379/366/49 | missing | missing: not built yet |"), "{md}");
    assert!(md.contains("Command: `"), "{md}");
    // The repository's Table 1 manifest loads and lists every row of the paper's table (street
    // rows once per level: 11 street rows → 9 × 3 levels + 5L3 + 5L4 = 29 entries, plus the 15
    // others), and every spec it names exists and resolves.
    let m =
        netspec::compare::Manifest::load(&std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/table1.toml"))
            .unwrap();
    assert_eq!(m.row.len(), 44);
    for fig in
        ["1a-L2", "1c-L4", "1d", "1e", "2a", "2g", "5L3", "5L4", "7a-L2", "7e-L4", "8-L3", "9b1", "9b4", "11a", "11b"]
    {
        assert!(m.row.iter().any(|r| r.name == fig), "{fig} missing from table1.toml");
    }
    for r in &m.row {
        if let Some(spec) = &r.spec {
            let s = netspec::spec::Spec::load(spec).unwrap_or_else(|e| panic!("{}: {e}", r.name));
            s.resolve(spec.parent().unwrap()).unwrap_or_else(|e| panic!("{}: {e}", r.name));
        }
    }
    // Parts of the table are selections of its rows (`compare --rows`), the same rows.
    let fig2 = m.select(&["2*".to_string()]).unwrap();
    assert_eq!(
        fig2.row.iter().map(|r| r.name.as_str()).collect::<Vec<_>>(),
        ["2a", "2b", "2c", "2d", "2e", "2f", "2g"]
    );
    let l4 = m.select(&["*-L4".to_string(), "5L4".to_string()]).unwrap();
    assert!(l4.row.iter().all(|r| r.name.ends_with("L4")) && l4.row.len() >= 5, "{:?}", l4.row);
    let e = m.select(&["2z".to_string()]).unwrap_err().to_string();
    assert!(e.contains("`2z` matches no row"), "{e}");
}

#[test]
fn row_patterns() {
    use netspec::compare::glob_match;
    for (p, n, want) in [
        ("2*", "2a", true),
        ("2*", "12a", false),
        ("*-L4", "1a-L4", true),
        ("*-L4", "1a-L3", false),
        ("?a", "2a", true),
        ("2a", "2a", true),
        ("2a", "2ab", false),
        ("*", "", true),
        ("a*b*c", "axxbyyc", true),
        ("a*b*c", "axxbyy", false),
    ] {
        assert_eq!(glob_match(p, n), want, "{p} {n}");
    }
}

/// `--paper-limits`: each row gets the paper's own time as its limit, capped; unsolved runs are
/// charged their own limit in the shifted geometric mean.
#[test]
fn paper_limits_per_row() {
    use netspec::compare::CompareSettings;
    let row = |time: &str| ManifestRow {
        name: "r".into(),
        spec: None,
        missing: Some("-".into()),
        paper: PaperRow { edges: None, variables: None, time: Some(time.into()) },
    };
    let mut s = CompareSettings {
        manifest: Manifest { row: vec![] },
        solvers: vec![],
        formulations: vec![],
        time_limit: 100.0,
        grace: 1.0,
        seeds: vec![],
        threads: None,
        paper_limits: true,
        no_start: false,
        interrupt: None,
        executor: Default::default(),
    };
    assert_eq!(s.limit_for(&row("35")), 35.0);
    assert_eq!(s.limit_for(&row("1018")), 100.0);
    assert_eq!(s.limit_for(&row("379/366/49")), 100.0);
    s.paper_limits = false;
    assert_eq!(s.limit_for(&row("35")), 100.0);
    let mut a = record("i", "x", "limit(time)", 35.0);
    a.time_limit = Some(35.0);
    let summary = summarize(&[a], &["x".into()], 100.0);
    assert!((summary[0].sgm_time - 35.0).abs() < 1e-9, "{summary:?}");
}

/// Instance names come from paths: the shortest trailing part that tells specs apart.
#[test]
fn instance_ids_are_path_derived_and_unique() {
    let ids = |paths: &[&str]| instance_ids(&paths.iter().map(PathBuf::from).collect::<Vec<_>>());
    assert_eq!(
        ids(&["models/streets/fig1b/L2/spec.json", "models/streets/fig7e/L2/spec.json", "models/fig2b.toml"]),
        ["fig1b/L2/spec", "fig7e/L2/spec", "fig2b"]
    );
    assert_eq!(ids(&["./a.toml"]), ["a"]);
    assert_eq!(ids(&["x/a.toml", "a.toml"]), ["x/a", "a"]);
    assert_eq!(ids(&["d/a.toml", "d/a.json"]), ["d/a.toml", "d/a.json"]);
    assert_eq!(ids(&["a.toml", "a.toml"]), ["a", "a#2"]);
    // Run directories: one per instance, never shared.
    let m = Manifest::from_specs(&["p/x/spec.toml", "q/x/spec.toml"].map(PathBuf::from));
    assert_eq!(m.run_keys(), ["p-x-spec", "q-x-spec"]);
    let clash = Manifest {
        row: ["a/b", "a-b"]
            .iter()
            .map(|n| ManifestRow {
                name: n.to_string(),
                spec: Some("s.toml".into()),
                missing: None,
                paper: PaperRow::default(),
            })
            .collect(),
    };
    let keys = clash.run_keys();
    assert!(keys[0] != keys[1] && keys[0].starts_with("a-b-") && keys[1].starts_with("a-b-"), "{keys:?}");
}

/// Runs `netspec compare` with HiGHS; returns stdout and the records.
fn compare(specs: &[&Path], extra: &[&str], out: &Path) -> (String, Vec<RunRecord>) {
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("compare")
        .args(specs)
        .args(["--solvers", "highs", "--grace", "5", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    (String::from_utf8(o.stdout).unwrap(), serde_json::from_value(json["records"].clone()).unwrap())
}

/// Two specs both called `spec.toml` (in different directories) are two instances, each
/// solved, each with its own record.
#[test]
fn same_file_names_are_different_instances() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("x/L2/spec.toml"), dir.path().join("y/L2/spec.toml"));
    for (p, f) in [(&a, "tiny_floorplan.toml"), (&b, "tiny_network.toml")] {
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, fixture(f)).unwrap();
    }
    let out = dir.path().join("out");
    let (stdout, records) = compare(&[&a, &b], &["--time-limit", "20"], &out);
    assert!(!stdout.contains("(resumed)"), "{stdout}");
    let names: Vec<&str> = records.iter().map(|r| r.instance.as_str()).collect();
    assert_eq!(names, ["x/L2/spec", "y/L2/spec"]);
    assert!(records.iter().all(|r| r.status == "optimal" && r.valid), "{records:?}");
    // Different instances, different answers: the floor plan's corridor is 3 long.
    assert_eq!(records[0].objective, Some(3.0));
    assert_ne!(records[0].objective, records[1].objective);
    assert!(
        out.join("runs/x-L2-spec__highs__default/run.json").exists()
            && out.join("runs/y-L2-spec__highs__default/run.json").exists()
    );
}

/// A record is reused only with the same settings: another time limit, thread count or an
/// edited spec solves again; the same settings resume. Records say what produced them.
#[test]
fn rerun_with_other_settings_solves_again() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("n.toml");
    std::fs::write(&spec, fixture("tiny_network.toml")).unwrap();
    let out = dir.path().join("out");
    let (first, records) = compare(&[&spec], &["--time-limit", "20"], &out);
    assert!(!first.contains("(resumed)") && !first.contains("solved again"), "{first}");
    let s = records[0].settings.clone().expect("settings recorded");
    assert_eq!((s.solver.as_str(), s.seed, s.threads, s.time_limit), ("highs", None, None, 20.0));
    assert_eq!(s.formulation.as_deref(), Some("tight"));
    assert_eq!(s.netspec_version, env!("CARGO_PKG_VERSION"));
    assert_eq!(s.spec, spec);

    let (second, records) = compare(&[&spec], &["--time-limit", "19"], &out);
    assert!(second.contains("(solved again: time limit 20 s → 19 s)"), "{second}");
    assert_eq!(records[0].settings.as_ref().unwrap().time_limit, 19.0);
    assert_eq!(records[0].time_limit, Some(19.0));
    let (third, _) = compare(&[&spec], &["--time-limit", "19"], &out);
    assert!(third.contains("(resumed)"), "{third}");
    let (fourth, records) = compare(&[&spec], &["--time-limit", "19", "--threads", "1"], &out);
    assert!(fourth.contains("(solved again: threads default → 1)"), "{fourth}");
    assert_eq!(records[0].settings.as_ref().unwrap().threads, Some(1));
    std::fs::write(&spec, fixture("tiny_network.toml") + "\n# edited\n").unwrap();
    let (fifth, _) = compare(&[&spec], &["--time-limit", "19", "--threads", "1"], &out);
    assert!(fifth.contains("solved again: spec digest"), "{fifth}");
    // A record without settings (an older netspec) is solved again.
    let path = out.join("runs/n__highs__default/run.json");
    let mut old: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    old.as_object_mut().unwrap().remove("settings");
    std::fs::write(&path, old.to_string()).unwrap();
    let (sixth, _) = compare(&[&spec], &["--time-limit", "19", "--threads", "1"], &out);
    assert!(sixth.contains("(solved again: no settings recorded)"), "{sixth}");
}

/// `kill -9` of `netspec compare` takes its running child with it (no orphan keeps solving).
#[cfg(target_os = "linux")]
#[test]
fn killing_compare_kills_its_child() {
    use std::time::{Duration, Instant};
    let dir = tempfile::tempdir().unwrap();
    // Fig. 2b: HiGHS does not finish it in a minute.
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("models/fig2b.toml");
    let mut parent = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("compare")
        .arg(&spec)
        .args(["--solvers", "highs", "--time-limit", "120", "--threads", "1", "--out"])
        .arg(dir.path())
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let ppid = parent.id();
    let stat = |pid: u32| std::fs::read_to_string(format!("/proc/{pid}/stat")).ok();
    // (pid, parent pid, state) of every process.
    let children = || -> Vec<u32> {
        std::fs::read_dir("/proc")
            .unwrap()
            .filter_map(|e| e.ok()?.file_name().to_str()?.parse::<u32>().ok())
            .filter(|&pid| {
                stat(pid)
                    .is_some_and(|s| s.rsplit(')').next().unwrap().split_whitespace().nth(1) == Some(&ppid.to_string()))
            })
            .collect()
    };
    let t0 = Instant::now();
    let child = loop {
        if let Some(&c) = children().first() {
            break c;
        }
        assert!(t0.elapsed() < Duration::from_secs(30), "no child appeared");
        std::thread::sleep(Duration::from_millis(20));
    };
    // Let the child get into its solve, then kill the parent outright.
    std::thread::sleep(Duration::from_millis(500));
    let alive = |pid: u32| {
        stat(pid).is_some_and(|s| !matches!(s.rsplit(')').next().unwrap().split_whitespace().next(), Some("Z" | "X")))
    };
    assert!(alive(child), "the child ended early");
    parent.kill().unwrap();
    parent.wait().unwrap();
    let t1 = Instant::now();
    while alive(child) {
        if t1.elapsed() > Duration::from_secs(10) {
            let _ = Command::new("kill").args(["-9", &child.to_string()]).status();
            panic!("the child {child} outlived its parent");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// `--formulations paper,strong`: every backend runs each recipe as its own column
/// (`highs/paper`, `highs/strong`), the child is given the recipe, both prove the same optimum,
/// and the tables and records carry the pair.
#[test]
fn formulation_axis() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("net.toml");
    std::fs::write(&spec, fixture("tiny_network.toml")).unwrap();
    let out = dir.path().join("out");
    let (stdout, records) = compare(&[&spec], &["--time-limit", "20", "--formulations", "paper,strong"], &out);
    let solvers: Vec<&str> = records.iter().map(|r| r.solver.as_str()).collect();
    assert_eq!(solvers, ["highs/paper", "highs/strong"], "{stdout}");
    assert!(records.iter().all(|r| r.status == "optimal" && r.valid), "{records:?}");
    let (a, b) = (records[0].objective.unwrap(), records[1].objective.unwrap());
    assert!(netspec::milp::objectives_agree(a, b, 1e-9), "{a} vs {b}");
    assert_eq!(records[1].settings.as_ref().unwrap().formulation.as_deref(), Some("strong"));
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    assert!(md.contains("highs/paper") && md.contains("highs/strong"), "{md}");
    for (label, recipe) in [("highs+paper", "paper"), ("highs+strong", "strong")] {
        let res: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(out.join(format!("runs/net__{label}__default/result.json"))).unwrap(),
        )
        .unwrap();
        assert_eq!(res["formulation"], recipe);
    }
}

/// `compare --merge`: two finished comparisons (other backends, other threads) become one
/// report, with every column of both, without solving anything; a column in both, or a
/// directory that holds no comparison, is an error naming it.
#[test]
fn merge_combines_finished_comparisons() {
    let dir = tempfile::tempdir().unwrap();
    let spec = dir.path().join("a.toml");
    std::fs::write(&spec, fixture("tiny_network.toml")).unwrap();
    let netspec = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_netspec")).current_dir(dir.path()).args(args).output().unwrap()
    };
    for (solver, threads) in [("highs", "2"), ("microlp", "1")] {
        let o = netspec(&[
            "compare",
            "a.toml",
            "--solvers",
            solver,
            "--threads",
            threads,
            "--time-limit",
            "20",
            "--out",
            solver,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = netspec(&["compare", "--merge", "highs,microlp", "--out", "both"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = dir.path().join("both");
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    assert!(md.contains("merged from `highs`, `microlp`"), "{md}");
    let header = md.lines().find(|l| l.starts_with("| instance |")).unwrap();
    assert!(header.contains(" highs |") && header.contains(" microlp |"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    let records: Vec<RunRecord> = serde_json::from_value(json["records"].clone()).unwrap();
    assert_eq!(records.len(), 2);
    // Each record keeps the settings it ran with.
    let threads: Vec<Option<u32>> = records.iter().map(|r| r.settings.as_ref().unwrap().threads).collect();
    assert_eq!(threads, [Some(2), Some(1)]);
    assert_eq!(json["settings"]["merged_from"].as_array().unwrap().len(), 2);
    let profile = std::fs::read_to_string(out.join("profile.svg")).unwrap();
    assert_eq!(profile.matches(r#"class="profile""#).count(), 2);
    let bars = std::fs::read_to_string(out.join("bars.svg")).unwrap();
    assert_eq!(bars.matches(r#"class="bar""#).count(), 2);
    // A merge is a comparison too: it merges again, but not with a comparison it holds.
    let o = netspec(&["compare", "--merge", "both,highs", "--out", "again"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("column `highs` is in both both and highs"), "{err}");
    let o = netspec(&["compare", "--merge", "highs,nowhere", "--out", "x"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("nowhere/results.json"), "{err}");
    // Merging solves nothing: no run directories in the merged output.
    assert!(!out.join("runs").exists());
}

/// A row whose spec cannot be used: the run's cause is printed with it and listed in
/// results.md, and compare exits non-zero; a backend named twice is refused before any run.
#[test]
fn failed_runs_say_why_and_duplicate_columns_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, "name = \"bad\"\n[mesh]\ngrid = { width = 3, height = 3 }\n[sinks]\nvertices = [99]\n")
        .unwrap();
    let out = dir.path().join("out");
    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .args(["compare", "--solvers", "highs", "--time-limit", "5", "--out"])
        .arg(&out)
        .arg(&bad)
        .output()
        .unwrap();
    let (stdout, stderr) = (String::from_utf8_lossy(&o.stdout), String::from_utf8_lossy(&o.stderr));
    assert!(!o.status.success(), "{stdout}");
    assert!(stdout.contains("failed") && stdout.contains("sinks.vertices"), "{stdout}");
    assert!(stderr.contains("1 of 1 runs could not run"), "{stderr}");
    let md = std::fs::read_to_string(out.join("results.md")).unwrap();
    assert!(md.contains("Runs that failed") && md.contains("sinks.vertices"), "{md}");
    let records: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("results.json")).unwrap()).unwrap();
    assert!(records["records"][0]["error"].as_str().is_some_and(|e| e.contains("sinks.vertices")), "{records}");

    let o = Command::new(env!("CARGO_BIN_EXE_netspec"))
        .args(["compare", "--solvers", "highs,highs", "--out"])
        .arg(&out)
        .arg(&bad)
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--solvers names `highs` twice"));
}
