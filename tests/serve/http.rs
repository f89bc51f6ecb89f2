//! Every endpoint over HTTP: pages, specs, checks, saves, solves, runs, files, comparison, and
//! bad input of every kind answered by a clear 4xx naming the field.

use super::{cli_objective, follow, runtime, server, SMALL};
use reqwest::{Client, StatusCode};
use serde_json::{json, Value};

async fn get(c: &Client, url: String) -> (StatusCode, String) {
    let r = c.get(url).send().await.unwrap();
    (r.status(), r.text().await.unwrap())
}

async fn post(c: &Client, url: String, body: impl Into<reqwest::Body>) -> (StatusCode, Value) {
    let r = c.post(url).header("content-type", "application/json").body(body).send().await.unwrap();
    let status = r.status();
    let text = r.text().await.unwrap();
    (status, serde_json::from_str(&text).unwrap_or(json!({ "raw": text })))
}

/// The small spec as the page holds it (JSON).
async fn small(c: &Client, base: &str) -> Value {
    let (s, body) = get(c, format!("{base}/api/spec?path=small.toml")).await;
    assert_eq!(s, 200, "{body}");
    serde_json::from_str::<Value>(&body).unwrap()["spec"].clone()
}

#[test]
fn pages_specs_and_checks() {
    let root = tempfile::tempdir().unwrap();
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let (s, page) = get(&c, format!("{base}/")).await;
        assert!(s == 200 && page.contains("<script src=\"/assets/app.js\">"), "{page}");
        for a in ["app.js", "app.css"] {
            assert_eq!(get(&c, format!("{base}/assets/{a}")).await.0, 200);
        }
        // Examples and the root's spec, with thumbnails drawn by the renderer.
        let (_, list) = get(&c, format!("{base}/api/specs")).await;
        let list: Value = serde_json::from_str(&list).unwrap();
        let ids: Vec<&str> = list["specs"].as_array().unwrap().iter().map(|s| s["id"].as_str().unwrap()).collect();
        assert!(ids.contains(&"fig2b") && ids.contains(&"small.toml"), "{ids:?}");
        let (s, svg) = get(&c, format!("{base}/api/thumb?example=fig2b")).await;
        assert!(s == 200 && svg.contains("<svg"), "{svg}");
        // A spec opens with its picture and where its 25 vertices and 40 edges are.
        let (_, body) = get(&c, format!("{base}/api/spec?path=small.toml")).await;
        let opened: Value = serde_json::from_str(&body).unwrap();
        assert_eq!(opened["view"]["points"].as_array().unwrap().len(), 25);
        assert_eq!(opened["view"]["edges"].as_array().unwrap().len(), 40);
        // An edit is checked and answered with its TOML.
        let mut spec = opened["spec"].clone();
        spec["weights"]["distance"] = json!(3.5);
        let (s, checked) = post(&c, format!("{base}/api/check"), json!({ "spec": spec }).to_string()).await;
        assert_eq!(s, 200, "{checked}");
        assert!(checked["toml"].as_str().unwrap().contains("distance = 3.5"), "{checked}");
        // A new spec from a generated mesh, in each shape.
        for shape in ["grid", "disc", "L"] {
            let (s, new) =
                post(&c, format!("{base}/api/new"), json!({ "width": 6, "height": 5, "shape": shape }).to_string())
                    .await;
            assert_eq!(s, 200, "{shape}: {new}");
            assert!(new["view"]["svg"].as_str().unwrap().contains("<svg"));
        }
        // Saved under the root, listed, and opened again.
        let (s, saved) =
            post(&c, format!("{base}/api/save"), json!({ "path": "mine/edited.toml", "spec": spec }).to_string()).await;
        assert_eq!(s, 200, "{saved}");
        let text = std::fs::read_to_string(root.path().join("mine/edited.toml")).unwrap();
        assert!(text.contains("distance = 3.5"), "{text}");
        let (s, _) = get(&c, format!("{base}/api/spec?path=mine/edited.toml")).await;
        assert_eq!(s, 200);
    });
}

#[test]
fn bad_input_is_a_clear_4xx_naming_the_field_and_the_server_keeps_answering() {
    let root = tempfile::tempdir().unwrap();
    let outside = tempfile::tempdir().unwrap();
    std::fs::write(outside.path().join("secret.toml"), SMALL).unwrap();
    std::os::unix::fs::symlink(outside.path(), root.path().join("link")).unwrap();
    std::os::unix::fs::symlink(outside.path().join("secret.toml"), root.path().join("secret.toml")).unwrap();
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let good = small(&c, &base).await;
        let expect = |what: &str, got: (StatusCode, Value), status: u16, field: &str| {
            assert_eq!(got.0.as_u16(), status, "{what}: {}", got.1);
            assert_eq!(got.1["field"].as_str(), Some(field), "{what}: {}", got.1);
            assert!(!got.1["error"].as_str().unwrap_or("").is_empty(), "{what}: {}", got.1);
        };
        let json_of = |(s, t): (StatusCode, String)| (s, serde_json::from_str::<Value>(&t).unwrap());
        // Malformed JSON, a missing field, a wrong type.
        expect("malformed", post(&c, format!("{base}/api/check"), "{\"spec\": ").await, 400, "spec");
        expect("no spec", post(&c, format!("{base}/api/check"), "{}").await, 400, "body");
        expect("new: width", post(&c, format!("{base}/api/new"), r#"{"width": "x", "height": 3}"#).await, 400, "width");
        expect(
            "new: shape",
            post(&c, format!("{base}/api/new"), r#"{"width": 3, "height": 3, "shape": "star"}"#).await,
            422,
            "shape",
        );
        // Unknown example, run, file.
        expect("example", json_of(get(&c, format!("{base}/api/spec?example=nope")).await), 404, "example");
        expect("run", json_of(get(&c, format!("{base}/api/runs/r9999")).await), 404, "id");
        // Paths outside the root: `..`, absolute, encoded, symbolic links (a folder and a file).
        for (what, q) in [
            ("dotdot", "path=../x.toml"),
            ("absolute", "path=/etc/passwd"),
            ("encoded", "path=%2e%2e%2fsecret.toml"),
            ("encoded absolute", "path=%2Fetc%2Fpasswd"),
            ("symlinked folder", "path=link/secret.toml"),
            ("symlinked file", "path=secret.toml"),
        ] {
            expect(what, json_of(get(&c, format!("{base}/api/spec?{q}")).await), 403, "path");
        }
        for path in ["../evil.toml", "/tmp/evil.toml", "link/evil.toml", "runs/r0001/spec.toml"] {
            let body = json!({ "path": path, "spec": good }).to_string();
            expect(path, post(&c, format!("{base}/api/save"), body).await, 403, "path");
        }
        assert!(!outside.path().join("evil.toml").exists());
        let body = json!({ "path": "x.txt", "spec": good }).to_string();
        expect("not toml", post(&c, format!("{base}/api/save"), body).await, 400, "path");
        // An oversize body, on a connection of its own: the server answers 413 without reading the
        // rest and closes it, so a pooled connection must not carry the next request.
        let big = format!("{{\"spec\": \"{}\"}}", "x".repeat(2 << 20));
        let r = Client::new().post(format!("{base}/api/check")).body(big).send().await.unwrap();
        assert_eq!(r.status(), StatusCode::PAYLOAD_TOO_LARGE);
        // Specs the validator refuses, with the CLI's message and the field named.
        let refused = |f: &dyn Fn(&mut Value)| {
            let mut s = good.clone();
            f(&mut s);
            json!({ "spec": s }).to_string()
        };
        for (what, body, field) in [
            ("sink out of range", refused(&|s| s["sinks"]["vertices"] = json!([6, 999])), "sinks.vertices[1]"),
            ("a weight of the wrong type", refused(&|s| s["weights"]["distance"] = json!("heavy")), "weights.distance"),
            ("an unknown key", refused(&|s| s["weights"]["speed"] = json!(1)), "weights"),
            ("a mesh too large", refused(&|s| s["mesh"]["grid"] = json!({ "width": 1000, "height": 1000 })), "mesh"),
            ("a control character", refused(&|s| s["name"] = json!("a\u{7}b")), "name"),
        ] {
            let got = post(&c, format!("{base}/api/check"), body).await;
            assert_eq!(got.0, 422, "{what}: {}", got.1);
            let named = got.1["field"].as_str().unwrap_or("");
            assert!(named.starts_with(field), "{what}: field {named:?}, want {field}: {}", got.1);
        }
        let body = refused(&|s| s["solver"]["threads"] = json!(64));
        expect("threads", post(&c, format!("{base}/api/solve"), body).await, 422, "solver.threads");
        // No run was made of a refused spec, and the server still answers.
        let (s, runs) = get(&c, format!("{base}/api/runs")).await;
        assert_eq!(s, 200);
        assert_eq!(serde_json::from_str::<Value>(&runs).unwrap()["runs"], json!([]));
        expect("compare one", json_of(get(&c, format!("{base}/api/compare?ids=r0001")).await), 400, "ids");
        assert_eq!(get(&c, format!("{base}/api/specs")).await.0, 200);
    });
}

#[test]
fn solves_stream_designs_keep_runs_and_compare() {
    let root = tempfile::tempdir().unwrap();
    let rt = runtime();
    let (first, second) = {
        let srv = server(root.path(), 1);
        let base = format!("http://{}", srv.addr());
        rt.block_on(async {
            let c = Client::new();
            let mut spec = small(&c, &base).await;
            let mut ids = Vec::new();
            for distance in [1.0, 4.0] {
                spec["weights"]["distance"] = json!(distance);
                let (s, r) = post(&c, format!("{base}/api/solve"), json!({ "spec": spec }).to_string()).await;
                assert_eq!(s, 200, "{r}");
                let id = r["id"].as_str().unwrap().to_string();
                let events = follow(&base, &id, |_| true).await;
                let kinds: Vec<&str> = events.iter().map(|e| e["kind"].as_str().unwrap()).collect();
                assert!(kinds.contains(&"design"), "{kinds:?}");
                let done = events.last().unwrap();
                assert_eq!(done["kind"], "done", "{done}");
                let sum = &done["summary"];
                assert_eq!(sum["verdict"], "valid", "{sum}");
                assert!(sum["status"].as_str().unwrap().starts_with("optimal"), "{sum}");
                assert!(done["svg"].as_str().unwrap().contains("<svg"));
                // The same objective as `netspec solve` on the run's spec file.
                let objective = sum["objective"].as_f64().unwrap();
                let cli = cli_objective(&root.path().join("runs").join(&id).join("spec.toml"));
                assert!((objective - cli).abs() < 1e-6, "serve {objective}, CLI {cli}");
                // The designs drawn on the way are never better than the optimum.
                for e in events.iter().filter(|e| e["kind"] == "design") {
                    assert!(e["objective"].as_f64().unwrap() >= objective - 1e-6, "{e}");
                }
                ids.push(id);
            }
            // Every export of a run.
            for (name, needle) in [
                ("result.json", "\"netspec.design\""),
                ("network.svg", "<svg"),
                ("network.geojson", "FeatureCollection"),
                ("spec.toml", "name = \"small\""),
                ("model.lp", "Subject To"),
                ("model.mps", "ROWS"),
            ] {
                let (s, body) = get(&c, format!("{base}/api/runs/{}/files/{name}", ids[0])).await;
                assert!(s == 200 && body.contains(needle), "{name}: {s} {}", &body[..body.len().min(200)]);
            }
            let png = c.get(format!("{base}/api/runs/{}/files/network.png", ids[0])).send().await.unwrap();
            assert_eq!(&png.bytes().await.unwrap()[..4], b"\x89PNG");
            let (s, _) = get(&c, format!("{base}/api/runs/{}/files/..%2Fsmall.toml", ids[0])).await;
            assert_eq!(s, 404);
            (ids[0].clone(), ids[1].clone())
        })
    };
    // A restart on the same root loses nothing: the runs, their results, the comparison.
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    rt.block_on(async {
        let c = Client::new();
        let (_, runs) = get(&c, format!("{base}/api/runs")).await;
        let runs: Value = serde_json::from_str(&runs).unwrap();
        let states: Vec<&str> = runs["runs"].as_array().unwrap().iter().map(|r| r["state"].as_str().unwrap()).collect();
        assert_eq!(states, ["finished", "finished"]);
        let events = follow(&base, &first, |_| true).await;
        assert_eq!(events.len(), 1);
        assert_eq!(events[0]["summary"]["verdict"], "valid");
        let (s, cmp) = get(&c, format!("{base}/api/compare?ids={first},{second}")).await;
        assert_eq!(s, 200, "{cmp}");
        let cmp: Value = serde_json::from_str(&cmp).unwrap();
        let rows = cmp["rows"].as_array().unwrap();
        let objective = rows.iter().find(|r| r[0] == "objective").unwrap();
        assert_eq!(objective.as_array().unwrap().len(), 3, "{objective}");
        let digest = rows.iter().find(|r| r[0] == "digest").unwrap();
        assert_ne!(digest[1], digest[2], "different specs, different digests");
        // A new run takes the next id.
        let spec = small(&c, &base).await;
        let (_, r) = post(&c, format!("{base}/api/solve"), json!({ "spec": spec }).to_string()).await;
        assert_eq!(r["id"], "r0003");
        follow(&base, "r0003", |_| true).await;
    });
}

#[test]
fn stop_and_a_closed_page_keep_the_best_design() {
    let root = tempfile::tempdir().unwrap();
    let srv = server(root.path(), 2);
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let spec: Value = {
            let s: netspec::spec::Spec = toml::from_str(&super::long_spec()).unwrap();
            serde_json::to_value(s).unwrap()
        };
        // Stop, once the first design is drawn.
        let (_, r) = post(&c, format!("{base}/api/solve"), json!({ "spec": spec }).to_string()).await;
        let id = r["id"].as_str().unwrap().to_string();
        let mut stopped = false;
        let events = follow(&base, &id, |e| {
            if e["kind"] == "design" && !stopped {
                stopped = true;
                let (c, url) = (c.clone(), format!("{base}/api/runs/{id}/stop"));
                tokio::spawn(async move { c.post(url).send().await.unwrap() });
            }
            true
        })
        .await;
        let sum = &events.last().unwrap()["summary"];
        assert_eq!(sum["interrupted"], true, "{sum}");
        assert_eq!(sum["verdict"], "valid", "{sum}");
        // A page closed while solving: its event stream ends, and so does the solve.
        let (_, r) = post(&c, format!("{base}/api/solve"), json!({ "spec": spec }).to_string()).await;
        let id = r["id"].as_str().unwrap().to_string();
        follow(&base, &id, |e| e["kind"] != "design").await;
        let record = loop {
            let (_, rec) = get(&c, format!("{base}/api/runs/{id}")).await;
            let rec: Value = serde_json::from_str(&rec).unwrap();
            if rec["state"] == "finished" {
                break rec;
            }
            tokio::time::sleep(std::time::Duration::from_millis(100)).await;
        };
        assert_eq!(record["summary"]["interrupted"], true, "{record}");
        assert_eq!(record["summary"]["verdict"], "valid", "{record}");
    });
}

/// The pictures `/api/outputs` lists, as (kind, path).
async fn listed_outputs(c: &Client, base: &str) -> Vec<(String, String)> {
    let (s, list) = get(c, format!("{base}/api/outputs")).await;
    assert_eq!(s, 200);
    let list: Value = serde_json::from_str(&list).unwrap();
    list["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| (o["kind"].as_str().unwrap().to_string(), o["path"].as_str().unwrap().to_string()))
        .collect()
}

#[test]
fn city_layout_and_traffic_pictures_are_listed_and_served_only_under_the_root() {
    let root = tempfile::tempdir().unwrap();
    let city = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0L1 1" data-level="1"/><path d="M1 1L2 2" data-level="3"/></svg>"#;
    for (dir, name, text) in [
        ("out/fig7a", "city.svg", city),
        ("out/traffic/a", "volume.svg", "<svg></svg>"),
        ("out/traffic", "comparison.svg", "<svg></svg>"),
        ("out/lake", "layout.svg", "<svg></svg>"),
        ("out/other", "notes.svg", "<svg></svg>"),
        ("runs/r0001", "city.svg", city),
    ] {
        std::fs::create_dir_all(root.path().join(dir)).unwrap();
        std::fs::write(root.path().join(dir).join(name), text).unwrap();
    }
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let got = listed_outputs(&c, &base).await;
        let want = [
            ("city", "out/fig7a/city.svg"),
            ("layout", "out/lake/layout.svg"),
            ("traffic", "out/traffic/a/volume.svg"),
            ("traffic", "out/traffic/comparison.svg"),
        ];
        assert_eq!(got, want.map(|(k, p)| (k.to_string(), p.to_string())));
        let (s, svg) = get(&c, format!("{base}/api/output?path=out/fig7a/city.svg")).await;
        assert!(s == 200 && svg.contains("data-level=\"3\""), "{s} {svg}");
        for (path, status) in [
            ("out/other/notes.svg", 400),
            ("../city.svg", 403),
            ("runs/r0001/city.svg", 403),
            ("out/missing/city.svg", 404),
        ] {
            let (s, body) = get(&c, format!("{base}/api/output?path={path}")).await;
            assert_eq!(s.as_u16(), status, "{path}: {body}");
        }
    });
}

#[test]
fn grow_pictures_are_listed_only_beside_a_grow_outputs_files() {
    let root = tempfile::tempdir().unwrap();
    for (dir, names) in [
        // A `netspec grow` output with `--every 10`.
        (
            "out/grow/river",
            &["network.json", "series.csv", "network.svg", "network.png", "step-000.svg", "step-010.svg", "step-x.svg"]
                [..],
        ),
        // A `netspec solve` output: its network.svg is not a grow picture.
        ("out/solve/fig2b", &["result.json", "network.svg", "network.png"][..]),
        // A series without the network: not a grow output.
        ("out/half", &["series.csv", "network.svg", "step-000.svg"][..]),
    ] {
        std::fs::create_dir_all(root.path().join(dir)).unwrap();
        for name in names {
            std::fs::write(root.path().join(dir).join(name), "<svg></svg>").unwrap();
        }
    }
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    runtime().block_on(async {
        let c = Client::new();
        let got = listed_outputs(&c, &base).await;
        let want = [
            ("grow", "out/grow/river/network.svg"),
            ("grow", "out/grow/river/step-000.svg"),
            ("grow", "out/grow/river/step-010.svg"),
        ];
        assert_eq!(got, want.map(|(k, p)| (k.to_string(), p.to_string())));
        for (path, status) in [
            ("out/grow/river/step-010.svg", 200),
            ("out/grow/river/network.svg", 200),
            ("out/grow/river/step-020.svg", 404),
            ("out/solve/fig2b/network.svg", 400),
            ("out/half/step-000.svg", 400),
        ] {
            let (s, body) = get(&c, format!("{base}/api/output?path={path}")).await;
            assert_eq!(s.as_u16(), status, "{path}: {body}");
        }
    });
}
