//! Plain-text snapshots of whole frames: the scenes in `examples/scenes`,
//! rendered through the whole pipeline in ascii mode without colour.

use rastty::Choice;
use rastty::{ColorDepth, GlyphMode, RenderOptions, Scene, render};

fn frame(scene: &str, cols: u16, rows: u16) -> String {
    frame_in(scene, cols, rows, GlyphMode::Ascii)
}

fn frame_in(scene: &str, cols: u16, rows: u16, glyphs: GlyphMode) -> String {
    let path = format!(
        "{}/examples/scenes/{scene}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = Scene::load(path.as_ref()).unwrap();
    let opts = RenderOptions {
        cols,
        rows,
        glyphs,
        color: ColorDepth::None,
        ..RenderOptions::default()
    };
    render(&scene, &opts).to_string()
}

#[test]
fn notes_single_triangle() {
    insta::assert_snapshot!(frame("notes-triangle", 40, 14));
}

#[test]
fn two_triangles_sharing_an_edge() {
    insta::assert_snapshot!(frame("shared-edge", 40, 14));
}

#[test]
fn triangle_at_the_top_shows_at_the_top() {
    let f = frame("top", 40, 14);
    assert!(
        f.lines().next().unwrap().contains('%'),
        "the first row shows it"
    );
    assert!(
        f.lines().last().unwrap().trim().is_empty(),
        "the last row does not"
    );
    insta::assert_snapshot!(f);
}

#[test]
fn orthographic_cube_corner() {
    insta::assert_snapshot!(frame("orthographic", 40, 14));
}

#[test]
fn perspective_floor() {
    insta::assert_snapshot!(frame("perspective", 40, 14));
}

#[test]
fn reference_example_triangle() {
    insta::assert_snapshot!(frame("triangle", 40, 14));
}

#[test]
fn default_scene_in_block_mode() {
    let opts = RenderOptions {
        cols: 40,
        rows: 14,
        glyphs: GlyphMode::Block,
        color: ColorDepth::None,
        ..RenderOptions::default()
    };
    insta::assert_snapshot!(render(&rastty::default_scene(), &opts).to_string());
}

/// The reference triangle in every glyph mode, as `--color none` prints it.
#[test]
fn every_glyph_mode() {
    for &mode in GlyphMode::ALL {
        insta::assert_snapshot!(
            format!("glyphs_{mode:?}"),
            frame_in("notes-triangle", 24, 8, mode)
        );
    }
}
