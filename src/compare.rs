//! Comparing backends on a set of specs (`netspec compare`): every (instance, backend, seed) is
//! solved in its own child process (`netspec solve`), killed at the time limit plus a grace
//! period, and recorded in its own `run.json` as soon as it ends, so an interrupted comparison
//! resumes where it stopped. Tables (Markdown, CSV) and a per-backend summary follow.

use crate::solvers::Termination;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// One (instance, backend, seed) run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// Instance name (the spec's file stem).
    pub instance: String,
    /// Backend name.
    pub solver: String,
    /// Seed (`None`: the solver's default).
    pub seed: Option<u64>,
    /// Mesh edges.
    pub edges: Option<usize>,
    /// MILP variables, rows and nonzeros.
    pub vars: Option<usize>,
    /// Rows.
    pub rows: Option<usize>,
    /// Nonzeros.
    pub nonzeros: Option<usize>,
    /// Termination label (`optimal`, `limit(time)`, …), `killed` or `failed`.
    pub status: String,
    /// Objective.
    pub objective: Option<f64>,
    /// Dual bound.
    pub dual_bound: Option<f64>,
    /// netspec's gap.
    pub gap: Option<f64>,
    /// Nodes.
    pub nodes: Option<u64>,
    /// Solver time, seconds.
    pub solver_time: Option<f64>,
    /// Wall time of the child process, seconds.
    pub wall_time: f64,
    /// The independent validity verdict.
    pub valid: bool,
    /// Whether the child was killed at limit + grace.
    pub killed: bool,
    /// The solver's version.
    pub solver_version: Option<String>,
    /// The child's exit code.
    pub exit_code: Option<i32>,
    /// The time limit this run had, seconds (with `--paper-limits`, the row's own).
    #[serde(default)]
    pub time_limit: Option<f64>,
}

/// The paper's figures for one instance (Table 1).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PaperRow {
    /// Mesh edges.
    #[serde(default)]
    pub edges: Option<usize>,
    /// Variables.
    #[serde(default)]
    pub variables: Option<usize>,
    /// Gurobi time as printed (street rows: `level2/level3/level4`).
    #[serde(default)]
    pub time: Option<String>,
}

/// One row of a manifest such as `models/table1.toml`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestRow {
    /// The row's name (the paper's figure id).
    pub name: String,
    /// The spec file, relative to the manifest; absent when the row cannot run yet.
    #[serde(default)]
    pub spec: Option<PathBuf>,
    /// Why the row cannot run yet (shown in the table; rows are never dropped silently).
    #[serde(default)]
    pub missing: Option<String>,
    /// The paper's figures.
    #[serde(default)]
    pub paper: PaperRow,
}

/// A manifest: instances with the paper's figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// The rows, in table order.
    pub row: Vec<ManifestRow>,
}

impl Manifest {
    /// Reads a TOML manifest; spec paths become relative to the current directory.
    pub fn load(path: &Path) -> Result<Manifest, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut m: Manifest = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let base = path.parent().unwrap_or(Path::new("."));
        for (i, r) in m.row.iter_mut().enumerate() {
            match (&r.spec, &r.missing) {
                (Some(s), None) => r.spec = Some(base.join(s)),
                (None, Some(_)) => {}
                _ => return Err(format!("{}: row[{i}] ({}): give exactly one of `spec` or `missing`", path.display(), r.name)),
            }
        }
        Ok(m)
    }

    /// A manifest of plain spec files (named by file stem, no paper figures).
    pub fn from_specs(specs: &[PathBuf]) -> Manifest {
        Manifest {
            row: specs.iter().map(|p| ManifestRow { name: instance_name(p), spec: Some(p.clone()), missing: None, paper: PaperRow::default() }).collect(),
        }
    }
}

/// Settings of a comparison.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CompareSettings {
    /// The instances.
    pub manifest: Manifest,
    /// Backend names.
    pub solvers: Vec<String>,
    /// Time limit per run, seconds.
    pub time_limit: f64,
    /// Extra seconds before the child is killed.
    pub grace: f64,
    /// Seeds (empty: one run with the solver's default).
    pub seeds: Vec<u64>,
    /// Threads per run, if set.
    pub threads: Option<u32>,
    /// Give each row the paper's own time for it (a single number in `paper.time`) as its
    /// limit, capped at `time_limit`; rows without one get `time_limit`.
    #[serde(default)]
    pub paper_limits: bool,
}

impl CompareSettings {
    /// The time limit of one row.
    pub fn limit_for(&self, row: &ManifestRow) -> f64 {
        match (self.paper_limits, paper_seconds(&row.paper)) {
            (true, Some(t)) if t > 0.0 => t.min(self.time_limit),
            _ => self.time_limit,
        }
    }
}

fn instance_name(spec: &Path) -> String {
    spec.file_stem().map_or_else(|| "instance".into(), |s| s.to_string_lossy().into_owned())
}

/// Runs every missing (instance, backend, seed) combination; returns all records, in a fixed
/// order. `exe` is the `netspec` binary; `progress` is called after each run.
pub fn run_all(exe: &Path, settings: &CompareSettings, out: &Path, mut progress: impl FnMut(&RunRecord, bool)) -> std::io::Result<Vec<RunRecord>> {
    let seeds: Vec<Option<u64>> = if settings.seeds.is_empty() { vec![None] } else { settings.seeds.iter().map(|&s| Some(s)).collect() };
    let mut records = Vec::new();
    for row in &settings.manifest.row {
        let Some(spec) = &row.spec else { continue };
        for solver in &settings.solvers {
            for &seed in &seeds {
                let name = row.name.clone();
                let dir = out.join("runs").join(format!("{name}__{solver}__{}", seed.map_or("default".into(), |s| s.to_string())));
                let record_path = dir.join("run.json");
                if let Ok(text) = std::fs::read_to_string(&record_path) {
                    if let Ok(r) = serde_json::from_str::<RunRecord>(&text) {
                        progress(&r, true);
                        records.push(r);
                        continue;
                    }
                }
                std::fs::create_dir_all(&dir)?;
                let mut r = run_one(exe, spec, solver, seed, settings, settings.limit_for(row), &dir)?;
                r.instance = name;
                crate::io::write_atomic(&record_path, &(serde_json::to_string_pretty(&r)? + "\n"))?;
                progress(&r, false);
                records.push(r);
            }
        }
    }
    Ok(records)
}

fn run_one(exe: &Path, spec: &Path, solver: &str, seed: Option<u64>, s: &CompareSettings, limit: f64, dir: &Path) -> std::io::Result<RunRecord> {
    let mut cmd = Command::new(exe);
    cmd.arg("solve").arg(spec).args(["--solver", solver, "--time-limit", &limit.to_string(), "--out"]).arg(dir);
    if let Some(seed) = seed {
        cmd.args(["--seed", &seed.to_string()]);
    }
    if let Some(t) = s.threads {
        cmd.args(["--threads", &t.to_string()]);
    }
    cmd.stdin(Stdio::null()).stdout(std::fs::File::create(dir.join("stdout.txt"))?).stderr(std::fs::File::create(dir.join("stderr.txt"))?);
    let _ = std::fs::remove_file(dir.join("result.json"));
    let t0 = Instant::now();
    let mut child = cmd.spawn()?;
    let deadline = Duration::from_secs_f64(limit + s.grace);
    let mut killed = false;
    let status = loop {
        if let Some(st) = child.try_wait()? {
            break Some(st);
        }
        if t0.elapsed() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            killed = true;
            break None;
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let wall_time = t0.elapsed().as_secs_f64();
    let result: Option<ResultView> =
        std::fs::read_to_string(dir.join("result.json")).ok().and_then(|t| serde_json::from_str(&t).ok());
    let mut r = RunRecord {
        instance: instance_name(spec),
        solver: solver.to_string(),
        seed,
        edges: None,
        vars: None,
        rows: None,
        nonzeros: None,
        status: if killed { "killed".into() } else { "failed".into() },
        objective: None,
        dual_bound: None,
        gap: None,
        nodes: None,
        solver_time: None,
        wall_time,
        valid: false,
        killed,
        solver_version: None,
        exit_code: status.and_then(|s| s.code()),
        time_limit: Some(limit),
    };
    if let (Some(res), false) = (result, killed) {
        r.edges = Some(res.mesh.num_edges());
        r.vars = Some(res.model_stats.vars);
        r.rows = Some(res.model_stats.rows);
        r.nonzeros = Some(res.model_stats.nonzeros);
        r.status = res.solve.termination.label();
        r.objective = res.solve.objective;
        r.dual_bound = res.solve.dual_bound;
        r.gap = res.solve.gap;
        r.nodes = res.solve.nodes;
        r.solver_time = res.solve.solver_time;
        r.valid = res.validity.valid;
        r.solver_version = Some(res.solve.solver_version);
    }
    Ok(r)
}

/// What a run record needs from a `result.json`: the fields a MILP solve's
/// [`crate::pipeline::DesignResult`] and a search's [`crate::heuristics::run::SearchResult`]
/// share.
#[derive(Deserialize)]
struct ResultView {
    mesh: crate::mesh::Mesh,
    model_stats: crate::milp::ModelStats,
    solve: SolveView,
    validity: ValidityView,
}

#[derive(Deserialize)]
struct SolveView {
    termination: Termination,
    objective: Option<f64>,
    dual_bound: Option<f64>,
    gap: Option<f64>,
    nodes: Option<u64>,
    solver_time: Option<f64>,
    solver_version: String,
}

#[derive(Deserialize)]
struct ValidityView {
    valid: bool,
}

/// Shifted geometric mean `exp(mean(ln(t + shift))) − shift` (the MIPLIB convention).
pub fn shifted_geometric_mean(times: &[f64], shift: f64) -> f64 {
    if times.is_empty() {
        return 0.0;
    }
    (times.iter().map(|t| (t + shift).ln()).sum::<f64>() / times.len() as f64).exp() - shift
}

/// Per-backend summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BackendSummary {
    /// Backend name.
    pub solver: String,
    /// Shifted geometric mean of time (shift 10 s; runs not proven optimal charged the limit).
    pub sgm_time: f64,
    /// Runs proven optimal (or infeasible) with a valid answer where there is one.
    pub solved: usize,
    /// Runs.
    pub runs: usize,
    /// Instances where this backend was the fastest to solve.
    pub wins: usize,
}

fn solved(r: &RunRecord) -> bool {
    (r.status == "optimal" && r.valid) || r.status == "infeasible"
}

/// Summaries per backend, in the order of `solvers`.
pub fn summarize(records: &[RunRecord], solvers: &[String], limit: f64) -> Vec<BackendSummary> {
    let mut instances: Vec<&str> = records.iter().map(|r| r.instance.as_str()).collect();
    instances.dedup();
    solvers
        .iter()
        .map(|s| {
            let mine: Vec<&RunRecord> = records.iter().filter(|r| &r.solver == s).collect();
            let times: Vec<f64> = mine
                .iter()
                .map(|r| {
                    let limit = r.time_limit.unwrap_or(limit);
                    if solved(r) {
                        r.wall_time.min(limit)
                    } else {
                        limit
                    }
                })
                .collect();
            let wins = instances
                .iter()
                .filter(|i| {
                    let best = records
                        .iter()
                        .filter(|r| r.instance == **i && solved(r))
                        .min_by(|a, b| a.wall_time.total_cmp(&b.wall_time));
                    best.is_some_and(|b| &b.solver == s)
                })
                .count();
            BackendSummary { solver: s.clone(), sgm_time: shifted_geometric_mean(&times, 10.0), solved: mine.iter().filter(|r| solved(r)).count(), runs: mine.len(), wins }
        })
        .collect()
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".into(), |v| format!("{v:.digits$}"))
}

/// The results table as Markdown: one row per manifest row (missing ones with their reason),
/// the paper's edges, variables and time beside ours, per backend time / status / gap.
pub fn markdown(manifest: &Manifest, records: &[RunRecord], solvers: &[String], summary: &[BackendSummary]) -> String {
    let mut s = String::from("| instance | edges (paper) | vars (paper) | paper time |");
    for b in solvers {
        let _ = write!(s, " {b} |");
    }
    s.push_str(" best objective |\n|---|---|---|---|");
    for _ in solvers {
        s.push_str("---|");
    }
    s.push_str("---|\n");
    let num = |v: Option<usize>| v.map_or("-".to_string(), |e| e.to_string());
    for row in &manifest.row {
        let i = row.name.as_str();
        let p = &row.paper;
        let rows: Vec<&RunRecord> = records.iter().filter(|r| r.instance == i).collect();
        let paper_time = p.time.clone().unwrap_or_else(|| "-".into());
        if let Some(why) = &row.missing {
            let _ = write!(s, "| {i} | - ({}) | - ({}) | {paper_time} |", num(p.edges), num(p.variables));
            for _ in solvers {
                s.push_str(" missing |");
            }
            let _ = writeln!(s, " missing: {why} |");
            continue;
        }
        let (edges, vars) = rows.first().map_or((None, None), |r| (r.edges, r.vars));
        let _ = write!(s, "| {i} | {} ({}) | {} ({}) | {paper_time} |", num(edges), num(p.edges), num(vars), num(p.variables));
        for b in solvers {
            match rows.iter().find(|r| &r.solver == b) {
                Some(r) => {
                    let _ = write!(s, " {:.2} s {}{} gap {} |", r.wall_time, r.status, if r.valid { "" } else { " (invalid)" }, opt(r.gap.map(|g| g * 100.0), 1));
                }
                None => s.push_str(" - |"),
            }
        }
        let best = rows.iter().filter(|r| r.valid).filter_map(|r| r.objective).fold(f64::INFINITY, f64::min);
        let _ = writeln!(s, " {} |", if best.is_finite() { format!("{best:.4}") } else { "-".into() });
    }
    s.push_str("\n| backend | sgm time (shift 10 s) | solved | wins |\n|---|---|---|---|\n");
    for b in summary {
        let _ = writeln!(s, "| {} | {:.2} s | {}/{} | {} |", b.solver, b.sgm_time, b.solved, b.runs, b.wins);
    }
    s.push_str(
        "\nFigures: `profile.svg`, the performance profile (fraction solved within time, per backend); \
         `bars.svg`, solver time per instance and backend (log scale; hatched: not solved, with the \
         status and gap; the dashed line is the time limit, the diamond the paper's Gurobi time).\n",
    );
    s
}

/// The records as CSV.
pub fn csv(records: &[RunRecord]) -> String {
    let mut s = String::from("instance,solver,seed,edges,vars,rows,nonzeros,status,objective,dual_bound,gap,nodes,solver_time,wall_time,valid,killed\n");
    for r in records {
        let o = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
        let u = |v: Option<usize>| v.map_or(String::new(), |v| v.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.instance,
            r.solver,
            r.seed.map_or(String::new(), |v| v.to_string()),
            u(r.edges),
            u(r.vars),
            u(r.rows),
            u(r.nonzeros),
            r.status,
            o(r.objective),
            o(r.dual_bound),
            o(r.gap),
            r.nodes.map_or(String::new(), |v| v.to_string()),
            o(r.solver_time),
            r.wall_time,
            r.valid,
            r.killed
        );
    }
    s
}

/// A performance profile as SVG: for each backend, the fraction of runs solved (optimal and
/// valid, or infeasible) within time t, for t from 0 to the limit (log scale from 0.01 s).
pub fn performance_profile_svg(records: &[RunRecord], solvers: &[String], limit: f64) -> String {
    let (w, h, left, bottom, top, right) = (640.0, 400.0, 60.0, 50.0, 30.0, 130.0);
    let (pw, ph) = (w - left - right, h - top - bottom);
    let t0 = 0.01f64;
    let limit = limit.max(t0 * 10.0);
    let x = |t: f64| left + pw * ((t.max(t0) / t0).ln() / (limit / t0).ln()).clamp(0.0, 1.0);
    let y = |f: f64| top + ph * (1.0 - f);
    let mut s = format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="DejaVu Sans, sans-serif" font-size="11">"#);
    s.push_str("\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    let _ = writeln!(s, r##"<text x="{left}" y="18" font-size="13" font-weight="bold">Performance profile: fraction solved within time</text>"##);
    let _ = writeln!(s, r##"<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##);
    let mut tick = t0;
    while tick <= limit * 1.0001 {
        let _ = writeln!(s, r##"<line x1="{0:.1}" y1="{top}" x2="{0:.1}" y2="{1:.1}" stroke="#eee"/><text x="{0:.1}" y="{2:.1}" text-anchor="middle">{3}</text>"##, x(tick), top + ph, top + ph + 16.0, tick);
        tick *= 10.0;
    }
    for k in 0..=4 {
        let f = k as f64 / 4.0;
        let _ = writeln!(s, r##"<text x="{:.1}" y="{:.1}" text-anchor="end">{:.0}%</text>"##, left - 6.0, y(f) + 4.0, f * 100.0);
    }
    let _ = writeln!(s, r##"<text x="{:.1}" y="{:.1}" text-anchor="middle">time (s, log scale; limit {limit} s)</text>"##, left + pw / 2.0, h - 10.0);
    for (i, b) in solvers.iter().enumerate() {
        let mine: Vec<&RunRecord> = records.iter().filter(|r| &r.solver == b).collect();
        if mine.is_empty() {
            continue;
        }
        let mut times: Vec<f64> = mine.iter().filter(|r| solved(r)).map(|r| r.wall_time).collect();
        times.sort_by(f64::total_cmp);
        let n = mine.len() as f64;
        let mut pts = vec![format!("{:.1},{:.1}", x(t0), y(0.0))];
        for (k, t) in times.iter().enumerate() {
            pts.push(format!("{:.1},{:.1}", x(*t), y(k as f64 / n)));
            pts.push(format!("{:.1},{:.1}", x(*t), y((k + 1) as f64 / n)));
        }
        pts.push(format!("{:.1},{:.1}", x(limit), y(times.len() as f64 / n)));
        let c = solver_color(i);
        let _ = writeln!(s, r#"<polyline class="profile" data-solver="{b}" points="{}" fill="none" stroke="{c}" stroke-width="2"/>"#, pts.join(" "));
        let ly = top + 14.0 + i as f64 * 18.0;
        let _ = writeln!(s, r#"<line x1="{:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{c}" stroke-width="3"/><text x="{:.1}" y="{:.1}">{b}</text>"#, w - right + 10.0, w - right + 30.0, w - right + 36.0, ly + 4.0);
    }
    s.push_str("</svg>\n");
    s
}

/// The colour of the `i`-th backend (in the order of the `solvers` list) in every figure.
fn solver_color(i: usize) -> &'static str {
    const COLORS: [&str; 6] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"];
    COLORS[i % COLORS.len()]
}

/// Escapes text for an SVG attribute or text node.
fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// The paper's time for a row, in seconds, when it is a single number (`"132"`); `None` for
/// per-level times (`"379/366/49"`), `"-"` or no time.
pub fn paper_seconds(p: &PaperRow) -> Option<f64> {
    p.time.as_deref()?.trim().parse::<f64>().ok().filter(|t| t.is_finite() && *t >= 0.0)
}

/// The time a bar shows for one run: the solver's own time, or the child's wall time when the
/// run reports none (killed, failed).
fn bar_time(r: &RunRecord) -> f64 {
    r.solver_time.unwrap_or(r.wall_time)
}

/// A short label for a run that is not solved (or is solved without an optimum): `killed`,
/// `failed`, `invalid`, `infeasible`, or the status with the gap (`limit(time) 12.5%`).
fn run_label(r: &RunRecord) -> Option<String> {
    if r.killed {
        return Some("killed".into());
    }
    if r.status == "optimal" {
        return (!r.valid).then(|| "invalid".into());
    }
    Some(match r.gap {
        Some(g) if r.status != "failed" => format!("{} {:.1}%", r.status, g * 100.0),
        _ => r.status.clone(),
    })
}

/// `10^k` as text without round-off (`0.001`, `1`, `1000`).
fn pow10_label(k: i32) -> String {
    if k >= 0 {
        format!("1{}", "0".repeat(k as usize))
    } else {
        format!("0.{}1", "0".repeat((-k - 1) as usize))
    }
}

/// A grouped bar chart as SVG: one group per manifest row that has a spec (`<g class="instance"
/// data-instance=…>`), one bar per backend in each (`<rect class="bar" data-instance=…
/// data-solver=… data-status=…>`), coloured as in [`performance_profile_svg`]. A bar's height is
/// the solver's own time on a log scale (the child's wall time for runs that report none); with
/// several seeds, the lower median, with a whisker from the fastest to the slowest seed. Runs not
/// solved (see [`summarize`]) are hatched and labelled with their status and gap; killed runs
/// also get a red cross, failed ones a dashed outline. The time limit is a dashed line; the
/// paper's Gurobi time, where the manifest gives one number, a diamond. Rows without a spec are
/// listed under the chart. The output depends only on the arguments.
pub fn bar_chart_svg(manifest: &Manifest, records: &[RunRecord], solvers: &[String], limit: f64) -> String {
    let rows: Vec<&ManifestRow> = manifest.row.iter().filter(|r| r.spec.is_some()).collect();
    let limit = if limit.is_finite() && limit > 0.0 { limit } else { 1.0 };
    let runs_of = |instance: &str, solver: &str| -> Vec<&RunRecord> {
        records.iter().filter(|r| r.instance == instance && r.solver == solver).collect()
    };
    // The axis: whole decades around every time shown (bars, limit, paper).
    let shown = records
        .iter()
        .filter(|r| rows.iter().any(|row| row.name == r.instance) && solvers.contains(&r.solver))
        .map(bar_time)
        .chain(rows.iter().filter_map(|row| paper_seconds(&row.paper)))
        .chain(std::iter::once(limit));
    let (tmin, tmax) = shown.fold((f64::INFINITY, 0.0f64), |(lo, hi), t| (if t > 0.0 { lo.min(t) } else { lo }, hi.max(t)));
    let lo_exp = tmin.max(1e-3).log10().floor() as i32;
    let hi_exp = (tmax.log10().ceil() as i32).max(lo_exp + 1);
    let (lo, hi) = (10f64.powi(lo_exp), 10f64.powi(hi_exp));

    let ns = solvers.len().max(1) as f64;
    let bar_w = 12.0;
    let group_w = ns * bar_w + 14.0;
    let (left, right, top, bottom, ph) = (60.0, 190.0, 40.0, 90.0, 300.0);
    let pw = (rows.len() as f64 * group_w).max(200.0);
    let (w, h) = (left + pw + right, top + ph + bottom);
    let y = |t: f64| top + ph * (1.0 - (t.clamp(lo, hi).log10() - lo_exp as f64) / (hi_exp - lo_exp) as f64);
    let base = top + ph;

    let mut s = format!(r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" font-family="DejaVu Sans, sans-serif" font-size="11">"#);
    s.push_str("\n<defs>\n");
    for i in 0..solvers.len() {
        let c = solver_color(i);
        let _ = writeln!(
            s,
            r#"<pattern id="hatch-{i}" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="{c}" fill-opacity="0.2"/><line x1="1.5" y1="0" x2="1.5" y2="6" stroke="{c}" stroke-width="2"/></pattern>"#
        );
    }
    s.push_str("</defs>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    let _ = writeln!(s, r##"<text x="{left}" y="20" font-size="13" font-weight="bold">Solver time per instance and backend</text>"##);
    let _ = writeln!(s, r##"<rect x="{left}" y="{top}" width="{pw:.1}" height="{ph}" fill="none" stroke="#888"/>"##);
    for k in lo_exp..=hi_exp {
        let ty = y(10f64.powi(k));
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{ty:.1}" x2="{:.1}" y2="{ty:.1}" stroke="#eee"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            left + pw,
            left - 6.0,
            ty + 4.0,
            pow10_label(k)
        );
    }
    let _ = writeln!(
        s,
        r##"<text transform="translate(16 {:.1}) rotate(-90)" text-anchor="middle">solver time (s, log scale)</text>"##,
        top + ph / 2.0
    );

    for (g, row) in rows.iter().enumerate() {
        let name = xml_escape(&row.name);
        let gx = left + g as f64 * group_w + 7.0;
        let _ = writeln!(s, r#"<g class="instance" data-instance="{name}">"#);
        for (i, b) in solvers.iter().enumerate() {
            let runs = runs_of(&row.name, b);
            if runs.is_empty() {
                continue;
            }
            let c = solver_color(i);
            let x0 = gx + i as f64 * bar_w;
            let mut times: Vec<f64> = runs.iter().map(|r| bar_time(r)).collect();
            times.sort_by(f64::total_cmp);
            let t = times[(times.len() - 1) / 2];
            let all_solved = runs.iter().all(|r| solved(r));
            // The run that explains the bar: the first not solved, else the first.
            let shown = runs.iter().find(|r| !solved(r)).unwrap_or(&runs[0]);
            let failed = shown.status == "failed" && !shown.killed;
            let top_y = y(t).min(base - 1.0);
            let fill = if all_solved {
                format!(r#"fill="{c}""#)
            } else if failed {
                format!(r#"fill="none" stroke="{c}" stroke-dasharray="3 2""#)
            } else {
                format!(r#"fill="url(#hatch-{i})" stroke="{c}" stroke-width="0.8""#)
            };
            let status = if shown.killed { "killed" } else { shown.status.as_str() };
            let _ = writeln!(
                s,
                r#"<rect class="bar" data-instance="{name}" data-solver="{b}" data-status="{status}" data-solved="{all_solved}" data-time="{t}" x="{:.1}" y="{top_y:.1}" width="{:.1}" height="{:.1}" {fill}><title>{name} / {b}: {} in {t:.3} s</title></rect>"#,
                x0 + 1.0,
                bar_w - 2.0,
                base - top_y,
                xml_escape(&shown.status),
            );
            if times.len() > 1 {
                let cx = x0 + bar_w / 2.0;
                let _ = writeln!(
                    s,
                    r##"<line class="whisker" x1="{cx:.1}" y1="{:.1}" x2="{cx:.1}" y2="{:.1}" stroke="#333"/>"##,
                    y(times[0]),
                    y(times[times.len() - 1])
                );
            }
            if shown.killed {
                let (cx, cy) = (x0 + bar_w / 2.0, top_y - 5.0);
                let _ = writeln!(
                    s,
                    r##"<path class="killed" d="M{:.1} {:.1}L{:.1} {:.1}M{:.1} {:.1}L{:.1} {:.1}" stroke="#c00" stroke-width="2"/>"##,
                    cx - 3.5,
                    cy - 3.5,
                    cx + 3.5,
                    cy + 3.5,
                    cx - 3.5,
                    cy + 3.5,
                    cx + 3.5,
                    cy - 3.5
                );
            }
            let unsolved = runs.iter().filter(|r| !solved(r)).count();
            let label = run_label(shown).map(|l| if runs.len() > 1 && unsolved > 0 { format!("{unsolved}/{} {l}", runs.len()) } else { l });
            if let Some(l) = label {
                let _ = writeln!(
                    s,
                    r#"<text class="label" transform="translate({:.1} {:.1}) rotate(-90)" font-size="9" paint-order="stroke" stroke="white" stroke-width="2.5">{}</text>"#,
                    x0 + bar_w / 2.0 + 3.0,
                    base - 4.0,
                    xml_escape(&l)
                );
            }
        }
        if let Some(p) = paper_seconds(&row.paper) {
            let (cx, cy, hw) = (gx + ns * bar_w / 2.0, y(p), ns * bar_w / 2.0);
            let _ = writeln!(
                s,
                r##"<g class="paper" data-instance="{name}" data-time="{p}"><line x1="{:.1}" y1="{cy:.1}" x2="{:.1}" y2="{cy:.1}" stroke="#000" stroke-width="1"/><path d="M{cx:.1} {:.1}L{:.1} {cy:.1}L{cx:.1} {:.1}L{:.1} {cy:.1}Z" fill="#000"/></g>"##,
                cx - hw,
                cx + hw,
                cy - 4.5,
                cx + 4.5,
                cy + 4.5,
                cx - 4.5
            );
        }
        let _ = writeln!(
            s,
            r#"<text transform="translate({:.1} {:.1}) rotate(-40)" text-anchor="end">{name}</text>"#,
            gx + ns * bar_w / 2.0 + 3.0,
            base + 14.0
        );
        s.push_str("</g>\n");
    }

    let ly = y(limit);
    let _ = writeln!(
        s,
        r##"<line class="limit" x1="{left}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="#000" stroke-dasharray="6 4"/><text x="{:.1}" y="{:.1}" text-anchor="end" paint-order="stroke" stroke="white" stroke-width="3">limit {limit} s</text>"##,
        left + pw,
        left + pw - 4.0,
        ly - 4.0
    );

    // Legend.
    let lx = left + pw + 14.0;
    let mut row_y = top + 24.0;
    for (i, b) in solvers.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<rect x="{lx:.1}" y="{:.1}" width="12" height="10" fill="{}"/><text x="{:.1}" y="{row_y:.1}">{b}</text>"#,
            row_y - 9.0,
            solver_color(i),
            lx + 18.0
        );
        row_y += 16.0;
    }
    row_y += 6.0;
    let legend = [
        (r##"<rect x="{X}" y="{Y}" width="12" height="10" fill="url(#hatch-0)" stroke="#1f77b4" stroke-width="0.8"/>"##, "not solved (status, gap)"),
        (r##"<rect x="{X}" y="{Y}" width="12" height="10" fill="none" stroke="#1f77b4" stroke-dasharray="3 2"/>"##, "failed"),
        (r##"<path d="M{X} {Y}l10 10m-10 0l10 -10" stroke="#c00" stroke-width="2"/>"##, "killed at limit + grace"),
        (r##"<line x1="{X}" y1="{YM}" x2="{X12}" y2="{YM}" stroke="#000" stroke-dasharray="6 4"/>"##, "time limit"),
        (r##"<path d="M{X6} {Y}l5 5l-5 5l-5 -5z" fill="#000"/>"##, "paper (Gurobi 2014)"),
    ];
    for (shape, text) in legend {
        let shape = shape
            .replace("{X12}", &format!("{:.1}", lx + 12.0))
            .replace("{X6}", &format!("{:.1}", lx + 6.0))
            .replace("{X}", &format!("{lx:.1}"))
            .replace("{YM}", &format!("{:.1}", row_y - 4.0))
            .replace("{Y}", &format!("{:.1}", row_y - 9.0));
        let _ = writeln!(s, r#"{shape}<text x="{:.1}" y="{row_y:.1}">{text}</text>"#, lx + 18.0);
        row_y += 16.0;
    }
    let missing: Vec<String> = manifest.row.iter().filter(|r| r.spec.is_none()).map(|r| xml_escape(&r.name)).collect();
    if !missing.is_empty() {
        let _ = writeln!(s, r#"<text x="{left}" y="{:.1}">Not shown (no spec yet): {}</text>"#, h - 8.0, missing.join(", "));
    }
    s.push_str("</svg>\n");
    s
}
