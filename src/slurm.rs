//! Slurm's command-line tools (`sbatch`, `squeue`, `scontrol`, `scancel`) behind typed calls,
//! for the commands that run their solves as cluster jobs (`compare` and `city` with
//! `--executor slurm`). The cluster is found as Slurm's own tools find it (`SLURM_CONF`, else
//! the site's configuration); nothing here needs accounting storage: jobs are followed with
//! `squeue --states=all`, which lists finished jobs for the controller's `MinJobAge`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;

/// How jobs are submitted.
#[derive(Clone, Debug, PartialEq)]
pub struct SlurmOptions {
    /// Partition (`--partition`); `None`: the cluster's default.
    pub partition: Option<String>,
    /// Account (`--account`); `None`: the user's default.
    pub account: Option<String>,
    /// Memory per task (`--mem`), in Slurm's notation (`4G`).
    pub mem: String,
    /// Seconds added to each job's time limit for start-up (loading the binary, building the
    /// model, writing the outputs).
    pub startup: f64,
    /// Further `sbatch` arguments, passed as given (`--qos=long`, `--constraint=avx2`).
    pub extra: Vec<String>,
}

impl Default for SlurmOptions {
    fn default() -> SlurmOptions {
        SlurmOptions { partition: None, account: None, mem: "4G".into(), startup: 120.0, extra: Vec::new() }
    }
}

/// What to start the cluster with, said in every error about a missing or unreachable one.
const WHAT_TO_START: &str =
    "run `scripts/slurm-local.sh start` (a single-node cluster on this machine) or load your site's slurm module";

/// Why a Slurm call failed.
#[derive(Debug, thiserror::Error)]
pub enum SlurmError {
    /// A Slurm command is not on `PATH`.
    #[error("`{command}` is not installed or not on PATH: {WHAT_TO_START}")]
    NotInstalled {
        /// The command.
        command: String,
    },
    /// The controller does not answer.
    #[error("the Slurm controller does not answer ({detail}): {WHAT_TO_START}, and check SLURM_CONF")]
    Unreachable {
        /// What `scontrol ping` said.
        detail: String,
    },
    /// The partition does not exist.
    #[error("Slurm partition `{name}` does not exist (partitions: {known}); give one with --slurm-partition")]
    BadPartition {
        /// The partition asked for.
        name: String,
        /// The cluster's partitions.
        known: String,
    },
    /// A command ran and failed.
    #[error("`{command}` failed: {detail}")]
    Command {
        /// The command line.
        command: String,
        /// Its error output.
        detail: String,
    },
    /// A file could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// Runs a Slurm command and returns its standard output, or a typed error.
fn run(program: &str, args: &[String]) -> Result<String, SlurmError> {
    let out = Command::new(program).args(args).output().map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => SlurmError::NotInstalled { command: program.into() },
        _ => SlurmError::Command { command: program.into(), detail: e.to_string() },
    })?;
    if out.status.success() {
        return Ok(String::from_utf8_lossy(&out.stdout).into_owned());
    }
    let mut detail = String::from_utf8_lossy(&out.stderr).trim().to_string();
    if detail.is_empty() {
        detail = String::from_utf8_lossy(&out.stdout).trim().to_string();
    }
    Err(SlurmError::Command { command: format!("{program} {}", args.join(" ")), detail })
}

/// Checks, before anything is written, that jobs can be submitted: `sbatch` is installed, the
/// controller answers, and the partition (if one is given) exists.
pub fn check(opts: &SlurmOptions) -> Result<(), SlurmError> {
    for c in ["sbatch", "squeue", "scancel"] {
        if !on_path(c) {
            return Err(SlurmError::NotInstalled { command: c.into() });
        }
    }
    match run("scontrol", &["ping".into()]) {
        Ok(text) if text.contains("is UP") => {}
        Ok(text) | Err(SlurmError::Command { detail: text, .. }) => {
            return Err(SlurmError::Unreachable {
                detail: text.trim().lines().next().unwrap_or("no answer").to_string(),
            })
        }
        Err(e) => return Err(e),
    }
    if let Some(p) = &opts.partition {
        let names = partitions()?;
        if !names.contains(p) {
            return Err(SlurmError::BadPartition { name: p.clone(), known: names.join(", ") });
        }
    }
    Ok(())
}

/// Whether `program` is an executable file in a directory of `PATH`.
fn on_path(program: &str) -> bool {
    std::env::var_os("PATH").is_some_and(|p| {
        std::env::split_paths(&p).any(|d| {
            let f = d.join(program);
            f.is_file()
                && std::fs::metadata(&f)
                    .is_ok_and(|m| std::os::unix::fs::PermissionsExt::mode(&m.permissions()) & 0o111 != 0)
        })
    })
}

/// The cluster's partitions, in `sinfo`'s order.
fn partitions() -> Result<Vec<String>, SlurmError> {
    let text = run("sinfo", &["-h".into(), "-o".into(), "%R".into()])?;
    let mut names: Vec<String> = text.lines().map(|l| l.trim().to_string()).filter(|l| !l.is_empty()).collect();
    names.dedup();
    Ok(names)
}

/// One batch job (or job array) to submit.
#[derive(Clone, Debug)]
pub struct Job {
    /// Job name (`--job-name`).
    pub name: String,
    /// The batch script.
    pub script: PathBuf,
    /// Task indices `0..n` of a job array; `None`: a single job.
    pub array: Option<usize>,
    /// CPUs per task.
    pub cpus: u32,
    /// Time limit, seconds (rounded up to whole minutes, Slurm's unit).
    pub seconds: f64,
    /// Working directory of the job.
    pub chdir: PathBuf,
    /// Standard output and error of the job (Slurm's `%A`, `%a`, `%j` patterns allowed).
    pub log: PathBuf,
    /// Start only after these jobs ended successfully (`--dependency=afterok:…`).
    pub after_ok: Vec<String>,
}

/// The `sbatch` arguments of `job` under `opts`.
pub fn sbatch_args(opts: &SlurmOptions, job: &Job) -> Vec<String> {
    let minutes = ((job.seconds + opts.startup) / 60.0).ceil().max(1.0) as u64;
    let mut a = vec![
        "--parsable".to_string(),
        format!("--job-name={}", job.name),
        format!("--cpus-per-task={}", job.cpus.max(1)),
        "--ntasks=1".into(),
        format!("--time={minutes}"),
        format!("--mem={}", opts.mem),
        format!("--chdir={}", job.chdir.display()),
        format!("--output={}", job.log.display()),
    ];
    if let Some(n) = job.array {
        a.push(format!("--array=0-{}", n.saturating_sub(1)));
    }
    if !job.after_ok.is_empty() {
        a.push(format!("--dependency=afterok:{}", job.after_ok.join(":")));
    }
    if let Some(p) = &opts.partition {
        a.push(format!("--partition={p}"));
    }
    if let Some(acc) = &opts.account {
        a.push(format!("--account={acc}"));
    }
    a.extend(opts.extra.iter().cloned());
    a.push(job.script.display().to_string());
    a
}

/// Submits a job and returns its id.
pub fn submit(opts: &SlurmOptions, job: &Job) -> Result<String, SlurmError> {
    let text = run("sbatch", &sbatch_args(opts, job))?;
    // `--parsable` prints `id` or `id;cluster`.
    let id = text.trim().split(';').next().unwrap_or("").to_string();
    if id.is_empty() || !id.chars().all(|c| c.is_ascii_digit()) {
        return Err(SlurmError::Command { command: "sbatch".into(), detail: format!("unexpected answer {text:?}") });
    }
    Ok(id)
}

/// A job's (or array task's) state as `squeue` reports it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct JobState {
    /// Slurm's state name (`PENDING`, `RUNNING`, `COMPLETED`, `TIMEOUT`, …).
    pub state: String,
    /// Slurm's reason (`Resources`, `Dependency`, `None`, …).
    pub reason: String,
}

impl JobState {
    /// Whether the job will not run any more.
    pub fn is_finished(&self) -> bool {
        !matches!(
            self.state.as_str(),
            "PENDING" | "RUNNING" | "CONFIGURING" | "COMPLETING" | "SUSPENDED" | "REQUEUED" | "RESIZING" | "SIGNALING"
        ) && !self.state.starts_with("REQUEUE")
            && !self.state.starts_with("STAGE")
    }
}

/// The states of a job's tasks (`None`: the job is not an array), from
/// `squeue --states=all`; tasks the controller no longer lists are absent.
pub fn states(job: &str) -> Result<BTreeMap<Option<usize>, JobState>, SlurmError> {
    let args: Vec<String> = ["-h", "-r", "--states=all", "-j", job, "-o", "%K|%T|%r"].map(String::from).to_vec();
    let text = match run("squeue", &args) {
        Ok(t) => t,
        // A job the controller has forgotten: nothing to list.
        Err(SlurmError::Command { detail, .. }) if detail.contains("Invalid job id") => String::new(),
        Err(e) => return Err(e),
    };
    Ok(parse_states(&text))
}

/// Parses `squeue -o "%K|%T|%r"` lines.
pub fn parse_states(text: &str) -> BTreeMap<Option<usize>, JobState> {
    text.lines()
        .filter_map(|l| {
            let mut f = l.trim().split('|');
            let (task, state, reason) = (f.next()?, f.next()?, f.next().unwrap_or(""));
            if state.is_empty() {
                return None;
            }
            Some((task.parse().ok(), JobState { state: state.to_string(), reason: reason.to_string() }))
        })
        .collect()
}

/// Cancels jobs or array tasks (`123`, `123_4`).
pub fn cancel(ids: &[String]) -> Result<(), SlurmError> {
    if ids.is_empty() {
        return Ok(());
    }
    run("scancel", ids).map(|_| ())
}

/// Copies `exe` to `stage/netspec-<digest>` unless it is there (jobs run this copy, so a
/// rebuild during a run changes nothing); returns the copy and the digest.
pub fn stage_binary(exe: &Path, stage: &Path) -> std::io::Result<(PathBuf, String)> {
    let bytes = std::fs::read(exe)?;
    let digest = crate::io::digest(&[&bytes]);
    let staged = stage.join(format!("netspec-{digest}"));
    if !staged.exists() {
        std::fs::create_dir_all(stage)?;
        let tmp = stage.join(format!(".netspec-{digest}.tmp"));
        std::fs::write(&tmp, &bytes)?;
        std::fs::set_permissions(&tmp, std::os::unix::fs::PermissionsExt::from_mode(0o755))?;
        std::fs::rename(&tmp, &staged)?;
    }
    Ok((staged, digest))
}

/// Writes an executable batch script that runs `argv` (each word quoted for the shell).
pub fn write_script(path: &Path, argv: &[String]) -> Result<(), SlurmError> {
    let quoted: Vec<String> = argv.iter().map(|a| shell_quote(a)).collect();
    let text = format!("#!/bin/sh\nexec {}\n", quoted.join(" "));
    let io = |source| SlurmError::Io { path: path.to_path_buf(), source };
    std::fs::write(path, text).map_err(io)?;
    std::fs::set_permissions(path, std::os::unix::fs::PermissionsExt::from_mode(0o755)).map_err(io)
}

/// A word quoted for `sh` (left bare when it is plainly safe; `$SLURM_ARRAY_TASK_ID` is kept
/// as a variable).
fn shell_quote(word: &str) -> String {
    if word == "$SLURM_ARRAY_TASK_ID" {
        return "\"$SLURM_ARRAY_TASK_ID\"".into();
    }
    if !word.is_empty() && word.chars().all(|c| c.is_ascii_alphanumeric() || "/._-=+:,".contains(c)) {
        return word.to_string();
    }
    format!("'{}'", word.replace('\'', "'\\''"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn states_parse_and_finish() {
        let s = parse_states("0|COMPLETED|None\n1|RUNNING|None\n2|PENDING|Resources\nN/A|TIMEOUT|None\n");
        assert_eq!(s.len(), 4);
        assert!(s[&Some(0)].is_finished() && !s[&Some(1)].is_finished() && !s[&Some(2)].is_finished());
        assert_eq!(s[&None].state, "TIMEOUT");
        assert!(s[&None].is_finished());
    }

    #[test]
    fn sbatch_arguments() {
        let job = Job {
            name: "x".into(),
            script: "/o/task.sh".into(),
            array: Some(3),
            cpus: 2,
            seconds: 70.0,
            chdir: "/w".into(),
            log: "/o/%A_%a.txt".into(),
            after_ok: vec!["7".into()],
        };
        let opts = SlurmOptions { partition: Some("p".into()), startup: 60.0, ..SlurmOptions::default() };
        let a = sbatch_args(&opts, &job);
        for want in
            ["--array=0-2", "--cpus-per-task=2", "--time=3", "--mem=4G", "--dependency=afterok:7", "--partition=p"]
        {
            assert!(a.contains(&want.to_string()), "{want}: {a:?}");
        }
        assert_eq!(a.last().unwrap(), "/o/task.sh");
        assert_eq!(shell_quote("it's"), "'it'\\''s'");
    }
}
