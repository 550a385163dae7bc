//! Render a scene with the library and print the frame as plain text: the
//! same string a test would hand to `insta::assert_snapshot!`.
//!
//! ```text
//! cargo run --example snapshot
//! ```
//!
//! In a test of your own:
//!
//! ```ignore
//! #[test]
//! fn my_scene() {
//!     let scene = rastty::scene::Scene::load("scene.toml".as_ref()).unwrap();
//!     let opts = rastty::RenderOptions { cols: 40, rows: 12, color: rastty::color::ColorDepth::None, ..Default::default() };
//!     insta::assert_snapshot!(rastty::render(&scene, &opts).to_string());
//! }
//! ```

use rastty::glam::Vec3;
use rastty::{
    GlyphMode, RenderOptions, color::ColorDepth, color::Rgb, render, scene::Projection,
    scene::Scene,
};

fn main() {
    // A scene built in code rather than read from TOML: two triangles that
    // share an edge, straight in the canonical cube.
    let v = Vec3::new;
    let scene = Scene::builder()
        .projection(Projection::None)
        .triangle(
            [v(-0.9, -0.8, 0.0), v(0.9, -0.8, 0.0), v(0.9, 0.8, 0.0)],
            Rgb::WHITE,
        )
        .triangle(
            [v(-0.9, -0.8, 0.0), v(0.9, 0.8, 0.0), v(-0.9, 0.8, 0.0)],
            Rgb::new(60, 60, 60),
        )
        .build()
        .expect("a scene with triangles and a camera that projects");
    let opts = RenderOptions {
        cols: 32,
        rows: 10,
        glyphs: GlyphMode::Ascii,
        color: ColorDepth::None,
        ..RenderOptions::default()
    };
    print!("{}", render(&scene, &opts));
}
