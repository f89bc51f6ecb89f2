//! `netspec traffic DESIGN…`: SUMO evaluations of designed networks, and a comparison when
//! several are given.

use anyhow::{Context, Result};
use netspec::render;
use netspec::traffic::{self, network::LoadOptions, picture as pictures, report, DemandSettings, Sumo, TrafficReport};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// The command line's settings.
pub struct TrafficArgs {
    pub designs: Vec<PathBuf>,
    pub labels: Vec<String>,
    pub demand: DemandSettings,
    pub load: LoadOptions,
    pub sumo_home: Option<PathBuf>,
    pub out: PathBuf,
    pub time_limit: Option<f64>,
}

/// A label from a design's path: its directory name (`result.json`'s parent's for a file).
fn default_label(p: &Path) -> String {
    let dir = if p.is_file() { p.parent().unwrap_or(p) } else { p };
    dir.file_name().map_or_else(|| "design".to_string(), |n| n.to_string_lossy().into_owned())
}

fn write_picture(dir: &Path, stem: &str, svg: &str) -> Result<()> {
    let svg_path = dir.join(format!("{stem}.svg"));
    std::fs::write(&svg_path, svg).with_context(|| format!("writing {}", svg_path.display()))?;
    let png_path = dir.join(format!("{stem}.png"));
    std::fs::write(&png_path, render::png(svg)?).with_context(|| format!("writing {}", png_path.display()))?;
    Ok(())
}

pub fn run_traffic(args: TrafficArgs) -> Result<ExitCode> {
    let started = Instant::now();
    let mut sumo = Sumo::locate(args.sumo_home.as_deref())?;
    if let Some(limit) = args.time_limit {
        if !(limit > 0.0 && limit.is_finite()) {
            anyhow::bail!("--time-limit must be a positive number of seconds, got {limit}");
        }
        // The tools stop early enough for the pictures and tables to be written within the limit.
        let tools = limit - netspec::run::output_reserve(limit);
        sumo.deadline = Some(started + std::time::Duration::from_secs_f64(tools));
    }
    let note = if sumo.version == traffic::sumo::SETUP_SUMO_VERSION {
        String::new()
    } else {
        format!(", not the {} scripts/setup.sh installs", traffic::sumo::SETUP_SUMO_VERSION)
    };
    println!("sumo       {} ({}{note})", sumo.version, sumo.bin.display());
    let mut labels: Vec<String> = args
        .designs
        .iter()
        .enumerate()
        .map(|(i, p)| args.labels.get(i).cloned().unwrap_or_else(|| default_label(p)))
        .collect();
    // Distinct labels (they name the output directories).
    let mut seen = BTreeSet::new();
    for (i, l) in labels.iter_mut().enumerate() {
        if !seen.insert(l.clone()) {
            *l = format!("{l}-{i}");
            seen.insert(l.clone());
        }
    }
    let mut reports: Vec<(String, TrafficReport)> = Vec::new();
    for (path, label) in args.designs.iter().zip(&labels) {
        let t0 = Instant::now();
        let net = traffic::network::load(path, &args.load)?;
        let load = t0.elapsed().as_secs_f64();
        // A label names a folder: made one safe path component.
        let dir =
            if args.designs.len() == 1 { args.out.clone() } else { args.out.join(netspec::run::safe_component(label)) };
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        let mut rep = traffic::evaluate(&net, &args.demand, &sumo, &dir)
            .with_context(|| format!("evaluating {}", path.display()))?;
        rep.timings.load = load;
        rep.timings.total += load;
        rep.write(&dir)?;
        write_picture(&dir, "volume", &pictures::volume_svg(&net, &rep))?;
        write_picture(&dir, "traveltime", &pictures::histogram_svg(&rep))?;
        println!();
        print!("{}", rep.summary());
        println!("wrote      {}/traffic.json, volume.svg/png, traveltime.svg/png, sumo/", dir.display());
        reports.push((label.clone(), rep));
    }
    if reports.len() > 1 {
        let rows: Vec<(String, &TrafficReport)> = reports.iter().map(|(l, r)| (l.clone(), r)).collect();
        let md = report::comparison_markdown(&rows);
        let md_path = args.out.join("comparison.md");
        std::fs::write(
            &md_path,
            format!(
                "# Traffic comparison\n\nCommand: `{}`\n\n![comparison](comparison.png)\n\n{md}",
                std::env::args().collect::<Vec<_>>().join(" ")
            ),
        )
        .with_context(|| format!("writing {}", md_path.display()))?;
        let json = serde_json::json!({ "designs": reports.iter().map(|(l, r)| serde_json::json!({ "label": l, "report": r })).collect::<Vec<_>>() });
        let json_path = args.out.join("comparison.json");
        std::fs::write(&json_path, serde_json::to_string_pretty(&json)? + "\n")
            .with_context(|| format!("writing {}", json_path.display()))?;
        write_picture(&args.out, "comparison", &pictures::comparison_svg(&rows))?;
        println!();
        print!("{md}");
        println!("wrote      {}/comparison.md, comparison.json, comparison.svg/png", args.out.display());
    }
    Ok(ExitCode::SUCCESS)
}
