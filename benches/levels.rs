//! Configuration-space construction (every ordered pair of block shapes) for the rectangle set
//! of `models/levels/fig1.toml` and the rectangle-and-L set of `models/levels/fig7-bottom.toml`,
//! beside a peer in the same run: the validator on a two-block layout. Run with
//! `cargo bench --bench levels`.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::levels::cspace::CSpaces;
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

criterion_group!(benches, cspaces);
criterion_main!(benches);
