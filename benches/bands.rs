//! Frames drawn in bands of rows on one thread and on several (the
//! `parallel` feature): render only (transform, clip, raster, blit), the
//! built-in torus and the Tux at 1000×300 and 400×120 cells and the Tux at
//! 200×60, half blocks, truecolor, turning 3° a frame. Each size is timed
//! with one band and with one band a core, side by side in one run.
//!
//! `cargo bench --bench bands`. The Tux (41k triangles) is read from
//! `../shared/models/`; without it, only the torus is timed.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use rastty::{ColorDepth, Frame, GlyphMode, RenderOptions, Renderer, Scene, Threads};

fn bands(c: &mut Criterion) {
    let root = env!("CARGO_MANIFEST_DIR");
    let tux = format!("{root}/../shared/models/linux-mascot-tux.obj");
    let mut scenes = vec![("torus", rastty::default_scene())];
    match Scene::of_model(Path::new(&tux)) {
        Ok(s) => scenes.push(("tux", s)),
        Err(_) => eprintln!("skipping tux: {tux} not found"),
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u16);
    let mut group = c.benchmark_group("bands");
    for (name, scene) in &scenes {
        for (cols, rows) in [(1000, 300), (400, 120), (200, 60)] {
            for threads in [1, cores] {
                let opts = RenderOptions {
                    cols,
                    rows,
                    glyphs: GlyphMode::Half,
                    color: ColorDepth::TrueColor,
                    threads: Threads::Exactly(threads),
                    ..RenderOptions::default()
                };
                let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
                let mut yaw = 0.0;
                group.bench_function(format!("{name}/{cols}x{rows}/{threads}"), |b| {
                    b.iter(|| {
                        yaw += 3.0;
                        let opts = RenderOptions {
                            turn: rastty::glam::Vec3::new(0.0, yaw, 0.0),
                            ..opts
                        };
                        renderer.render_into(scene, &opts, &mut frame);
                    })
                });
            }
        }
    }
    group.finish();
}

criterion_group!(benches, bands);
criterion_main!(benches);
