//! The `netspec` command-line tool: a thin layer over the library.

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand};
use netspec::io::{read_model_file, write_model_file};
use netspec::milp::Tolerances;
use netspec::heuristics::run::Method;
use netspec::report::{SolveReport, SCHEMA_VERSION};
use netspec::solvers::{LogTarget, SolveOptions, SolverKind};
use std::path::PathBuf;
use std::process::ExitCode;

mod cli {
    pub mod city;
    pub mod design;
    pub mod search;
}

/// Exit code when the solver's answer fails netspec's independent check.
const EXIT_CHECK_FAILED: u8 = 3;

#[derive(Parser)]
#[command(name = "netspec", version, about = "Network design from functional specifications, by integer programming", long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve an MPS or LP file and check the answer independently.
    #[command(name = "solve-file")]
    SolveFile {
        /// The model file (`.mps` or `.lp`).
        file: PathBuf,
        #[command(flatten)]
        solve: SolveArgs,
        /// Also write the JSON result (schema in docs/result-schema.md) here; `-` for stdout.
        #[arg(long, value_name = "PATH")]
        json: Option<PathBuf>,
    },
    /// Design a network from a spec file (TOML or JSON): build the MILP, solve it, check and
    /// validate the answer, and write result.json, network.svg and network.png.
    Solve {
        /// The spec file.
        spec: PathBuf,
        #[command(flatten)]
        solve: SolveArgs,
        /// Output directory (default: out/<spec name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Also write the MILP (`.lp` or `.mps`, by extension).
        #[arg(long, value_name = "FILE")]
        export: Option<PathBuf>,
        /// Build and export the model without solving it.
        #[arg(long)]
        no_solve: bool,
    },
    /// Compare backends on spec files: each run in its own process, killed at the time limit
    /// plus a grace period, recorded as it ends (rerun to resume); writes results.md,
    /// results.csv, results.json, a performance profile (profile.svg) and a bar chart of the
    /// time per instance and backend (bars.svg) to --out.
    Compare {
        /// Spec files.
        #[arg(required_unless_present = "manifest")]
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
        /// Output directory.
        #[arg(long, default_value = "out/compare")]
        out: PathBuf,
    },
    /// Lay out a city's streets (§5.1): sub-regions from the major roads, levels 2–4 per
    /// sub-region (in parallel), smoothing; writes city.json, streets.geojson, city.svg/png and
    /// every level's spec, mesh and result under regions/. Rerun to resume an interrupted run.
    City {
        /// The city spec (TOML).
        spec: PathBuf,
        /// Backend (default: the spec's, else the embedded HiGHS).
        #[arg(long, value_name = "NAME")]
        solver: Option<SolverKind>,
        /// Time limit for every level's solve, seconds (default: each level's `time_limit`).
        #[arg(long, value_name = "SECONDS")]
        time_limit: Option<f64>,
        /// Total thread budget (default: the spec's).
        #[arg(long)]
        threads: Option<u32>,
        /// Threads per solve (default: the spec's).
        #[arg(long)]
        threads_per_solve: Option<u32>,
        /// Relative gap.
        #[arg(long, value_name = "REL")]
        gap: Option<f64>,
        /// Solve every level again even if an earlier run finished it.
        #[arg(long)]
        fresh: bool,
        /// Output directory (default: out/<city name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Convert a model between MPS and LP (formats chosen by extension).
    Convert {
        /// Input file (`.mps` or `.lp`).
        input: PathBuf,
        /// Output file (`.mps` or `.lp`).
        output: PathBuf,
    },
    /// List the compiled backends with their versions and capabilities.
    Solvers {
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// Options shared by every command that solves.
#[derive(Args, Clone, Default)]
struct SolveArgs {
    /// Backend: highs, cbc, scip, microlp or good_lp (default: the embedded HiGHS); for `solve`,
    /// also a search without a solver: heuristic (construction and local search) or anneal (the
    /// paper's stochastic search).
    #[arg(long, value_name = "NAME")]
    solver: Option<Method>,
    /// Wall-clock time limit in seconds.
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
    /// Relative MIP gap at which to stop.
    #[arg(long, value_name = "REL")]
    gap: Option<f64>,
    /// Absolute MIP gap at which to stop.
    #[arg(long, value_name = "ABS")]
    abs_gap: Option<f64>,
    /// Number of threads.
    #[arg(long)]
    threads: Option<u32>,
    /// Random seed.
    #[arg(long)]
    seed: Option<u64>,
    /// Branch-and-bound node limit.
    #[arg(long)]
    node_limit: Option<u64>,
    /// Show the solver's own log on stdout.
    #[arg(long, conflicts_with = "log_file")]
    verbose: bool,
    /// Write the solver's own log to this file.
    #[arg(long, value_name = "PATH")]
    log_file: Option<PathBuf>,
}

impl SolveArgs {
    fn options(&self) -> SolveOptions {
        SolveOptions {
            time_limit: self.time_limit,
            rel_gap: self.gap,
            abs_gap: self.abs_gap,
            threads: self.threads,
            seed: self.seed,
            node_limit: self.node_limit,
            log: match (&self.log_file, self.verbose) {
                (Some(p), _) => LogTarget::File(p.clone()),
                (None, true) => LogTarget::Stdout,
                (None, false) => LogTarget::Quiet,
            },
            mip_start: None,
            progress: None,
        }
    }

    fn solver(&self) -> Result<SolverKind> {
        match self.solver {
            Some(Method::Milp(k)) => Ok(k),
            Some(m) => bail!("`{m}` is a design search, not a MILP backend: it needs a spec (`netspec solve`)"),
            None => SolverKind::default_kind().context("no backend compiled in"),
        }
    }
}

fn main() -> ExitCode {
    // Behave like other Unix tools when the reader of our output goes away (`| head`): end
    // quietly instead of panicking on a broken pipe.
    #[cfg(unix)]
    // SAFETY: resetting a signal disposition to its default before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            // Print the cause chain, skipping causes whose text the message above already shows
            // (our error types name the file and then embed their source).
            let mut shown = e.to_string();
            eprintln!("error: {shown}");
            for cause in e.chain().skip(1) {
                let text = cause.to_string();
                if !shown.contains(&text) {
                    eprintln!("  caused by: {text}");
                }
                shown = text;
            }
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::SolveFile { file, solve, json } => solve_file(&file, &solve, json.as_deref()),
        Command::Solve { spec, solve, out, export, no_solve } => cli::design::solve_spec(&spec, &solve, out, export, no_solve),
        Command::Compare { specs, manifest, solvers, time_limit, grace, seeds, threads, paper_limits, out } => {
            let manifest = match manifest {
                Some(m) => netspec::compare::Manifest::load(&m).map_err(anyhow::Error::msg)?,
                None => netspec::compare::Manifest::from_specs(&specs),
            };
            let solvers: Vec<String> = if solvers.is_empty() {
                SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp).map(|k| k.name().to_string()).collect()
            } else {
                solvers.iter().map(|k| k.name().to_string()).collect()
            };
            let settings = netspec::compare::CompareSettings { manifest, solvers: solvers.clone(), time_limit, grace, seeds, threads, paper_limits };
            std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
            let exe = std::env::current_exe().context("locating the netspec binary")?;
            let records = netspec::compare::run_all(&exe, &settings, &out, |r, resumed| {
                println!(
                    "{:<24} {:<8} {:<16} {:>8.2} s {}{}",
                    r.instance,
                    r.solver,
                    r.status,
                    r.wall_time,
                    if r.valid { "valid" } else { "-" },
                    if resumed { " (resumed)" } else { "" }
                );
            })
            .with_context(|| format!("running the comparison into {}", out.display()))?;
            let summary = netspec::compare::summarize(&records, &solvers, time_limit);
            let md = netspec::compare::markdown(&settings.manifest, &records, &solvers, &summary);
            let cpu = std::fs::read_to_string("/proc/cpuinfo")
                .ok()
                .and_then(|t| t.lines().find(|l| l.starts_with("model name")).and_then(|l| l.split(':').nth(1)).map(|s| s.trim().to_string()))
                .unwrap_or_else(|| "unknown CPU".into());
            let command: Vec<String> = std::env::args().collect();
            let header = format!(
                "netspec {} compare, time limit {time_limit} s{}, grace {grace} s; {cpu}, {} cores\n\nCommand: `{}`\n\n",
                env!("CARGO_PKG_VERSION"),
                if paper_limits { " (each row at most the paper's time for it)" } else { "" },
                std::thread::available_parallelism().map_or(0, |n| n.get()),
                command.join(" ")
            );
            std::fs::write(out.join("results.md"), header + &md)?;
            std::fs::write(out.join("results.csv"), netspec::compare::csv(&records))?;
            std::fs::write(out.join("profile.svg"), netspec::compare::performance_profile_svg(&records, &solvers, time_limit))?;
            std::fs::write(out.join("bars.svg"), netspec::compare::bar_chart_svg(&settings.manifest, &records, &solvers, time_limit))?;
            let all = serde_json::json!({ "netspec_version": env!("CARGO_PKG_VERSION"), "command": command, "cpu": cpu, "settings": settings, "records": records, "summary": summary });
            std::fs::write(out.join("results.json"), serde_json::to_string_pretty(&all)? + "\n")?;
            print!("\n{md}");
            Ok(ExitCode::SUCCESS)
        }
        Command::City { spec, solver, time_limit, threads, threads_per_solve, gap, fresh, out } => {
            cli::city::run_city(&spec, cli::city::CityArgs { solver, time_limit, threads, threads_per_solve, gap, fresh, out })
        }
        Command::Convert { input, output } => {
            let read = read_model_file(&input)?;
            for w in &read.warnings {
                eprintln!("warning: {}: {w}", input.display());
            }
            let map = write_model_file(&read.model, &output)?;
            println!(
                "wrote {} ({}){}",
                output.display(),
                read.model.stats(),
                if map.is_identity() { String::new() } else { format!("; {} names sanitised", map.vars.len() + map.rows.len()) }
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Solvers { json } => {
            let list = netspec::report::solver_list();
            if json {
                println!("{}", serde_json::to_string_pretty(&list)?);
            } else {
                for s in &list {
                    println!("{:<8} {:<10} {}", s.name, s.version, s.capability_summary());
                }
                let missing: Vec<_> = SolverKind::ALL.iter().filter(|k| !k.is_compiled()).map(|k| k.name()).collect();
                if !missing.is_empty() {
                    println!("not compiled in: {} (enable the cargo features of the same names)", missing.join(", "));
                }
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn solve_file(file: &std::path::Path, args: &SolveArgs, json: Option<&std::path::Path>) -> Result<ExitCode> {
    let read = read_model_file(file)?;
    for w in &read.warnings {
        eprintln!("warning: {}: {w}", file.display());
    }
    let kind = args.solver()?;
    let solver = kind.instance()?;
    let options = args.options();
    let result = solver.solve(&read.model, &options).with_context(|| format!("solving {}", file.display()))?;
    let report = SolveReport::new(file.display().to_string(), &read.model, options, result, &Tolerances::default());
    print!("{}", report.summary());
    if let Some(path) = json {
        let text = serde_json::to_string_pretty(&report)?;
        if path.as_os_str() == "-" {
            println!("{text}");
        } else {
            std::fs::write(path, text + "\n").with_context(|| format!("writing {}", path.display()))?;
            println!("result     {} (schema v{SCHEMA_VERSION})", path.display());
        }
    }
    if report.check.as_ref().is_some_and(|c| !c.is_feasible()) {
        return Ok(ExitCode::from(EXIT_CHECK_FAILED));
    }
    if let netspec::solvers::Termination::Error(e) = &report.result.termination {
        bail!("the solver failed: {e}");
    }
    Ok(ExitCode::SUCCESS)
}
