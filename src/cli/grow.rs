//! `netspec grow CONTEXT --out DIR`: road networks grown by traffic, with a progress bar of the
//! steps; exits with 1 when the independent check of the network finds violations.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::grow::{self, GrowRequest};
use std::process::ExitCode;

/// Violations printed one per line; the rest are counted (all are in `network.json`).
const SHOWN: usize = 10;

/// Runs the library entry point with a bar of the steps and prints a summary line; warns about
/// violations of the network's invariants and then exits with 1.
pub fn run(req: &GrowRequest) -> Result<ExitCode> {
    let bar = ProgressBar::new(1);
    bar.set_style(ProgressStyle::with_template("grow {bar:30} step {pos}/{len} {elapsed}").expect("static template"));
    let summary = grow::run(req, &mut |k, n| {
        bar.set_length(n as u64);
        bar.set_position(k as u64);
    });
    bar.finish_and_clear();
    let s = summary?;
    let r = &s.last;
    println!(
        "seed {} · {} steps · {} settlements · {:.1} ha built up · {} blocks · {:.1} km minor · {:.1} km major · {} ports · {} bridges · {} trade routes · overflow {} · {:.2} s initial network, {:.2} s steps",
        s.seed,
        r.step,
        r.settlements,
        r.built_up_ha,
        r.blocks,
        r.minor_km,
        r.major_km,
        r.ports,
        r.bridges,
        r.trade_routes,
        r.overflow,
        s.init_seconds,
        s.step_seconds
    );
    let json = req.out.join("network.json");
    println!("wrote {}", json.display());
    for (step, n) in &s.snapshot_violations {
        eprintln!("warning: the network at step {step} had {n} violation(s) of its invariants");
    }
    if s.violations.is_empty() {
        return Ok(ExitCode::SUCCESS);
    }
    eprintln!("warning: the grown network has {} violation(s) of its invariants:", s.violations.len());
    for v in s.violations.iter().take(SHOWN) {
        eprintln!("  {v}");
    }
    if s.violations.len() > SHOWN {
        eprintln!("  … and {} more", s.violations.len() - SHOWN);
    }
    eprintln!(
        "error: the independent check of the grown network failed: {} violation(s), listed under `violations` in {}",
        s.violations.len(),
        json.display()
    );
    Ok(ExitCode::FAILURE)
}
