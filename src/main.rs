//! The `netspec` command-line tool: a thin layer over the library (one `clap` struct per command
//! in `src/cli/`, each making one library call).

use clap::Parser;
use std::process::ExitCode;

mod cli;

fn main() -> ExitCode {
    // Behave like other Unix tools when the reader of our output goes away (`| head`): end
    // quietly instead of panicking on a broken pipe.
    #[cfg(unix)]
    // SAFETY: resetting a signal disposition to its default before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    match cli::Cli::parse().command.run() {
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
