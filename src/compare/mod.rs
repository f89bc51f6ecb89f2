//! Comparing backends on a set of specs (`netspec compare`): every (instance, backend, seed) is
//! solved in its own child process (`netspec solve`), killed at the time limit plus a grace
//! period, and recorded in its own `run.json` as soon as it ends, so an interrupted comparison
//! resumes where it stopped. Tables (Markdown, CSV) and a per-backend summary follow.
//!
//! Instances are named by their paths (the shortest trailing part that tells them apart:
//! `fig1b/L2/spec` and `fig7e/L2/spec`), so no two share records. Every record carries the
//! settings that produced it ([`RunSettings`]); a rerun reuses a record only when they match.
//! On Linux a child dies with the comparison (`PR_SET_PDEATHSIG`), so killing the parent never
//! leaves a solve running.

use crate::render::{
    self,
    chart::{Bar, BarChart, BarGroup, ProfileSeries},
};
use crate::solvers::Termination;

pub mod cluster;
pub mod makespan;
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
    /// Why the run failed (`failed`: the child's error message, from its `stderr.txt`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Everything that produced this record; a rerun with other settings solves again.
    /// (`None` in records written before settings were recorded: they are always solved again.)
    #[serde(default)]
    pub settings: Option<RunSettings>,
    /// Digest of the netspec binary that ran it, for runs on a cluster (the staged copy).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub binary_digest: Option<String>,
    /// The Slurm state of a cluster task that ended without a record (`TIMEOUT`, `NODE_FAIL`,
    /// `OUT_OF_MEMORY`, `CANCELLED`, `PREEMPTED`, …); such a run is solved again on resume.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slurm_state: Option<String>,
}

/// The settings that produced a run: a record is reused only when all of them are the same.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunSettings {
    /// The spec file, as given.
    pub spec: PathBuf,
    /// Digest of the spec file's bytes (and of its mesh file's, if it names one).
    pub spec_digest: String,
    /// The spec's `formulation` (its TOML/JSON value as text), if it sets one.
    pub formulation: Option<String>,
    /// Backend.
    pub solver: String,
    /// Seed (`None`: the solver's default).
    pub seed: Option<u64>,
    /// Threads (`None`: the solver's default).
    pub threads: Option<u32>,
    /// Time limit, seconds.
    pub time_limit: f64,
    /// The netspec version that ran it.
    pub netspec_version: String,
    /// A MILP backend's MIP start: `heuristic` (the default) or `none` (`--no-start`); `None`
    /// for the searches, and in records made before starts existed (they run again).
    #[serde(default)]
    pub start: Option<String>,
}

impl RunSettings {
    /// The settings of one run of `spec`. A spec that cannot be read gets an empty digest (its
    /// run fails, and is tried again next time).
    pub fn new(spec: &Path, solver: &str, seed: Option<u64>, threads: Option<u32>, time_limit: f64) -> RunSettings {
        let bytes = std::fs::read(spec).unwrap_or_default();
        let text = String::from_utf8_lossy(&bytes);
        let value: Option<serde_json::Value> = if spec.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
            serde_json::from_str(&text).ok()
        } else {
            toml::from_str::<toml::Value>(&text).ok().and_then(|v| serde_json::to_value(v).ok())
        };
        let field = |path: &[&str]| path.iter().try_fold(value.as_ref()?, |v, k| v.get(*k));
        let formulation = field(&["formulation"]).map(|v| v.as_str().map_or_else(|| v.to_string(), str::to_string));
        let mesh_bytes = field(&["mesh", "file"])
            .and_then(|f| f.as_str())
            .and_then(|f| std::fs::read(spec.parent().unwrap_or(Path::new(".")).join(f)).ok())
            .unwrap_or_default();
        RunSettings {
            spec: spec.to_path_buf(),
            spec_digest: if bytes.is_empty() { String::new() } else { crate::io::digest(&[&bytes, &mesh_bytes]) },
            formulation,
            solver: solver.to_string(),
            seed,
            threads,
            time_limit,
            netspec_version: env!("CARGO_PKG_VERSION").into(),
            start: None,
        }
    }

    /// What differs from `other`, as `name old → new` phrases (empty when they match).
    pub fn changes_from(&self, other: &RunSettings) -> Vec<String> {
        let mut out = Vec::new();
        let mut diff = |name: &str, a: String, b: String| {
            if a != b {
                out.push(format!("{name} {b} → {a}"));
            }
        };
        let opt = |v: Option<String>| v.unwrap_or_else(|| "default".into());
        diff("spec", self.spec.display().to_string(), other.spec.display().to_string());
        diff("spec digest", self.spec_digest.clone(), other.spec_digest.clone());
        diff("formulation", opt(self.formulation.clone()), opt(other.formulation.clone()));
        diff("solver", self.solver.clone(), other.solver.clone());
        diff("seed", opt(self.seed.map(|s| s.to_string())), opt(other.seed.map(|s| s.to_string())));
        diff("threads", opt(self.threads.map(|s| s.to_string())), opt(other.threads.map(|s| s.to_string())));
        diff("time limit", format!("{} s", self.time_limit), format!("{} s", other.time_limit));
        diff("netspec", self.netspec_version.clone(), other.netspec_version.clone());
        diff("start", opt(self.start.clone()), opt(other.start.clone()));
        out
    }
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
        let text = crate::io::read_utf8(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut m: Manifest = toml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let base = path.parent().unwrap_or(Path::new("."));
        for (i, r) in m.row.iter().enumerate() {
            if let Some(j) = m.row[..i].iter().position(|o| o.name == r.name) {
                return Err(format!(
                    "{}: row[{i}] has the same name as row[{j}] ({:?}); names must be unique",
                    path.display(),
                    r.name
                ));
            }
        }
        for (i, r) in m.row.iter_mut().enumerate() {
            match (&r.spec, &r.missing) {
                (Some(s), None) => r.spec = Some(base.join(s)),
                (None, Some(_)) => {}
                _ => {
                    return Err(format!(
                        "{}: row[{i}] ({}): give exactly one of `spec` or `missing`",
                        path.display(),
                        r.name
                    ))
                }
            }
        }
        Ok(m)
    }

    /// A manifest of plain spec files, no paper figures, each named by [`instance_ids`].
    pub fn from_specs(specs: &[PathBuf]) -> Manifest {
        Manifest {
            row: specs
                .iter()
                .zip(instance_ids(specs))
                .map(|(p, name)| ManifestRow { name, spec: Some(p.clone()), missing: None, paper: PaperRow::default() })
                .collect(),
        }
    }

    /// The rows whose names match one of `patterns` (a name, or a glob with `*` and `?`:
    /// `2*`, `*-L4`), in table order. A pattern that matches no row is an error naming it.
    pub fn select(&self, patterns: &[String]) -> Result<Manifest, String> {
        if patterns.is_empty() {
            return Ok(self.clone());
        }
        if let Some(p) = patterns.iter().find(|p| !self.row.iter().any(|r| glob_match(p, &r.name))) {
            let names: Vec<&str> = self.row.iter().map(|r| r.name.as_str()).collect();
            return Err(format!("--rows: `{p}` matches no row (rows: {})", names.join(", ")));
        }
        let row = self.row.iter().filter(|r| patterns.iter().any(|p| glob_match(p, &r.name))).cloned().collect();
        Ok(Manifest { row })
    }

    /// The directory name of each row's runs (under `runs/`): its name with characters other
    /// than letters, digits, `.`, `_` and `-` replaced by `-` (`fig1b/L2/spec` →
    /// `fig1b-L2-spec`), plus a digest of the name where that would make two rows share one.
    pub fn run_keys(&self) -> Vec<String> {
        let safe: Vec<String> = self
            .row
            .iter()
            .map(|r| {
                r.name.chars().map(|c| if c.is_ascii_alphanumeric() || "._-".contains(c) { c } else { '-' }).collect()
            })
            .collect();
        safe.iter()
            .zip(&self.row)
            .map(|(k, r)| {
                if safe.iter().filter(|o| *o == k).count() > 1 {
                    format!("{k}-{}", &crate::io::digest(&[r.name.as_bytes()])[..8])
                } else {
                    k.clone()
                }
            })
            .collect()
    }
}

/// Unique instance names from spec paths: each path without its extension, cut to the shortest
/// trailing run of components that no other spec shares (`models/streets/fig1b/L2/spec.json` and
/// `models/streets/fig7e/L2/spec.json` → `fig1b/L2/spec` and `fig7e/L2/spec`; `models/fig2b.toml`
/// alone → `fig2b`). Specs that differ only by extension keep it; a path given twice gets `#2`.
pub fn instance_ids(specs: &[PathBuf]) -> Vec<String> {
    let parts: Vec<Vec<String>> = specs
        .iter()
        .map(|p| {
            let mut c: Vec<String> = p
                .components()
                .filter(|c| {
                    !matches!(
                        c,
                        std::path::Component::CurDir | std::path::Component::RootDir | std::path::Component::Prefix(_)
                    )
                })
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if let (Some(last), Some(stem)) = (c.last_mut(), p.file_stem()) {
                *last = stem.to_string_lossy().into_owned();
            }
            c
        })
        .collect();
    let suffix = |i: usize, k: usize| parts[i][parts[i].len().saturating_sub(k)..].join("/");
    let mut k = vec![1usize; specs.len()];
    loop {
        let ids: Vec<String> = (0..specs.len()).map(|i| suffix(i, k[i])).collect();
        let mut grew = false;
        for i in 0..specs.len() {
            if k[i] < parts[i].len() && ids.iter().enumerate().any(|(j, id)| j != i && *id == ids[i]) {
                k[i] += 1;
                grew = true;
            }
        }
        if !grew {
            break;
        }
    }
    let mut ids: Vec<String> = (0..specs.len()).map(|i| suffix(i, k[i])).collect();
    // Still equal: the same path but for the extension, or the same path twice.
    let clashing: Vec<bool> =
        (0..ids.len()).map(|i| (0..ids.len()).any(|j| ids[j] == ids[i] && specs[j] != specs[i])).collect();
    for (i, clash) in clashing.into_iter().enumerate() {
        if let (true, Some(ext)) = (clash, specs[i].extension()) {
            ids[i] = format!("{}.{}", ids[i], ext.to_string_lossy());
        }
    }
    for i in 0..ids.len() {
        let mut n = 1;
        let base = ids[i].clone();
        while ids[..i].contains(&ids[i]) {
            n += 1;
            ids[i] = format!("{base}#{n}");
        }
    }
    ids
}

/// The solver names that are searches, not MILP backends (they take no MIP start).
const SEARCHES: [&str; 2] = ["heuristic", "anneal"];

/// Settings of a comparison.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct CompareSettings {
    /// The instances.
    pub manifest: Manifest,
    /// Backend names.
    pub solvers: Vec<String>,
    /// Formulation recipes to run every backend with (`paper`, `tight`, `strong`); empty: the
    /// spec's own. With recipes, each (backend, recipe) pair is one column, `highs/strong`.
    #[serde(default)]
    pub formulations: Vec<String>,
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
    /// Solve without the heuristic's MIP start (`solve --no-start`).
    #[serde(default)]
    pub no_start: bool,
    /// A request to stop (Ctrl-C): the running child is sent SIGINT (it stops its solver and
    /// writes its best design, recorded as `interrupted`), and no further run starts.
    #[serde(skip)]
    pub interrupt: Option<crate::solvers::Interrupt>,
    /// Where the runs execute (not part of the results: a run is the same wherever it ran).
    #[serde(skip)]
    pub executor: Executor,
}

impl CompareSettings {
    /// The (label, backend, recipe) of every column: `highs`, or `highs/strong` with recipes.
    pub fn methods(&self) -> Vec<(String, String, Option<String>)> {
        let mut out = Vec::new();
        for s in &self.solvers {
            if self.formulations.is_empty() {
                out.push((s.clone(), s.clone(), None));
            } else {
                for f in &self.formulations {
                    out.push((format!("{s}/{f}"), s.clone(), Some(f.clone())));
                }
            }
        }
        out
    }

    /// The time limit of one row.
    pub fn limit_for(&self, row: &ManifestRow) -> f64 {
        match (self.paper_limits, paper_seconds(&row.paper)) {
            (true, Some(t)) if t > 0.0 => t.min(self.time_limit),
            _ => self.time_limit,
        }
    }
}

/// How a record came about.
#[derive(Clone, Debug, PartialEq)]
pub enum RunSource {
    /// Solved now, no earlier record.
    Solved,
    /// Reused from an earlier run with the same settings.
    Resumed,
    /// Solved again: an earlier record had other settings (what changed).
    Rerun(Vec<String>),
}

/// What a comparison reports as it goes.
#[derive(Clone, Debug)]
pub enum Event<'a> {
    /// A run has its record (solved now, or reused).
    Run(&'a RunRecord, &'a RunSource),
    /// The runs without a reusable record were submitted to Slurm as one job array.
    Submitted {
        /// The array's job id.
        job: &'a str,
        /// Its tasks, one per run.
        tasks: usize,
    },
    /// The array's tasks by Slurm state (`squeue`), when the counts change.
    Queue {
        /// Tasks waiting to start.
        pending: usize,
        /// Tasks running.
        running: usize,
    },
}

/// Why a comparison could not run.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// Reading or writing the output folder failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// Slurm refused or is not there.
    #[error(transparent)]
    Slurm(#[from] crate::slurm::SlurmError),
}

/// Where the runs execute.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Executor {
    /// Child processes on this machine, one at a time (the default).
    #[default]
    Local,
    /// Tasks of a Slurm job array ([`cluster`]).
    Slurm(crate::slurm::SlurmOptions),
}

/// One run of a comparison: what produces it and where its record goes.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct PlannedRun {
    /// The manifest row's name.
    pub instance: String,
    /// The column's label (`highs`, `highs/strong`).
    pub label: String,
    /// The backend.
    pub solver: String,
    /// The recipe, if the column has one.
    pub formulation: Option<String>,
    /// The seed.
    pub seed: Option<u64>,
    /// The spec file.
    pub spec: PathBuf,
    /// The time limit, seconds.
    pub limit: f64,
    /// The run's folder (its `run.json`, `result.json`, `stdout.txt`, `stderr.txt`).
    pub dir: PathBuf,
    /// The settings its record must carry to be reused.
    pub wanted: RunSettings,
}

/// Every run of a comparison, in table order, each with its earlier record when that can be
/// reused, else why it runs.
pub fn plan(settings: &CompareSettings, out: &Path) -> Vec<(PlannedRun, Result<RunRecord, RunSource>)> {
    let seeds: Vec<Option<u64>> =
        if settings.seeds.is_empty() { vec![None] } else { settings.seeds.iter().map(|&s| Some(s)).collect() };
    let mut runs = Vec::new();
    for (row, key) in settings.manifest.row.iter().zip(settings.manifest.run_keys()) {
        let Some(spec) = &row.spec else { continue };
        for (label, solver, formulation) in settings.methods() {
            for &seed in &seeds {
                let dir = out.join("runs").join(format!(
                    "{key}__{}__{}",
                    label.replace('/', "+"),
                    seed.map_or("default".into(), |s| s.to_string())
                ));
                let limit = settings.limit_for(row);
                let mut wanted = RunSettings::new(spec, &label, seed, settings.threads, limit);
                if formulation.is_some() {
                    wanted.formulation = formulation.clone();
                }
                if !SEARCHES.contains(&solver.as_str()) {
                    wanted.start = Some(if settings.no_start { "none" } else { "heuristic" }.to_string());
                }
                let run = PlannedRun {
                    instance: row.name.clone(),
                    label: label.clone(),
                    solver: solver.clone(),
                    formulation: formulation.clone(),
                    seed,
                    spec: spec.clone(),
                    limit,
                    dir,
                    wanted,
                };
                let decision = decide(&run);
                runs.push((run, decision));
            }
        }
    }
    runs
}

/// The earlier record of `run` if it can be reused, else why the run happens.
fn decide(run: &PlannedRun) -> Result<RunRecord, RunSource> {
    let old =
        std::fs::read_to_string(run.dir.join("run.json")).ok().and_then(|t| serde_json::from_str::<RunRecord>(&t).ok());
    let wanted = &run.wanted;
    Err(match old {
        None => return Err(RunSource::Solved),
        // An interrupted run is not finished, nor is a cluster task that ended without a record.
        Some(r) if r.status == "interrupted" => RunSource::Rerun(vec!["interrupted".to_string()]),
        Some(r) if r.slurm_state.is_some() => {
            RunSource::Rerun(vec![format!("its Slurm task ended {}", r.slurm_state.unwrap_or_default())])
        }
        Some(r) if r.settings.as_ref() == Some(wanted) && r.instance == run.instance => return Ok(r),
        Some(r) => RunSource::Rerun(match &r.settings {
            Some(had) if had != wanted => wanted.changes_from(had),
            Some(_) => vec![format!("instance {} → {}", r.instance, run.instance)],
            None => vec!["no settings recorded".into()],
        }),
    })
}

/// Runs every (instance, backend, seed) combination that has no record with the same settings,
/// with the settings' executor; returns all records, in table order. `exe` is the `netspec`
/// binary; `progress` hears of each record as it is made or reused (and of the cluster's queue).
/// With Slurm, nothing is written before the cluster is found able to take the jobs.
pub fn run_all(
    exe: &Path,
    settings: &CompareSettings,
    out: &Path,
    progress: impl FnMut(Event),
) -> Result<Vec<RunRecord>, CompareError> {
    match &settings.executor {
        Executor::Local => Ok(run_local(exe, settings, out, progress)?),
        Executor::Slurm(opts) => cluster::run_slurm(exe, settings, opts, out, progress),
    }
}

/// The local executor: each run a child process of this one, in table order.
fn run_local(
    exe: &Path,
    settings: &CompareSettings,
    out: &Path,
    mut progress: impl FnMut(Event),
) -> std::io::Result<Vec<RunRecord>> {
    std::fs::create_dir_all(out)?;
    let mut records = Vec::new();
    for (run, decision) in plan(settings, out) {
        if settings.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            break;
        }
        let source = match decision {
            Ok(r) => {
                progress(Event::Run(&r, &RunSource::Resumed));
                records.push(r);
                continue;
            }
            Err(source) => source,
        };
        let r = solve_and_record(exe, settings, &run, None)?;
        progress(Event::Run(&r, &source));
        records.push(r);
    }
    Ok(records)
}

/// Solves one planned run in a child process and writes its record (`run.json`), marked with
/// the digest of the binary that ran it when one is given.
pub fn solve_and_record(
    exe: &Path,
    settings: &CompareSettings,
    run: &PlannedRun,
    binary_digest: Option<String>,
) -> std::io::Result<RunRecord> {
    std::fs::create_dir_all(&run.dir)?;
    let mut r =
        run_one(exe, &run.spec, &run.solver, run.formulation.as_deref(), run.seed, settings, run.limit, &run.dir)?;
    r.binary_digest = binary_digest;
    save_record(run, r)
}

/// Names a record after its planned run, gives it the run's settings and writes it.
fn save_record(run: &PlannedRun, mut r: RunRecord) -> std::io::Result<RunRecord> {
    r.solver = run.label.clone();
    r.instance = run.instance.clone();
    r.settings = Some(run.wanted.clone());
    crate::io::write_atomic(&run.dir.join("run.json"), &(serde_json::to_string_pretty(&r)? + "\n"))?;
    Ok(r)
}

#[allow(clippy::too_many_arguments)]
fn run_one(
    exe: &Path,
    spec: &Path,
    solver: &str,
    formulation: Option<&str>,
    seed: Option<u64>,
    s: &CompareSettings,
    limit: f64,
    dir: &Path,
) -> std::io::Result<RunRecord> {
    let mut cmd = Command::new(exe);
    // The run's wall time is the solve's: an infeasible spec is not explained here.
    cmd.arg("solve")
        .arg(spec)
        .args(["--no-explain", "--solver", solver, "--time-limit", &limit.to_string(), "--out"])
        .arg(dir);
    if let Some(f) = formulation {
        cmd.args(["--formulation", f]);
    }
    if let Some(seed) = seed {
        cmd.args(["--seed", &seed.to_string()]);
    }
    if let Some(t) = s.threads {
        cmd.args(["--threads", &t.to_string()]);
    }
    if s.no_start && !SEARCHES.contains(&solver) {
        cmd.arg("--no-start");
    }
    cmd.stdin(Stdio::null())
        .stdout(std::fs::File::create(dir.join("stdout.txt"))?)
        .stderr(std::fs::File::create(dir.join("stderr.txt"))?);
    // Its own process group: a Ctrl-C at the terminal reaches this process only, which passes
    // it on once (a second SIGINT would make the child quit without its result).
    std::os::unix::process::CommandExt::process_group(&mut cmd, 0);
    die_with_parent(&mut cmd);
    let _ = std::fs::remove_file(dir.join("result.json"));
    let t0 = Instant::now();
    let mut child = cmd.spawn()?;
    let deadline = Duration::try_from_secs_f64(limit + s.grace).unwrap_or(Duration::MAX); // inf: no limit
    let mut killed = false;
    let mut forwarded = false;
    let status = loop {
        if let Some(st) = child.try_wait()? {
            break Some(st);
        }
        if !forwarded && s.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            // SAFETY: signalling our own child, which has not been reaped yet.
            unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) };
            forwarded = true;
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
    Ok(record_from_dir(dir, solver, seed, limit, wall_time, status.and_then(|s| s.code()), killed))
}

/// The record of a finished run from what its process left in `dir` (`result.json`, and
/// `stderr.txt` when it failed), whoever ran it.
pub fn record_from_dir(
    dir: &Path,
    solver: &str,
    seed: Option<u64>,
    limit: f64,
    wall_time: f64,
    exit_code: Option<i32>,
    killed: bool,
) -> RunRecord {
    let result: Option<ResultView> =
        std::fs::read_to_string(dir.join("result.json")).ok().and_then(|t| serde_json::from_str(&t).ok());
    let mut r = RunRecord {
        instance: String::new(),
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
        exit_code,
        time_limit: Some(limit),
        error: None,
        settings: None,
        binary_digest: None,
        slurm_state: None,
    };
    match (result, killed) {
        (Some(res), false) => {
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
        (None, false) => r.error = Some(failure_cause(dir, exit_code)),
        _ => {}
    }
    r
}

/// Why a run left no result: its `error:` line and the causes under it, from `stderr.txt`.
fn failure_cause(dir: &Path, exit_code: Option<i32>) -> String {
    let text = std::fs::read_to_string(dir.join("stderr.txt")).unwrap_or_default();
    let lines: Vec<&str> = text
        .lines()
        .skip_while(|l| !l.starts_with("error:"))
        .take_while(|l| l.starts_with("error:") || l.starts_with("  caused by:"))
        .map(|l| l.trim_start_matches("error:").trim_start_matches("  caused by:").trim())
        .collect();
    if lines.is_empty() {
        let tail = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap_or("no message");
        format!("exit code {}: {tail}", exit_code.map_or("none".into(), |c| c.to_string()))
    } else {
        lines.join(": ")
    }
}

/// Makes the child die when this process dies (Linux: `PR_SET_PDEATHSIG` with `SIGKILL`, set in
/// the child between fork and exec; if the parent is already gone by then, the child exits at
/// once). The signal follows the death of the thread that spawned the child, so spawn from a
/// thread that lives as long as the comparison (here: the caller of [`run_all`]).
fn die_with_parent(cmd: &mut Command) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: the closure runs in the forked child before exec and calls only
        // async-signal-safe functions (prctl, getppid, _exit).
        let parent = unsafe { libc::getpid() };
        unsafe {
            cmd.pre_exec(move || {
                if libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL as libc::c_ulong, 0, 0, 0) != 0 {
                    return Err(std::io::Error::last_os_error());
                }
                if libc::getppid() != parent {
                    libc::_exit(1);
                }
                Ok(())
            });
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = cmd;
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

/// Finished comparisons combined into one ([`merge`]).
#[derive(Clone, Debug)]
pub struct Merged {
    /// The rows of the combined table.
    pub manifest: Manifest,
    /// Every column of every comparison, in order.
    pub columns: Vec<String>,
    /// Every record of every comparison.
    pub records: Vec<RunRecord>,
    /// The largest time limit of the comparisons (the charts' axis).
    pub time_limit: f64,
    /// Each comparison's directory and its stored settings, as read.
    pub sources: Vec<(PathBuf, serde_json::Value)>,
}

/// Reads the `results.json` of finished comparisons (`compare --out DIR`, or an earlier merge)
/// and combines them: columns in the order of `dirs`, then of each comparison's own columns.
/// The rows are `manifest`'s if given, else the first comparison's. A column label that
/// appears in two comparisons is an error naming both, as is a directory without a readable
/// `results.json`.
pub fn merge(dirs: &[PathBuf], manifest: Option<Manifest>) -> Result<Merged, String> {
    #[derive(Deserialize)]
    struct Saved {
        settings: serde_json::Value,
        records: Vec<RunRecord>,
        summary: Vec<BackendSummary>,
    }
    // Each column with the comparison it came from (to name both when it comes again).
    let mut columns: Vec<(String, PathBuf)> = Vec::new();
    let (mut records, mut sources, mut time_limit, mut first_manifest) = (Vec::new(), Vec::new(), 0.0f64, None);
    for dir in dirs {
        let path = dir.join("results.json");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("{}: {e} (a finished `netspec compare --out {}`?)", path.display(), dir.display()))?;
        let saved: Saved =
            serde_json::from_str(&text).map_err(|e| format!("{}: not a comparison's results: {e}", path.display()))?;
        for b in &saved.summary {
            if let Some((_, other)) = columns.iter().find(|(c, _)| *c == b.solver) {
                return Err(format!(
                    "column `{}` is in both {} and {}: merge comparisons with different columns",
                    b.solver,
                    other.display(),
                    dir.display()
                ));
            }
            columns.push((b.solver.clone(), dir.clone()));
        }
        if let Some(limit) = saved.settings.get("time_limit").and_then(|v| v.as_f64()) {
            time_limit = time_limit.max(limit);
        }
        if first_manifest.is_none() {
            let m = saved
                .settings
                .get("manifest")
                .cloned()
                .ok_or_else(|| format!("{}: settings.manifest is missing", path.display()))?;
            first_manifest = Some(
                serde_json::from_value::<Manifest>(m)
                    .map_err(|e| format!("{}: settings.manifest: {e}", path.display()))?,
            );
        }
        records.extend(saved.records);
        sources.push((dir.clone(), saved.settings));
    }
    let manifest = manifest.or(first_manifest).ok_or("nothing to merge: no comparison directories given")?;
    Ok(Merged { manifest, columns: columns.into_iter().map(|(c, _)| c).collect(), records, time_limit, sources })
}

/// Whether `name` matches `pattern`, where `*` stands for any run of characters and `?` for
/// one.
pub fn glob_match(pattern: &str, name: &str) -> bool {
    let (p, n): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // The classic two-pointer match with backtracking to the last `*`.
    let (mut i, mut j, mut star, mut mark) = (0, 0, None, 0);
    while j < n.len() {
        if i < p.len() && (p[i] == '?' || p[i] == n[j]) {
            i += 1;
            j += 1;
        } else if i < p.len() && p[i] == '*' {
            star = Some(i);
            mark = j;
            i += 1;
        } else if let Some(s) = star {
            i = s + 1;
            mark += 1;
            j = mark;
        } else {
            return false;
        }
    }
    p[i..].iter().all(|&c| c == '*')
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
    /// Runs proven optimal (gap ≤ [`PROVEN_GAP`]) or infeasible, with a valid answer where there
    /// is one.
    pub solved: usize,
    /// Runs.
    pub runs: usize,
    /// Instances where this backend was the fastest to solve.
    pub wins: usize,
}

/// The relative gap at which a run with a valid design counts as proven optimal although its
/// solver went on (the gap Table 1's target names; Gurobi's default `MIPGap`). netspec's own
/// `optimal` is stricter (see [`crate::solvers::OPTIMALITY_TOLERANCE`]).
pub const PROVEN_GAP: f64 = 1e-4;

/// Proven: infeasible, or a valid design that is optimal or within [`PROVEN_GAP`] of its bound.
fn solved(r: &RunRecord) -> bool {
    r.status == "infeasible" || (r.valid && (r.status == "optimal" || r.gap.is_some_and(|g| g <= PROVEN_GAP)))
}

/// Summaries per backend, in the order of `solvers`.
pub fn summarize(records: &[RunRecord], solvers: &[String], limit: f64) -> Vec<BackendSummary> {
    // Each instance once, in first-seen order (merged comparisons list a row once per source).
    let mut seen = std::collections::BTreeSet::new();
    let instances: Vec<&str> = records.iter().map(|r| r.instance.as_str()).filter(|i| seen.insert(*i)).collect();
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
            BackendSummary {
                solver: s.clone(),
                sgm_time: shifted_geometric_mean(&times, 10.0),
                solved: mine.iter().filter(|r| solved(r)).count(),
                runs: mine.len(),
                wins,
            }
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
        let _ = write!(
            s,
            "| {i} | {} ({}) | {} ({}) | {paper_time} |",
            num(edges),
            num(p.edges),
            num(vars),
            num(p.variables)
        );
        for b in solvers {
            match rows.iter().find(|r| &r.solver == b) {
                Some(r) => {
                    let _ = write!(
                        s,
                        " {:.2} s {}{} gap {} |",
                        r.wall_time,
                        r.status,
                        if r.valid { "" } else { " (invalid)" },
                        opt(r.gap.map(|g| g * 100.0), 1)
                    );
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
    let failed: Vec<&RunRecord> = records.iter().filter(|r| r.error.is_some()).collect();
    if !failed.is_empty() {
        s.push_str("\nRuns that failed (no result):\n\n");
        for r in failed {
            let _ = writeln!(s, "- {} / {}: {}", r.instance, r.solver, r.error.as_deref().unwrap_or_default());
        }
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
    let mut s = String::from("instance,solver,seed,edges,vars,rows,nonzeros,status,objective,dual_bound,gap,nodes,solver_time,wall_time,valid,killed,error\n");
    for r in records {
        let o = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
        let u = |v: Option<usize>| v.map_or(String::new(), |v| v.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
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
            r.killed,
            csv_field(r.error.as_deref().unwrap_or_default())
        );
    }
    s
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// A performance profile as SVG ([`render::chart::performance_profile_svg`]): for each backend,
/// the fraction of runs solved (optimal and valid, or infeasible) within time t, for t from 0 to
/// the limit (log scale from 0.01 s).
pub fn performance_profile_svg(records: &[RunRecord], solvers: &[String], limit: f64) -> String {
    let series: Vec<ProfileSeries> = solvers
        .iter()
        .map(|b| {
            let mine: Vec<&RunRecord> = records.iter().filter(|r| &r.solver == b).collect();
            ProfileSeries {
                name: b.clone(),
                solved_times: mine.iter().filter(|r| solved(r)).map(|r| r.wall_time).collect(),
                runs: mine.len(),
            }
        })
        .collect();
    render::chart::performance_profile_svg(&series, limit)
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
    let groups = manifest
        .row
        .iter()
        .filter(|r| r.spec.is_some())
        .map(|row| BarGroup {
            name: row.name.clone(),
            bars: solvers
                .iter()
                .map(|b| {
                    let runs: Vec<&RunRecord> =
                        records.iter().filter(|r| r.instance == row.name && &r.solver == b).collect();
                    if runs.is_empty() {
                        return None;
                    }
                    // The run that explains the bar: the first not solved, else the first.
                    let shown = runs.iter().find(|r| !solved(r)).unwrap_or(&runs[0]);
                    let unsolved = runs.iter().filter(|r| !solved(r)).count();
                    Some(Bar {
                        times: runs.iter().map(|r| bar_time(r)).collect(),
                        solved: unsolved == 0,
                        status: if shown.killed { "killed".into() } else { shown.status.clone() },
                        killed: shown.killed,
                        failed: shown.status == "failed" && !shown.killed,
                        label: run_label(shown).map(|l| {
                            if runs.len() > 1 && unsolved > 0 {
                                format!("{unsolved}/{} {l}", runs.len())
                            } else {
                                l
                            }
                        }),
                    })
                })
                .collect(),
            reference: paper_seconds(&row.paper),
        })
        .collect();
    render::chart::bar_chart_svg(&BarChart {
        series: solvers.to_vec(),
        groups,
        limit,
        reference_label: "paper (Gurobi 2014)".into(),
        not_shown: manifest.row.iter().filter(|r| r.spec.is_none()).map(|r| r.name.clone()).collect(),
    })
}

/// What a comparison's report is made of ([`write_report`]).
pub struct Report<'a> {
    /// The rows.
    pub manifest: &'a Manifest,
    /// Every run's record.
    pub records: &'a [RunRecord],
    /// The columns (a backend, or a backend and a formulation).
    pub columns: &'a [String],
    /// The time limit (the longest, when rows had their own).
    pub time_limit: f64,
    /// The runs, for the header (`time limit 60 s, grace 10 s`).
    pub what: &'a str,
    /// The command line that made them.
    pub command: &'a [String],
    /// Stored in `results.json`.
    pub settings: serde_json::Value,
    /// Makespan estimates to add (`--makespan`), if any.
    pub makespan: &'a [makespan::Estimate],
}

/// Writes a comparison's reports to `out` (`results.md`, `.csv`, `.json`, `profile.svg`,
/// `bars.svg`) and returns the Markdown table.
pub fn write_report(out: &Path, r: Report) -> Result<String, String> {
    let Report { manifest, records, columns, time_limit, what, command, settings, makespan } = r;
    std::fs::create_dir_all(out).map_err(|e| format!("creating {}: {e}", out.display()))?;
    let summary = summarize(records, columns, time_limit);
    let md = markdown(manifest, records, columns, &summary) + &makespan::markdown(makespan);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let header = format!(
        "netspec {} compare, {what}; {cpu}, {} cores\n\nCommand: `{}`\n\n",
        env!("CARGO_PKG_VERSION"),
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        command.join(" ")
    );
    let write = |name: &str, text: String| {
        std::fs::write(out.join(name), text).map_err(|e| format!("writing {}: {e}", out.join(name).display()))
    };
    write("results.md", header + &md)?;
    write("results.csv", csv(records))?;
    write("profile.svg", performance_profile_svg(records, columns, time_limit))?;
    write("bars.svg", bar_chart_svg(manifest, records, columns, time_limit))?;
    let mut all = serde_json::json!({
        "netspec_version": env!("CARGO_PKG_VERSION"),
        "command": command,
        "cpu": cpu,
        "settings": settings,
        "records": records,
        "summary": summary,
    });
    if !makespan.is_empty() {
        all["makespan"] = serde_json::to_value(makespan).expect("estimates serialise");
    }
    write("results.json", serde_json::to_string_pretty(&all).expect("records serialise") + "\n")?;
    Ok(md)
}
