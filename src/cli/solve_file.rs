//! `netspec solve-file FILE`: prints [`netspec::report::solve_file`]'s report.

use super::args::SolveArgs;
use anyhow::{bail, Context, Result};
use netspec::report::{SolveFileRequest, SCHEMA_VERSION};
use netspec::solvers::{LimitKind, Termination};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit code when the solver's answer fails netspec's independent check.
const EXIT_CHECK_FAILED: u8 = 3;

/// `netspec solve-file`'s arguments.
#[derive(clap::Args)]
pub struct SolveFileArgs {
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
}

impl SolveFileArgs {
    /// Solves the model file and prints the summary (and writes the JSON result if asked).
    pub fn run(self) -> Result<ExitCode> {
        let req = SolveFileRequest {
            file: self.file,
            settings: self.solve.settings(),
            start: self.start,
            sol: self.solve.sol.clone(),
            interrupt: Some(super::interrupt::install()?),
        };
        report(&req, &self.solve, self.json.as_deref())
    }
}

/// Solves and prints the summary (and writes the JSON result if asked).
fn report(req: &SolveFileRequest, args: &SolveArgs, json: Option<&Path>) -> Result<ExitCode> {
    let report = netspec::report::solve_file(req, &mut |w| eprintln!("warning: {}: {}", w.path.display(), w.message))?;
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
        Termination::Limit(LimitKind::Interrupt) => Ok(ExitCode::from(super::interrupt::EXIT_INTERRUPTED)),
        _ => Ok(ExitCode::SUCCESS),
    }
}
