//! `netspec grow CONTEXT --out DIR`: road networks grown by traffic, with a progress bar of the
//! steps.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::grow::{self, GrowRequest};
use std::process::ExitCode;

/// Runs the library entry point with a bar of the steps and prints a summary line.
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
    println!("wrote {}", req.out.join("network.json").display());
    Ok(ExitCode::SUCCESS)
}
