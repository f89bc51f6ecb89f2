//! `netspec solvers`: the compiled backends, their versions and capabilities.

use anyhow::Result;
use netspec::report::SolverInfo;
use netspec::solvers::SolverKind;
use std::process::ExitCode;

/// `netspec solvers`' arguments.
#[derive(clap::Args)]
pub struct SolversArgs {
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

impl SolversArgs {
    /// Prints the list.
    pub fn run(self) -> Result<ExitCode> {
        let list = netspec::report::solver_list();
        if self.json {
            println!("{}", serde_json::to_string_pretty(&list)?);
        } else {
            print_table(&list);
        }
        Ok(ExitCode::SUCCESS)
    }
}

/// One line per backend, then which report progress live and which are not compiled in.
fn print_table(list: &[SolverInfo]) {
    for s in list {
        println!("{:<8} {:<10} {}", s.name, s.version, s.capability_summary());
    }
    let (live, at_end): (Vec<_>, Vec<_>) = list.iter().partition(|s| s.capabilities.reports_progress);
    let names = |v: &[&SolverInfo]| v.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", ");
    println!(
        "live: improving designs and progress while solving from {}; only at the end from {}",
        names(&live),
        names(&at_end)
    );
    let missing: Vec<_> = SolverKind::ALL.iter().filter(|k| !k.is_compiled()).map(|k| k.name()).collect();
    if !missing.is_empty() {
        println!("not compiled in: {} (enable the cargo features of the same names)", missing.join(", "));
    }
}
