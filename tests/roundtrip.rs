//! The encoder's bytes, read back by an independent terminal emulator (the
//! `vt100` crate): its screen must equal the frame, character, foreground
//! and background of every cell, for every glyph mode and colour depth, for
//! full frames and for sequences of frames sent as diffs, resizes included.

mod common;

use common::{as_displayed, nz, terminal};
use glam::Vec3;
use proptest::prelude::*;
use rastty::color::{Ink, Quantizer};
use rastty::encode::{Encoder, Rep, write_lines};
use rastty::scene::{Triangle, TriangleColor};
use rastty::{ColorDepth, Frame, GlyphMode, RenderOptions, Renderer, Rgb, Scene};

fn vt_color(ink: Ink) -> vt100::Color {
    match ink {
        Ink::Default => vt100::Color::Default,
        Ink::Indexed(i) => vt100::Color::Idx(i),
        Ink::Rgb(Rgb([r, g, b])) => vt100::Color::Rgb(r, g, b),
    }
}

/// Asserts that the emulator's screen shows `frame` as `depth` sends it
/// (matched and dithered as the encoder does by default).
fn assert_screen(screen: &vt100::Screen, frame: &Frame, depth: ColorDepth) -> Result<(), String> {
    let mut q = Quantizer::of(depth.into());
    let (rows, cols) = screen.size();
    let (rows, cols) = (rows.get(), cols.get());
    if (cols, rows) != (frame.cols(), frame.rows()) {
        return Err(format!(
            "size {cols}×{rows}, frame {}×{}",
            frame.cols(),
            frame.rows()
        ));
    }
    for r in 0..frame.rows() {
        for c in 0..frame.cols() {
            let want = frame.get(c, r);
            let got = screen.cell(r, c).ok_or("no cell")?;
            let ch = got.contents().chars().next().unwrap_or(' ');
            let bg = vt_color(q.ink_at(want.bg, c, r));
            let ok_fg = want.ch == ' ' || got.fgcolor() == vt_color(q.ink_at(want.fg, c, r));
            if ch != want.ch || got.bgcolor() != bg || !ok_fg {
                return Err(format!(
                    "cell ({c}, {r}): want {:?} fg {:?} bg {:?}, got {:?} fg {:?} bg {:?}",
                    want.ch,
                    want.fg,
                    bg,
                    ch,
                    got.fgcolor(),
                    got.bgcolor()
                ));
            }
        }
    }
    Ok(())
}

fn scene(name: &str) -> Scene {
    let path = format!("{}/examples/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    Scene::load(path.as_ref()).unwrap()
}

fn opts(cols: u16, rows: u16, glyphs: GlyphMode, color: ColorDepth) -> RenderOptions {
    RenderOptions {
        cols,
        rows,
        glyphs,
        color,
        ..RenderOptions::default()
    }
}

#[test]
fn full_frames_in_every_mode_and_depth() {
    let mut renderer = Renderer::new();
    for name in ["default", "orthographic", "shared-edge"] {
        let scene = scene(name);
        for glyphs in GlyphMode::ALL {
            for depth in ColorDepth::ALL {
                for rep in [Rep::Off, Rep::On] {
                    let frame = renderer
                        .render(&scene, &opts(40, 12, glyphs, depth))
                        .clone();
                    let mut bytes = Vec::new();
                    Encoder::new(depth)
                        .with_rep(rep)
                        .encode(&frame, &mut bytes)
                        .unwrap();
                    let mut vt = terminal(12, 40);
                    vt.process(&bytes);
                    assert_screen(vt.screen(), &frame, depth)
                        .unwrap_or_else(|e| panic!("{name} {glyphs:?} {depth:?} {rep:?}: {e}"));
                }
            }
        }
    }
}

#[test]
fn render_lines_read_back_the_same() {
    let scene = scene("default");
    for glyphs in GlyphMode::ALL {
        for depth in ColorDepth::ALL {
            let frame = rastty::render(&scene, &opts(30, 9, glyphs, depth));
            let mut bytes = Vec::new();
            write_lines(&frame, depth, Rep::On, &mut Vec::new(), &mut bytes).unwrap();
            let mut vt = terminal(9, 30);
            vt.process(&as_displayed(&bytes));
            assert_screen(vt.screen(), &frame, depth)
                .unwrap_or_else(|e| panic!("{glyphs:?} {depth:?}: {e}"));
            if depth == ColorDepth::None {
                assert!(!bytes.contains(&0x1b), "plain text has no escapes");
            }
        }
    }
}

/// A random triangle in the canonical cube, flat or per-vertex coloured.
fn triangle() -> impl Strategy<Value = Triangle> {
    let v = || (-1.2f32..1.2, -1.2f32..1.2, -0.9f32..0.9).prop_map(|(x, y, z)| Vec3::new(x, y, z));
    let c = || any::<[u8; 3]>().prop_map(Rgb);
    (
        v(),
        v(),
        v(),
        c(),
        prop::option::of((c(), c())),
        any::<bool>(),
    )
        .prop_map(|(a, b, d, c0, more, _)| Triangle {
            vertices: [a, b, d],
            color: match more {
                None => TriangleColor::Flat(c0),
                Some((c1, c2)) => TriangleColor::PerVertex([c0, c1, c2]),
            },
        })
}

fn frame_step() -> impl Strategy<Value = (Vec<Triangle>, u16, u16)> {
    // Sizes from a small set, so that consecutive frames often share one
    // (diffs) and sometimes do not (resizes).
    (
        prop::collection::vec(triangle(), 0..6),
        prop::sample::select(vec![8u16, 13, 20]),
        prop::sample::select(vec![4u16, 7]),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(
        std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(64)
    ))]

    #[test]
    fn sequences_of_diffs_keep_the_screen_equal_to_the_frame(
        steps in prop::collection::vec(frame_step(), 1..8),
        glyphs in prop::sample::select(GlyphMode::ALL.to_vec()),
        depth in prop::sample::select(ColorDepth::ALL.to_vec()),
        rep in prop::sample::select(vec![Rep::Off, Rep::On]),
        background in prop::option::of(any::<[u8; 3]>().prop_map(Rgb)),
    ) {
        let mut renderer = Renderer::new();
        let mut encoder = Encoder::new(depth).with_rep(rep);
        let mut vt: Option<vt100::Parser> = None;
        for (k, (triangles, cols, rows)) in steps.into_iter().enumerate() {
            let scene = Scene { background, ..Scene::in_canonical_cube(triangles) };
            let frame = renderer.render(&scene, &opts(cols, rows, glyphs, depth)).clone();
            // A resize: the terminal changes size first, as a real one does.
            match &mut vt {
                Some(p) if p.screen().size() == (nz(rows), nz(cols)) => {}
                Some(p) => p.set_size(nz(rows), nz(cols)),
                None => vt = Some(terminal(rows, cols)),
            }
            let mut bytes = Vec::new();
            encoder.encode(&frame, &mut bytes).unwrap();
            let vt = vt.as_mut().unwrap();
            vt.process(&bytes);
            if let Err(e) = assert_screen(vt.screen(), &frame, depth) {
                prop_assert!(false, "frame {}: {}", k, e);
            }
        }
    }
}

/// The byte table in docs/usage.md, half mode: the spinning square's later frames
/// stay within the 1,400-byte budget (ratatui's Canvas sends about 2,830),
/// and replaying every frame in the emulator ends on the last frame.
#[test]
fn spinning_square_in_half_mode_stays_within_budget() {
    use rastty::animate;
    use rastty::animate::{Axis, Spin};
    let scene = scene("square");
    let o = opts(80, 24, GlyphMode::Half, ColorDepth::TrueColor);
    let spin = Spin {
        axis: Axis::Z,
        step: 6.0,
    };
    let mut bytes = Vec::new();
    let mut sizes = Vec::new();
    animate::play(
        &scene,
        &o,
        spin,
        60,
        Encoder::new(ColorDepth::TrueColor),
        &mut bytes,
        |n| sizes.push(n),
    )
    .unwrap();
    let later = sizes[1..].iter().sum::<usize>() as f64 / 59.0;
    assert!(later <= 1400.0, "{later:.0} bytes per later frame");
    let mut vt = terminal(24, 80);
    vt.process(&bytes);
    let last = RenderOptions {
        turn: spin.turn(o.turn, 59),
        ..o
    };
    assert_screen(
        vt.screen(),
        &rastty::render(&scene, &last),
        ColorDepth::TrueColor,
    )
    .unwrap();
}
