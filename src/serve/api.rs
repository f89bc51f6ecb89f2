//! The HTTP API and the page's assets.

use super::error::ApiError;
use super::runs::{self, RunHandle, RunRecord, RunState};
use super::specs::{self, under_root};
use super::ServeOptions;
use axum::body::Bytes;
use axum::extract::{DefaultBodyLimit, Path as UrlPath, Query, State};
use axum::http::header;
use axum::response::sse::{Event as SseEvent, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{json, Value};
use std::collections::{BTreeMap, VecDeque};
use std::path::PathBuf;
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex};

type ApiResult<T> = Result<T, ApiError>;

/// The server's state: the root, the runs, and the solve slots.
pub struct App {
    root: PathBuf,
    runs_dir: PathBuf,
    runs: Mutex<BTreeMap<String, Arc<RunHandle>>>,
    slots: Arc<tokio::sync::Semaphore>,
    per_solve_threads: u32,
    max_cells: usize,
    max_queue: usize,
    max_solves: usize,
    next: Mutex<u64>,
    extracts: super::sites::ExtractCache,
    bin: Option<PathBuf>,
}

impl App {
    /// The state for a root (canonical); reads the runs kept there.
    pub fn new(root: PathBuf, o: &ServeOptions) -> std::io::Result<App> {
        let runs_dir = root.join(specs::RUNS);
        std::fs::create_dir_all(&runs_dir)?;
        let mut runs = BTreeMap::new();
        let mut next = 1;
        for h in runs::load_all(&runs_dir) {
            let id = h.record().id;
            if let Some(n) = id.strip_prefix('r').and_then(|n| n.parse::<u64>().ok()) {
                next = next.max(n + 1);
            }
            runs.insert(id, Arc::new(h));
        }
        Ok(App {
            root,
            runs_dir,
            runs: Mutex::new(runs),
            slots: Arc::new(tokio::sync::Semaphore::new(o.max_solves)),
            per_solve_threads: (o.threads / o.max_solves as u32).max(1),
            max_cells: o.max_cells,
            max_queue: o.max_queue,
            max_solves: o.max_solves,
            next: Mutex::new(next),
            extracts: Default::default(),
            bin: o.netspec_bin.clone(),
        })
    }

    /// Asks every solve to stop (the server is stopping).
    pub fn stop_all(&self) {
        for h in self.runs.lock().unwrap_or_else(|e| e.into_inner()).values() {
            h.interrupt.trigger();
        }
    }

    fn run(&self, id: &str) -> ApiResult<Arc<RunHandle>> {
        self.runs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(id)
            .cloned()
            .ok_or_else(|| ApiError::not_found("id", format!("no run `{id}`")))
    }
}

/// The routes.
pub fn router(app: Arc<App>, max_body: usize) -> Router {
    Router::new()
        .route("/", get(|| async { asset("index.html") }))
        .route("/assets/{name}", get(|UrlPath(name): UrlPath<String>| async move { asset(&name) }))
        .route("/api/specs", get(list_specs))
        .route("/api/spec", get(open_spec))
        .route("/api/thumb", get(thumb))
        .route("/api/new", post(new_spec))
        .route("/api/outputs", get(list_outputs))
        .route("/api/output", get(output))
        .route("/api/check", post(check))
        .route("/api/save", post(save))
        .route("/api/solve", post(solve))
        .route("/api/runs", get(list_runs))
        .route("/api/runs/{id}", get(get_run))
        .route("/api/runs/{id}/events", get(events))
        .route("/api/runs/{id}/stop", post(stop))
        .route("/api/runs/{id}/files/{name}", get(file))
        .route("/api/compare", get(compare))
        .route("/api/extracts", get(list_extracts))
        .route("/api/extract", get(extract_info))
        .route("/api/extract/features", get(extract_features))
        .route("/api/upload", post(upload).layer(DefaultBodyLimit::max(super::sites::MAX_UPLOAD)))
        .route("/api/sites", post(make_site))
        .route("/api/sites/{name}", get(open_site))
        .route("/api/sites/{name}/runs", post(site_run))
        .route("/api/sites/{name}/compare.csv", get(site_csv))
        .route("/api/sites/{name}/designs/{label}", get(site_design))
        .route("/api/runs/{id}/resume", post(resume))
        .route("/api/runs/{id}/out/{name}", get(run_output))
        .fallback(|| async { ApiError::not_found("path", "no such page or endpoint".into()) })
        .layer(DefaultBodyLimit::max(max_body))
        .with_state(app)
}

/// The page's files, embedded in the binary.
fn asset(name: &str) -> Response {
    let (body, kind) = match name {
        "index.html" => (include_str!("assets/index.html"), "text/html; charset=utf-8"),
        "app.js" => (include_str!("assets/app.js"), "text/javascript; charset=utf-8"),
        "app.css" => (include_str!("assets/app.css"), "text/css; charset=utf-8"),
        "sites.js" => (include_str!("assets/sites.js"), "text/javascript; charset=utf-8"),
        "leaflet.js" => (include_str!("assets/vendor/leaflet/leaflet.js"), "text/javascript; charset=utf-8"),
        "leaflet.css" => (include_str!("assets/vendor/leaflet/leaflet.css"), "text/css; charset=utf-8"),
        "LICENSE-leaflet.txt" => (include_str!("assets/vendor/leaflet/LICENSE"), "text/plain; charset=utf-8"),
        _ => return ApiError::not_found("name", format!("no asset `{name}`")).into_response(),
    };
    ([(header::CONTENT_TYPE, kind)], body).into_response()
}

/// Parses a JSON body, naming the field of an error.
fn body<T: serde::de::DeserializeOwned>(bytes: &Bytes) -> ApiResult<T> {
    let de = &mut serde_json::Deserializer::from_slice(bytes);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let field = if path == "." { "body".to_string() } else { path };
        ApiError::bad(&field, format!("malformed request: {}", e.inner()))
    })
}

/// Runs blocking work (spec resolution, rendering, file building) off the async threads.
async fn blocking<T: Send + 'static>(f: impl FnOnce() -> ApiResult<T> + Send + 'static) -> ApiResult<T> {
    tokio::task::spawn_blocking(f).await.map_err(|e| ApiError::internal(format!("the work failed: {e}")))?
}

async fn list_specs(State(app): State<Arc<App>>) -> ApiResult<Json<Value>> {
    let root = app.root.clone();
    let list = blocking(move || Ok(specs::list(&root))).await?;
    Ok(Json(json!({ "specs": list })))
}

async fn list_outputs(State(app): State<Arc<App>>) -> ApiResult<Json<Value>> {
    let root = app.root.clone();
    let list = blocking(move || Ok(specs::outputs(&root))).await?;
    Ok(Json(json!({ "outputs": list })))
}

#[derive(Deserialize)]
struct OutputQuery {
    path: String,
}

/// A city, traffic, layout, field or grow picture under the root (only those, [`specs::picture_kind`]).
async fn output(State(app): State<Arc<App>>, Query(q): Query<OutputQuery>) -> ApiResult<Response> {
    blocking(move || {
        let path = under_root(&app.root, &q.path, "path")?;
        if specs::picture_kind(&path).is_none() {
            return Err(ApiError::bad("path", format!("`{}`: only {} are shown", q.path, specs::shown())));
        }
        let svg = std::fs::read_to_string(&path)
            .map_err(|_| ApiError::not_found("path", format!("no picture `{}` under --root", q.path)))?;
        Ok(([(header::CONTENT_TYPE, "image/svg+xml")], svg).into_response())
    })
    .await
}

/// Where a spec comes from: an example's name or a path under the root.
#[derive(Deserialize)]
struct Source {
    example: Option<String>,
    path: Option<String>,
}

/// Reads the spec `src` names, as TOML text.
fn source_text(app: &App, src: &Source) -> ApiResult<String> {
    match (&src.example, &src.path) {
        (Some(name), None) => Ok(specs::example(name)?.to_string()),
        (None, Some(rel)) => {
            let path = under_root(&app.root, rel, "path")?;
            if !path.is_file() {
                return Err(ApiError::not_found("path", format!("no spec file `{rel}` under --root")));
            }
            std::fs::read_to_string(&path).map_err(|e| ApiError::bad("path", format!("`{rel}`: {e}")))
        }
        _ => Err(ApiError::bad("example", "give either `example` or `path`".into())),
    }
}

async fn open_spec(State(app): State<Arc<App>>, Query(src): Query<Source>) -> ApiResult<Json<Value>> {
    blocking(move || {
        let text = source_text(&app, &src)?;
        let spec = crate::spec::Spec::from_toml(&text).map_err(specs::spec_error)?;
        let p = specs::resolve(&spec, &app.root, app.max_cells)?;
        Ok(Json(json!({ "spec": spec, "toml": text, "view": specs::view(&p) })))
    })
    .await
}

async fn thumb(State(app): State<Arc<App>>, Query(src): Query<Source>) -> ApiResult<Response> {
    blocking(move || {
        let text = source_text(&app, &src)?;
        let spec = crate::spec::Spec::from_toml(&text).map_err(specs::spec_error)?;
        let p = specs::resolve(&spec, &app.root, app.max_cells)?;
        Ok(([(header::CONTENT_TYPE, "image/svg+xml")], specs::view(&p).svg).into_response())
    })
    .await
}

#[derive(Deserialize)]
struct NewSpec {
    width: usize,
    height: usize,
    #[serde(default = "grid")]
    shape: String,
}

fn grid() -> String {
    "grid".into()
}

async fn new_spec(State(app): State<Arc<App>>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let req: NewSpec = body(&bytes)?;
    let value = specs::new_spec(req.width, req.height, &req.shape)?;
    checked(app, value).await
}

#[derive(Deserialize)]
struct SpecBody {
    spec: Value,
}

/// A spec checked as the command line checks it: its TOML and its picture, or the error.
async fn checked(app: Arc<App>, value: Value) -> ApiResult<Json<Value>> {
    blocking(move || {
        let spec = specs::parse_spec(value)?;
        let p = specs::resolve(&spec, &app.root, app.max_cells)?;
        let toml = toml::to_string(&spec).map_err(|e| ApiError::internal(format!("writing TOML: {e}")))?;
        Ok(Json(json!({ "spec": spec, "toml": toml, "view": specs::view(&p) })))
    })
    .await
}

async fn check(State(app): State<Arc<App>>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let req: SpecBody = body(&bytes)?;
    checked(app, req.spec).await
}

#[derive(Deserialize)]
struct SaveBody {
    path: String,
    spec: Value,
}

async fn save(State(app): State<Arc<App>>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let req: SaveBody = body(&bytes)?;
    blocking(move || {
        if !req.path.ends_with(".toml") {
            return Err(ApiError::bad("path", format!("`{}`: a spec is saved as a .toml file", req.path)));
        }
        let path = under_root(&app.root, &req.path, "path")?;
        let spec = specs::parse_spec(req.spec)?;
        specs::resolve(&spec, &app.root, app.max_cells)?;
        let toml = toml::to_string(&spec).map_err(|e| ApiError::internal(format!("writing TOML: {e}")))?;
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(|e| ApiError::bad("path", format!("`{}`: {e}", req.path)))?;
        }
        std::fs::write(&path, toml).map_err(|e| ApiError::bad("path", format!("`{}`: {e}", req.path)))?;
        Ok(Json(json!({ "saved": req.path })))
    })
    .await
}

async fn solve(State(app): State<Arc<App>>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let req: SpecBody = body(&bytes)?;
    let queued = app.runs.lock().unwrap_or_else(|e| e.into_inner()).values().filter(|h| !h.is_over()).count();
    if queued >= app.max_queue + app.max_solves {
        return Err(ApiError::unavailable(format!(
            "{queued} solves are running or queued: try again when one has finished"
        )));
    }
    let app2 = app.clone();
    let (h, problem) = blocking(move || prepare(&app2, req.spec)).await?;
    let id = h.record().id;
    let threads = app.per_solve_threads;
    let max_cells = app.max_cells;
    let slots = app.slots.clone();
    h.push(json!({ "kind": "queued" }));
    tokio::spawn(async move {
        let Ok(_permit) = slots.acquire_owned().await else { return };
        let _ = tokio::task::spawn_blocking(move || runs::solve(&h, problem, threads, max_cells)).await;
    });
    Ok(Json(json!({ "id": id })))
}

/// Checks the spec and its settings, and makes the run's folder with its `spec.toml`.
fn prepare(app: &App, value: Value) -> ApiResult<(Arc<RunHandle>, crate::spec::Problem)> {
    let mut spec = specs::parse_spec(value)?;
    if let Some(t) = spec.solver.threads {
        if t > app.per_solve_threads {
            return Err(ApiError::invalid(
                Some("solver.threads".into()),
                format!("at most {} threads per solve on this server, got {t}", app.per_solve_threads),
            ));
        }
    }
    let p = specs::resolve(&spec, &app.root, app.max_cells)?;
    // The run's spec file sits in the run's folder: a mesh file is named from the root.
    if let Some(file) = &spec.mesh.file {
        spec.mesh.file = Some(app.root.join(file));
    }
    let toml = toml::to_string(&spec).map_err(|e| ApiError::internal(format!("writing TOML: {e}")))?;
    let threads = spec.solver.threads.unwrap_or(app.per_solve_threads);
    let id = {
        let mut n = app.next.lock().unwrap_or_else(|e| e.into_inner());
        let id = format!("r{:04}", *n);
        *n += 1;
        id
    };
    let dir = app.runs_dir.join(&id);
    std::fs::create_dir_all(&dir).map_err(|e| ApiError::internal(format!("making the run's folder: {e}")))?;
    std::fs::write(dir.join("spec.toml"), &toml).map_err(|e| ApiError::internal(format!("writing the spec: {e}")))?;
    let record = RunRecord {
        id: id.clone(),
        name: spec.name.clone(),
        digest: crate::io::digest(&[toml.as_bytes()]),
        created: std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()),
        settings: runs::settings_of(&spec, threads),
        state: RunState::Queued,
        summary: None,
        error: None,
    };
    let h = Arc::new(RunHandle::new(dir, record));
    h.update(|_| {});
    app.runs.lock().unwrap_or_else(|e| e.into_inner()).insert(id, h.clone());
    Ok((h, p))
}

async fn list_runs(State(app): State<Arc<App>>) -> Json<Value> {
    let runs: Vec<RunRecord> =
        app.runs.lock().unwrap_or_else(|e| e.into_inner()).values().map(|h| h.record()).collect();
    Json(json!({ "runs": runs }))
}

async fn get_run(State(app): State<Arc<App>>, UrlPath(id): UrlPath<String>) -> ApiResult<Json<RunRecord>> {
    Ok(Json(app.run(&id)?.record()))
}

async fn stop(State(app): State<Arc<App>>, UrlPath(id): UrlPath<String>) -> ApiResult<Json<Value>> {
    let h = app.run(&id)?;
    h.interrupt.trigger();
    Ok(Json(json!({ "stopping": id })))
}

/// Counts an open event stream; the last one closed while the run is not over stops it (the
/// page was closed).
struct Watcher(Arc<RunHandle>);

impl Drop for Watcher {
    fn drop(&mut self) {
        if self.0.watchers.fetch_sub(1, Ordering::SeqCst) == 1 && !self.0.is_over() {
            self.0.interrupt.trigger();
        }
    }
}

async fn events(State(app): State<Arc<App>>, UrlPath(id): UrlPath<String>) -> ApiResult<impl IntoResponse> {
    let h = app.run(&id)?;
    h.watchers.fetch_add(1, Ordering::SeqCst);
    let rx = h.subscribe();
    let state = (Watcher(h), rx, 0usize, VecDeque::<Value>::new(), false);
    let stream = futures_util::stream::unfold(state, |(w, mut rx, mut next, mut pending, mut ended)| async move {
        loop {
            if let Some(ev) = pending.pop_front() {
                ended |= matches!(ev["kind"].as_str(), Some("done" | "failed"));
                let sse = SseEvent::default().data(ev.to_string());
                return Some((Ok::<_, std::convert::Infallible>(sse), (w, rx, next, pending, ended)));
            }
            if ended {
                return None;
            }
            // Mark the receiver's value seen before reading, so no event is missed.
            rx.borrow_and_update();
            let new = w.0.events_from(next);
            next += new.len();
            pending.extend(new);
            if !pending.is_empty() {
                continue;
            }
            if w.0.is_over() && next == 0 {
                // A run read back from disk has no events: its record says how it ended.
                let r = w.0.record();
                pending.push_back(json!({ "kind": "done", "summary": r.summary, "error": r.error, "state": r.state }));
                ended = true;
                continue;
            }
            if rx.changed().await.is_err() {
                return None;
            }
        }
    });
    Ok(Sse::new(stream).keep_alive(KeepAlive::default()))
}

/// The files of a run that can be fetched.
const FILES: &[(&str, &str)] = &[
    ("result.json", "application/json"),
    ("network.svg", "image/svg+xml"),
    ("network.png", "image/png"),
    ("network.geojson", "application/geo+json"),
    ("spec.toml", "application/toml"),
    ("model.mps", "text/plain"),
    ("model.lp", "text/plain"),
    ("run.json", "application/json"),
];

async fn file(State(app): State<Arc<App>>, UrlPath((id, name)): UrlPath<(String, String)>) -> ApiResult<Response> {
    let h = app.run(&id)?;
    let Some(&(_, kind)) = FILES.iter().find(|(n, _)| *n == name) else {
        let known: Vec<&str> = FILES.iter().map(|(n, _)| *n).collect();
        return Err(ApiError::not_found("name", format!("no file `{name}`: one of {}", known.join(", "))));
    };
    let max_cells = app.max_cells;
    blocking(move || {
        let path = h.dir.join(&name);
        if name.starts_with("model.") && !path.exists() {
            let p = crate::run::load(&h.dir.join("spec.toml"), None, max_cells)
                .map_err(|e| ApiError::internal(e.to_string()))?;
            let f = crate::pipeline::build(&p);
            crate::run::export(&p, &f, &path).map_err(|e| ApiError::internal(e.to_string()))?;
        }
        let bytes = std::fs::read(&path)
            .map_err(|_| ApiError::not_found("name", format!("run `{id}` has no `{name}` (yet)")))?;
        let disposition = format!("inline; filename=\"{id}-{name}\"");
        Ok(([(header::CONTENT_TYPE, kind.to_string()), (header::CONTENT_DISPOSITION, disposition)], bytes)
            .into_response())
    })
    .await
}

#[derive(Deserialize)]
struct CompareQuery {
    ids: String,
}

/// Runs side by side: one row per measurement, one column per run.
async fn compare(State(app): State<Arc<App>>, Query(q): Query<CompareQuery>) -> ApiResult<Json<Value>> {
    let ids: Vec<&str> = q.ids.split(',').map(str::trim).filter(|s| !s.is_empty()).collect();
    if ids.len() < 2 {
        return Err(ApiError::bad("ids", "name two runs or more, separated by commas".into()));
    }
    let records: Vec<RunRecord> = ids.iter().map(|id| app.run(id).map(|h| h.record())).collect::<ApiResult<_>>()?;
    Ok(Json(json!({ "runs": records, "rows": super::runs::compare_rows(&records) })))
}

// --- Real sites (`sites`) ---

async fn list_extracts(State(app): State<Arc<App>>) -> ApiResult<Json<Value>> {
    let root = app.root.clone();
    Ok(Json(blocking(move || Ok(super::sites::list(&root))).await?))
}

#[derive(Deserialize)]
struct ExtractQuery {
    path: String,
    #[serde(default)]
    bbox: Option<String>,
}

/// An extract under the root, read (or from the cache).
fn layers(app: &App, rel: &str) -> ApiResult<Arc<super::sites::Layers>> {
    let path = under_root(&app.root, rel, "path")?;
    if !path.is_file() {
        return Err(ApiError::not_found("path", format!("no extract `{rel}` under --root")));
    }
    app.extracts.get(&path, rel)
}

async fn extract_info(State(app): State<Arc<App>>, Query(q): Query<ExtractQuery>) -> ApiResult<Json<Value>> {
    blocking(move || {
        let l = layers(&app, &q.path)?;
        Ok(Json(json!({ "path": q.path, "extent": l.extent, "nodes": l.extract.nodes.len(),
                        "ways": l.extract.ways.len(), "attribution": crate::osm::ATTRIBUTION })))
    })
    .await
}

async fn extract_features(State(app): State<Arc<App>>, Query(q): Query<ExtractQuery>) -> ApiResult<Json<Value>> {
    blocking(move || {
        let l = layers(&app, &q.path)?;
        let view = match &q.bbox {
            None => l.extent,
            Some(b) => {
                let v: Vec<f64> = b
                    .split(',')
                    .map(|x| x.trim().parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| ApiError::bad("bbox", format!("`{b}`: W,S,E,N in degrees")))?;
                match v[..] {
                    [w, s, e, n] if v.iter().all(|x| x.is_finite()) && w <= e && s <= n => [w, s, e, n],
                    _ => return Err(ApiError::bad("bbox", format!("`{b}`: W,S,E,N with W ≤ E and S ≤ N"))),
                }
            }
        };
        Ok(Json(l.features(view)))
    })
    .await
}

#[derive(Deserialize)]
struct UploadQuery {
    name: String,
}

/// An extract or a GeoJSON site sent by the page, kept as `ROOT/uploads/<name>` once its first
/// bytes say it is OSM XML, OSM PBF or GeoJSON.
async fn upload(State(app): State<Arc<App>>, Query(q): Query<UploadQuery>, bytes: Bytes) -> ApiResult<Json<Value>> {
    blocking(move || {
        let name = q.name.rsplit(['/', '\\']).next().unwrap_or_default().to_string();
        let ok_name = !name.is_empty()
            && !name.starts_with('.')
            && (super::sites::is_extract(&name) || name.ends_with(".geojson"));
        if !ok_name {
            return Err(ApiError::bad("name", format!("`{}`: an upload is a .osm, .osm.pbf or .geojson file", q.name)));
        }
        let head = String::from_utf8_lossy(&bytes[..bytes.len().min(256)]).to_string();
        let pbf = bytes.windows(9).take(64).any(|w| w == b"OSMHeader");
        let xml = head.trim_start().starts_with('<') && head.contains("<osm");
        let json = head.trim_start().starts_with('{');
        if !(pbf || xml || json) {
            return Err(ApiError::invalid(
                Some("body".into()),
                format!("`{name}` is neither an OpenStreetMap extract (OSM PBF or XML) nor GeoJSON"),
            ));
        }
        let dir = app.root.join(super::sites::UPLOADS);
        std::fs::create_dir_all(&dir)
            .map_err(|e| ApiError::internal(format!("making {}: {e}", super::sites::UPLOADS)))?;
        let rel = format!("{}/{name}", super::sites::UPLOADS);
        crate::run::write_atomic(&dir.join(&name), &bytes)
            .map_err(|e| ApiError::internal(format!("writing {rel}: {e}")))?;
        if !json {
            // Read it now, so that a broken extract is refused here and not on the map.
            if let Err(e) = layers(&app, &rel) {
                let _ = std::fs::remove_file(dir.join(&name));
                return Err(e);
            }
        }
        Ok(Json(json!({ "path": rel, "bytes": bytes.len() })))
    })
    .await
}

async fn make_site(State(app): State<Arc<App>>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let req: super::sites::SiteBody = body(&bytes)?;
    blocking(move || super::sites::make(&app.root, &app.extracts, req).map(Json)).await
}

async fn open_site(State(app): State<Arc<App>>, UrlPath(name): UrlPath<String>) -> ApiResult<Json<Value>> {
    blocking(move || {
        let mut v = super::sites::open(&app.root, &name)?;
        let runs: Vec<RunRecord> = app
            .runs
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .values()
            .map(|h| h.record())
            .filter(|r| runs::is_urban(r) && r.settings["site"] == name.as_str())
            .collect();
        v["runs"] = json!(runs);
        Ok(Json(v))
    })
    .await
}

async fn site_run(State(app): State<Arc<App>>, UrlPath(name): UrlPath<String>, bytes: Bytes) -> ApiResult<Json<Value>> {
    let m: super::sites::MethodBody = body(&bytes)?;
    super::sites::check_name(&name)?;
    let site_dir = app.root.join(super::sites::SITES).join(&name);
    if !site_dir.join("site.geojson").is_file() {
        return Err(ApiError::not_found("name", format!("no site `{name}`")));
    }
    let Some(bin) = app.bin.clone() else {
        return Err(ApiError::unavailable("this server has no netspec binary to run methods with".into()));
    };
    let designs = super::sites::designs(&app.root, &name);
    if m.method == "traffic" && designs.is_empty() {
        return Err(ApiError::invalid(
            Some("method".into()),
            "run a design first: traffic compares the designs with the real streets".into(),
        ));
    }
    let id = {
        let mut n = app.next.lock().unwrap_or_else(|e| e.into_inner());
        let id = format!("r{:04}", *n);
        *n += 1;
        id
    };
    let dir = app.runs_dir.join(&id);
    let args = super::sites::command(&site_dir, &dir.join("out"), &m, &designs)?;
    std::fs::create_dir_all(&dir).map_err(|e| ApiError::internal(format!("making the run's folder: {e}")))?;
    let record = RunRecord {
        id: id.clone(),
        name: format!("{name} · {}", m.method),
        digest: crate::io::digest(&[args.join(" ").as_bytes()]),
        created: std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs()),
        settings: json!({ "kind": "urban", "site": name, "method": m.method, "request": m, "args": args }),
        state: RunState::Queued,
        summary: None,
        error: None,
    };
    let h = Arc::new(RunHandle::new(dir, record));
    h.update(|_| {});
    app.runs.lock().unwrap_or_else(|e| e.into_inner()).insert(id.clone(), h.clone());
    start_urban(&app, h, bin, args, site_dir);
    Ok(Json(json!({ "id": id })))
}

/// Queues an urban run on the solve slots.
fn start_urban(app: &Arc<App>, h: Arc<RunHandle>, bin: PathBuf, args: Vec<String>, site_dir: PathBuf) {
    h.push(json!({ "kind": "queued" }));
    let slots = app.slots.clone();
    let root = app.root.clone();
    tokio::spawn(async move {
        let Ok(_permit) = slots.acquire_owned().await else { return };
        let _ = tokio::task::spawn_blocking(move || super::sites::execute(&h, &bin, &args, &site_dir, &root)).await;
    });
}

/// Runs an interrupted, failed or finished urban run again in its folder: `city` resumes the
/// levels it had solved, the others start over.
async fn resume(State(app): State<Arc<App>>, UrlPath(id): UrlPath<String>) -> ApiResult<Json<Value>> {
    let h = app.run(&id)?;
    let rec = h.record();
    if !runs::is_urban(&rec) {
        return Err(ApiError::invalid(Some("id".into()), format!("run `{id}` is a solve: solve its spec again")));
    }
    if !h.is_over() {
        return Err(ApiError::invalid(
            Some("id".into()),
            format!("run `{id}` is still {:?}", rec.state).to_lowercase(),
        ));
    }
    let Some(bin) = app.bin.clone() else {
        return Err(ApiError::unavailable("this server has no netspec binary to run methods with".into()));
    };
    let args: Vec<String> = serde_json::from_value(rec.settings["args"].clone())
        .map_err(|e| ApiError::internal(format!("run `{id}`: {e}")))?;
    let site = rec.settings["site"].as_str().unwrap_or_default().to_string();
    if rec.settings["method"] != "city" {
        let _ = std::fs::remove_dir_all(h.dir.join("out"));
    }
    // A fresh handle: the stop flag and the events start over.
    let fresh = Arc::new(RunHandle::new(h.dir.clone(), RunRecord { state: RunState::Queued, error: None, ..rec }));
    fresh.update(|_| {});
    app.runs.lock().unwrap_or_else(|e| e.into_inner()).insert(id.clone(), fresh.clone());
    start_urban(&app, fresh, bin, args, app.root.join(super::sites::SITES).join(site));
    Ok(Json(json!({ "id": id })))
}

async fn site_csv(State(app): State<Arc<App>>, UrlPath(name): UrlPath<String>) -> ApiResult<Response> {
    blocking(move || {
        let v = super::sites::open(&app.root, &name)?;
        let csv = super::sites::compare_csv(&v["compare"]);
        let disposition = format!("attachment; filename=\"{name}-comparison.csv\"");
        Ok(([(header::CONTENT_TYPE, "text/csv".to_string()), (header::CONTENT_DISPOSITION, disposition)], csv)
            .into_response())
    })
    .await
}

/// A design's streets on the site as WGS 84 GeoJSON (`LABEL.geojson`), from the comparison.
async fn site_design(
    State(app): State<Arc<App>>,
    UrlPath((name, file)): UrlPath<(String, String)>,
) -> ApiResult<Response> {
    blocking(move || {
        let label = file
            .strip_suffix(".geojson")
            .ok_or_else(|| ApiError::not_found("label", format!("`{file}`: ask for LABEL.geojson")))?;
        let v = super::sites::open(&app.root, &name)?;
        let d = v["compare"]["designs"]
            .as_array()
            .into_iter()
            .flatten()
            .find(|d| d["label"] == label)
            .ok_or_else(|| ApiError::not_found("label", format!("site `{name}` has no design `{label}`")))?;
        let mut gj = d["streets"].clone();
        gj["attribution"] = json!(crate::osm::ATTRIBUTION);
        let disposition = format!("attachment; filename=\"{name}-{label}.geojson\"");
        Ok((
            [(header::CONTENT_TYPE, "application/geo+json".to_string()), (header::CONTENT_DISPOSITION, disposition)],
            gj.to_string(),
        )
            .into_response())
    })
    .await
}

/// The files of an urban run's output that can be fetched.
const OUTPUTS: &[(&str, &str)] = &[
    ("layout.json", "application/json"),
    ("layout.geojson", "application/geo+json"),
    ("layout.svg", "image/svg+xml"),
    ("network.json", "application/json"),
    ("network.geojson", "application/geo+json"),
    ("network.svg", "image/svg+xml"),
    ("series.csv", "text/csv"),
    ("city.json", "application/json"),
    ("streets.geojson", "application/geo+json"),
    ("city.svg", "image/svg+xml"),
    ("comparison.json", "application/json"),
    ("comparison.md", "text/markdown"),
    ("comparison.svg", "image/svg+xml"),
];

async fn run_output(
    State(app): State<Arc<App>>,
    UrlPath((id, name)): UrlPath<(String, String)>,
) -> ApiResult<Response> {
    let h = app.run(&id)?;
    let Some(&(_, kind)) = OUTPUTS.iter().find(|(n, _)| *n == name) else {
        let known: Vec<&str> = OUTPUTS.iter().map(|(n, _)| *n).collect();
        return Err(ApiError::not_found("name", format!("no output `{name}`: one of {}", known.join(", "))));
    };
    blocking(move || {
        let bytes = std::fs::read(h.dir.join("out").join(&name))
            .map_err(|_| ApiError::not_found("name", format!("run `{id}` has no `{name}`")))?;
        let disposition = format!("attachment; filename=\"{id}-{name}\"");
        Ok(([(header::CONTENT_TYPE, kind.to_string()), (header::CONTENT_DISPOSITION, disposition)], bytes)
            .into_response())
    })
    .await
}
