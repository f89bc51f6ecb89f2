//! Traffic evaluation of designed street networks in SUMO (paper §5.1: "We use SUMO to do
//! traffic simulations to evaluate our functional specifications").
//!
//! One evaluation ([`evaluate`]):
//! 1. [`network`]: the design graph of a `netspec solve` or `netspec city` output, in metres,
//!    with each street's level and (for cities) its smoothed shape;
//! 2. [`export`]: SUMO plain XML (`.nod.xml`, `.edg.xml`, `.typ.xml`, one road type per level),
//!    turned into a `.net.xml` by SUMO's own `netconvert`;
//! 3. [`demand`]: seeded trips — through traffic between points on the region's boundary,
//!    local traffic between random interior points — placed on the nearest street of the
//!    design, so designs of one region get the same demand; routed by SUMO's `duarouter`;
//! 4. [`sumo`]: `sumo` headless with tripinfo, edge data, vehicle routes and statistics output;
//! 5. [`parse`] and [`report`]: vehicles inserted / arrived / teleported, travel time (mean,
//!    95th percentile), route length, waiting time, and how much of the through traffic runs on
//!    local streets; traffic volume per street for the pictures ([`picture`], drawn by
//!    `render::traffic`).
//!
//! [`run`] is `netspec traffic`: several designs under the same demand, their files and a
//! comparison.

pub mod demand;
pub mod export;
pub mod network;
pub mod parse;
pub mod picture;
pub mod report;
pub mod road;
pub mod run;
pub mod streets;
pub mod sumo;

pub use demand::DemandSettings;
pub use report::TrafficReport;
pub use road::{RoadEdge, RoadNetwork};
pub use sumo::Sumo;

use std::path::{Path, PathBuf};
use std::time::Instant;

/// Why a traffic evaluation could not be done, naming the file concerned.
#[derive(Debug, thiserror::Error)]
#[error("{}: {kind}", path.display())]
pub struct TrafficError {
    /// The file or directory concerned (the input, a SUMO input or output, or a SUMO binary).
    pub path: PathBuf,
    /// What is wrong.
    #[source]
    pub kind: TrafficErrorKind,
}

/// What went wrong in a traffic evaluation.
#[derive(Debug, thiserror::Error)]
pub enum TrafficErrorKind {
    /// The directory holds neither a design nor a city result.
    #[error("no design here: expected result.json (a `netspec solve` output), city.json (a `netspec city` output), layout.json (a `netspec layout` output) or network.json (a `netspec grow` output)")]
    NoResult,
    /// A file could not be read or written.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// A file is not what it should be.
    #[error("cannot read {what}: {message}")]
    Parse {
        /// What the file should have been.
        what: &'static str,
        /// The parser's message.
        message: String,
    },
    /// The result holds no network (infeasible, time limit without a solution, …).
    #[error("the result has no network ({0}); nothing to simulate")]
    NoNetwork(String),
    /// The network failed netspec's independent checks.
    #[error("the network failed netspec's independent checks ({0}); not simulating it")]
    Invalid(String),
    /// SUMO's binaries are not where they should be.
    #[error("SUMO not found (looked in {looked}); install it with `bash scripts/setup.sh sumo` (or `./dev setup sumo`), or set SUMO_HOME")]
    SumoMissing {
        /// Where we looked.
        looked: String,
    },
    /// A SUMO tool ran and failed.
    #[error("`{tool}` failed ({status}): {detail} (full output in {})", log.display())]
    ToolFailed {
        /// The tool (`netconvert`, `duarouter`, `sumo`).
        tool: String,
        /// Its exit status.
        status: String,
        /// The last lines it printed.
        detail: String,
        /// Its whole output.
        log: PathBuf,
    },
    /// SUMO's output does not say what it should.
    #[error("{0}")]
    Output(String),
    /// The command's time limit ran out while a SUMO tool ran; it was stopped.
    #[error("the time limit ran out while `{tool}` ran; it was stopped (raise --time-limit)")]
    TimeLimit {
        /// The tool.
        tool: String,
    },
}

impl TrafficError {
    /// An error about `path`.
    pub fn new(path: impl Into<PathBuf>, kind: TrafficErrorKind) -> TrafficError {
        TrafficError { path: path.into(), kind }
    }
}

pub(crate) fn read(path: &Path) -> Result<String, TrafficError> {
    crate::io::read_utf8(path).map_err(|e| TrafficError::new(path, e.into()))
}

pub(crate) fn write(path: &Path, text: &str) -> Result<(), TrafficError> {
    std::fs::write(path, text).map_err(|e| TrafficError::new(path, e.into()))
}

/// Runs one whole evaluation of `net` into `dir` (SUMO's files under `dir/sumo/`): export,
/// `netconvert`, demand, `duarouter`, `sumo`, and the parsed report (write it with
/// [`TrafficReport::write`]). Pictures are the caller's (see [`picture`]).
pub fn evaluate(
    net: &RoadNetwork,
    demand: &DemandSettings,
    sumo: &Sumo,
    dir: &Path,
) -> Result<TrafficReport, TrafficError> {
    let t0 = Instant::now();
    let sdir = dir.join("sumo");
    std::fs::create_dir_all(&sdir).map_err(|e| TrafficError::new(&sdir, e.into()))?;
    let mut timings = report::Timings::default();

    let t = Instant::now();
    let files = export::write_plain(net, &sdir, "net")?;
    timings.export = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let net_xml = sdir.join("net.net.xml");
    sumo.netconvert(&files, &net_xml)?;
    timings.netconvert = t.elapsed().as_secs_f64();
    let sumo_net = parse::net(&net_xml)?;

    let t = Instant::now();
    let trips = demand::generate(&net.region, demand);
    let placed = demand::place(&trips, net, &sumo_net);
    let trips_xml = sdir.join("trips.trips.xml");
    write(&trips_xml, &demand::trips_xml(&placed))?;
    let routes_xml = sdir.join("routes.rou.xml");
    sumo.duarouter(&net_xml, &trips_xml, &routes_xml, demand.seed)?;
    let routed = parse::route_count(&routes_xml)?;
    timings.routing = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let outputs = sumo.simulate(&net_xml, &routes_xml, &sdir, demand)?;
    timings.simulation = t.elapsed().as_secs_f64();

    let t = Instant::now();
    let mut rep = report::build(net, demand, sumo, &sumo_net, &trips, &placed, routed, &outputs)?;
    timings.parse = t.elapsed().as_secs_f64();
    timings.total = t0.elapsed().as_secs_f64();
    rep.timings = timings;
    Ok(rep)
}
