//! What the planner saves: four scenes, each rendered (no encoding) with the
//! plan and with every stage forced on, at 200×60 cells in half mode.
//!
//! `cargo bench --bench plan`

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rastty::Pipeline;
use rastty::Shading;
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, scene::Scene};

/// The scenes, their shading, and whether they turn (models do; scene files
/// stay as drawn).
fn scenes() -> Vec<(&'static str, Scene, Shading, bool)> {
    let root = env!("CARGO_MANIFEST_DIR");
    let example =
        |n: &str| Scene::load(Path::new(&format!("{root}/examples/scenes/{n}.toml"))).unwrap();
    let model = |p: &str| Scene::of_model(Path::new(p)).unwrap();
    vec![
        ("2d-flat-tiles", example("tiles"), Shading::Smooth, false),
        ("flat-convex-sphere", model("sphere"), Shading::Flat, true),
        (
            "smooth-lit-bunny",
            model(&format!("{root}/tests/models/bunny.obj")),
            Shading::Smooth,
            true,
        ),
        (
            "overlapping-meshes",
            example("overlap"),
            Shading::Smooth,
            false,
        ),
    ]
}

fn plan(c: &mut Criterion) {
    let mut group = c.benchmark_group("plan");
    for (name, scene, shading, turns) in scenes() {
        for pipeline in [Pipeline::Planned, Pipeline::Full] {
            let opts = RenderOptions {
                cols: 200,
                rows: 60,
                glyphs: GlyphMode::Half,
                color: ColorDepth::TrueColor,
                shading,
                pipeline,
                turn: if turns {
                    Vec3::new(10.0, 30.0, 0.0)
                } else {
                    Vec3::ZERO
                },
                ..RenderOptions::default()
            };
            let mut r = Renderer::new();
            group.bench_function(format!("{name}/{pipeline:?}"), |b| {
                b.iter(|| r.render(&scene, &opts).cols())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, plan);
criterion_main!(benches);
