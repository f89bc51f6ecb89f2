//! The Slurm executor of a comparison: the runs without a reusable record become one job array,
//! each task one run. The netspec binary is staged once into the output folder
//! (`slurm/netspec-<digest>`, its digest in every record); each task runs it as
//! `netspec compare-task PLAN INDEX`, which solves the run in a child process, kills it at the
//! limit plus grace and writes its `run.json` into the output folder (on the shared filesystem)
//! exactly as a local run does. This process follows the records as they appear and the tasks'
//! states in `squeue`; a task that ends without a record (TIMEOUT, NODE_FAIL, OUT_OF_MEMORY,
//! CANCELLED, PREEMPTED, …) is recorded with that state and solved again on the next resume. An
//! interrupt (Ctrl-C) cancels the array; every record already written is kept.

use super::child::{save_record, solve_and_record};
use super::error::CompareError;
use super::manifest::Manifest;
use super::plan::{plan, CompareSettings, Event, Executor, PlannedRun, RunSource};
use super::record::{record_from_dir, RunRecord};
use crate::slurm::{self, Job, JobState, SlurmError, SlurmOptions};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::{Duration, Instant};

/// What every task of one array needs: the runs (task `i` is `runs[i]`) and the settings they
/// share. Written as `slurm/plan-<digest>.json`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct TaskPlan {
    /// Seconds past a run's limit before its solve is killed.
    pub grace: f64,
    /// Threads per run.
    pub threads: Option<u32>,
    /// Solve without the heuristic's MIP start.
    pub no_start: bool,
    /// Digest of the staged binary.
    pub binary_digest: String,
    /// The runs, by task index.
    pub runs: Vec<PlannedRun>,
}

/// How long a finished task may take to show its record (a shared filesystem's delay).
const RECORD_GRACE: Duration = Duration::from_secs(10);
/// How often the records and `squeue` are read.
const POLL: Duration = Duration::from_millis(500);

/// Runs one task of an array: the plan's run `index`, solved by `exe` (the staged binary), its
/// record written into the output folder.
pub fn run_task(exe: &Path, plan_path: &Path, index: usize) -> Result<RunRecord, CompareError> {
    let text = std::fs::read_to_string(plan_path)?;
    let plan: TaskPlan = serde_json::from_str(&text)
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidData, format!("{}: {e}", plan_path.display())))?;
    let run = plan.runs.get(index).ok_or_else(|| {
        std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            format!("{}: task {index} of {} runs", plan_path.display(), plan.runs.len()),
        )
    })?;
    let settings = CompareSettings {
        manifest: Manifest { row: Vec::new() },
        solvers: Vec::new(),
        formulations: Vec::new(),
        time_limit: run.limit,
        grace: plan.grace,
        seeds: Vec::new(),
        threads: plan.threads,
        paper_limits: false,
        no_start: plan.no_start,
        interrupt: None,
        executor: Executor::Local,
    };
    Ok(solve_and_record(exe, &settings, run, Some(plan.binary_digest.clone()))?)
}

/// The Slurm executor ([`super::executor::run_all`] with [`Executor::Slurm`]).
pub(super) fn run_slurm(
    exe: &Path,
    settings: &CompareSettings,
    opts: &SlurmOptions,
    out: &Path,
    mut progress: impl FnMut(Event),
) -> Result<Vec<RunRecord>, CompareError> {
    slurm::check(opts)?;
    let planned = plan(settings, out);
    let mut records: Vec<Option<RunRecord>> = vec![None; planned.len()];
    let mut todo: Vec<(usize, PlannedRun, RunSource)> = Vec::new();
    for (i, (run, decision)) in planned.into_iter().enumerate() {
        match decision {
            Ok(r) => {
                progress(Event::Run(&r, &RunSource::Resumed));
                records[i] = Some(r);
            }
            Err(source) => todo.push((i, run, source)),
        }
    }
    if !todo.is_empty() && !settings.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
        let existed = out.exists();
        let submitted = submit(exe, settings, opts, out, &todo);
        let job = match submitted {
            Ok(job) => job,
            Err(e) => {
                if !existed {
                    let _ = std::fs::remove_dir_all(out);
                }
                return Err(e);
            }
        };
        progress(Event::Submitted { job: &job, tasks: todo.len() });
        follow(settings, &job, out, &todo, &mut records, &mut progress)?;
    }
    Ok(records.into_iter().flatten().collect())
}

/// Stages the binary, writes the plan and the task script, clears the runs' stale records and
/// submits the array; returns its job id.
fn submit(
    exe: &Path,
    settings: &CompareSettings,
    opts: &SlurmOptions,
    out: &Path,
    todo: &[(usize, PlannedRun, RunSource)],
) -> Result<String, CompareError> {
    let cwd = std::env::current_dir()?;
    let stage = cwd.join(out).join("slurm");
    std::fs::create_dir_all(stage.join("logs"))?;
    let (binary, digest) = slurm::stage_binary(exe, &stage)?;
    let plan = TaskPlan {
        grace: settings.grace,
        threads: settings.threads,
        no_start: settings.no_start,
        binary_digest: digest,
        runs: todo.iter().map(|(_, r, _)| r.clone()).collect(),
    };
    let text = serde_json::to_string_pretty(&plan).map_err(std::io::Error::from)? + "\n";
    let key = &crate::io::digest(&[text.as_bytes()])[..12];
    let plan_path = stage.join(format!("plan-{key}.json"));
    crate::io::write_atomic(&plan_path, &text)?;
    let script = stage.join(format!("task-{key}.sh"));
    let argv = [binary.display().to_string(), "compare-task".into(), plan_path.display().to_string()];
    slurm::write_script(&script, &[&argv[..], &["$SLURM_ARRAY_TASK_ID".to_string()]].concat())?;
    for (_, run, _) in todo {
        std::fs::create_dir_all(&run.dir)?;
        match std::fs::remove_file(run.dir.join("run.json")) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => return Err(e.into()),
            _ => {}
        }
    }
    let longest = todo.iter().map(|(_, r, _)| r.limit).fold(0.0, f64::max);
    let job = Job {
        name: format!("netspec-compare-{key}"),
        script,
        array: Some(todo.len()),
        cpus: settings.threads.unwrap_or(1),
        seconds: if longest.is_finite() { longest + settings.grace } else { 365.0 * 86400.0 },
        chdir: cwd,
        log: stage.join("logs").join("%A_%a.txt"),
        after_ok: Vec::new(),
    };
    Ok(slurm::submit(opts, &job)?)
}

/// Follows the array until every task has a record or has ended without one; cancels it on an
/// interrupt.
fn follow(
    settings: &CompareSettings,
    job: &str,
    out: &Path,
    todo: &[(usize, PlannedRun, RunSource)],
    records: &mut [Option<RunRecord>],
    progress: &mut impl FnMut(Event),
) -> Result<(), CompareError> {
    let mut open: BTreeMap<usize, Option<Instant>> = (0..todo.len()).map(|t| (t, None)).collect();
    let mut cancelled = false;
    let mut missing_polls: BTreeMap<usize, u32> = BTreeMap::new();
    let mut last_counts = (usize::MAX, usize::MAX);
    while !open.is_empty() {
        if !cancelled && settings.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            slurm::cancel(&[job.to_string()])?;
            cancelled = true;
        }
        let states = slurm::states(job)?;
        let counts = (count(&states, "PENDING"), count(&states, "RUNNING"));
        if counts != last_counts {
            progress(Event::Queue { pending: counts.0, running: counts.1 });
            last_counts = counts;
        }
        let mut done = Vec::new();
        for (&t, seen_end) in open.iter_mut() {
            let (i, run, source) = &todo[t];
            if let Some(r) = read_record(run) {
                progress(Event::Run(&r, source));
                records[*i] = Some(r);
                done.push(t);
                continue;
            }
            match states.get(&Some(t)) {
                Some(st) if st.is_finished() => {
                    let since = *seen_end.get_or_insert_with(Instant::now);
                    if st.state != "COMPLETED" || since.elapsed() > RECORD_GRACE {
                        let r = ended_without_record(run, st, &out.join("slurm").join("logs"), job, t)?;
                        progress(Event::Run(&r, source));
                        records[*i] = Some(r);
                        done.push(t);
                    }
                }
                Some(_) => {
                    missing_polls.remove(&t);
                }
                None => {
                    // Not listed: a pending task cancelled (by us: it never ran, no record), or
                    // forgotten by the controller.
                    let n = missing_polls.entry(t).or_default();
                    *n += 1;
                    if cancelled || *n >= 3 {
                        if !cancelled {
                            let gone = JobState { state: "CANCELLED".into(), reason: "gone from squeue".into() };
                            let r = ended_without_record(run, &gone, &out.join("slurm").join("logs"), job, t)?;
                            progress(Event::Run(&r, source));
                            records[*i] = Some(r);
                        }
                        done.push(t);
                    }
                }
            }
        }
        for t in done {
            open.remove(&t);
        }
        if !open.is_empty() {
            std::thread::sleep(POLL);
        }
    }
    Ok(())
}

fn count(states: &BTreeMap<Option<usize>, JobState>, state: &str) -> usize {
    states.values().filter(|s| s.state == state).count()
}

/// The run's record, if its task has written it.
fn read_record(run: &PlannedRun) -> Option<RunRecord> {
    let text = std::fs::read_to_string(run.dir.join("run.json")).ok()?;
    serde_json::from_str(&text).ok()
}

/// The record of a task that ended without writing one: its Slurm state as the status.
fn ended_without_record(
    run: &PlannedRun,
    st: &JobState,
    logs: &Path,
    job: &str,
    task: usize,
) -> Result<RunRecord, SlurmError> {
    let mut r = record_from_dir(&run.dir, &run.solver, run.seed, run.limit, 0.0, None, false);
    r.status = st.state.to_lowercase();
    r.slurm_state = Some(st.state.clone());
    r.error = Some(format!(
        "the Slurm task {job}_{task} ended {} without a record (its log: {})",
        st.state,
        logs.join(format!("{job}_{task}.txt")).display()
    ));
    save_record(run, r).map_err(|source| SlurmError::Io { path: run.dir.join("run.json"), source })
}
