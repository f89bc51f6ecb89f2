//! `netspec traffic DESIGN…`: SUMO evaluations of designed networks, and a comparison when
//! several are given.

use anyhow::{Context, Result};
use netspec::render;
use netspec::traffic::{self, network::LoadOptions, picture as pictures, report, DemandSettings, Sumo, TrafficReport};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// `netspec traffic`'s arguments.
#[derive(clap::Args)]
pub struct TrafficArgs {
    /// Designs: `netspec city` output directories, `netspec solve` output directories or
    /// result.json files (a city's regions/NN-name/L<n>/ too).
    #[arg(required = true)]
    designs: Vec<PathBuf>,
    /// Names of the designs, comma-separated (default: their directory names).
    #[arg(long, value_delimiter = ',')]
    labels: Vec<String>,
    /// Seconds during which trips depart.
    #[arg(long, default_value_t = 3600.0, value_name = "SECONDS")]
    duration: f64,
    /// Through trips per hour (boundary to the far side of the boundary).
    #[arg(long, default_value_t = 300.0, value_name = "PER_HOUR")]
    through_rate: f64,
    /// Local trips per hour (interior point to interior point).
    #[arg(long, default_value_t = 600.0, value_name = "PER_HOUR")]
    local_rate: f64,
    /// Seed of the demand, duarouter and sumo.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Metres per model unit (default: the city spec's; 20 for solve results).
    #[arg(long, value_name = "M")]
    metres_per_unit: Option<f64>,
    /// Level of a solve result's streets: 1 major, 2 collector, 3 local (default), 4 cul-de-sac.
    #[arg(long, value_parser = clap::value_parser!(u8).range(1..=4))]
    level: Option<u8>,
    /// The window of a `netspec grow` network, metres: x0,y0,x1,y1 (default: its whole map).
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = super::args::parse_window)]
    window: Option<[f64; 4]>,
    /// The region every design is simulated on (a site.geojson of `netspec site`, or any
    /// GeoJSON site): designs are moved into its metres through WGS 84 and clipped to it,
    /// and demand is drawn in its outline.
    #[arg(long, value_name = "REGION.geojson")]
    region: Option<PathBuf>,
    /// Trade flows (a trade.json of `netspec grow --window`): trade trips between the
    /// entrances nearest to each flow's ends, for every design.
    #[arg(long, value_name = "FILE")]
    trade: Option<PathBuf>,
    /// Trade trips per hour, shared among the flows by weight.
    #[arg(long, default_value_t = 300.0, value_name = "PER_HOUR")]
    trade_rate: f64,
    /// SUMO_HOME to use (default: $SUMO_HOME, then the copy scripts/setup.sh installs, then PATH).
    #[arg(long, value_name = "DIR")]
    sumo_home: Option<PathBuf>,
    /// Output directory.
    #[arg(long, value_name = "DIR", default_value = "out/traffic")]
    out: PathBuf,
    /// Time limit of the whole evaluation, seconds: a SUMO tool still running when it runs
    /// out is stopped and the command fails, saying so (default: none).
    #[arg(long, value_name = "SECONDS")]
    time_limit: Option<f64>,
}

impl TrafficArgs {
    /// The demand every design gets (the trade file read).
    fn demand(&self) -> Result<DemandSettings> {
        Ok(DemandSettings {
            duration: self.duration,
            through_per_hour: self.through_rate,
            local_per_hour: self.local_rate,
            seed: self.seed,
            trade_per_hour: self.trade_rate,
            trade: match &self.trade {
                Some(f) => traffic::demand::TradeFile::load(f)?.flows,
                None => Vec::new(),
            },
        })
    }

    /// How the designs are read (the region file read).
    fn load_options(&self) -> Result<LoadOptions> {
        Ok(LoadOptions {
            metres_per_unit: self.metres_per_unit,
            level: self.level,
            window: self.window,
            region: self.region.as_deref().map(traffic::network::SiteRegion::load).transpose()?,
        })
    }

    /// Evaluates the designs.
    pub fn run(self) -> Result<ExitCode> {
        let (demand, load) = (self.demand()?, self.load_options()?);
        run_traffic(&self, &demand, &load)
    }
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

fn run_traffic(args: &TrafficArgs, demand: &DemandSettings, load_options: &LoadOptions) -> Result<ExitCode> {
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
        let net = traffic::network::load(path, load_options)?;
        let load = t0.elapsed().as_secs_f64();
        // A label names a folder: made one safe path component.
        let dir =
            if args.designs.len() == 1 { args.out.clone() } else { args.out.join(netspec::run::safe_component(label)) };
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        let mut rep =
            traffic::evaluate(&net, demand, &sumo, &dir).with_context(|| format!("evaluating {}", path.display()))?;
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
