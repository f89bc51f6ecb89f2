//! Configuration-space construction (every ordered pair of block shapes) for the rectangle set
//! of `models/levels/fig1.toml` and the rectangle-and-L set of `models/levels/fig7-bottom.toml`,
//! beside a peer in the same run: the validator on a two-block layout. Then the annealer's
//! first layout of the graph families a designer draws (unit squares, door width 0.5: a path of
//! 1,000, a cycle of 200, a 2 × 50 ladder, a 10 × 10 grid graph, a caterpillar of 300, a
//! complete binary tree of 31), each beside the validator on the layout found. Run with
//! `cargo bench --bench levels`.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::levels::anneal::{anneal, AnnealOptions};
use netspec::levels::cspace::CSpaces;
use netspec::levels::generate::Generated;
use netspec::levels::spec::{Level, NodeId};
use netspec::levels::validate::validate;
use netspec::levels::{Layout, Placement};
use std::hint::black_box;
use std::path::Path;

fn load(name: &str) -> Level {
    Level::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/levels").join(name)).unwrap()
}

fn cspaces(c: &mut Criterion) {
    for name in ["fig1.toml", "fig7-bottom.toml"] {
        let level = load(name);
        c.bench_function(&format!("cspaces {name} ({} blocks)", level.blocks.len()), |b| {
            b.iter(|| CSpaces::new(black_box(&level)))
        });
    }
    let level = load("fig1.toml");
    let b0 = level.nodes[0].blocks[0];
    let layout = Layout {
        nodes: (0..level.nodes.len() as u32).map(|i| Placement::new(&level, NodeId(i), b0, [i as f64, 0.0])).collect(),
    };
    c.bench_function("peer: validate a 14-block row", |b| b.iter(|| validate(black_box(&level), black_box(&layout))));
}

fn families(c: &mut Criterion) {
    let mut g = c.benchmark_group("families");
    g.sample_size(10);
    for family in ["path:1000", "cycle:200", "ladder:50", "grid:10x10", "caterpillar:100x2", "tree:31"] {
        let level = Generated::parse(family).unwrap().level(0.5).unwrap();
        let cs = CSpaces::new(&level);
        let o = AnnealOptions { time_limit: 10.0, ..AnnealOptions::default() };
        let first = anneal(&level, &cs, &o);
        assert_eq!(first.layouts.len(), 1, "{family}: {}", first.stopped);
        g.bench_function(format!("anneal {family}"), |b| b.iter(|| anneal(black_box(&level), &cs, &o)));
        let layout = &first.layouts[0];
        g.bench_function(format!("peer: validate {family}"), |b| b.iter(|| validate(black_box(&level), layout)));
    }
    g.finish();
}

criterion_group!(benches, cspaces, families);
criterion_main!(benches);
