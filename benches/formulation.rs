//! Emitting the network MILP (every family on) for a 1,200-edge mesh — target: under
//! 20 ms — and, per Table 1 instance, building and exporting its MILP. Run with
//! `cargo bench --bench formulation`.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::spec::Spec;
use std::hint::black_box;
use std::path::Path;

/// A 24×24 grid has 1,200 edges (the paper's Fig. 5 level-3 size). Every family is on:
/// penalised zig-zags, too-close pairs and T-junctions, forbidden dead-ends and branches,
/// point-to-point with 4×4 blocks (at most 100 paths per pair: uncapped, tolerance-2 path sets
/// between 4×4 blocks of a 24×24 grid run to 23,000 paths and dominate), the paper variant
/// (ν dead-end rows).
const SPEC: &str = r#"
name = "bench1200"
boundary = "wall"
formulation = "paper"
[mesh]
grid = { width = 24, height = 24 }
[sinks]
all_boundary = true
[weights]
length = 1
distance = 1
zigzag = 5
too_close = 2
t_junction = 3
[features]
dead_ends = "forbid"
branches = "forbid"
[point_to_point]
blocks = 4
max_paths = 100
"#;

fn bench(c: &mut Criterion) {
    let problem = Spec::from_toml(SPEC).unwrap().resolve(Path::new(".")).unwrap();
    assert_eq!(problem.mesh.num_edges(), 1200);
    let nm = netspec::pipeline::build(&problem);
    eprintln!("1,200-edge model: {}", nm.model.stats());
    let mut g = c.benchmark_group("formulation");
    g.sample_size(20);
    g.bench_function("emit_1200_edges_all_families", |b| b.iter(|| black_box(netspec::pipeline::build(&problem))));
    g.finish();
}

/// Per Table 1 instance (`models/table1.toml`, the rows that exist): building the MILP from the
/// resolved spec, and exporting it as MPS and as LP to memory.
fn table1(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let manifest = netspec::compare::Manifest::load(&dir.join("table1.toml")).unwrap();
    let mut build = c.benchmark_group("table1_build");
    build.sample_size(10);
    let mut models = Vec::new();
    for row in &manifest.row {
        let Some(spec) = &row.spec else { continue };
        let problem = Spec::load(spec).unwrap().resolve(spec.parent().unwrap_or(&dir)).unwrap();
        build.bench_function(&row.name, |b| b.iter(|| black_box(netspec::pipeline::build(&problem))));
        models.push((row.name.clone(), netspec::pipeline::build(&problem).model));
    }
    build.finish();
    let mut export = c.benchmark_group("table1_export");
    export.sample_size(10);
    for (name, model) in &models {
        export.bench_function(format!("{name}/mps"), |b| {
            b.iter(|| {
                let mut buf = Vec::with_capacity(1 << 22);
                netspec::io::mps::write(model, &mut buf, &Default::default()).unwrap();
                buf
            })
        });
        export.bench_function(format!("{name}/lp"), |b| {
            b.iter(|| {
                let mut buf = Vec::with_capacity(1 << 22);
                netspec::io::lp::write(model, &mut buf, &Default::default()).unwrap();
                buf
            })
        });
    }
    export.finish();
}

criterion_group!(benches, bench, table1);
criterion_main!(benches);
