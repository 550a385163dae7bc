//! The ratatui widget (feature `ratatui`; this test crate also runs with
//! `--no-default-features --features ratatui`, the renderer alone plus the
//! widget): its buffer shows, cell by cell, the glyphs and colours that
//! `rastty render` prints for the same size and options, read back through
//! the `vt100` terminal emulator.

use crate::common;

use ratatui_core::backend::TestBackend;
use ratatui_core::buffer::Buffer;
use ratatui_core::layout::Rect;
use ratatui_core::style::Color;
use ratatui_core::terminal::Terminal;
use ratatui_core::widgets::{StatefulWidget, Widget};

/// The plain widget's `render` (the stateful one has the same name).
fn draw(w: SceneWidget<'_>, area: Rect, buf: &mut Buffer) {
    Widget::render(w, area, buf);
}
use rastty::encode::{Rep, write_lines};
use rastty::glam::Vec3;
use rastty::ratatui::{SceneState, SceneWidget};
use rastty::scene::Shape;
use rastty::{
    Frame, GlyphMode, RenderOptions, color::ColorDepth, color::Rgb, render, scene::Scene,
    scene::default_scene,
};

/// The colour a vt100 screen shows for a ratatui colour: the named
/// colours are palette entries 0–15, sent as SGR 30–37 and 90–97.
fn vt_color(c: Color) -> vt100::Color {
    let named = [
        Color::Black,
        Color::Red,
        Color::Green,
        Color::Yellow,
        Color::Blue,
        Color::Magenta,
        Color::Cyan,
        Color::Gray,
        Color::DarkGray,
        Color::LightRed,
        Color::LightGreen,
        Color::LightYellow,
        Color::LightBlue,
        Color::LightMagenta,
        Color::LightCyan,
        Color::White,
    ];
    match c {
        Color::Reset => vt100::Color::Default,
        Color::Rgb(r, g, b) => vt100::Color::Rgb(r, g, b),
        Color::Indexed(i) => vt100::Color::Idx(i),
        c => vt100::Color::Idx(named.iter().position(|n| *n == c).expect("a named colour") as u8),
    }
}

/// What `rastty render` prints for `frame` at `depth`, on a vt100 screen.
fn printed(frame: &Frame, depth: ColorDepth) -> vt100::Parser {
    let (mut buf, mut out) = (Vec::new(), Vec::new());
    write_lines(frame, depth, Rep::Off, &mut buf, &mut out).unwrap();
    let mut vt = common::terminal(frame.rows(), frame.cols());
    vt.process(&common::as_displayed(&out));
    vt
}

/// Checks that `buf`'s cells inside `area` show what the screen shows.
fn assert_same(buf: &Buffer, area: Rect, vt: &vt100::Parser, what: &str) {
    let screen = vt.screen();
    for row in 0..area.height {
        for col in 0..area.width {
            let cell = &buf[(area.x + col, area.y + row)];
            let shown = screen.cell(row, col).unwrap();
            let want = (
                shown.contents().to_string(),
                shown.fgcolor(),
                shown.bgcolor(),
            );
            let blank = want.0.is_empty() || want.0 == " ";
            let got = (
                cell.symbol().to_string(),
                vt_color(cell.fg),
                vt_color(cell.bg),
            );
            if blank {
                // A blank shows only its background.
                assert_eq!(
                    (got.0.as_str(), got.2),
                    (" ", want.2),
                    "{what}: cell ({col}, {row})"
                );
            } else {
                assert_eq!(got, want, "{what}: cell ({col}, {row})");
            }
        }
    }
}

fn options(cols: u16, rows: u16, glyphs: GlyphMode, color: ColorDepth) -> RenderOptions {
    RenderOptions {
        cols,
        rows,
        glyphs,
        color,
        turn: Vec3::new(0.0, 30.0, 0.0),
        ..Default::default()
    }
}

/// Per-vertex colours, a background and a shaded mesh: every kind of
/// colour a cell can get.
fn colourful() -> Scene {
    Scene::builder()
        .background(Rgb::new(0x10, 0x18, 0x30))
        .mesh(Shape::Torus.mesh(Rgb::new(0xff, 0x90, 0x40)))
        .triangle_colors(
            [
                Vec3::new(-2.0, -1.5, -1.0),
                Vec3::new(2.0, -1.5, -1.0),
                Vec3::new(0.0, 1.8, -1.0),
            ],
            [
                Rgb::new(255, 0, 0),
                Rgb::new(0, 255, 0),
                Rgb::new(0, 0, 255),
            ],
        )
        .light(rastty::scene::Light::default())
        .build()
        .unwrap()
}

/// Sixteen bands in the sixteen ANSI colours, unlit: at 16 colours every
/// palette entry, and so every named ratatui colour, appears.
fn bands() -> Scene {
    let triangles = rastty::color::ANSI16
        .iter()
        .enumerate()
        .flat_map(|(i, &c)| {
            let (x0, x1) = (i as f32 / 8.0 - 1.0, (i + 1) as f32 / 8.0 - 1.0);
            let v = |x, y| Vec3::new(x, y, 0.0);
            [
                [v(x0, -1.0), v(x1, -1.0), v(x1, 1.0)],
                [v(x0, -1.0), v(x1, 1.0), v(x0, 1.0)],
            ]
            .map(|vertices| rastty::scene::Triangle {
                vertices,
                color: rastty::scene::TriangleColor::Flat(c),
            })
        })
        .collect();
    Scene::in_canonical_cube(triangles)
}

#[test]
fn the_widget_shows_what_render_prints_at_every_depth() {
    let scenes = [
        ("default", default_scene()),
        ("colourful", colourful()),
        ("bands", bands()),
    ];
    for (name, scene) in &scenes {
        for glyphs in [GlyphMode::Half, GlyphMode::Quadrant, GlyphMode::Braille] {
            for depth in ColorDepth::ALL {
                let opts = options(48, 16, glyphs, depth);
                let mut buf = Buffer::empty(Rect::new(0, 0, 48, 16));
                draw(SceneWidget::new(scene, &opts), buf.area, &mut buf);
                let frame = render(scene, &opts);
                if *name == "bands" && depth == ColorDepth::Ansi16 {
                    // Every palette entry is on the screen.
                    let vt = printed(&frame, depth);
                    let shown: std::collections::BTreeSet<String> = (0..16)
                        .flat_map(|r| (0..48).map(move |c| (r, c)))
                        .flat_map(|(r, c)| {
                            let cell = vt.screen().cell(r, c).unwrap();
                            [cell.fgcolor(), cell.bgcolor()]
                        })
                        .filter(|c| *c != vt100::Color::Default)
                        .map(|c| format!("{c:?}"))
                        .collect();
                    assert_eq!(shown.len(), 16, "{shown:?}");
                }
                let vt = printed(&frame, depth);
                assert_same(&buf, buf.area, &vt, &format!("{name} {glyphs:?} {depth:?}"));
            }
        }
    }
}

#[test]
fn an_area_inside_a_larger_buffer_is_drawn_there_and_nowhere_else() {
    let scene = colourful();
    let opts = options(80, 24, GlyphMode::Sextant, ColorDepth::Ansi256);
    let mut buf = Buffer::empty(Rect::new(0, 0, 60, 20));
    let marker = ratatui_core::style::Style::new().bg(Color::Magenta);
    buf.set_style(buf.area, marker);
    let area = Rect::new(7, 3, 30, 12);
    draw(SceneWidget::new(&scene, &opts), area, &mut buf);
    // The frame at the area's size, whatever the options' cols and rows.
    let vt = printed(
        &render(
            &scene,
            &options(30, 12, GlyphMode::Sextant, ColorDepth::Ansi256),
        ),
        ColorDepth::Ansi256,
    );
    assert_same(&buf, area, &vt, "inside");
    for y in 0..20 {
        for x in 0..60 {
            if !area.contains((x, y).into()) {
                let c = &buf[(x, y)];
                assert_eq!((c.symbol(), c.bg), (" ", Color::Magenta), "({x}, {y})");
            }
        }
    }
}

#[test]
fn an_area_cut_by_the_buffer_is_drawn_at_the_size_that_shows() {
    let scene = default_scene();
    let opts = options(10, 10, GlyphMode::Half, ColorDepth::TrueColor);
    let mut buf = Buffer::empty(Rect::new(0, 0, 40, 10));
    let area = Rect::new(25, 4, 30, 12);
    draw(SceneWidget::new(&scene, &opts), area, &mut buf);
    let shown = area.intersection(buf.area);
    assert_eq!(shown, Rect::new(25, 4, 15, 6));
    let vt = printed(
        &render(
            &scene,
            &options(15, 6, GlyphMode::Half, ColorDepth::TrueColor),
        ),
        ColorDepth::TrueColor,
    );
    assert_same(&buf, shown, &vt, "cut");
}

#[test]
fn uncovered_cells_keep_the_buffers_colours() {
    // The default scene has no background: its uncovered cells are the
    // terminal's default in `rastty render`, and in the widget whatever the
    // buffer had (a Block's background, say).
    let scene = default_scene();
    assert_eq!(scene.background, None);
    let opts = options(40, 12, GlyphMode::Half, ColorDepth::TrueColor);
    let frame = render(&scene, &opts);
    let mut buf = Buffer::empty(Rect::new(0, 0, 40, 12));
    buf.set_style(buf.area, ratatui_core::style::Style::new().bg(Color::Blue));
    draw(SceneWidget::new(&scene, &opts), buf.area, &mut buf);
    let mut uncovered = 0;
    for row in 0..12 {
        for col in 0..40 {
            let (cell, want) = (&buf[(col, row)], frame.get(col, row));
            match want.bg {
                None => {
                    assert_eq!(cell.bg, Color::Blue, "({col}, {row})");
                    uncovered += 1;
                }
                Some(Rgb([r, g, b])) => {
                    assert_eq!(cell.bg, Color::Rgb(r, g, b), "({col}, {row})")
                }
            }
        }
    }
    assert!(uncovered > 100 && uncovered < 40 * 12, "{uncovered}");
}

#[test]
fn the_stateful_widget_draws_what_the_plain_one_draws_frame_after_frame() {
    let scene = colourful();
    let mut state = SceneState::new();
    for (k, depth) in [
        ColorDepth::TrueColor,
        ColorDepth::Ansi16,
        ColorDepth::Ansi16,
    ]
    .into_iter()
    .enumerate()
    {
        let mut opts = options(50, 14, GlyphMode::Octant, depth);
        opts.turn.y = 10.0 * k as f32;
        let (mut plain, mut kept) = (
            Buffer::empty(Rect::new(0, 0, 50, 14)),
            Buffer::empty(Rect::new(0, 0, 50, 14)),
        );
        draw(SceneWidget::new(&scene, &opts), plain.area, &mut plain);
        StatefulWidget::render(
            SceneWidget::new(&scene, &opts),
            kept.area,
            &mut kept,
            &mut state,
        );
        assert_eq!(plain, kept, "frame {k}");
        assert_eq!(state.frame(), &render(&scene, &opts), "frame {k}");
    }
}

#[test]
fn a_terminal_of_the_test_backend_shows_the_frames_text() {
    let scene = default_scene();
    let opts = options(40, 12, GlyphMode::Quadrant, ColorDepth::TrueColor);
    let mut terminal = Terminal::new(TestBackend::new(40, 12)).unwrap();
    terminal
        .draw(|f| f.render_widget(SceneWidget::new(&scene, &opts), f.area()))
        .unwrap();
    let text: String = terminal
        .backend()
        .buffer()
        .content
        .chunks(40)
        .map(|row| row.iter().map(|c| c.symbol()).collect::<String>() + "\n")
        .collect();
    assert_eq!(text, render(&scene, &opts).to_string());
    insta::assert_snapshot!(text);
}
