//! Real sites in `netspec serve` over HTTP: an extract under the root listed, read and drawn by
//! view; a site made from a box; layout and grow run on it as child processes with their output
//! streamed; the comparison with the real streets (JSON, CSV, GeoJSON); a city cancelled and
//! resumed; runs kept across a restart; and bad input (a file that is not OSM, a box outside the
//! extract, a polygon that crosses itself, a site over 25 km², an upload over 200 MB, paths
//! outside the root) answered with the field named while the server keeps answering.

use super::{follow, runtime};
use netspec::serve::{ServeOptions, Server};
use reqwest::{Client, StatusCode};
use serde_json::{json, Value};
use std::path::Path;

fn server(root: &Path) -> Server {
    let opts = ServeOptions {
        root: root.to_path_buf(),
        port: 0,
        max_solves: 2,
        threads: 2,
        netspec_bin: Some(env!("CARGO_BIN_EXE_netspec").into()),
        ..Default::default()
    };
    Server::start(opts).expect("the server starts")
}

async fn get(c: &Client, url: String) -> (StatusCode, Value) {
    let r = c.get(url).send().await.unwrap();
    let s = r.status();
    (s, r.json().await.unwrap_or(Value::Null))
}

async fn post(c: &Client, url: String, body: impl Into<reqwest::Body>) -> (StatusCode, Value) {
    let r = c.post(url).body(body).send().await.unwrap();
    let s = r.status();
    (s, r.json().await.unwrap_or(Value::Null))
}

/// A root holding the made-up town of the site tests as `town.osm`.
fn root() -> tempfile::TempDir {
    let root = tempfile::tempdir().unwrap();
    std::fs::write(root.path().join("town.osm"), crate::site::town_xml()).unwrap();
    root
}

fn bbox() -> Value {
    let v: Vec<f64> = crate::site::BBOX.split(',').map(|x| x.parse().unwrap()).collect();
    json!(v)
}

#[test]
fn a_site_is_drawn_made_run_and_compared_with_its_real_streets() {
    let root = root();
    let base;
    {
        let srv = server(root.path());
        base = format!("http://{}", srv.addr());
        runtime().block_on(async {
            let c = Client::new();
            let (s, list) = get(&c, format!("{base}/api/extracts")).await;
            assert_eq!(s, 200);
            assert_eq!(list["extracts"][0]["path"], "town.osm");
            let (s, info) = get(&c, format!("{base}/api/extract?path=town.osm")).await;
            assert_eq!(s, 200, "{info}");
            assert!(info["attribution"].as_str().unwrap().contains("OpenStreetMap"));
            // The view's features: streets by class, the lake and the park; a small view fewer.
            let (_, all) = get(&c, format!("{base}/api/extract/features?path=town.osm")).await;
            let n = all["features"].as_array().unwrap().len();
            let layers: std::collections::BTreeSet<&str> = all["features"]
                .as_array()
                .unwrap()
                .iter()
                .map(|f| f["properties"]["layer"].as_str().unwrap())
                .collect();
            assert_eq!(layers, ["park", "street", "water"].into(), "{layers:?}");
            let (_, few) =
                get(&c, format!("{base}/api/extract/features?path=town.osm&bbox=11.0,48.0,11.002,48.002")).await;
            assert!(few["features"].as_array().unwrap().len() < n);
            // The site.
            let body = json!({"extract": "town.osm", "name": "town", "bbox": bbox()}).to_string();
            let (s, made) = post(&c, format!("{base}/api/sites"), body).await;
            assert_eq!(s, 200, "{made}");
            assert!(made["land_km2"].as_f64().unwrap() > 1.0 && made["roads"].as_u64().unwrap() == 3, "{made}");
            // Layout and grow, streamed to the end.
            let mut ids = Vec::new();
            for m in [json!({"method": "layout"}), json!({"method": "grow", "steps": 4})] {
                let (s, r) = post(&c, format!("{base}/api/sites/town/runs"), m.to_string()).await;
                assert_eq!(s, 200, "{r}");
                ids.push(r["id"].as_str().unwrap().to_string());
            }
            for id in &ids {
                let events = follow(&base, id, |_| true).await;
                let last = events.last().unwrap();
                assert_eq!(last["kind"], "done", "{last}");
                assert_eq!(last["state"], "finished", "{last}");
                assert!(events.iter().any(|e| e["kind"] == "line"), "the command's lines are streamed");
            }
            let (_, site) = get(&c, format!("{base}/api/sites/town")).await;
            let designs = site["compare"]["designs"].as_array().unwrap();
            let labels: Vec<&str> = designs.iter().map(|d| d["label"].as_str().unwrap()).collect();
            assert_eq!(labels, ["map", "grown", "layout"]);
            assert!(designs[0]["distance"].is_null() && designs[2]["distance"]["mean"].as_f64().unwrap() > 0.0);
            assert!(!designs[1]["streets"]["features"].as_array().unwrap().is_empty());
            let csv = c.get(format!("{base}/api/sites/town/compare.csv")).send().await.unwrap().text().await.unwrap();
            assert_eq!(csv.lines().count(), 4, "{csv}");
            assert!(csv.starts_with("design,street_density_km"));
            let gj = c.get(format!("{base}/api/sites/town/designs/layout.geojson")).send().await.unwrap();
            assert_eq!(gj.status(), 200);
            let lj = c.get(format!("{base}/api/runs/{}/out/layout.json", ids[0])).send().await.unwrap();
            assert_eq!(lj.status(), 200);
            // A city with long levels, cancelled: interrupted; resumed, it runs again.
            let (_, r) = post(
                &c,
                format!("{base}/api/sites/town/runs"),
                json!({"method": "city", "time_limit": 120}).to_string(),
            )
            .await;
            let city = r["id"].as_str().unwrap().to_string();
            follow(&base, &city, |e| e["kind"] != "line").await;
            let (s, _) = post(&c, format!("{base}/api/runs/{city}/stop"), "").await;
            assert_eq!(s, 200);
            let last = follow(&base, &city, |_| true).await.pop().unwrap();
            assert_eq!(last["state"], "interrupted", "{last}");
            let (s, r) = post(&c, format!("{base}/api/runs/{city}/resume"), "").await;
            assert_eq!(s, 200, "{r}");
            follow(&base, &city, |e| e["kind"] != "line").await;
        });
        // The server stops (dropped) with the city running: its child is killed with it.
    }
    let srv = server(root.path());
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let (_, site) = get(&c, format!("{base}/api/sites/town")).await;
        let states: Vec<(String, String)> = site["runs"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| (r["settings"]["method"].as_str().unwrap().into(), r["state"].as_str().unwrap().into()))
            .collect();
        assert!(states.contains(&("layout".into(), "finished".into())), "{states:?}");
        assert!(states.contains(&("city".into(), "interrupted".into())), "{states:?}");
    });
    let _ = base;
}

#[test]
fn bad_sites_are_named_and_the_server_keeps_answering() {
    let root = root();
    std::fs::write(root.path().join("junk.osm"), "this is not OpenStreetMap").unwrap();
    let srv = server(root.path());
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let expect = |what: &str, got: (StatusCode, Value), status: u16, field: &str| {
            assert_eq!(got.0.as_u16(), status, "{what}: {}", got.1);
            assert_eq!(got.1["field"].as_str(), Some(field), "{what}: {}", got.1);
            assert!(!got.1["error"].as_str().unwrap_or("").is_empty(), "{what}: {}", got.1);
            got.1["error"].as_str().unwrap().to_string()
        };
        let e = expect("not OSM", get(&c, format!("{base}/api/extract?path=junk.osm")).await, 422, "path");
        assert!(e.contains("junk.osm") && !e.contains(&root.path().display().to_string()), "{e}");
        expect("outside the root", get(&c, format!("{base}/api/extract?path=../x.osm")).await, 403, "path");
        let site = |v: Value| post(&c, format!("{base}/api/sites"), v.to_string());
        let (s, r) = site(json!({"extract": "town.osm", "name": "far", "bbox": [12.0, 49.0, 12.01, 49.01]})).await;
        assert_eq!(s, 422, "{r}");
        assert!(r["error"].as_str().unwrap().contains("outside the extract"), "{r}");
        let bow = json!([[11.005, 48.002], [11.015, 48.009], [11.015, 48.002], [11.005, 48.009]]);
        let e = expect(
            "bow tie",
            site(json!({"extract": "town.osm", "name": "bow", "polygon": bow})).await,
            422,
            "polygon",
        );
        assert!(e.contains("intersects itself"), "{e}");
        let big = json!([10.9, 47.9, 11.1, 48.1]);
        let e = expect("too big", site(json!({"extract": "town.osm", "name": "big", "bbox": big})).await, 422, "bbox");
        assert!(e.contains("25 km²"), "{e}");
        expect("name", site(json!({"extract": "town.osm", "name": "../x", "bbox": bbox()})).await, 400, "name");
        expect("no such site", get(&c, format!("{base}/api/sites/nope")).await, 404, "name");
        // Uploads: not OSM, then over 200 MB (refused before it is read).
        let e = expect("upload junk", post(&c, format!("{base}/api/upload?name=x.osm"), "hello").await, 422, "body");
        assert!(e.contains("neither"), "{e}");
        let huge = vec![b'<'; (200 << 20) + 1];
        let r = Client::new().post(format!("{base}/api/upload?name=big.osm")).body(huge).send().await.unwrap();
        assert_eq!(r.status(), StatusCode::PAYLOAD_TOO_LARGE);
        assert!(!root.path().join("uploads/big.osm").exists() && !root.path().join("uploads/x.osm").exists());
        // A good upload is listed.
        let (s, r) = post(&c, format!("{base}/api/upload?name=again.osm"), crate::site::town_xml()).await;
        assert_eq!(s, 200, "{r}");
        let (_, list) = get(&c, format!("{base}/api/extracts")).await;
        assert!(list["extracts"].as_array().unwrap().iter().any(|e| e["path"] == "uploads/again.osm"));
        // Nothing written outside the root, and the server still answers.
        assert_eq!(get(&c, format!("{base}/api/extracts")).await.0, 200);
    });
}
