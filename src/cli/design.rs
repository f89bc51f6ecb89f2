//! `netspec solve SPEC`: the design command.

use crate::SolveArgs;
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use netspec::heuristics::run::Method;
use netspec::pipeline::{self, DesignResult};
use netspec::render::{self, Caption};
use netspec::solvers::SolverKind;
use netspec::spec::Spec;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

/// Exit code when the design fails an independent check.
const EXIT_INVALID: u8 = 3;

pub fn solve_spec(path: &Path, args: &SolveArgs, out: Option<PathBuf>, export: Option<PathBuf>, no_solve: bool) -> Result<ExitCode> {
    let spec = Spec::load(path)?;
    let base = path.parent().unwrap_or(Path::new("."));
    let problem = spec.resolve(base).map_err(|kind| netspec::spec::SpecError { path: path.to_path_buf(), kind })?;
    let t0 = std::time::Instant::now();
    let nm = pipeline::build(&problem);
    let build_ms = t0.elapsed().as_secs_f64() * 1e3;
    println!("spec       {} — {}", spec.name, spec.description);
    println!(
        "mesh       {} vertices, {} edges, {} faces; {} sinks",
        problem.mesh.num_vertices(),
        problem.mesh.num_edges(),
        problem.mesh.num_faces(),
        problem.is_sink.iter().filter(|&&s| s).count()
    );
    let big_m = nm.big_m.map_or(String::new(), |m| format!(", big-M {m:.1}"));
    println!("model      {} — formulation {} (built in {build_ms:.1} ms{big_m})", nm.model.stats(), nm.recipe.label);
    for (family, st) in &nm.families {
        println!("  {family:<24} {:>7} vars {:>7} rows {:>8} nonzeros", st.vars, st.rows, st.nonzeros);
    }
    if let Some(ps) = &nm.path_sets {
        let truncated = ps.pairs.iter().filter(|p| p.truncated).count();
        println!("paths      {} pairs, {} paths enumerated in {:.3} s ({truncated} pairs truncated)", ps.pairs.len(), ps.total_paths, ps.seconds);
    }
    if let Some(file) = &export {
        if nm.is_complete() {
            // No comment: the `paper` recipe's files stay byte for byte what they always were.
            netspec::io::write_model_file(&nm.model, file)?;
        } else {
            // Lazily separated rows cannot be written out: write the same recipe with them in
            // their compact form, and say so.
            let compact = netspec::formulations::build_compact(&problem);
            let note = format!(
                "netspec formulation: {} — written complete: its lazily separated cutset rows are\nreplaced by the equivalent single-commodity flow ({}); same optimum.",
                nm.recipe.label, compact.recipe.label
            );
            netspec::io::write_model_file_with_comments(&compact.model, file, &[note])?;
        }
        println!("exported   {}", file.display());
    }
    if no_solve {
        return Ok(ExitCode::SUCCESS);
    }
    // Command line over spec over default.
    let kind = match (args.solver, spec.solver.name) {
        (Some(Method::Search(m)), _) => return crate::cli::search::solve_search(&problem, &nm, m, args, spec.solver.time_limit, out),
        (Some(Method::Milp(k)), _) | (None, Some(k)) => k,
        (None, None) => SolverKind::default_kind().context("no backend compiled in")?,
    };
    let mut options = args.options();
    options.time_limit = options.time_limit.or(spec.solver.time_limit);
    options.rel_gap = options.rel_gap.or(spec.solver.gap);
    options.abs_gap = options.abs_gap.or(spec.solver.abs_gap);
    options.node_limit = options.node_limit.or(spec.solver.node_limit);
    options.threads = options.threads.or(spec.solver.threads);
    options.seed = options.seed.or(spec.solver.seed);

    let bar = ProgressBar::new_spinner();
    bar.set_style(ProgressStyle::with_template("{spinner} solving with {prefix} {elapsed} {msg}").expect("static template"));
    bar.set_prefix(format!("{kind}{}", options.time_limit.map_or(String::new(), |t| format!(" (limit {t} s)"))));
    bar.enable_steady_tick(Duration::from_millis(200));
    if kind.instance()?.capabilities().reports_progress {
        let b = bar.clone();
        options.progress = Some(netspec::solvers::ProgressSink(std::sync::Arc::new(move |p: netspec::solvers::Progress| {
            let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
            b.set_message(format!("incumbent {} bound {} nodes {}", f(p.primal), f(p.dual), p.nodes));
        })));
    }
    let res = pipeline::solve_built(&problem, &nm, kind, &options);
    bar.finish_and_clear();
    let res = res?;
    print_summary(&res);

    let dir = out.unwrap_or_else(|| PathBuf::from("out").join(&spec.name));
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let json = dir.join("result.json");
    std::fs::write(&json, serde_json::to_string_pretty(&res)? + "\n").with_context(|| format!("writing {}", json.display()))?;
    let caption = Caption {
        name: if spec.description.is_empty() { spec.name.clone() } else { format!("{} — {}", spec.name, spec.description) },
        solver: format!("{} {}", res.solve.solver, res.solve.solver_version),
        status: res.solve.termination.label(),
        objective: res.solve.objective,
        gap: res.solve.gap,
        verdict: verdict(&res),
    };
    if let Some(net) = &res.network {
        let placements = nm.placements.as_ref().map(|r| r.placements.as_slice());
        let svg = render::svg(&problem, net, nm.path_sets.as_ref(), placements, &caption);
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

fn verdict(r: &DesignResult) -> String {
    match (&r.network, r.validity.valid) {
        (None, _) => "no network".into(),
        (Some(_), true) => "valid".into(),
        (Some(_), false) => {
            let n = r.validity.design_violations.len() + r.validity.milp_check.as_ref().map_or(0, |c| c.violations.len());
            format!("INVALID ({n} violations)")
        }
    }
}

fn print_summary(r: &DesignResult) {
    let s = &r.solve;
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    println!("solver     {} {}", s.solver, s.solver_version);
    println!("status     {}", s.termination);
    println!("objective  {}", num(s.objective));
    println!("bound      {}", num(s.dual_bound));
    println!("gap        {}", s.gap.map_or("-".into(), |g| format!("{:.2}%", 100.0 * g)));
    println!(
        "time       {} solver, {:.2} s wall, {} nodes",
        s.solver_time.map_or("-".into(), |t| format!("{t:.2} s")),
        s.wall_time,
        s.nodes.map_or("-".into(), |n| n.to_string())
    );
    if let Some(m) = &r.metrics {
        println!(
            "network    {} edges, length {:.2}, {} dead-ends, {} 3-way + {} 4-way junctions, {} T, {} too-close, {} zig-zags",
            m.edges, m.length, m.dead_ends, m.junctions_3way, m.junctions_4way, m.t_junctions, m.too_close, m.zigzags
        );
        println!("travel     mean {:.3}, max {:.3} to the nearest sink; coverage slack {}", m.mean_travel, m.max_travel, m.coverage_slack);
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
    if r.validity.objective_agrees == Some(false) {
        println!("  objective recomputed from the design: {:?}", r.validity.objective_recomputed);
    }
}
