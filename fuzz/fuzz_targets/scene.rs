//! The scene parser on arbitrary text, and rendering what it accepts.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        if let Ok(scene) = rastty::scene::Scene::parse(text, "fuzz.toml") {
            let opts = rastty::RenderOptions { cols: 16, rows: 6, ..Default::default() };
            let _ = rastty::render(&scene, &opts);
        }
    }
});
