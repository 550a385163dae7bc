//! The rasterizer's traversals on the same frames: the notes' three
//! methods, identical coverage, different cost.
//!
//! `cargo bench --bench raster`

use criterion::{Criterion, criterion_group, criterion_main};
use rastty::Choice;
use rastty::{
    GlyphMode, RenderOptions, Renderer, color::ColorDepth, raster::Traversal, scene::Scene,
};

fn scene(name: &str) -> Scene {
    let path = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::load(path.as_ref()).unwrap()
}

fn traversals(c: &mut Criterion) {
    let mut group = c.benchmark_group("traversal");
    for name in ["perspective", "notes-triangle"] {
        let scene = scene(name);
        for &t in Traversal::ALL {
            let opts = RenderOptions {
                cols: 200,
                rows: 60,
                glyphs: GlyphMode::Block,
                color: ColorDepth::TrueColor,
                traversal: t,
                ..RenderOptions::default()
            };
            let mut r = Renderer::new();
            group.bench_function(format!("{name}/{t:?}"), |b| {
                b.iter(|| r.render(&scene, &opts).cols())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, traversals);
criterion_main!(benches);
