//! `netspec serve`: the browser application, until Ctrl-C.

use anyhow::Result;
use std::path::PathBuf;
use std::process::ExitCode;

/// `netspec serve`'s arguments.
#[derive(clap::Args)]
pub struct ServeArgs {
    /// The folder whose specs are listed, and where runs (`runs/`) and saved specs go.
    #[arg(long, value_name = "DIR", default_value = ".")]
    root: PathBuf,
    /// The port to listen on (0: any free port).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// The address to listen on; the default keeps the server to this machine.
    #[arg(long, default_value = "127.0.0.1")]
    bind: std::net::IpAddr,
    /// Solves running at once (more wait in a queue).
    #[arg(long, default_value_t = 2)]
    max_solves: usize,
    /// Threads all running solves share (default: the cores).
    #[arg(long)]
    threads: Option<u32>,
}

impl From<ServeArgs> for netspec::serve::ServeOptions {
    fn from(a: ServeArgs) -> Self {
        let defaults = netspec::serve::ServeOptions::default();
        netspec::serve::ServeOptions {
            root: a.root,
            port: a.port,
            bind: a.bind,
            max_solves: a.max_solves,
            threads: a.threads.unwrap_or(defaults.threads),
            netspec_bin: std::env::current_exe().ok(),
            ..defaults
        }
    }
}

impl ServeArgs {
    /// Serves until stopped.
    pub fn run(self) -> Result<ExitCode> {
        netspec::serve::run(self.into(), |addr| println!("netspec serve: http://{addr}/ (Ctrl-C stops)"))?;
        Ok(ExitCode::SUCCESS)
    }
}
