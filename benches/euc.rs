//! rastty against a peer: the `euc` crate (a software rasterizer in Rust)
//! draws the same mesh, turned the same way, on the same sample grid
//! (200×120 samples: 200×60 cells in half mode), with a depth buffer, back
//! faces culled and the same per-vertex lighting interpolated. rastty's
//! frame also includes what euc does not do: the blit into 12,000 terminal
//! cells. euc snaps nothing and has no tie rule; rastty's path is exact.
//!
//! `cargo bench --bench euc`; `examples/vs_euc.rs` counts instructions.

#[path = "euc_pipeline.rs"]
mod euc_pipeline;

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use rastty::{Renderer, scene::Scene};

fn vs_euc(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let scene = Scene::of_model(Path::new(&format!("{root}/tests/models/bunny.obj"))).unwrap();
    let opts = euc_pipeline::options();
    let mut group = c.benchmark_group("vs-euc");
    let mut r = Renderer::new();
    group.bench_function("rastty/bunny/200x120-samples", |b| {
        b.iter(|| r.render(&scene, &opts).cols())
    });
    let (pipeline, indices, mut color, mut depth) = euc_pipeline::setup(&scene, &opts);
    group.bench_function("euc/bunny/200x120-samples", |b| {
        b.iter(|| euc_pipeline::frame(&pipeline, &indices, &mut color, &mut depth))
    });
    // How much each drew, for the record.
    r.render(&scene, &opts);
    let ours = r
        .framebuffer()
        .samples()
        .iter()
        .filter(|s| s.is_some())
        .count();
    let theirs = color.as_ref().iter().filter(|&&p| p != 0).count();
    eprintln!("samples drawn: rastty {ours}, euc {theirs}");
    group.finish();
}

criterion_group!(benches, vs_euc);
criterion_main!(benches);
