//! `netspec layout` on a square kilometre (`models/layout/km2.toml`, about 1,500 parcels; the
//! paper's Table 2 times regions of a few thousand parcels), beside a peer in the same run: the
//! blocks, parcels and metrics of the same streets, and the independent validator. Then Table
//! 2's stages one by one, each timed inside the pipeline (`iter_custom` with the stage's own
//! clock): the split with its template matching, the backtracking choice of templates, and the
//! global optimisation of 10 iterations. Run with `cargo bench --bench layout`.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::layout::field::FieldMethod;
use netspec::layout::metrics::metrics;
use netspec::layout::parcels::{blocks, parcellate, StreetIndex};
use netspec::layout::region::read_region;
use netspec::layout::run::{layout, LayoutOptions};
use netspec::layout::split::Selection;
use netspec::layout::validate::validate;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

fn km2(c: &mut Criterion) {
    let region = read_region(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/layout/km2.toml")).unwrap();
    let opts =
        LayoutOptions { field: FieldMethod::Distance, selection: Selection::Best, seed: region.seed, optimise: 0 };
    let mut g = c.benchmark_group("layout");
    g.sample_size(10);
    g.bench_function("km2: split, parcels, metrics, check", |b| b.iter(|| layout(black_box(&region), &opts).unwrap()));
    let l = layout(&region, &opts).unwrap();
    g.bench_function("peer: km2 blocks, parcels and metrics of the same streets", |b| {
        b.iter(|| {
            let bl = blocks(&region.polygon, black_box(&l.streets));
            let p = parcellate(&bl, &StreetIndex::new(&l.streets), region.parcel.depth, region.parcel.width);
            metrics(&region.polygon, &l.streets, &bl, &p)
        })
    });
    g.bench_function("peer: km2 validator", |b| {
        b.iter(|| validate(&region.polygon, black_box(&l.streets), &l.parcels))
    });
    g.finish();
}

/// Table 2's stages on km2: each iteration runs the pipeline and adds up one stage's seconds.
fn stages(c: &mut Criterion) {
    let region = read_region(&Path::new(env!("CARGO_MANIFEST_DIR")).join("models/layout/km2.toml")).unwrap();
    let opts =
        LayoutOptions { field: FieldMethod::Distance, selection: Selection::Best, seed: region.seed, optimise: 10 };
    let mut g = c.benchmark_group("layout stages");
    g.sample_size(10);
    type Stage = fn(&netspec::layout::run::Times) -> f64;
    let list: [(&str, Stage); 3] = [
        ("km2 stage: split with matching", |t| t.split),
        ("km2 stage: backtracking", |t| t.backtracking),
        ("km2 stage: optimisation, 10 iterations", |t| t.optimise),
    ];
    for (name, stage) in list {
        g.bench_function(name, |b| {
            b.iter_custom(|n| {
                (0..n).map(|_| Duration::from_secs_f64(stage(&layout(black_box(&region), &opts).unwrap().times))).sum()
            })
        });
    }
    g.finish();
}

criterion_group!(benches, km2, stages);
criterion_main!(benches);
