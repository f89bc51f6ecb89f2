//! `netspec grow CONTEXT --out DIR [--window X0,Y0,X1,Y1]`: road networks grown by traffic, with
//! a progress bar of the steps, and a window of one as a city spec and trade flows; exits with 3
//! when the independent check of the network finds violations.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::grow::{self, GrowRequest};
use std::path::PathBuf;
use std::process::ExitCode;

/// Violations printed one per line; the rest are counted (all are in `network.json`).
const SHOWN: usize = 10;

/// Exit code of a grown network that fails the independent check (as `city` and `layout`).
const EXIT_INVALID: u8 = 3;

/// `netspec grow`'s arguments.
#[derive(clap::Args)]
pub struct GrowArgs {
    /// The context file, or with --window a `netspec grow` output directory.
    context: PathBuf,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// Seed of every random choice (default: the context's `seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Time steps (default: the context's `steps`).
    #[arg(long, value_name = "N")]
    steps: Option<u32>,
    /// Also write step-NNN.svg every K steps (and at step 0), and steps.svg/.png with them
    /// side by side.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..))]
    every: Option<u32>,
    /// Draw every minor road, dead-end stubs too (by default the pictures show the streets
    /// that bound blocks or join roads).
    #[arg(long)]
    all_streets: bool,
    /// Also write gallery.svg/.png: the initial networks of N seeds from the run's seed on.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..))]
    gallery: Option<u32>,
    /// A window of the map, metres (x0,y0,x1,y1): writes city.toml (its grown major roads,
    /// water as obstacles, unbuilt sub-regions running no level) and trade.json (the trade
    /// flows across it).
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = super::args::parse_window)]
    window: Option<[f64; 4]>,
}

impl GrowArgs {
    /// Grows the context (or windows a grown network).
    pub fn run(self) -> Result<ExitCode> {
        let req = GrowRequest {
            context: self.context,
            out: self.out,
            seed: self.seed,
            steps: self.steps,
            every: self.every,
            all_streets: self.all_streets,
            gallery: self.gallery,
            interrupt: None,
        };
        run(&req, self.window)
    }
}

/// Grows (unless the context is a grown output directory) and writes the window's files.
fn run(req: &GrowRequest, window: Option<[f64; 4]>) -> Result<ExitCode> {
    let grown = match req.source(window)? {
        grow::Source::Grown(dir) => dir,
        grow::Source::Context => {
            if !grow_map(req)? {
                return Ok(ExitCode::from(EXIT_INVALID));
            }
            req.out.clone()
        }
    };
    if let Some(w) = window {
        let s = grow::window::write(&grown, w, &req.window_name(), &req.out)?;
        println!(
            "window {},{},{},{}: {} major roads ({:.2} km), {} sub-regions ({} unbuilt, no level), water bodies as obstacles: {}, {} trade flows ({} routes end inside)",
            w[0], w[1], w[2], w[3], s.roads, s.road_m / 1000.0, s.regions, s.empty_regions, s.obstacles, s.flows, s.routes_ending_inside
        );
        for f in &s.files {
            println!("wrote {}", f.display());
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Runs the library entry point with a bar of the steps and prints a summary line; warns about
/// violations of the network's invariants. Whether the network passed the check.
fn grow_map(req: &GrowRequest) -> Result<bool> {
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
        return Ok(true);
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
    Ok(false)
}
