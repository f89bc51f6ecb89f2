//! `netspec level LEVEL.toml`: lay out a game level from its connectivity graph.

use anyhow::{anyhow, ensure, Context, Result};
use netspec::levels::{self, LevelError, LevelRequest, Status};
use netspec::solvers::SolverKind;
use std::path::PathBuf;
use std::process::ExitCode;

/// Exit code when neither a layout nor a proof was found within the limits.
const EXIT_UNKNOWN: u8 = 4;

/// `netspec level`'s arguments.
#[derive(clap::Args)]
pub struct LevelArgs {
    /// The level file.
    spec: PathBuf,
    /// Method: `anneal` (the paper's incremental simulated annealing), `milp` (the exact
    /// placement MILP), or `both` side by side on two threads (the first to answer stops the
    /// other).
    #[arg(long, default_value = "both", value_name = "METHOD")]
    method: levels::Method,
    /// Seed of the annealer.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Run the annealer with N seeds from --seed on: summary.json and a table over them.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=100_000))]
    seeds: u64,
    /// Distinct layouts wanted.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    count: u64,
    /// Backend of the exact model (default: highs when compiled in).
    #[arg(long)]
    solver: Option<SolverKind>,
    /// Seconds for the whole command: both methods, the proof and its explanation.
    #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
    time_limit: f64,
    /// Solver threads.
    #[arg(long)]
    threads: Option<u32>,
    /// When no layout exists, do not look for the edges that conflict.
    #[arg(long)]
    no_explain: bool,
    /// Output directory (level.json).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Export the first layout as mesh.json and network.toml into the output directory.
    #[arg(long, requires = "out")]
    export_spec: bool,
    /// Grid spacing inside the rooms of the export (default: the door width).
    #[arg(long, requires = "export_spec")]
    spacing: Option<f64>,
    /// The node whose room gets the sink (default: the first node).
    #[arg(long, value_name = "NODE", requires = "export_spec")]
    entrance: Option<String>,
    /// Coverage range of the export, in level units, at least 1 (default: the smallest the
    /// rooms' forced vertices satisfy, so the network is the shortest through every room).
    #[arg(long, value_name = "R", requires = "export_spec")]
    coverage: Option<f64>,
}

impl LevelArgs {
    /// The library's request, with the backend chosen and the limit checked.
    fn request(self) -> Result<LevelRequest> {
        let solver = self.solver.or_else(SolverKind::default_kind).ok_or_else(|| anyhow!("no backend compiled in"))?;
        ensure!(
            self.time_limit > 0.0 && self.time_limit.is_finite(),
            "--time-limit must be a positive number of seconds, got {}",
            self.time_limit
        );
        let (spacing, entrance, coverage) = (self.spacing, self.entrance, self.coverage);
        Ok(LevelRequest {
            spec: self.spec,
            method: self.method,
            count: self.count as usize,
            solver,
            time_limit: self.time_limit,
            threads: self.threads,
            out: self.out,
            explain: !self.no_explain,
            seed: self.seed,
            export: self.export_spec.then_some(levels::bridge::BridgeOptions { spacing, entrance, coverage }),
            seeds: self.seeds as usize,
        })
    }

    /// Lays the level out.
    pub fn run(self) -> Result<ExitCode> {
        run(self.request()?)
    }
}

/// `netspec level-gen`'s arguments.
#[derive(clap::Args)]
pub struct LevelGenArgs {
    /// The family, e.g. `grid:10x10` or `grid:10x10+triangle`.
    family: String,
    /// The door width.
    #[arg(long, default_value_t = 0.5)]
    door_width: f64,
    /// Write here instead of standard output.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
}

impl LevelGenArgs {
    /// Writes the level file.
    pub fn run(self) -> Result<ExitCode> {
        let g = levels::generate::Generated::parse(&self.family)?;
        ensure!(
            self.door_width > 0.0 && self.door_width <= 1.0,
            "--door-width must be in (0, 1] for unit squares, got {}",
            self.door_width
        );
        let text = g.to_toml(self.door_width);
        match self.out {
            Some(path) => std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?,
            None => print!("{text}"),
        }
        Ok(ExitCode::SUCCESS)
    }
}

/// Runs the library entry point and prints a summary.
fn run(req: LevelRequest) -> Result<ExitCode> {
    let out = match levels::run(&req) {
        Ok(out) => out,
        Err(e @ LevelError::NoLayout { .. }) => {
            // Nothing to export is the same outcome as neither a layout nor a proof.
            eprintln!("error: {e}");
            return Ok(ExitCode::from(EXIT_UNKNOWN));
        }
        Err(e) => return Err(e.into()),
    };
    println!("status     {}", out.status.as_str());
    println!("layouts    {} (each checked by the validator)", out.layouts.len());
    println!("cspaces    {:.3} s", out.cspace_time);
    if let Some(a) = &out.anneal {
        println!(
            "anneal     {} layout(s) · {} chains ({} placed exactly) · {} trials · {} restart(s) · stopped: {}{}",
            a.layouts.len(),
            a.chains.len(),
            a.exact_extensions,
            a.trials,
            a.restarts,
            if a.stopped == "stopped" { "the exact search answered first" } else { a.stopped.as_str() },
            a.time_to_first.map_or(String::new(), |t| format!(" · first layout {t:.3} s")),
        );
    }
    if let Some(m) = out.milp.as_ref().filter(|m| m.note.as_deref() == Some("stopped")) {
        println!("milp       {} · stopped: the annealer answered first", m.solver);
    } else if let Some(m) = &out.milp {
        println!(
            "milp       {} · {} vars, {} rows · {} solve(s){}{}",
            m.solver,
            m.size.0,
            m.size.1,
            m.solves,
            m.time_to_first.map_or(String::new(), |t| format!(" · first layout {t:.3} s")),
            m.time_to_proof.map_or(String::new(), |t| format!(" · proof {t:.3} s")),
        );
        if let Some(ok) = m.start_accepted {
            println!("           MIP start {}", if ok { "accepted" } else { "rejected by the checker" });
        }
        if let Some(note) = &m.note {
            println!("           {note}");
        }
        if let Some(c) = &m.conflict {
            let edges: Vec<String> = c.edges.iter().map(|[a, b]| format!("{a}–{b}")).collect();
            let how = if c.minimal { "minimal" } else { "not proven minimal" };
            println!("conflict   {} ({how}, {} checks)", edges.join(", "), c.checks);
        }
    }
    if let Some(s) = &out.seeds {
        print!("{}", netspec::levels::seeds::table(s));
    }
    for f in &out.files {
        println!("wrote      {}", f.display());
    }
    // Feasible and proven infeasible are both answers; unknown is not.
    Ok(if out.status == Status::Unknown { ExitCode::from(EXIT_UNKNOWN) } else { ExitCode::SUCCESS })
}
