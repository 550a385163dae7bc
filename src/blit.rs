//! Stage 6: blitters, from a cell's samples to one glyph and its colours.
//!
//! A [`GlyphMode`] fixes how many samples a cell holds (`w × h`) and how
//! they become a [`Cell`]. Blitters know nothing of ANSI: they produce
//! characters and full-precision colours, and the encoder decides how to
//! send them.
//!
//! Within a cell, samples are numbered row-major from the top-left:
//! sample `i` is column `i % w`, row `i / w` counted from the top. Glyph
//! tables index their patterns by that bit order.
//!
//! Without colour ([`ColorDepth::None`]) the glyph alone carries the
//! picture: `block` picks a shade from ` ░▒▓█` and `ascii` a character
//! from ` .:-=+*#%@`, both by brightness; any drawn sample gets at least the
//! first non-blank step, so a dark triangle on the terminal's background
//! still shows.

use crate::color::{ColorDepth, Rgb};
use crate::frame::{Cell, Frame};
use crate::framebuffer::Framebuffer;
use crate::raster::Grid;

/// How samples become glyphs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum GlyphMode {
    /// One sample per cell, drawn as a character of a brightness ramp.
    Ascii,
    /// One sample per cell, the whole cell in its colour.
    #[default]
    Block,
}

/// The ascii brightness ramp, darkest first.
pub const ASCII_RAMP: [char; 10] = [' ', '.', ':', '-', '=', '+', '*', '#', '%', '@'];
/// The shade ramp `block` uses without colour, darkest first.
pub const SHADE_RAMP: [char; 5] = [' ', '░', '▒', '▓', '█'];

impl GlyphMode {
    pub const ALL: [GlyphMode; 2] = [GlyphMode::Ascii, GlyphMode::Block];

    /// Samples per cell, `(w, h)`.
    pub const fn cell_size(self) -> (u32, u32) {
        match self {
            GlyphMode::Ascii | GlyphMode::Block => (1, 1),
        }
    }

    /// The sample grid behind `cols × rows` cells.
    pub fn grid(self, cols: u16, rows: u16) -> Grid {
        let (w, h) = self.cell_size();
        Grid::new(cols as u32 * w, rows as u32 * h)
    }

    /// One cell from its samples (see the module doc for their order).
    pub fn cell(self, samples: &[Option<Rgb>], depth: ColorDepth, background: Option<Rgb>) -> Cell {
        let s = samples[0];
        match (self, s) {
            (_, None) => Cell {
                ch: ' ',
                fg: None,
                bg: background.filter(|_| depth.has_color()),
            },
            (GlyphMode::Block, Some(c)) if depth.has_color() => Cell {
                ch: ' ',
                fg: None,
                bg: Some(c),
            },
            (GlyphMode::Block, Some(c)) => Cell {
                ch: ramp(&SHADE_RAMP, c),
                fg: None,
                bg: None,
            },
            (GlyphMode::Ascii, Some(c)) => Cell {
                ch: ramp(&ASCII_RAMP, c),
                fg: Some(c).filter(|_| depth.has_color()),
                bg: background.filter(|_| depth.has_color()),
            },
        }
    }
}

/// The ramp step for a drawn sample: never the blank first step.
fn ramp(steps: &[char], c: Rgb) -> char {
    let top = (steps.len() - 2) as f32;
    steps[1 + (c.luma() * top).round() as usize]
}

/// Turns the framebuffer into `frame` (resized to fit), cell by cell. Sample
/// row `H − 1 − r` shows on terminal row `r`.
pub fn blit(
    fb: &Framebuffer,
    mode: GlyphMode,
    depth: ColorDepth,
    background: Option<Rgb>,
    frame: &mut Frame,
) {
    let (w, h) = mode.cell_size();
    let grid = fb.grid();
    let (cols, rows) = ((grid.width / w) as u16, (grid.height / h) as u16);
    frame.reset(cols, rows);
    let mut samples = [None; 8];
    let n = (w * h) as usize;
    for row in 0..rows {
        // The cell's top sample row.
        let top = grid.height - 1 - row as u32 * h;
        for col in 0..cols {
            for (i, s) in samples[..n].iter_mut().enumerate() {
                let (dx, dy) = (i as u32 % w, i as u32 / w);
                *s = fb.get(col as u32 * w + dx, top - dy);
            }
            frame.set(col, row, mode.cell(&samples[..n], depth, background));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramps_skip_blank_for_drawn_samples() {
        assert_eq!(ramp(&ASCII_RAMP, Rgb::BLACK), '.');
        assert_eq!(ramp(&ASCII_RAMP, Rgb::WHITE), '@');
        assert_eq!(ramp(&SHADE_RAMP, Rgb::BLACK), '░');
        assert_eq!(ramp(&SHADE_RAMP, Rgb::WHITE), '█');
    }

    #[test]
    fn terminal_row_zero_shows_the_top_sample_row() {
        let mut fb = Framebuffer::new(Grid::new(2, 3));
        fb.set(0, 2, Rgb::WHITE); // top-left
        fb.set(1, 0, Rgb::WHITE); // bottom-right
        let mut frame = Frame::default();
        blit(&fb, GlyphMode::Ascii, ColorDepth::None, None, &mut frame);
        assert_eq!(frame.to_string(), "@ \n  \n @\n");
    }

    #[test]
    fn colour_goes_to_the_right_plane() {
        let red = Rgb::new(255, 0, 0);
        let bg = Some(Rgb::BLACK);
        let block = GlyphMode::Block.cell(&[Some(red)], ColorDepth::TrueColor, bg);
        assert_eq!(
            block,
            Cell {
                ch: ' ',
                fg: None,
                bg: Some(red)
            }
        );
        let ascii = GlyphMode::Ascii.cell(&[Some(red)], ColorDepth::TrueColor, bg);
        assert_eq!((ascii.fg, ascii.bg), (Some(red), bg));
        let empty = GlyphMode::Block.cell(&[None], ColorDepth::TrueColor, bg);
        assert_eq!(
            empty,
            Cell {
                ch: ' ',
                fg: None,
                bg
            }
        );
        let plain = GlyphMode::Ascii.cell(&[Some(red)], ColorDepth::None, bg);
        assert_eq!((plain.fg, plain.bg), (None, None));
    }
}
