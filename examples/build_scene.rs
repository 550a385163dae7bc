//! Build a scene in code (a mesh, a triangle with a colour at each corner,
//! a light, a camera) and print it in colour, frame after frame into the
//! same memory.
//!
//! ```text
//! cargo run --example build_scene
//! ```

use rastty::encode::{Rep, write_lines};
use rastty::glam::{Mat4, Vec3};
use rastty::scene::Shape;
use rastty::{
    Frame, GlyphMode, RenderOptions, Renderer, color::ColorDepth, color::Rgb, scene::Light,
    scene::Scene,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::builder()
        .look_at(Vec3::new(3.0, 2.6, 4.5), Vec3::new(0.0, 0.2, 0.0))
        .background(Rgb::new(0x10, 0x14, 0x20))
        // A cube standing on a floor of one triangle with three colours.
        .mesh(Shape::Cube.mesh(Rgb::new(0x40, 0x90, 0xff)).with_model(
            Mat4::from_translation(Vec3::new(0.0, 0.7, 0.0)) * Mat4::from_scale(Vec3::splat(0.7)),
        ))
        .triangle_colors(
            // Corners 120° apart around the origin, 2.6 out.
            [90.0f32, 210.0, 330.0].map(|deg| {
                let (s, c) = deg.to_radians().sin_cos();
                Vec3::new(2.6 * c, 0.0, 2.6 * s)
            }),
            [
                Rgb::new(255, 80, 80),
                Rgb::new(80, 255, 80),
                Rgb::new(80, 80, 255),
            ],
        )
        .light(Light {
            direction: Vec3::new(-1.0, -2.0, -1.5),
            ..Light::default()
        })
        .build()?;

    // One renderer and one frame for every turn: nothing is allocated once
    // the first frame has sized them.
    let (mut renderer, mut frame) = (Renderer::new(), Frame::default());
    let (mut scratch, mut out) = (Vec::new(), std::io::stdout().lock());
    for yaw in [0.0, 45.0] {
        let opts = RenderOptions {
            cols: 60,
            rows: 18,
            glyphs: GlyphMode::Half,
            color: ColorDepth::TrueColor,
            turn: Vec3::new(0.0, yaw, 0.0),
            ..Default::default()
        };
        renderer.render_into(&scene, &opts, &mut frame);
        write_lines(&frame, opts.color, Rep::Off, &mut scratch, &mut out)?;
    }
    Ok(())
}
