//! `netspec stats DESIGN…`: street statistics of designs on one region, beside the real streets.

use anyhow::Result;
use netspec::measure::{self, StatsRequest};
use netspec::traffic::network::{LoadOptions, SiteRegion};
use std::path::PathBuf;
use std::process::ExitCode;

/// The command line of `netspec stats`.
#[derive(clap::Args)]
pub struct StatsArgs {
    /// Designs: layout, grow, city or solve output directories, a site's map/, or a GeoJSON of
    /// streets.
    #[arg(required = true)]
    pub designs: Vec<PathBuf>,
    /// Names of the designs, comma-separated (default: their directory names).
    #[arg(long, value_delimiter = ',')]
    pub labels: Vec<String>,
    /// The region every design is judged on (a site.geojson of `netspec site`, or any GeoJSON
    /// site): designs are moved into its metres through WGS 84 and clipped to it.
    #[arg(long, value_name = "REGION.geojson")]
    pub region: Option<PathBuf>,
    /// The design the distances are taken to (default: the first site map/ given).
    #[arg(long, value_name = "LABEL")]
    pub reference: Option<String>,
    /// Radius (metres) within which intersections merge, as OSMnx's consolidate_intersections.
    #[arg(long, default_value_t = netspec::stats::CLEAN_INT_TOL, value_name = "M")]
    pub clean_int_tol: f64,
    /// Metres per model unit of a solve design (default 20).
    #[arg(long, value_name = "M")]
    pub metres_per_unit: Option<f64>,
    /// The window of a grow design, metres: x0,y0,x1,y1 (default: its whole map).
    #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = super::args::parse_window)]
    pub window: Option<[f64; 4]>,
    /// Print one JSON object per design instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Also write stats.json, orientation-<label>.svg/png and comparison.svg/png here.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Runs `netspec stats` and prints the table (or JSON).
pub fn run(a: StatsArgs) -> Result<ExitCode> {
    if !(a.clean_int_tol >= 0.0 && a.clean_int_tol.is_finite()) {
        anyhow::bail!("--clean-int-tol must be a non-negative number of metres, got {}", a.clean_int_tol);
    }
    let region = a.region.as_deref().map(SiteRegion::load).transpose()?;
    let req = StatsRequest {
        designs: a.designs,
        labels: a.labels,
        load: LoadOptions { metres_per_unit: a.metres_per_unit, level: None, window: a.window, region },
        settings: netspec::stats::Settings { clean_int_tol: a.clean_int_tol },
        reference: a.reference,
    };
    let designs = measure::run(&req)?;
    if a.json {
        for d in &designs {
            println!("{}", serde_json::to_string(d)?);
        }
    } else {
        print!("{}", measure::table(&designs));
    }
    if let Some(dir) = &a.out {
        for f in measure::write(dir, &designs)? {
            if !a.json {
                println!("wrote {}", f.display());
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
