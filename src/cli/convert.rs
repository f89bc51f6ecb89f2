//! `netspec convert IN OUT`: a model between MPS and LP.

use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

/// `netspec convert`'s arguments.
#[derive(clap::Args)]
pub struct ConvertArgs {
    /// Input file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
    input: PathBuf,
    /// Output file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
    output: PathBuf,
}

impl ConvertArgs {
    /// Converts, printing the reader's warnings and what was written.
    pub fn run(self) -> Result<ExitCode> {
        let c = netspec::io::convert(&self.input, &self.output)?;
        for w in &c.warnings {
            eprintln!("warning: {}: {w}", self.input.display());
        }
        let renamed = if c.renamed == 0 { String::new() } else { format!("; {} names sanitised", c.renamed) };
        println!("wrote {} ({}){renamed}", self.output.display(), c.stats);
        Ok(ExitCode::SUCCESS)
    }
}
