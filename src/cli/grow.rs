//! `netspec grow CONTEXT --out DIR [--window X0,Y0,X1,Y1]`: road networks grown by traffic, with
//! a progress bar of the steps, and a window of one as a city spec and trade flows.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::grow::{self, GrowRequest};
use std::process::ExitCode;

/// Grows (unless the context is a grown output directory) and writes the window's files.
pub fn run(req: &GrowRequest, window: Option<[f64; 4]>) -> Result<ExitCode> {
    let grown = if req.context.is_dir() {
        anyhow::ensure!(
            window.is_some(),
            "{} is a directory: give a context file to grow, or --window to window a grown network",
            req.context.display()
        );
        req.context.clone()
    } else {
        grow_map(req)?;
        req.out.clone()
    };
    if let Some(w) = window {
        let name = req.out.file_name().map_or_else(|| "window".to_string(), |n| n.to_string_lossy().into_owned());
        let s = grow::window::write(&grown, w, &name, &req.out)?;
        println!(
            "window {},{},{},{}: {} major roads ({:.2} km), {} sub-regions ({} unbuilt, no level), {} water obstacles, {} trade flows ({} routes end inside)",
            w[0], w[1], w[2], w[3], s.roads, s.road_m / 1000.0, s.regions, s.empty_regions, s.obstacles, s.flows, s.routes_ending_inside
        );
        for f in &s.files {
            println!("wrote {}", f.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs the library entry point with a bar of the steps and prints a summary line.
fn grow_map(req: &GrowRequest) -> Result<()> {
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
    Ok(())
}
