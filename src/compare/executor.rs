//! Running a comparison's plan where its settings say: one child process at a time on this
//! machine, or a Slurm job array ([`super::cluster`]).

use super::child::solve_and_record;
use super::cluster;
use super::error::CompareError;
use super::plan::{plan, CompareSettings, Event, Executor, RunSource};
use super::record::RunRecord;
use std::path::Path;

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
