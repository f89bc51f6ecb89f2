//! Nothing found is lost: every design a solve finds on the way — the checked MIP start, then
//! each improving incumbent — is written into the output folder as it arrives (`result.json`
//! with `"status": "running"`, `network.svg`/`.png`), each file by write-then-rename, so a
//! process killed at any moment leaves the last complete design on disk.
//!
//! The solver's threads only hand the point over a channel; a writer thread decodes, draws and
//! writes it (the latest point when several arrived while it was writing).

use crate::design::picture::network_svg;
use crate::design::{Network, Objective};
use crate::formulations::Formulation;
use crate::render::Caption;
use crate::solvers::PointSink;
use crate::spec::Problem;
use serde_json::json;
use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// The `status` of a `result.json` written while the solve goes on.
pub const RUNNING: &str = "running";
/// The `status` of a `result.json` written when the run is over.
pub const FINISHED: &str = "finished";

/// Writes `bytes` to `path` through a temporary file in the same folder renamed over it: a reader
/// (or a process killed meanwhile) sees the old file or the new one, never part of one.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// A point found on the way: the solver's objective and the point.
type Point = (f64, Vec<f64>);

/// The sending side of a running writer: a [`PointSink`] for the backend, closed when the solve
/// is over (points that come later are dropped).
#[derive(Clone)]
pub struct RunningSink(Arc<Mutex<Option<Sender<Point>>>>);

impl RunningSink {
    /// The backend's sink: hands each point to the writer, after `then` (the caller's own sink).
    pub fn point_sink(&self, then: Option<PointSink>) -> PointSink {
        let tx = self.0.clone();
        PointSink(Arc::new(move |objective: f64, x: &[f64]| {
            if let Some(t) = &then {
                (t.0)(objective, x);
            }
            if let Some(tx) = tx.lock().unwrap_or_else(|e| e.into_inner()).as_ref() {
                let _ = tx.send((objective, x.to_vec()));
            }
        }))
    }

    /// No more points: the writer ends once it has written the last one.
    pub fn close(&self) {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).take();
    }
}

/// Starts the writer on a thread of `scope`; it ends after [`RunningSink::close`].
pub fn spawn<'s, 'e: 's>(
    scope: &'s std::thread::Scope<'s, 'e>,
    out: &'e Path,
    p: &'e Problem,
    f: &'e Formulation,
) -> (RunningSink, std::thread::ScopedJoinHandle<'s, ()>) {
    let (tx, rx) = channel();
    let started = Instant::now();
    let handle = scope.spawn(move || write_loop(out, p, f, rx, started));
    (RunningSink(Arc::new(Mutex::new(Some(tx)))), handle)
}

fn write_loop(out: &Path, p: &Problem, f: &Formulation, rx: Receiver<Point>, started: Instant) {
    let mut count = 0usize;
    while let Ok(mut point) = rx.recv() {
        while let Ok(next) = rx.try_recv() {
            point = next;
        }
        count += 1;
        let source = if count == 1 { "first design" } else { "incumbent" };
        // A design that cannot be written now is written with the next one or at the end.
        let _ = write_running(out, p, f, &point, source, started.elapsed().as_secs_f64());
    }
}

/// Writes one design found on the way: `network.png`, `network.svg`, then `result.json`.
fn write_running(
    out: &Path,
    p: &Problem,
    f: &Formulation,
    (solver_objective, x): &Point,
    source: &str,
    seconds: f64,
) -> std::io::Result<()> {
    std::fs::create_dir_all(out)?;
    let net = f.decode(p, x);
    let objective = Objective::of(p, &net);
    let caption = Caption {
        name: p.spec.name.clone(),
        solver: "design found on the way".into(),
        status: RUNNING.into(),
        objective: Some(objective.total),
        gap: None,
        verdict: "not yet checked".into(),
    };
    let placements = f.placements.as_ref().map(|r| r.placements.as_slice());
    let svg = network_svg(p, &net, f.path_sets.as_ref(), placements, &caption);
    if let Ok(png) = crate::render::png(&svg) {
        write_atomic(&out.join("network.png"), &png)?;
    }
    write_atomic(&out.join("network.svg"), svg.as_bytes())?;
    let text = serde_json::to_string_pretty(&running_record(p, &net, &objective, *solver_objective, source, seconds))
        .expect("records serialise");
    write_atomic(&out.join("result.json"), (text + "\n").as_bytes())
}

/// The `result.json` of a run still going: the spec, the design, its recomputed objective.
fn running_record(
    p: &Problem,
    net: &Network,
    objective: &Objective,
    solver_objective: f64,
    source: &str,
    seconds: f64,
) -> serde_json::Value {
    let active_edges = crate::pipeline::result::active_edge_pairs(p, Some(net));
    json!({
        "schema": "netspec.design",
        "schema_version": 2,
        "netspec_version": env!("CARGO_PKG_VERSION"),
        "status": RUNNING,
        "source": source,
        "seconds": seconds,
        "spec": p.spec,
        "active_edges": active_edges,
        "network": net,
        "design_found": true,
        "solver_objective": solver_objective.is_finite().then_some(solver_objective),
        "objective": objective,
    })
}

/// A design left on disk by a run that did not finish: `result.json` with `"status": "running"`.
#[derive(Debug)]
pub struct LeftDesign {
    /// The file.
    pub path: PathBuf,
    /// The design.
    pub network: Network,
    /// Its objective as written (recomputed from the design).
    pub objective: Option<f64>,
}

/// The design an unfinished run left in `dir`, if its `result.json` says `running`.
pub fn left_design(dir: &Path) -> Option<LeftDesign> {
    #[derive(serde::Deserialize)]
    struct View {
        schema: Option<String>,
        status: Option<String>,
        network: Option<Network>,
        objective: Option<Objective>,
    }
    let path = dir.join("result.json");
    let text = std::fs::read_to_string(&path).ok()?;
    let v: View = serde_json::from_str(&text).ok()?;
    if v.schema.as_deref() != Some("netspec.design") || v.status.as_deref() != Some(RUNNING) {
        return None;
    }
    Some(LeftDesign { path, network: v.network?, objective: v.objective.map(|o| o.total) })
}
