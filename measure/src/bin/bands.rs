//! One band against one band a core, frame by frame in turn, so that the
//! ratio holds however the machine's clock wanders: the built-in torus and
//! the Tux, at 200×60 to 1000×300 cells, half blocks, truecolor, turning 3°
//! a frame, render only (transform, clip, raster, blit).
//!
//! `cargo run --release -p rastty-measure --bin bands`. The Tux (41k triangles) is read
//! from `../shared/models/`; without it, only the torus is timed.

use std::path::Path;
use std::time::{Duration, Instant};

use rastty::{Frame, GlyphMode, RenderOptions, Renderer, Threads, color::ColorDepth, scene::Scene};

/// Rounds of ten frames each way; the first two warm up.
const ROUNDS: u32 = 22;

fn main() {
    let tux = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/linux-mascot-tux.obj"
    );
    let mut scenes = vec![("torus", rastty::scene::default_scene())];
    match Scene::of_model(Path::new(tux)) {
        Ok(s) => scenes.push(("tux", s)),
        Err(_) => eprintln!("skipping tux: {tux} not found"),
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u16);
    println!("| scene | cells | 1 band (ms a frame) | {cores} bands | ratio |");
    println!("|---|---|---:|---:|---:|");
    for (name, scene) in &scenes {
        for (cols, rows) in [(200, 60), (400, 120), (600, 180), (1000, 300)] {
            let opts = |threads| RenderOptions {
                cols,
                rows,
                glyphs: GlyphMode::Half,
                color: ColorDepth::TrueColor,
                threads: Threads::Exactly(threads),
                ..RenderOptions::default()
            };
            let mut sides = [(Renderer::new(), opts(1)), (Renderer::new(), opts(cores))];
            let mut total = [Duration::ZERO; 2];
            let mut frame = Frame::default();
            for round in 0..ROUNDS {
                for (k, (renderer, opts)) in sides.iter_mut().enumerate() {
                    let start = Instant::now();
                    for i in 0..10 {
                        let turn = rastty::glam::Vec3::new(0.0, 3.0 * i as f32, 0.0);
                        renderer.render_into(scene, &RenderOptions { turn, ..*opts }, &mut frame);
                    }
                    if round >= 2 {
                        total[k] += start.elapsed();
                    }
                }
            }
            let ms = |d: Duration| d.as_secs_f64() * 1e3 / (10 * (ROUNDS - 2)) as f64;
            println!(
                "| {name} | {cols}×{rows} | {:.2} | {:.2} | {:.2} |",
                ms(total[0]),
                ms(total[1]),
                total[1].as_secs_f64() / total[0].as_secs_f64()
            );
        }
    }
}
