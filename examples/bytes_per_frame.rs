//! Bytes per frame of the diffing encoder: an 80×24 animation of a square
//! split into a red and a blue triangle on a dark background
//! (`examples/scenes/square.toml`) turning one full circle about the view
//! axis in 60 frames, in every glyph mode, in truecolor. Prints the
//! Markdown table in docs/usage.md.
//!
//! ```text
//! cargo run --release --example bytes_per_frame
//! ```

use rastty::animate;
use rastty::animate::{Axis, Spin};
use rastty::encode::{Encoder, Rep};
use rastty::{ColorDepth, GlyphMode, RenderOptions, Scene};

fn main() {
    let path = format!("{}/examples/scenes/square.toml", env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::load(path.as_ref()).expect("the square scene");
    println!("| glyphs | first frame | later frames, mean | later frames, mean, with `--rep` |");
    println!("|---|---:|---:|---:|");
    for glyphs in GlyphMode::ALL {
        let [plain, rep] = [Rep::Off, Rep::On].map(|rep| {
            let opts = RenderOptions {
                cols: 80,
                rows: 24,
                glyphs,
                color: ColorDepth::TrueColor,
                ..RenderOptions::default()
            };
            let encoder = Encoder::new(ColorDepth::TrueColor).with_rep(rep);
            let spin = Spin {
                axis: Axis::Z,
                step: 6.0,
            };
            let mut sizes = Vec::new();
            animate::play(
                &scene,
                &opts,
                spin,
                60,
                encoder,
                &mut std::io::sink(),
                |n| sizes.push(n),
            )
            .unwrap();
            (sizes[0], sizes[1..].iter().sum::<usize>() as f64 / 59.0)
        });
        println!(
            "| {glyphs:?} | {} | {:.0} | {:.0} |",
            plain.0, plain.1, rep.1
        );
    }
}
