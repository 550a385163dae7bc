//! Bytes per frame of the diffing encoder: an 80×24 animation of a square
//! split into a red and a blue triangle on a dark background
//! (`examples/scenes/square.toml`) turning one full circle about the view
//! axis in 60 frames, in every glyph mode, in truecolor. Prints the
//! README's Markdown table.
//!
//! ```text
//! cargo run --release --example bytes_per_frame
//! ```

use rastty::encode::{Encoder, Rep};
use rastty::{ColorDepth, GlyphMode, RenderOptions, Renderer, Scene};

fn main() {
    let path = format!("{}/examples/scenes/square.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::load(path.as_ref()).expect("the square scene");
    println!(
        "| glyphs | first frame (bytes) | later frames, mean (bytes) | later frames, mean, with REP (bytes) |"
    );
    println!("|---|---:|---:|---:|");
    for mode in GlyphMode::ALL {
        let [plain, rep] = [Rep::Off, Rep::On].map(|r| measure(&scene, mode, r));
        println!("| {mode:?} | {} | {:.0} | {:.0} |", plain.0, plain.1, rep.1);
    }
}

/// The first frame's bytes and the mean of the 59 later frames.
fn measure(scene: &Scene, glyphs: GlyphMode, rep: Rep) -> (usize, f64) {
    let mut renderer = Renderer::new();
    let mut encoder = Encoder::new(ColorDepth::TrueColor).with_rep(rep);
    let mut sizes = Vec::new();
    for k in 0..60 {
        let opts = RenderOptions {
            cols: 80,
            rows: 24,
            glyphs,
            color: ColorDepth::TrueColor,
            turn: glam::Vec3::new(0.0, 0.0, k as f32 * 6.0),
            ..RenderOptions::default()
        };
        let frame = renderer.render(scene, &opts);
        sizes.push(encoder.encode(frame, &mut std::io::sink()).unwrap());
    }
    let later = &sizes[1..];
    (
        sizes[0],
        later.iter().sum::<usize>() as f64 / later.len() as f64,
    )
}
