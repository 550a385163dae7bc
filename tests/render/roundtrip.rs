//! The encoder's bytes, read back by an independent terminal emulator (the
//! `vt100` crate): its screen must equal the frame, character, foreground
//! and background of every cell, for every glyph mode and colour depth, for
//! full frames and for sequences of frames sent as diffs, resizes included.

use crate::common;

use common::{as_displayed, nz, terminal};
use glam::Vec3;
use proptest::prelude::*;
use rastty::Choice;
use rastty::color::{Ink, Quantizer};
use rastty::encode::{Encoder, Rep, TermCell, write_lines};
use rastty::scene::{Triangle, TriangleColor};
use rastty::{
    Frame, GlyphMode, RenderOptions, Renderer, color::ColorDepth, color::Rgb, scene::Scene,
};

fn vt_color(ink: Ink) -> vt100::Color {
    match ink {
        Ink::Default => vt100::Color::Default,
        Ink::Indexed(i) => vt100::Color::Idx(i),
        Ink::Rgb(Rgb([r, g, b])) => vt100::Color::Rgb(r, g, b),
    }
}

/// One sample of a cell as the terminal paints it: an ink of the
/// foreground or of the background plane (whose defaults differ).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Paint {
    Fg(vt100::Color),
    Bg(vt100::Color),
}

impl Paint {
    /// Defaults are told apart by plane; any other colour is itself.
    fn same(self, other: Paint) -> bool {
        let color = |p| match p {
            Paint::Fg(c) | Paint::Bg(c) => c,
        };
        match (color(self), color(other)) {
            (vt100::Color::Default, vt100::Color::Default) => self == other,
            (a, b) => a == b,
        }
    }
}

/// What a cell of `glyphs` with `ch` in `fg` on `bg` paints, sample by
/// sample (one sample for a character that is not a block pattern of the
/// mode): a space paints its background, `█` its foreground, a block
/// element of the two-colour modes its pattern, `▀`/`▄` elsewhere (a
/// dithered cell's halves) its two colours top first, anything else is
/// compared as itself.
fn paints(
    glyphs: GlyphMode,
    ch: char,
    fg: vt100::Color,
    bg: vt100::Color,
) -> (Option<char>, Vec<Paint>) {
    let n = glyphs.samples();
    match ch {
        ' ' => (None, vec![Paint::Bg(bg); n]),
        '█' => (None, vec![Paint::Fg(fg); n]),
        // A dithered cell of one colour, in halves whatever the mode (in
        // either orientation).
        '▀' if glyphs.pattern(ch).is_none() => (Some('▀'), vec![Paint::Fg(fg), Paint::Bg(bg)]),
        '▄' if glyphs.pattern(ch).is_none() => (Some('▀'), vec![Paint::Fg(bg), Paint::Bg(fg)]),
        _ => match glyphs {
            GlyphMode::Half | GlyphMode::Quadrant | GlyphMode::Sextant | GlyphMode::Octant => {
                let mask = glyphs.pattern(ch).expect("a glyph of the mode");
                let s = (0..n)
                    .map(|i| {
                        if mask >> i & 1 == 1 {
                            Paint::Fg(fg)
                        } else {
                            Paint::Bg(bg)
                        }
                    })
                    .collect();
                (None, s)
            }
            _ => (Some(ch), vec![Paint::Fg(fg), Paint::Bg(bg)]),
        },
    }
}

/// Asserts that the emulator's screen shows the picture of `frame` (drawn
/// in `glyphs`) as `depth` sends it (matched and dithered as the encoder
/// does by default): every sample of every cell in the same colour. The
/// encoder may draw a cell the other way round (`▄` with the colours
/// swapped for `▀`), which shows the same.
fn assert_screen(
    screen: &vt100::Screen,
    frame: &Frame,
    glyphs: GlyphMode,
    depth: ColorDepth,
) -> Result<(), String> {
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
            let want = TermCell::at(frame, &mut q, c, r);
            let got = screen.cell(r, c).ok_or("no cell")?;
            let ch = got.contents().chars().next().unwrap_or(' ');
            let (fg, bg) = (vt_color(want.fg), vt_color(want.bg));
            let (want_ch, want_paint) = paints(glyphs, want.ch, fg, bg);
            let (got_ch, got_paint) = paints(glyphs, ch, got.fgcolor(), got.bgcolor());
            let same = want_ch == got_ch
                && want_paint.len() == got_paint.len()
                && want_paint.iter().zip(&got_paint).all(|(a, b)| a.same(*b));
            if !same {
                return Err(format!(
                    "cell ({c}, {r}): want {:?} fg {fg:?} bg {bg:?}, got {ch:?} fg {:?} bg {:?}",
                    want.ch,
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
        for &glyphs in GlyphMode::ALL {
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
                    assert_screen(vt.screen(), &frame, glyphs, depth)
                        .unwrap_or_else(|e| panic!("{name} {glyphs:?} {depth:?} {rep:?}: {e}"));
                }
            }
        }
    }
}

#[test]
fn render_lines_read_back_the_same() {
    let scene = scene("default");
    for &glyphs in GlyphMode::ALL {
        for depth in ColorDepth::ALL {
            let frame = rastty::render(&scene, &opts(30, 9, glyphs, depth));
            let mut bytes = Vec::new();
            write_lines(&frame, depth, Rep::On, &mut Vec::new(), &mut bytes).unwrap();
            let mut vt = terminal(9, 30);
            vt.process(&as_displayed(&bytes));
            assert_screen(vt.screen(), &frame, glyphs, depth)
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
            if let Err(e) = assert_screen(vt.screen(), &frame, glyphs, depth) {
                prop_assert!(false, "frame {}: {}", k, e);
            }
        }
    }
}

/// The byte table in docs/usage.md: in every glyph mode the spinning
/// square's later frames stay within their budget (half mode within 1,000
/// bytes; each sub-cell mode below what ratatui's Canvas sends for the same
/// samples, `examples/bytes_per_frame.rs`), and replaying every frame in
/// the emulator ends on the last frame.
#[test]
fn spinning_square_stays_within_budget_in_every_mode() {
    use rastty::animate;
    use rastty::animate::Spin;
    use rastty::transform::Axis;
    let scene = scene("square");
    let spin = Spin {
        view: Default::default(),
        axis: Axis::Z,
        step: 6.0,
        play: None,
    };
    let budgets = [
        (GlyphMode::Ascii, 600.0),
        (GlyphMode::Block, 900.0),
        (GlyphMode::Half, 1000.0),
        (GlyphMode::Quadrant, 1300.0),
        (GlyphMode::Sextant, 1500.0),
        (GlyphMode::Octant, 1500.0),
        (GlyphMode::Braille, 1700.0),
    ];
    for (glyphs, budget) in budgets {
        let o = opts(80, 24, glyphs, ColorDepth::TrueColor);
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
        assert!(
            later <= budget,
            "{glyphs:?}: {later:.0} bytes per later frame, budget {budget}"
        );
        let mut vt = terminal(24, 80);
        vt.process(&bytes);
        let last = RenderOptions {
            turn: spin.turn(o.turn, 59),
            ..o
        };
        assert_screen(
            vt.screen(),
            &rastty::render(&scene, &last),
            glyphs,
            ColorDepth::TrueColor,
        )
        .unwrap_or_else(|e| panic!("{glyphs:?}: {e}"));
    }
}
