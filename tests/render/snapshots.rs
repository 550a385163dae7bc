//! Text snapshots of whole frames: the scenes in `examples/scenes`,
//! rendered through the whole pipeline in ascii mode without colour, and
//! one in sextants with its colours (`Frame::with_colors`).

use rastty::Choice;
use rastty::{GlyphMode, RenderOptions, color::ColorDepth, render, scene::Scene};

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
    insta::assert_snapshot!(render(&rastty::scene::default_scene(), &opts).to_string());
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

/// A frame's text with its colours: the glyphs, then one line a row of
/// runs of one foreground and background, `-` for the terminal's own.
#[test]
fn with_colors_writes_glyphs_then_runs_of_colour() {
    use rastty::{Cell, Frame, color::Rgb};
    let mut f = Frame::new(3, 2);
    let orange = Some(Rgb::new(0xff, 0xa0, 0x40));
    let navy = Some(Rgb::new(0x10, 0x20, 0x30));
    f.set(
        0,
        0,
        Cell {
            ch: '▗',
            fg: orange,
            bg: None,
        },
    );
    f.set(
        1,
        0,
        Cell {
            ch: '▄',
            fg: orange,
            bg: None,
        },
    );
    f.set(
        2,
        0,
        Cell {
            ch: '▖',
            fg: orange,
            bg: None,
        },
    );
    f.set(
        1,
        1,
        Cell {
            ch: '▀',
            fg: orange,
            bg: navy,
        },
    );
    assert_eq!(
        f.with_colors().to_string(),
        "▗▄▖\n ▀ \ncolours (columns fg/bg):\n0: 0..3 #ffa040/-\n1: 0..1 -/- 1..2 #ffa040/#102030 2..3 -/-\n"
    );
    // Its glyphs alone are the frame's Display.
    assert!(f.with_colors().to_string().starts_with(&f.to_string()));
}

/// The two-triangle scene in sextants and truecolor, with its colours:
/// the snapshot fails on a colour change that leaves every glyph as it
/// was, which the glyphs alone would not.
#[test]
fn colours_are_in_the_snapshot() {
    let path = format!(
        "{}/examples/scenes/shared-edge.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = Scene::load(path.as_ref()).unwrap();
    let opts = RenderOptions {
        cols: 24,
        rows: 8,
        glyphs: GlyphMode::Sextant,
        color: ColorDepth::TrueColor,
        ..RenderOptions::default()
    };
    let frame = render(&scene, &opts);
    insta::assert_snapshot!(frame.with_colors().to_string());

    // One triangle a shade darker: the same glyphs, other colours.
    let mut darker = scene.clone();
    let c = &mut darker.triangles[0].color;
    *c = match *c {
        rastty::scene::TriangleColor::Flat(rgb) => rastty::scene::TriangleColor::Flat(
            rastty::color::Rgb::new(rgb.0[0] / 2, rgb.0[1] / 2, rgb.0[2] / 2),
        ),
        other => other,
    };
    let other = render(&darker, &opts);
    assert_eq!(other.to_string(), frame.to_string());
    assert_ne!(
        other.with_colors().to_string(),
        frame.with_colors().to_string()
    );
}
