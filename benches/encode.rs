//! The encoder: a full frame, and the diff between two consecutive frames
//! of the spinning square, at 200×60 cells in half mode, truecolor.
//!
//! `cargo bench --bench encode`

use criterion::{Criterion, criterion_group, criterion_main};
use glam::Vec3;
use rastty::encode::Encoder;
use rastty::{Frame, GlyphMode, RenderOptions, color::ColorDepth, scene::Scene};

fn frames(name: &str, turns: [f32; 2]) -> [Frame; 2] {
    let path = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::load(path.as_ref()).unwrap();
    turns.map(|roll| {
        let opts = RenderOptions {
            cols: 200,
            rows: 60,
            glyphs: GlyphMode::Half,
            color: ColorDepth::TrueColor,
            turn: Vec3::new(0.0, 0.0, roll),
            ..RenderOptions::default()
        };
        rastty::render(&scene, &opts)
    })
}

fn encode(c: &mut Criterion) {
    let mut group = c.benchmark_group("encode");
    let [a, b] = frames("square", [0.0, 6.0]);
    let mut enc = Encoder::new(ColorDepth::TrueColor);
    group.bench_function("square/full", |bench| {
        bench.iter(|| {
            enc.invalidate();
            enc.prepare(&a);
            enc.last_bytes().len()
        })
    });
    group.bench_function("square/diff", |bench| {
        bench.iter(|| {
            enc.prepare(&a);
            enc.prepare(&b);
            enc.last_bytes().len()
        })
    });
    let [d, _] = frames("default", [0.0, 0.0]);
    for depth in [
        ColorDepth::TrueColor,
        ColorDepth::Ansi256,
        ColorDepth::Ansi16,
    ] {
        let mut enc = Encoder::new(depth);
        group.bench_function(format!("default/full/{depth:?}"), |bench| {
            bench.iter(|| {
                enc.invalidate();
                enc.prepare(&d);
                enc.last_bytes().len()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, encode);
criterion_main!(benches);
