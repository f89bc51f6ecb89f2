//! The one integration-test binary (linking the native solvers into many binaries is slow).

// The MOI.Test-style conformance suite, instantiated for every compiled backend.
mod conformance;
// The external corpus (fixtures/highs-check, HiGHS's test instances): read, solve with every backend, compare.
mod corpus;
// Files we write, read back by HiGHS, CBC and SCIP through their own readers.
mod native_readers;
// The command-line tool, run as a subprocess.
mod cli;
// The network IP (paper §4) on small grids, the validator, spec errors.
mod network;
// Room tiling: floor plans and game levels (paper §5.2–5.3).
mod rooms;
// `netspec compare`: tables, summary arithmetic, resume.
mod compare;
// Designs without a solver: construction, local search, repair, stochastic search, MIP starts.
mod heuristics;
// Street layouts: cities, levels, resume, outputs (paper §5.1).
mod urban;
// Traffic evaluation in SUMO: real netconvert, duarouter and sumo.
mod traffic;
// The everyday solve loop: infeasibility found by netspec, honest optimality, time limits,
// interrupts, option errors, .gz files, solution files, raw parameters.
mod solve_loop;
// Fuzz targets: the MPS, LP and solution readers and the spec parser never panic.
mod fuzz;
// Infeasibility explained: minimal conflicting sets of a spec's requirements.
mod explain;
// `compare` and `city` on a real single-node Slurm cluster (scripts/slurm-local.sh).
mod slurm;
// `netspec serve`: its HTTP API, runs, and a real browser on its page.
mod serve;
// Game levels from a connectivity graph (Ma et al. 2014): configuration spaces, the exact model.
mod levels;
// Game levels on the graph families designers draw: paths, cycles, ladders, grids, trees.
mod level_families;
// A laid-out level exported as a mesh and a network spec, solved, crossings checked by geometry.
mod level_bridge;
// Road networks grown by traffic (Beneš et al. 2014) on small maps.
mod grow;
// Real sites from OpenStreetMap extracts, and their streets measured as OSMnx measures them.
mod site;
// One time limit per command; nothing found is lost (processes killed with SIGKILL).
mod promises;

/// Runs `scripts/setup.sh PART` once per test process (idempotent, about a second when done): the
/// tests that use SUMO or Chromium install them themselves, as `./dev demo` does not.
pub fn setup_part(part: &'static str) {
    use std::collections::BTreeMap;
    use std::sync::{Mutex, OnceLock};
    static DONE: OnceLock<Mutex<BTreeMap<&'static str, Result<(), String>>>> = OnceLock::new();
    let mut done = DONE.get_or_init(Default::default).lock().unwrap_or_else(|e| e.into_inner());
    let r = done.entry(part).or_insert_with(|| {
        let script = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/setup.sh");
        match std::process::Command::new("bash").arg(&script).arg(part).output() {
            Ok(o) if o.status.success() => Ok(()),
            Ok(o) => Err(format!("scripts/setup.sh {part} failed: {}", String::from_utf8_lossy(&o.stderr))),
            Err(e) => Err(format!("scripts/setup.sh {part} could not be run: {e}")),
        }
    });
    if let Err(e) = r {
        panic!("{e}");
    }
}
// Urban layouts by domain splitting (Yang et al. 2013): validity, seeds, GeoJSON sites, errors.
mod layout;
