//! Per-backend overhead: netspec's whole `Solver::solve` call (validation, translation into the
//! native solver, the solve, reading the result back, freeing the native model) against the
//! solver's own reported run time (`SolveResult::solver_time`), on the same models.
//!
//! Target: overhead (total − solver time) under 5 % of the total, or under 10 ms.
//!
//! Criterion measures the total call; every call's total and solver time are also collected and
//! printed as a table at the end, with a breakdown of where the overhead goes (see
//! `docs/benchmarks.md`, "Per-backend overhead"). CBC reports no run time of its own: its solver
//! time is netspec's measurement of the native `Cbc_solve` call, so its "overhead" is everything
//! around that call.
//!
//! Run with `cargo bench --bench overhead`. Under `cargo test` (no `--bench` argument) every
//! benchmark runs once, as a smoke test.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::milp::{Model, Sense, VarId};
use netspec::solvers::{SolveOptions, SolverKind};
use netspec::spec::Spec;
use std::cell::RefCell;
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

/// A deterministic xorshift stream.
fn rng(seed: u64) -> impl FnMut() -> u64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    }
}

/// A multi-dimensional 0-1 knapsack: 30 items, 3 capacity rows at about 40 % of the weights.
fn knapsack() -> Model {
    let mut next = rng(0x9E3779B97F4A7C15);
    let mut m = Model::new("knapsack");
    m.sense = Sense::Maximize;
    let n = 30;
    let x: Vec<VarId> = (0..n).map(|j| m.add_binary(format!("x{j}"), (10 + next() % 90) as f64)).collect();
    for k in 0..3 {
        let w: Vec<f64> = (0..n).map(|_| (5 + next() % 45) as f64).collect();
        let cap = (w.iter().sum::<f64>() * 0.4).floor();
        m.add_le(format!("cap{k}"), x.iter().zip(&w).map(|(&v, &a)| (v, a)), cap);
    }
    m
}

/// A min-cost flow LP on a 40×40 grid (arcs both ways, capacity 30): 1,600 conservation rows,
/// 6,240 arc variables, 12,480 nonzeros; 8 sources and 8 sinks of 20 units each.
fn flow_lp() -> Model {
    const N: usize = 40;
    let mut next = rng(0x2545F4914F6CDD1D);
    let mut m = Model::new("flow_lp");
    let node = |r: usize, c: usize| r * N + c;
    let mut out: Vec<Vec<VarId>> = vec![Vec::new(); N * N];
    let mut inc: Vec<Vec<VarId>> = vec![Vec::new(); N * N];
    for r in 0..N {
        for c in 0..N {
            let mut arc = |a: usize, b: usize, m: &mut Model| {
                let v = m.add_continuous(format!("f_{a}_{b}"), 0.0, 30.0, (1 + next() % 20) as f64);
                out[a].push(v);
                inc[b].push(v);
            };
            if c + 1 < N {
                arc(node(r, c), node(r, c + 1), &mut m);
                arc(node(r, c + 1), node(r, c), &mut m);
            }
            if r + 1 < N {
                arc(node(r, c), node(r + 1, c), &mut m);
                arc(node(r + 1, c), node(r, c), &mut m);
            }
        }
    }
    let mut supply = vec![0.0; N * N];
    for k in 0..8 {
        supply[node(2 + 4 * k, 1)] = 20.0;
        supply[node(3 + 4 * k, N - 2)] = -20.0;
    }
    for i in 0..N * N {
        let terms = out[i].iter().map(|&v| (v, 1.0)).chain(inc[i].iter().map(|&v| (v, -1.0)));
        m.add_eq(format!("bal_{i}"), terms, supply[i]);
    }
    m
}

/// The network IP (paper §4, tight formulation) on a 4×4 grid with every boundary vertex a sink
/// (the `tiny_network` of the compare tests): 249 variables, 331 rows.
fn network() -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/specs/tiny_network.toml");
    let problem = Spec::load(&path).unwrap().resolve(Path::new(".")).unwrap();
    netspec::pipeline::build(&problem).model
}

/// Quiet, one thread where the backend takes a thread count (microlp has none).
fn options(kind: SolverKind) -> SolveOptions {
    let caps = kind.instance().unwrap().capabilities();
    SolveOptions { threads: caps.threads.then_some(1), ..Default::default() }
}

/// One row of the table: every call's (total, solver time) in seconds.
struct Row {
    backend: &'static str,
    model: &'static str,
    calls: Vec<(f64, f64)>,
}

fn bench(c: &mut Criterion) {
    let models = [("knapsack", knapsack()), ("flow_lp", flow_lp()), ("network", network())];
    let kinds: Vec<SolverKind> = SolverKind::compiled().into_iter().filter(|k| *k != SolverKind::GoodLp).collect();
    let rows: RefCell<Vec<Row>> = RefCell::new(Vec::new());
    for (name, model) in &models {
        let mut g = c.benchmark_group(format!("overhead/{name}"));
        g.sample_size(10).warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_secs(2));
        for &kind in &kinds {
            let solver = kind.instance().unwrap();
            let o = options(kind);
            let mut calls = Vec::new();
            g.bench_function(kind.name(), |b| {
                b.iter_custom(|iters| {
                    let mut sum = Duration::ZERO;
                    for _ in 0..iters {
                        let t0 = Instant::now();
                        let r = solver.solve(black_box(model), &o).unwrap();
                        let total = t0.elapsed();
                        sum += total;
                        assert_eq!(r.termination, netspec::solvers::Termination::Optimal, "{kind} on {name}");
                        calls.push((total.as_secs_f64(), r.solver_time.expect("solver time")));
                    }
                    sum
                })
            });
            rows.borrow_mut().push(Row { backend: kind.name(), model: name, calls });
        }
        g.finish();
    }
    print_table(&rows.into_inner(), &models);
    if std::env::args().any(|a| a == "--bench") {
        breakdown(&models);
    }
}

/// Mean milliseconds of `f` over `n` calls.
fn mean_ms(n: u32, mut f: impl FnMut()) -> f64 {
    let t0 = Instant::now();
    for _ in 0..n {
        f();
    }
    t0.elapsed().as_secs_f64() * 1e3 / n as f64
}

/// Where the overhead goes, in the parts that can be timed from outside the backends: netspec's
/// own work common to every backend (the preflight's `Model::validate`; the CSC copy that the
/// HiGHS and CBC backends load from), and SCIP's fixed cost per solve (creating an instance
/// with the default plugins, and freeing it), which its `solving_time` does not include.
fn breakdown(models: &[(&str, Model)]) {
    println!("\nParts of the overhead (mean of 20 calls):\n\n| model | Model::validate ms | Model::to_csc ms |\n|---|---|---|");
    for (name, m) in models {
        let v = mean_ms(20, || {
            black_box(m.validate()).unwrap();
        });
        let c = mean_ms(20, || {
            black_box(m.to_csc());
        });
        println!("| {name} | {v:.3} | {c:.3} |");
    }
    #[cfg(feature = "scip")]
    {
        let mut free = 0.0;
        let create = mean_ms(20, || {
            let m = russcip::Model::try_new().unwrap().include_default_plugins().create_prob("empty");
            let t = Instant::now();
            drop(black_box(m));
            free += t.elapsed().as_secs_f64() * 1e3 / 20.0;
        }) - free;
        println!("\nSCIP, per solve and outside its solving time: SCIPcreate + default plugins + empty problem {create:.2} ms, SCIPfree of that empty instance {free:.2} ms.");
    }
}

fn print_table(rows: &[Row], models: &[(&str, Model)]) {
    let smoke = !std::env::args().any(|a| a == "--bench");
    println!(
        "\nPer-backend overhead{} (mean over every call, warm-up included)",
        if smoke { " — smoke run, one call each" } else { "" }
    );
    for (name, m) in models {
        println!("  {name}: {}", m.stats());
    }
    println!("\n| backend | model | calls | mean total ms | mean solver ms | overhead ms | overhead % | target met (< 5 % or < 10 ms) |");
    println!("|---|---|---|---|---|---|---|---|");
    for r in rows {
        let n = r.calls.len().max(1) as f64;
        let total = r.calls.iter().map(|c| c.0).sum::<f64>() / n * 1e3;
        let solver = r.calls.iter().map(|c| c.1).sum::<f64>() / n * 1e3;
        let over = total - solver;
        let pct = if total > 0.0 { over / total * 100.0 } else { 0.0 };
        let met = pct < 5.0 || over < 10.0;
        let note = if r.backend == "cbc" { " (CBC: solver time is netspec's timing of Cbc_solve)" } else { "" };
        println!(
            "| {} | {} | {} | {total:.2} | {solver:.2} | {over:.2} | {pct:.1} % | {}{note} |",
            r.backend,
            r.model,
            r.calls.len(),
            if met { "yes" } else { "no" }
        );
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
