//! Runs: every solve the page starts, kept under `ROOT/runs/<id>/` (the spec as TOML, the
//! outputs `netspec solve` writes, and `run.json`), with the events of a running solve for the
//! page's event stream.

use crate::design::picture::network_svg;
use crate::design::{Metrics, Network, Objective};
use crate::render::Caption;
use crate::run::{Design, Event, Incumbent, IncumbentSink, SolveRequest};
use crate::solvers::{Interrupt, Progress, ProgressSink};
use crate::spec::{Problem, Spec};
use serde::{Deserialize, Serialize};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Seconds an infeasible spec's explanation may take when the spec has no time limit (with one,
/// what is left of it).
const EXPLAIN_SECONDS: f64 = 10.0;

/// Where a run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RunState {
    /// Waiting for a free solve slot.
    Queued,
    /// Solving.
    Running,
    /// Finished with a result (whatever its termination).
    Finished,
    /// The solve could not be made (the message says why).
    Failed,
    /// The server stopped while the run was queued or running, before it found a design.
    Lost,
    /// The server stopped (or was killed) while the run was running, after it had found a
    /// design: the last one written, checked by the validator when the server read it back.
    Interrupted,
}

/// A finished run's result, as the page and `compare` show it.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Summary {
    /// The status line: termination, and whether a design was found.
    pub status: String,
    /// The objective.
    pub objective: Option<f64>,
    /// The proven bound.
    pub bound: Option<f64>,
    /// The relative gap.
    pub gap: Option<f64>,
    /// The independent validity verdict (`valid`, `INVALID (n violations)`, `no design`).
    pub verdict: String,
    /// Whether the Stop button (or a closed page) ended the solve.
    pub interrupted: bool,
    /// The design's measurements.
    pub metrics: Option<Metrics>,
    /// For an infeasible spec, the conflicting requirements (`explain`), one line each.
    pub conflicts: Vec<String>,
    /// Wall-clock seconds of the solve.
    pub seconds: f64,
}

/// A run as `run.json` keeps it.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct RunRecord {
    /// The run's id (its folder's name).
    pub id: String,
    /// The spec's name.
    pub name: String,
    /// A digest of the spec's TOML text.
    pub digest: String,
    /// Seconds since the Unix epoch when the run was asked for.
    pub created: u64,
    /// Backend, formulation, time limit and threads.
    pub settings: Value,
    /// Where it is.
    pub state: RunState,
    /// The result, once finished.
    pub summary: Option<Summary>,
    /// Why it failed.
    pub error: Option<String>,
}

/// A run in memory: its record, the stop request, and its events so far.
pub struct RunHandle {
    /// Its folder.
    pub dir: PathBuf,
    /// Stops the solve (keeping the best design).
    pub interrupt: Interrupt,
    record: Mutex<RunRecord>,
    events: Mutex<Vec<Value>>,
    changed: tokio::sync::watch::Sender<usize>,
    started: Instant,
    /// Open event streams.
    pub watchers: AtomicUsize,
}

impl RunHandle {
    /// A new run (queued), or one read back from its folder.
    pub fn new(dir: PathBuf, record: RunRecord) -> RunHandle {
        RunHandle {
            dir,
            interrupt: Interrupt::new(),
            record: Mutex::new(record),
            events: Mutex::new(Vec::new()),
            changed: tokio::sync::watch::channel(0).0,
            started: Instant::now(),
            watchers: AtomicUsize::new(0),
        }
    }

    /// Its record now.
    pub fn record(&self) -> RunRecord {
        self.record.lock().unwrap_or_else(|e| e.into_inner()).clone()
    }

    /// Whether the run is over (finished, failed or lost).
    pub fn is_over(&self) -> bool {
        !matches!(self.record().state, RunState::Queued | RunState::Running)
    }

    /// Events from `from` on.
    pub fn events_from(&self, from: usize) -> Vec<Value> {
        let ev = self.events.lock().unwrap_or_else(|e| e.into_inner());
        ev.get(from..).map(<[Value]>::to_vec).unwrap_or_default()
    }

    /// A receiver told of every new event.
    pub fn subscribe(&self) -> tokio::sync::watch::Receiver<usize> {
        self.changed.subscribe()
    }

    fn seconds(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Appends an event (with its time) and wakes the streams.
    pub fn push(&self, mut event: Value) {
        event["t"] = json!(self.seconds());
        let n = {
            let mut ev = self.events.lock().unwrap_or_else(|e| e.into_inner());
            ev.push(event);
            ev.len()
        };
        self.changed.send_replace(n);
    }

    /// Changes the record and writes `run.json`.
    pub fn update(&self, f: impl FnOnce(&mut RunRecord)) {
        let text = {
            let mut r = self.record.lock().unwrap_or_else(|e| e.into_inner());
            f(&mut r);
            serde_json::to_string_pretty(&*r).expect("records serialise")
        };
        let _ = crate::run::write_atomic(&self.dir.join("run.json"), (text + "\n").as_bytes());
    }
}

/// Every run record kept under `runs`, with its folder, in folder order.
pub fn load_records(runs: &Path) -> Vec<(RunRecord, PathBuf)> {
    let Ok(entries) = std::fs::read_dir(runs) else { return Vec::new() };
    let mut dirs: Vec<PathBuf> = entries.flatten().map(|e| e.path()).filter(|p| p.is_dir()).collect();
    dirs.sort();
    dirs.into_iter()
        .filter_map(|dir| {
            let text = std::fs::read_to_string(dir.join("run.json")).ok()?;
            Some((serde_json::from_str::<RunRecord>(&text).ok()?, dir))
        })
        .collect()
}

/// Whether a record is a run of an urban method on a site (`serve::sites`), not a solve.
pub fn is_urban(rec: &RunRecord) -> bool {
    rec.settings["kind"] == "urban"
}

/// Reads every run kept under `runs`; one left queued or running by a stopped server is
/// `interrupted` with the last design it wrote (validated), or `lost` when it wrote none. A run of
/// an urban method left so is `interrupted`: it is resumed (city) or run again.
pub fn load_all(runs: &Path) -> Vec<RunHandle> {
    let mut out = Vec::new();
    for (mut rec, dir) in load_records(runs) {
        let lost = matches!(rec.state, RunState::Queued | RunState::Running);
        if lost && is_urban(&rec) {
            rec.state = RunState::Interrupted;
            rec.error = Some("the server stopped while it ran".into());
        } else if lost {
            match interrupted_summary(&dir) {
                Some(summary) => {
                    rec.state = RunState::Interrupted;
                    rec.summary = Some(summary);
                }
                None => rec.state = RunState::Lost,
            }
        }
        let h = RunHandle::new(dir, rec);
        if lost {
            h.update(|_| {});
        }
        out.push(h);
    }
    out
}

/// The summary of the design an unfinished run left in `dir` (`result.json` with `"status":
/// "running"), checked by the validator against the run's spec.
fn interrupted_summary(dir: &Path) -> Option<Summary> {
    let left = crate::run::left_design(dir)?;
    let p = crate::run::load(&dir.join("spec.toml"), None, crate::spec::DEFAULT_MAX_CELLS).ok()?;
    if left.network.active.len() != p.mesh.num_edges() {
        return None;
    }
    let f = crate::pipeline::build(&p);
    let violations = crate::design::validate(&p, &left.network, f.path_sets.as_ref());
    let metrics = Metrics::of(&p, &left.network);
    let verdict =
        if violations.is_empty() { "valid".to_string() } else { format!("INVALID ({} violations)", violations.len()) };
    Some(Summary {
        status: format!("interrupted (the server stopped), design found ({} edges)", metrics.edges),
        objective: Some(Objective::of(&p, &left.network).total),
        verdict,
        interrupted: true,
        metrics: Some(metrics),
        ..Summary::default()
    })
}

/// The settings a run is made with, for its record.
pub fn settings_of(spec: &Spec, threads: u32) -> Value {
    json!({
        "solver": spec.solver.name.map_or("highs".to_string(), |k| k.to_string()),
        "formulation": serde_json::to_value(&spec.formulation).unwrap_or(Value::Null),
        "time_limit": spec.solver.time_limit,
        "threads": threads,
    })
}

/// Solves the run's `spec.toml` as `netspec solve` does (on this thread), streaming the start,
/// every improving design and the progress, then the result.
pub fn solve(h: &Arc<RunHandle>, problem: Problem, threads: u32, max_cells: usize) {
    h.update(|r| r.state = RunState::Running);
    h.push(json!({ "kind": "started" }));
    let problem = Arc::new(problem);
    let req = SolveRequest {
        spec: h.dir.join("spec.toml"),
        flags: crate::pipeline::settings::Settings { threads: Some(threads), ..Default::default() },
        out: Some(h.dir.clone()),
        explain: Some(match problem.spec.solver.time_limit.filter(|t| t.is_finite()) {
            Some(_) => crate::run::ExplainBudget::Remaining,
            None => crate::run::ExplainBudget::Seconds(EXPLAIN_SECONDS),
        }),
        interrupt: Some(h.interrupt.clone()),
        progress: Some(progress_sink(h.clone())),
        incumbents: Some(incumbent_sink(h.clone(), problem.clone())),
        max_cells: Some(max_cells),
        ..Default::default()
    };
    let mut on = |e: Event| {
        if let Event::SolveStarted { kind, time_limit, .. } = e {
            let live = kind.instance().is_ok_and(|s| s.capabilities().reports_progress);
            h.push(json!({ "kind": "solving", "solver": kind.to_string(), "time_limit": time_limit, "live": live }));
        }
    };
    match crate::run::solve_spec(&req, &mut on) {
        Ok(solved) => {
            let summary = solved.design.as_ref().map(|d| {
                let mut s = summarize(d);
                s.conflicts = solved.explanation.as_ref().map(|e| e.lines()).unwrap_or_default();
                s.seconds = h.seconds();
                s
            });
            let svg = std::fs::read_to_string(h.dir.join("network.svg")).ok();
            h.update(|r| {
                r.state = RunState::Finished;
                r.summary = summary.clone();
            });
            h.push(json!({ "kind": "done", "summary": summary, "svg": svg }));
        }
        Err(e) => {
            h.update(|r| {
                r.state = RunState::Failed;
                r.error = Some(e.to_string());
            });
            h.push(json!({ "kind": "failed", "error": e.to_string() }));
        }
    }
}

fn progress_sink(h: Arc<RunHandle>) -> ProgressSink {
    ProgressSink(Arc::new(move |p: Progress| {
        h.push(json!({ "kind": "progress", "primal": p.primal, "dual": p.dual, "nodes": p.nodes }));
    }))
}

/// Draws every improving design as it comes (its objective recomputed from the design).
fn incumbent_sink(h: Arc<RunHandle>, p: Arc<Problem>) -> IncumbentSink {
    let best = Mutex::new(f64::INFINITY);
    IncumbentSink(Arc::new(move |inc: Incumbent| {
        let net = Network { active: inc.active, directions: Vec::new(), labels: Vec::new(), rooms: Vec::new() };
        let objective = Objective::of(&p, &net).total;
        {
            let mut b = best.lock().unwrap_or_else(|e| e.into_inner());
            if objective >= *b {
                return;
            }
            *b = objective;
        }
        let caption = Caption {
            name: p.spec.name.clone(),
            solver: "incumbent".into(),
            status: "solving".into(),
            objective: Some(objective),
            gap: None,
            verdict: "not yet checked".into(),
        };
        let svg = network_svg(&p, &net, None, None, &caption);
        h.push(json!({ "kind": "design", "objective": objective, "solver_objective": inc.objective, "svg": svg }));
    }))
}

/// A design run's summary.
pub fn summarize(d: &Design) -> Summary {
    let o = d.outcome();
    let status = match (&o.infeasibility, d.metrics()) {
        _ if o.is_search() => {
            format!("{}, {}", o.termination.label(), if d.network().is_some() { "design found" } else { "no design" })
        }
        (Some(why), _) => format!("{}: {why}", o.termination),
        (None, Some(m)) => format!("{}, design found ({} edges)", o.termination, m.edges),
        (None, None) => format!("{}, no design", o.termination),
    };
    Summary {
        status,
        objective: o.objective,
        bound: o.dual_bound,
        gap: o.gap,
        verdict: d.verdict("no design"),
        interrupted: d.interrupted(),
        metrics: d.metrics().cloned(),
        conflicts: Vec::new(),
        seconds: 0.0,
    }
}

/// The table of runs side by side, as `compare` tabulates solves: a row per measurement (label,
/// then one cell per run).
pub fn compare_rows(records: &[RunRecord]) -> Vec<Vec<String>> {
    type Cell = fn(&RunRecord, &Summary, Option<&Metrics>) -> String;
    let rows: Vec<(&str, Cell)> = vec![
        ("spec", |r, _, _| r.name.clone()),
        ("digest", |r, _, _| r.digest.clone()),
        ("solver", |r, _, _| r.settings["solver"].as_str().unwrap_or("-").to_string()),
        ("status", |_, s, _| s.status.clone()),
        ("objective", |_, s, _| s.objective.map_or("-".into(), |v| format!("{v:.4}"))),
        ("bound", |_, s, _| s.bound.map_or("-".into(), |v| format!("{v:.4}"))),
        ("gap", |_, s, _| s.gap.map_or("-".into(), |g| format!("{:.2}%", 100.0 * g))),
        ("validity", |_, s, _| s.verdict.clone()),
        ("seconds", |_, s, _| format!("{:.2}", s.seconds)),
        ("edges", |_, _, m| m.map_or("-".into(), |m| m.edges.to_string())),
        ("length", |_, _, m| m.map_or("-".into(), |m| format!("{:.2}", m.length))),
        ("dead-ends", |_, _, m| m.map_or("-".into(), |m| m.dead_ends.to_string())),
        ("3-way junctions", |_, _, m| m.map_or("-".into(), |m| m.junctions_3way.to_string())),
        ("4-way junctions", |_, _, m| m.map_or("-".into(), |m| m.junctions_4way.to_string())),
        ("T-junctions", |_, _, m| m.map_or("-".into(), |m| m.t_junctions.to_string())),
        ("zig-zags", |_, _, m| m.map_or("-".into(), |m| m.zigzags.to_string())),
        ("mean travel", |_, _, m| m.map_or("-".into(), |m| format!("{:.3}", m.mean_travel))),
        ("max travel", |_, _, m| m.map_or("-".into(), |m| format!("{:.3}", m.max_travel))),
    ];
    let empty = Summary::default();
    rows.into_iter()
        .map(|(label, cell)| {
            let mut row = vec![label.to_string()];
            for r in records {
                let s = r.summary.as_ref().unwrap_or(&empty);
                row.push(cell(r, s, s.metrics.as_ref()));
            }
            row
        })
        .collect()
}
