//! Loading models: Tux (41k triangles, normals in the file) and the bunny
//! (3.7k triangles, normals computed) from disk, and generated tori of 10k,
//! 100k and 1M triangles parsed from memory, to see how the cost grows.
//! Whole-process instructions and peak memory are `scripts/load-cost.sh`.
//!
//! `cargo bench --bench load`

use std::path::Path;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rastty::scene::{LoadOptions, obj};

#[path = "../examples/torus_obj.rs"]
mod torus_obj;

fn load(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut group = c.benchmark_group("load");
    group.sample_size(10);
    for name in ["linux-mascot-tux", "bunny"] {
        let path = format!("{root}/tests/models/{name}.obj");
        group.throughput(Throughput::Bytes(std::fs::metadata(&path).unwrap().len()));
        group.bench_function(name, |b| {
            b.iter(|| obj::load(Path::new(&path), &LoadOptions::default()).unwrap())
        });
    }
    for n in [10_000, 100_000, 1_000_000] {
        let mut text = Vec::new();
        torus_obj::write_torus(n, &mut text).unwrap();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("torus", n), &text, |b, text| {
            b.iter(|| obj::parse(text, "torus.obj", Path::new(".")).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, load);
criterion_main!(benches);
