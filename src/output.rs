//! Where a frame's samples go: the one seam between the renderer and what
//! it draws for, in the spirit of tiny-skia's `Blitter` and ratatui's
//! `Backend`. The stages draw on the options' grid of samples
//! ([`RenderOptions::grid`]) and know nothing of what the samples become;
//! an [`Output`] turns them into its units, a band of rows at a time where
//! the frame is drawn in bands (each band on its own thread, into its own
//! rows of units) or all at once.
//!
//! A [`Frame`] is the output of character cells: each cell's samples
//! become one glyph and two colours ([`crate::blit::GlyphMode`]), which the
//! [`Encoder`](crate::encode::Encoder), the ratatui widget and pictures
//! take from it. The renderer draws into any output through one path
//! (`Renderer::render_to`, which `render_into` calls with a frame):
//! another output (pixels) is another implementation here, and nothing in
//! the stages changes.

use crate::blit;
use crate::color::Rgb;
use crate::frame::{Cell, Frame, Known};
use crate::framebuffer::View;
use crate::options::RenderOptions;

/// What a frame's samples are turned into: units (character cells,
/// pixels…), each of a fixed block of samples, in rows from the top.
pub(crate) trait Output {
    /// One unit of the output.
    type Unit: Send;
    /// How the units are filled for one frame (its settings), shared by the
    /// bands' threads.
    type Fill: Sync;
    /// What filling some rows found (which units changed, say), gathered
    /// over the bands by [`Output::merge`].
    type Done: Copy + Send;

    /// The samples one unit covers, across and down, in a frame of `opts`.
    fn unit(opts: &RenderOptions) -> (u32, u32);

    /// Readies the output for a frame of `opts` (sized to its grid, in
    /// units), the uncovered samples `background` (`None`: the
    /// terminal's own); returns how its units are filled.
    fn begin(&mut self, opts: &RenderOptions, background: Option<Rgb>) -> Self::Fill;

    /// Its units, the top row first.
    fn units_mut(&mut self) -> &mut [Self::Unit];

    /// Fills `units`, whole rows of them, from `samples`, the rows of
    /// samples beneath them (a band's, or the frame's).
    fn fill(how: &Self::Fill, samples: View<'_>, units: &mut [Self::Unit]) -> Self::Done;

    /// What two bands found, together (`a` the lower band's).
    fn merge(a: Self::Done, b: Self::Done) -> Self::Done;

    /// Takes what filling the frame found, once every unit is filled.
    fn end(&mut self, done: Self::Done);
}

/// How a frame's cells are filled: its glyphs and colours.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cells {
    glyphs: crate::blit::GlyphMode,
    color: crate::color::ColorDepth,
    background: Option<Rgb>,
    split: crate::blit::Split,
}

impl Output for Frame {
    type Unit = Cell;
    type Fill = Cells;
    type Done = Known;

    fn unit(opts: &RenderOptions) -> (u32, u32) {
        opts.cell_samples()
    }

    fn begin(&mut self, opts: &RenderOptions, background: Option<Rgb>) -> Cells {
        self.set_plain(matches!(
            opts.glyphs,
            crate::blit::GlyphMode::Ascii | crate::blit::GlyphMode::Braille
        ));
        let grid = opts.grid();
        let (w, h) = opts.cell_samples();
        // Every cell is written by the fills.
        self.resize((grid.width / w) as u16, (grid.height / h) as u16);
        Cells {
            glyphs: opts.glyphs,
            color: opts.color,
            background,
            split: opts.split,
        }
    }

    fn units_mut(&mut self) -> &mut [Cell] {
        self.cells_mut()
    }

    fn fill(how: &Cells, samples: View<'_>, cells: &mut [Cell]) -> Known {
        blit::blit_band(
            samples,
            how.glyphs,
            how.color,
            how.background,
            how.split,
            cells,
        )
    }

    /// The cells drawn in either band; the rest show the fill the first
    /// band found (the same in every band: the background).
    fn merge(a: Known, b: Known) -> Known {
        Known {
            rect: a.rect.union(b.rect),
            ..a
        }
    }

    fn end(&mut self, done: Known) {
        self.set_known(done);
    }
}

/// How a frame's pixels are filled: what an undrawn pixel is.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PixelFill {
    background: crate::pixels::Rgba,
}

impl Output for crate::pixels::Pixels {
    type Unit = crate::pixels::Rgba;
    type Fill = PixelFill;
    type Done = ();

    /// A pixel is one sample.
    fn unit(_: &RenderOptions) -> (u32, u32) {
        (1, 1)
    }

    fn begin(&mut self, opts: &RenderOptions, background: Option<Rgb>) -> PixelFill {
        let grid = opts.grid();
        self.resize(grid.width, grid.height);
        PixelFill {
            background: match background {
                Some(Rgb([r, g, b])) => [r, g, b, 255],
                None => [0; 4],
            },
        }
    }

    fn units_mut(&mut self) -> &mut [crate::pixels::Rgba] {
        self.rgba_mut()
    }

    /// Each pixel row from its sample row (rows of samples count from the
    /// bottom, of pixels from the top): a drawn sample encoded to sRGB,
    /// opaque; any other the background.
    fn fill(how: &PixelFill, samples: View<'_>, pixels: &mut [crate::pixels::Rgba]) {
        let (band, drawn) = (samples.band(), samples.drawn());
        let w = samples.grid().width as usize;
        if w == 0 {
            return;
        }
        for (row, y) in pixels.chunks_exact_mut(w).zip((band.y0..band.y1).rev()) {
            if y < drawn.y0 || y >= drawn.y1 {
                row.fill(how.background);
                continue;
            }
            let (x0, x1) = (drawn.x0 as usize, (drawn.x1 as usize).min(w));
            row[..x0].fill(how.background);
            row[x1..].fill(how.background);
            for (p, s) in row[x0..x1].iter_mut().zip(&samples.row(y)[x0..x1]) {
                *p = match s {
                    Some(c) => {
                        let Rgb([r, g, b]) = c.to_srgb();
                        [r, g, b, 255]
                    }
                    None => how.background,
                };
            }
        }
    }

    fn merge(_: (), _: ()) {}

    fn end(&mut self, _: ()) {}
}
