//! Times the library's solve of a spec as the Python package's `netspec.solve` makes it
//! ([`netspec::run::solve_loaded`], nothing written), for the overhead measurement of
//! `python/bench/overhead.py` (docs/python.md): prints one line, `seconds objective`.
//!
//! `cargo run --release --example solve_timing -- SPEC [THREADS] [--no-start]`

use netspec::pipeline::settings::Settings;
use netspec::run::{load, solve_loaded, SolveRequest};
use std::path::PathBuf;
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let spec = PathBuf::from(args.next().ok_or("usage: solve_timing SPEC [THREADS]")?);
    let threads = args.next().map(|t| t.parse::<u32>()).transpose()?;
    let start = match args.next().as_deref() {
        Some("--no-start") => netspec::run::StartChoice::Nothing,
        _ => netspec::run::StartChoice::Heuristic,
    };
    let t0 = Instant::now();
    let problem = load(&spec, None, netspec::spec::DEFAULT_MAX_CELLS)?;
    let req =
        SolveRequest { spec, flags: Settings { threads, ..Settings::default() }, start, ..SolveRequest::default() };
    let (_, solved) = solve_loaded(&problem, &req, t0, None, &mut |_| {})?;
    let seconds = t0.elapsed().as_secs_f64();
    let objective = solved.design.and_then(|d| d.objective());
    println!("{seconds:.6} {}", objective.map_or("-".to_string(), |o| o.to_string()));
    Ok(())
}
