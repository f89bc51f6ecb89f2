//! A city on a Slurm cluster: each sub-region's level is one batch job running the staged
//! netspec binary (`netspec city SPEC --level-job R:N`), level n after level n − 1 ended well
//! (`--dependency=afterok`), so the regions proceed side by side and each level starts from the
//! roads its predecessor left on the shared filesystem. When every job has ended, the city is
//! assembled here from the levels' saved states exactly as a local run writes it (smoothing,
//! metrics, pictures); a level whose job did not finish is reported skipped, never solved here.

use super::city::{CityError, CityRunOptions};
use super::output::{run_city_on, CityResult};
use super::spec::CitySpec;
use crate::geometry::planar::Region;
use crate::slurm::{self, Job, SlurmError, SlurmOptions};
use std::path::Path;
use std::time::Duration;

/// Why a city could not run on the cluster.
#[derive(Debug, thiserror::Error)]
pub enum CityClusterError {
    /// Slurm refused or is not there.
    #[error(transparent)]
    Slurm(#[from] SlurmError),
    /// The city itself.
    #[error(transparent)]
    City(#[from] CityError),
}

/// One region's level as a job.
struct LevelJob {
    region: usize,
    level: u8,
    id: String,
}

/// Runs a city's levels as Slurm jobs and assembles the result. `exe` is the netspec binary,
/// `spec_path` the city file; `job_flags` are the `netspec city` flags every job gets so that it
/// resolves the same options as `opts` (backend, limits, threads, gap).
#[allow(clippy::too_many_arguments)]
pub fn run_city_slurm(
    exe: &Path,
    spec: &CitySpec,
    spec_path: &Path,
    regs: Vec<(Region, Option<usize>)>,
    out: &Path,
    opts: &CityRunOptions,
    job_flags: &[String],
    slurm_opts: &SlurmOptions,
) -> Result<CityResult, CityClusterError> {
    slurm::check(slurm_opts)?;
    let cwd = std::env::current_dir().map_err(|source| CityError::Io { path: ".".into(), source })?;
    let stage = cwd.join(out).join("slurm");
    let io = |source| CityError::Io { path: stage.clone(), source };
    std::fs::create_dir_all(stage.join("logs")).map_err(io)?;
    let (binary, _) = slurm::stage_binary(exe, &stage).map_err(io)?;
    let mut jobs: Vec<LevelJob> = Vec::new();
    for (i, (_, entry)) in regs.iter().enumerate() {
        let mut previous: Option<String> = None;
        for n in spec.region_levels(*entry) {
            let limit = opts.time_limit.or(spec.level(*entry, n).map_err(CityError::from)?.time_limit);
            let script = stage.join(format!("city-{i:02}-L{n}.sh"));
            let mut argv = vec![binary.display().to_string(), "city".into(), spec_path.display().to_string()];
            argv.extend(["--out".into(), out.display().to_string(), "--level-job".into(), format!("{i}:{n}")]);
            argv.extend(job_flags.iter().cloned());
            slurm::write_script(&script, &argv)?;
            let job = Job {
                name: format!("netspec-city-{i:02}-L{n}"),
                script,
                array: None,
                cpus: opts.threads_per_solve,
                seconds: limit.filter(|t| t.is_finite()).unwrap_or(7.0 * 86400.0),
                chdir: cwd.clone(),
                log: stage.join("logs").join(format!("city-{i:02}-L{n}-%j.txt")),
                after_ok: previous.iter().cloned().collect(),
            };
            let id = match slurm::submit(slurm_opts, &job) {
                Ok(id) => id,
                Err(e) => {
                    let _ = slurm::cancel(&jobs.iter().map(|j| j.id.clone()).collect::<Vec<_>>());
                    return Err(e.into());
                }
            };
            previous = Some(id.clone());
            jobs.push(LevelJob { region: i, level: n, id });
        }
    }
    wait(&jobs, opts)?;
    let assemble = CityRunOptions { resume: true, reuse_only: true, only: None, ..opts.clone() };
    Ok(run_city_on(spec, regs, out, &assemble)?)
}

/// Waits until no job is pending or running; on an interrupt, cancels them all.
fn wait(jobs: &[LevelJob], opts: &CityRunOptions) -> Result<(), SlurmError> {
    let ids: Vec<String> = jobs.iter().map(|j| j.id.clone()).collect();
    let mut cancelled = false;
    let mut started = vec![false; jobs.len()];
    loop {
        if !cancelled && opts.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
            slurm::cancel(&ids)?;
            cancelled = true;
        }
        let mut open = 0;
        for (k, j) in jobs.iter().enumerate() {
            let states = slurm::states(&j.id)?;
            let Some(st) = states.get(&None) else { continue };
            if st.reason == "DependencyNeverSatisfied" && !st.is_finished() {
                // Its predecessor failed, on a cluster that keeps such jobs pending.
                slurm::cancel(std::slice::from_ref(&j.id))?;
                continue;
            }
            if !st.is_finished() {
                open += 1;
            }
            if st.state == "RUNNING" && !started[k] {
                started[k] = true;
                if let Some(o) = &opts.observer {
                    o(&super::CityEvent::LevelStarted {
                        region: j.region,
                        level: j.level,
                        time_limit: opts.time_limit,
                    });
                }
            }
        }
        if open == 0 {
            return Ok(());
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// One level's job (`netspec city --level-job R:N`): solves region `region`'s level `level`
/// (its earlier levels reused from their saved states) and returns that level's report.
pub fn run_level_job(
    spec: &CitySpec,
    out: &Path,
    opts: &CityRunOptions,
    region: usize,
    level: u8,
) -> Result<Option<super::LevelReport>, CityError> {
    let regs = super::city::regions(spec)?;
    let job = CityRunOptions { only: Some((region, level)), reuse_only: false, ..opts.clone() };
    let reports = super::city::run_regions(spec, regs, out, &job)?;
    Ok(reports.into_iter().next().and_then(|r| r.levels.into_iter().find(|l| l.level == level)))
}
