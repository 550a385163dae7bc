//! An OBJ model on arbitrary bytes, opened as `rastty render` opens one and
//! drawn: a frame as the model is first seen and one turned, in half
//! blocks and in octants. An error is fine, a panic is not. (The bytes are
//! written to a file of their own, so that the model takes the path a
//! user's does; files it names are looked for beside it, where there are
//! none.)
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use rastty::glam::Vec3;
use rastty::scene::Scene;
use rastty::{GlyphMode, RenderOptions, Renderer};

/// This process's scratch directory, made once (as `mtl_texture`'s).
fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("rastty-fuzz-obj-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("a scratch directory");
        d
    })
}

fuzz_target!(|data: &[u8]| {
    let path = dir().join("fuzz.obj");
    std::fs::write(&path, data).expect("the model written");
    let Ok(scene) = Scene::open(&path) else {
        return;
    };
    let mut r = Renderer::new();
    for (glyphs, turn) in [
        (GlyphMode::Half, Vec3::ZERO),
        (GlyphMode::Octant, Vec3::new(10.0, 137.0, 0.0)),
    ] {
        let opts = RenderOptions {
            cols: 32,
            rows: 12,
            glyphs,
            turn,
            ..RenderOptions::default()
        };
        r.render(&scene, &opts);
    }
});
