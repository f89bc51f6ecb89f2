//! What a comparison runs: its settings ([`CompareSettings`]), every (instance, column, seed)
//! run in table order with its earlier record when that can be reused ([`plan`]), and the
//! events it reports as it goes.

use super::manifest::{paper_seconds, Manifest, ManifestRow};
use super::record::{RunRecord, RunSettings};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// The solver names that are searches, not MILP backends (they take no MIP start).
pub(crate) const SEARCHES: [&str; 2] = ["heuristic", "anneal"];

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
