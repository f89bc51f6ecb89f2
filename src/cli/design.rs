//! `netspec solve SPEC`: the design command.

use crate::SolveArgs;
use anyhow::{Context, Result};
use indicatif::{ProgressBar, ProgressStyle};
use netspec::explain::{ExplainOptions, Explanation};
use netspec::heuristics::run::Method;
use netspec::pipeline::{self, DesignResult};
use netspec::render::{self, Caption};
use netspec::solvers::SolverKind;
use netspec::solvers::{InvalidOption, LimitKind, SolveOptions, Termination};
use netspec::spec::{RecipeName, Spec};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

/// Exit code when the design fails an independent check.
const EXIT_INVALID: u8 = 3;

/// Where `solve`'s MIP start comes from.
pub enum StartArg {
    /// `--no-start`.
    Nothing,
    /// The default: the construction heuristic.
    Heuristic,
    /// `--start FILE`: a `result.json` or a `.sol` file.
    File(PathBuf),
}

/// Reads `--start FILE`: the network of an earlier `result.json` (its mesh must be this spec's),
/// or a `.sol` point of this model, decoded.
fn start_design(
    file: &Path,
    problem: &netspec::spec::Problem,
    nm: &netspec::formulations::Formulation,
) -> Result<netspec::design::Network> {
    let is_sol = file.extension().is_some_and(|e| e.eq_ignore_ascii_case("sol"));
    if is_sol {
        let sol = netspec::io::sol::read(&nm.model, file)?;
        return Ok(nm.decode(problem, &sol.values));
    }
    #[derive(serde::Deserialize)]
    struct View {
        schema: Option<String>,
        network: Option<netspec::design::Network>,
    }
    let text = std::fs::read_to_string(file).with_context(|| format!("reading the start {}", file.display()))?;
    let view: View =
        serde_json::from_str(&text).with_context(|| format!("{}: not a netspec result.json", file.display()))?;
    if view.schema.as_deref() != Some("netspec.design") {
        anyhow::bail!("{}: not a netspec result.json (no `\"schema\": \"netspec.design\"`)", file.display());
    }
    let net =
        view.network.with_context(|| format!("{}: the result has no network (`network` is null)", file.display()))?;
    if net.active.len() != problem.mesh.num_edges() {
        anyhow::bail!(
            "{}: the start's network has {} edges, this spec's mesh {} — is it a result of another spec?",
            file.display(),
            net.active.len(),
            problem.mesh.num_edges()
        );
    }
    Ok(net)
}

/// `explain`: the time budget for explaining an infeasible spec (`None`: do not explain).
#[allow(clippy::too_many_arguments)]
pub fn solve_spec(
    path: &Path,
    args: &SolveArgs,
    out: Option<PathBuf>,
    export: Option<PathBuf>,
    no_solve: bool,
    formulation: Option<RecipeName>,
    relax: bool,
    explain: Option<f64>,
    start: StartArg,
) -> Result<ExitCode> {
    let mut spec = Spec::load(path)?;
    if let Some(r) = formulation {
        spec.formulation = r.into();
    }
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
    if let Some(order) = nm.symmetry_order {
        println!("symmetry   the problem maps onto itself under {order} rotations and reflections: connectivity from the distance flow alone (no cutsets), HiGHS presolve off, so HiGHS can use the symmetry (`symmetric_flow = false` in [formulation] turns this off)");
    }
    if let Some(ps) = &nm.path_sets {
        let truncated = ps.pairs.iter().filter(|p| p.truncated).count();
        println!(
            "paths      {} pairs, {} paths enumerated in {:.3} s ({truncated} pairs truncated)",
            ps.pairs.len(),
            ps.total_paths,
            ps.seconds
        );
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
    if relax {
        let kind = args.solver()?;
        let solver = kind.instance()?;
        let mut sep = nm.separator();
        let b = netspec::solvers::lazy::lp_bound(
            solver.as_ref(),
            &nm.model,
            sep.as_mut().map(|s| s as &mut dyn netspec::solvers::Separator),
            &args.options()?,
        )?;
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
        println!(
            "LP bound   {} as written, {} after {} cut rounds ({} rows), {:.2} s with {kind}",
            f(b.plain),
            f(b.with_cuts),
            b.rounds,
            b.rows,
            b.seconds
        );
        if let (Some(sol), Some(x)) = (&args.sol, &b.point) {
            let header = format!("LP relaxation after {} cut rounds ({kind})", b.rounds);
            netspec::io::sol::write(&nm.model, x, b.with_cuts, &header, sol)?;
            println!("LP point   {}", sol.display());
        }
    }
    if no_solve {
        return Ok(ExitCode::SUCCESS);
    }
    // Command line over spec over default.
    let kind = match (args.solver, spec.solver.name) {
        (Some(Method::Search(m)), _) => {
            return crate::cli::search::solve_search(&problem, &nm, m, args, spec.solver.time_limit, out)
        }
        (Some(Method::Milp(k)), _) | (None, Some(k)) => k,
        (None, None) => SolverKind::default_kind().context("no backend compiled in")?,
    };
    check_spec_options(path, &spec)?;
    let mut options = args.options()?;
    options.time_limit = options.time_limit.or(spec.solver.time_limit);
    options.rel_gap = options.rel_gap.or(spec.solver.gap);
    options.abs_gap = options.abs_gap.or(spec.solver.abs_gap);
    options.node_limit = options.node_limit.or(spec.solver.node_limit);
    options.threads = options.threads.or(spec.solver.threads);
    options.seed = options.seed.or(spec.solver.seed);
    options.interrupt = Some(crate::cli::interrupt::install()?);

    let from = match start {
        StartArg::Nothing => pipeline::StartFrom::Nothing,
        StartArg::Heuristic => pipeline::default_start(options.finite_time_limit()),
        StartArg::File(file) => pipeline::StartFrom::Design {
            network: start_design(&file, &problem, &nm)?,
            source: file.display().to_string(),
        },
    };
    // Prepare the start first, so the progress line can show it while the solver runs.
    let from = match kind.instance()?.capabilities().mip_start {
        true => match pipeline::start_for(&problem, &nm, &from, options.seed.unwrap_or(0), options.heuristic_threads())
        {
            Some((point, report)) => pipeline::StartFrom::Prepared { point, report },
            None => from,
        },
        false => from,
    };
    let start_note = match &from {
        pipeline::StartFrom::Prepared { report, .. } => {
            let obj = report.objective.map_or("-".to_string(), |o| format!("{o:.4}"));
            format!("start {obj}{}", if report.accepted { "" } else { " (refused)" })
        }
        _ => "no start".to_string(),
    };
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} solving with {prefix} {elapsed} {msg}").expect("static template"),
    );
    bar.set_prefix(format!("{kind}{}", options.time_limit.map_or(String::new(), |t| format!(" (limit {t} s)"))));
    bar.enable_steady_tick(Duration::from_millis(200));
    bar.set_message(start_note.clone());
    if kind.instance()?.capabilities().reports_progress {
        let b = bar.clone();
        options.progress =
            Some(netspec::solvers::ProgressSink(std::sync::Arc::new(move |p: netspec::solvers::Progress| {
                let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
                b.set_message(format!("{start_note}, incumbent {} bound {} nodes {}", f(p.primal), f(p.dual), p.nodes));
            })));
    }
    let res = pipeline::solve_from(&problem, &nm, kind, &options, &from);
    bar.finish_and_clear();
    let res = res?;
    print_summary(&res);
    if let (Some(sol), Some(x)) = (&args.sol, &res.primal_point) {
        let header = format!("{} {}, {}", res.solve.solver, res.solve.solver_version, res.solve.termination.label());
        netspec::io::sol::write(&nm.model, x, res.solve.objective, &header, sol)?;
        println!("solution   {}", sol.display());
    }
    let explanation = match explain {
        Some(budget) if res.solve.termination == Termination::Infeasible => {
            let bar = ProgressBar::new_spinner();
            bar.set_style(
                ProgressStyle::with_template("{spinner} explaining: which requirements conflict? {elapsed}")
                    .expect("static template"),
            );
            bar.enable_steady_tick(Duration::from_millis(200));
            let opts = ExplainOptions {
                time_budget: budget,
                check_time_limit: budget.min(5.0),
                threads: options.threads,
                known_infeasible: true,
                ..ExplainOptions::default()
            };
            let e = netspec::explain::explain(&problem, kind, &opts);
            bar.finish_and_clear();
            for (i, line) in e.lines().iter().enumerate() {
                println!("{}{line}", if i == 0 { "explain    " } else { "           " });
            }
            Some(e)
        }
        _ => None,
    };

    let dir = out.unwrap_or_else(|| PathBuf::from("out").join(&spec.name));
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    let json = dir.join("result.json");
    // result.json: the design result, plus `infeasibility` when the spec was explained.
    #[derive(serde::Serialize)]
    struct Written<'a> {
        #[serde(flatten)]
        result: &'a DesignResult,
        #[serde(skip_serializing_if = "Option::is_none")]
        infeasibility: Option<&'a Explanation>,
    }
    let written = Written { result: &res, infeasibility: explanation.as_ref() };
    std::fs::write(&json, serde_json::to_string_pretty(&written)? + "\n")
        .with_context(|| format!("writing {}", json.display()))?;
    let caption = Caption {
        name: if spec.description.is_empty() {
            spec.name.clone()
        } else {
            format!("{} — {}", spec.name, spec.description)
        },
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
        let geo = dir.join("network.geojson");
        std::fs::write(
            &geo,
            netspec::traffic::export::design_geojson(&res, netspec::traffic::network::DEFAULT_SOLVE_LEVEL),
        )
        .with_context(|| format!("writing {}", geo.display()))?;
        println!("geojson    {} (WGS 84, one model unit a metre from the default origin)", geo.display());
    } else if let Some(e) = explanation.as_ref().filter(|e| !e.conflicts.is_empty()) {
        let svg = render::network::conflict_svg(&problem, e, &caption);
        let svg_path = dir.join("network.svg");
        std::fs::write(&svg_path, &svg).with_context(|| format!("writing {}", svg_path.display()))?;
        let png_path = dir.join("network.png");
        std::fs::write(&png_path, render::png(&svg)?).with_context(|| format!("writing {}", png_path.display()))?;
        println!("picture    {} (and .svg): the conflicting requirements", png_path.display());
    }
    if let Some(g) = res.rooms.as_ref().and_then(|r| r.block_graph.as_ref()) {
        let dot = dir.join("blocks.dot");
        std::fs::write(&dot, g.to_dot(&spec.name)).with_context(|| format!("writing {}", dot.display()))?;
        println!("blocks     {} blocks, {} links: {:?} ({})", g.nodes.len(), g.edges.len(), g.shape, dot.display());
    }
    println!("result     {}", json.display());
    Ok(if res.network.is_some() && !res.validity.valid {
        ExitCode::from(EXIT_INVALID)
    } else if res.solve.termination == Termination::Limit(LimitKind::Interrupt) {
        ExitCode::from(crate::cli::interrupt::EXIT_INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

/// Checks the spec's `[solver]` values, naming the field (`solver.gap`) and the file.
fn check_spec_options(path: &Path, spec: &Spec) -> Result<()> {
    let s = &spec.solver;
    let o = SolveOptions {
        time_limit: s.time_limit,
        rel_gap: s.gap,
        abs_gap: s.abs_gap,
        threads: s.threads,
        ..Default::default()
    };
    o.validate().map_err(|e: InvalidOption| {
        let field = match e.option {
            "rel_gap" => "gap",
            other => other,
        };
        anyhow::anyhow!("{}: solver.{field} {}", path.display(), e.reason)
    })
}

/// Why the solver stopped and whether a design exists: `optimal, design found (47 edges)`,
/// `limit(time), design found (47 edges, gap 12 %)`, `limit(time), no design`.
fn status_line(r: &DesignResult) -> String {
    let s = &r.solve;
    if let (Termination::Infeasible, Some(why)) = (&s.termination, &s.infeasibility) {
        return format!("infeasible (found by netspec before solving): {why}");
    }
    let design = match &r.metrics {
        Some(m) => {
            let gap = match (&s.termination, s.gap) {
                (Termination::Optimal, _) | (_, None) => String::new(),
                (_, Some(g)) => format!(", gap {}", netspec::solvers::percent(g)),
            };
            format!("design found ({} edges{gap})", m.edges)
        }
        None => "no design".to_string(),
    };
    format!("{}, {design}", s.termination)
}

fn verdict(r: &DesignResult) -> String {
    verdict_line(r.network.is_some(), &r.validity, "no network")
}

/// The `validity` line: `none` without a design, else valid or how many violations.
pub(crate) fn verdict_line(has_design: bool, v: &pipeline::Validity, none: &str) -> String {
    match (has_design, v.valid) {
        (false, _) => none.into(),
        (true, true) => "valid".into(),
        (true, false) => {
            let n = v.design_violations.len() + v.milp_check.as_ref().map_or(0, |c| c.violations.len());
            format!("INVALID ({n} violations)")
        }
    }
}

fn print_summary(r: &DesignResult) {
    let s = &r.solve;
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    println!("solver     {} {}", s.solver, s.solver_version);
    println!("status     {}", status_line(r));
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
        println!(
            "travel     mean {:.3}, max {:.3} to the nearest sink; coverage slack {}",
            m.mean_travel, m.max_travel, m.coverage_slack
        );
    }
    if let Some(o) = &r.objective {
        println!(
            "design     objective {:.6} recomputed from the network: length {:.3}, distance term {:.3}, travel {:.3} (weights length {}, distance {}, travel {})",
            o.total, o.length, o.distance, o.travel, r.spec.weights.length.describe(), r.spec.weights.distance.describe(), r.spec.weights.travel.describe()
        );
    }
    if let Some(st) = &r.start {
        let obj = st.objective.map_or("-".to_string(), |o| format!("{o:.6}"));
        let secs = st.seconds.map_or(String::new(), |t| format!(" in {t:.2} s"));
        let verdict = match (&st.reason, st.accepted) {
            (Some(why), _) => format!("refused: {why}"),
            (None, true) if st.returned => {
                "accepted; the solver found nothing better, so it is the design returned".to_string()
            }
            (None, true) => "accepted".to_string(),
            (None, false) => "not used".to_string(),
        };
        println!("start      {} objective {obj}{secs}, {verdict}", st.source);
    }
    if let Some(l) = &r.lazy {
        println!(
            "lazy rows  {} by {:?}: {} rounds, {} rows added, {:.2} s separating{}",
            l.separator,
            l.mode,
            l.rounds,
            l.rows_added,
            l.separation_seconds,
            l.root_bounds.map_or(String::new(), |(a, b)| format!(
                "; root LP {a:.4} → {b:.4} in {} cut rounds{} ({} slack rows left out)",
                l.root_rounds,
                if l.warm_root_rounds { ", each from the last basis" } else { "" },
                l.root_rows_dropped
            ))
        );
    }
    if let Some(s) = &r.split {
        let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
        let phase2 = s.phase2.as_ref().map_or("did not run".to_string(), |p| {
            format!(
                "{}, objective {}, bound {}, {:.2} s",
                p.termination,
                num(p.objective),
                num(p.dual_bound),
                p.wall_time
            )
        });
        println!(
            "split      lattice {}: phase 1 (min the large terms) {}, {} ≥ bound {}, {:.2} s; phase 2 {phase2}",
            s.quantum,
            s.phase1.termination,
            num(s.phase1.objective),
            num(s.phase1.dual_bound),
            s.phase1.wall_time
        );
    }
    if let Some(l) = &r.lattice {
        let offset = if l.lattice.offset == 0.0 { String::new() } else { format!("{} + ", l.lattice.offset) };
        let bound = l
            .solver_bound
            .map_or("no bound to round".to_string(), |b| format!("the backend's bound {b:.6} rounded up to it"));
        println!("lattice    every design's objective is on {offset}{}·ℤ: {bound} (`objective_lattice = false` in [formulation] turns this off)", l.lattice.step);
    }
    if !r.solver_hints.is_empty() {
        println!("tuning     {} (the recipe's; `solver_tuning = false` / `parallel_search = false` / `symmetric_flow = false` in [formulation] or your own --param replaces it)", r.solver_hints.join(", "));
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
