//! The 3MF loader on arbitrary bytes (a zip archive, its relationships and
//! model parts): an error is fine, a panic is not; what it reads is drawn.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let options = rastty::scene::LoadOptions {
        max_bytes: 1 << 24,
        max_triangles: 1 << 16,
        ..Default::default()
    };
    if let Ok(loaded) = rastty::scene::threemf::parse_with(data, "fuzz.3mf", &options) {
        let mesh = rastty::scene::Mesh::of(
            std::sync::Arc::new(loaded.geometry),
            rastty::color::Rgb::WHITE,
        );
        let scene = rastty::scene::Scene::of_mesh(mesh);
        let mut r = rastty::Renderer::new();
        r.render(
            &scene,
            &rastty::RenderOptions {
                cols: 20,
                rows: 8,
                ..Default::default()
            },
        );
    }
});
