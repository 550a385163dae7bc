//! Whole frames: transform, clip, raster, blit and encode (as a diff from
//! the previous frame, as `spin` sends them), at 200×60 cells in half mode,
//! truecolor, smooth shading, the model turning 3° a frame.
//!
//! `cargo bench --bench frame`. The Tux (41k triangles) is read from
//! `../shared/models/`; without it, only the bunny is timed.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use rastty::animate::{LiveStatus, Player, Spin};
use rastty::encode::Encoder;
use rastty::transform::Axis;
use rastty::{GlyphMode, RenderOptions, color::ColorDepth, scene::Scene};

fn frames(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let models = [
        ("bunny", format!("{root}/tests/models/bunny.obj")),
        (
            "tux",
            format!("{root}/../shared/models/linux-mascot-tux.obj"),
        ),
    ];
    let mut group = c.benchmark_group("frame");
    for (name, path) in models {
        let Ok(scene) = Scene::of_model(Path::new(&path)) else {
            eprintln!("skipping {name}: {path} not found");
            continue;
        };
        let opts = RenderOptions {
            cols: 200,
            rows: 60,
            glyphs: GlyphMode::Half,
            color: ColorDepth::TrueColor,
            ..RenderOptions::default()
        };
        let spin = Spin {
            view: Default::default(),
            axis: Axis::Y,
            step: 3.0,
            play: None,
        };
        let mut player = Player::new(scene, opts, spin, Encoder::new(ColorDepth::TrueColor));
        let mut sink = std::io::sink();
        group.bench_function(format!("{name}/200x60/half"), |b| {
            b.iter(|| {
                player.advance(1);
                player.show(&mut sink, LiveStatus::default()).unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, frames);
criterion_main!(benches);
