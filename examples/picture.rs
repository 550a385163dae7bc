//! A PNG and an SVG of a scene, made in code: for documentation, and for
//! CI artefacts a reviewer can look at. The frame is drawn for the
//! picture's cell shape, so a round thing stays round.
//!
//! ```text
//! cargo run --example picture -- torus.png
//! ```

use rastty::color::Palette;
use rastty::glam::Vec3;
use rastty::picture::{self, CellPx, Picture, Theme};
use rastty::scene::Shape;
use rastty::{
    GlyphMode, RenderOptions, color::ColorDepth, color::Rgb, render, scene::Light, scene::Scene,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "torus.png".into());
    let scene = Scene::builder()
        .look_at(Vec3::new(0.0, 2.0, 3.2), Vec3::ZERO)
        .background(Rgb::new(0x10, 0x14, 0x20))
        .mesh(Shape::Torus.mesh(Rgb::new(0xff, 0xa0, 0x40)))
        .light(Light {
            direction: Vec3::new(-1.0, -2.0, -1.5),
            ..Light::default()
        })
        .build()?;
    let cell = CellPx::default(); // 8×16 pixels
    let opts = RenderOptions {
        cols: 64,
        rows: 20,
        glyphs: GlyphMode::Sextant,
        color: ColorDepth::TrueColor,
        cell_aspect: cell.aspect(),
        ..Default::default()
    };
    let frame = render(&scene, &opts);
    let palette = Palette::from(opts.color);

    let png = Picture::paint(&frame, palette, Theme::default(), cell)?;
    png.write_png(std::io::BufWriter::new(std::fs::File::create(&path)?))?;
    println!("wrote {path}: {}×{} pixels", png.width(), png.height());

    // The same frame as SVG text (`picture::save` picks the format from a
    // path's extension, as `rastty render --output` does).
    let svg = picture::svg(&frame, palette, Theme::default(), cell)?;
    println!("and {} bytes of SVG", svg.len());
    Ok(())
}
