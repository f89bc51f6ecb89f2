//! `netspec compare`: runs [`netspec::compare::run_all`] and writes its report, printing each
//! run as it ends.

use super::args::ExecutorArgs;
use anyhow::{bail, Context, Result};
use netspec::compare::makespan::{self, Shape};
use netspec::compare::{CompareSettings, Event, Executor, Manifest, Report, RunSource};
use netspec::pipeline::Method;
use netspec::solvers::SolverKind;
use netspec::spec::Variant;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `netspec compare`'s arguments.
#[derive(clap::Args)]
pub struct CompareArgs {
    /// Spec files.
    #[arg(required_unless_present_any = ["manifest", "merge"])]
    specs: Vec<PathBuf>,
    /// A manifest of instances with the paper's figures (e.g. models/table1.toml).
    #[arg(long, conflicts_with = "specs")]
    manifest: Option<PathBuf>,
    /// Backends, comma-separated (default: every compiled one but good_lp); the searches
    /// `heuristic` and `anneal` may be listed too.
    #[arg(long, value_delimiter = ',')]
    solvers: Vec<Method>,
    /// Time limit per run, seconds.
    #[arg(long, default_value_t = 60.0)]
    time_limit: f64,
    /// Seconds past the limit before a run is killed.
    #[arg(long, default_value_t = 10.0)]
    grace: f64,
    /// Seeds to run (default: one run with each solver's default).
    #[arg(long, value_delimiter = ',')]
    seeds: Vec<u64>,
    /// Threads per run.
    #[arg(long)]
    threads: Option<u32>,
    /// Give each row the paper's own time for it as its limit (capped at --time-limit).
    #[arg(long)]
    paper_limits: bool,
    /// Formulations, comma-separated (`paper`, `strong`, `strong:out_arcs=off`): every
    /// backend runs with each, as its own column (`highs/strong`). Default: the spec's own.
    #[arg(long, value_delimiter = ',')]
    formulations: Vec<Variant>,
    /// Only the manifest rows with these names (comma-separated; `*` and `?` match any run
    /// of characters and one: `2*`, `*-L4`).
    #[arg(long, value_delimiter = ',', value_name = "ROW")]
    rows: Vec<String>,
    /// Solve without the heuristic's MIP start (each child gets `solve --no-start`).
    #[arg(long)]
    no_start: bool,
    #[command(flatten)]
    executor: ExecutorArgs,
    /// Estimate how long these runs take on clusters of K nodes with C cores each
    /// (comma-separated `KxC`: `1x2,20x2`), by list scheduling their recorded wall times;
    /// printed and added to results.md.
    #[arg(long, value_delimiter = ',', value_name = "KxC")]
    makespan: Vec<Shape>,
    /// Combine finished comparisons (each DIR's results.json) into one report in --out
    /// without solving: every column of every DIR, in the order given (column labels must
    /// differ). With --manifest, its rows are the table's; else the first DIR's.
    #[arg(long, value_delimiter = ',', value_name = "DIR", conflicts_with_all = ["specs", "solvers", "seeds", "formulations", "no_start", "paper_limits", "threads"])]
    merge: Vec<PathBuf>,
    /// Output directory.
    #[arg(long, default_value = "out/compare")]
    out: PathBuf,
}

impl CompareArgs {
    /// Runs the comparison, or merges finished ones with `--merge`.
    pub fn run(self) -> Result<ExitCode> {
        if !self.merge.is_empty() {
            return merge(&self.merge, self.manifest.as_deref(), &self.rows, &self.out, &self.makespan);
        }
        run(self)
    }
}

/// `netspec compare-task`'s arguments.
#[derive(clap::Args)]
pub struct TaskArgs {
    /// The array's plan (`slurm/plan-*.json` in the comparison's folder).
    plan: PathBuf,
    /// The task's index in it.
    index: usize,
}

impl TaskArgs {
    /// Runs the task.
    pub fn run(self) -> Result<ExitCode> {
        task(&self.plan, self.index)
    }
}

fn command() -> Vec<String> {
    std::env::args().collect()
}

/// Combines finished comparisons into one report.
fn merge(dirs: &[PathBuf], manifest: Option<&Path>, rows: &[String], out: &Path, shapes: &[Shape]) -> Result<ExitCode> {
    let manifest = manifest.map(|m| Manifest::load(m).and_then(|m| m.select(rows))).transpose()?;
    let merged = netspec::compare::merge(dirs, manifest)?;
    let from: Vec<String> = dirs.iter().map(|d| format!("`{}`", d.display())).collect();
    let settings = serde_json::json!({ "manifest": merged.manifest, "time_limit": merged.time_limit, "merged_from": merged.sources });
    let md = netspec::compare::write_report(
        out,
        Report {
            manifest: &merged.manifest,
            records: &merged.records,
            columns: &merged.columns,
            time_limit: merged.time_limit,
            what: &format!("merged from {}", from.join(", ")),
            command: &command(),
            settings,
            makespan: &makespan::estimate(&merged.records, shapes),
        },
    )?;
    print!("{md}");
    Ok(ExitCode::SUCCESS)
}

/// Runs a comparison.
fn run(a: CompareArgs) -> Result<ExitCode> {
    let executor = a.executor.slurm()?.map_or(Executor::Local, Executor::Slurm);
    let manifest = match &a.manifest {
        Some(m) => Manifest::load(m)?,
        None => Manifest::from_specs(&a.specs),
    };
    let manifest = manifest.select(&a.rows)?;
    for (flag, names) in [
        ("--solvers", a.solvers.iter().map(|m| m.to_string()).collect::<Vec<_>>()),
        ("--formulations", a.formulations.iter().map(|f| f.to_string()).collect()),
    ] {
        if let Some(dup) = names.iter().enumerate().find_map(|(i, n)| names[..i].contains(n).then_some(n)) {
            bail!("{flag} names `{dup}` twice: each column must differ");
        }
    }
    let solvers: Vec<String> = if a.solvers.is_empty() {
        SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp).map(|k| k.name().to_string()).collect()
    } else {
        a.solvers.iter().map(|k| k.name().to_string()).collect()
    };
    for (flag, v) in [("--time-limit", a.time_limit), ("--grace", a.grace)] {
        if v.is_nan() || v < 0.0 {
            bail!("{flag} must be a number of seconds ≥ 0, got {v}");
        }
    }
    if a.threads == Some(0) {
        bail!("--threads must be ≥ 1, got 0");
    }
    let interrupt = Some(super::interrupt::install()?);
    let formulations: Vec<String> = a.formulations.iter().map(|f| f.to_string()).collect();
    let settings = CompareSettings {
        manifest,
        solvers,
        formulations,
        time_limit: a.time_limit,
        grace: a.grace,
        seeds: a.seeds,
        threads: a.threads,
        paper_limits: a.paper_limits,
        no_start: a.no_start,
        interrupt,
        executor,
    };
    // The columns of every table and chart: a backend, or a (backend, formulation) pair.
    let columns: Vec<String> = settings.methods().into_iter().map(|(label, _, _)| label).collect();
    let exe = std::env::current_exe().context("locating the netspec binary")?;
    let records = netspec::compare::run_all(&exe, &settings, &a.out, |event| {
        let (r, source) = match event {
            Event::Run(r, source) => (r, source),
            Event::Submitted { job, tasks } => {
                println!("submitted Slurm job array {job} ({tasks} tasks)");
                return;
            }
            Event::Queue { pending, running } => {
                println!("slurm: {running} running, {pending} pending");
                return;
            }
        };
        println!(
            "{:<24} {:<14} {:<16} {:>8.2} s {}{}{}",
            r.instance,
            r.solver,
            r.status,
            r.wall_time,
            if r.valid { "valid" } else { "-" },
            match source {
                RunSource::Solved => String::new(),
                RunSource::Resumed => " (resumed)".into(),
                RunSource::Rerun(why) => format!(" (solved again: {})", why.join(", ")),
            },
            r.error.as_ref().map_or(String::new(), |e| format!("\n    {e}"))
        );
    })
    .with_context(|| format!("running the comparison into {}", a.out.display()))?;
    let what = format!(
        "time limit {} s{}, grace {} s",
        a.time_limit,
        if a.paper_limits { " (each row at most the paper's time for it)" } else { "" },
        a.grace
    );
    let md = netspec::compare::write_report(
        &a.out,
        Report {
            manifest: &settings.manifest,
            records: &records,
            columns: &columns,
            time_limit: a.time_limit,
            what: &what,
            command: &command(),
            settings: serde_json::to_value(&settings)?,
            makespan: &makespan::estimate(&records, &a.makespan),
        },
    )?;
    print!("\n{md}");
    if settings.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
        println!("interrupted: the runs recorded above are kept; rerun to resume");
        return Ok(ExitCode::from(super::interrupt::EXIT_INTERRUPTED));
    }
    let failed = records.iter().filter(|r| r.error.is_some()).count();
    if failed > 0 {
        eprintln!(
            "error: {failed} of {} runs could not run (their causes are listed above and in results.md)",
            records.len()
        );
        return Ok(ExitCode::FAILURE);
    }
    Ok(ExitCode::SUCCESS)
}

/// One task of a Slurm job array: solves the plan's run `index` and writes its record.
fn task(plan: &Path, index: usize) -> Result<ExitCode> {
    let exe = std::env::current_exe().context("locating the netspec binary")?;
    let r = netspec::compare::cluster::run_task(&exe, plan, index)
        .with_context(|| format!("task {index} of {}", plan.display()))?;
    println!("{} {} {} {:.2} s", r.instance, r.solver, r.status, r.wall_time);
    Ok(ExitCode::SUCCESS)
}
