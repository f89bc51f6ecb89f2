//! The `netspec` command-line tool: a thin layer over the library.

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand};
use netspec::pipeline::Method;
use netspec::io::{read_model_file, write_model_file};
use netspec::milp::Tolerances;
use netspec::report::{SolveReport, SCHEMA_VERSION};
use netspec::solvers::{InvalidOption, LogTarget, RawParam, SolveOptions, SolverKind, Termination};
use std::path::PathBuf;
use std::process::ExitCode;

mod cli {
    pub mod city;
    pub mod design;
    pub mod interrupt;
    pub mod search;
    pub mod traffic;
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
    /// Solve an MPS or LP file (also `.mps.gz`, `.lp.gz`) and check the answer independently.
    #[command(name = "solve-file")]
    SolveFile {
        /// The model file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
        file: PathBuf,
        #[command(flatten)]
        solve: SolveArgs,
        /// Start from the solution in this file (`name value` lines, e.g. an earlier `--sol`).
        /// netspec checks it first; a start that fails the check is reported and not used.
        #[arg(long, value_name = "FILE.sol")]
        start: Option<PathBuf>,
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
        /// Formulation recipe, replacing the spec's: paper, tight or strong.
        #[arg(long, value_name = "RECIPE")]
        formulation: Option<netspec::spec::RecipeName>,
        /// Solve only the LP relaxation (with the recipe's cutting-plane rounds) and print its
        /// bound.
        #[arg(long, conflicts_with = "no_solve")]
        relax: bool,
        /// When the spec is infeasible, do not look for the requirements that conflict.
        #[arg(long)]
        no_explain: bool,
        /// Time budget for explaining an infeasible spec, seconds.
        #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
        explain_time: f64,
        /// Start from this design: an earlier `result.json` of the same spec, or a `.sol` file
        /// of this model (`--sol`). It is checked first; a start that fails is reported, not used.
        /// Default: the construction heuristic's design (a twentieth of the time limit, ≤ 1 s; while
        /// it has no design, up to a fifth, ≤ 60 s; one search per solver thread).
        #[arg(long, value_name = "FILE", conflicts_with = "no_start")]
        start: Option<PathBuf>,
        /// Solve without a MIP start.
        #[arg(long)]
        no_start: bool,
    },
    /// Compare backends on spec files: each run in its own process, killed at the time limit
    /// plus a grace period, recorded as it ends (rerun to resume); writes results.md,
    /// results.csv, results.json, a performance profile (profile.svg) and a bar chart of the
    /// time per instance and backend (bars.svg) to --out.
    Compare {
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
        /// Formulation recipes, comma-separated (paper, tight, strong): every backend runs with
        /// each, as its own column (`highs/strong`). Default: the spec's own.
        #[arg(long, value_delimiter = ',')]
        formulations: Vec<netspec::spec::RecipeName>,
        /// Solve without the heuristic's MIP start (each child gets `solve --no-start`).
        #[arg(long)]
        no_start: bool,
        /// Combine finished comparisons (each DIR's results.json) into one report in --out
        /// without solving: every column of every DIR, in the order given (column labels must
        /// differ). With --manifest, its rows are the table's; else the first DIR's.
        #[arg(long, value_delimiter = ',', value_name = "DIR", conflicts_with_all = ["specs", "solvers", "seeds", "formulations", "no_start", "paper_limits", "threads"])]
        merge: Vec<PathBuf>,
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
    /// Evaluate designed street networks in SUMO (installed by scripts/setup.sh): export to
    /// SUMO's plain XML with a road type per level, netconvert, seeded through and local
    /// trips routed by duarouter, a headless simulation; writes traffic.json, volume.svg/png
    /// and traveltime.svg/png per design, and with several designs (same demand) comparison.md,
    /// comparison.json and comparison.svg/png.
    Traffic {
        /// Designs: `netspec city` output directories, `netspec solve` output directories or
        /// result.json files (a city's regions/NN-name/L<n>/ too).
        #[arg(required = true)]
        designs: Vec<PathBuf>,
        /// Names of the designs, comma-separated (default: their directory names).
        #[arg(long, value_delimiter = ',')]
        labels: Vec<String>,
        /// Seconds during which trips depart.
        #[arg(long, default_value_t = 3600.0, value_name = "SECONDS")]
        duration: f64,
        /// Through trips per hour (boundary to the far side of the boundary).
        #[arg(long, default_value_t = 300.0, value_name = "PER_HOUR")]
        through_rate: f64,
        /// Local trips per hour (interior point to interior point).
        #[arg(long, default_value_t = 600.0, value_name = "PER_HOUR")]
        local_rate: f64,
        /// Seed of the demand, duarouter and sumo.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Metres per model unit (default: the city spec's; 20 for solve results).
        #[arg(long, value_name = "M")]
        metres_per_unit: Option<f64>,
        /// Level of a solve result's streets: 1 major, 2 collector, 3 local (default), 4 cul-de-sac.
        #[arg(long, value_parser = clap::value_parser!(u8).range(1..=4))]
        level: Option<u8>,
        /// SUMO_HOME to use (default: $SUMO_HOME, then the copy scripts/setup.sh installs, then PATH).
        #[arg(long, value_name = "DIR")]
        sumo_home: Option<PathBuf>,
        /// Output directory.
        #[arg(long, value_name = "DIR", default_value = "out/traffic")]
        out: PathBuf,
    },
    /// Convert a model between MPS and LP (formats chosen by extension; `.gz` compressed).
    Convert {
        /// Input file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
        input: PathBuf,
        /// Output file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
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
    /// A solver's own parameter, passed through: `highs.mip_heuristic_effort=0.3`,
    /// `scip.limits/nodes=1000`, `cbc.cuts=off` (repeatable; each backend takes its own).
    #[arg(long = "param", value_name = "BACKEND.NAME=VALUE")]
    params: Vec<RawParam>,
    /// Write the solution found (`name value` per variable) to this file; with `solve --relax`,
    /// the LP relaxation's point after the cut rounds.
    #[arg(long, value_name = "FILE.sol")]
    sol: Option<PathBuf>,
}

/// The command-line flag of a [`SolveOptions`] field, for error messages.
fn flag_of(option: &str) -> &str {
    match option {
        "time_limit" => "--time-limit",
        "rel_gap" => "--gap",
        "abs_gap" => "--abs-gap",
        "threads" => "--threads",
        "seed" => "--seed",
        "node_limit" => "--node-limit",
        other => other,
    }
}

/// An option error that names the command-line flag.
fn flag_error(e: InvalidOption) -> anyhow::Error {
    anyhow::anyhow!("{} {}", flag_of(e.option), e.reason)
}

impl SolveArgs {
    /// The options of the command line, validated (errors name the flag).
    fn options(&self) -> Result<SolveOptions> {
        let o = self.unchecked_options();
        o.validate().map_err(flag_error)?;
        Ok(o)
    }

    fn unchecked_options(&self) -> SolveOptions {
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
            params: self.params.clone(),
            interrupt: None,
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
        Command::SolveFile { file, solve, start, json } => solve_file(&file, &solve, start.as_deref(), json.as_deref()),
        Command::Solve {
            spec,
            solve,
            out,
            export,
            no_solve,
            formulation,
            relax,
            no_explain,
            explain_time,
            start,
            no_start,
        } => {
            let start = match (start, no_start) {
                (_, true) => cli::design::StartArg::Nothing,
                (Some(file), false) => cli::design::StartArg::File(file),
                (None, false) => cli::design::StartArg::Heuristic,
            };
            cli::design::solve_spec(
                &spec,
                &solve,
                out,
                export,
                no_solve || relax,
                formulation,
                relax,
                (!no_explain).then_some(explain_time),
                start,
            )
        }
        Command::Compare {
            specs,
            manifest,
            solvers,
            time_limit,
            grace,
            seeds,
            threads,
            paper_limits,
            formulations,
            no_start,
            merge,
            out,
        } => {
            if !merge.is_empty() {
                let manifest =
                    manifest.map(|m| netspec::compare::Manifest::load(&m).map_err(anyhow::Error::msg)).transpose()?;
                let merged = netspec::compare::merge(&merge, manifest).map_err(anyhow::Error::msg)?;
                std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
                let from: Vec<String> = merge.iter().map(|d| format!("`{}`", d.display())).collect();
                let settings = serde_json::json!({ "manifest": merged.manifest, "time_limit": merged.time_limit, "merged_from": merged.sources });
                let md = write_comparison(
                    &out,
                    &merged.manifest,
                    &merged.records,
                    &merged.columns,
                    merged.time_limit,
                    &format!("merged from {}", from.join(", ")),
                    settings,
                )?;
                print!("{md}");
                return Ok(ExitCode::SUCCESS);
            }
            let manifest = match manifest {
                Some(m) => netspec::compare::Manifest::load(&m).map_err(anyhow::Error::msg)?,
                None => netspec::compare::Manifest::from_specs(&specs),
            };
            let solvers: Vec<String> = if solvers.is_empty() {
                SolverKind::compiled()
                    .into_iter()
                    .filter(|k| *k != SolverKind::GoodLp)
                    .map(|k| k.name().to_string())
                    .collect()
            } else {
                solvers.iter().map(|k| k.name().to_string()).collect()
            };
            for (flag, v) in [("--time-limit", time_limit), ("--grace", grace)] {
                if v.is_nan() || v < 0.0 {
                    bail!("{flag} must be a number of seconds ≥ 0, got {v}");
                }
            }
            if threads == Some(0) {
                bail!("--threads must be ≥ 1, got 0");
            }
            let interrupt = Some(cli::interrupt::install()?);
            let formulations: Vec<String> = formulations.iter().map(|f| f.name().to_string()).collect();
            let settings = netspec::compare::CompareSettings {
                manifest,
                solvers: solvers.clone(),
                formulations,
                time_limit,
                grace,
                seeds,
                threads,
                paper_limits,
                no_start,
                interrupt,
            };
            // The columns of every table and chart: a backend, or a (backend, recipe) pair.
            let solvers: Vec<String> = settings.methods().into_iter().map(|(label, _, _)| label).collect();
            std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
            let exe = std::env::current_exe().context("locating the netspec binary")?;
            let records = netspec::compare::run_all(&exe, &settings, &out, |r, source| {
                println!(
                    "{:<24} {:<14} {:<16} {:>8.2} s {}{}",
                    r.instance,
                    r.solver,
                    r.status,
                    r.wall_time,
                    if r.valid { "valid" } else { "-" },
                    match source {
                        netspec::compare::RunSource::Solved => String::new(),
                        netspec::compare::RunSource::Resumed => " (resumed)".into(),
                        netspec::compare::RunSource::Rerun(why) => format!(" (solved again: {})", why.join(", ")),
                    }
                );
            })
            .with_context(|| format!("running the comparison into {}", out.display()))?;
            let what = format!(
                "time limit {time_limit} s{}, grace {grace} s",
                if paper_limits { " (each row at most the paper's time for it)" } else { "" }
            );
            let md = write_comparison(
                &out,
                &settings.manifest,
                &records,
                &solvers,
                time_limit,
                &what,
                serde_json::to_value(&settings)?,
            )?;
            print!("\n{md}");
            if settings.interrupt.as_ref().is_some_and(|i| i.is_triggered()) {
                println!("interrupted: the runs recorded above are kept; rerun to resume");
                return Ok(ExitCode::from(cli::interrupt::EXIT_INTERRUPTED));
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::City { spec, solver, time_limit, threads, threads_per_solve, gap, fresh, out } => cli::city::run_city(
            &spec,
            cli::city::CityArgs { solver, time_limit, threads, threads_per_solve, gap, fresh, out },
        ),
        Command::Traffic {
            designs,
            labels,
            duration,
            through_rate,
            local_rate,
            seed,
            metres_per_unit,
            level,
            sumo_home,
            out,
        } => cli::traffic::run_traffic(cli::traffic::TrafficArgs {
            designs,
            labels,
            demand: netspec::traffic::DemandSettings {
                duration,
                through_per_hour: through_rate,
                local_per_hour: local_rate,
                seed,
            },
            load: netspec::traffic::network::LoadOptions { metres_per_unit, level },
            sumo_home,
            out,
        }),
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
                if map.is_identity() {
                    String::new()
                } else {
                    format!("; {} names sanitised", map.vars.len() + map.rows.len())
                }
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

fn solve_file(
    file: &std::path::Path,
    args: &SolveArgs,
    start: Option<&std::path::Path>,
    json: Option<&std::path::Path>,
) -> Result<ExitCode> {
    let mut options = args.options()?;
    let read = read_model_file(file)?;
    for w in &read.warnings {
        eprintln!("warning: {}: {w}", file.display());
    }
    if let Some(path) = start {
        let sol = netspec::io::sol::read(&read.model, path)?;
        if !sol.missing.is_empty() {
            eprintln!(
                "warning: {}: {} variables not in the file start at 0 (first: {})",
                path.display(),
                sol.missing.len(),
                sol.missing[0]
            );
        }
        options.mip_start = Some(sol.values);
    }
    let kind = args.solver()?;
    let solver = kind.instance()?;
    options.interrupt = Some(cli::interrupt::install()?);
    let result = solver.solve(&read.model, &options).with_context(|| format!("solving {}", file.display()))?;
    if let (Some(path), Some(x)) = (&args.sol, &result.primal) {
        let header = format!("{} {}, {}", result.solver, result.solver_version, result.termination.label());
        netspec::io::sol::write(&read.model, x, result.objective, &header, path)?;
    }
    let report = SolveReport::new(file.display().to_string(), &read.model, options, result, &Tolerances::default());
    print!("{}", report.summary());
    if let (Some(path), true) = (&args.sol, report.result.primal.is_some()) {
        println!("solution   {}", path.display());
    }
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
    match &report.result.termination {
        Termination::Error(e) => bail!("the solver failed: {e}"),
        Termination::Limit(netspec::solvers::LimitKind::Interrupt) => {
            Ok(ExitCode::from(cli::interrupt::EXIT_INTERRUPTED))
        }
        _ => Ok(ExitCode::SUCCESS),
    }
}

/// Writes a comparison's reports to `out` (results.md, .csv, .json, profile.svg, bars.svg) and
/// returns the Markdown table. `what` describes the runs for the header; `settings` is stored
/// in results.json.
fn write_comparison(
    out: &std::path::Path,
    manifest: &netspec::compare::Manifest,
    records: &[netspec::compare::RunRecord],
    columns: &[String],
    time_limit: f64,
    what: &str,
    settings: serde_json::Value,
) -> Result<String> {
    let summary = netspec::compare::summarize(records, columns, time_limit);
    let md = netspec::compare::markdown(manifest, records, columns, &summary);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let command: Vec<String> = std::env::args().collect();
    let header = format!(
        "netspec {} compare, {what}; {cpu}, {} cores\n\nCommand: `{}`\n\n",
        env!("CARGO_PKG_VERSION"),
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        command.join(" ")
    );
    let write = |name: &str, text: String| {
        std::fs::write(out.join(name), text).with_context(|| format!("writing {}", out.join(name).display()))
    };
    write("results.md", header + &md)?;
    write("results.csv", netspec::compare::csv(records))?;
    write("profile.svg", netspec::compare::performance_profile_svg(records, columns, time_limit))?;
    write("bars.svg", netspec::compare::bar_chart_svg(manifest, records, columns, time_limit))?;
    let all = serde_json::json!({ "netspec_version": env!("CARGO_PKG_VERSION"), "command": command, "cpu": cpu, "settings": settings, "records": records, "summary": summary });
    write("results.json", serde_json::to_string_pretty(&all)? + "\n")?;
    Ok(md)
}
