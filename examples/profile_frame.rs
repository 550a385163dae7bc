//! Renders and encodes frames of a model in a loop, for a profiler:
//! `cargo run --release --example profile_frame -- MODEL [FRAMES]`.

use std::path::Path;

use rastty::animate::{Axis, Player, Spin};
use rastty::encode::Encoder;
use rastty::{ColorDepth, GlyphMode, RenderOptions, Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = args.get(1).map_or("tests/models/bunny.obj", String::as_str);
    let frames: u64 = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(300);
    let scene = Scene::of_model(Path::new(model)).expect("a model");
    let opts = RenderOptions {
        cols: 200,
        rows: 60,
        glyphs: GlyphMode::Half,
        color: ColorDepth::TrueColor,
        ..RenderOptions::default()
    };
    let mut player = Player::new(
        scene,
        opts,
        Spin {
            axis: Axis::Y,
            step: 3.0,
        },
        Encoder::new(ColorDepth::TrueColor),
    );
    let start = std::time::Instant::now();
    let mut bytes = 0;
    for _ in 0..frames {
        player.advance(1);
        bytes += player.show(&mut std::io::sink(), 0.0).unwrap();
    }
    let t = start.elapsed();
    eprintln!(
        "{frames} frames in {t:?}: {:?} a frame, {} bytes a frame",
        t / frames as u32,
        bytes as u64 / frames
    );
}
