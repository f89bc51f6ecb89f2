//! The `netspec` command-line tool: a thin layer over the library.

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use netspec::pipeline::Method;
use netspec::solvers::SolverKind;
use netspec::spec::Variant;
use std::path::PathBuf;
use std::process::ExitCode;

mod cli {
    pub mod args;
    pub mod city;
    pub mod compare;
    pub mod grow;
    pub mod interrupt;
    pub mod layout;
    pub mod level;
    pub mod site;
    pub mod solve;
    pub mod solve_file;
    pub mod stats;
    pub mod traffic;
}

use cli::args::{ExecutorArgs, SolveArgs};

#[derive(Parser)]
#[command(name = "netspec", version, about = "Network design from functional specifications, by integer programming", long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve an MPS or LP file (also `.mps.gz`, `.lp.gz`) and check the answer independently.
    #[command(name = "solve-file")]
    SolveFile {
        /// The model file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
        file: PathBuf,
        #[command(flatten)]
        solve: SolveArgs,
        /// Start from the solution in this file (`name value` lines, e.g. an earlier `--sol`).
        /// netspec checks it first; a start that fails the check is reported and not used.
        #[arg(long, value_name = "FILE.sol")]
        start: Option<PathBuf>,
        /// Also write the JSON result (schema in docs/result-schema.md) here; `-` for stdout.
        #[arg(long, value_name = "PATH")]
        json: Option<PathBuf>,
    },
    /// Design a network from a spec file (TOML or JSON): build the MILP, solve it, check and
    /// validate the answer, and write result.json, network.svg and network.png.
    Solve {
        /// The spec file.
        spec: PathBuf,
        #[command(flatten)]
        solve: SolveArgs,
        /// Output directory (default: out/<the spec file's name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Also write the MILP (`.lp` or `.mps`, by extension).
        #[arg(long, value_name = "FILE")]
        export: Option<PathBuf>,
        /// Build and export the model without solving it.
        #[arg(long)]
        no_solve: bool,
        /// Formulation, replacing the spec's: paper, tight or strong, optionally with parts and
        /// switches (`strong:out_arcs=off`, `tight:connectivity=flow`) and the solve strategy's
        /// switches (`strong:split_objective=off`).
        #[arg(long, value_name = "RECIPE[:KEY=VALUE]…")]
        formulation: Option<Variant>,
        /// Solve only the LP relaxation (with the recipe's cutting-plane rounds) and print its
        /// bound.
        #[arg(long, conflicts_with = "no_solve")]
        relax: bool,
        /// When the spec is infeasible, do not look for the requirements that conflict.
        #[arg(long)]
        no_explain: bool,
        /// Time budget for explaining an infeasible spec, seconds, from when the explanation
        /// starts: it may run past --time-limit, which the solve says up front (default: what is
        /// left of --time-limit; 60 s without one).
        #[arg(long, value_name = "SECONDS")]
        explain_time: Option<f64>,
        /// Start from this design: an earlier `result.json` of the same spec, or a `.sol` file
        /// of this model (`--sol`). It is checked first; a start that fails is reported, not used.
        /// Default: the construction heuristic's design (a twentieth of the time limit, ≤ 1 s; while
        /// it has no design, up to a fifth, ≤ 60 s; one search per solver thread).
        #[arg(long, value_name = "FILE", conflicts_with = "no_start")]
        start: Option<PathBuf>,
        /// Solve without a MIP start.
        #[arg(long)]
        no_start: bool,
        /// Refuse a mesh of more cells than this (default 250,000), before building it.
        #[arg(long, value_name = "CELLS")]
        max_cells: Option<usize>,
    },
    /// Compare backends on spec files: each run in its own process, killed at the time limit
    /// plus a grace period, recorded as it ends (rerun to resume); writes results.md,
    /// results.csv, results.json, a performance profile (profile.svg) and a bar chart of the
    /// time per instance and backend (bars.svg) to --out.
    Compare {
        /// Spec files.
        #[arg(required_unless_present_any = ["manifest", "merge"])]
        specs: Vec<PathBuf>,
        /// A manifest of instances with the paper's figures (e.g. models/table1.toml).
        #[arg(long, conflicts_with = "specs")]
        manifest: Option<PathBuf>,
        /// Backends, comma-separated (default: every compiled one but good_lp); the searches
        /// `heuristic` and `anneal` may be listed too.
        #[arg(long, value_delimiter = ',')]
        solvers: Vec<Method>,
        /// Time limit per run, seconds.
        #[arg(long, default_value_t = 60.0)]
        time_limit: f64,
        /// Seconds past the limit before a run is killed.
        #[arg(long, default_value_t = 10.0)]
        grace: f64,
        /// Seeds to run (default: one run with each solver's default).
        #[arg(long, value_delimiter = ',')]
        seeds: Vec<u64>,
        /// Threads per run.
        #[arg(long)]
        threads: Option<u32>,
        /// Give each row the paper's own time for it as its limit (capped at --time-limit).
        #[arg(long)]
        paper_limits: bool,
        /// Formulations, comma-separated (`paper`, `strong`, `strong:out_arcs=off`): every
        /// backend runs with each, as its own column (`highs/strong`). Default: the spec's own.
        #[arg(long, value_delimiter = ',')]
        formulations: Vec<Variant>,
        /// Only the manifest rows with these names (comma-separated; `*` and `?` match any run
        /// of characters and one: `2*`, `*-L4`).
        #[arg(long, value_delimiter = ',', value_name = "ROW")]
        rows: Vec<String>,
        /// Solve without the heuristic's MIP start (each child gets `solve --no-start`).
        #[arg(long)]
        no_start: bool,
        #[command(flatten)]
        executor: ExecutorArgs,
        /// Estimate how long these runs take on clusters of K nodes with C cores each
        /// (comma-separated `KxC`: `1x2,20x2`), by list scheduling their recorded wall times;
        /// printed and added to results.md.
        #[arg(long, value_delimiter = ',', value_name = "KxC")]
        makespan: Vec<netspec::compare::makespan::Shape>,
        /// Combine finished comparisons (each DIR's results.json) into one report in --out
        /// without solving: every column of every DIR, in the order given (column labels must
        /// differ). With --manifest, its rows are the table's; else the first DIR's.
        #[arg(long, value_delimiter = ',', value_name = "DIR", conflicts_with_all = ["specs", "solvers", "seeds", "formulations", "no_start", "paper_limits", "threads"])]
        merge: Vec<PathBuf>,
        /// Output directory.
        #[arg(long, default_value = "out/compare")]
        out: PathBuf,
    },
    /// One task of a `compare --executor slurm` job array (run by Slurm, not by hand).
    #[command(name = "compare-task", hide = true)]
    CompareTask {
        /// The array's plan (`slurm/plan-*.json` in the comparison's folder).
        plan: PathBuf,
        /// The task's index in it.
        index: usize,
    },
    /// Lay out a city's streets (§5.1): sub-regions from the major roads, levels 2–4 per
    /// sub-region (in parallel), smoothing; writes city.json, streets.geojson, city.svg/png and
    /// every level's spec, mesh and result under regions/. Rerun to resume an interrupted run.
    City {
        /// The city spec (TOML).
        spec: PathBuf,
        /// Backend (default: the spec's, else the embedded HiGHS).
        #[arg(long, value_name = "NAME")]
        solver: Option<SolverKind>,
        /// Time limit of every level, seconds, for all of its work (model, start, solve,
        /// outputs; default: each level's `time_limit`).
        #[arg(long, value_name = "SECONDS")]
        time_limit: Option<f64>,
        /// Time limit of the whole city, seconds: no level starts after it, a running level
        /// stops at it with its best network, and the city is assembled and written within it.
        #[arg(long, value_name = "SECONDS")]
        total_time_limit: Option<f64>,
        /// Total thread budget (default: the spec's).
        #[arg(long)]
        threads: Option<u32>,
        /// Threads per solve (default: the spec's).
        #[arg(long)]
        threads_per_solve: Option<u32>,
        /// Relative gap.
        #[arg(long, value_name = "REL")]
        gap: Option<f64>,
        /// Solve every level again even if an earlier run finished it.
        #[arg(long)]
        fresh: bool,
        /// Refuse a city whose level meshes could exceed this many cells (default 250,000).
        #[arg(long, value_name = "CELLS")]
        max_cells: Option<usize>,
        #[command(flatten)]
        executor: ExecutorArgs,
        /// Solve one sub-region's level as a cluster job does (`REGION:LEVEL`; run by Slurm).
        #[arg(long, hide = true, value_name = "REGION:LEVEL")]
        level_job: Option<String>,
        /// Output directory (default: out/<the city file's name>).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// A real site from an OpenStreetMap extract you bring (OSM PBF or XML): site.geojson (the
    /// region less its water, with its major roads: what `netspec layout` reads), map/ (the real
    /// drivable streets as a design, for `netspec stats` and `netspec traffic`), and with --grow
    /// and --city a grow context and an IP city spec of the same site. Data © OpenStreetMap
    /// contributors, ODbL.
    Site(cli::site::SiteArgs),
    /// Street statistics of designs (OSMnx's basic_stats, orientation entropy and order,
    /// blocks) on one region, each with its distance to the real streets of a site's map/.
    Stats(cli::stats::StatsArgs),
    /// Evaluate designed street networks in SUMO (installed by scripts/setup.sh): export to
    /// SUMO's plain XML with a road type per level, netconvert, seeded through and local
    /// trips routed by duarouter, a headless simulation; writes traffic.json, volume.svg/png
    /// and traveltime.svg/png per design, and with several designs (same demand) comparison.md,
    /// comparison.json and comparison.svg/png.
    Traffic {
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
        #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_window)]
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
    },
    /// Design in the browser: a local web application to open, edit and solve specs, watch the
    /// solve, and compare and export designs (docs/serve.md).
    Serve {
        /// The folder whose specs are listed, and where runs (`runs/`) and saved specs go.
        #[arg(long, value_name = "DIR", default_value = ".")]
        root: PathBuf,
        /// The port to listen on (0: any free port).
        #[arg(long, default_value_t = 8080)]
        port: u16,
        /// The address to listen on; the default keeps the server to this machine.
        #[arg(long, default_value = "127.0.0.1")]
        bind: std::net::IpAddr,
        /// Solves running at once (more wait in a queue).
        #[arg(long, default_value_t = 2)]
        max_solves: usize,
        /// Threads all running solves share (default: the cores).
        #[arg(long)]
        threads: Option<u32>,
    },
    /// Lay out a game level from its connectivity graph (Ma et al. 2014): blocks, a door width,
    /// nodes and edges in LEVEL.toml (format in docs/levels.md). Writes level.json with
    /// `--out`. Exit code 0 for a layout or a proof that none exists, 4 for neither. With
    /// `--export-spec`, also writes the first layout as mesh.json and network.toml (a spec for
    /// `netspec solve` whose network passes between rooms only through doors).
    Level {
        /// The level file.
        spec: PathBuf,
        /// Method: the paper's annealer, the exact MILP, or both side by side (the first to answer stops the other).
        #[arg(long, value_enum, default_value = "both")]
        method: LevelMethod,
        /// Seed of the annealer.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Run the annealer with N seeds from --seed on: summary.json and a table over them.
        #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=100_000))]
        seeds: u64,
        /// Distinct layouts wanted.
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
        count: u64,
        /// Backend of the exact model (default: highs when compiled in).
        #[arg(long)]
        solver: Option<SolverKind>,
        /// Seconds for the whole command: both methods, the proof and its explanation.
        #[arg(long, value_name = "SECONDS", default_value_t = 60.0)]
        time_limit: f64,
        /// Solver threads.
        #[arg(long)]
        threads: Option<u32>,
        /// When no layout exists, do not look for the edges that conflict.
        #[arg(long)]
        no_explain: bool,
        /// Output directory (level.json).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Export the first layout as mesh.json and network.toml into the output directory.
        #[arg(long, requires = "out")]
        export_spec: bool,
        /// Grid spacing inside the rooms of the export (default: the door width).
        #[arg(long, requires = "export_spec")]
        spacing: Option<f64>,
        /// The node whose room gets the sink (default: the first node).
        #[arg(long, value_name = "NODE", requires = "export_spec")]
        entrance: Option<String>,
        /// Coverage range of the export, in level units, at least 1 (default: the smallest the
        /// rooms' forced vertices satisfy, so the network is the shortest through every room).
        #[arg(long, value_name = "R", requires = "export_spec")]
        coverage: Option<f64>,
    },
    /// Lay out an urban region by hierarchical domain splitting (Yang et al. 2013): every part is
    /// matched against the template library first and cut along a streamline of its
    /// boundary-aligned cross field only where no template fits; zones marked in the region keep
    /// their use; the §7 metrics and an independent check. REGION is TOML (metres) or GeoJSON
    /// (WGS 84); format in docs/layout.md. Writes layout.json, layout.svg/.png, registration and
    /// histograms pictures, layout.geojson and run.json with --out.
    Layout {
        /// The region file.
        region: PathBuf,
        /// Seed of every random choice (default: the region's `seed`).
        #[arg(long)]
        seed: Option<u64>,
        /// Layouts to make: the first by --mode, the others drawn by quality with seeds seed+1, ….
        #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=1000))]
        variations: u64,
        /// The cross field: boundary-aligned smooth, or the distance field (the paper's most used).
        #[arg(long, value_enum, default_value = "distance")]
        field: FieldKind,
        /// Streamline choice: the best (comparison mode) or drawn by quality (variation mode).
        #[arg(long, value_enum, default_value = "best")]
        mode: SelectionKind,
        /// Iterations of the global optimisation of the streets (fairness and strip fitting,
        /// the paper's §6, which runs 10); 0 for none. Off by default: on most example regions
        /// it raises the registration distance and the corner deviation (docs/layout.md).
        #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=100))]
        optimise: u64,
        /// Output directory.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// A layout.json of this region to lay a part of out again (with --relayout).
        #[arg(long, value_name = "LAYOUT.json", requires = "relayout")]
        from: Option<PathBuf>,
        /// The part (an id of the `parts` tree in --from's layout.json) to lay out again, the rest
        /// kept as it is.
        #[arg(long, value_name = "PART", requires = "from", conflicts_with_all = ["optimise", "variations"])]
        relayout: Option<String>,
    },
    /// Grow a road network by traffic (Beneš, Wilkie & Křivánek 2014): settlements, minor streets
    /// around growth nuclei and major roads built where trade between neighbouring cities
    /// saturates the routes. CONTEXT is a TOML historical context (docs/grow.md). Writes
    /// network.json, series.csv, network.svg/.png (and network.geojson with an origin) into DIR;
    /// with --window also city.toml and trade.json of that window (CONTEXT may then be a grown
    /// output directory, which is windowed without growing again). The network is checked
    /// independently; exits with 3 if network.json lists violations.
    Grow {
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
        /// Also write step-NNN.svg every K steps (and at step 0).
        #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..))]
        every: Option<u32>,
        /// A window of the map, metres (x0,y0,x1,y1): writes city.toml (its grown major roads,
        /// water as obstacles, unbuilt sub-regions running no level) and trade.json (the trade
        /// flows across it).
        #[arg(long, value_name = "X0,Y0,X1,Y1", value_parser = parse_window)]
        window: Option<[f64; 4]>,
    },
    /// A region's cross field (smooth or distance): field.json (singularities with their index,
    /// the field per vertex), field.svg and field.png with a few streamlines.
    Field {
        /// The region file (TOML or GeoJSON).
        region: PathBuf,
        /// The construction.
        #[arg(long, value_enum, default_value = "distance")]
        method: FieldKind,
        /// Triangle size in metres (default: a third of the parcel depth).
        #[arg(long)]
        h: Option<f64>,
        /// Output directory.
        #[arg(long, value_name = "DIR")]
        out: PathBuf,
    },
    /// Write a level file of unit squares for a graph family: `path:N`, `cycle:N`, `ladder:N`
    /// (2 × N), `grid:RxC`, `caterpillar:NxL` (a spine of N, L legs each), `star:N`, `tree:N`
    /// (complete binary); `+triangle` adds an edge that closes a triangle.
    LevelGen {
        /// The family, e.g. `grid:10x10` or `grid:10x10+triangle`.
        family: String,
        /// The door width.
        #[arg(long, default_value_t = 0.5)]
        door_width: f64,
        /// Write here instead of standard output.
        #[arg(long, value_name = "FILE")]
        out: Option<PathBuf>,
    },
    /// Convert a model between MPS and LP (formats chosen by extension; `.gz` compressed).
    Convert {
        /// Input file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
        input: PathBuf,
        /// Output file (`.mps`, `.lp`, `.mps.gz` or `.lp.gz`).
        output: PathBuf,
    },
    /// List the compiled backends with their versions and capabilities.
    Solvers {
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// `x0,y0,x1,y1` as four finite numbers with `x0 < x1`, `y0 < y1`.
pub(crate) fn parse_window(s: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> =
        s.split(',').map(|x| x.trim().parse::<f64>()).collect::<Result<_, _>>().map_err(|e| e.to_string())?;
    match v[..] {
        [x0, y0, x1, y1] if v.iter().all(|x| x.is_finite()) && x0 < x1 && y0 < y1 => Ok([x0, y0, x1, y1]),
        _ => Err(format!("expected x0,y0,x1,y1 with x0 < x1 and y0 < y1 (metres), got `{s}`")),
    }
}

/// A cross field's construction.
#[derive(Copy, Clone, Debug, clap::ValueEnum)]
enum FieldKind {
    /// Smooth and boundary-aligned (harmonic in the power representation).
    Smooth,
    /// Aligned with the gradient of the distance to the boundary (D-field).
    Distance,
}

impl From<FieldKind> for netspec::layout::field::FieldMethod {
    fn from(m: FieldKind) -> Self {
        match m {
            FieldKind::Smooth => netspec::layout::field::FieldMethod::Smooth,
            FieldKind::Distance => netspec::layout::field::FieldMethod::Distance,
        }
    }
}

/// How `netspec layout` picks a streamline.
#[derive(Copy, Clone, Debug, clap::ValueEnum)]
enum SelectionKind {
    /// The highest quality.
    Best,
    /// Drawn with probability proportional to quality.
    Random,
}

impl From<SelectionKind> for netspec::layout::split::Selection {
    fn from(m: SelectionKind) -> Self {
        match m {
            SelectionKind::Best => netspec::layout::split::Selection::Best,
            SelectionKind::Random => netspec::layout::split::Selection::Random,
        }
    }
}

/// `--method` of `netspec level`.
#[derive(Copy, Clone, Debug, clap::ValueEnum)]
enum LevelMethod {
    /// The paper's incremental simulated annealing.
    Anneal,
    /// The exact placement MILP.
    Milp,
    /// Both side by side on two threads; the first answer stops the other.
    Both,
}

impl From<LevelMethod> for netspec::levels::Method {
    fn from(m: LevelMethod) -> Self {
        match m {
            LevelMethod::Anneal => netspec::levels::Method::Anneal,
            LevelMethod::Milp => netspec::levels::Method::Milp,
            LevelMethod::Both => netspec::levels::Method::Both,
        }
    }
}

fn main() -> ExitCode {
    // Behave like other Unix tools when the reader of our output goes away (`| head`): end
    // quietly instead of panicking on a broken pipe.
    #[cfg(unix)]
    // SAFETY: resetting a signal disposition to its default before any thread is started.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    match run(cli) {
        Ok(code) => code,
        Err(e) => {
            // Print the cause chain, skipping causes whose text the message above already shows
            // (our error types name the file and then embed their source).
            let mut shown = e.to_string();
            eprintln!("error: {shown}");
            for cause in e.chain().skip(1) {
                let text = cause.to_string();
                if !shown.contains(&text) {
                    eprintln!("  caused by: {text}");
                }
                shown = text;
            }
            ExitCode::FAILURE
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::SolveFile { file, solve, start, json } => cli::solve_file::run(file, &solve, start, json.as_deref()),
        Command::Solve {
            spec,
            solve,
            out,
            export,
            no_solve,
            formulation,
            relax,
            no_explain,
            explain_time,
            start,
            no_start,
            max_cells,
        } => {
            let start = match (start, no_start) {
                (_, true) => netspec::run::StartChoice::Nothing,
                (Some(file), false) => netspec::run::StartChoice::File(file),
                (None, false) => netspec::run::StartChoice::Heuristic,
            };
            cli::solve::solve(netspec::run::SolveRequest {
                spec,
                variant: formulation,
                flags: solve.settings(),
                out,
                export,
                no_solve,
                relax,
                sol: solve.sol.clone(),
                explain: (!no_explain).then_some(
                    explain_time.map_or(netspec::run::ExplainBudget::Remaining, netspec::run::ExplainBudget::Seconds),
                ),
                start,
                interrupt: None,
                progress: None,
                max_cells,
                incumbents: None,
            })
        }
        Command::Compare {
            specs,
            manifest,
            solvers,
            time_limit,
            grace,
            seeds,
            threads,
            paper_limits,
            formulations,
            rows,
            no_start,
            executor,
            makespan,
            merge,
            out,
        } => {
            if !merge.is_empty() {
                return cli::compare::merge(&merge, manifest.as_deref(), &rows, &out, &makespan);
            }
            cli::compare::run(cli::compare::CompareArgs {
                specs,
                manifest,
                solvers,
                time_limit,
                grace,
                seeds,
                threads,
                paper_limits,
                formulations,
                rows,
                no_start,
                executor: executor
                    .slurm()?
                    .map_or(netspec::compare::Executor::Local, netspec::compare::Executor::Slurm),
                makespan,
                out,
            })
        }
        Command::CompareTask { plan, index } => cli::compare::task(&plan, index),
        Command::City {
            spec,
            solver,
            time_limit,
            total_time_limit,
            threads,
            threads_per_solve,
            gap,
            fresh,
            max_cells,
            executor,
            level_job,
            out,
        } => {
            let args = cli::city::CityArgs {
                solver,
                time_limit,
                total_time_limit,
                threads,
                threads_per_solve,
                gap,
                fresh,
                out,
                max_cells,
                slurm: executor.slurm()?,
                level_job,
            };
            cli::city::run_city(&spec, args)
        }
        Command::Traffic {
            designs,
            labels,
            duration,
            through_rate,
            local_rate,
            seed,
            metres_per_unit,
            level,
            window,
            region,
            trade,
            trade_rate,
            sumo_home,
            out,
            time_limit,
        } => cli::traffic::run_traffic(cli::traffic::TrafficArgs {
            designs,
            labels,
            demand: netspec::traffic::DemandSettings {
                duration,
                through_per_hour: through_rate,
                local_per_hour: local_rate,
                seed,
                trade_per_hour: trade_rate,
                trade: match &trade {
                    Some(f) => netspec::traffic::demand::TradeFile::load(f)?.flows,
                    None => Vec::new(),
                },
            },
            load: netspec::traffic::network::LoadOptions {
                metres_per_unit,
                level,
                window,
                region: region.as_deref().map(netspec::traffic::network::SiteRegion::load).transpose()?,
            },
            sumo_home,
            out,
            time_limit,
        }),
        Command::Site(args) => cli::site::run(args),
        Command::Stats(args) => cli::stats::run(args),
        Command::Serve { root, port, bind, max_solves, threads } => {
            let mut opts = netspec::serve::ServeOptions { root, port, bind, max_solves, ..Default::default() };
            opts.threads = threads.unwrap_or(opts.threads);
            netspec::serve::run(opts, |addr| println!("netspec serve: http://{addr}/ (Ctrl-C stops)"))?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Level {
            spec,
            method,
            seed,
            seeds,
            count,
            solver,
            time_limit,
            threads,
            no_explain,
            out,
            export_spec,
            spacing,
            entrance,
            coverage,
        } => {
            let solver =
                solver.or_else(SolverKind::default_kind).ok_or_else(|| anyhow::anyhow!("no backend compiled in"))?;
            if !(time_limit > 0.0 && time_limit.is_finite()) {
                anyhow::bail!("--time-limit must be a positive number of seconds, got {time_limit}");
            }
            cli::level::run(netspec::levels::LevelRequest {
                spec,
                method: method.into(),
                count: count as usize,
                solver,
                time_limit,
                threads,
                out,
                explain: !no_explain,
                seed,
                export: export_spec.then_some(netspec::levels::bridge::BridgeOptions { spacing, entrance, coverage }),
                seeds: seeds as usize,
            })
        }
        Command::Layout { region, seed, variations, field, mode, optimise, out, from, relayout } => {
            cli::layout::run(&netspec::layout::run::LayoutRequest {
                region,
                field: field.into(),
                selection: mode.into(),
                seed,
                variations: variations as usize,
                optimise: optimise as usize,
                out,
                relayout: from.zip(relayout),
            })
        }
        Command::Grow { context, out, seed, steps, every, window } => {
            cli::grow::run(&netspec::grow::GrowRequest { context, out, seed, steps, every }, window)
        }
        Command::Field { region, method, h, out } => {
            if let Some(h) = h.filter(|h| !(h.is_finite() && *h > 0.0)) {
                anyhow::bail!("--h must be a positive number of metres, got {h}");
            }
            cli::layout::field(&region, method.into(), h, &out)
        }
        Command::LevelGen { family, door_width, out } => {
            let g = netspec::levels::generate::Generated::parse(&family)?;
            if !(door_width > 0.0 && door_width <= 1.0) {
                anyhow::bail!("--door-width must be in (0, 1] for unit squares, got {door_width}");
            }
            let text = g.to_toml(door_width);
            match out {
                Some(path) => std::fs::write(&path, text).with_context(|| format!("writing {}", path.display()))?,
                None => print!("{text}"),
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Convert { input, output } => {
            let c = netspec::io::convert(&input, &output)?;
            for w in &c.warnings {
                eprintln!("warning: {}: {w}", input.display());
            }
            let renamed = if c.renamed == 0 { String::new() } else { format!("; {} names sanitised", c.renamed) };
            println!("wrote {} ({}){renamed}", output.display(), c.stats);
            Ok(ExitCode::SUCCESS)
        }
        Command::Solvers { json } => {
            let list = netspec::report::solver_list();
            if json {
                println!("{}", serde_json::to_string_pretty(&list)?);
            } else {
                for s in &list {
                    println!("{:<8} {:<10} {}", s.name, s.version, s.capability_summary());
                }
                let (live, at_end): (Vec<_>, Vec<_>) = list.iter().partition(|s| s.capabilities.reports_progress);
                let names = |v: &[&netspec::report::SolverInfo]| {
                    v.iter().map(|s| s.name.as_str()).collect::<Vec<_>>().join(", ")
                };
                println!(
                    "live: improving designs and progress while solving from {}; only at the end from {}",
                    names(&live),
                    names(&at_end)
                );
                let missing: Vec<_> = SolverKind::ALL.iter().filter(|k| !k.is_compiled()).map(|k| k.name()).collect();
                if !missing.is_empty() {
                    println!("not compiled in: {} (enable the cargo features of the same names)", missing.join(", "));
                }
            }
            Ok(ExitCode::SUCCESS)
        }
    }
}
