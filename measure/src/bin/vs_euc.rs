//! rastty and euc drawing the bunny, frame after frame, for an instruction
//! counter (repeatable where wall-clock times on a shared machine are not):
//!
//! ```text
//! cargo build --release -p rastty-measure --bin vs_euc
//! valgrind --tool=callgrind target/release/vs_euc rastty 40
//! valgrind --tool=callgrind target/release/vs_euc euc 40
//! ```
//!
//! `scripts/figures.sh` does both and writes instructions a frame to
//! docs/figures.md.

use rastty_measure::euc_pipeline;

use std::path::Path;

use rastty::{Renderer, scene::Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let who = args.get(1).map_or("rastty", String::as_str);
    let frames: usize = args.get(2).and_then(|n| n.parse().ok()).unwrap_or(100);
    let scene = Scene::of_model(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/models/bunny.obj"
    )))
    .expect("the bunny");
    let opts = euc_pipeline::options();
    if who == "euc" {
        let (pipeline, indices, mut color, mut depth) = euc_pipeline::setup(&scene, &opts);
        for _ in 0..frames {
            euc_pipeline::frame(&pipeline, &indices, &mut color, &mut depth);
        }
    } else {
        let mut r = Renderer::new();
        for _ in 0..frames {
            r.render(&scene, &opts);
        }
    }
}
