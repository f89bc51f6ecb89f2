//! `netspec solve SPEC`: prints what [`netspec::run::solve_spec`] does as it goes.

use super::args::SolveArgs;
use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::pipeline::DesignResult;
use netspec::run::{Event, ExplainBudget, SolveRequest, StartChoice};
use netspec::solvers::{Progress, ProgressSink};
use netspec::spec::Variant;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// Exit code when the design fails an independent check.
const EXIT_INVALID: u8 = 3;

/// `netspec solve`'s arguments.
#[derive(clap::Args)]
pub struct SolveCmd {
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
    /// Default: the construction heuristic's design (a tenth of the time limit, ≤ 2 s of work;
    /// while it has no design, up to a fifth, ≤ 60 s; one search per solver thread).
    #[arg(long, value_name = "FILE", conflicts_with = "no_start")]
    start: Option<PathBuf>,
    /// Solve without a MIP start.
    #[arg(long)]
    no_start: bool,
    /// Refuse a mesh of more cells than this (default 250,000), before building it.
    #[arg(long, value_name = "CELLS")]
    max_cells: Option<usize>,
}

impl From<SolveCmd> for SolveRequest {
    fn from(a: SolveCmd) -> SolveRequest {
        let start = match (a.start, a.no_start) {
            (_, true) => StartChoice::Nothing,
            (Some(file), false) => StartChoice::File(file),
            (None, false) => StartChoice::Heuristic,
        };
        SolveRequest {
            spec: a.spec,
            variant: a.formulation,
            flags: a.solve.settings(),
            out: a.out,
            export: a.export,
            no_solve: a.no_solve,
            relax: a.relax,
            sol: a.solve.sol.clone(),
            explain: (!a.no_explain).then_some(a.explain_time.map_or(ExplainBudget::Remaining, ExplainBudget::Seconds)),
            start,
            interrupt: None,
            progress: None,
            max_cells: a.max_cells,
            incumbents: None,
        }
    }
}

impl SolveCmd {
    /// Solves the spec.
    pub fn run(self) -> Result<ExitCode> {
        solve(self.into())
    }
}

/// Runs `solve` and prints its events; the exit code says whether the design is valid.
pub fn solve(mut req: SolveRequest) -> Result<ExitCode> {
    req.interrupt = Some(crate::cli::interrupt::install()?);
    let bar = ProgressBar::new_spinner();
    bar.set_style(ProgressStyle::with_template("{spinner} {prefix} {elapsed} {msg}").expect("static template"));
    let line = bar.clone();
    req.progress = Some(ProgressSink(Arc::new(move |p: Progress| {
        let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
        line.set_message(format!("incumbent {} bound {} nodes {}", f(p.primal), f(p.dual), p.nodes));
    })));
    let solved = netspec::run::solve_spec(&req, &mut |e| print_event(&e, &bar));
    bar.finish_and_clear();
    let Some(design) = solved?.design else { return Ok(ExitCode::SUCCESS) };
    Ok(if design.is_invalid() {
        ExitCode::from(EXIT_INVALID)
    } else if design.interrupted() {
        ExitCode::from(crate::cli::interrupt::EXIT_INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

fn spin(bar: &ProgressBar, prefix: String, msg: String) {
    bar.set_prefix(prefix);
    bar.set_message(msg);
    bar.enable_steady_tick(Duration::from_millis(200));
}

fn print_event(e: &Event, bar: &ProgressBar) {
    match e {
        Event::Built { problem, formulation: nm, millis } => {
            let spec = &problem.spec;
            println!("spec       {} — {}", spec.name, spec.description);
            println!(
                "mesh       {} vertices, {} edges, {} faces; {} sinks",
                problem.mesh.num_vertices(),
                problem.mesh.num_edges(),
                problem.mesh.num_faces(),
                problem.is_sink.iter().filter(|&&s| s).count()
            );
            let big_m = nm.big_m.map_or(String::new(), |m| format!(", big-M {m:.1}"));
            println!(
                "model      {} — formulation {} (built in {millis:.1} ms{big_m})",
                nm.model.stats(),
                nm.recipe.label
            );
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
        }
        Event::LimitExtended { what, seconds, limit } => println!(
            "limit      --{what}-time {seconds} s: if the spec is infeasible, explaining it may run past the {limit} s time limit by up to {seconds} s"
        ),
        Event::Exported { path, .. } => println!("exported   {}", path.display()),
        Event::Relaxed { kind, bound: b } => {
            let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
            println!(
                "LP bound   {} as written, {} after {} cut rounds ({} rows), {:.2} s with {kind}",
                f(b.plain),
                f(b.with_cuts),
                b.rounds,
                b.rows,
                b.seconds
            );
        }
        Event::SearchStarted { method, limit, seed, threads, asked } => {
            let note = match (threads, asked) {
                (1, 1) => "one thread".to_string(),
                (1, _) => format!(
                    "one thread: the {} search does not run in parallel, --threads {asked} not honoured",
                    method.name()
                ),
                (t, _) => format!("{t} independent searches, one per thread"),
            };
            println!("search     {} (limit {limit} s, seed {seed}, {note})", method.name());
            spin(bar, format!("searching with {}", method.name()), String::new());
        }
        Event::SolveStarted { kind, time_limit, start } => {
            let note = match start {
                Some(r) => {
                    let obj = r.objective.map_or("-".to_string(), |o| format!("{o:.4}"));
                    format!("start {obj}{}", if r.accepted { "" } else { " (refused)" })
                }
                None => "no start".to_string(),
            };
            let limit = time_limit.map_or(String::new(), |t| format!(" (limit {t} s)"));
            spin(bar, format!("solving with {kind}{limit}"), note);
        }
        Event::Designed(d) => {
            bar.finish_and_clear();
            match d.solve.is_search() {
                true => print_search(d, &d.verdict("no design")),
                false => print_milp(d, &d.verdict("no network")),
            }
        }
        Event::Explaining => spin(bar, "explaining: which requirements conflict?".into(), String::new()),
        Event::Explained(x) => {
            bar.finish_and_clear();
            for (i, line) in x.lines().iter().enumerate() {
                println!("{}{line}", if i == 0 { "explain    " } else { "           " });
            }
        }
        Event::Wrote { what, path } => match *what {
            "picture" => println!("picture    {} (and .svg)", path.display()),
            "geojson" => {
                println!("geojson    {} (WGS 84, one model unit a metre from the default origin)", path.display())
            }
            "blocks" => println!("blocks     {}", path.display()),
            "solution" => println!("solution   {}", path.display()),
            other => println!("{other:<10} {}", path.display()),
        },
    }
}

fn print_milp(r: &DesignResult, verdict: &str) {
    let s = &r.solve;
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    println!("solver     {} {}", s.solver, s.solver_version);
    for w in &s.warnings {
        println!("warning    {w}");
    }
    println!("status     {}", netspec::run::milp_status_line(r));
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
        println!("lattice    every design's objective is on {offset}{}·ℤ: {bound} (`objective_lattice = false` in [solver] turns this off)", l.lattice.step);
    }
    if !r.solver_hints.is_empty() {
        println!("tuning     {} (the solve strategy's; `solver_tuning = false` / `parallel_search = false` in [solver], `symmetric_flow = false` in [formulation], or your own --param replaces it)", r.solver_hints.join(", "));
    }
    println!("validity   {verdict}");
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

fn print_search(r: &DesignResult, verdict: &str) {
    let s = &r.solve;
    let num = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6}"));
    println!("status     {}", netspec::run::search_status_line(r));
    let details = s.search.as_ref();
    if let Some(why) = details.and_then(|d| d.infeasible_because.as_ref()) {
        println!("reason     {why}");
    }
    println!("objective  {}", num(s.objective));
    println!(
        "time       {:.2} s search, {:.2} s wall; first design at {}",
        s.solver_time.unwrap_or(0.0),
        s.wall_time,
        details.and_then(|d| d.first_design_seconds).map_or("-".into(), |t| format!("{t:.3} s"))
    );
    match details.map(|d| &d.stats) {
        Some(st) if st.passes > 0 => println!("passes     {} ({} operations performed)", st.passes, st.steps),
        Some(st) => println!(
            "search     {} constructions ({} valid), {} moves tried, {} kept, {} kicks",
            st.constructions, st.constructed, st.moves_tried, st.moves_accepted, st.kicks
        ),
        None => {}
    }
    if let Some(m) = &r.metrics {
        println!(
            "network    {} edges, length {:.2}, {} dead-ends, {} 3-way + {} 4-way junctions, {} T, {} too-close, {} zig-zags",
            m.edges, m.length, m.dead_ends, m.junctions_3way, m.junctions_4way, m.t_junctions, m.too_close, m.zigzags
        );
    }
    println!("validity   {verdict}");
    for v in r.validity.design_violations.iter().take(10) {
        println!("  {v}");
    }
    if let Some(c) = &r.validity.milp_check {
        for v in c.violations.iter().take(10) {
            println!("  MILP: {v}");
        }
    }
}
