//! `netspec level LEVEL.toml`: lay out a game level from its connectivity graph.

use anyhow::Result;
use netspec::levels::{self, LevelError, LevelRequest, Status};
use std::process::ExitCode;

/// Exit code when neither a layout nor a proof was found within the limits.
const EXIT_UNKNOWN: u8 = 4;

/// Runs the library entry point and prints a summary.
pub fn run(req: LevelRequest) -> Result<ExitCode> {
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
