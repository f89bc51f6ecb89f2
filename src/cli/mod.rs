//! The command line: one `clap` struct per command in the command's file, each of which builds
//! its library request, makes the one library call, prints, and returns the exit code.

pub mod args;
pub mod city;
pub mod compare;
pub mod convert;
pub mod grow;
pub mod interrupt;
pub mod layout;
pub mod level;
pub mod serve;
pub mod site;
pub mod solve;
pub mod solve_file;
pub mod solvers;
pub mod stats;
pub mod traffic;

use anyhow::Result;
use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// `netspec`'s arguments.
#[derive(Parser)]
#[command(name = "netspec", version, about = "Network design from functional specifications, by integer programming", long_about = None)]
pub struct Cli {
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Subcommand)]
pub enum Command {
    /// Solve an MPS or LP file (also `.mps.gz`, `.lp.gz`) and check the answer independently.
    #[command(name = "solve-file")]
    SolveFile(solve_file::SolveFileArgs),
    /// Design a network from a spec file (TOML or JSON): build the MILP, solve it, check and
    /// validate the answer, and write result.json, network.svg and network.png.
    Solve(solve::SolveCmd),
    /// Compare backends on spec files: each run in its own process, killed at the time limit
    /// plus a grace period, recorded as it ends (rerun to resume); writes results.md,
    /// results.csv, results.json, a performance profile (profile.svg) and a bar chart of the
    /// time per instance and backend (bars.svg) to --out.
    Compare(compare::CompareArgs),
    /// One task of a `compare --executor slurm` job array (run by Slurm, not by hand).
    #[command(name = "compare-task", hide = true)]
    CompareTask(compare::TaskArgs),
    /// Lay out a city's streets (§5.1): sub-regions from the major roads, levels 2–4 per
    /// sub-region (in parallel), smoothing; writes city.json, streets.geojson, city.svg/png and
    /// every level's spec, mesh and result under regions/. Rerun to resume an interrupted run.
    City(city::CityArgs),
    /// A real site from an OpenStreetMap extract you bring (OSM PBF or XML): site.geojson (the
    /// region less its water, with its major roads: what `netspec layout` reads), map/ (the real
    /// drivable streets as a design, for `netspec stats` and `netspec traffic`), and with --grow
    /// and --city a grow context and an IP city spec of the same site. Data © OpenStreetMap
    /// contributors, ODbL.
    Site(site::SiteArgs),
    /// Street statistics of designs (OSMnx's basic_stats, orientation entropy and order,
    /// blocks) on one region, each with its distance to the real streets of a site's map/.
    Stats(stats::StatsArgs),
    /// Evaluate designed street networks in SUMO (installed by scripts/setup.sh): export to
    /// SUMO's plain XML with a road type per level, netconvert, seeded through and local
    /// trips routed by duarouter, a headless simulation; writes traffic.json, volume.svg/png
    /// and traveltime.svg/png per design, and with several designs (same demand) comparison.md,
    /// comparison.json and comparison.svg/png.
    Traffic(traffic::TrafficArgs),
    /// Design in the browser: a local web application to open, edit and solve specs, watch the
    /// solve, and compare and export designs (docs/serve.md).
    Serve(serve::ServeArgs),
    /// Lay out a game level from its connectivity graph (Ma et al. 2014): blocks, a door width,
    /// nodes and edges in LEVEL.toml (format in docs/levels.md). Writes level.json with
    /// `--out`. Exit code 0 for a layout or a proof that none exists, 4 for neither. With
    /// `--export-spec`, also writes the first layout as mesh.json and network.toml (a spec for
    /// `netspec solve` whose network passes between rooms only through doors).
    Level(level::LevelArgs),
    /// Lay out an urban region by hierarchical domain splitting (Yang et al. 2013): every part is
    /// matched against the template library first and cut along a streamline of its
    /// boundary-aligned cross field only where no template fits; zones marked in the region keep
    /// their use; the §7 metrics and an independent check. REGION is TOML (metres) or GeoJSON
    /// (WGS 84); format in docs/layout.md. Writes layout.json, layout.svg/.png, registration and
    /// histograms pictures, layout.geojson and run.json with --out.
    Layout(layout::LayoutArgs),
    /// Grow a road network by traffic (Beneš, Wilkie & Křivánek 2014): settlements, minor streets
    /// around growth nuclei and major roads built where trade between neighbouring cities
    /// saturates the routes. CONTEXT is a TOML historical context (docs/grow.md). Writes
    /// network.json, series.csv, network.svg/.png (and network.geojson with an origin) into DIR;
    /// with --window also city.toml and trade.json of that window (CONTEXT may then be a grown
    /// output directory, which is windowed without growing again). The network is checked
    /// independently; exits with 3 if network.json lists violations.
    Grow(grow::GrowArgs),
    /// A region's cross field (smooth or distance): field.json (singularities with their index,
    /// the field per vertex), field.svg and field.png with a few streamlines.
    Field(layout::FieldArgs),
    /// Write a level file of unit squares for a graph family: `path:N`, `cycle:N`, `ladder:N`
    /// (2 × N), `grid:RxC`, `caterpillar:NxL` (a spine of N, L legs each), `star:N`, `tree:N`
    /// (complete binary); `+triangle` adds an edge that closes a triangle.
    LevelGen(level::LevelGenArgs),
    /// Convert a model between MPS and LP (formats chosen by extension; `.gz` compressed).
    Convert(convert::ConvertArgs),
    /// List the compiled backends with their versions and capabilities.
    Solvers(solvers::SolversArgs),
}

impl Command {
    /// Runs the command.
    pub fn run(self) -> Result<ExitCode> {
        match self {
            Command::SolveFile(a) => a.run(),
            Command::Solve(a) => a.run(),
            Command::Compare(a) => a.run(),
            Command::CompareTask(a) => a.run(),
            Command::City(a) => a.run(),
            Command::Site(a) => site::run(a),
            Command::Stats(a) => stats::run(a),
            Command::Traffic(a) => a.run(),
            Command::Serve(a) => a.run(),
            Command::Level(a) => a.run(),
            Command::Layout(a) => a.run(),
            Command::Grow(a) => a.run(),
            Command::Field(a) => a.run(),
            Command::LevelGen(a) => a.run(),
            Command::Convert(a) => a.run(),
            Command::Solvers(a) => a.run(),
        }
    }
}
