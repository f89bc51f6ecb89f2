//! `netspec serve`: every endpoint over real HTTP (good and bad input), solves streamed to the
//! page, runs kept across a restart, and a real browser driving the page (`browser`).

mod browser;
mod http;
mod sites;

use netspec::serve::{ServeOptions, Server};
use serde_json::Value;
use std::path::Path;

/// A 4 × 4 grid with two interior sinks: optimal in well under a second.
pub const SMALL: &str = r#"name = "small"
description = "a 4×4 grid with two interior sinks"
[mesh]
grid = { width = 4, height = 4 }
[sinks]
vertices = [6, 18]
[coverage]
range = 2
[features]
dead_ends = "allow"
[weights]
length = 1
distance = 1
[solver]
name = "highs"
time_limit = 30
threads = 1
"#;

/// Fig. 2e of the paper (12 × 12, interior sinks) with a long limit: a solve still running
/// after its first designs, to be stopped.
pub fn long_spec() -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/models/fig2e.toml")).unwrap();
    format!("{text}\n[solver]\nname = \"highs\"\ntime_limit = 120\nthreads = 1\n")
}

/// A server on a free loopback port over a fresh root holding `small.toml`.
pub fn server(root: &Path, max_solves: usize) -> Server {
    if !root.join("small.toml").exists() {
        std::fs::write(root.join("small.toml"), SMALL).unwrap();
    }
    let opts = ServeOptions { root: root.to_path_buf(), port: 0, max_solves, threads: 2, ..Default::default() };
    Server::start(opts).expect("the server starts")
}

/// A runtime for the async clients.
pub fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().unwrap()
}

/// Reads a run's event stream until its `done` (or `failed`) event; `on` sees every event and
/// may end the reading early by returning `false`.
pub async fn follow(base: &str, id: &str, mut on: impl FnMut(&Value) -> bool) -> Vec<Value> {
    let mut resp = reqwest::get(format!("{base}/api/runs/{id}/events")).await.unwrap();
    assert_eq!(resp.status(), 200);
    let (mut buf, mut out) = (String::new(), Vec::new());
    while let Some(chunk) = resp.chunk().await.unwrap() {
        buf.push_str(&String::from_utf8_lossy(&chunk));
        while let Some(end) = buf.find("\n\n") {
            let block: String = buf.drain(..end + 2).collect();
            let data: String = block.lines().filter_map(|l| l.strip_prefix("data:")).map(|d| d.trim_start()).collect();
            if data.is_empty() {
                continue;
            }
            let ev: Value = serde_json::from_str(&data).unwrap();
            let more = on(&ev);
            let last = matches!(ev["kind"].as_str(), Some("done" | "failed"));
            out.push(ev);
            if last || !more {
                return out;
            }
        }
    }
    out
}

/// The objective `netspec solve` finds on a spec file (same settings: the file's).
pub fn cli_objective(spec: &Path) -> f64 {
    let out = tempfile::tempdir().unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_netspec"))
        .arg("solve")
        .arg(spec)
        .arg("--out")
        .arg(out.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let result: Value =
        serde_json::from_str(&std::fs::read_to_string(out.path().join("result.json")).unwrap()).unwrap();
    result["solve"]["objective"].as_f64().expect("the CLI found a design")
}
