//! A real browser on the page: headless Chromium driven over WebDriver (`chromium-driver`, both
//! installed by `scripts/setup.sh browser`, which the test runs). Every wait is on the page's state, never a fixed sleep.

use super::{cli_objective, runtime, server};
use fantoccini::{Client, ClientBuilder, Locator};
use netspec::serve::ServeOptions;
use serde_json::{json, Value};
use std::net::TcpListener;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// chromedriver on a free port, ended with the test.
struct Driver {
    child: Child,
    port: u16,
    profile: tempfile::TempDir,
}

impl Drop for Driver {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start_driver() -> Driver {
    crate::setup_part("browser");
    let port = TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
    let child = Command::new("chromedriver")
        .arg(format!("--port={port}"))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap_or_else(|e| {
            panic!("chromedriver could not be started ({e}): run `scripts/setup.sh browser` (Debian packages chromium and chromium-driver)")
        });
    Driver { child, port, profile: tempfile::tempdir().unwrap() }
}

async fn connect(d: &Driver) -> Client {
    let args = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--disable-dev-shm-usage",
        "--window-size=1500,1100",
    ];
    let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
    args.push(format!("--user-data-dir={}", d.profile.path().display()));
    let caps = json!({ "goog:chromeOptions": { "args": args } });
    let caps = caps.as_object().unwrap().clone();
    let url = format!("http://127.0.0.1:{}", d.port);
    let deadline = Instant::now() + Duration::from_secs(30);
    loop {
        let connector = hyper_util::client::legacy::connect::HttpConnector::new();
        match ClientBuilder::new(connector).capabilities(caps.clone()).connect(&url).await {
            Ok(c) => return c,
            Err(e) if Instant::now() > deadline => panic!("no WebDriver session with chromedriver at {url}: {e}"),
            Err(_) => tokio::time::sleep(Duration::from_millis(200)).await,
        }
    }
}

/// Waits until the JavaScript expression `cond` is true on the page (at most `secs`).
async fn wait_for(c: &Client, cond: &str, secs: u64) {
    let deadline = Instant::now() + Duration::from_secs(secs);
    loop {
        let v = c.execute(&format!("return !!({cond});"), vec![]).await.unwrap();
        if v == Value::Bool(true) {
            return;
        }
        if Instant::now() > deadline {
            let state = c.execute("return document.querySelector('#result').innerText + ' | ' + document.querySelector('#error').innerText + ' | ' + document.querySelector('#run-state').innerText;", vec![]).await.unwrap();
            panic!("waited {secs} s for `{cond}`; the page shows: {state}");
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
}

async fn text(c: &Client, css: &str) -> String {
    c.find(Locator::Css(css)).await.unwrap().text().await.unwrap()
}

async fn checks(c: &Client) -> u64 {
    c.execute("return Number(document.body.dataset.checks || 0);", vec![]).await.unwrap().as_u64().unwrap()
}

/// Types `value` into the field and leaves it, then waits for the server's check.
async fn set_field(c: &Client, field: &str, value: &str) {
    let before = checks(c).await;
    let input = c.find(Locator::Css(&format!("input[data-field='{field}']"))).await.unwrap();
    input.clear().await.unwrap();
    input.send_keys(&format!("{value}\u{E004}")).await.unwrap();
    wait_for(c, &format!("Number(document.body.dataset.checks || 0) > {before}"), 30).await;
}

/// Clicks vertex `v` of the drawn spec and waits for the server's check.
async fn click_vertex(c: &Client, v: usize) {
    let before = checks(c).await;
    c.find(Locator::Css(&format!("#picture .hit-v[data-v='{v}']"))).await.unwrap().click().await.unwrap();
    wait_for(c, &format!("Number(document.body.dataset.checks || 0) > {before}"), 30).await;
}

/// Clicks Solve and waits until the page watches run `id` (so nothing shown is left from the
/// run before).
async fn start_run(c: &Client, id: &str) {
    c.find(Locator::Css("#solve")).await.unwrap().click().await.unwrap();
    wait_for(c, &format!("document.querySelector('#run-state').textContent.startsWith('run {id}:')"), 30).await;
}

/// Solves as run `id` and waits for its end (at most `secs`).
async fn solve_and_wait(c: &Client, id: &str, secs: u64) {
    start_run(c, id).await;
    wait_for(c, "document.querySelector('#result').dataset.state === 'done'", secs).await;
}

#[test]
fn a_browser_edits_solves_stops_explains_and_reloads() {
    let root = tempfile::tempdir().unwrap();
    // A city picture as `netspec city` draws its streets: a path per street, with its level.
    std::fs::create_dir_all(root.path().join("out")).unwrap();
    let city = r#"<svg xmlns="http://www.w3.org/2000/svg" width="100" height="100"><path d="M0 0L90 90" stroke="black" data-level="1"/><path d="M0 90L90 0" stroke="red" data-level="3"/></svg>"#;
    std::fs::write(root.path().join("out/city.svg"), city).unwrap();
    let srv = server(root.path(), 1);
    let base = format!("http://{}", srv.addr());
    let driver = start_driver();
    runtime().block_on(async {
        let c = connect(&driver).await;
        c.goto(&base).await.unwrap();
        // Pick the small spec; its 25 vertices become clickable.
        wait_for(&c, "document.querySelector(\"#specs li[data-id='small.toml']\")", 30).await;
        c.find(Locator::Css("#specs li[data-id='small.toml']")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#picture .hit-v').length === 25", 30).await;
        // A bad value is shown next to its field with the spec code's message.
        set_field(&c, "weights.zigzag", "sometimes").await;
        wait_for(&c, "document.querySelector(\".field-error[data-for='weights.zigzag']\")", 5).await;
        set_field(&c, "weights.zigzag", "0").await;
        wait_for(&c, "!document.querySelector('.field-error')", 5).await;
        // Change a weight and solve: progress, the final design, the CLI's objective.
        set_field(&c, "weights.distance", "2").await;
        solve_and_wait(&c, "r0001", 60).await;
        let updates: u64 = text(&c, "#updates").await.parse().unwrap();
        assert!(updates >= 1, "no progress update shown");
        assert_eq!(text(&c, "#verdict").await, "valid");
        assert!(text(&c, "#status").await.starts_with("optimal"));
        let svg = c.execute("return document.querySelector('#picture svg').outerHTML;", vec![]).await.unwrap();
        assert!(svg.as_str().unwrap().contains("<line"), "no design drawn");
        let spec_file = root.path().join("runs/r0001/spec.toml");
        assert!(std::fs::read_to_string(&spec_file).unwrap().contains("distance = 2.0"));
        let shown: f64 = text(&c, "#objective").await.parse().unwrap();
        let cli = cli_objective(&spec_file);
        assert!((shown - cli).abs() < 1e-4, "page {shown}, CLI {cli}");
        // An infeasible edit: the only sink in a walled corner. The conflict is shown.
        click_vertex(&c, 0).await;
        click_vertex(&c, 6).await;
        click_vertex(&c, 18).await;
        solve_and_wait(&c, "r0002", 90).await;
        assert!(text(&c, "#status").await.starts_with("infeasible"), "{}", text(&c, "#status").await);
        let conflicts = text(&c, "#conflicts").await;
        assert!(conflicts.contains("conflict") && conflicts.contains("coverage"), "{conflicts}");
        // Stop a longer solve once a design is drawn: the best design is kept and valid.
        c.find(Locator::Css("#specs li[data-id='fig2e']")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#picture .hit-v').length === 169", 30).await;
        set_field(&c, "solver.time_limit", "120").await;
        set_field(&c, "solver.threads", "1").await;
        start_run(&c, "r0003").await;
        wait_for(&c, "Number(document.querySelector('#updates').textContent) >= 1", 60).await;
        c.find(Locator::Css("#stop")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelector('#result').dataset.state === 'done'", 60).await;
        assert!(text(&c, "#status").await.starts_with("interrupted"), "{}", text(&c, "#status").await);
        assert_eq!(text(&c, "#verdict").await, "valid");
        let png = c.screenshot().await.unwrap();
        assert_eq!(&png[..4], b"\x89PNG");
        if let Ok(path) = std::env::var("NETSPEC_SERVE_SCREENSHOT") {
            std::fs::write(path, &png).unwrap();
        }
        // A reload shows the earlier runs; two of them side by side.
        c.refresh().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#runs li').length === 3", 30).await;
        for id in ["r0001", "r0003"] {
            c.find(Locator::Css(&format!("#runs li[data-id='{id}'] input"))).await.unwrap().click().await.unwrap();
        }
        c.find(Locator::Css("#compare")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#compare-view img').length === 2", 30).await;
        let table = text(&c, "#compare-view table").await;
        assert!(table.contains("objective") && table.contains("valid"), "{table}");
        // A city output opens with its levels, each toggled on and off.
        c.find(Locator::Css("#outputs li[data-path='out/city.svg'] a")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#levels input').length === 2", 30).await;
        c.find(Locator::Css("#levels input[data-level-toggle='3']")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelector(\"#picture [data-level='3']\").style.display === 'none'", 5).await;
        wait_for(&c, "document.querySelector(\"#picture [data-level='1']\").style.display === ''", 5).await;
        c.close().await.unwrap();
    });
}

/// Sets an input's value by CSS selector (as typing would) and fires its change event.
async fn set_input(c: &Client, css: &str, value: &str) {
    let script =
        "const e = document.querySelector(arguments[0]); e.value = arguments[1]; e.dispatchEvent(new Event('change'));";
    c.execute(script, vec![json!(css), json!(value)]).await.unwrap();
}

/// The state shown for the site's run of `method`.
fn run_state(method: &str, state: &str) -> String {
    format!(
        "Array.from(document.querySelectorAll('#site-runs li')).some(li => li.querySelector('b').textContent.endsWith(' {method}') && li.dataset.state === '{state}')"
    )
}

#[test]
fn a_browser_draws_a_site_runs_the_methods_and_compares_them_with_the_real_streets() {
    use fantoccini::actions::{InputSource, MouseActions, PointerAction, MOUSE_BUTTON_LEFT};
    let root = tempfile::tempdir().unwrap();
    std::fs::write(root.path().join("town.osm"), crate::site::town_xml()).unwrap();
    let opts = ServeOptions {
        root: root.path().to_path_buf(),
        port: 0,
        max_solves: 2,
        threads: 2,
        netspec_bin: Some(env!("CARGO_BIN_EXE_netspec").into()),
        ..Default::default()
    };
    let srv = netspec::serve::Server::start(opts).unwrap();
    let base = format!("http://{}", srv.addr());
    let driver = start_driver();
    super::runtime().block_on(async {
        let c = connect(&driver).await;
        c.goto(&base).await.unwrap();
        c.find(Locator::Css("#tab-sites")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#extracts li').length === 1", 30).await;
        c.find(Locator::Css("#extracts li[data-path='town.osm']")).await.unwrap().click().await.unwrap();
        wait_for(&c, "sites.featuresDrawn >= 1", 30).await;
        // Draw a box by dragging across the middle of the map.
        c.find(Locator::Css("#draw-box")).await.unwrap().click().await.unwrap();
        let map = c.find(Locator::Css("#map")).await.unwrap();
        let drag = MouseActions::new("mouse".into())
            .then(PointerAction::MoveToElement { element: map, duration: None, x: -160, y: -150 })
            .then(PointerAction::Down { button: MOUSE_BUTTON_LEFT })
            .then(PointerAction::MoveBy { duration: Some(Duration::from_millis(200)), x: 150, y: 150 })
            .then(PointerAction::MoveBy { duration: Some(Duration::from_millis(200)), x: 170, y: 150 })
            .then(PointerAction::Up { button: MOUSE_BUTTON_LEFT });
        c.perform_actions(drag).await.unwrap();
        wait_for(&c, "document.querySelector('#site-bbox').value.split(',').length === 4", 10).await;
        set_input(&c, "#site-name", "town").await;
        c.find(Locator::Css("#make-site")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelector('#site-title').textContent === 'Site town'", 60).await;
        assert_eq!(text(&c, "#site-error").await, "");
        // Grow (few steps) and layout: both designs beside the real streets.
        set_input(&c, "[data-m='grow.steps']", "4").await;
        c.find(Locator::Css("[data-method='grow']")).await.unwrap().click().await.unwrap();
        c.find(Locator::Css("[data-method='layout']")).await.unwrap().click().await.unwrap();
        wait_for(&c, &format!("{} && {}", run_state("grow", "finished"), run_state("layout", "finished")), 180).await;
        wait_for(&c, "document.querySelectorAll('#compare-grid .panel').length === 3", 60).await;
        let table = text(&c, "#compare-table").await;
        assert!(table.contains("reference") && table.contains("grown") && table.contains("layout"), "{table}");
        assert_eq!(c.execute("return document.querySelectorAll('#compare-grid svg.rose').length", vec![]).await.unwrap(), json!(3));
        // A city with long levels, cancelled.
        set_input(&c, "[data-m='city.time_limit']", "120").await;
        c.find(Locator::Css("[data-method='city']")).await.unwrap().click().await.unwrap();
        wait_for(&c, &run_state("city", "running"), 60).await;
        let png = c.screenshot().await.unwrap();
        assert_eq!(&png[..4], b"\x89PNG");
        if let Ok(path) = std::env::var("NETSPEC_SERVE_SITES_SCREENSHOT") {
            std::fs::write(path, &png).unwrap();
        }
        c.execute(
            "Array.from(document.querySelectorAll('#site-runs li')).find(li => li.querySelector('b').textContent.endsWith(' city')).querySelector('.cancel').click()",
            vec![],
        )
        .await
        .unwrap();
        wait_for(&c, &run_state("city", "interrupted"), 60).await;
        // A reload finds the site, its runs and its comparison.
        c.refresh().await.unwrap();
        c.find(Locator::Css("#tab-sites")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelectorAll('#sites li').length === 1", 30).await;
        c.find(Locator::Css("#sites li[data-site='town']")).await.unwrap().click().await.unwrap();
        wait_for(&c, &format!("{} && {}", run_state("layout", "finished"), run_state("city", "interrupted")), 30).await;
        wait_for(&c, "document.querySelectorAll('#compare-grid .panel').length === 3", 30).await;
        // A bad box is named on the page, and the server still answers.
        c.find(Locator::Css("#extracts li[data-path='town.osm']")).await.unwrap().click().await.unwrap();
        set_input(&c, "#site-bbox", "12.0,49.0,12.01,49.01").await;
        set_input(&c, "#site-name", "far").await;
        c.find(Locator::Css("#make-site")).await.unwrap().click().await.unwrap();
        wait_for(&c, "document.querySelector('#site-error').textContent.includes('outside the extract')", 30).await;
        c.close().await.unwrap();
    });
}
