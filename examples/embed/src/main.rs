//! A crate that depends on rastty with its default features, as a library
//! user's does, and draws one frame of a torus as text. CI builds and runs
//! it and checks with `cargo tree` that none of the program's crates
//! (clap, the terminal's, plotters) come with the library.

use rastty::glam::Vec3;
use rastty::scene::Shape;
use rastty::{GlyphMode, RenderOptions, color::ColorDepth, color::Rgb, render, scene::Scene};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::builder()
        .look_at(Vec3::new(0.0, 2.0, 3.2), Vec3::ZERO)
        .mesh(Shape::Torus.mesh(Rgb::new(0xff, 0xa0, 0x40)))
        .build()?;
    let opts = RenderOptions {
        cols: 40,
        rows: 12,
        glyphs: GlyphMode::Ascii,
        color: ColorDepth::None,
        ..Default::default()
    };
    print!("{}", render(&scene, &opts));
    Ok(())
}
