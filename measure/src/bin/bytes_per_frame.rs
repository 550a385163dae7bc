//! Bytes per frame of the diffing encoder: an 80×24 animation of a square
//! split into a red and a blue triangle on a dark background
//! (`examples/scenes/square.toml`) turning one full circle about the view
//! axis in 60 frames, in every glyph mode, in truecolor. Prints the
//! Markdown table in docs/usage.md.
//!
//! The last column is ratatui's: the same samples (rastty's framebuffer of
//! each frame) painted as points on ratatui 0.30's `Canvas` with the marker
//! of the same sub-cell grid, drawn by a `Terminal` on its crossterm back
//! end into a byte buffer (ratatui diffs its buffers too). Its sub-cell
//! markers give a cell one colour, the last painted, on the canvas's
//! background; rastty's give it two. The last column leaves the canvas in
//! the terminal's default background, which is not the same picture (no
//! dark square behind the triangles) but sends no background colour at
//! all. rastty's figures include the 16 bytes of synchronized output a
//! frame, which ratatui does not send.
//!
//! ```text
//! cargo run --release -p rastty-measure --bin bytes_per_frame
//! ```

use rastty::Choice;
use std::io::{self, Write};
use std::rc::Rc;

use rastty::animate;
use rastty::animate::Spin;
use rastty::encode::{Encoder, Rep};
use rastty::transform::Axis;
use rastty::{GlyphMode, RenderOptions, Renderer, color::ColorDepth, scene::Scene};
use ratatui::backend::CrosstermBackend;
use ratatui::layout::Rect;
use ratatui::style::Color;
use ratatui::symbols::Marker;
use ratatui::widgets::canvas::{Canvas, Painter, Shape};
use ratatui::{Terminal, TerminalOptions, Viewport};

const COLS: u16 = 80;
const ROWS: u16 = 24;
const FRAMES: u64 = 60;
const SPIN: Spin = Spin {
    axis: Axis::Z,
    step: 6.0,
    play: None,
    view: rastty::scene::View::AS_GIVEN,
};

fn main() {
    let path = format!(
        "{}/../examples/scenes/square.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = Scene::load(path.as_ref()).expect("the square scene");
    println!(
        "| glyphs | first frame | later frames, mean | later frames, mean, with `--rep` | ratatui `Canvas`, later frames, mean | ratatui, no background |"
    );
    println!("|---|---:|---:|---:|---:|---:|");
    for &glyphs in GlyphMode::ALL {
        let opts = RenderOptions {
            cols: COLS,
            rows: ROWS,
            glyphs,
            color: ColorDepth::TrueColor,
            ..RenderOptions::default()
        };
        let [plain, rep] = [Rep::Off, Rep::On].map(|rep| {
            let encoder = Encoder::new(ColorDepth::TrueColor).with_rep(rep);
            let mut sizes = Vec::new();
            animate::play(
                &scene,
                &opts,
                SPIN,
                FRAMES,
                encoder,
                &mut std::io::sink(),
                |n| sizes.push(n),
            )
            .unwrap();
            (sizes[0], mean(&sizes[1..]))
        });
        let [theirs, bare] = [true, false].map(|bg| {
            marker(glyphs).map_or("".into(), |m| {
                format!("{:.0}", mean(&ratatui_sizes(&scene, &opts, m, bg)[1..]))
            })
        });
        println!(
            "| {glyphs:?} | {} | {:.0} | {:.0} | {theirs} | {bare} |",
            plain.0, plain.1, rep.1
        );
    }
}

fn mean(sizes: &[usize]) -> f64 {
    sizes.iter().sum::<usize>() as f64 / sizes.len() as f64
}

/// ratatui's marker with the same samples a cell, if it has one.
fn marker(glyphs: GlyphMode) -> Option<Marker> {
    match glyphs {
        GlyphMode::Ascii => None,
        GlyphMode::Block => Some(Marker::Block),
        GlyphMode::Half => Some(Marker::HalfBlock),
        GlyphMode::Quadrant => Some(Marker::Quadrant),
        GlyphMode::Sextant => Some(Marker::Sextant),
        GlyphMode::Octant => Some(Marker::Octant),
        GlyphMode::Braille => Some(Marker::Braille),
    }
}

/// A frame's covered samples, top row first, as canvas points.
struct Samples {
    width: usize,
    colors: Vec<Option<Color>>,
}

impl Shape for Samples {
    fn draw(&self, painter: &mut Painter) {
        for (i, c) in self.colors.iter().enumerate() {
            if let Some(c) = *c {
                painter.paint(i % self.width, i / self.width, c);
            }
        }
    }
}

/// A writer that counts what it is given.
#[derive(Clone, Default)]
struct Counter(Rc<std::cell::Cell<usize>>);

impl Write for Counter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.set(self.0.get() + buf.len());
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// Bytes ratatui's terminal writes for each frame of the animation, the
/// canvas painted in the scene's background or left in the terminal's.
fn ratatui_sizes(
    scene: &Scene,
    opts: &RenderOptions,
    marker: Marker,
    with_background: bool,
) -> Vec<usize> {
    let background = scene.background.map(|c| Color::Rgb(c.0[0], c.0[1], c.0[2]));
    // Only the triangles' samples: the canvas paints its own background.
    let bare = Scene {
        background: None,
        ..scene.clone()
    };
    let area = Rect::new(0, 0, COLS, ROWS);
    let count = Counter::default();
    let backend = CrosstermBackend::new(count.clone());
    let mut terminal = Terminal::with_options(
        backend,
        TerminalOptions {
            viewport: Viewport::Fixed(area),
        },
    )
    .unwrap();
    let mut renderer = Renderer::new();
    let mut sizes = Vec::new();
    for k in 0..FRAMES {
        let o = RenderOptions {
            turn: SPIN.turn(opts.turn, k),
            ..*opts
        };
        renderer.render(&bare, &o);
        let fb = renderer.framebuffer();
        let grid = fb.grid();
        let (w, h) = (grid.width as usize, grid.height as usize);
        let mut colors = vec![None; w * h];
        for y in 0..h {
            // The framebuffer's rows run from the bottom, the canvas's from
            // the top.
            for (x, s) in fb.row(y as u32).iter().enumerate() {
                colors[(h - 1 - y) * w + x] = s.map(|c| {
                    let [r, g, b] = c.to_srgb().0;
                    Color::Rgb(r, g, b)
                });
            }
        }
        let samples = Samples { width: w, colors };
        let before = count.0.get();
        terminal
            .draw(|f| {
                let mut canvas = Canvas::default()
                    .marker(marker)
                    .x_bounds([0.0, w as f64])
                    .y_bounds([0.0, h as f64])
                    .paint(|ctx| ctx.draw(&samples));
                if let Some(bg) = background.filter(|_| with_background) {
                    canvas = canvas.background_color(bg);
                }
                f.render_widget(canvas, f.area());
            })
            .unwrap();
        sizes.push(count.0.get() - before);
    }
    sizes
}
