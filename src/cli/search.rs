//! `netspec solve SPEC --solver heuristic|anneal`: a design search instead of a MILP backend,
//! with the same outputs (result.json, network.svg/png) and checks.

use crate::SolveArgs;
use anyhow::{bail, Context, Result};
use netspec::formulations::Formulation;
use netspec::heuristics::run::{run_search, SearchMethod, SearchResult};
use netspec::render::{self, Caption};
use netspec::spec::Problem;
use std::path::PathBuf;
use std::process::ExitCode;

/// Exit code when the design fails an independent check.
const EXIT_INVALID: u8 = 3;

/// Default time limits, seconds.
const HEURISTIC_SECONDS: f64 = 10.0;
const ANNEAL_SECONDS: f64 = 60.0;

pub fn solve_search(
    problem: &Problem,
    nm: &Formulation,
    method: SearchMethod,
    args: &SolveArgs,
    spec_limit: Option<f64>,
    out: Option<PathBuf>,
) -> Result<ExitCode> {
    for (set, name) in [
        (args.gap.is_some(), "--gap"),
        (args.abs_gap.is_some(), "--abs-gap"),
        (args.node_limit.is_some(), "--node-limit"),
    ] {
        if set {
            bail!("option `{name}` is not supported by the {} search: it has no bound and no nodes", method.name());
        }
    }
    let limit = args.time_limit.or(spec_limit).unwrap_or(match method {
        SearchMethod::Heuristic => HEURISTIC_SECONDS,
        SearchMethod::Anneal => ANNEAL_SECONDS,
    });
    let seed = args.seed.unwrap_or(0);
    if args.threads == Some(0) {
        bail!("--threads must be ≥ 1, got 0");
    }
    let asked = args.threads.unwrap_or(1) as usize;
    let threads = match method {
        SearchMethod::Heuristic => asked,
        SearchMethod::Anneal => 1,
    };
    let thread_note = match (threads, asked) {
        (1, 1) => "one thread".to_string(),
        (1, _) => {
            format!("one thread: the {} search does not run in parallel, --threads {asked} not honoured", method.name())
        }
        (t, _) => format!("{t} independent searches, one per thread"),
    };
    println!("search     {} (limit {limit} s, seed {seed}, {thread_note})", method.name());
    let res = run_search(problem, nm, method, limit, seed, threads);
    print_summary(&res);
    let spec = &problem.spec;
    let dir = out.unwrap_or_else(|| PathBuf::from("out").join(&spec.name));
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let json = dir.join("result.json");
    std::fs::write(&json, serde_json::to_string_pretty(&res)? + "\n")
        .with_context(|| format!("writing {}", json.display()))?;
    if let Some(net) = &res.network {
        let caption = Caption {
            name: if spec.description.is_empty() {
                spec.name.clone()
            } else {
                format!("{} — {}", spec.name, spec.description)
            },
            solver: format!("netspec {} {}", method.name(), res.solve.solver_version),
            status: res.solve.termination.label(),
            objective: res.solve.objective,
            gap: None,
            verdict: verdict(&res),
        };
        let placements = nm.placements.as_ref().map(|r| r.placements.as_slice());
        let svg = render::svg(problem, net, nm.path_sets.as_ref(), placements, &caption);
        let svg_path = dir.join("network.svg");
        std::fs::write(&svg_path, &svg).with_context(|| format!("writing {}", svg_path.display()))?;
        let png_path = dir.join("network.png");
        std::fs::write(&png_path, render::png(&svg)?).with_context(|| format!("writing {}", png_path.display()))?;
        println!("picture    {} (and .svg)", png_path.display());
    }
    if let Some(g) = res.rooms.as_ref().and_then(|r| r.block_graph.as_ref()) {
        let dot = dir.join("blocks.dot");
        std::fs::write(&dot, g.to_dot(&spec.name)).with_context(|| format!("writing {}", dot.display()))?;
        println!("blocks     {} blocks, {} links: {:?} ({})", g.nodes.len(), g.edges.len(), g.shape, dot.display());
    }
    println!("result     {}", json.display());
    Ok(if res.network.is_some() && !res.validity.valid { ExitCode::from(EXIT_INVALID) } else { ExitCode::SUCCESS })
}

fn verdict(r: &SearchResult) -> String {
    crate::cli::design::verdict_line(r.network.is_some(), &r.validity, "no design")
}

fn print_summary(r: &SearchResult) {
    let s = &r.solve;
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    println!(
        "status     {}",
        if r.network.is_some() { s.termination.label() } else { format!("{} (no design)", s.termination.label()) }
    );
    if let Some(why) = &s.infeasible_because {
        println!("reason     {why}");
    }
    println!("objective  {}", num(s.objective));
    println!(
        "time       {:.2} s search, {:.2} s wall; first design at {}",
        s.solver_time.unwrap_or(0.0),
        s.wall_time,
        s.first_design_seconds.map_or("-".into(), |t| format!("{t:.3} s"))
    );
    let st = &s.stats;
    if st.passes > 0 {
        println!("passes     {} ({} operations performed)", st.passes, st.steps);
    } else {
        println!(
            "search     {} constructions ({} valid), {} moves tried, {} kept, {} kicks",
            st.constructions, st.constructed, st.moves_tried, st.moves_accepted, st.kicks
        );
    }
    if let Some(m) = &r.metrics {
        println!(
            "network    {} edges, length {:.2}, {} dead-ends, {} 3-way + {} 4-way junctions, {} T, {} too-close, {} zig-zags",
            m.edges, m.length, m.dead_ends, m.junctions_3way, m.junctions_4way, m.t_junctions, m.too_close, m.zigzags
        );
    }
    println!("validity   {}", verdict(r));
    for v in r.validity.design_violations.iter().take(10) {
        println!("  {v}");
    }
    if let Some(c) = &r.validity.milp_check {
        for v in c.violations.iter().take(10) {
            println!("  MILP: {v}");
        }
    }
}
