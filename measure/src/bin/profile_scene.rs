//! Renders a scene or model in a loop at 200×60 cells in half mode, for a
//! profiler or an instruction counter:
//!
//! ```text
//! cargo run --release -p rastty-measure --bin profile_scene -- SCENE [FRAMES] [full] [flat]
//! ```
//!
//! `full` forces every pipeline stage on, `flat` uses flat shading. A
//! model turns 3° a frame (a scene file stays put); `scripts/figures.sh` counts its
//! instructions under callgrind.

use std::path::Path;

use glam::Vec3;
use rastty::Pipeline;
use rastty::Shading;
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, scene::Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = Path::new(
        args.get(1)
            .map_or("examples/scenes/tiles.toml", String::as_str),
    );
    let scene = Scene::open(path).expect("a scene");
    let spins = Scene::is_model(path);
    let frames: u32 = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(1000);
    let flag = |f: &str| args.iter().skip(3).any(|a| a == f);
    let opts = RenderOptions {
        cols: 200,
        rows: 60,
        glyphs: GlyphMode::Half,
        color: ColorDepth::TrueColor,
        pipeline: if flag("full") {
            Pipeline::Full
        } else {
            Pipeline::Planned
        },
        shading: if flag("flat") {
            Shading::Flat
        } else {
            Shading::Smooth
        },
        ..RenderOptions::default()
    };
    let mut r = Renderer::new();
    let start = std::time::Instant::now();
    for k in 0..frames {
        let turn = if spins {
            Vec3::new(10.0, (k % 120) as f32 * 3.0, 0.0)
        } else {
            Vec3::ZERO
        };
        r.render(&scene, &RenderOptions { turn, ..opts });
    }
    eprintln!("{:?} a frame", start.elapsed() / frames.max(1));
}
