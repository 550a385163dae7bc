//! Meshes through the whole pipeline: model files (OBJ with materials, STL
//! binary and ASCII), built-in shapes, near-plane clipping and the depth
//! buffer, as plain-text snapshots at fixed angles.

use std::path::Path;

use glam::Vec3;
use rastty::Shading;
use rastty::color::Lin;
use rastty::{GlyphMode, RenderOptions, color::ColorDepth, color::Rgb, render, scene::Scene};

fn model(name: &str) -> Scene {
    let path = format!("{}/tests/models/{name}", env!("CARGO_MANIFEST_DIR"));
    Scene::of_model(Path::new(&path)).unwrap()
}

fn scene(name: &str) -> Scene {
    let path = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::load(Path::new(&path)).unwrap()
}

fn opts(glyphs: GlyphMode, yaw: f32, pitch: f32) -> RenderOptions {
    RenderOptions {
        cols: 48,
        rows: 18,
        glyphs,
        color: ColorDepth::None,
        turn: Vec3::new(pitch, yaw, 0.0),
        ..RenderOptions::default()
    }
}

fn both_modes(name: &str, scene: &Scene, yaw: f32, pitch: f32) {
    for glyphs in [GlyphMode::Ascii, GlyphMode::Half] {
        let text = render(scene, &opts(glyphs, yaw, pitch)).to_string();
        assert!(
            text.chars().any(|c| c != ' ' && c != '\n'),
            "{name} {glyphs:?} draws something"
        );
        insta::assert_snapshot!(format!("{name}_{glyphs:?}"), text);
    }
}

#[test]
fn cube() {
    let scene = Scene::of_model(Path::new("cube")).unwrap();
    both_modes("cube", &scene, 30.0, 20.0);
}

#[test]
fn bunny() {
    both_modes("bunny", &model("bunny.obj"), 20.0, 0.0);
}

#[test]
fn teapot() {
    both_modes("teapot", &model("teapot.obj"), 30.0, 15.0);
}

#[test]
fn fox() {
    both_modes("fox", &model("fox.obj"), 60.0, 10.0);
}

#[test]
fn fox_wears_its_material_colours() {
    let scene = model("fox.obj");
    let mesh = &scene.meshes[0];
    let kd: Vec<Lin> = (0..mesh.faces.len()).map(|f| mesh.face_color(f)).collect();
    // fox.mtl's Kd values, in linear light: the orange of its fur, which
    // shows as #c67a24 (read as sRGB it would be a rust brown, #904a04).
    let fur = Lin::from_unit([0.564712, 0.194618, 0.017642]);
    assert!(kd.contains(&fur));
    assert_eq!(fur.to_srgb(), Rgb::new(0xc6, 0x7a, 0x24));
    let o = RenderOptions {
        color: ColorDepth::TrueColor,
        shading: Shading::None,
        ..opts(GlyphMode::Block, 60.0, 10.0)
    };
    let frame = render(&scene, &o);
    let shown: std::collections::HashSet<Rgb> = frame.cells().iter().filter_map(|c| c.bg).collect();
    let materials: std::collections::HashSet<Rgb> = kd.into_iter().map(Lin::to_srgb).collect();
    assert_eq!(materials.len(), 4);
    // Unlit, the colours on screen are exactly the materials' (the fourth,
    // the eyes, is too small to own a sample from this side).
    let on_screen = materials.iter().filter(|m| shown.contains(m)).count();
    assert!(on_screen >= 3, "{on_screen} of the materials shown");
    assert!(
        shown.iter().all(|c| materials.contains(c)),
        "nothing but material colours"
    );
}

#[test]
fn stl_binary_and_ascii_are_the_same_dog() {
    let bin = model("shiba-inu-binary.stl");
    let ascii = model("shiba-inu-ascii.stl");
    assert_eq!(bin.meshes[0].faces.len(), 358);
    assert_eq!(bin.meshes[0].faces.len(), ascii.meshes[0].faces.len());
    let o = opts(GlyphMode::Half, 40.0, 10.0);
    let a = render(&bin, &o).to_string();
    assert_eq!(a, render(&ascii, &o).to_string());
    insta::assert_snapshot!(a);
}

#[test]
fn a_triangle_crossing_the_near_plane_is_clipped_not_mirrored() {
    let scene = scene("near-plane");
    let o = RenderOptions {
        color: ColorDepth::TrueColor,
        ..opts(GlyphMode::Half, 0.0, 0.0)
    };
    let mut r = rastty::Renderer::new();
    let frame = r.render(&scene, &o).clone();
    let stats = *r.stats();
    assert_eq!(stats.clipped, 2, "the floor's two triangles are cut");
    assert_eq!(stats.clip_rejected, 1, "the marker behind the eye is gone");
    // The floor reaches the bottom of the screen, and nothing white shows.
    let bottom = frame.row(frame.rows() - 1);
    assert!(bottom.iter().all(|c| c.bg.is_some_and(|b| b != Rgb::BLACK)));
    assert!(
        !frame
            .cells()
            .iter()
            .any(|c| c.fg == Some(Rgb::WHITE) || c.bg == Some(Rgb::WHITE))
    );
    insta::assert_snapshot!(render(&scene, &opts(GlyphMode::Ascii, 0.0, 0.0)).to_string());
}

#[test]
fn games101_assignment_2_the_nearer_triangle_wins() {
    let scene = scene("assignment2");
    let o = RenderOptions {
        color: ColorDepth::TrueColor,
        glyphs: GlyphMode::Block,
        ..opts(GlyphMode::Block, 0.0, 0.0)
    };
    let mut r = rastty::Renderer::new();
    r.render(&scene, &o);
    let fb = r.framebuffer();
    // A point inside both triangles, (0.5, 0.6) on the near one's plane and
    // on the far one's line of sight: projected, it shows the near colour.
    let near = Rgb::new(0xd9, 0xee, 0xb9);
    let far = Rgb::new(0x3a, 0x55, 0xee);
    let samples: Vec<Rgb> = fb.samples().iter().flatten().map(|c| c.to_srgb()).collect();
    assert!(samples.contains(&near) && samples.contains(&far));
    let grid = fb.grid();
    let vp = scene.camera.view_projection(o.aspect());
    let p = vp * Vec3::new(0.5, 0.6, -2.0).extend(1.0);
    let (x, y) = (
        ((p.x / p.w + 1.0) * grid.width as f32 / 2.0) as u32,
        ((p.y / p.w + 1.0) * grid.height as f32 / 2.0) as u32,
    );
    assert_eq!(fb.get(x, y).map(Lin::to_srgb), Some(near));
    insta::assert_snapshot!(render(&scene, &opts(GlyphMode::Ascii, 0.0, 0.0)).to_string());
}
