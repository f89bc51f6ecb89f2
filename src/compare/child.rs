//! One run as a child process of this one (`netspec solve`), killed at its limit plus grace
//! and recorded in its `run.json` as soon as it ends. On Linux the child dies with its parent
//! (`PR_SET_PDEATHSIG`), so killing the comparison never leaves a solve running.

use super::plan::{CompareSettings, PlannedRun, SEARCHES};
use super::record::{record_from_dir, RunRecord};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

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
pub(crate) fn save_record(run: &PlannedRun, mut r: RunRecord) -> std::io::Result<RunRecord> {
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

/// Makes the child die when this process dies (Linux: `PR_SET_PDEATHSIG` with `SIGKILL`, set in
/// the child between fork and exec; if the parent is already gone by then, the child exits at
/// once). The signal follows the death of the thread that spawned the child, so spawn from a
/// thread that lives as long as the comparison (here: the caller of
/// [`super::executor::run_all`]) or the child.
pub fn die_with_parent(cmd: &mut Command) {
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
