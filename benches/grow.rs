//! `netspec grow` on the 8 × 8 km river map at 20 m (`models/grow/river.toml`, r = 8: 160,801
//! lattice vertices, 176 directions): the initial network (§3.2: terrain, city pairs, the
//! lattice shortest paths with reuse, nuclei) and one time step (step 31 of the same map: minor
//! growth, traffic and major roads for every pair, the built-up area). Run with
//! `cargo bench --bench grow`.

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use netspec::grow::context::Context;
use netspec::grow::step::Sim;
use std::hint::black_box;
use std::path::Path;

fn river(c: &mut Criterion) {
    let ctx = Context::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/grow/river.toml")).unwrap();
    let mut g = c.benchmark_group("grow");
    g.sample_size(10);
    g.bench_function("river 8 km at 20 m: initial network", |b| {
        b.iter(|| Sim::new(black_box(&ctx), ctx.seed).unwrap())
    });
    let mut sim = Sim::new(&ctx, ctx.seed).unwrap();
    for _ in 0..30 {
        sim.step();
    }
    g.bench_function("river 8 km at 20 m: step 31", |b| {
        b.iter_batched(|| sim.clone(), |mut s| s.step(), BatchSize::LargeInput)
    });
    g.finish();
}

criterion_group!(benches, river);
criterion_main!(benches);
