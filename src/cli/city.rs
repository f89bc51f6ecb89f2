//! `netspec city SPEC`: street layouts for a whole city, with a progress bar per sub-region.

use super::args::ExecutorArgs;
use anyhow::{Context, Result};
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};
use netspec::pipeline::settings::Settings;
use netspec::pipeline::Method;
use netspec::solvers::SolverKind;
use netspec::urban::{self, CityEvent, CityRunOptions, CitySpec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Exit code when some level produced no network (infeasible, time limit without a solution,
/// error) — the rest of the city is still written.
const EXIT_INCOMPLETE: u8 = 4;
/// Exit code when a network fails an independent check.
const EXIT_INVALID: u8 = 3;

/// The time kept from `--total-time-limit` for smoothing, assembling and writing the city after
/// its levels: a tenth, at most 5 s.
fn assembly_reserve(total: f64) -> f64 {
    (0.1 * total).min(5.0)
}

/// `netspec city`'s arguments.
#[derive(clap::Args)]
pub struct CityArgs {
    /// The city spec (TOML).
    spec: PathBuf,
    /// Backend (default: the spec's, else the embedded HiGHS).
    #[arg(long, value_name = "NAME")]
    solver: Option<SolverKind>,
    /// Time limit of every level, seconds, for all of its work (model, start, solve,
    /// outputs; default: each level's `time_limit`).
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
    /// Time limit of the whole city, seconds: no level starts after it, a running level
    /// stops at it with its best network, and the city is assembled and written within it.
    #[arg(long, value_name = "SECONDS")]
    total_time_limit: Option<f64>,
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
    /// Refuse a city whose level meshes could exceed this many cells (default 250,000).
    #[arg(long, value_name = "CELLS")]
    max_cells: Option<usize>,
    #[command(flatten)]
    executor: ExecutorArgs,
    /// Solve one sub-region's level as a cluster job does (`REGION:LEVEL`; run by Slurm).
    #[arg(long, hide = true, value_name = "REGION:LEVEL")]
    level_job: Option<String>,
    /// Output directory (default: out/<the city file's name>).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

impl CityArgs {
    /// Runs the city.
    pub fn run(self) -> Result<ExitCode> {
        let slurm = self.executor.slurm()?;
        run_city(&self.spec.clone(), &self, slurm)
    }
}

/// The flags every cluster job of a city gets, so that it resolves the same options.
fn job_flags(args: &CityArgs, opts: &CityRunOptions) -> Vec<String> {
    let mut f = vec![
        "--solver".to_string(),
        opts.solver.name().to_string(),
        "--threads".into(),
        opts.threads.to_string(),
        "--threads-per-solve".into(),
        opts.threads_per_solve.to_string(),
    ];
    if let Some(t) = opts.time_limit {
        f.extend(["--time-limit".into(), t.to_string()]);
    }
    if let Some(g) = args.gap {
        f.extend(["--gap".into(), g.to_string()]);
    }
    if let Some(c) = args.max_cells {
        f.extend(["--max-cells".into(), c.to_string()]);
    }
    if args.fresh {
        f.push("--fresh".into());
    }
    f
}

/// One level as a cluster job: exit 0 when it has a network (its next level may start).
fn level_job(spec: &CitySpec, out: &Path, opts: &CityRunOptions, job: &str) -> Result<ExitCode> {
    let parsed = job.split_once(':').and_then(|(r, l)| Some((r.parse::<usize>().ok()?, l.parse::<u8>().ok()?)));
    let (region, level) = parsed.with_context(|| format!("--level-job {job}: give REGION:LEVEL"))?;
    let report = urban::cluster::run_level_job(spec, out, opts, region, level)?
        .with_context(|| format!("--level-job {job}: the city has no such region and level"))?;
    println!("region {region} L{level}: {}", report.verdict());
    Ok(if report.has_network() { ExitCode::SUCCESS } else { ExitCode::FAILURE })
}

fn run_city(path: &Path, args: &CityArgs, slurm: Option<netspec::slurm::SlurmOptions>) -> Result<ExitCode> {
    let started = Instant::now();
    let spec = CitySpec::load(path)?;
    let flags = Settings {
        method: args.solver.map(Method::Milp),
        time_limit: args.time_limit,
        gap: args.gap,
        ..Settings::default()
    };
    let max_cells = args.max_cells.unwrap_or(netspec::spec::DEFAULT_MAX_CELLS);
    let mut opts = CityRunOptions::resolve(&spec, path, &flags, args.threads, args.threads_per_solve, max_cells)?;
    opts.resume = !args.fresh;
    if let Some(total) = args.total_time_limit {
        if !(total > 0.0 && total.is_finite()) {
            anyhow::bail!("--total-time-limit must be a positive number of seconds, got {total}");
        }
        anyhow::ensure!(slurm.is_none(), "--total-time-limit: the cluster's jobs have their own limits (--time-limit)");
        opts.deadline = Some(started + Duration::from_secs_f64(total - assembly_reserve(total)));
    }
    let interrupt = crate::cli::interrupt::install()?;
    opts.interrupt = Some(interrupt.clone());
    let out = args.out.clone().unwrap_or_else(|| netspec::run::default_out_dir(path));
    if let Some(job) = &args.level_job {
        return level_job(&spec, &out, &opts, job);
    }
    let regions = urban::city::regions(&spec).with_context(|| format!("{}", path.display()))?;
    println!("city       {} — {}", spec.name, spec.description);
    println!(
        "           {} sub-regions, levels {:?}, {} × {} thread(s) with {}",
        regions.len(),
        spec.level_numbers(),
        (opts.threads / opts.threads_per_solve).max(1),
        opts.threads_per_solve,
        opts.solver
    );

    // One bar per sub-region; the message says which level runs and how it is going.
    let multi = MultiProgress::new();
    let style = ProgressStyle::with_template("{prefix:<22} {bar:12} {pos}/{len} {msg}").expect("static template");
    let bars: Vec<ProgressBar> = regions
        .iter()
        .enumerate()
        .map(|(i, (_, entry))| {
            let name = spec.region_name(i, *entry);
            let b = multi.add(ProgressBar::new(spec.region_levels(*entry).len() as u64));
            b.set_style(style.clone());
            b.set_prefix(format!("{i:02} {name}"));
            b.set_message("waiting");
            b.enable_steady_tick(Duration::from_millis(250));
            b
        })
        .collect();
    // Progress bars are shared handles: the observer (called from the worker threads) gets clones.
    let handles = bars.clone();
    opts.observer = Some(Arc::new(move |e: &CityEvent| {
        let bars = &handles;
        match e {
            CityEvent::LevelStarted { region, level, time_limit } => {
                bars[*region].set_message(format!(
                    "L{level} solving{}",
                    time_limit.map_or(String::new(), |t| format!(" (limit {t} s)"))
                ));
            }
            CityEvent::LevelProgress { region, level, progress } => {
                let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2}"));
                bars[*region].set_message(format!(
                    "L{level} {:.0} s incumbent {} bound {}",
                    progress.elapsed,
                    f(progress.primal),
                    f(progress.dual)
                ));
            }
            CityEvent::LevelDone { region, report } => {
                bars[*region].inc(1);
                let line = format!("L{} {}", report.level, report.verdict());
                bars[*region].set_message(line.clone());
                bars[*region].println(format!("{:<22} {line}", bars[*region].prefix()));
            }
        }
    }));
    let result = match &slurm {
        None => urban::run_city_on(&spec, regions, &out, &opts).map_err(anyhow::Error::from),
        Some(slurm) => {
            let exe = std::env::current_exe().context("locating the netspec binary")?;
            let flags = job_flags(args, &opts);
            urban::cluster::run_city_slurm(&exe, &spec, path, regions, &out, &opts, &flags, slurm)
                .map_err(anyhow::Error::from)
        }
    };
    for b in &bars {
        b.finish();
    }
    let result = result.with_context(|| format!("{}", path.display()))?;

    println!();
    for r in &result.regions {
        for l in &r.levels {
            println!(
                "{:02} {:<18} L{} {:<44} obj {:>10} gap {:>8} {:>7} s {}",
                r.index,
                r.name,
                l.level,
                l.verdict(),
                l.objective.map_or("-".into(), |v| format!("{v:.3}")),
                l.gap.map_or("-".into(), |v| format!("{:.2}%", 100.0 * v)),
                l.wall_time.map_or("-".into(), |v| format!("{v:.1}")),
                match l.valid {
                    Some(true) => "valid".to_string(),
                    Some(false) => "INVALID".to_string(),
                    None => l.message.clone().unwrap_or_default(),
                }
            );
        }
    }
    println!("levels     {}", urban::city::levels_summary(&result.regions));
    let m = &result.metrics;
    println!("metrics    {} ({} m per unit)", m.summary(), spec.metres_per_unit);
    if let Some(l) = &result.layout_metrics {
        println!(
            "parcels    {} of 30 × 18 m on 15 m streets ({} undesirable) · corners {:.2}° · area ratio {:.3} · streets {:.1} % · residential {:.1} %",
            l.parcels, l.undesirable, l.corner_deviation_mean, l.area_ratio_mean, l.land_use.streets, l.land_use.residential
        );
    }
    println!(
        "smoothing  {:?}: {} snakes, energy {:.4} → {:.4}",
        result.smoothing.method, result.smoothing.snakes, result.smoothing.energy_before, result.smoothing.energy_after
    );
    println!("wrote      {}/city.json, streets.geojson, city.svg, city.png, regions/", out.display());
    Ok(if !result.valid {
        ExitCode::from(EXIT_INVALID)
    } else if interrupt.is_triggered() {
        println!("interrupted: finished levels are kept; rerun to resume");
        ExitCode::from(crate::cli::interrupt::EXIT_INTERRUPTED)
    } else if !result.complete {
        ExitCode::from(EXIT_INCOMPLETE)
    } else {
        ExitCode::SUCCESS
    })
}
