//! `netspec traffic DESIGN…`: SUMO evaluations of designed networks, and a comparison when
//! several are given.

use anyhow::Result;
use netspec::traffic::run::{TrafficEvent, TrafficRequest};
use netspec::traffic::{self, network::LoadOptions, DemandSettings};
use std::path::PathBuf;
use std::process::ExitCode;

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
        run_traffic(&self, demand, load)
    }
}

/// Runs the library entry point, printing SUMO's version, each design's summary and the comparison.
fn run_traffic(args: &TrafficArgs, demand: DemandSettings, load: LoadOptions) -> Result<ExitCode> {
    let req = TrafficRequest {
        designs: args.designs.clone(),
        labels: args.labels.clone(),
        demand,
        load,
        sumo_home: args.sumo_home.clone(),
        out: args.out.clone(),
        time_limit: args.time_limit,
        command: std::env::args().collect::<Vec<_>>().join(" "),
    };
    traffic::run::run(&req, &mut |e| match e {
        TrafficEvent::Located(sumo) => {
            let note = if sumo.version == traffic::sumo::SETUP_SUMO_VERSION {
                String::new()
            } else {
                format!(", not the {} scripts/setup.sh installs", traffic::sumo::SETUP_SUMO_VERSION)
            };
            println!("sumo       {} ({}{note})", sumo.version, sumo.bin.display());
        }
        TrafficEvent::Evaluated(d) => {
            println!();
            print!("{}", d.report.summary());
            println!("wrote      {}/traffic.json, volume.svg/png, traveltime.svg/png, sumo/", d.dir.display());
        }
        TrafficEvent::Compared(md) => {
            println!();
            print!("{md}");
            println!("wrote      {}/comparison.md, comparison.json, comparison.svg/png", args.out.display());
        }
    })?;
    Ok(ExitCode::SUCCESS)
}
