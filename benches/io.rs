//! Model building and file I/O at 10^6 nonzeros, with HiGHS's own writer as the peer measured in
//! the same run.
//!
//! Targets: build ≥ 5 M nonzeros/s; MPS/LP write ≥ 100 MB/s and ≥ 2× HiGHS's writer;
//! read ≥ 50 MB/s. Run with `./dev bench` (or `cargo bench --bench io`).

use criterion::{criterion_group, criterion_main, BatchSize, Criterion, Throughput};
use netspec::io::{lp, mps};
use netspec::milp::{Model, VarId};
use std::hint::black_box;

const ROWS: usize = 50_000;
const VARS: usize = 100_000;
const PER_ROW: usize = 20; // 10^6 nonzeros

/// A sparse MILP with 10^6 nonzeros: half binaries, a quarter integers, a quarter continuous,
/// rows of all kinds, a deterministic pseudo-random pattern.
fn build() -> Model {
    let mut m = Model::new("bench");
    m.reserve(VARS, ROWS, ROWS * PER_ROW);
    let mut s: u64 = 0x2545F4914F6CDD1D;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    for j in 0..VARS {
        let obj = (next() % 1000) as f64 / 7.0;
        match j % 4 {
            0 | 1 => m.add_binary(format!("E_e{j}"), obj),
            2 => m.add_integer(format!("N_v{j}"), 0.0, 10.0, obj),
            _ => m.add_continuous(format!("D_h{j}"), 0.0, 1e4, obj),
        };
    }
    let mut terms = Vec::with_capacity(PER_ROW);
    for r in 0..ROWS {
        terms.clear();
        let base = next() as usize % (VARS - PER_ROW * 5);
        for k in 0..PER_ROW {
            terms.push((VarId((base + k * 5) as u32), ((next() % 200) as f64 - 100.0) / 3.0));
        }
        let rhs = (next() % 100) as f64;
        match r % 4 {
            0 => m.add_le(format!("c{r}"), terms.iter().copied(), rhs),
            1 => m.add_ge(format!("c{r}"), terms.iter().copied(), -rhs),
            2 => m.add_eq(format!("c{r}"), terms.iter().copied(), rhs),
            _ => m.add_row(format!("c{r}"), -rhs, rhs, terms.iter().copied()),
        };
    }
    m
}

fn bench_io(c: &mut Criterion) {
    let model = build();
    let nnz = model.num_nonzeros() as u64;

    let mut g = c.benchmark_group("build");
    g.sample_size(10).throughput(Throughput::Elements(nnz));
    g.bench_function("model_1e6_nonzeros", |b| b.iter(|| black_box(build())));
    g.finish();

    let mut mps_text = Vec::new();
    mps::write(&model, &mut mps_text, &mps::WriteOptions::default()).unwrap();
    let mut lp_text = Vec::new();
    lp::write(&model, &mut lp_text, &lp::WriteOptions::default()).unwrap();

    for (name, bytes) in [("mps", mps_text.len()), ("lp", lp_text.len())] {
        let mut g = c.benchmark_group(format!("write_{name}"));
        g.sample_size(10).throughput(Throughput::Bytes(bytes as u64));
        g.bench_function("netspec", |b| {
            b.iter_batched(
                || Vec::with_capacity(bytes + 1024),
                |mut buf| {
                    if name == "mps" {
                        mps::write(&model, &mut buf, &mps::WriteOptions::default()).unwrap();
                    } else {
                        lp::write(&model, &mut buf, &lp::WriteOptions::default()).unwrap();
                    }
                    buf
                },
                BatchSize::LargeInput,
            )
        });
        #[cfg(feature = "highs")]
        {
            let dir = std::env::temp_dir().join(format!("netspec-bench-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let ours = dir.join(format!("ours.{name}"));
            let theirs = dir.join(format!("highs.{name}"));
            // Both to a file, so the comparison includes the same file-system cost.
            g.bench_function("netspec_to_file", |b| b.iter(|| netspec::io::write_model_file(&model, &ours).unwrap()));
            let mut loaded = netspec::solvers::highs::LoadedModel::new(&model).unwrap();
            g.bench_function("highs_writer_to_file", |b| b.iter(|| loaded.write(&theirs).unwrap()));
            let _ = std::fs::remove_dir_all(&dir);
        }
        g.finish();
    }

    let mut g = c.benchmark_group("read");
    g.sample_size(10);
    let mps_str = String::from_utf8(mps_text).unwrap();
    let lp_str = String::from_utf8(lp_text).unwrap();
    g.throughput(Throughput::Bytes(mps_str.len() as u64));
    g.bench_function("mps", |b| b.iter(|| black_box(mps::read_str(&mps_str).unwrap())));
    g.throughput(Throughput::Bytes(lp_str.len() as u64));
    g.bench_function("lp", |b| b.iter(|| black_box(lp::read_str(&lp_str).unwrap())));
    g.finish();
}

criterion_group!(benches, bench_io);
criterion_main!(benches);
